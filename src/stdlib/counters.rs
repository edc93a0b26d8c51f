//! CTU, CTD, CTUD and their typed variants. Counting inputs react to rising
//! edges; the previous input values are kept in hidden slots.
//!
//! Layouts: CTU = CU, R, PV, Q, CV, CU_prev; CTD = CD, LD, PV, Q, CV, CD_prev;
//! CTUD = CU, CD, R, LD, PV, QU, QD, CV, CU_prev, CD_prev.

use crate::ir::op::CounterRange;

/// Compares slot values in the counter's signedness.
#[inline(always)]
fn less(a: u64, b: u64, r: CounterRange) -> bool {
    match r {
        CounterRange::Udint | CounterRange::Ulint => a < b,
        _ => (a as i64) < (b as i64),
    }
}

#[inline(always)]
fn max_of(r: CounterRange) -> u64 {
    match r {
        CounterRange::Int => i16::MAX as u64,
        CounterRange::Dint => i32::MAX as u64,
        CounterRange::Lint => i64::MAX as u64,
        CounterRange::Udint => u32::MAX as u64,
        CounterRange::Ulint => u64::MAX,
    }
}

#[inline(always)]
fn min_of(r: CounterRange) -> u64 {
    match r {
        CounterRange::Int => i16::MIN as i64 as u64,
        CounterRange::Dint => i32::MIN as i64 as u64,
        CounterRange::Lint => i64::MIN as u64,
        CounterRange::Udint | CounterRange::Ulint => 0,
    }
}

/// `Q := CV >= PV` or `CV <= 0` style tests for the counter's signedness.
#[inline(always)]
fn ge(a: u64, b: u64, r: CounterRange) -> bool {
    !less(a, b, r)
}

/// Up counter.
#[inline(always)]
pub fn ctu(s: &mut [u64], r: CounterRange) {
    let cu = s[0];
    let rising = cu & !s[5] & 1 == 1;
    s[5] = cu;
    if s[1] != 0 {
        s[4] = 0;
    } else if rising && less(s[4], max_of(r), r) {
        s[4] = s[4].wrapping_add(1);
    }
    s[3] = ge(s[4], s[2], r) as u64;
}

/// Down counter.
#[inline(always)]
pub fn ctd(s: &mut [u64], r: CounterRange) {
    let cd = s[0];
    let rising = cd & !s[5] & 1 == 1;
    s[5] = cd;
    if s[1] != 0 {
        s[4] = s[2];
    } else if rising && less(min_of(r), s[4], r) {
        s[4] = s[4].wrapping_sub(1);
    }
    s[3] = !less(0, s[4], r) as u64;
}

/// Up-down counter; does not count when CU and CD rise in the same call.
#[inline(always)]
pub fn ctud(s: &mut [u64], r: CounterRange) {
    let (cu, cd) = (s[0], s[1]);
    let cu_rise = cu & !s[8] & 1 == 1;
    let cd_rise = cd & !s[9] & 1 == 1;
    s[8] = cu;
    s[9] = cd;
    if s[2] != 0 {
        s[7] = 0;
    } else if s[3] != 0 {
        s[7] = s[4];
    } else if !(cu_rise && cd_rise) {
        if cu_rise && less(s[7], max_of(r), r) {
            s[7] = s[7].wrapping_add(1);
        } else if cd_rise && less(min_of(r), s[7], r) {
            s[7] = s[7].wrapping_sub(1);
        }
    }
    s[5] = ge(s[7], s[4], r) as u64;
    s[6] = !less(0, s[7], r) as u64;
}
