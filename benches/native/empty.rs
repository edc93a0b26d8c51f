//! Reference for `bench_empty.st`: the program `x := x + 1` on a DINT.
//!
//! It measures the fixed cost of a scan cycle. Its "checksum" is `x`, which
//! equals the number of cycles run.

/// Program state of `bench_empty.st`.
pub struct BenchEmpty {
    x: i32,
}

impl Default for BenchEmpty {
    fn default() -> Self {
        Self::new()
    }
}

impl BenchEmpty {
    /// The state before the first cycle.
    pub fn new() -> Self {
        Self { x: 0 }
    }

    /// Runs one scan cycle (`now_ns` is unused).
    pub fn cycle(&mut self, now_ns: i64) {
        let s = std::hint::black_box(self);
        std::hint::black_box(now_ns);
        s.x = s.x.wrapping_add(1);
    }

    /// The program's variable `x`.
    pub fn checksum(&self) -> i32 {
        self.x
    }
}
