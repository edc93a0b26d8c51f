//! The Rust functions machine code calls: faults, interrupt polls, calls
//! into the interpreter and standard FBs, and the instructions that run
//! out of line (each exactly as the interpreter runs it, mostly by
//! calling the same code).
//!
//! Every helper is `extern "C"` and receives the [`Ctx`] of the running
//! entry. `code_pc` packs a block index (high 32 bits) and an
//! instruction index (low 32 bits). A helper that returns `u32` returns 0
//! to go on and 1 after recording a fault in [`Ctx::fault`]; the machine
//! code then returns 1 itself.

use super::ctx::Ctx;
use crate::ir::op::{CodeIdx, Op, Slot};
use crate::stdlib;
use crate::value::convert;
use crate::vm::{Fault, FaultKind};
use crate::vm::{index_fault, int_pow};
use std::sync::atomic::Ordering;

/// `raise`'s `why`: the fault follows from the instruction and its operands.
pub(super) const WHY_OPERANDS: u32 = 0;
/// `raise`'s `why`: an address outside memory or the frame.
pub(super) const WHY_BAD_ADDRESS: u32 = 1;

fn split(code_pc: u64) -> (CodeIdx, u32) {
    (CodeIdx::new((code_pc >> 32) as u32), code_pc as u32)
}

fn record(ctx: &mut Ctx, kind: FaultKind, code_pc: u64) -> u32 {
    let (code, pc) = split(code_pc);
    ctx.fault = Some(Fault { kind, code, pc });
    1
}

/// A fault detected inline (a zero divisor, an index out of range, an
/// address outside memory): works out the interpreter's fault kind from
/// the instruction and the operands still in the frame.
///
/// # Safety
/// `ctx` is the running entry's, `op` an instruction of the verified
/// block running on the frame at `fp`.
pub(super) unsafe extern "C" fn raise(
    ctx: *mut Ctx,
    op: *const Op,
    code_pc: u64,
    fp: *mut u64,
    why: u32,
) -> u32 {
    // SAFETY: the caller's contract.
    let (ctx, op) = unsafe { (&mut *ctx, &*op) };
    // SAFETY: slots of a verified instruction lie in the frame.
    let r = |s: Slot| unsafe { *fp.add(s.index()) };
    // SAFETY: the image outlives the entry.
    let img = unsafe { &*ctx.image };
    let kind = match (why, *op) {
        (WHY_BAD_ADDRESS, _) => FaultKind::BadAddress,
        (
            _,
            Op::LoadElem { idx, desc, .. }
            | Op::StoreElem { idx, desc, .. }
            | Op::ElemAddr { idx, desc, .. }
            | Op::ElemRef { idx, desc, .. }
            | Op::IndexStep { idx, desc, .. }
            | Op::JzElem { idx, desc, .. }
            | Op::JnzElem { idx, desc, .. }
            | Op::StoreStep { idx, desc, .. },
        ) => index_fault(r(idx), &img.arrays[desc.index()]),
        (_, Op::DivS { .. } | Op::DivU { .. } | Op::ModS { .. } | Op::ModU { .. }) => {
            FaultKind::DivisionByZero
        }
        _ => FaultKind::BadAddress,
    };
    record(ctx, kind, code_pc)
}

/// The interrupt word was found set: the interpreter's check of it (a
/// stale watchdog bit is cleared and the code goes on).
///
/// # Safety
/// `ctx` is the running entry's.
pub(super) unsafe extern "C" fn poll(ctx: *mut Ctx, code_pc: u64) -> u32 {
    // SAFETY: the caller's contract; the interrupt word outlives the run.
    let ctx = unsafe { &mut *ctx };
    let pending = unsafe { (*ctx.interrupt).pending() };
    match pending {
        Some(kind) => record(ctx, kind, code_pc),
        None => 0,
    }
}

