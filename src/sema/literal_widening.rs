//! An integer literal too large for the other operand's type, the CODESYS
//! way: `off * 60000` with `off : INT` (OSCAT's CALENDAR_CALC).
//!
//! IEC 61131-3 types an untyped literal by the other operand, so 60000
//! beside an INT does not fit (E304). CODESYS computes in at least 32 bits
//! and types the literal by its value, so the operation is done in the
//! smallest signed integer type that holds both the literal and every
//! value of the other operand (DINT here, LINT beyond), the result having
//! that type. plcrun does the same with warning W348 (`--strict` makes it
//! an error); when no such type exists the IEC error stays.

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use crate::elementary::ElemType;
use crate::ir::type_table::TypeTable;
use crate::source::Span;

impl BodyBuilder<'_> {
    /// The common type of `va op vb` after widening for a literal operand
    /// that does not fit `common`; `common` itself otherwise.
    pub(super) fn widen_for_literal(&mut self, va: &Val, vb: &Val, common: Ty, span: Span) -> Ty {
        let Ty::T(t) = common else {
            return common;
        };
        if self.is_enum(t) {
            return common;
        }
        let Some(e) = self.scalar(t).filter(|e| e.is_int()) else {
            return common;
        };
        let literal = |v: &Val| match v {
            Val::Const(Const::Int(n), Ty::AnyInt) => Some(*n),
            _ => None,
        };
        let Some(n) = literal(va).or_else(|| literal(vb)) else {
            return common;
        };
        let fits = |t: ElemType| t.int_range().is_some_and(|(lo, hi)| lo <= n && n <= hi);
        if fits(e) {
            return common;
        }
        let Some(wide) = [ElemType::Dint, ElemType::Lint]
            .into_iter()
            .find(|w| e.widens_to(*w) && fits(*w))
        else {
            return common;
        };
        self.diags.warning(
            "W348",
            span,
            format!(
                "the literal {n} does not fit {e}: the operation is done in {wide}, as CODESYS \
                 does (IEC types the literal as {e}); write {wide}#{n} or convert the operand"
            ),
        );
        Ty::T(TypeTable::elem(wide))
    }
}
