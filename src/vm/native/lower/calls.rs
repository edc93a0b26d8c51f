//! Calls: user FBs and functions through the block table (machine code,
//! or the interpreter for a block the tier did not compile), standard FBs
//! inline (fbs.rs) or through one helper. A callee's fault comes back as
//! status 1; the call is then noted as one the fault unwound through, as
//! the interpreter notes it. A user callee may read and write any memory
//! (in-out arguments point anywhere): every held slot is written back and
//! dropped first. A standard FB touches its instance only.

use super::{I32, I64, Lower};
use crate::ir::op::{CodeIdx, Op};
use crate::vm::native::helpers::{self, WHY_BAD_ADDRESS};
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{InstBuilder, MemFlagsData, Value};

impl Lower<'_, '_> {
    /// Translates a call; false when `op` is not one.
    pub(super) fn calls(&mut self, op: &Op) -> bool {
        match *op {
            Op::CallFb { code, inst } => {
                let base = self.base();
                let base = self.b.ins().iadd_imm_s(base, inst.index() as i64);
                self.call_block(code, base);
            }
            Op::CallFbInd { code, p } => {
                let base = self.get(p);
                self.call_block(code, base);
            }
            Op::CallFn { code } => {
                let frame = self.img.codes[code.index()].frame;
                let base = self.b.ins().iconst(I64, frame as i64);
                self.call_block(code, base);
            }
            Op::CallNative { fb, inst } => {
                if super::fbs::inlined(fb) {
                    self.inline_fb(fb, super::fbs::Pins::Frame(inst));
                    return true;
                }
                let lo = u64::from(inst.get());
                self.drop_range(lo, lo + u64::from(fb.instance_slots()));
                let (at, off) = self.slot_at(inst);
                let inst = self.b.ins().iadd_imm_s(at, off as i64);
                self.call_standard(inst);
            }
            Op::CallNativeInd { fb, p } => {
                // The instance's slots must lie in memory (checked without
                // overflow, as the interpreter checks them).
                let n = fb.instance_slots() as i64;
                let known = self.pointed(p, 0, n as u64);
                let start = self.get(p);
                let len = self.len();
                let beyond = self.b.ins().icmp(IntCC::UnsignedGreaterThan, start, len);
                let room = self.b.ins().isub(len, start);
                let short = self.b.ins().icmp_imm_s(IntCC::UnsignedLessThan, room, n);
                let bad = self.b.ins().bor(beyond, short);
                self.fault_if(bad, WHY_BAD_ADDRESS);
                let bytes = self.b.ins().ishl_imm_s(start, 3);
                let mem = self.mem();
                let inst = self.b.ins().iadd(mem, bytes);
                let run = |l: &mut Self| {
                    if super::fbs::inlined(fb) {
                        l.inline_fb(fb, super::fbs::Pins::At(inst));
                    } else {
                        l.call_standard(inst);
                    }
                    None
                };
                if let Some((lo, hi)) = known {
                    // An element of a frame array of FBs: the slots it
                    // may touch are known here.
                    self.drop_range(lo, hi);
                    run(self);
                } else {
                    let rel = self.frame_relative(start);
                    self.guarded(rel, n as u64, true, run);
                }
            }
            _ => return false,
        }
        true
    }

    /// Block `code` at `base`, through its table entry.
    fn call_block(&mut self, code: CodeIdx, base: Value) {
        self.drop_all();
        let slot = self.table as i64 + code.index() as i64 * 8;
        let table = self.b.ins().iconst(I64, slot);
        // The table is complete before any code runs and never changes.
        let flags = MemFlagsData::trusted().with_readonly();
        let entry = self.b.ins().load(I64, flags, table, 0);
        let index = self.b.ins().iconst(I32, code.get() as i64);
        let bytes = self.b.ins().ishl_imm_s(base, 3);
        let mem = self.mem();
        let fp = self.b.ins().iadd(mem, bytes);
        let ctx = self.ctx();
        let inst = self
            .b
            .ins()
            .call_indirect(self.sigs.entry, entry, &[ctx, base, index, fp]);
        self.after_call();
        let status = self.b.inst_results(inst)[0];
        let unwind = self.b.create_block();
        let next = self.b.create_block();
        self.b.set_cold_block(unwind);
        self.b.ins().brif(status, unwind, &[], next, &[]);
        self.b.switch_to_block(unwind);
        self.b.seal_block(unwind);
        self.aside(|l| {
            let code_pc = l.code_pc();
            let args = [l.ctx(), code_pc, l.base()];
            l.call(l.sigs.unwound, helpers::unwound as *const (), &args);
            l.b.ins().jump(l.fail, &[]);
        });
        self.b.switch_to_block(next);
        self.b.seal_block(next);
    }

    /// The standard FB of this instruction on the instance at `inst`.
    fn call_standard(&mut self, inst: Value) {
        let op = self.op_ptr();
        let args = [self.ctx(), op, inst];
        self.call(
            self.sigs.call_native,
            helpers::call_native as *const (),
            &args,
        );
    }
}
