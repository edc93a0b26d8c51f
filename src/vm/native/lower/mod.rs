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
mod proved;

use super::ctx::{Ctx, EntryFn};
use super::helpers::{self, WHY_BAD_ADDRESS};
use crate::ir::image::Image;
use crate::ir::op::{CodeIdx, Op, Slot};
use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::ir::{
    AbiParam, Block, Function, InstBuilder, MemFlagsData, SigRef, Signature, StackSlot,
    StackSlotData, StackSlotKind, UserFuncName, Value, types,
};
use cranelift_codegen::isa::TargetIsa;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext, Variable};
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

/// The entry's parameters and the values it reads from [`Ctx`], each a
/// variable (see [`Env`]), by index.
const CTX: usize = 0;
const BASE: usize = 1;
const FP: usize = 2;
const MEM: usize = 3;
const LEN: usize = 4;
const IRQ: usize = 5;
const NOW: usize = 6;
const ALL_ENV: u8 = 0x7f;

/// The values every instruction may need: the context, the frame's base
/// and address, and memory's address and length, the interrupt word's
/// address and the cycle's clock as read from the context. They never
/// change while the block runs, but a value kept across a call must sit
/// in a callee-saved register or on the stack, and the register
/// allocator then tends to spill it for the whole function and reload it
/// at every use. So each is a variable, and after a call (`stale`) the
/// next use loads it again (the first three from a stack slot written at
/// entry, the others from the context) and keeps the new value in a
/// register until the next call.
struct Env {
    vars: [Variable; 7],
    /// Which of them a call made since their last definition on the path
    /// being translated (bit `1 << k`): the next use reloads it.
    stale: u8,
    /// `ctx`, `base` and `fp`, stored at entry.
    saved: StackSlot,
}

