//! `AND_THEN` and `OR_ELSE` (CODESYS): the right operand is evaluated
//! only when the left one does not decide the result, so it may guard a
//! division or an index (`i <= 10 AND_THEN a[i] > 0`).

use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use crate::elementary::ElemType;
use crate::ir::op::{Op, Target};
use crate::ir::type_table::TypeTable;
use crate::syntax::ast::{BinaryOp, Expr};

impl BodyBuilder<'_> {
    /// Checks and emits `a AND_THEN b` or `a OR_ELSE b`: the result slot
    /// starts as the value that the left operand decides (FALSE for
    /// AND_THEN, TRUE for OR_ELSE), a jump skips the right operand when
    /// the left one equals it, and otherwise the right operand is the
    /// result. Both operands must be BOOL (E303).
    pub(super) fn short_circuit(&mut self, op: BinaryOp, a: &Expr, b: &Expr) -> Val {
        let decides = op == BinaryOp::OrElse;
        let bool_t = TypeTable::elem(ElemType::Bool);
        let d = self.block.temp();
        let k = self.block.const_slot(decides as u64);
        self.block.emit(Op::Mov { d, s: k });
        let Some(va) = self.bool_operand(op, a) else {
            return Val::error();
        };
        let sa = self.materialize(&va);
        let skip = self.branch_on_slot(sa, decides, Target::UNPATCHED);
        let Some(vb) = self.bool_operand(op, b) else {
            return Val::error();
        };
        let sb = self.materialize(&vb);
        self.block.mov(d, sb);
        let end = self.block.here();
        self.block.patch(skip, end);
        Val::Slot(d, bool_t)
    }

    /// One operand of AND_THEN / OR_ELSE: a BOOL value, or E302 naming
    /// the operator and the type found.
    fn bool_operand(&mut self, op: BinaryOp, e: &Expr) -> Option<Val> {
        let bool_t = TypeTable::elem(ElemType::Bool);
        let v = self.expr(e, Some(bool_t));
        if v.is_error() {
            return None;
        }
        if v.ty() != Ty::T(bool_t) {
            self.bad_operand(e.span, super::binary::binary_name(op), v.ty());
            return None;
        }
        Some(v)
    }
}
