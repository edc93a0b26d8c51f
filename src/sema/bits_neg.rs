//! Unary `-` on a bit string (BYTE..LWORD), the CODESYS way.
//!
//! IEC 61131-3 defines negation for ANY_NUM only; bit strings are not
//! numbers. CODESYS accepts `-dw` and, as for its other arithmetic on bit
//! strings (W350), computes it as the unsigned integer of the same width:
//! the result is the two's complement `0 - x` wrapped to the bit string's
//! width, and keeps the bit string's type. Each use warns W324, which
//! `--strict` makes an error.

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use super::typeck::shift_of;
use crate::elementary::ElemType;
use crate::ir::op::Op;
use crate::source::Span;

/// Two's complement of `b` in a `bits`-wide bit string (zero-extended).
fn negate_in_width(b: u64, bits: u32) -> u64 {
    let r = b.wrapping_neg();
    if bits >= 64 {
        r
    } else {
        r & ((1u64 << bits) - 1)
    }
}

impl BodyBuilder<'_> {
    /// `-v` when `v` is a bit string BYTE..LWORD; `None` otherwise (the
    /// IEC rules then apply and report).
    pub(super) fn bit_string_neg(&mut self, v: &Val, span: Span) -> Option<Val> {
        let id = v.ty().id()?;
        if self.is_enum(id) {
            return None;
        }
        let e = self.scalar(id)?;
        if !matches!(
            e,
            ElemType::Byte | ElemType::Word | ElemType::Dword | ElemType::Lword
        ) {
            return None;
        }
        self.diags.warning(
            "W324",
            span,
            format!(
                "unary `-` on a bit string ({}) is a CODESYS extension: it gives the two's \
                 complement in the same width (0 - x)",
                e.name()
            ),
        );
        Some(match v {
            Val::Const(Const::Bits(b), t) => {
                Val::Const(Const::Bits(negate_in_width(*b, e.bits())), *t)
            }
            _ => {
                let a = self.materialize(v);
                let zero = self.materialize(&Val::Const(Const::Bits(0), Ty::T(id)));
                let d = self.block.temp();
                self.block.emit(Op::SubU {
                    d,
                    a: zero,
                    b: a,
                    shift: shift_of(e),
                });
                Val::Slot(d, self.plain(id))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::negate_in_width;

    #[test]
    fn twos_complement_in_width() {
        assert_eq!(negate_in_width(1, 8), 0xFF);
        assert_eq!(negate_in_width(0, 16), 0);
        assert_eq!(negate_in_width(0x8000, 16), 0x8000);
        assert_eq!(negate_in_width(1, 32), 0xFFFF_FFFF);
        assert_eq!(negate_in_width(1, 64), u64::MAX);
    }
}
