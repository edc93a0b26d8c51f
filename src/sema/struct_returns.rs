//! Calls that denote storage rather than a value:
//! - a FUNCTION returning an array or a structure (`s := F(x);`,
//!   `F(x).a`): its result is copied out of the function's static frame
//!   into temporaries of the caller at once, so that a second call of the
//!   same function in the same statement (`G(F(1), F(2))`) cannot
//!   overwrite it; strings in it get string temporaries of their own;
//! - a METHOD returning an array or a structure, the same way;
//! - `inst(...).Q`: the instance is called, then the expression denotes
//!   the instance, whose outputs are read (CODESYS accepts this; W345).

use super::body::BodyBuilder;
use super::emit::{Place, PlaceRef, Val};
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{TypeId, TypeKind};
use crate::syntax::ast::Call;

impl BodyBuilder<'_> {
    /// The place call `call` denotes (`None` after an error).
    pub(super) fn call_place(&mut self, call: &Call) -> Option<PlaceRef> {
        // `Tc2_Utilities.SYSTEMTIME_TO_FILETIME(t)`: the function itself.
        if let Some(plain) = self.without_namespace(call) {
            return self.call_place(&plain);
        }
        let method = self.oop_call(call, true);
        if method.is_none() && !self.calls_a_function(call) {
            let inst = self.place(&call.callee)?;
            self.fb_call(&inst, &call.args, call.span);
            self.diags.warning(
                "W345",
                call.span,
                "calling a function block instance inside an expression is a CODESYS extension; edition 3 calls it as a statement, then reads its outputs",
            );
            return Some(PlaceRef {
                writable: false,
                readonly_reason: Some("it is read from an instance called in this expression"),
                ..inst
            });
        }
        let v = method.unwrap_or_else(|| self.call_function(call, None, true));
        match v {
            Val::Slot(addr, ty) if self.is_aggregate(ty) => Some(self.result_copy(addr, ty)),
            v => {
                if !v.is_error() {
                    self.diags
                        .error("E402", call.span, "this expression is not a variable");
                }
                None
            }
        }
    }

    /// True for an array, a structure or a function block instance (a
    /// FUNCTION may return one, as CODESYS allows).
    fn is_aggregate(&self, ty: TypeId) -> bool {
        matches!(
            self.types.get(ty).kind,
            TypeKind::Array { .. }
                | TypeKind::Struct { .. }
                | TypeKind::Pou { program: false, .. }
                | TypeKind::NativeFb(_)
        )
    }

    /// The address of the aggregate result of function `p` (slot 0 of its
    /// frame).
    pub(super) fn aggregate_result_address(&mut self, p: usize, ret: TypeId) -> Val {
        Val::Slot(self.callee_frame_address(p, 0), ret)
    }

    /// A temporary holding the address of slot `offset` of function `p`'s
    /// static frame (relocated when the linker places the frame).
    pub(super) fn callee_frame_address(&mut self, p: usize, offset: u32) -> Slot {
        let d = self.block.temp();
        let imm = i32::try_from(offset).unwrap_or(i32::MAX);
        let at = self.block.emit(Op::LoadI { d, imm });
        self.block.fixups.push((at, p));
        // The immediate is relocated: not a constant to fold.
        self.block.last_def = None;
        d
    }

    /// Copies a result of type `ty` at the address in `addr` into fresh
    /// temporaries; the place of the copy.
    fn result_copy(&mut self, addr: Slot, ty: TypeId) -> PlaceRef {
        let size = self.types.size(ty);
        let region = self.block.temps(size.max(1));
        let mut strings = Vec::new();
        self.string_slots(ty, 0, &mut strings);
        for (off, max, wide) in strings {
            let id = self.string_temp(max, wide);
            self.block.emit(Op::Mov {
                d: region.offset(off),
                s: id,
            });
            self.block.last_def = None;
        }
        let d = self.block.temp();
        self.block.emit(Op::AddrOf { d, off: region });
        self.copy_value(d, addr, ty);
        PlaceRef {
            place: Place::Frame(region),
            ty,
            writable: false,
            readonly_reason: Some("it is the result of a function call"),
            input_image: false,
        }
    }

    /// The offsets (from `base`), capacities and widths of the string
    /// slots of a value of type `ty`.
    fn string_slots(&self, ty: TypeId, base: u32, out: &mut Vec<(u32, u32, bool)>) {
        match &self.types.get(ty).kind {
            TypeKind::Str { max, wide } => out.push((base, *max, *wide)),
            TypeKind::Struct { fields } => {
                for f in fields {
                    self.string_slots(f.ty, base + f.offset, out);
                }
            }
            TypeKind::Array { dims, elem } if self.contains_strings(*elem) => {
                let count: u64 = dims.iter().map(|d| d.len()).product();
                let stride = self.types.size(*elem);
                for i in 0..count as u32 {
                    self.string_slots(*elem, base + i * stride, out);
                }
            }
            // An instance returned by a FUNCTION: the strings among its
            // variables (a copy of it copies them by text, fb_copy.rs).
            TypeKind::Pou { .. } => {
                for (offset, member) in self.fb_string_members(ty) {
                    self.string_slots(member, base + offset, out);
                }
            }
            _ => {}
        }
    }
}
