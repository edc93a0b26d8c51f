//! Jumps, branches, loop instructions and `Ret`. A jump to an instruction
//! at or before itself looks at the interrupt word first, naming itself,
//! exactly where the interpreter's `jump!` does.

use super::{I64, Lower};
use crate::ir::op::{Cmp, Op};
use cranelift_codegen::ir::InstBuilder;
use cranelift_codegen::ir::Value;
use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};

/// The jump targets of `op` and whether the code after it starts a new
/// block (it branches, jumps or returns).
pub(super) fn successors(op: &Op) -> ([Option<usize>; 1], bool) {
    let t = match *op {
        Op::Jmp { t }
        | Op::Jz { t, .. }
        | Op::Jnz { t, .. }
        | Op::JnCmpSI { t, .. }
        | Op::JnCmpS { t, .. }
        | Op::JzElem { t, .. }
        | Op::JnzElem { t, .. }
        | Op::JnCmpF32 { t, .. }
        | Op::JnCmpF64 { t, .. }
        | Op::ForNext { t, .. }
        | Op::ForNextS { t, .. } => Some(t.index()),
        Op::AddBr { t, .. } | Op::ForScan { t, .. } => Some(t.index()),
        Op::Ret => return ([None], true),
        _ => return ([None], false),
    };
    ([t], true)
}

/// The integer predicate of `cmp` on signed values.
pub(super) fn signed(cmp: Cmp) -> IntCC {
    match cmp {
        Cmp::Eq => IntCC::Equal,
        Cmp::Ne => IntCC::NotEqual,
        Cmp::Lt => IntCC::SignedLessThan,
        Cmp::Le => IntCC::SignedLessThanOrEqual,
        Cmp::Gt => IntCC::SignedGreaterThan,
        Cmp::Ge => IntCC::SignedGreaterThanOrEqual,
    }
}

/// The integer predicate of `cmp` on unsigned values.
pub(super) fn unsigned(cmp: Cmp) -> IntCC {
    match cmp {
        Cmp::Eq => IntCC::Equal,
        Cmp::Ne => IntCC::NotEqual,
        Cmp::Lt => IntCC::UnsignedLessThan,
        Cmp::Le => IntCC::UnsignedLessThanOrEqual,
        Cmp::Gt => IntCC::UnsignedGreaterThan,
        Cmp::Ge => IntCC::UnsignedGreaterThanOrEqual,
    }
}

/// The float predicate of `cmp` as Rust's operators mean it: `<>` holds
/// for NaN, every other comparison with NaN fails.
pub(super) fn float(cmp: Cmp) -> FloatCC {
    match cmp {
        Cmp::Eq => FloatCC::Equal,
        Cmp::Ne => FloatCC::NotEqual,
        Cmp::Lt => FloatCC::LessThan,
        Cmp::Le => FloatCC::LessThanOrEqual,
        Cmp::Gt => FloatCC::GreaterThan,
        Cmp::Ge => FloatCC::GreaterThanOrEqual,
    }
}

