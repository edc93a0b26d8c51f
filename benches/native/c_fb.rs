//! Reference for `bench_c_fb_array.st` and `bench_c_fb_unrolled.st`.
//!
//! Both programs run 1000 `R_TRIG` + 1000 `CTU` + 1000 `TON` instances each
//! cycle (3000 standard FB calls): instance `i` sees
//! `CLK := ((cycles + i) MOD 4) < 2`, counts the pulses with
//! `CU := trig.Q, R := cnt.Q` (the counter's Q of the previous call) and
//! `PV := 50 + i MOD 7`, and times `cnt.CV > 25` with `PT := T#10ms`. The
//! array variant loops over `ARRAY[0..999] OF` each FB; the unrolled variant
//! has 1000 numbered instances in straight-line code. Their work and state
//! are the same, so one reference (with arrays) serves both.

use super::{Ctu, RTrig, Ton};

/// Number of instances of each FB.
pub const INSTANCES: usize = 1000;
/// `PT` of every timer: `T#10ms`.
pub const TIMER_PT_NS: i64 = 10_000_000;

/// Program state of `bench_c_fb_array.st`.
// Every ST variable is kept, including ones only written (`i`, `phase`, `ton_q`).
#[allow(dead_code)]
pub struct BenchC {
    checksum: i32,
    cycles: i32,
    trig: [RTrig; INSTANCES],
    cnt: [Ctu; INSTANCES],
    tmr: [Ton; INSTANCES],
    i: i32,
    phase: i32,
    sum_cv: i32,
    pulses: i32,
    ton_q: i32,
}

impl Default for BenchC {
    fn default() -> Self {
        Self::new()
    }
}

impl BenchC {
    /// The state before the first cycle (declared initial values).
    pub fn new() -> Self {
        Self {
            checksum: 0,
            cycles: 0,
            trig: [RTrig::default(); INSTANCES],
            cnt: [Ctu::default(); INSTANCES],
            tmr: [Ton::default(); INSTANCES],
            i: 0,
            phase: 0,
            sum_cv: 0,
            pulses: 0,
            ton_q: 0,
        }
    }

    /// Runs one scan cycle at clock value `now_ns`.
    pub fn cycle(&mut self, now_ns: i64) {
        let s = std::hint::black_box(self);
        let now = std::hint::black_box(now_ns);
        s.cycles = s.cycles.wrapping_add(1);
        let mut sum_cv: i32 = 0;
        let mut ton_q: i32 = 0;
        let mut pulses = s.pulses;
        let mut phase = s.phase;
        for i in 0..INSTANCES {
            let idx = i as i32;
            phase = s.cycles.wrapping_add(idx) % 4;
            let trig = &mut s.trig[i];
            trig.call(phase < 2);
            if trig.q {
                pulses = pulses.wrapping_add(1);
            }
            let cnt = &mut s.cnt[i];
            // DINT_TO_INT(50 + (i MOD 7)): always in INT range.
            cnt.call(trig.q, cnt.q, (50 + idx % 7) as i16);
            let tmr = &mut s.tmr[i];
            tmr.call(cnt.cv > 25, TIMER_PT_NS, now);
            if tmr.q {
                ton_q = ton_q.wrapping_add(1);
            }
            sum_cv = sum_cv.wrapping_add(i32::from(cnt.cv));
        }
        s.i = INSTANCES as i32;
        s.phase = phase;
        s.pulses = pulses;
        s.sum_cv = sum_cv;
        s.ton_q = ton_q;
        s.checksum = sum_cv.wrapping_add((pulses % 100_000).wrapping_mul(1000));
    }

    /// The program's `checksum` variable.
    pub fn checksum(&self) -> i32 {
        self.checksum
    }

    /// Number of timers whose Q was TRUE in the last cycle (`ton_q`; not part
    /// of the checksum because it depends on the clock).
    pub fn ton_q(&self) -> i32 {
        self.ton_q
    }
}
