//! CODESYS's implicit subrange checks: when a project declares
//! `CheckRangeSigned(value, lower, upper : DINT) : DINT` (or
//! `CheckRangeUnsigned` on UDINT, `CheckLRangeSigned` on LINT,
//! `CheckLRangeUnsigned` on ULINT), a computed value stored into a
//! variable of a subrange type (assigned, passed, returned) is replaced by
//! what the function returns for it and the bounds — the usual one clamps
//! to the bounds. Signed bases up to DINT go through `CheckRangeSigned`,
//! unsigned ones and bit strings up to 32 bits through
//! `CheckRangeUnsigned`, the 64-bit ones through the `L` checks. The
//! runtime's own check (R003) still guards the result. Where it applies:
//! implicit_checks.rs.

use super::body::BodyBuilder;
use super::emit::Val;
use super::implicit_checks::{
    CHECK_LRANGE_SIGNED, CHECK_LRANGE_UNSIGNED, CHECK_RANGE_SIGNED, CHECK_RANGE_UNSIGNED,
};
use crate::elementary::ElemType;
use crate::ir::op::Slot;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;

impl BodyBuilder<'_> {
    /// The value `s` about to be stored as a `to` (a subrange type) passed
    /// through the project's range check when one applies here; `s`
    /// itself otherwise.
    pub(super) fn range_checked(&mut self, s: Slot, to: TypeId, span: Span) -> Slot {
        let TypeKind::Subrange { base, lo, hi } = self.types.get(to).kind else {
            return s;
        };
        let wide = base.bits() > 32;
        let (name, input) = match (base.is_signed_int(), wide) {
            (true, false) => (CHECK_RANGE_SIGNED, ElemType::Dint),
            (false, false) => (CHECK_RANGE_UNSIGNED, ElemType::Udint),
            (true, true) => (CHECK_LRANGE_SIGNED, ElemType::Lint),
            (false, true) => (CHECK_LRANGE_UNSIGNED, ElemType::Ulint),
        };
        let Some(check) = self.implicit_check(name, span) else {
            return s;
        };
        // The bounds are the subrange's, so they fit the check's type.
        let bound = |b: i64| Val::Const(super::consts::Const::Bits(b as u64), input_ty(input));
        self.through_check(check, (s, base, input), vec![bound(lo), bound(hi)], span)
    }
}

/// The checker's type of a constant of `e`.
fn input_ty(e: ElemType) -> super::emit::Ty {
    super::emit::Ty::T(TypeTable::elem(e))
}
