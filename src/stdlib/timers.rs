//! TON, TOF and TP on the scheduler's clock (`now`, nanoseconds, constant
//! within a cycle). Layout for all three: IN, PT, Q, ET, start, prev_IN, running.
//!
//! PT is read only while a timer times; once its output has switched at
//! the end of the delay or pulse, Q and ET stay as they are until IN
//! changes, whatever PT does (`docs/semantics.md` §4, "Changes of PT").

#[inline(always)]
fn elapsed(now: i64, start: u64, pt: u64) -> u64 {
    (now.wrapping_sub(start as i64)).min(pt as i64).max(0) as u64
}

/// On-delay: Q rises once IN has been TRUE for PT, and stays TRUE until
/// IN falls.
#[inline(always)]
pub fn ton(s: &mut [u64], now: i64) {
    let input = s[0] != 0;
    if input {
        if s[5] == 0 {
            s[4] = now as u64;
            s[2] = 0;
        }
        // Timing until Q rises; then done until IN falls.
        if s[2] == 0 {
            let et = elapsed(now, s[4], s[1]);
            s[3] = et;
            s[2] = ((et as i64) >= (s[1] as i64)) as u64;
        }
    } else {
        s[2] = 0;
        s[3] = 0;
    }
    s[5] = input as u64;
}

/// Off-delay: Q follows IN up and falls PT after IN fell, and stays FALSE
/// until IN rises.
#[inline(always)]
pub fn tof(s: &mut [u64], now: i64) {
    let input = s[0] != 0;
    if input {
        s[2] = 1;
        s[3] = 0;
        s[6] = 0;
    } else {
        if s[5] != 0 {
            s[4] = now as u64;
            s[6] = 1;
        }
        if s[6] != 0 {
            let et = elapsed(now, s[4], s[1]);
            s[3] = et;
            // The delay ran out: done, ET kept, until IN rises again.
            s[6] = ((et as i64) < (s[1] as i64)) as u64;
        }
        s[2] = s[6];
    }
    s[5] = input as u64;
}

/// Pulse: a rising IN starts a pulse of length PT that IN cannot cut short.
#[inline(always)]
pub fn tp(s: &mut [u64], now: i64) {
    let input = s[0] != 0;
    if s[6] == 0 && input && s[5] == 0 {
        s[6] = 1;
        s[4] = now as u64;
    }
    if s[6] != 0 {
        let et = elapsed(now, s[4], s[1]);
        s[3] = et;
        if (et as i64) >= (s[1] as i64) {
            s[6] = 0;
        }
    }
    s[2] = s[6];
    if s[6] == 0 && !input {
        s[3] = 0;
    }
    s[5] = input as u64;
}
