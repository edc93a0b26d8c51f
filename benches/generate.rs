//! Generators of large ST sources for compile-time and scaling benchmarks.
//!
//! - [`large_program`]: one `PROGRAM` of a requested number of lines (100 000
//!   for the "`plcrun check` under one second" test) with many variables and
//!   statements of varied kinds: assignments with integer, REAL and boolean
//!   expressions, IF/ELSIF/ELSE, CASE, FOR, WHILE, REPEAT, standard function
//!   and FB calls, calls of a user FUNCTION and FUNCTION_BLOCK, comments. The
//!   program is also safe to run (no division by zero, no out-of-range index
//!   or conversion, bounded loops).
//! - [`sfc_ring`]: a textual SFC chart of N steps in a ring with one active
//!   step, for comparing a 10-step with a 10 000-step chart; its expected
//!   checksum after a number of cycles is [`sfc_ring_checksum`].
//!
//! Used from the benchmark harness and the tests through `#[path]`.

use std::fmt::Write as _;

// The includer provides `rng` (tests/support/rng.rs), so that a test
// binary that already has it compiles it once.
use super::rng::Rng;

/// Variables of each kind declared by [`large_program`].
pub const LARGE_DINTS: usize = 1000;
/// BOOL variables declared by [`large_program`].
pub const LARGE_BOOLS: usize = 500;
/// REAL variables declared by [`large_program`].
pub const LARGE_REALS: usize = 500;
/// TON instances declared by [`large_program`].
pub const LARGE_TIMERS: usize = 50;
/// Length of the DINT array `arr` (`ARRAY[0..LARGE_ARRAY-1]`).
pub const LARGE_ARRAY: usize = 100;

/// Lines of the user FUNCTION and FUNCTION_BLOCK before the PROGRAM.
const PRELUDE: &str = "\
(* Generated compile-time benchmark: one large PROGRAM. *)
FUNCTION gen_mix : DINT
VAR_INPUT
  a : DINT;
  b : DINT;
END_VAR
  gen_mix := (a * 31 + b) MOD 1000003;
END_FUNCTION

FUNCTION_BLOCK gen_acc
VAR_INPUT
  inc : DINT;
END_VAR
VAR_OUTPUT
  total : DINT;
END_VAR
  total := total + inc;
END_FUNCTION_BLOCK

";

/// Generates an ST source of exactly `lines` lines (at least 3 000) holding
/// a user FUNCTION, a FUNCTION_BLOCK and one large `PROGRAM big`.
///
/// The PROGRAM's first variable is `checksum : DINT`, updated at the end of
/// each cycle. Statements are chosen pseudo-randomly (fixed seed) among a
/// dozen kinds, so the parser, name resolution and type checker all see a
/// realistic mix.
pub fn large_program(lines: usize) -> String {
    assert!(lines >= 3000, "too few lines for the declarations");
    let mut out = String::with_capacity(lines * 40);
    out.push_str(PRELUDE);
    out.push_str("PROGRAM big\nVAR\n  checksum : DINT := 0;\n");
    for i in 0..LARGE_DINTS {
        let _ = writeln!(out, "  d{i} : DINT := {};", i % 97);
    }
    for i in 0..LARGE_BOOLS {
        let init = if i % 3 == 0 { "TRUE" } else { "FALSE" };
        let _ = writeln!(out, "  b{i} : BOOL := {init};");
    }
    for i in 0..LARGE_REALS {
        let _ = writeln!(out, "  r{i} : REAL := {}.5;", i % 13);
    }
    for i in 0..LARGE_TIMERS {
        let _ = writeln!(out, "  t{i} : TON;");
    }
    let _ = writeln!(out, "  arr : ARRAY[0..{}] OF DINT;", LARGE_ARRAY - 1);
    out.push_str("  acc : gen_acc;\n  k : DINT;\n  n : INT := 0;\nEND_VAR\n");

    // Reserve the last two lines: the checksum statement and END_PROGRAM.
    let body_end = lines - 2;
    let mut used = out.lines().count();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut block = String::new();
    while used < body_end {
        block.clear();
        statement(&mut rng, &mut block);
        let n = block.lines().count();
        if used + n > body_end {
            // Fill the remainder with one-line statements.
            for _ in used..body_end {
                let (a, b) = (rng.below(LARGE_DINTS), rng.below(LARGE_DINTS));
                let _ = writeln!(out, "  d{a} := d{b} + 1;");
            }
            break;
        }
        out.push_str(&block);
        used += n;
    }
    out.push_str("  checksum := d0 + d1 + acc.total;\nEND_PROGRAM\n");
    out
}