/// The state of one block's translation.
struct Lower<'a, 'f> {
    b: FunctionBuilder<'f>,
    img: &'a Image,
    code: CodeIdx,
    ops: &'a [Op],
    table: *const EntryFn,
    sigs: Sigs,
    /// The function's parameters, and values read at entry.
    env: Env,
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
        let vars = [(); 7].map(|()| b.declare_var(I64));
        let saved =
            b.create_sized_stack_slot(StackSlotData::new(StackSlotKind::ExplicitSlot, 24, 3));
        for (k, param) in [(CTX, p[0]), (BASE, p[1]), (FP, p[3])] {
            b.def_var(vars[k], param);
            b.ins().stack_store(I64, param, saved, 8 * k as i32);
        }
        Lower {
            b,
            img,
            code,
            ops,
            table,
            sigs,
            env: Env {
                vars,
                stale: 0,
                saved,
            },
            starts: vec![None; ops.len() + 1],
            fail,
            pc: 0,
            frontend: isa.frontend_config(),
            cache: cache::Cache::default(),
            regions: edges::Regions::new(ops),
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
        for k in [MEM, LEN, IRQ] {
            let v = self.reload_env(k);
            self.b.def_var(self.env.vars[k], v);
        }
        let block = &self.img.codes[self.code.index()];
        let (base, len) = (self.base(), self.len());
        let beyond = self.b.ins().icmp(
            cranelift_codegen::ir::condcodes::IntCC::UnsignedGreaterThan,
            base,
            len,
        );
        let room = self.b.ins().isub(len, base);
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
            let now = self.reload_env(NOW);
            self.b.def_var(self.env.vars[NOW], now);
        }
        for &(slot, value) in &block.entry_init {
            let v = self.b.ins().iconst(I64, value as i64);
            self.set(slot, v);
        }
        if !block.entry_strings.is_empty() {
            // The helper reads the frame.
            self.drop_all();
            let code = self.b.ins().iconst(I32, self.code.get() as i64);
            let args = [self.ctx(), code, self.fp()];
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

    // --- the entry's values ---

    /// Value `k` of [`Env`], loaded again when a call came since its last
    /// definition.
    fn env_value(&mut self, k: usize) -> Value {
        let bit = 1u8 << k;
        if self.env.stale & bit != 0 {
            self.env.stale &= !bit;
            let v = self.reload_env(k);
            self.b.def_var(self.env.vars[k], v);
            return v;
        }
        self.b.use_var(self.env.vars[k])
    }

    /// Value `k` of [`Env`] read again from where it is kept.
    fn reload_env(&mut self, k: usize) -> Value {
        let field = match k {
            CTX | BASE | FP => {
                let saved = self.env.saved;
                return self.b.ins().stack_load(I64, I64, saved, 8 * k as i32);
            }
            MEM => offset_of!(Ctx, mem),
            LEN => offset_of!(Ctx, len),
            IRQ => offset_of!(Ctx, irq),
            _ => offset_of!(Ctx, now),
        };
        let ctx = self.ctx();
        self.b
            .ins()
            .load(I64, MemFlagsData::trusted(), ctx, field as i32)
    }

    /// After a call: every value of [`Env`] is loaded again at its next
    /// use.
    fn after_call(&mut self) {
        self.env.stale = ALL_ENV;
    }

    /// Translates a path that leaves the main one (`side`), with the main
    /// path's knowledge of which values are current kept for when the
    /// translation comes back to it.
    fn aside<R>(&mut self, side: impl FnOnce(&mut Self) -> R) -> R {
        let stale = self.env.stale;
        let r = side(self);
        self.env.stale = stale;
        r
    }

    /// The running entry's context.
    fn ctx(&mut self) -> Value {
        self.env_value(CTX)
    }

    /// The frame's base (a slot index in memory).
    fn base(&mut self) -> Value {
        self.env_value(BASE)
    }

    /// The frame's machine address.
    fn fp(&mut self) -> Value {
        self.env_value(FP)
    }

    /// Memory's machine address.
    fn mem(&mut self) -> Value {
        self.env_value(MEM)
    }

    /// Memory's length in slots.
    fn len(&mut self) -> Value {
        self.env_value(LEN)
    }

    /// The interrupt word's address.
    fn irq(&mut self) -> Value {
        self.env_value(IRQ)
    }

    /// The cycle's clock (read at entry when an inlined timer needs it).
    fn now(&mut self) -> Value {
        self.env_value(NOW)
    }

    // --- frame access ---

    /// The address and displacement of frame slot `s` (displacements
    /// beyond 2 GiB are added to the address instead).
    fn slot_at(&mut self, s: Slot) -> (Value, i32) {
        let off = s.index() as u64 * 8;
        let fp = self.fp();
        match i32::try_from(off) {
            Ok(off) => (fp, off),
            Err(_) => (self.b.ins().iadd_imm_s(fp, off as i64), 0),
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
        self.after_call();
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
        self.aside(|l| {
            l.write_back_copy();
            l.b.ins().jump(l.fail, &[]);
        });
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
        self.aside(|l| {
            // The report reads the operands, and memory is what the
            // interpreter would leave.
            l.write_back_copy();
            let (op, code_pc) = (l.op_ptr(), l.code_pc());
            let why = l.b.ins().iconst(I32, why as i64);
            let args = [l.ctx(), op, code_pc, l.fp(), why];
            if let Some(status) = l.call(l.sigs.raise, helpers::raise as *const (), &args) {
                l.b.ins().return_(&[status]);
            }
        });
        self.b.switch_to_block(next);
        self.b.seal_block(next);
    }

    /// The interpreter's `tick`: the interrupt word, and when it is set
    /// the out-of-line check that may fault at this instruction.
    fn tick(&mut self) {
        // An atomic load: never merged with an earlier one or moved out of
        // a loop, so an empty endless loop still sees the watchdog.
        let irq = self.irq();
        let word = self.b.ins().atomic_load(I32, MemFlagsData::trusted(), irq);
        let slow = self.b.create_block();
        let next = self.b.create_block();
        self.b.set_cold_block(slow);
        self.b.ins().brif(word, slow, &[], next, &[]);
        self.b.switch_to_block(slow);
        self.b.seal_block(slow);
        self.aside(|l| {
            // The poll may stop the code here: memory must be current.
            l.write_back_copy();
            let current = !l.env.stale & ALL_ENV;
            let code_pc = l.code_pc();
            let args = [l.ctx(), code_pc];
            if let Some(status) = l.call(l.sigs.poll, helpers::poll as *const (), &args) {
                let resume = l.b.create_block();
                l.b.set_cold_block(resume);
                l.b.ins().brif(status, l.fail, &[], resume, &[]);
                l.b.switch_to_block(resume);
                l.b.seal_block(resume);
                // Going on: what the main path holds is defined again
                // here (the poll changed no memory, and every held value
                // is in it), so no value of the hot path lives across
                // the call.
                l.env.stale |= current;
                for k in 0..7 {
                    if current & (1 << k) != 0 {
                        l.env_value(k);
                    }
                }
                l.reload_copy();
                l.b.ins().jump(next, &[]);
            }
        });
        self.b.switch_to_block(next);
        self.b.seal_block(next);
        // Floats computed from held values before the poll would live
        // across it on the slow path: computed again from the variables.
        self.forget_floats();
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
        let args = [self.ctx(), op, code_pc, self.fp()];
        if let Some(status) = self.call(self.sigs.step, helpers::step as *const (), &args) {
            self.fail_if(status);
        }
    }
}
