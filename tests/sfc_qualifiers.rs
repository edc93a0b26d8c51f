//! One test per action qualifier: alone, with R, on two steps at once, and
//! across step deactivation. Every expected `out` string (one character per
//! cycle, `1` = TRUE, cycle 0 first) is derived by hand from semantics §5 with
//! 10 ms cycles; the derivation is the comment of each case.
//!
//! The action is the BOOL variable `out` (`out := Q` every call the action is
//! live), so the trace shows Q directly.

use crate::support::sfc_run;

use rstest::rstest;
use sfc_run::{bits, stimulus, trace_src};

/// S0 -go1-> S1 -go2-> S2 -go3-> S0, with `out(<assoc>)` on S1.
fn sequence(assoc: &str) -> String {
    format!(
        "PROGRAM q
VAR go1, go2, go3 : BOOL; out : BOOL; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : out({assoc}); END_STEP
STEP S2 : END_STEP
TRANSITION FROM S0 TO S1 := go1; END_TRANSITION
TRANSITION FROM S1 TO S2 := go2; END_TRANSITION
TRANSITION FROM S2 TO S0 := go3; END_TRANSITION
END_PROGRAM
"
    )
}

fn run_sequence(assoc: &str, go1: &str, go2: &str, go3: &str) -> String {
    let src = sequence(assoc);
    let stim = stimulus(&[("go1", go1), ("go2", go2), ("go3", go3)]);
    let csv = trace_src(&src, Some(&stim), 16, "S1.X,out");
    bits(&csv, "out")
}

// S1 is active in cycles 2..=7 (go1 in cycle 2, go2 in cycle 8), 16 cycles.
#[rstest]
// N: Q exactly while S1 is active.
#[case::n("N", "0011111100000000")]
// No qualifier means N.
#[case::default("", "0011111100000000")]
// S: set in cycle 2, never reset.
#[case::s("S", "0011111111111111")]
// L 30 ms: L rises in cycle 2 (20 ms); Q while elapsed < 30 ms: cycles 2,3,4.
#[case::l("L, T#30ms", "0011100000000000")]
// D 30 ms: Q once elapsed >= 30 ms and while D: cycles 5,6,7.
#[case::d("D, T#30ms", "0000011100000000")]
// P: one call on the rising edge.
#[case::p("P", "0010000000000000")]
// P1: the same.
#[case::p1("P1", "0010000000000000")]
// P0: one call on the falling edge: S1 deactivated in cycle 8.
#[case::p0("P0", "0000000010000000")]
// SD 30 ms: stored in cycle 2, Q from cycle 5 on, forever (no R).
#[case::sd("SD, T#30ms", "0000011111111111")]
// DS 30 ms: held 30 ms by cycle 5 -> stored, Q from cycle 5 on.
#[case::ds("DS, T#30ms", "0000011111111111")]
// SL 30 ms: stored in cycle 2, Q for 30 ms: cycles 2,3,4.
#[case::sl("SL, T#30ms", "0011100000000000")]
// R alone: Q stays FALSE.
#[case::r("R", "0000000000000000")]
fn qualifier_alone(#[case] assoc: &str, #[case] want: &str) {
    assert_eq!(
        run_sequence(assoc, "0010000000000000", "0000000010000000", "0"),
        want,
        "{assoc}"
    );
}

// S1 is active only in cycles 2 and 3 (go2 in cycle 4): what survives the
// deactivation.
#[rstest]
// N: stops with the step.
#[case::n("N", "0011000000000000")]
// S: stored, survives.
#[case::s("S", "0011111111111111")]
// L 30 ms: the input falls after 10 ms, so Q stops with the step.
#[case::l("L, T#30ms", "0011000000000000")]
// D 30 ms: the step never lasts 30 ms: never.
#[case::d("D, T#30ms", "0000000000000000")]
// SD 30 ms: stored in cycle 2, Q from cycle 5 on although S1 left in cycle 4.
#[case::sd("SD, T#30ms", "0000011111111111")]
// DS 30 ms: DS falls before 30 ms: nothing stored, never.
#[case::ds("DS, T#30ms", "0000000000000000")]
// SL 30 ms: Q for 30 ms after cycle 2 (cycles 2,3,4), step gone in 4.
#[case::sl("SL, T#30ms", "0011100000000000")]
// P0: the falling edge in cycle 4.
#[case::p0("P0", "0000100000000000")]
// P: the rising edge only.
#[case::p("P", "0010000000000000")]
fn qualifier_across_deactivation(#[case] assoc: &str, #[case] want: &str) {
    assert_eq!(
        run_sequence(assoc, "0010000000000000", "0000100000000000", "0"),
        want,
        "{assoc}"
    );
}

/// S0 -go1-> S1 -go2-> S2 -go3-> S0 with `out(<assoc>)` on S1 and
/// `out(R)` on S2.
fn with_reset(assoc: &str) -> String {
    sequence(assoc).replace("STEP S2 : END_STEP", "STEP S2 : out(R); END_STEP")
}

