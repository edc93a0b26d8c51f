//! Integer, bit-string and BOOL instructions: 64-bit machine arithmetic,
//! then the interpreter's wrap to the type's width (`wrap_s`/`wrap_u`
//! with the same shift), so every result has the same bits.

use super::flow::{signed, unsigned};
use super::{I64, Lower};
use crate::ir::op::{Op, ShiftKind, Slot};
use crate::vm::native::helpers::WHY_OPERANDS as DIVISION;
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{InstBuilder, Value};

impl Lower<'_, '_> {
    /// Translates an integer instruction; false when `op` is not one.
    pub(super) fn int(&mut self, op: &Op) -> bool {
        match *op {
            Op::AddS { d, a, b, shift } => self.binary(d, a, b, |l, x, y| {
                let v = l.b.ins().iadd(x, y);
                l.wrap_s(v, shift)
            }),
            Op::AddU { d, a, b, shift } => self.binary(d, a, b, |l, x, y| {
                let v = l.b.ins().iadd(x, y);
                l.wrap_u(v, shift)
            }),
            Op::AddSI { d, a, imm, shift } => {
                let x = self.get(a);
                let v = self.b.ins().iadd_imm_s(x, imm as i64);
                let v = self.wrap_s(v, shift);
                self.set(d, v);
            }
            Op::SubS { d, a, b, shift } => self.binary(d, a, b, |l, x, y| {
                let v = l.b.ins().isub(x, y);
                l.wrap_s(v, shift)
            }),
            Op::SubU { d, a, b, shift } => self.binary(d, a, b, |l, x, y| {
                let v = l.b.ins().isub(x, y);
                l.wrap_u(v, shift)
            }),
            Op::MulS { d, a, b, shift } => self.binary(d, a, b, |l, x, y| {
                let v = l.b.ins().imul(x, y);
                l.wrap_s(v, shift)
            }),
            Op::MulU { d, a, b, shift } => self.binary(d, a, b, |l, x, y| {
                let v = l.b.ins().imul(x, y);
                l.wrap_u(v, shift)
            }),
            Op::DivS { d, a, b, shift } | Op::ModS { d, a, b, shift } => {
                let (x, y) = (self.get(a), self.get(b));
                let zero = self.b.ins().icmp_imm_s(IntCC::Equal, y, 0);
                self.fault_if(zero, DIVISION);
                let v = self.signed_div(x, y, matches!(op, Op::ModS { .. }));
                let v = self.wrap_s(v, shift);
                self.set(d, v);
            }
            Op::DivU { d, a, b, shift } | Op::ModU { d, a, b, shift } => {
                let (x, y) = (self.get(a), self.get(b));
                let zero = self.b.ins().icmp_imm_s(IntCC::Equal, y, 0);
                self.fault_if(zero, DIVISION);
                let v = if matches!(op, Op::ModU { .. }) {
                    self.b.ins().urem(x, y)
                } else {
                    self.b.ins().udiv(x, y)
                };
                let v = self.wrap_u(v, shift);
                self.set(d, v);
            }
            Op::ModSI { d, a, imm, shift } => {
                // `imm` is not 0 (support.rs); by -1 the remainder is 0.
                let x = self.get(a);
                let v = if imm == -1 {
                    self.b.ins().iconst(I64, 0)
                } else {
                    let y = self.b.ins().iconst(I64, imm as i64);
                    self.b.ins().srem(x, y)
                };
                let v = self.wrap_s(v, shift);
                self.set(d, v);
            }
            Op::NegS { d, a, shift } => {
                let x = self.get(a);
                let v = self.b.ins().ineg(x);
                let v = self.wrap_s(v, shift);
                self.set(d, v);
            }
            Op::AbsS { d, a, shift } => {
                let x = self.get(a);
                let neg = self.b.ins().ineg(x);
                let below = self.b.ins().icmp_imm_s(IntCC::SignedLessThan, x, 0);
                let v = self.b.ins().select(below, neg, x);
                let v = self.wrap_s(v, shift);
                self.set(d, v);
            }
            _ => return self.bits(op),
        }
        true
    }

