//! Reference for `bench_d_real_math.st`: REAL arithmetic.
//!
//! 1000 PID-like loops per cycle on `ARRAY[0..999] OF REAL`, with `SIN` for
//! the set-point, `SQRT(ABS(u))` in a first-order plant model and an
//! anti-windup clamp of the integral term. All arithmetic is `f32` in the
//! ST's evaluation order (left-associative, no fused multiply-add), with the
//! ST's untyped literals taken as REAL; `REAL_TO_DINT` rounds halves away from
//! zero (`f32::round`).

/// Number of loops (array length).
pub const LOOPS: usize = 1000;

/// The program's wrap-around bound for `phase`: the literal `6.2831853`
/// (kept as written in the ST, not `TAU`).
#[allow(clippy::approx_constant)]
const PHASE_WRAP: f32 = 6.283_185_3;

/// Program state of `bench_d_real_math.st`.
// Every ST variable is kept, including ones only written (`outp`, `i`, ...).
#[allow(dead_code)]
pub struct BenchD {
    checksum: i32,
    cycles: i32,
    pv: [f32; LOOPS],
    integ: [f32; LOOPS],
    prev_err: [f32; LOOPS],
    outp: [f32; LOOPS],
    i: i32,
    x: f32,
    phase: f32,
    sp: f32,
    err: f32,
    deriv: f32,
    u: f32,
    acc: f32,
    kp: f32,
    ki: f32,
    kd: f32,
    tstep: f32,
}

impl Default for BenchD {
    fn default() -> Self {
        Self::new()
    }
}

impl BenchD {
    /// The state before the first cycle (declared initial values).
    pub fn new() -> Self {
        Self {
            checksum: 0,
            cycles: 0,
            pv: [0.0; LOOPS],
            integ: [0.0; LOOPS],
            prev_err: [0.0; LOOPS],
            outp: [0.0; LOOPS],
            i: 0,
            x: 0.0,
            phase: 0.0,
            sp: 0.0,
            err: 0.0,
            deriv: 0.0,
            u: 0.0,
            acc: 0.0,
            kp: 1.2,
            ki: 0.5,
            kd: 0.05,
            tstep: 0.01,
        }
    }

    /// Runs one scan cycle (the program uses no timers, so `now_ns` is unused).
    pub fn cycle(&mut self, now_ns: i64) {
        let s = std::hint::black_box(self);
        std::hint::black_box(now_ns);
        s.cycles = s.cycles.wrapping_add(1);
        s.phase += 0.001;
        if s.phase > PHASE_WRAP {
            s.phase -= PHASE_WRAP;
        }
        let (kp, ki, kd, tstep, phase) = (s.kp, s.ki, s.kd, s.tstep, s.phase);
        let mut acc: f32 = 0.0;
        let mut x: f32 = 0.0;
        let (mut sp, mut err, mut deriv, mut u) = (s.sp, s.err, s.deriv, s.u);
        for i in 0..LOOPS {
            sp = 50.0 + 40.0 * (phase + x).sin();
            err = sp - s.pv[i];
            // IF integ > 100 THEN 100 ELSIF integ < -100 THEN -100: a clamp.
            let integ = (s.integ[i] + ki * err * tstep).clamp(-100.0, 100.0);
            s.integ[i] = integ;
            deriv = (err - s.prev_err[i]) / tstep;
            u = kp * err + integ + kd * deriv;
            s.prev_err[i] = err;
            s.pv[i] = s.pv[i] + (u - s.pv[i]) * 0.05 + 0.01 * u.abs().sqrt();
            s.outp[i] = u;
            acc += u;
            x += 0.00628;
        }
        s.i = LOOPS as i32;
        (s.sp, s.err, s.deriv, s.u, s.acc, s.x) = (sp, err, deriv, u, acc, x);
        // REAL_TO_DINT: round half away from zero (in range for this program).
        s.checksum = (acc * 10.0).round() as i32;
    }

    /// The program's `checksum` variable.
    pub fn checksum(&self) -> i32 {
        self.checksum
    }
}
