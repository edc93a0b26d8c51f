//! The native standard function blocks (IEC 61131-3 R_TRIG, F_TRIG, SR, RS,
//! CTU, CTD, CTUD and typed variants, TON, TOF, TP), exactly as
//! `docs/semantics.md` §4 defines them.
//!
//! Each block works on its instance memory: a slice of slots whose layout
//! (the pin order) is given by [`layout`]. Inputs are written by the caller
//! before the call and outputs read after it, so a call copies nothing.

mod bistable;
mod counters;
mod edges;
mod layout;
mod timers;

pub use layout::{NativeParam, ParamDir, interface, lookup_native, native_name};

use crate::ir::op::NativeFb;

/// Runs one call of the native block `fb` on instance memory `inst`, with the
/// cycle's clock value `now` (nanoseconds).
#[inline]
pub fn call(fb: NativeFb, inst: &mut [u64], now: i64) {
    match fb {
        NativeFb::RTrig => edges::r_trig(inst),
        NativeFb::FTrig => edges::f_trig(inst),
        NativeFb::Sr => bistable::sr(inst),
        NativeFb::Rs => bistable::rs(inst),
        NativeFb::Ctu(r) => counters::ctu(inst, r),
        NativeFb::Ctd(r) => counters::ctd(inst, r),
        NativeFb::Ctud(r) => counters::ctud(inst, r),
        NativeFb::Ton => timers::ton(inst, now),
        NativeFb::Tof => timers::tof(inst, now),
        NativeFb::Tp => timers::tp(inst, now),
    }
}
