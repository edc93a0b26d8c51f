//! Translation of one verified code block into one Cranelift function
//! with the [`EntryFn`] signature `(ctx, base, code, fp) -> status`.
//!
//! Frame slots are held in variables across instructions (`cache`) and
//! written back wherever memory must be current: before a helper, a call,
//! a fault report, a poll that may stop the code, an access through an
//! address that may land on a held slot, and the return. So a helper, a
//! callee, the interpreter and the runtime see the interpreter's memory
//! whenever they can look at it. Each instruction's family is lowered in
//! its own file.

mod alias;
mod cache;
mod calls;
mod edges;
mod fbs;
mod float;
mod flow;
mod int;
mod memory;

use super::ctx::{Ctx, EntryFn};
use super::helpers::{self, WHY_BAD_ADDRESS};
use crate::ir::image::Image;
use crate::ir::op::{CodeIdx, Op, Slot};
use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::ir::{
    AbiParam, Block, Function, InstBuilder, MemFlagsData, SigRef, Signature, UserFuncName, Value,
    types,
};
use cranelift_codegen::isa::TargetIsa;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use std::mem::offset_of;

const I64: types::Type = types::I64;
const I32: types::Type = types::I32;

/// Compiles block `code` of `img` (whose instructions, copied to a place
/// that outlives the code, are `ops`) to machine code for `isa`. Calls
/// to other blocks go through `table`, which outlives the code.
pub(super) fn function(
    isa: &dyn TargetIsa,
    img: &Image,
    code: CodeIdx,
    ops: &[Op],
    table: *const EntryFn,
) -> Result<Vec<u8>, String> {
    let call_conv = isa.default_call_conv();
    let sig = signature(call_conv, &[I64, I64, I32, I64], Some(I32));
    let mut func = Function::with_name_signature(UserFuncName::default(), sig);
    let mut fctx = FunctionBuilderContext::new();
    let b = FunctionBuilder::new(&mut func, &mut fctx);
    Lower::new(b, isa, img, code, ops, table).block()?;
    let mut context = cranelift_codegen::Context::for_function(func);
    let compiled = context
        .compile(isa, &mut ControlPlane::default())
        .map_err(|e| format!("code generation failed: {:?}", e.inner))?;
    if !compiled.buffer.relocs().is_empty() {
        // Every address is a constant in the code; a relocation would mean
        // code that cannot run where it is copied.
        return Err("code generation produced relocations".into());
    }
    Ok(compiled.code_buffer().to_vec())
}

fn signature(
    cc: cranelift_codegen::isa::CallConv,
    params: &[types::Type],
    ret: Option<types::Type>,
) -> Signature {
    let mut sig = Signature::new(cc);
    sig.params.extend(params.iter().map(|&t| AbiParam::new(t)));
    sig.returns.extend(ret.map(AbiParam::new));
    sig
}

/// The helpers' signatures, imported into the function.
struct Sigs {
    /// `raise(ctx, op, code_pc, fp, why) -> u32`
    raise: SigRef,
    /// `poll(ctx, code_pc) -> u32`
    poll: SigRef,
    /// `unwound(ctx, code_pc, base)`
    unwound: SigRef,
    /// A block: `(ctx, base, code, fp) -> u32`
    entry: SigRef,
    /// `call_native(ctx, op, inst)`
    call_native: SigRef,
    /// `step(ctx, op, code_pc, fp) -> u32`
    step: SigRef,
    /// `entry_strings(ctx, code, fp)`
    entry_strings: SigRef,
    /// `math_f32(op, x) -> f32`
    math_f32: SigRef,
    /// `math_f64(op, x) -> f64`
    math_f64: SigRef,
}