    /// Bit and BOOL operations, comparisons, selections.
    fn bits(&mut self, op: &Op) -> bool {
        match *op {
            Op::And { d, a, b } => self.binary(d, a, b, |l, x, y| l.b.ins().band(x, y)),
            Op::Or { d, a, b } => self.binary(d, a, b, |l, x, y| l.b.ins().bor(x, y)),
            Op::Xor { d, a, b } => self.binary(d, a, b, |l, x, y| l.b.ins().bxor(x, y)),
            Op::AndN { d, a, b } => self.binary(d, a, b, |l, x, y| {
                let n = l.b.ins().bxor_imm_s(y, 1);
                l.b.ins().band(x, n)
            }),
            Op::OrN { d, a, b } => self.binary(d, a, b, |l, x, y| {
                let n = l.b.ins().bxor_imm_s(y, 1);
                l.b.ins().bor(x, n)
            }),
            Op::NotB { d, a } => {
                let x = self.get(a);
                let v = self.b.ins().bxor_imm_s(x, 1);
                self.set(d, v);
            }
            Op::NotW { d, a, shift } => {
                let x = self.get(a);
                let v = self.b.ins().bnot(x);
                let v = self.wrap_u(v, shift);
                self.set(d, v);
            }
            Op::Shift {
                d,
                a,
                b,
                kind,
                bits,
            } => {
                let (x, n) = (self.get(a), self.get(b));
                let v = self.shift(x, n, kind, bits);
                self.set(d, v);
            }
            Op::CmpS { d, a, b, cmp } => self.binary(d, a, b, |l, x, y| {
                let c = l.b.ins().icmp(signed(cmp), x, y);
                l.b.ins().uextend(I64, c)
            }),
            Op::CmpU { d, a, b, cmp } => self.binary(d, a, b, |l, x, y| {
                let c = l.b.ins().icmp(unsigned(cmp), x, y);
                l.b.ins().uextend(I64, c)
            }),
            Op::CmpSI { d, a, imm, cmp } => {
                let x = self.get(a);
                let c = self.b.ins().icmp_imm_s(signed(cmp), x, imm as i64);
                let v = self.b.ins().uextend(I64, c);
                self.set(d, v);
            }
            Op::CMov { d, c, s } => {
                let (cond, v, old) = (self.get(c), self.get(s), self.get(d));
                let v = self.b.ins().select(cond, v, old);
                self.set(d, v);
            }
            Op::MinMaxS { d, a, b, max } | Op::MinMaxU { d, a, b, max } => {
                let cc = if matches!(op, Op::MinMaxS { .. }) {
                    IntCC::SignedLessThan
                } else {
                    IntCC::UnsignedLessThan
                };
                self.binary(d, a, b, |l, x, y| {
                    // `if (x < y) != max { x } else { y }`
                    let less = l.b.ins().icmp(cc, x, y);
                    let pick_x = if max {
                        l.b.ins().bxor_imm_s(less, 1)
                    } else {
                        less
                    };
                    l.b.ins().select(pick_x, x, y)
                })
            }
            _ => return false,
        }
        true
    }

    /// `d := f(a, b)`.
    fn binary(
        &mut self,
        d: Slot,
        a: Slot,
        b: Slot,
        f: impl FnOnce(&mut Self, Value, Value) -> Value,
    ) {
        let (x, y) = (self.get(a), self.get(b));
        let v = f(self, x, y);
        self.set(d, v);
    }

    /// Rust's `wrapping_div`/`wrapping_rem` for a non-zero divisor: the
    /// machine instruction traps on `MIN / -1`, so -1 is handled apart
    /// (quotient `-x` wrapped, remainder 0).
    fn signed_div(&mut self, x: Value, y: Value, rem: bool) -> Value {
        let minus_one = self.b.ins().icmp_imm_s(IntCC::Equal, y, -1);
        let one = self.b.ins().iconst(I64, 1);
        let safe = self.b.ins().select(minus_one, one, y);
        let (plain, special) = if rem {
            (self.b.ins().srem(x, safe), self.b.ins().iconst(I64, 0))
        } else {
            (self.b.ins().sdiv(x, safe), self.b.ins().ineg(x))
        };
        self.b.ins().select(minus_one, special, plain)
    }

    /// The interpreter's `shift`: `x` masked to `bits`, shifted or
    /// rotated by `n` (`bits` is 1..=64: support.rs).
    fn shift(&mut self, x: Value, n: Value, kind: ShiftKind, bits: u8) -> Value {
        let mask = if bits == 64 {
            u64::MAX
        } else {
            (1u64 << bits) - 1
        } as i64;
        let x = self.b.ins().band_imm_s(x, mask);
        let zero = self.b.ins().iconst(I64, 0);
        match kind {
            ShiftKind::Shl | ShiftKind::Shr => {
                let too_far =
                    self.b
                        .ins()
                        .icmp_imm_s(IntCC::UnsignedGreaterThanOrEqual, n, bits as i64);
                let v = if kind == ShiftKind::Shl {
                    let v = self.b.ins().ishl(x, n);
                    self.b.ins().band_imm_s(v, mask)
                } else {
                    self.b.ins().ushr(x, n)
                };
                self.b.ins().select(too_far, zero, v)
            }
            ShiftKind::Rol | ShiftKind::Ror => {
                let n = self.b.ins().urem_imm_s(n, bits as i64);
                let width = self.b.ins().iconst(I64, bits as i64);
                let m = self.b.ins().isub(width, n);
                let (a, b) = if kind == ShiftKind::Rol {
                    (self.b.ins().ishl(x, n), self.b.ins().ushr(x, m))
                } else {
                    (self.b.ins().ushr(x, n), self.b.ins().ishl(x, m))
                };
                let v = self.b.ins().bor(a, b);
                let v = self.b.ins().band_imm_s(v, mask);
                let none = self.b.ins().icmp_imm_s(IntCC::Equal, n, 0);
                self.b.ins().select(none, x, v)
            }
        }
    }
}