/// Appends one generated statement (one or more lines) to `out`.
fn statement(rng: &mut Rng, out: &mut String) {
    let d = |rng: &mut Rng| rng.below(LARGE_DINTS);
    let b = |rng: &mut Rng| rng.below(LARGE_BOOLS);
    let r = |rng: &mut Rng| rng.below(LARGE_REALS);
    let (d1, d2, d3) = (d(rng), d(rng), d(rng));
    let (b1, b2, b3) = (b(rng), b(rng), b(rng));
    let (r1, r2) = (r(rng), r(rng));
    let small = rng.below(1000) + 1;
    let _ = match rng.below(14) {
        0 => writeln!(out, "  d{d1} := d{d2} * {small} + d{d3} - {};", small / 2),
        1 => writeln!(out, "  d{d1} := (d{d2} + d{d3}) MOD {small};"),
        2 => writeln!(out, "  b{b1} := (b{b2} AND NOT b{b3}) OR (d{d1} > d{d2});"),
        3 => writeln!(
            out,
            "  r{r1} := r{r2} * 0.5 + DINT_TO_REAL(d{d1} MOD 100) / 7.0;"
        ),
        4 => writeln!(
            out,
            "  IF d{d1} > d{d2} THEN\n    d{d3} := d{d3} + 1;\n  ELSIF b{b1} THEN\n    \
             d{d3} := d{d3} - 1;\n  ELSE\n    b{b2} := NOT b{b2};\n  END_IF;"
        ),
        5 => writeln!(
            out,
            "  CASE d{d1} MOD 5 OF\n    0: d{d2} := d{d2} + {small};\n    1, 2: d{d2} := d{d3};\n    \
             3..4: b{b1} := TRUE;\n  ELSE\n    d{d2} := 0;\n  END_CASE;"
        ),
        6 => writeln!(
            out,
            "  FOR k := 0 TO {} DO\n    arr[k] := arr[k] + d{d1};\n  END_FOR;",
            LARGE_ARRAY - 1
        ),
        7 => writeln!(
            out,
            "  k := 0;\n  WHILE k < {} DO\n    k := k + 1;\n  END_WHILE;",
            small % 16
        ),
        8 => writeln!(
            out,
            "  REPEAT\n    n := n + 1;\n  UNTIL n > 10\n  END_REPEAT;\n  n := 0;"
        ),
        9 => writeln!(
            out,
            "  t{}(IN := b{b1}, PT := T#{small}ms);\n  b{b2} := t{}.Q;",
            d1 % LARGE_TIMERS,
            d1 % LARGE_TIMERS
        ),
        10 => writeln!(
            out,
            "  d{d1} := MAX(d{d2}, MIN(d{d3}, {small})) + ABS(d{d2} MOD 50);"
        ),
        11 => writeln!(
            out,
            "  r{r1} := SQRT(ABS(r{r2})) + SIN(r{r1}); (* REAL functions *)"
        ),
        12 => writeln!(
            out,
            "  d{d1} := gen_mix(a := d{d2} MOD 1000, b := d{d3} MOD 1000);\n  acc(inc := d{d1} MOD 10);"
        ),
        _ => writeln!(
            out,
            "  arr[(d{d1} MOD {len} + {len}) MOD {len}] := arr[{}] - d{d2};",
            small % LARGE_ARRAY,
            len = LARGE_ARRAY
        ),
    };
}

