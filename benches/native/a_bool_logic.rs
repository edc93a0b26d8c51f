//! Reference for `bench_a_bool_logic.st`: boolean / bit logic.
//!
//! The ST program is generated straight-line code over 200 numbered BOOLs of
//! each kind (`Xnnn` step flags, `Cnnn` transition conditions, `Ynnn` action
//! outputs) and 200 `TON`s `Tnnn`. Its structure is regular:
//!
//! - 10 chains of 20 steps; step `k` belongs to chain `k / 20`, the first
//!   step of each chain starts TRUE;
//! - `Ck := Xk AND ((in[a] XOR in[b]) OR (in[c] AND NOT in[d]))` with
//!   `a = k`, `b = 3k + 1`, `c = 5k + 2`, `d = 7k + 5`, all mod 16
//!   (tabulated in [`TRANSITION_INPUTS`]);
//! - `Xk := (Xk AND NOT Ck) OR C(pred k)`, the predecessor of a chain's first
//!   step being its last step;
//! - `Tk(IN := Xk, PT := T#20ms); Yk := Xk AND NOT Tk.Q;`
//! - `wraps` counts the chains whose last transition fired, and `pattern`
//!   weights the first three steps of each chain by 1..=30.
//!
//! Here those 200-fold repetitions are loops over arrays; the test suite
//! re-renders the ST statements from the same tables and compares them with
//! the program text line by line, so the loops compute exactly what the ST
//! does. All conditions are computed before any step changes, as in the ST.

use super::Ton;

/// Number of steps (and of each kind of numbered variable).
pub const STEPS: usize = 200;
/// Steps per chain.
pub const CHAIN_LEN: usize = 20;
/// Number of chains.
pub const CHAINS: usize = STEPS / CHAIN_LEN;
/// `PT` of every step timer: `T#20ms`.
pub const TIMER_PT_NS: i64 = 20_000_000;
/// Initial value of the LFSR: `16#ACE1`.
pub const LFSR_SEED: u16 = 0xACE1;
/// Galois LFSR feedback taps: `16#B400`.
pub const LFSR_TAPS: u16 = 0xB400;
/// Steps of each chain that contribute to `pattern` (offsets in the chain).
pub const PATTERN_STEPS_PER_CHAIN: usize = 3;

/// Input indices `[a, b, c, d]` of `Ck := Xk AND ((in[a] XOR in[b]) OR
/// (in[c] AND NOT in[d]))`; they depend on `k mod 16` only.
pub const TRANSITION_INPUTS: [[u8; 4]; 16] = transition_inputs();

const fn transition_inputs() -> [[u8; 4]; 16] {
    let mut t = [[0u8; 4]; 16];
    let mut k = 0;
    while k < 16 {
        t[k] = [
            k as u8,
            ((3 * k + 1) % 16) as u8,
            ((5 * k + 2) % 16) as u8,
            ((7 * k + 5) % 16) as u8,
        ];
        k += 1;
    }
    t
}

/// Index of the step whose transition activates step `k`.
pub const fn predecessor(k: usize) -> usize {
    if k.is_multiple_of(CHAIN_LEN) {
        k + CHAIN_LEN - 1
    } else {
        k - 1
    }
}

/// Program state of `bench_a_bool_logic.st`.
// Every ST variable is kept, including outputs that nothing reads (`y`).
#[allow(dead_code)]
pub struct BenchA {
    checksum: i32,
    cycles: i32,
    lfsr: u16,
    wraps: i32,
    pattern: i32,
    inputs: [bool; 16],
    x: [bool; STEPS],
    c: [bool; STEPS],
    y: [bool; STEPS],
    t: [Ton; STEPS],
}

impl Default for BenchA {
    fn default() -> Self {
        Self::new()
    }
}

impl BenchA {
    /// The state before the first cycle (declared initial values).
    pub fn new() -> Self {
        let mut x = [false; STEPS];
        for chain in 0..CHAINS {
            x[chain * CHAIN_LEN] = true;
        }
        Self {
            checksum: 0,
            cycles: 0,
            lfsr: LFSR_SEED,
            wraps: 0,
            pattern: 0,
            inputs: [false; 16],
            x,
            c: [false; STEPS],
            y: [false; STEPS],
            t: [Ton::default(); STEPS],
        }
    }

    /// Runs one scan cycle at clock value `now_ns`.
    pub fn cycle(&mut self, now_ns: i64) {
        let s = std::hint::black_box(self);
        let now = std::hint::black_box(now_ns);
        s.cycles = s.cycles.wrapping_add(1);

        // 16-bit Galois LFSR.
        s.lfsr = if s.lfsr & 0x0001 != 0 {
            (s.lfsr >> 1) ^ LFSR_TAPS
        } else {
            s.lfsr >> 1
        };
        for (bit, input) in s.inputs.iter_mut().enumerate() {
            *input = s.lfsr & (1 << bit) != 0;
        }

        // Transition conditions from the current step states.
        let inp = &s.inputs;
        for k in 0..STEPS {
            let [a, b, c, d] = TRANSITION_INPUTS[k % 16];
            let (a, b, c, d) = (
                inp[a as usize],
                inp[b as usize],
                inp[c as usize],
                inp[d as usize],
            );
            s.c[k] = s.x[k] && ((a ^ b) || (c && !d));
        }

        // Step evolution.
        for k in 0..STEPS {
            s.x[k] = (s.x[k] && !s.c[k]) || s.c[predecessor(k)];
        }

        // Actions: a TON per step and a pulse-limited output.
        for k in 0..STEPS {
            s.t[k].call(s.x[k], TIMER_PT_NS, now);
            s.y[k] = s.x[k] && !s.t[k].q;
        }

        // Completed chain rounds.
        for chain in 0..CHAINS {
            if s.c[chain * CHAIN_LEN + CHAIN_LEN - 1] {
                s.wraps = s.wraps.wrapping_add(1);
            }
        }
        let mut pattern: i32 = 0;
        let mut weight: i32 = 1;
        for chain in 0..CHAINS {
            for offset in 0..PATTERN_STEPS_PER_CHAIN {
                if s.x[chain * CHAIN_LEN + offset] {
                    pattern = pattern.wrapping_add(weight);
                }
                weight += 1;
            }
        }
        s.pattern = pattern;
        s.checksum = s.wraps.wrapping_mul(1000).wrapping_add(s.pattern);
    }

    /// The program's `checksum` variable.
    pub fn checksum(&self) -> i32 {
        self.checksum
    }
}