/// The state of one block's translation.
struct Lower<'a, 'f> {
    b: FunctionBuilder<'f>,
    img: &'a Image,
    code: CodeIdx,
    ops: &'a [Op],
    table: *const EntryFn,
    sigs: Sigs,
    /// The function's parameters, and values computed once at entry.
    ctx: Value,
    base: Value,
    fp: Value,
    mem: Value,
    len: Value,
    irq: Value,
    /// The block starting at each instruction that is a jump target or
    /// follows a branch.
    starts: Vec<Option<Block>>,
    /// Returns 1 (a fault was recorded).
    fail: Block,
    /// The instruction being translated.
    pc: usize,
    frontend: cranelift_codegen::isa::TargetFrontendConfig,
    /// The slots held in variables now.
    cache: cache::Cache,
    /// The regions' entries and the slots' last uses.
    regions: edges::Regions,
    /// The cycle's clock, loaded at entry when an inlined timer needs it.
    now: Option<Value>,
}

impl<'a, 'f> Lower<'a, 'f> {
    fn new(
        mut b: FunctionBuilder<'f>,
        isa: &dyn TargetIsa,
        img: &'a Image,
        code: CodeIdx,
        ops: &'a [Op],
        table: *const EntryFn,
    ) -> Self {
        let cc = isa.default_call_conv();
        let mut import =
            |p: &[types::Type], r: Option<types::Type>| b.import_signature(signature(cc, p, r));
        let sigs = Sigs {
            raise: import(&[I64, I64, I64, I64, I32], Some(I32)),
            poll: import(&[I64, I64], Some(I32)),
            unwound: import(&[I64, I64, I64], None),
            entry: import(&[I64, I64, I32, I64], Some(I32)),
            call_native: import(&[I64, I64, I64], None),
            step: import(&[I64, I64, I64, I64], Some(I32)),
            entry_strings: import(&[I64, I32, I64], None),
            math_f32: import(&[I64, types::F32], Some(types::F32)),
            math_f64: import(&[I64, types::F64], Some(types::F64)),
        };
        let entry = b.create_block();
        b.append_block_params_for_function_params(entry);
        b.switch_to_block(entry);
        b.seal_block(entry);
        let p = b.block_params(entry).to_vec();
        let fail = b.create_block();
        b.set_cold_block(fail);
        let zero = b.ins().iconst(I64, 0);
        Lower {
            b,
            img,
            code,
            ops,
            table,
            sigs,
            ctx: p[0],
            base: p[1],
            fp: p[3],
            mem: zero,
            len: zero,
            irq: zero,
            starts: vec![None; ops.len() + 1],
            fail,
            pc: 0,
            frontend: isa.frontend_config(),
            cache: cache::Cache::default(),
            regions: edges::Regions::new(ops),
            now: None,
        }
    }

    /// Translates the whole block.
    fn block(mut self) -> Result<(), String> {
        self.prologue();
        self.find_starts();
        let mut open = true;
        for pc in 0..self.ops.len() {
            self.pc = pc;
            if let Some(start) = self.starts[pc] {
                if open {
                    self.jump_to(pc);
                }
                self.b.switch_to_block(start);
                if !self.regions.loop_head[pc] {
                    // Every edge into it is translated (none comes back).
                    self.b.seal_block(start);
                }
                self.enter_region(pc);
            } else if !open {
                // Unreachable straight-line code after a jump: compiled
                // into a block of its own, which nothing enters.
                let dead = self.b.create_block();
                self.b.switch_to_block(dead);
                self.b.seal_block(dead);
                self.enter(&[], None);
            }
            if open && self.starts[pc].is_none() && self.regions.window_ends(pc) {
                self.drop_all();
            }
            let ops = self.ops;
            open = self.op(&ops[pc])?;
            if open {
                self.retire_after(pc);
            }
        }
        if open {
            // Verified blocks end with Ret; kept total all the same.
            let one = self.b.ins().iconst(I32, 1);
            self.b.ins().return_(&[one]);
        }
        self.b.switch_to_block(self.fail);
        let one = self.b.ins().iconst(I32, 1);
        self.b.ins().return_(&[one]);
        self.b.seal_all_blocks();
        self.b.finalize(self.frontend);
        Ok(())
    }