// S1 active 2..=5 (go2 in 6), S2 (with R) active 6..=9 (go3 in 10), S0 from 10.
#[rstest]
// S: set 2..5; R in 6 clears it; nothing sets it again.
#[case::s("S", "0011110000000000")]
// SD 30 ms: stored in 2, Q in 5; R in 6 clears it.
#[case::sd("SD, T#30ms", "0000010000000000")]
// DS 30 ms: 30 ms held by cycle 5 -> stored, Q in 5; R in 6 clears it.
#[case::ds("DS, T#30ms", "0000010000000000")]
// SL 30 ms: Q 2,3,4 (time limit), R in 6 clears the flag.
#[case::sl("SL, T#30ms", "0011100000000000")]
// N and R never overlap here: N's Q is unaffected.
#[case::n("N", "0011110000000000")]
// L 30 ms: 2,3,4.
#[case::l("L, T#30ms", "0011100000000000")]
// D 30 ms: only cycle 5 (S1 leaves in 6).
#[case::d("D, T#30ms", "0000010000000000")]
fn qualifier_then_reset(#[case] assoc: &str, #[case] want: &str) {
    let src = with_reset(assoc);
    let stim = stimulus(&[
        ("go1", "0010000000000000"),
        ("go2", "0000001000000000"),
        ("go3", "0000000000100000"),
    ]);
    let csv = trace_src(&src, Some(&stim), 16, "out");
    assert_eq!(bits(&csv, "out"), want, "{assoc}");
}

/// A simultaneous divergence S0 -go1-> (A, B); A -ga-> A2; B -gb-> B2;
/// (A2, B2) -go3-> S0. `out(qa)` on A and `out(qb)` on B.
fn parallel(qa: &str, qb: &str) -> String {
    format!(
        "PROGRAM q
VAR go1, ga, gb, go3 : BOOL; out : BOOL; END_VAR
INITIAL_STEP S0 : END_STEP
STEP A : out({qa}); END_STEP
STEP B : out({qb}); END_STEP
STEP A2 : END_STEP
STEP B2 : END_STEP
TRANSITION FROM S0 TO (A, B) := go1; END_TRANSITION
TRANSITION FROM A TO A2 := ga; END_TRANSITION
TRANSITION FROM B TO B2 := gb; END_TRANSITION
TRANSITION FROM (A2, B2) TO S0 := go3; END_TRANSITION
END_PROGRAM
"
    )
}

// A active 2..=4 (ga in 5), B active 2..=7 (gb in 8), back to S0 in 10.
#[rstest]
// N on both: inputs OR-ed: 2..7.
#[case::n_n("N", "N", "0011111100000000")]
// N with R on the other step: R overrides while B is active (2..7); after
// that no step drives the action.
#[case::n_r("N", "R", "0000000000000000")]
// S with R at the same time: the reset dominates (no flag is stored while
// R is TRUE), so nothing is left once B leaves.
#[case::s_r("S", "R", "0000000000000000")]
// S on A and N on B: the stored flag keeps Q after both are gone.
#[case::s_n("S", "N", "0011111111111111")]
// P on both: one rising edge of the OR-ed input: cycle 2 only.
#[case::p_p("P", "P", "0010000000000000")]
// P0 on both: the OR-ed P0 input falls when B leaves (cycle 8), not when A
// leaves (B still holds it).
#[case::p0_p0("P0", "P0", "0000000010000000")]
// L 30 ms on A and L 50 ms on B: one L input (rose in cycle 2); its duration
// is the first active step's in declaration order: A's 30 ms while A is
// active (Q in 2,3,4), then B's 50 ms (elapsed 30, 40 ms < 50 in cycles 5, 6;
// 50 ms in cycle 7 ends it).
#[case::l_l("L, T#30ms", "L, T#50ms", "0011111000000000")]
// D 30 ms on A only (2..4, never 30 ms) and N on B: N alone shows.
#[case::d_n("D, T#30ms", "N", "0011111100000000")]
fn qualifier_on_two_steps(#[case] qa: &str, #[case] qb: &str, #[case] want: &str) {
    let src = parallel(qa, qb);
    let stim = stimulus(&[
        ("go1", "0010000000000000"),
        ("ga", "0000010000000000"),
        ("gb", "0000000010000000"),
        ("go3", "0000000000100000"),
    ]);
    let csv = trace_src(&src, Some(&stim), 16, "A.X,B.X,out");
    assert_eq!(bits(&csv, "A.X"), "0011100000000000");
    assert_eq!(bits(&csv, "B.X"), "0011111100000000");
    assert_eq!(bits(&csv, "out"), want, "{qa} / {qb}");
}

/// Durations may be TIME variables.
#[test]
fn duration_from_a_variable() {
    let src = sequence("L, lim").replace("out : BOOL;", "out : BOOL; lim : TIME := T#20ms;");
    let stim = stimulus(&[("go1", "0010000000000000"), ("go2", "0000000010000000")]);
    let csv = trace_src(&src, Some(&stim), 16, "out");
    // L 20 ms from cycle 2: cycles 2, 3.
    assert_eq!(bits(&csv, "out"), "0011000000000000");
}
