//! CODESYS `REFERENCE TO`: a reference that names its target wherever it
//! is used, bound with `r REF= x`. Its value and checks are those of
//! `REF_TO`; only the syntax differs. A `REFERENCE TO T` input of a
//! FUNCTION, FUNCTION_BLOCK or METHOD is bound the same way by the call:
//! `F(r := x)` binds `r` to the variable `x` (of type `T`, an FB instance
//! as well as an elementary variable), as `r REF= x` would.

use super::ref_parts;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{RefFlavor, TypeId};
use crate::sema::body::BodyBuilder;
use crate::sema::emit::{Place, PlaceRef, Ty, Val};
use crate::syntax::ast::{Expr, ExprKind};

/// The outcome of [`BodyBuilder::reference_argument`].
pub(in crate::sema) enum RefArg {
    /// Not a `REFERENCE TO` parameter bound from a variable: the argument
    /// is an ordinary value (a `REF_TO` value, `REF(x)`, ...).
    Value,
    /// The reference value, in a temporary.
    Bound(Slot),
    /// An error was reported.
    Error,
}

impl BodyBuilder<'_> {
    /// The type a value of type `t` stands for where it is used: the
    /// target of a `REFERENCE TO`, any other type as is.
    pub(in crate::sema) fn designated(&self, t: TypeId) -> TypeId {
        match ref_parts(self.types, t) {
            Some((target, RefFlavor::Reference)) => target,
            _ => t,
        }
    }

    /// The argument `e` of a parameter of type `ty`: when `ty` is a
    /// `REFERENCE TO T` and `e` names a variable (not a reference value),
    /// the reference binding the parameter to that variable.
    pub(in crate::sema) fn reference_argument(
        &mut self,
        ty: TypeId,
        e: &Expr,
        what: &str,
    ) -> RefArg {
        let Some((target, RefFlavor::Reference)) = ref_parts(self.types, ty) else {
            return RefArg::Value;
        };
        let Some(given) = self.static_type(e) else {
            return RefArg::Value;
        };
        if matches!(ref_parts(self.types, given), Some((_, f)) if f != RefFlavor::Reference) {
            return RefArg::Value;
        }
        let Some(q) = self.place(e) else {
            return RefArg::Error;
        };
        if q.ty != target {
            self.mismatch(e.span, Ty::T(q.ty), target, what);
            return RefArg::Error;
        }
        if !q.writable {
            self.diags.error(
                "E412",
                e.span,
                format!("{what} is a REFERENCE TO: it needs a writable variable"),
            );
            return RefArg::Error;
        }
        self.note_input_write(&q, e.span);
        RefArg::Bound(self.reference_value(&q))
    }

    /// A new reference value designating the variable at `q`.
    pub(in crate::sema) fn reference_value(&mut self, q: &PlaceRef) -> Slot {
        let len = self.types.size(q.ty).max(1);
        let layout = self.object_layout(q.ty);
        let addr = self.address_of(q);
        let d = self.block.temp();
        self.block.emit(Op::RefMake {
            d,
            p: addr,
            len,
            layout,
        });
        d
    }

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
            // A target whose type is unknown has its error already (E203).
            if p.ty == crate::ir::type_table::TypeTable::error() {
                return;
            }
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
        if let ExprKind::Call(_) = &value.kind {
            // `r REF= obj.Get();`: a call that returns a REFERENCE TO (TcUnit)
            // gives the reference itself.
            let v = self.expr(value, None);
            match v.ty().id().and_then(|ty| ref_parts(self.types, ty)) {
                Some((vt, RefFlavor::Reference)) if vt == t => {
                    let s = self.materialize(&v);
                    self.write_place(&p, s);
                }
                _ if v.is_error() => {}
                _ => self.mismatch(value.span, v.ty(), p.ty, "REF="),
            }
            return;
        }
        let Some(q) = self.place(value) else {
            return;
        };
        if q.ty != t {
            self.mismatch(value.span, Ty::T(q.ty), t, "REF=");
            return;
        }
        let d = self.reference_value(&q);
        self.write_place(&p, d);
    }
}
