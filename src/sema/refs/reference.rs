//! CODESYS `REFERENCE TO`: a reference that names its target wherever it
//! is used, bound with `r REF= x`. Its value and checks are those of
//! `REF_TO`; only the syntax differs.

use super::{layout_code, ref_parts};
use crate::ir::op::Op;
use crate::ir::type_table::RefFlavor;
use crate::sema::body::BodyBuilder;
use crate::sema::emit::{Place, PlaceRef, Ty, Val};
use crate::syntax::ast::Expr;

impl BodyBuilder<'_> {
    /// The variable a `REFERENCE TO` place is bound to (checked when the
    /// code runs: an unbound reference is R030); any other place as is.
    pub(in crate::sema) fn implicit_deref(&mut self, p: PlaceRef) -> PlaceRef {
        let Some((target, RefFlavor::Reference)) = ref_parts(self.types, p.ty) else {
            return p;
        };
        let Val::Slot(r, _) = self.read_place(&p) else {
            return p;
        };
        let width = self.types.size(target).max(1);
        let a = self.checked_address(r, width);
        PlaceRef {
            place: Place::Ind { p: a, off: 0 },
            ty: target,
            writable: true,
            readonly_reason: None,
            input_image: false,
        }
    }

    /// `target REF= value;`: binds the `REFERENCE TO` variable `target` to
    /// the variable `value` (of exactly its target type).
    pub(in crate::sema) fn ref_bind(&mut self, target: &Expr, value: &Expr) {
        let Some(p) = self.place_raw(target) else {
            return;
        };
        let Some((t, RefFlavor::Reference)) = ref_parts(self.types, p.ty) else {
            let name = self.types.name(p.ty).to_string();
            self.diags.error(
                "E255",
                target.span,
                format!("`REF=` binds a REFERENCE TO variable, not a {name}"),
            );
            return;
        };
        if !self.check_writable(&p, target.span) {
            return;
        }
        self.check_escape_of(target, value, value.span);
        let Some(q) = self.place(value) else {
            return;
        };
        if q.ty != t {
            self.mismatch(value.span, Ty::T(q.ty), t, "REF=");
            return;
        }
        let len = self.types.size(q.ty).max(1);
        let layout = layout_code(self.types, q.ty);
        let addr = self.address_of(&q);
        let d = self.block.temp();
        self.block.emit(Op::RefMake {
            d,
            p: addr,
            len,
            layout,
        });
        self.write_place(&p, d);
    }
}
