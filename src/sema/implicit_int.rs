//! CODESYS's implicit conversions between integer types and bit strings
//! that may change the value: a narrower destination (`b : BYTE := w`), or
//! a change of sign (`u : UDINT := i` with `i : INT`). CODESYS V3 and
//! TwinCAT 3 compile them with a warning and keep the low bits of the
//! two's complement, as `*_TO_*` between bit strings does; plcrun does the
//! same in the files written in that dialect (W490, refused by
//! `--strict`), and refuses them elsewhere (E301), as IEC does. The conversions that keep every
//! value are `ElemType::widens_to` and `bits_arith::codesys_widens`.

use super::body::BodyBuilder;
use crate::elementary::{ElemType, Family};
use crate::ir::op::Conv;
use crate::sema::emit::{Ty, Val};
use crate::source::Span;

/// Whether `from` and `to` are both integers or bit strings (not BOOL)
/// and a `from` value stored in a `to` may change: the conversion W490
/// allows.
pub(super) fn may_change(from: ElemType, to: ElemType) -> bool {
    let integral = |e: ElemType| {
        matches!(e.family(), Family::Signed | Family::Unsigned | Family::Bits)
            && e != ElemType::Bool
    };
    integral(from)
        && integral(to)
        && from != to
        && !from.widens_to(to)
        && !super::bits_arith::codesys_widens(from, to)
}

/// The instruction that turns a `from` slot into a `to` one when
/// [`may_change`] holds: the low bits of `to`'s width, sign-extended for
/// a signed `to`, zero-extended otherwise.
pub(super) fn wrap(from: ElemType, to: ElemType) -> Option<Conv> {
    if !may_change(from, to) {
        return None;
    }
    let shift = super::typeck::shift_of(to);
    Some(if to.is_signed_int() {
        Conv::WrapS(shift)
    } else {
        Conv::WrapU(shift)
    })
}

impl BodyBuilder<'_> {
    /// W490 for an implicit conversion of `from` to `to` that may change
    /// the value; true when it is one.
    pub(super) fn implicit_int_conversion(
        &mut self,
        from: ElemType,
        to: ElemType,
        span: Span,
    ) -> bool {
        if !may_change(from, to) || !self.model.codesys_files.contains(&span.file) {
            return false;
        }
        let why = if from.bits() > to.bits() {
            "the value is cut to its low bits"
        } else {
            "the sign may change"
        };
        self.diags.warning(
            "W490",
            span,
            format!(
                "implicit conversion of {} to {} (CODESYS): {why}; write {}_TO_{} to say so",
                from.name(),
                to.name(),
                from.name(),
                to.name()
            ),
        );
        true
    }
}

impl BodyBuilder<'_> {
    /// In a CODESYS-dialect file, the type a signed and an unsigned
    /// integer combine in (`nState > GeneralConstants.MAX_STATES`, INT
    /// and UINT): the smallest signed integer holding both, as CODESYS
    /// converts them (LINT for a ULINT, W490 as a ULINT may not fit). A
    /// slot holds an integer's value sign- or zero-extended, so the
    /// operands need no conversion.
    pub(super) fn mixed_sign_common(&mut self, va: &Val, vb: &Val, span: Span) -> Option<Ty> {
        if !self.model.codesys_files.contains(&span.file) {
            return None;
        }
        let int = |me: &Self, v: &Val| {
            v.ty()
                .id()
                .filter(|t| !me.is_enum(*t))
                .and_then(|t| me.types.scalar(t))
                .filter(|e| e.is_int())
        };
        let (a, b) = (int(self, va)?, int(self, vb)?);
        if a.is_signed_int() == b.is_signed_int() {
            return None;
        }
        let bits = a.bits().max(b.bits());
        let unsigned_bits = if a.is_signed_int() {
            b.bits()
        } else {
            a.bits()
        };
        let wide = bits.max(unsigned_bits * 2).min(64);
        let common = match wide {
            16 => ElemType::Int,
            32 => ElemType::Dint,
            64 => ElemType::Lint,
            _ => ElemType::Sint,
        };
        for e in [a, b] {
            if e != common {
                self.implicit_int_conversion(e, common, span);
            }
        }
        Some(Ty::T(crate::ir::type_table::TypeTable::elem(common)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ElemType as E;

    #[test]
    fn only_conversions_that_may_change_the_value_count() {
        assert!(may_change(E::Int, E::Udint));
        assert!(may_change(E::Ulint, E::Udint));
        assert!(may_change(E::Word, E::Byte));
        assert!(may_change(E::Udint, E::Dint));
        assert!(!may_change(E::Int, E::Dint));
        assert!(!may_change(E::Byte, E::Int));
        assert!(!may_change(E::Bool, E::Int));
        assert!(!may_change(E::Int, E::Real));
        assert!(!may_change(E::Time, E::Dint));
    }
}
