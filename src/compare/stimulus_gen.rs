//! The random stimulus: deterministic per seed, the same on every machine.
//!
//! The generator is SplitMix64 (64-bit state; each draw adds
//! `0x9E3779B97F4A7C15` to the state and mixes it with the two
//! multiply-xorshift rounds of the published algorithm), started with the
//! state equal to the seed. For each cycle `c` in `0..cycles`, and in it for
//! each driven input in [`super::Pairing::inputs`] order (inputs of
//! [`InputKind::Fixed`] are skipped and draw nothing):
//!
//! 1. an input still holding its last new value (see 3) draws nothing;
//! 2. otherwise one draw `u` in `[0, 1)` (the top 53 bits of a draw over
//!    2^53); if `u < change_prob` the input changes at `c` to a new value
//!    (one more draw, see [`InputKind`]: BOOL flips without a draw; an
//!    integer takes `lo + d % (hi - lo)`, skipping over the current value;
//!    REAL the same over the whole numbers -100..=100; TIME the same over
//!    0, 10 ms, ..., 1 s; an enumeration over its values);
//! 3. after a change, one draw `h = min_hold + d % (max_hold - min_hold + 1)`:
//!    the input keeps its new value for `h` cycles (`c .. c + h - 1`); it
//!    may change again at `c + h` at the earliest.
//!
//! The current value an input starts from is its initial value in A.

use super::error::CompareError;
use super::input_plan::{InputChange, InputPlan};
use super::pairing::{InputKind, Pairing};

/// Settings of the random stimulus generator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RandomStimulus {
    /// Probability that an input not held changes at a cycle (0 < p <= 1).
    pub change_prob: f64,
    /// Fewest cycles a new value is held (>= 1).
    pub min_hold: u64,
    /// Most cycles a new value is held (>= `min_hold`).
    pub max_hold: u64,
}

impl Default for RandomStimulus {
    /// Change probability 0.1, hold 1 to 20 cycles.
    fn default() -> Self {
        RandomStimulus {
            change_prob: 0.1,
            min_hold: 1,
            max_hold: 20,
        }
    }
}

/// SplitMix64, as described in the module docs.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// `d % n` for `n >= 1`.
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }
}

impl RandomStimulus {
    /// Refuses settings outside their ranges.
    pub fn validate(&self) -> Result<(), CompareError> {
        let bad = |problem: String| Err(CompareError::BadRandomSettings { problem });
        if !(self.change_prob > 0.0 && self.change_prob <= 1.0) {
            return bad(format!(
                "--change-prob must be in (0, 1], not {}",
                self.change_prob
            ));
        }
        if self.min_hold < 1 {
            return bad("--min-hold must be at least 1 cycle".into());
        }
        if self.max_hold < self.min_hold {
            return bad(format!(
                "--max-hold ({}) must not be below --min-hold ({})",
                self.max_hold, self.min_hold
            ));
        }
        Ok(())
    }

    /// The plan of `cycles` cycles for `seed`; `initial` holds each
    /// input's starting value as the generator counts it (see
    /// [`super::Pair::random_plan`]).
    pub(crate) fn generate(
        &self,
        pairing: &Pairing,
        initial: &[i64],
        seed: u64,
        cycles: u64,
    ) -> InputPlan {
        let mut rng = SplitMix64(seed);
        let mut current = initial.to_vec();
        let mut held = vec![0u64; pairing.inputs.len()];
        let mut changes = Vec::new();
        for cycle in 0..cycles {
            for (i, input) in pairing.inputs.iter().enumerate() {
                if input.kind == InputKind::Fixed {
                    continue;
                }
                if held[i] > 0 {
                    held[i] -= 1;
                    continue;
                }
                if rng.unit() >= self.change_prob {
                    continue;
                }
                let (code, value) = new_value(&input.kind, current[i], &mut rng);
                current[i] = code;
                changes.push(InputChange {
                    cycle,
                    input: i,
                    value,
                });
                let span = self.max_hold - self.min_hold + 1;
                held[i] = self.min_hold + rng.below(span) - 1;
            }
        }
        InputPlan { cycles, changes }
    }
}

/// A value other than `current` (as the generator counts it: 0/1, the
/// integer, the whole REAL, the TIME in steps of 10 ms, the enumeration
/// index), and its literal.
fn new_value(kind: &InputKind, current: i64, rng: &mut SplitMix64) -> (i64, String) {
    let other = |lo: i64, hi: i64, rng: &mut SplitMix64| {
        let span = (hi - lo) as u64; // values other than the current one
        if (lo..=hi).contains(&current) {
            let v = lo + rng.below(span) as i64;
            if v >= current { v + 1 } else { v }
        } else {
            lo + rng.below(span + 1) as i64
        }
    };
    match kind {
        InputKind::Bool => {
            let v = i64::from(current == 0);
            (v, if v == 1 { "TRUE" } else { "FALSE" }.to_string())
        }
        InputKind::Int { lo, hi } => {
            let v = other(*lo, *hi, rng);
            (v, v.to_string())
        }
        InputKind::Real => {
            let v = other(-100, 100, rng);
            (v, format!("{v}.0"))
        }
        InputKind::Time { long } => {
            let v = other(0, 100, rng);
            let prefix = if *long { "LT#" } else { "T#" };
            (v, format!("{prefix}{}ms", v * 10))
        }
        InputKind::Enum(values) => {
            let v = other(0, values.len() as i64 - 1, rng);
            (v, values[v as usize].clone())
        }
        InputKind::Fixed => (current, String::new()),
    }
}

#[cfg(test)]
mod tests {
    use super::SplitMix64;

    #[test]
    fn splitmix64_matches_the_published_sequence() {
        // The first outputs of SplitMix64 seeded with 1234567 (reference
        // values of the algorithm's author).
        let mut r = SplitMix64(1234567);
        assert_eq!(r.next(), 6457827717110365317);
        assert_eq!(r.next(), 3203168211198807973);
    }
}
