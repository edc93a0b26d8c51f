//! REAL and LREAL arithmetic and comparisons. A REAL lives in the low 32
//! bits of its slot (the interpreter's `f32_of`/`of_f32`); every
//! operation is one IEEE operation rounded as written (a multiply-add is
//! a multiply, then an add: never fused), so results match to the bit.

use super::flow::float;
use super::{I64, Lower};
use crate::ir::op::{MathFn, Op};
use crate::vm::native::helpers;
use cranelift_codegen::ir::{InstBuilder, Value};

impl Lower<'_, '_> {
    /// Translates a float instruction; false when `op` is not one.
    pub(super) fn float(&mut self, op: &Op) -> bool {
        use cranelift_codegen::ir::Opcode as O;
        let (d, a, b, wide, opcode) = match *op {
            Op::AddF32 { d, a, b } => (d, a, b, false, O::Fadd),
            Op::SubF32 { d, a, b } => (d, a, b, false, O::Fsub),
            Op::MulF32 { d, a, b } => (d, a, b, false, O::Fmul),
            Op::DivF32 { d, a, b } => (d, a, b, false, O::Fdiv),
            Op::AddF64 { d, a, b } => (d, a, b, true, O::Fadd),
            Op::SubF64 { d, a, b } => (d, a, b, true, O::Fsub),
            Op::MulF64 { d, a, b } => (d, a, b, true, O::Fmul),
            Op::DivF64 { d, a, b } => (d, a, b, true, O::Fdiv),
            _ => return self.float_other(op),
        };
        let (x, y) = (self.get_float(a, wide), self.get_float(b, wide));
        let v = self.arith(opcode, x, y);
        self.set_float(d, v, wide);
        true
    }

    fn float_other(&mut self, op: &Op) -> bool {
        use cranelift_codegen::ir::Opcode as O;
        match *op {
            Op::NegF32 { d, a } | Op::NegF64 { d, a } => {
                let wide = matches!(op, Op::NegF64 { .. });
                let x = self.get_float(a, wide);
                let v = self.b.ins().fneg(x);
                self.set_float(d, v, wide);
            }
            Op::CmpF32 { d, a, b, cmp } | Op::CmpF64 { d, a, b, cmp } => {
                let wide = matches!(op, Op::CmpF64 { .. });
                let (x, y) = (self.get_float(a, wide), self.get_float(b, wide));
                let c = self.b.ins().fcmp(float(cmp), x, y);
                let v = self.b.ins().uextend(I64, c);
                self.set(d, v);
            }
            Op::MulAddF32 { d, a, b } | Op::MulAddF64 { d, a, b } => {
                let wide = matches!(op, Op::MulAddF64 { .. });
                // The verified operand word that follows holds `c`.
                let Some(&Op::Operand { s: c }) = self.ops.get(self.pc + 1) else {
                    return false;
                };
                let (x, y) = (self.get_float(a, wide), self.get_float(b, wide));
                let product = self.arith(O::Fmul, x, y);
                let z = self.get_float(c, wide);
                let v = self.arith(O::Fadd, product, z);
                self.set_float(d, v, wide);
            }
            Op::MathF32 { d, a, f } | Op::MathF64 { d, a, f } => {
                let wide = matches!(op, Op::MathF64 { .. });
                let x = self.get_float(a, wide);
                let v = match f {
                    // Single IEEE operations, as Rust's `abs` and `sqrt`.
                    MathFn::Abs => self.b.ins().fabs(x),
                    MathFn::Sqrt => self.b.ins().sqrt(x),
                    _ => self.math_call(x, wide),
                };
                self.set_float(d, v, wide);
            }
            _ => return false,
        }
        true
    }

    /// The interpreter's `MathFn::apply_*` on `x`, through a helper that
    /// takes and returns the value in a register.
    fn math_call(&mut self, x: Value, wide: bool) -> Value {
        let op = self.op_ptr();
        let (sig, addr) = if wide {
            (self.sigs.math_f64, helpers::math_f64 as *const ())
        } else {
            (self.sigs.math_f32, helpers::math_f32 as *const ())
        };
        self.call(sig, addr, &[op, x])
            .expect("a math helper returns")
    }

    fn arith(&mut self, opcode: cranelift_codegen::ir::Opcode, x: Value, y: Value) -> Value {
        use cranelift_codegen::ir::Opcode as O;
        match opcode {
            O::Fadd => self.b.ins().fadd(x, y),
            O::Fsub => self.b.ins().fsub(x, y),
            O::Fmul => self.b.ins().fmul(x, y),
            _ => self.b.ins().fdiv(x, y),
        }
    }
}
