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
use super::implicit_checks::{CHECK_DIV_DINT, CHECK_DIV_LINT, CHECK_DIV_LREAL, CHECK_DIV_REAL};
use crate::elementary::ElemType;
use crate::ir::op::Slot;
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
        self.through_check(check, (b, e, input), Vec::new(), span)
    }
}