impl Lower<'_, '_> {
    /// Translates a control-flow instruction: `Some(open)` when `op` is
    /// one (`open`: whether straight-line code goes on after it).
    pub(super) fn flow(&mut self, op: &Op) -> Option<bool> {
        match *op {
            Op::Ret => {
                self.write_back_all();
                let zero = self.b.ins().iconst(super::I32, 0);
                self.b.ins().return_(&[zero]);
                Some(false)
            }
            Op::Jmp { t } => {
                self.goto(t.index());
                Some(false)
            }
            Op::Jz { c, t } | Op::Jnz { c, t } => {
                let v = self.get(c);
                let cmp = if matches!(op, Op::Jz { .. }) {
                    IntCC::Equal
                } else {
                    IntCC::NotEqual
                };
                let cond = self.b.ins().icmp_imm_s(cmp, v, 0);
                self.branch(cond, t.index());
                Some(false)
            }
            Op::JnCmpSI { a, imm, cmp, t } => {
                let v = self.get(a);
                let holds = self.b.ins().icmp_imm_s(signed(cmp), v, imm as i64);
                let cond = self.b.ins().bxor_imm_s(holds, 1);
                self.branch(cond, t.index());
                Some(false)
            }
            Op::JnCmpS { a, b, cmp, t } => {
                let (x, y) = (self.get(a), self.get(b));
                let holds = self.b.ins().icmp(signed(cmp), x, y);
                let cond = self.b.ins().bxor_imm_s(holds, 1);
                self.branch(cond, t.index());
                Some(false)
            }
            Op::JnCmpF32 { a, b, cmp, t } | Op::JnCmpF64 { a, b, cmp, t } => {
                let wide = matches!(op, Op::JnCmpF64 { .. });
                let (x, y) = (self.get_float(a, wide), self.get_float(b, wide));
                let holds = self.b.ins().fcmp(float(cmp), x, y);
                let cond = self.b.ins().bxor_imm_s(holds, 1);
                self.branch(cond, t.index());
                Some(false)
            }
            Op::JzElem { idx, desc, t } | Op::JnzElem { idx, desc, t } => {
                let at = self.element(idx, desc);
                self.element_access(desc, false);
                let v =
                    self.b
                        .ins()
                        .load(I64, cranelift_codegen::ir::MemFlagsData::trusted(), at, 0);
                let cmp = if matches!(op, Op::JzElem { .. }) {
                    IntCC::Equal
                } else {
                    IntCC::NotEqual
                };
                let cond = self.b.ins().icmp_imm_s(cmp, v, 0);
                self.branch(cond, t.index());
                Some(false)
            }
            Op::AddBr {
                d,
                b,
                imm,
                t,
                cmp,
                shift,
            } => {
                let (x, y) = (self.get(d), self.get(b));
                let sum = self.b.ins().iadd(x, y);
                let v = self.wrap_s(sum, shift);
                self.set(d, v);
                let cond = self.b.ins().icmp_imm_s(signed(cmp), v, imm as i64);
                self.branch(cond, t.index());
                Some(false)
            }
            Op::ForNext {
                i,
                lim,
                t,
                step,
                shift,
            } => {
                let limit = self.b.ins().iconst(I64, lim as i64);
                self.for_next(i, limit, step, shift, t.index());
                Some(false)
            }
            Op::ForNextS {
                i,
                lim,
                t,
                step,
                shift,
            } => {
                let limit = self.get(lim);
                self.for_next(i, limit, step, shift, t.index());
                Some(false)
            }
            // The fused scan runs as the FOR back edge it replaces: its
            // partner, the element test at `t`, is compiled in place and
            // comes back here, so each turn looks at the interrupt word
            // once, at this instruction, as the interpreter does.
            Op::ForScan {
                i,
                lim,
                t,
                step,
                shift,
                ..
            } => {
                let limit = self.b.ins().iconst(I64, lim as i64);
                self.for_next(i, limit, step as i16, shift, t.index());
                Some(false)
            }
            _ => None,
        }
    }

    /// `i := wrap(i + step)`, then to `t` while the exact sum is within
    /// `lim` (the interpreter's `for_next`).
    fn for_next(&mut self, i: crate::ir::op::Slot, lim: Value, step: i16, shift: u8, t: usize) {
        let x = self.get(i);
        let s = self.b.ins().iconst(I64, step as i64);
        let (sum, overflow) = self.b.ins().sadd_overflow(x, s);
        let v = self.wrap_s(sum, shift);
        self.set(i, v);
        let cc = if step > 0 {
            IntCC::SignedLessThanOrEqual
        } else {
            IntCC::SignedGreaterThanOrEqual
        };
        let within = self.b.ins().icmp(cc, sum, lim);
        let ok = self.b.ins().bxor_imm_s(overflow, 1);
        let go = self.b.ins().band(within, ok);
        self.branch(go, t);
    }

    /// `v` wrapped to `64 - shift` bits, sign-extended (`wrap_s`).
    pub(super) fn wrap_s(&mut self, v: Value, shift: u8) -> Value {
        if shift == 0 {
            return v;
        }
        let up = self.b.ins().ishl_imm_s(v, shift as i64);
        self.b.ins().sshr_imm_s(up, shift as i64)
    }

    /// `v` wrapped to `64 - shift` bits, zero-extended (`wrap_u`).
    pub(super) fn wrap_u(&mut self, v: Value, shift: u8) -> Value {
        if shift == 0 {
            return v;
        }
        let up = self.b.ins().ishl_imm_s(v, shift as i64);
        self.b.ins().ushr_imm_s(up, shift as i64)
    }

    /// Unconditional jump to instruction `t`.
    fn goto(&mut self, t: usize) {
        if t <= self.pc {
            self.tick();
        }
        self.jump_to(t);
    }

    /// To instruction `t` when `cond` is non-zero, else to the next one.
    fn branch(&mut self, cond: Value, t: usize) {
        let next = self.pc + 1;
        if t <= self.pc {
            self.retire(&[t, next]);
            let back = self.b.create_block();
            let (to_next, fill) = self.edge_block(next);
            self.b.ins().brif(cond, back, &[], to_next, &[]);
            self.b.switch_to_block(back);
            self.b.seal_block(back);
            self.goto(t);
            if fill {
                self.fill_edge(to_next, next);
            }
        } else {
            self.branch_two(cond, t, next);
        }
    }
}
