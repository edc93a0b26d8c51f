//! Assignment inside an expression, `(x := v)` (CODESYS, TwinCAT): `v` is
//! stored in `x`, and the expression's value is the value stored (converted
//! to `x`'s type), so `IF (i := i + 1) = n THEN` counts and tests in one.

use super::body::BodyBuilder;
use super::emit::Val;
use crate::ir::op::Op;
use crate::ir::op::Slot;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::Expr;

impl BodyBuilder<'_> {
    /// Stores `value` into `target` and gives the value stored.
    pub(super) fn assign_expr(&mut self, target: &Expr, value: &Expr, span: Span) -> Val {
        if let Some((base, sel)) = self.part_of(target) {
            let ty = TypeTable::elem(sel.size.elem());
            let v = self.expr(value, Some(ty));
            let v = self.coerce(v, ty, value.span, "assignment");
            if v.is_error() {
                return v;
            }
            let kept = self.kept_copy(&v, ty);
            self.store_part(base, sel, Val::Slot(kept, ty), value.span);
            return Val::Slot(kept, ty);
        }
        let Some(p) = self.place(target) else {
            self.expr(value, None);
            return Val::error();
        };
        if !self.check_writable(&p, target.span) {
            self.expr(value, None);
            return Val::error();
        }
        match self.types.get(p.ty).kind {
            TypeKind::Error => return Val::error(),
            TypeKind::Array { .. }
            | TypeKind::Struct { .. }
            | TypeKind::NativeFb(_)
            | TypeKind::Pou { .. }
            | TypeKind::Step
            | TypeKind::OpenArray { .. } => {
                let name = self.types.name(p.ty).to_string();
                self.diags.error(
                    "E414",
                    span,
                    format!(
                        "an assignment inside an expression stores one value; a {name} is copied by an assignment statement"
                    ),
                );
                return Val::error();
            }
            _ => {}
        }
        self.check_ref_escape(target, value);
        let v = self.expr(value, Some(p.ty));
        let v = self.coerce(v, p.ty, value.span, "assignment");
        if v.is_error() {
            return v;
        }
        let kept = self.kept_copy(&v, p.ty);
        self.write_place(&p, kept);
        Val::Slot(kept, p.ty)
    }

    /// `v` copied into a temporary of its own: the expression's value must
    /// not change when the target, or a variable `v` was read from, is
    /// written again later in the same expression.
    fn kept_copy(&mut self, v: &Val, ty: TypeId) -> Slot {
        let s = self.materialize(v);
        let kept = match self.types.get(ty).kind {
            TypeKind::Str { max, wide } => {
                let t = self.string_temp(max, wide);
                self.block.emit(Op::StrMov { d: t, s });
                t
            }
            _ => {
                let t = self.block.temp();
                self.block.emit(Op::Mov { d: t, s });
                t
            }
        };
        // Not to be retargeted by the store that follows.
        self.block.last_def = None;
        kept
    }
}