    /// Entry: the frame checked against memory (a base read from a
    /// pointer may be anywhere), the interrupt word looked at, the
    /// temporaries reset: the interpreter's order, with its faults at
    /// instruction 0.
    fn prologue(&mut self) {
        let flags = MemFlagsData::trusted();
        let ctx = self.ctx;
        self.mem = self
            .b
            .ins()
            .load(I64, flags, ctx, offset_of!(Ctx, mem) as i32);
        self.len = self
            .b
            .ins()
            .load(I64, flags, ctx, offset_of!(Ctx, len) as i32);
        self.irq = self
            .b
            .ins()
            .load(I64, flags, ctx, offset_of!(Ctx, irq) as i32);
        let block = &self.img.codes[self.code.index()];
        let beyond = self.b.ins().icmp(
            cranelift_codegen::ir::condcodes::IntCC::UnsignedGreaterThan,
            self.base,
            self.len,
        );
        let room = self.b.ins().isub(self.len, self.base);
        let small = self.b.ins().icmp_imm_s(
            cranelift_codegen::ir::condcodes::IntCC::UnsignedLessThan,
            room,
            block.frame_size as i64,
        );
        let bad = self.b.ins().bor(beyond, small);
        // `fp` (a parameter, `mem + 8 × base` from the caller) is used
        // only after this check.
        self.fault_if(bad, WHY_BAD_ADDRESS);
        self.tick();
        if self.ops.iter().any(fbs::needs_clock) {
            let flags = MemFlagsData::trusted();
            let now = self
                .b
                .ins()
                .load(I64, flags, ctx, offset_of!(Ctx, now) as i32);
            self.now = Some(now);
        }
        for &(slot, value) in &block.entry_init {
            let v = self.b.ins().iconst(I64, value as i64);
            self.set(slot, v);
        }
        if !block.entry_strings.is_empty() {
            // The helper reads the frame.
            self.drop_all();
            let code = self.b.ins().iconst(I32, self.code.get() as i64);
            let args = [self.ctx, code, self.fp];
            self.call(
                self.sigs.entry_strings,
                helpers::entry_strings as *const (),
                &args,
            );
        }
    }

    /// Creates a block for every instruction a jump lands on or that
    /// follows a branch, jump or return.
    fn find_starts(&mut self) {
        for pc in 0..self.ops.len() {
            let (targets, ends) = flow::successors(&self.ops[pc]);
            for t in targets.into_iter().flatten() {
                self.start_at(t);
            }
            if ends {
                self.start_at(pc + 1);
            }
        }
    }

    fn start_at(&mut self, pc: usize) {
        if pc < self.starts.len() && self.starts[pc].is_none() {
            self.starts[pc] = Some(self.b.create_block());
        }
    }

    /// The block starting at instruction `pc` (created by `find_starts`).
    fn start(&mut self, pc: usize) -> Block {
        match self.starts[pc] {
            Some(b) => b,
            None => {
                let b = self.b.create_block();
                self.starts[pc] = Some(b);
                b
            }
        }
    }

    /// Translates one instruction; false when it ends the straight-line
    /// code (a jump or a return).
    fn op(&mut self, op: &Op) -> Result<bool, String> {
        if matches!(op, Op::Nop | Op::Operand { .. }) {
            // An operand word is read by the instruction before it.
            return Ok(true);
        }
        if super::support::out_of_line(op) {
            self.out_of_line(op);
            return Ok(true);
        }
        if let Some(open) = self.flow(op) {
            return Ok(open);
        }
        if self.calls(op) || self.int(op) || self.float(op) || self.memory(op) {
            return Ok(true);
        }
        Err(format!(
            "instruction {} ({}) has no translation",
            self.pc,
            op.name()
        ))
    }

    // --- frame access ---

    /// The address and displacement of frame slot `s` (displacements
    /// beyond 2 GiB are added to the address instead).
    fn slot_at(&mut self, s: Slot) -> (Value, i32) {
        let off = s.index() as u64 * 8;
        match i32::try_from(off) {
            Ok(off) => (self.fp, off),
            Err(_) => (self.b.ins().iadd_imm_s(self.fp, off as i64), 0),
        }
    }

    // --- helpers, faults, interrupts ---