/// A call at `code_pc` (running at `base`) returned a fault: the
/// interpreter's note of the call the fault unwinds through.
///
/// # Safety
/// `ctx` is the running entry's.
pub(super) unsafe extern "C" fn unwound(ctx: *mut Ctx, code_pc: u64, base: usize) {
    // SAFETY: the caller's contract; no other reference to the machine
    // is live while machine code runs.
    let m = unsafe { &mut *(*ctx).machine };
    let (code, pc) = split(code_pc);
    m.unwound(code, pc as usize, base);
}

/// The table entry of a block the tier did not compile: runs it in the
/// interpreter (whose own calls come back to native code).
///
/// # Safety
/// `ctx` is the running entry's; `code` a block of its image.
pub(super) unsafe extern "C" fn interpret(
    ctx: *mut Ctx,
    base: usize,
    code: u32,
    _fp: *mut u64,
) -> u32 {
    // SAFETY: the caller's contract, as for `unwound`.
    let ctx = unsafe { &mut *ctx };
    let (m, img) = unsafe { (&mut *ctx.machine, &*ctx.image) };
    match m.call_mixed(img, CodeIdx::new(code), base) {
        Ok(()) => 0,
        Err(f) => {
            ctx.fault = Some(f);
            1
        }
    }
}

/// `CallNative`/`CallNativeInd`: one standard FB on the instance at
/// `inst` (inside memory: verified, or checked by the caller).
///
/// # Safety
/// `ctx` is the running entry's; `inst` starts the FB's instance slots.
pub(super) unsafe extern "C" fn call_native(ctx: *mut Ctx, op: *const Op, inst: *mut u64) {
    // SAFETY: the caller's contract.
    let (now, op) = unsafe { ((*ctx).now, &*op) };
    if let Op::CallNative { fb, .. } | Op::CallNativeInd { fb, .. } = *op {
        // SAFETY: the instance holds `fb.instance_slots()` slots.
        unsafe { stdlib::call_raw(fb, inst, now) }
    }
}

/// `MathF32` other than ABS and SQRT (which are single IEEE operations,
/// compiled inline): the interpreter's `MathFn::apply_f32` on `x`.
///
/// # Safety
/// `op` points to an instruction of a compiled block.
pub(super) unsafe extern "C" fn math_f32(op: *const Op, x: f32) -> f32 {
    // SAFETY: the caller's contract.
    match unsafe { *op } {
        Op::MathF32 { f, .. } => f.apply_f32(x),
        _ => x,
    }
}

/// `MathF64` as `math_f32` for LREAL.
///
/// # Safety
/// `op` points to an instruction of a compiled block.
pub(super) unsafe extern "C" fn math_f64(op: *const Op, x: f64) -> f64 {
    // SAFETY: the caller's contract.
    match unsafe { *op } {
        Op::MathF64 { f, .. } => f.apply_f64(x),
        _ => x,
    }
}

/// A block's entry strings (reset at every call).
///
/// # Safety
/// `ctx` is the running entry's; `code` the block running on `fp`.
pub(super) unsafe extern "C" fn entry_strings(ctx: *mut Ctx, code: u32, fp: *mut u64) {
    // SAFETY: the caller's contract.
    let ctx = unsafe { &mut *ctx };
    let (m, img) = unsafe { (&mut *ctx.machine, &*ctx.image) };
    for &(slot, k) in &img.codes[code as usize].entry_strings {
        // SAFETY: entry string slots are verified in the frame.
        let id = unsafe { *fp.add(slot.index()) };
        m.set_string(id, &img.str_consts[k.index()]);
    }
}

