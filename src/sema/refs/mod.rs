//! References and pointers in the checker: `REF_TO T` / `POINTER TO T`
//! types, `REF(x)`, `ADR(x)`, `SIZEOF`, `NULL`, `r^`, comparisons,
//! pointer arithmetic and `__ISVALIDREF`.
//!
//! A reference value is one slot (see [`crate::ir::refs`]): the object it
//! was taken from and an offset. `REF(x)` emits `RefMake` over the slots of
//! `x`; every `r^` emits `RefAddr`, which checks NULL and the object's
//! extent at run time and yields an absolute address the ordinary indirect
//! loads and stores then use. `r^[i]` on a reference to an array moves the
//! reference to the element first (`RefIndex`) so that only the element is
//! checked against the object: a `POINTER TO ARRAY[0..32767] OF BYTE`
//! walks a 10-byte array safely.

mod calls;
mod convert;
mod object_layout;
mod ops;
mod place;
mod reference;
mod string_bytes;
mod types;

pub(super) use reference::RefArg;

use crate::elementary::ElemType;
use crate::ir::type_table::{RefFlavor, TypeDef, TypeId, TypeKind, TypeTable};

/// The target and flavour of a reference type.
pub(super) fn ref_parts(types: &TypeTable, t: TypeId) -> Option<(TypeId, RefFlavor)> {
    match types.get(t).kind {
        TypeKind::Ref { target, flavor } => Some((target, flavor)),
        _ => None,
    }
}

/// The reference type of `flavor` to `target` (interned).
pub(in crate::sema) fn intern_ref(
    types: &mut TypeTable,
    target: TypeId,
    flavor: RefFlavor,
) -> TypeId {
    let name = match flavor {
        RefFlavor::RefTo => format!("REF_TO {}", types.name(target)),
        RefFlavor::Pointer => format!("POINTER TO {}", types.name(target)),
        RefFlavor::Reference => format!("REFERENCE TO {}", types.name(target)),
        RefFlavor::Null => "NULL".to_string(),
    };
    types.intern(TypeDef {
        name,
        kind: TypeKind::Ref { target, flavor },
        size: 1,
    })
}

/// The type of `NULL`.
pub(super) fn null_type(types: &mut TypeTable) -> TypeId {
    intern_ref(types, TypeTable::void(), RefFlavor::Null)
}

/// `SIZEOF` in bytes: elementary types by their width (BOOL 1 byte, TIME
/// and the date types 8 as stored here), `STRING(n)` n+1, `WSTRING(n)`
/// 2(n+1), arrays and structures the sum of their parts (no padding), a
/// reference 8. `None` for types without a size (VOID, errors).
pub(super) fn size_bytes(types: &TypeTable, t: TypeId) -> Option<u64> {
    Some(match &types.get(t).kind {
        TypeKind::Elem(e) => elem_bytes(*e),
        TypeKind::Enum { base, .. } | TypeKind::Subrange { base, .. } => elem_bytes(*base),
        TypeKind::Str { wide, max } => (*max as u64 + 1) * if *wide { 2 } else { 1 },
        TypeKind::Array { dims, elem } => {
            let n: u64 = dims.iter().map(|d| d.len()).product();
            n.checked_mul(size_bytes(types, *elem)?)?
        }
        TypeKind::Struct { fields } => fields
            .iter()
            .map(|f| size_bytes(types, f.ty))
            .sum::<Option<u64>>()?,
        TypeKind::Pou { members, .. } => members
            .iter()
            .map(|m| size_bytes(types, m.ty).unwrap_or(0))
            .sum(),
        TypeKind::NativeFb(fb) => crate::stdlib::interface(*fb)
            .iter()
            .map(|p| elem_bytes(p.ty))
            .sum(),
        TypeKind::Step => 8 + 8,
        TypeKind::Ref { .. } => 8,
        TypeKind::Void | TypeKind::Error | TypeKind::OpenArray { .. } => return None,
    })
}

fn elem_bytes(e: ElemType) -> u64 {
    match e {
        ElemType::Bool => 1,
        ElemType::String => 255,
        ElemType::WString => 510,
        _ => (e.bits() as u64).div_ceil(8),
    }
}

/// The layout code (`ir::refs::elem_code`) of an object of type `t`: its
/// innermost element's elementary type (STRING and WSTRING included), or
/// 0 for a structure, an FB or anything else without one byte layout.
pub(super) fn layout_code(types: &TypeTable, t: TypeId) -> u8 {
    let inner = types.innermost(t);
    let e = match &types.get(inner).kind {
        TypeKind::Str { wide: false, .. } => ElemType::String,
        TypeKind::Str { wide: true, .. } => ElemType::WString,
        _ => match types.scalar(inner) {
            Some(e) => e,
            None => return 0,
        },
    };
    crate::ir::refs::elem_code(e)
}

/// Bytes per slot of the innermost element of `t`: how a typed pointer's
/// slot offset turns into bytes (1 for anything without a byte layout).
pub(super) fn view_unit(types: &TypeTable, t: TypeId) -> u16 {
    let inner = types.innermost(t);
    match types.scalar(inner) {
        Some(e) if !matches!(e, ElemType::String | ElemType::WString) => {
            crate::ir::refs::elem_bytes(e) as u16
        }
        _ => 1,
    }
}

/// The elementary type a dereference of a `POINTER TO t` reads through
/// `RefLoad`/`RefStore` (so that a byte view works): any elementary type
/// but the strings; `None` for the rest, which keep the typed `RefAddr`.
pub(super) fn viewable(types: &TypeTable, t: TypeId) -> Option<ElemType> {
    if matches!(types.get(t).kind, TypeKind::Str { .. }) {
        return None;
    }
    types
        .scalar(t)
        .filter(|e| !matches!(e, ElemType::String | ElemType::WString))
}