/// Generates a textual SFC `PROGRAM sfc_ring` with `steps` steps in a ring.
///
/// `S0` is the initial step (no action); step `Sk` (k ≥ 1) has action
/// `Ak(N)` whose body adds `k` to `checksum`. Transition `Sk → S(k+1)` (the
/// last one back to `S0`) has condition `ck`, a BOOL initialised to
/// `advancing`: with `true` the single active step moves one step per cycle,
/// with `false` the chart stays idle in `S0`.
pub fn sfc_ring(steps: usize, advancing: bool) -> String {
    assert!(steps >= 2, "a ring needs at least two steps");
    let init = if advancing { "TRUE" } else { "FALSE" };
    let mut out = String::with_capacity(steps * 120);
    let _ = writeln!(
        out,
        "(* Generated SFC ring of {steps} steps, one active. *)"
    );
    out.push_str("PROGRAM sfc_ring\nVAR\n  checksum : DINT := 0;\n");
    for k in 0..steps {
        let _ = writeln!(out, "  c{k} : BOOL := {init};");
    }
    out.push_str("END_VAR\n");
    out.push_str("  INITIAL_STEP S0 : END_STEP\n");
    for k in 1..steps {
        let _ = writeln!(out, "  STEP S{k} : A{k}(N); END_STEP");
    }
    for k in 0..steps {
        let _ = writeln!(
            out,
            "  TRANSITION FROM S{k} TO S{} := c{k}; END_TRANSITION",
            (k + 1) % steps
        );
    }
    for k in 1..steps {
        let _ = writeln!(
            out,
            "  ACTION A{k} : checksum := checksum + {k}; END_ACTION"
        );
    }
    out.push_str("END_PROGRAM\n");
    out
}

/// Expected `checksum` of [`sfc_ring`] after `cycles` cycles, under
/// plcrun's SFC rules: the first call activates `S0` and evolves in the same
/// call; an `N` action's body runs while its step is active and once more
/// (the final scan) in the call its step is deactivated.
pub fn sfc_ring_checksum(steps: usize, advancing: bool, cycles: u64) -> i32 {
    if !advancing {
        return 0;
    }
    let n = steps as u64;
    let mut sum: i32 = 0;
    for call in 0..cycles {
        // Active after this call's evolution, and active in the previous call.
        let active = (call + 1) % n;
        sum = sum.wrapping_add(active as i32);
        if call >= 1 {
            let previous = call % n;
            // The previous step's action gets its final scan (S0 has none;
            // the value 0 adds nothing either way).
            sum = sum.wrapping_add(previous as i32);
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    #[test]
    fn large_program_has_the_requested_size_and_variety() {
        let src = super::large_program(100_000);
        assert_eq!(src.lines().count(), 100_000);
        assert!(
            src.len() > 2_000_000 && src.len() < 6_000_000,
            "{} bytes",
            src.len()
        );
        assert!(src.ends_with("END_PROGRAM\n"));
        for needle in [
            "FUNCTION gen_mix",
            "FUNCTION_BLOCK gen_acc",
            "IF ",
            "ELSIF ",
            "CASE ",
            "FOR k := 0 TO",
            "WHILE k <",
            "REPEAT",
            "SQRT(",
            "gen_mix(a :=",
            "acc(inc :=",
            "(IN := b",
            "arr[",
        ] {
            assert!(src.contains(needle), "no `{needle}`");
        }
        assert_eq!(super::large_program(100_000), src, "deterministic");
        assert_eq!(super::large_program(3000).lines().count(), 3000);
    }

    #[test]
    fn sfc_ring_has_one_step_transition_and_action_per_position() {
        for steps in [10, 10_000] {
            let src = super::sfc_ring(steps, true);
            assert_eq!(src.matches("INITIAL_STEP ").count(), 1);
            assert_eq!(src.matches("  STEP S").count(), steps - 1);
            assert_eq!(src.matches("TRANSITION FROM").count(), steps);
            assert_eq!(src.matches("END_ACTION").count(), steps - 1);
            let last = format!("TRANSITION FROM S{} TO S0 := c{};", steps - 1, steps - 1);
            assert!(src.contains(&last));
        }
        assert!(super::sfc_ring(10, true).contains("  STEP S1 : A1(N); END_STEP\n"));
        assert!(super::sfc_ring(10, false).contains("c3 : BOOL := FALSE;"));
    }

    #[test]
    fn sfc_ring_checksum_follows_the_ring() {
        // Call 0: S1 runs (1). Call 1: S2 runs, S1 final scan (2 + 1).
        assert_eq!(super::sfc_ring_checksum(10, true, 1), 1);
        assert_eq!(super::sfc_ring_checksum(10, true, 2), 4);
        // Ring of 3: actives 1,2,0,1; final scans -,1,2,0.
        assert_eq!(super::sfc_ring_checksum(3, true, 4), 1 + 2 + 1 + 2 + 1);
        assert_eq!(super::sfc_ring_checksum(10_000, false, 1000), 0);
    }
}
