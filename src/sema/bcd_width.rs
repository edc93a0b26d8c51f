//! The width of an edition-2 `*_TO_BCD` result from its context.
//!
//! Edition 2 declares `INT_TO_BCD` (and the other `<int>_TO_BCD`) as an
//! overloaded conversion from an integer to ANY_BIT; edition 3 spells the
//! width out (`INT_TO_BCD_WORD`). Without a context plcrun gives the bit
//! string of the source's width (INT to WORD); where the context expects a
//! bit string (`b := INT_TO_BCD(i)` with `b : BYTE`) the result takes that
//! width instead, warning W347. A value with more decimal digits than the
//! width holds is a runtime fault, as for the edition-3 spellings.

use super::body::BodyBuilder;
use crate::elementary::{ElemType, Family};
use crate::ir::type_table::TypeId;
use crate::source::Span;

impl BodyBuilder<'_> {
    /// The result type of `<int>_TO_BCD`: `to` when the name gives it,
    /// else the bit string the context expects (W347 when that is not the
    /// source's width), else `None` (the source's width).
    pub(super) fn bcd_target_type(
        &mut self,
        fname: &str,
        to: Option<ElemType>,
        source_bits: Option<u32>,
        expect: Option<TypeId>,
        span: Span,
    ) -> Option<ElemType> {
        if to.is_some() {
            return to;
        }
        let want = expect
            .filter(|t| !self.is_enum(*t))
            .and_then(|t| self.scalar(t))
            .filter(|e| e.family() == Family::Bits)?;
        if source_bits == Some(want.bits()) {
            return Some(want);
        }
        self.diags.warning(
            "W347",
            span,
            format!(
                "{fname} gives the {want} the context expects (edition 2: the result is any bit \
                 string); edition 3 writes {fname}_{want}"
            ),
        );
        Some(want)
    }
}
