//! `AND`, `OR`, `XOR` and `NOT` on integers (`i AND 16#0F`, `NOT di`), as
//! CODESYS and TwinCAT accept them: bitwise on the two's complement of
//! the integer's width, the type kept. IEC gives these operators bit
//! strings only, so each use is a compatibility warning (W488).

use super::body::BodyBuilder;
use super::consts::{Const, int_to_slot, slot_to_int};
use super::emit::{Ty, Val};
use crate::ir::op::Op;
use crate::source::Span;
use crate::syntax::ast::BinaryOp;

impl BodyBuilder<'_> {
    /// W488 when `op` is a bit operator applied to integers of type
    /// `common` (already accepted by `operands_fit`).
    pub(super) fn int_bit_operands(&mut self, op: BinaryOp, common: Ty, span: Span) {
        if !matches!(op, BinaryOp::And | BinaryOp::Or | BinaryOp::Xor) {
            return;
        }
        let Ty::T(t) = common else {
            return;
        };
        if let Some(e) = self.scalar(t).filter(|e| e.is_int()) {
            self.int_bit_warning(super::binary::binary_name(op), e.name(), span);
        }
    }

    /// `NOT v` for an integer `v`: every bit of its width inverted (W488);
    /// `None` when `v` is not an integer.
    pub(super) fn int_not(&mut self, v: &Val, span: Span) -> Option<Val> {
        let t = v.ty().id()?;
        if self.is_enum(t) {
            return None;
        }
        let e = self.scalar(t).filter(|e| e.is_int())?;
        self.int_bit_warning("NOT", e.name(), span);
        Some(match v {
            Val::Const(Const::Bits(b), _) => {
                let v = slot_to_int(*b, e);
                let inverted = if e.is_signed_int() {
                    !v
                } else {
                    !v & ((1i128 << e.bits()) - 1)
                };
                Val::Const(Const::Bits(int_to_slot(inverted, e)?), Ty::T(t))
            }
            Val::Slot(s, _) => {
                let d = self.block.temp();
                // Signed values are held sign-extended: inverting all 64
                // bits keeps them so. Unsigned ones are cut to their width.
                let shift = if e.is_signed_int() {
                    0
                } else {
                    super::typeck::shift_of(e)
                };
                self.block.emit(Op::NotW { d, a: *s, shift });
                Val::Slot(d, t)
            }
            _ => return None,
        })
    }

    fn int_bit_warning(&mut self, op: &str, ty: &str, span: Span) {
        self.diags.warning(
            "W488",
            span,
            format!("{op} on the integer type {ty} (a CODESYS extension): bitwise, on the two's complement of its width"),
        );
    }
}
