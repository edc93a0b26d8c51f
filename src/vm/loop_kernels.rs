//! The inner loops of two fused loop instructions, `StoreStep` and
//! `ForScan`, as functions of their own outside the dispatch function.
//!
//! Two reasons. In a function of its own a loop keeps its operands in
//! registers (inside `run`, every store through the frame pointer makes the
//! compiler read the array descriptor again) and its comparison is chosen
//! once, not through a jump table each turn. And its code no longer moves
//! when any arm of `run` changes: these loops are where bench b spends most
//! of its time, and their placement inside `run` is what made b's wall time
//! move by several percent with an unchanged loop (docs/performance.md,
//! "The lottery is not closed").
//!
//! Each kernel does exactly what its instruction pair does turn by turn:
//! the same stores to the frame in the same order, the loop variable
//! written back every turn, the interrupt word looked at where the pair's
//! backward jump looks at it.

use super::exec::for_next;
use super::{FaultKind, Interrupt};
use crate::ir::image::ArrayDesc;
use crate::ir::op::{Cmp, wrap_s};

/// Why a kernel handed control back.
#[derive(Debug, PartialEq)]
pub(crate) enum LoopExit {
    /// The loop ended normally.
    Done,
    /// `StoreStep`: this index (the raw value of the loop variable) lies
    /// outside the array. `ForScan`: the element test must run, on an index
    /// outside the array.
    BadIndex(u64),
    /// `ForScan`: the element looked for was found.
    Found,
    /// The watchdog or an abort stopped the loop at its backward jump.
    Interrupted(FaultKind),
}

/// Where a kernel works: the frame and the array it walks.
pub(crate) struct FrameArray<'a> {
    /// The frame; `desc`'s elements lie inside it (verified).
    pub fp: *mut u64,
    /// The array walked.
    pub desc: &'a ArrayDesc,
}

impl FrameArray<'_> {
    /// Whether frame slot `slot` is one of the array's element slots.
    pub fn covers(&self, slot: usize) -> bool {
        let first = self.desc.offset as u64;
        let end = first + self.desc.len * self.desc.stride as u64;
        (first..end).contains(&(slot as u64))
    }
}

/// The `WHILE j <cmp> limit DO a[j] := v; j := j + step; END_WHILE` of a
/// `StoreStep`, entered with its first store still to do. `v` and `step`
/// are read once: the caller has checked that neither they nor `j` are
/// elements of the array.
///
/// # Safety
/// `at.fp` points at a frame that holds every element of `at.desc` and
/// the slot `j`.
#[inline(never)]
pub(crate) unsafe fn store_stride(
    at: &FrameArray<'_>,
    j: usize,
    (v, step): (u64, u64),
    (cmp, limit, shift): (Cmp, i64, u8),
    irq: &Interrupt,
) -> LoopExit {
    // One loop per comparison, each with its test inlined.
    // SAFETY: passed on from the caller.
    unsafe {
        match cmp {
            Cmp::Le => store_stride_while(at, j, (v, step), shift, irq, |x| x <= limit),
            Cmp::Lt => store_stride_while(at, j, (v, step), shift, irq, |x| x < limit),
            Cmp::Ge => store_stride_while(at, j, (v, step), shift, irq, |x| x >= limit),
            Cmp::Gt => store_stride_while(at, j, (v, step), shift, irq, |x| x > limit),
            Cmp::Eq => store_stride_while(at, j, (v, step), shift, irq, |x| x == limit),
            Cmp::Ne => store_stride_while(at, j, (v, step), shift, irq, |x| x != limit),
        }
    }
}

/// `store_stride` for one comparison.
///
/// # Safety
/// As for `store_stride`.
#[inline(always)]
unsafe fn store_stride_while(
    at: &FrameArray<'_>,
    j_slot: usize,
    (v, step): (u64, u64),
    shift: u8,
    irq: &Interrupt,
    goes_on: impl Fn(i64) -> bool,
) -> LoopExit {
    let (fp, lo, len) = (at.fp, at.desc.lo, at.desc.len);
    let (first, stride) = (at.desc.offset as u64, at.desc.stride as u64);
    // SAFETY: j_slot lies in the frame (caller).
    let mut j = unsafe { *fp.add(j_slot) };
    loop {
        let k = (j as i64).wrapping_sub(lo) as u64;
        if k >= len {
            return LoopExit::BadIndex(j);
        }
        // SAFETY: k < len, and the array lies in the frame (caller).
        unsafe { *fp.add((first + k * stride) as usize) = v };
        j = wrap_s(j.wrapping_add(step), shift);
        // SAFETY: as above.
        unsafe { *fp.add(j_slot) = j };
        if !goes_on(j as i64) {
            return LoopExit::Done;
        }
        if let Some(kind) = irq.stop_request() {
            return LoopExit::Interrupted(kind);
        }
    }
}

/// The scan of a `ForScan`: steps the FOR variable `i` and stops at the
/// first element equal to `when` (`Found`), at an index outside the array
/// (`BadIndex`, for the element test to report) or at the loop's end.
///
/// # Safety
/// `at.fp` points at a frame that holds every element of `at.desc` and
/// the slot `i`.
#[inline(never)]
pub(crate) unsafe fn scan_flags(
    at: &FrameArray<'_>,
    i: usize,
    (step, lim, shift): (i16, i64, u8),
    when: bool,
    irq: &Interrupt,
) -> LoopExit {
    let (fp, lo, len) = (at.fp, at.desc.lo, at.desc.len);
    let (first, stride) = (at.desc.offset as u64, at.desc.stride as u64);
    // SAFETY: i lies in the frame (caller).
    let mut v = unsafe { *fp.add(i) };
    loop {
        let go;
        (v, go) = for_next(v, step, lim, shift);
        // SAFETY: as above.
        unsafe { *fp.add(i) = v };
        if !go {
            return LoopExit::Done;
        }
        if let Some(kind) = irq.stop_request() {
            return LoopExit::Interrupted(kind);
        }
        let k = (v as i64).wrapping_sub(lo) as u64;
        if k >= len {
            return LoopExit::BadIndex(v);
        }
        // SAFETY: k < len, and the array lies in the frame (caller).
        if (unsafe { *fp.add((first + k * stride) as usize) } != 0) == when {
            return LoopExit::Found;
        }
    }
}
