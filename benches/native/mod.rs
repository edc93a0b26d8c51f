//! Hand-written native Rust references of the benchmark PLC programs.
//!
//! Each reference does the same work per cycle as its ST program in
//! `benches/programs/`, with the same semantics and therefore the same
//! checksum. Program variables are struct fields that persist across cycles,
//! standard function-block instances are the small structs below with a `call`
//! method, and ST arrays are Rust arrays. Integer arithmetic uses the widths
//! of the ST types (DINT → `i32` wrapping, INT → `i16`, WORD → `u16`), REAL is
//! `f32`, TIME is `i64` nanoseconds.
//!
//! The references are the yardstick the interpreter is measured against, so
//! they are written the way a careful C programmer would write the same
//! program by hand: no algorithmic shortcuts, no work skipped across cycles.
//! Every `cycle` starts with [`std::hint::black_box`] on the program state,
//! which makes the optimiser treat the state as read and written by unknown
//! code between cycles (as a scan cycle driven by a runtime is), while leaving
//! the work inside a cycle fully optimisable.
//!
//! The standard FBs follow plcrun's `semantics.md` §4: `R_TRIG` pulses on a
//! CLK that is TRUE at the first call; `CTU` counts on the rising edge of CU
//! (`IF R THEN CV := 0 ELSIF CU rose AND CV < PVmax THEN CV := CV + 1`, then
//! `Q := CV >= PV`); `TON` records its start time on the call where IN rises
//! and uses the clock value of the cycle it is called in.

pub mod a_bool_logic;
pub mod b_int_sieve;
pub mod c_fb;
pub mod d_real_math;
pub mod empty;

pub use a_bool_logic::BenchA;
pub use b_int_sieve::BenchB;
pub use c_fb::BenchC;
pub use d_real_math::BenchD;
pub use empty::BenchEmpty;

/// Virtual-clock cycle time: cycle `k` (counting from 0) runs at `k × 10 ms`.
pub const CYCLE_NS: i64 = 10_000_000;

/// Clock value (ns) of cycle `k` on the virtual clock.
pub fn cycle_time_ns(k: u64) -> i64 {
    k as i64 * CYCLE_NS
}

/// Uniform access to the references for tests and the benchmark harness.
///
/// Each reference also has the same three methods as inherent methods; this
/// trait only forwards to them so generic code can drive any of them.
pub trait Reference {
    /// Short benchmark name (`a`, `b`, `c`, `d`, `empty`).
    const NAME: &'static str;
    /// A fresh instance in the state before the first cycle.
    fn fresh() -> Self;
    /// Runs one cycle at clock value `now_ns`.
    fn step(&mut self, now_ns: i64);
    /// The program's `checksum` variable (for `empty`, the counter `x`).
    fn value(&self) -> i32;
}

macro_rules! impl_reference {
    ($ty:ty, $name:literal) => {
        impl Reference for $ty {
            const NAME: &'static str = $name;
            fn fresh() -> Self {
                <$ty>::new()
            }
            #[inline]
            fn step(&mut self, now_ns: i64) {
                self.cycle(now_ns)
            }
            fn value(&self) -> i32 {
                self.checksum()
            }
        }
    };
}

impl_reference!(BenchA, "a");
impl_reference!(BenchB, "b");
impl_reference!(BenchC, "c");
impl_reference!(BenchD, "d");
impl_reference!(BenchEmpty, "empty");

/// Runs a fresh reference for `cycles` cycles (cycle `k` at `k × 10 ms`) and
/// returns its checksum.
pub fn run<R: Reference>(cycles: u64) -> i32 {
    let mut r = R::fresh();
    for k in 0..cycles {
        r.step(cycle_time_ns(k));
    }
    r.value()
}

/// IEC `R_TRIG`: `Q := CLK AND NOT M; M := CLK;` with `M` initially FALSE.
#[derive(Clone, Copy, Debug, Default)]
pub struct RTrig {
    /// Input CLK as last passed.
    pub clk: bool,
    /// Output Q.
    pub q: bool,
    m: bool,
}

impl RTrig {
    /// One call with `CLK := clk`.
    #[inline]
    pub fn call(&mut self, clk: bool) {
        self.clk = clk;
        self.q = clk && !self.m;
        self.m = clk;
    }
}

/// IEC `CTU` (INT variant): CU counts on its rising edge, PVmax = 32767.
#[derive(Clone, Copy, Debug, Default)]
pub struct Ctu {
    /// Input CU as last passed.
    pub cu: bool,
    /// Input R as last passed.
    pub r: bool,
    /// Input PV as last passed.
    pub pv: i16,
    /// Output Q.
    pub q: bool,
    /// Output CV.
    pub cv: i16,
    /// Edge memory of CU (the implicit `R_TRIG` of the `R_EDGE` input).
    cu_m: bool,
}

impl Ctu {
    /// One call with `CU := cu, R := r, PV := pv`.
    #[inline]
    pub fn call(&mut self, cu: bool, r: bool, pv: i16) {
        self.cu = cu;
        self.r = r;
        self.pv = pv;
        let rose = cu && !self.cu_m;
        self.cu_m = cu;
        if r {
            self.cv = 0;
        } else if rose && self.cv < i16::MAX {
            self.cv += 1;
        }
        self.q = self.cv >= pv;
    }
}

/// IEC `TON` on the cycle clock; times are `i64` nanoseconds.
#[derive(Clone, Copy, Debug, Default)]
pub struct Ton {
    /// Input IN as last passed.
    pub input: bool,
    /// Input PT as last passed (ns).
    pub pt: i64,
    /// Output Q.
    pub q: bool,
    /// Output ET (ns).
    pub et: i64,
    start: i64,
    prev_in: bool,
}

impl Ton {
    /// One call with `IN := input, PT := pt` in the cycle whose clock is `now`.
    #[inline]
    pub fn call(&mut self, input: bool, pt: i64, now: i64) {
        self.input = input;
        self.pt = pt;
        if input {
            if !self.prev_in {
                self.start = now;
            }
            let et = (now - self.start).min(pt);
            self.et = et;
            self.q = et >= pt;
        } else {
            self.q = false;
            self.et = 0;
        }
        self.prev_in = input;
    }
}
