//! CODESYS's implicit division checks: when a project declares
//! `CheckDivDInt(divisor : DINT) : DINT` (or `CheckDivLInt`,
//! `CheckDivReal`, `CheckDivLReal`), a division whose divisor is computed
//! divides by what the function returns — the usual one returns 1 for 0,
//! so `x / 0` is `x` instead of a fault. An integer divisor goes through
//! the check of its width (DINT up to 32 bits, LINT above) and comes back
//! with its low bits, as CODESYS converts it; `MOD`, a constant divisor
//! and a duration divided by a number call none. Where it applies:
//! implicit_checks.rs.

use super::body::BodyBuilder;
use super::emit::Val;
use super::implicit_checks::{CHECK_DIV_DINT, CHECK_DIV_LINT, CHECK_DIV_LREAL, CHECK_DIV_REAL};
use super::implicit_int::wrap;
use crate::elementary::ElemType;
use crate::ir::op::Slot;
use crate::ir::type_table::TypeTable;
use crate::source::Span;

impl BodyBuilder<'_> {
    /// The divisor `b` (of type `e`) passed through the project's division
    /// check when one applies here; `b` itself otherwise.
    pub(super) fn checked_divisor(&mut self, b: Slot, e: ElemType, span: Span) -> Slot {
        let (name, input) = match e {
            ElemType::Real => (CHECK_DIV_REAL, ElemType::Real),
            ElemType::Lreal => (CHECK_DIV_LREAL, ElemType::Lreal),
            e if e.is_int() && e.bits() > 32 => (CHECK_DIV_LINT, ElemType::Lint),
            e if e.is_int() => (CHECK_DIV_DINT, ElemType::Dint),
            _ => return b,
        };
        let Some(check) = self.implicit_check(name, span) else {
            return b;
        };
        let arg = self.quietly_as(Val::Slot(b, TypeTable::elem(e)), e, input, span);
        let result = self.call_implicit_check(check, vec![arg], span);
        let back = self.quietly_as(result, input, e, span);
        self.materialize(&back)
    }

    /// `v` of type `from` as a `to`: the same slot when every value fits,
    /// else its low bits (the implicit conversion CODESYS makes, without
    /// its warning: the compiler wrote it, not the user).
    pub(super) fn quietly_as(&mut self, v: Val, from: ElemType, to: ElemType, span: Span) -> Val {
        match (v, wrap(from, to)) {
            (v, Some(conv)) => self.apply_conv(v, conv, to, span),
            (Val::Slot(s, _), None) => Val::Slot(s, TypeTable::elem(to)),
            (other, None) => other,
        }
    }
}