    /// `(block << 32) | instruction`, as the helpers take it.
    fn code_pc(&mut self) -> Value {
        let v = ((self.code.get() as u64) << 32) | self.pc as u64;
        self.b.ins().iconst(I64, v as i64)
    }

    /// The address of the instruction being translated (in the copy the
    /// compiled code keeps).
    fn op_ptr(&mut self) -> Value {
        let at = &self.ops[self.pc] as *const Op;
        self.b.ins().iconst(I64, at as i64)
    }

    /// Calls the helper at `addr`; its result, if any.
    fn call(&mut self, sig: SigRef, addr: *const (), args: &[Value]) -> Option<Value> {
        let callee = self.b.ins().iconst(I64, addr as i64);
        let inst = self.b.ins().call_indirect(sig, callee, args);
        self.b.inst_results(inst).first().copied()
    }

    /// Goes on when `status` is 0, returns 1 (the fault recorded)
    /// otherwise, with every held value written back first.
    fn fail_if(&mut self, status: Value) {
        let cold = self.b.create_block();
        let next = self.b.create_block();
        self.b.set_cold_block(cold);
        self.b.ins().brif(status, cold, &[], next, &[]);
        self.b.switch_to_block(cold);
        self.b.seal_block(cold);
        self.write_back_copy();
        self.b.ins().jump(self.fail, &[]);
        self.b.switch_to_block(next);
        self.b.seal_block(next);
    }

    /// When `cond` holds: the fault of this instruction (`why`, see
    /// `helpers::raise`), recorded out of line.
    fn fault_if(&mut self, cond: Value, why: u32) {
        let cold = self.b.create_block();
        let next = self.b.create_block();
        self.b.set_cold_block(cold);
        self.b.ins().brif(cond, cold, &[], next, &[]);
        self.b.switch_to_block(cold);
        self.b.seal_block(cold);
        // The report reads the operands, and memory is what the
        // interpreter would leave.
        self.write_back_copy();
        let (op, code_pc) = (self.op_ptr(), self.code_pc());
        let why = self.b.ins().iconst(I32, why as i64);
        let args = [self.ctx, op, code_pc, self.fp, why];
        if let Some(status) = self.call(self.sigs.raise, helpers::raise as *const (), &args) {
            self.b.ins().return_(&[status]);
        }
        self.b.switch_to_block(next);
        self.b.seal_block(next);
    }

    /// The interpreter's `tick`: the interrupt word, and when it is set
    /// the out-of-line check that may fault at this instruction.
    fn tick(&mut self) {
        // An atomic load: never merged with an earlier one or moved out of
        // a loop, so an empty endless loop still sees the watchdog.
        let word = self
            .b
            .ins()
            .atomic_load(I32, MemFlagsData::trusted(), self.irq);
        let slow = self.b.create_block();
        let next = self.b.create_block();
        self.b.set_cold_block(slow);
        self.b.ins().brif(word, slow, &[], next, &[]);
        self.b.switch_to_block(slow);
        self.b.seal_block(slow);
        // The poll may stop the code here: memory must be current.
        self.write_back_copy();
        let code_pc = self.code_pc();
        let args = [self.ctx, code_pc];
        if let Some(status) = self.call(self.sigs.poll, helpers::poll as *const (), &args) {
            self.b.ins().brif(status, self.fail, &[], next, &[]);
        }
        self.b.switch_to_block(next);
        self.b.seal_block(next);
    }

    /// An instruction that runs in Rust (`helpers::step`). A pure one
    /// (`support::pure`) reads its input slots and writes its result
    /// only; any other may touch the whole frame.
    fn out_of_line(&mut self, op: &Op) {
        if super::support::pure(op) {
            self.around_pure(op);
        } else {
            self.drop_all();
        }
        let (op, code_pc) = (self.op_ptr(), self.code_pc());
        let args = [self.ctx, op, code_pc, self.fp];
        if let Some(status) = self.call(self.sigs.step, helpers::step as *const (), &args) {
            self.fail_if(status);
        }
    }
}
