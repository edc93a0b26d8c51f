//! Which value lies at an absolute address: the check that lets a pointer
//! kept in an integer (`pv : PVOID := ADR(st)`, then `p := pv`) become a
//! typed pointer to a structure again.
//!
//! A pointer made from an integer is a byte view (`ir::refs::VIEW`), which
//! reads and writes elementary values only. TwinCAT code keeps pointers to
//! structures in `PVOID`s (Tc2_Utilities' hash table and linked list hold
//! their values so) and reads the structures back through them. Typed
//! code trusts the types of the slots it reads — a STRING's slot holds its
//! buffer's id — so such a pointer is typed again only when the memory it
//! designates holds a value of its element type there, found by walking
//! the types of the program's variables down to that address.

use crate::ir::image::Image;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, TypeTable};

/// Whether the `ty` at absolute slot address `addr` is a whole value of
/// that type inside a global variable or a program instance.
pub(super) fn holds(img: &Image, addr: u32, ty: TypeId) -> bool {
    let types = &img.types;
    let roots = img.globals.iter().map(|g| (g.addr, g.ty));
    let roots = roots.chain(img.programs.iter().map(|p| (p.base, p.ty)));
    for (start, root) in roots {
        let off = addr.wrapping_sub(start);
        if addr >= start && off < types.size(root) {
            return within(types, root, off, ty);
        }
    }
    false
}

/// Whether a `want` starts at slot `off` of a value of type `ty`.
fn within(types: &TypeTable, mut ty: TypeId, mut off: u32, want: TypeId) -> bool {
    loop {
        if off == 0 && same(types, ty, want) {
            return true;
        }
        let (inner, at) = match &types.get(ty).kind {
            TypeKind::Struct { fields: members } | TypeKind::Pou { members, .. } => {
                // A VAR_IN_OUT (a METHOD's too) or VAR_EXTERNAL member
                // is one slot holding an address, not a value of its type.
                let Some(m) = members.iter().find(|m| {
                    !matches!(m.kind, MemberKind::InOut | MemberKind::External)
                        && off >= m.offset
                        && off - m.offset < types.size(m.ty)
                }) else {
                    return false;
                };
                (m.ty, off - m.offset)
            }
            TypeKind::Array { elem, .. } => {
                let stride = types.size(*elem);
                if stride == 0 {
                    return false;
                }
                (*elem, off % stride)
            }
            _ => return false,
        };
        ty = inner;
        off = at;
    }
}

/// Whether a value of type `a` may be read as a `b`: the same type, or
/// two strings of the same width.
fn same(types: &TypeTable, a: TypeId, b: TypeId) -> bool {
    a == b || types.same_width_strings(a, b)
}
