//! RTC, the real-time clock block of IEC 61131-3 (first edition; kept by
//! matiec and Beremiz): on the scheduler's clock (`now`, nanoseconds), as
//! docs/semantics.md §4 defines it. Layout: IN, PDT, Q, CDT, AT_ZERO,
//! IN_PREV, where AT_ZERO is the date and time that clock value 0 stands
//! for since the last preset.

/// On a rising IN the clock is preset to PDT; while IN stays TRUE, CDT is
/// PDT plus the time since that call. Q follows IN; CDT is
/// DT#1970-01-01-00:00:00 while IN is FALSE.
///
/// Out of line, unlike the other blocks: inlined into the executor's
/// dispatch loop it made benchmarks that never call it 9-20 % slower
/// (scripts/ab.sh; the loop's code layout decides its speed, ADR 0006).
#[inline(never)]
pub fn rtc(s: &mut [u64], now: i64) {
    let input = s[0] != 0;
    if input {
        if s[5] == 0 {
            s[4] = (s[1] as i64).wrapping_sub(now) as u64;
        }
        s[3] = (s[4] as i64).wrapping_add(now) as u64;
    } else {
        s[3] = 0;
    }
    s[2] = input as u64;
    s[5] = input as u64;
}
