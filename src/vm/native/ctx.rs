//! The context native code runs with, and the way in from the
//! interpreter. One [`Ctx`] lives on the Rust stack for each entry into
//! native code; generated code reads its first fields at fixed offsets
//! and hands its address to every helper.

use crate::ir::image::Image;
use crate::ir::op::CodeIdx;
use crate::vm::{Fault, FaultKind, Interrupt, Machine};
use std::sync::atomic::AtomicU32;

/// The signature of every entry of a [`super::Compiled`] block table:
/// `(ctx, frame base, block index, frame address) -> 0` (returned) or `1`
/// (a fault, waiting in [`Ctx::fault`]). The frame address is
/// `mem + 8 × base`, computed by the caller (wrapping, not dereferenced:
/// the callee checks `base` first); receiving it as one value keeps the
/// generated code from spending two registers on it.
pub(crate) type EntryFn = unsafe extern "C" fn(*mut Ctx, usize, u32, *mut u64) -> u32;

/// What a running native block needs besides its frame. `repr(C)`: the
/// generated code loads `mem`, `len`, `irq` and `now` at their offsets
/// ([`std::mem::offset_of`]).
#[repr(C)]
pub(crate) struct Ctx {
    /// The machine's memory (`Machine::mem`, which no one resizes while a
    /// block runs).
    pub(super) mem: *mut u64,
    /// Its length in slots.
    pub(super) len: u64,
    /// The interrupt word, polled where the interpreter polls it.
    pub(super) irq: *const AtomicU32,
    /// What holds it (for the check after the word was found set).
    pub(super) interrupt: *const Interrupt,
    /// The cycle's clock value (`Machine::now`).
    pub(super) now: i64,
    /// The machine, for the helpers (strings, references, the interpreter).
    pub(super) machine: *mut Machine,
    /// The verified image the blocks belong to.
    pub(super) image: *const Image,
    /// The fault a helper recorded before native code returned 1.
    pub(super) fault: Option<Fault>,
}

/// Runs block `code` at `base` as machine code when the machine holds
/// native code for it; `None` when it must run in the interpreter.
#[inline]
pub(crate) fn enter(
    m: &mut Machine,
    img: &Image,
    code: CodeIdx,
    base: usize,
) -> Option<Result<(), Fault>> {
    let entry = m.native()?.native_entry(code)?;
    let mem = m.mem.as_mut_ptr();
    let len = m.mem.len() as u64;
    let interrupt: *const Interrupt = std::sync::Arc::as_ptr(m.interrupt());
    // SAFETY: the `Arc` in the machine keeps the interrupt alive.
    let irq = unsafe { (*interrupt).word() } as *const AtomicU32;
    let now = m.now;
    let mut ctx = Ctx {
        mem,
        len,
        irq,
        interrupt,
        now,
        machine: m,
        image: img,
        fault: None,
    };
    // SAFETY: `entry` was compiled from this verified image (the machine
    // runs native code only for the image it was compiled from:
    // `Compiled::fits`), and `ctx` describes this machine's memory; the
    // code checks `base` against it before touching the frame.
    let fp = mem.wrapping_add(base);
    let status = unsafe { entry(&mut ctx, base, code.get(), fp) };
    if status == 0 {
        return Some(Ok(()));
    }
    Some(Err(ctx.fault.take().unwrap_or(Fault {
        // A helper always records its fault; this is never reached.
        kind: FaultKind::BadAddress,
        code,
        pc: 0,
    })))
}