/// An instruction that runs out of line (`support::out_of_line`), exactly
/// as the interpreter runs it.
///
/// # Safety
/// `ctx` is the running entry's, `op` an instruction of the verified
/// block running on the frame at `fp`.
pub(super) unsafe extern "C" fn step(
    ctx: *mut Ctx,
    op: *const Op,
    code_pc: u64,
    fp: *mut u64,
) -> u32 {
    // SAFETY: the caller's contract.
    let (ctx, op) = unsafe { (&mut *ctx, &*op) };
    // SAFETY: slots of a verified instruction lie in the frame.
    let r = |s: Slot| unsafe { *fp.add(s.index()) };
    let w = |s: Slot, v: u64| -> Result<(), FaultKind> {
        // SAFETY: as for `r`.
        unsafe { *fp.add(s.index()) = v };
        Ok(())
    };
    let f32_of = |x: u64| f32::from_bits(x as u32);
    let of_f32 = |x: f32| x.to_bits() as u64;
    let result: Result<(), FaultKind> = match *op {
        Op::PowS { d, a, b, shift } => match int_pow(r(a) as i64, r(b) as i64) {
            Some(v) => w(d, crate::ir::op::wrap_s(v, shift)),
            None => Err(FaultKind::NegativeExponent),
        },
        Op::PowF32 { d, a, b } => w(d, of_f32(f32_of(r(a)).powf(f32_of(r(b))))),
        Op::PowF64 { d, a, b } => w(d, f64::from_bits(r(a)).powf(f64::from_bits(r(b))).to_bits()),
        Op::Convert { d, a, conv } => match convert::convert(conv, r(a)) {
            Ok(v) => w(d, v),
            Err(e) => Err(FaultKind::from(e)),
        },
        Op::MinMaxF32 { d, a, b, max } => {
            let (x, y) = (f32_of(r(a)), f32_of(r(b)));
            w(d, of_f32(if max { x.max(y) } else { x.min(y) }))
        }
        Op::MinMaxF64 { d, a, b, max } => {
            let (x, y) = (f64::from_bits(r(a)), f64::from_bits(r(b)));
            w(d, (if max { x.max(y) } else { x.min(y) }).to_bits())
        }
        Op::Mux { d, k, first, n } => {
            let sel = r(k) as i64;
            if sel < 0 || sel >= n as i64 {
                Err(FaultKind::MuxOutOfRange {
                    k: sel,
                    n: n as u32,
                })
            } else {
                // The run `first .. first + n` lies in the frame (verified).
                w(d, r(first.offset(sel as u32)))
            }
        }
        Op::MulTimeF64 { d, a, b } => {
            let v = (r(a) as i64) as f64 * f64::from_bits(r(b));
            match convert::f64_to_i64(v.round()) {
                Some(x) => w(d, x as u64),
                None => Err(FaultKind::ConversionOverflow),
            }
        }
        Op::DivTimeF64 { d, a, b } => {
            let y = f64::from_bits(r(b));
            if y == 0.0 {
                Err(FaultKind::DivisionByZero)
            } else {
                match convert::f64_to_i64(((r(a) as i64) as f64 / y).round()) {
                    Some(x) => w(d, x as u64),
                    None => Err(FaultKind::ConversionOverflow),
                }
            }
        }
        Op::MemCopy { d, s, n } => return mem_copy(ctx, r(d), r(s), n, code_pc),
        _ => {
            // SAFETY: the image and the machine outlive the entry; `fp`
            // is the verified frame of `op`'s block.
            let (m, img) = unsafe { (&mut *ctx.machine, &*ctx.image) };
            unsafe { m.out_of_line(img, fp, op) }
        }
    };
    match result {
        Ok(()) => 0,
        Err(kind) => record(ctx, kind, code_pc),
    }
}

/// `MemCopy`: both ranges checked against memory without overflow, then
/// the interrupt word looked at (a copy's time grows with memory).
fn mem_copy(ctx: &mut Ctx, to: u64, from: u64, n: u32, code_pc: u64) -> u32 {
    let (to, from, n, len) = (to as usize, from as usize, n as usize, ctx.len as usize);
    if to > len || from > len || n > len - to || n > len - from {
        return record(ctx, FaultKind::BadAddress, code_pc);
    }
    // SAFETY: both ranges lie inside memory (checked above); `copy`
    // allows overlap.
    unsafe { std::ptr::copy(ctx.mem.add(from), ctx.mem.add(to), n) };
    // SAFETY: the interrupt word outlives the run.
    if unsafe { (*ctx.irq).load(Ordering::Relaxed) } != 0 {
        // SAFETY: as `poll`'s.
        return unsafe { poll(ctx, code_pc) };
    }
    0
}
