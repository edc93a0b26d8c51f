//! The native standard function blocks (IEC 61131-3 R_TRIG, F_TRIG, SR, RS,
//! CTU, CTD, CTUD and typed variants, TON, TOF, TP, RTC), exactly as
//! `docs/semantics.md` §4 defines them.
//!
//! Each block works on its instance memory: a slice of slots whose layout
//! (the pin order) is given by [`interface`]. Inputs are written by the caller
//! before the call and outputs read after it, so a call copies nothing.

mod bistable;
mod clock;
mod counters;
mod edges;
mod pins;
mod timers;

pub use pins::{ParamDir, interface, lookup_native, native_name};

use crate::ir::op::NativeFb;

/// Runs one call of `fb` on the instance whose first slot is at `p`.
///
/// # Safety
/// `p` must point to at least `fb.instance_slots()` (= `interface(fb).len()`)
/// valid, writable slots that nothing else references during the call.
#[inline(always)]
pub(crate) unsafe fn call_raw(fb: NativeFb, p: *mut u64, now: i64) {
    // Each arm builds a slice of the block's fixed size, so the compiler
    // knows the bounds and the call is inlined into the executor.
    macro_rules! slots {
        ($n:expr) => {
            // SAFETY: the caller guarantees `$n` (= interface length) slots.
            unsafe { std::slice::from_raw_parts_mut(p, $n) }
        };
    }
    match fb {
        NativeFb::RTrig => edges::r_trig(slots!(3)),
        NativeFb::FTrig => edges::f_trig(slots!(3)),
        NativeFb::Sr => bistable::sr(slots!(3)),
        NativeFb::Rs => bistable::rs(slots!(3)),
        NativeFb::Ctu(r) => counters::ctu(slots!(6), r),
        NativeFb::Ctd(r) => counters::ctd(slots!(6), r),
        NativeFb::Ctud(r) => counters::ctud(slots!(10), r),
        NativeFb::Ton => timers::ton(slots!(7), now),
        NativeFb::Tof => timers::tof(slots!(7), now),
        NativeFb::Tp => timers::tp(slots!(7), now),
        NativeFb::Rtc => clock::rtc(slots!(6), now),
    }
}
