//! Chart evolution and action execution (semantics §5), run through the
//! library's `Session` (the same CSV trace `plcrun` prints). Each expected
//! string has one character per cycle (cycle 0 first) and is derived by hand
//! in the comment above it; cycles are 10 ms.

use crate::support::sfc_run;

use rstest::rstest;
use sfc_run::{bits, column, diagnostics, stimulus, trace_src};

#[test]
fn step_time_at_activation_during_and_after() {
    let src = "PROGRAM p
VAR go1, go2 : BOOL; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : END_STEP
STEP S2 : END_STEP
TRANSITION FROM S0 TO S1 := go1; END_TRANSITION
TRANSITION FROM S1 TO S2 := go2; END_TRANSITION
END_PROGRAM";
    let stim = stimulus(&[("go1", "00100000"), ("go2", "00000100")]);
    let csv = trace_src(src, Some(&stim), 8, "S0.X,S0.T,S1.X,S1.T");
    // S0: active from the first call (T#0s), T grows by 10 ms per call; it
    // leaves in cycle 2 keeping T#20ms.
    assert_eq!(
        column(&csv, "S0.T"),
        [
            "T#0s", "T#10ms", "T#20ms", "T#20ms", "T#20ms", "T#20ms", "T#20ms", "T#20ms"
        ]
    );
    // S1: T#0s before its first activation; T#0s in the activating call
    // (cycle 2), 10, 20 ms; deactivated in cycle 5 with T = 30 ms (the value
    // of that call, computed before the evolution), kept afterwards.
    assert_eq!(bits(&csv, "S1.X"), "00111000");
    assert_eq!(
        column(&csv, "S1.T"),
        [
            "T#0s", "T#0s", "T#0s", "T#10ms", "T#20ms", "T#30ms", "T#30ms", "T#30ms"
        ]
    );
}

#[test]
fn transition_sees_the_current_step_time() {
    // S1 -> S2 when S1.T >= 20 ms: S1 activated in cycle 0 (first call,
    // T#0s), cycle 1 T = 10 ms, cycle 2 T = 20 ms -> fires in cycle 2.
    let src = "PROGRAM p
INITIAL_STEP S1 : END_STEP
STEP S2 : END_STEP
TRANSITION FROM S1 TO S2 := S1.T >= T#20ms; END_TRANSITION
END_PROGRAM";
    let csv = trace_src(src, None, 5, "S1.X,S2.X");
    assert_eq!(bits(&csv, "S1.X"), "11000");
    assert_eq!(bits(&csv, "S2.X"), "00111");
}

#[test]
fn one_evolution_per_call() {
    // All conditions TRUE: the first call activates S0 and fires S0 -> S1;
    // S1 -> S2 only in the next call, S2 -> S0 in the one after.
    let src = "PROGRAM p
INITIAL_STEP S0 : END_STEP
STEP S1 : END_STEP
STEP S2 : END_STEP
TRANSITION FROM S0 TO S1 := TRUE; END_TRANSITION
TRANSITION FROM S1 TO S2 := TRUE; END_TRANSITION
TRANSITION FROM S2 TO S0 := TRUE; END_TRANSITION
END_PROGRAM";
    let csv = trace_src(src, None, 6, "S0.X,S1.X,S2.X");
    assert_eq!(bits(&csv, "S0.X"), "001001");
    assert_eq!(bits(&csv, "S1.X"), "100100");
    assert_eq!(bits(&csv, "S2.X"), "010010");
}

#[test]
fn simultaneous_divergence_and_convergence() {
    // S0 -go-> (A, B); A -ga-> A2; B -gb-> B2; (A2, B2) -j-> S0.
    // go in 1: A, B from 1. ga in 2: A2 from 2. gb in 5: B2 from 5.
    // j is held from cycle 3: the convergence is enabled only once A2 and B2
    // are both active (cycle 6, the call after B2's activation, since j is
    // evaluated on the situation at the start of the call: in cycle 5 B2 was
    // not yet active). S0 again from 6.
    let src = "PROGRAM p
VAR go, ga, gb, j : BOOL; END_VAR
INITIAL_STEP S0 : END_STEP
STEP A : END_STEP
STEP B : END_STEP
STEP A2 : END_STEP
STEP B2 : END_STEP
TRANSITION FROM S0 TO (A, B) := go; END_TRANSITION
TRANSITION FROM A TO A2 := ga; END_TRANSITION
TRANSITION FROM B TO B2 := gb; END_TRANSITION
TRANSITION FROM (A2, B2) TO S0 := j; END_TRANSITION
END_PROGRAM";
    let stim = stimulus(&[
        ("go", "01000000"),
        ("ga", "00100000"),
        ("gb", "00000100"),
        ("j", "00011111"),
    ]);
    let csv = trace_src(src, Some(&stim), 8, "S0.X,A.X,B.X,A2.X,B2.X");
    assert_eq!(bits(&csv, "S0.X"), "10000011");
    assert_eq!(bits(&csv, "A.X"), "01000000");
    assert_eq!(bits(&csv, "B.X"), "01111000");
    assert_eq!(bits(&csv, "A2.X"), "00111100");
    assert_eq!(bits(&csv, "B2.X"), "00000100");
}

#[test]
fn all_clearable_transitions_fire_on_one_situation() {
    // A and B are active together (from cycle 1). A -> A2 needs B.X, B -> B2
    // is always clearable. In cycle 2 both are evaluated while A and B are
    // active, so both fire: A2 and B2 active from cycle 2 (if B had moved
    // first, A would be stuck).
    let src = "PROGRAM p
INITIAL_STEP S0 : END_STEP
STEP A : END_STEP
STEP B : END_STEP
STEP A2 : END_STEP
STEP B2 : END_STEP
TRANSITION FROM S0 TO (A, B) := TRUE; END_TRANSITION
TRANSITION FROM A TO A2 := B.X; END_TRANSITION
TRANSITION FROM B TO B2 := TRUE; END_TRANSITION
END_PROGRAM";
    let csv = trace_src(src, None, 4, "A.X,B.X,A2.X,B2.X");
    // Cycle 0: S0 -> (A, B). Cycle 1: A and B active since cycle 0's
    // evolution, both transitions clearable: A2, B2.
    assert_eq!(bits(&csv, "A.X"), "1000");
    assert_eq!(bits(&csv, "B.X"), "1000");
    assert_eq!(bits(&csv, "A2.X"), "0111");
    assert_eq!(bits(&csv, "B2.X"), "0111");
}

// Alternative divergence from S0 to X1, X2, X3, X4:
//   t1 (PRIORITY := 2) -> X1 on c1; t2 (PRIORITY := 1) -> X2 on c2;
//   t3 (no priority) -> X3 on c3; t4 (no priority) -> X4 on c4.
// Explicit priorities first (lower first), then the others in textual order.
#[rstest]
#[case::all("1111", "X2")]
#[case::c1_c3_c4("1011", "X1")]
#[case::c3_c4("0011", "X3")]
#[case::c4("0001", "X4")]
#[case::c1("1000", "X1")]
fn alternative_branches_by_priority(#[case] conds: &str, #[case] winner: &str) {
    let c = |k: usize| {
        if conds.as_bytes()[k] == b'1' {
            "TRUE"
        } else {
            "FALSE"
        }
    };
    let src = format!(
        "PROGRAM p
INITIAL_STEP S0 : END_STEP
STEP X1 : END_STEP
STEP X2 : END_STEP
STEP X3 : END_STEP
STEP X4 : END_STEP
TRANSITION t1 (PRIORITY := 2) FROM S0 TO X1 := {}; END_TRANSITION
TRANSITION t2 (PRIORITY := 1) FROM S0 TO X2 := {}; END_TRANSITION
TRANSITION t3 FROM S0 TO X3 := {}; END_TRANSITION
TRANSITION t4 FROM S0 TO X4 := {}; END_TRANSITION
END_PROGRAM",
        c(0),
        c(1),
        c(2),
        c(3)
    );
    let csv = trace_src(&src, None, 1, "S0.X,X1.X,X2.X,X3.X,X4.X");
    // Only one branch is taken, in the first call.
    for x in ["X1", "X2", "X3", "X4"] {
        let want = if x == winner { "1" } else { "0" };
        assert_eq!(bits(&csv, &format!("{x}.X")), want, "{x}");
    }
    assert_eq!(bits(&csv, "S0.X"), "0");
}

#[test]
fn rule_5_step_deactivated_and_activated_stays_active() {
    // S1 loops to itself when S1.T >= 20 ms: T = 0, 10, 20 -> fires in
    // cycle 2, S1 stays active (rule 5) and T restarts: cycle 2 shows T#0s.
    // Its N action stays TRUE throughout (its input never falls), and its
    // P1 action pulses only once (cycle 0): the OR-ed input never has a
    // rising edge again. The counting action runs every call, no final scan.
    let src = "PROGRAM p
VAR n : INT; lamp, pulse : BOOL; END_VAR
INITIAL_STEP S1 : lamp(N); pulse(P1); Count(N); END_STEP
TRANSITION FROM S1 TO S1 := S1.T >= T#20ms; END_TRANSITION
ACTION Count : n := n + 1; END_ACTION
END_PROGRAM";
    let csv = trace_src(src, None, 7, "S1.X,S1.T,lamp,pulse,n");
    assert_eq!(bits(&csv, "S1.X"), "1111111");
    assert_eq!(
        column(&csv, "S1.T"),
        ["T#0s", "T#10ms", "T#0s", "T#10ms", "T#0s", "T#10ms", "T#0s"]
    );
    assert_eq!(bits(&csv, "lamp"), "1111111");
    assert_eq!(bits(&csv, "pulse"), "1000000");
    assert_eq!(column(&csv, "n"), ["1", "2", "3", "4", "5", "6", "7"]);
}

#[test]
fn final_scan_runs_once_with_q_false() {
    // Step S1 active in cycles 1..=3 (go1 in 1, go2 in 4). Act (N) runs in
    // 1, 2, 3 with Act.Q TRUE, then once more in cycle 4 with Act.Q FALSE
    // (final scan): runs = 4, finals = 1. Pulse (P) runs in cycle 1 (Q TRUE)
    // and its final scan in cycle 2: prun = 2, pfinal = 1.
    // Plain statement after the actions: seenQ := Act.Q every call.
    let src = "PROGRAM p
VAR go1, go2 : BOOL; runs, finals, prun, pfinal : INT; seenQ, seenA : BOOL; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : Act(N); Pulse(P); END_STEP
STEP S2 : END_STEP
TRANSITION FROM S0 TO S1 := go1; END_TRANSITION
TRANSITION FROM S1 TO S2 := go2; END_TRANSITION
ACTION Act :
    runs := runs + 1;
    IF NOT Act.Q THEN finals := finals + 1; END_IF;
    seenA := Act.A;
END_ACTION
ACTION Pulse :
    LD prun
    ADD 1
    ST prun
    LD Pulse.Q
    JMPC done
    LD pfinal
    ADD 1
    ST pfinal
done:
END_ACTION
seenQ := Act.Q;
END_PROGRAM";
    let stim = stimulus(&[("go1", "01000000"), ("go2", "00001000")]);
    let csv = trace_src(
        src,
        Some(&stim),
        7,
        "Act.Q,Act.A,runs,finals,prun,pfinal,seenQ,seenA",
    );
    assert_eq!(bits(&csv, "Act.Q"), "0111000");
    // A is TRUE while the body runs (also in the final scan) and FALSE after.
    assert_eq!(bits(&csv, "Act.A"), "0111000");
    assert_eq!(bits(&csv, "seenA"), "0111111");
    assert_eq!(column(&csv, "runs"), ["0", "1", "2", "3", "4", "4", "4"]);
    assert_eq!(column(&csv, "finals"), ["0", "0", "0", "0", "1", "1", "1"]);
    assert_eq!(column(&csv, "prun"), ["0", "1", "2", "2", "2", "2", "2"]);
    assert_eq!(column(&csv, "pfinal"), ["0", "0", "1", "1", "1", "1", "1"]);
    assert_eq!(bits(&csv, "seenQ"), "0111000");
}

#[test]
fn il_transition_conditions() {
    // S0 -> S1 on `a AND b` written in IL; S1 -> S0 on NOT a (IL, LDN).
    let src = "PROGRAM p
VAR a, b : BOOL; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : END_STEP
TRANSITION go FROM S0 TO S1 :
    LD a
    AND b
END_TRANSITION
TRANSITION back FROM S1 TO S0 :
    LDN a
END_TRANSITION
END_PROGRAM";
    let stim = stimulus(&[("a", "0111100"), ("b", "0001000")]);
    let csv = trace_src(src, Some(&stim), 7, "S0.X,S1.X");
    // a AND b only in cycle 3 -> S1 from 3; a falls in 5 -> S0 from 5.
    assert_eq!(bits(&csv, "S1.X"), "0001100");
    assert_eq!(bits(&csv, "S0.X"), "1110011");
}

#[test]
fn two_charts_in_one_body() {
    // Two disjoint charts, each with its initial step, evolving together.
    let src = "PROGRAM p
VAR go : BOOL; END_VAR
INITIAL_STEP A0 : END_STEP
STEP A1 : END_STEP
TRANSITION FROM A0 TO A1 := go; END_TRANSITION
TRANSITION FROM A1 TO A0 := NOT go; END_TRANSITION
INITIAL_STEP B0 : END_STEP
STEP B1 : END_STEP
TRANSITION FROM B0 TO B1 := TRUE; END_TRANSITION
TRANSITION FROM B1 TO B0 := TRUE; END_TRANSITION
END_PROGRAM";
    let stim = stimulus(&[("go", "0011000")]);
    let csv = trace_src(src, Some(&stim), 6, "A1.X,B1.X");
    assert_eq!(bits(&csv, "A1.X"), "001100");
    assert_eq!(bits(&csv, "B1.X"), "101010");
}

#[test]
fn chart_in_a_function_block_with_two_instances() {
    // Each instance: Idle -go-> Busy (q := TRUE via N) -Busy.T >= 20 ms-> Idle.
    // a.go from cycle 1 held; b.go only in cycle 3.
    // a: On in 1, 2 (T 0, 10), T = 20 in 3 -> Off in 3; go still TRUE ->
    //    On in 4, 5, Off in 6, On in 7.
    // b: On in 3, 4, Off in 5.
    // The program also reads the step from outside (a.Busy.X).
    let src = "FUNCTION_BLOCK Pulser
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
INITIAL_STEP Idle : END_STEP
STEP Busy : q(N); END_STEP
TRANSITION FROM Idle TO Busy := go; END_TRANSITION
TRANSITION FROM Busy TO Idle := Busy.T >= T#20ms; END_TRANSITION
END_FUNCTION_BLOCK
PROGRAM p
VAR a, b : Pulser; ga, gb : BOOL; qa, qb, onA : BOOL; END_VAR
a(go := ga);
b(go := gb);
qa := a.q;
qb := b.q;
onA := a.Busy.X;
END_PROGRAM";
    let stim = stimulus(&[("ga", "01111111"), ("gb", "00010000")]);
    let csv = trace_src(src, Some(&stim), 8, "qa,qb,onA,a.Busy.X,b.Busy.X,b.Idle.X");
    assert_eq!(bits(&csv, "qa"), "01101101");
    assert_eq!(bits(&csv, "onA"), "01101101");
    assert_eq!(bits(&csv, "a.Busy.X"), "01101101");
    assert_eq!(bits(&csv, "qb"), "00011000");
    assert_eq!(bits(&csv, "b.Busy.X"), "00011000");
    assert_eq!(bits(&csv, "b.Idle.X"), "11100111");
}

// Diagnostics: (source, code, line of the diagnostic).
#[rstest]
#[case::unknown_step(
    "PROGRAM p\nINITIAL_STEP S0 : END_STEP\nTRANSITION FROM S0 TO S9 := TRUE; END_TRANSITION\nEND_PROGRAM",
    "E602",
    3
)]
#[case::duplicate_step(
    "PROGRAM p\nINITIAL_STEP S0 : END_STEP\nSTEP S0 : END_STEP\nEND_PROGRAM",
    "E603",
    3
)]
#[case::duplicate_action(
    "PROGRAM p\nVAR n : INT; END_VAR\nINITIAL_STEP S0 : A(N); END_STEP\nACTION A : n := 1; END_ACTION\nACTION A : n := 2; END_ACTION\nEND_PROGRAM",
    "E604",
    5
)]
#[case::action_named_like_variable(
    "PROGRAM p\nVAR A : INT; END_VAR\nINITIAL_STEP S0 : END_STEP\nACTION A : A := 1; END_ACTION\nEND_PROGRAM",
    "E604",
    4
)]
#[case::no_initial_step(
    "PROGRAM p\nSTEP S0 : END_STEP\nSTEP S1 : END_STEP\nTRANSITION FROM S0 TO S1 := TRUE; END_TRANSITION\nEND_PROGRAM",
    "E605",
    1
)]
#[case::chart_without_initial(
    "PROGRAM p\nINITIAL_STEP S0 : END_STEP\nSTEP S1 : END_STEP\nSTEP S2 : END_STEP\nTRANSITION FROM S1 TO S2 := TRUE; END_TRANSITION\nEND_PROGRAM",
    "E605",
    3
)]
#[case::unreachable_step(
    "PROGRAM p\nINITIAL_STEP S0 : END_STEP\nSTEP S1 : END_STEP\nTRANSITION FROM S1 TO S0 := TRUE; END_TRANSITION\nEND_PROGRAM",
    "W601",
    3
)]
#[case::condition_not_bool(
    "PROGRAM p\nVAR n : INT; END_VAR\nINITIAL_STEP S0 : END_STEP\nSTEP S1 : END_STEP\nTRANSITION FROM S0 TO S1 := n + 1; END_TRANSITION\nEND_PROGRAM",
    "E607",
    5
)]
#[case::il_condition_not_bool(
    "PROGRAM p\nVAR n : INT; END_VAR\nINITIAL_STEP S0 : END_STEP\nSTEP S1 : END_STEP\nTRANSITION FROM S0 TO S1 :\n LD n\nEND_TRANSITION\nEND_PROGRAM",
    "E607",
    5
)]
#[case::missing_duration(
    "PROGRAM p\nVAR x : BOOL; END_VAR\nINITIAL_STEP S0 :\n x(L);\nEND_STEP\nEND_PROGRAM",
    "E608",
    4
)]
#[case::missing_duration_sd(
    "PROGRAM p\nVAR x : BOOL; END_VAR\nINITIAL_STEP S0 :\n x(SD);\nEND_STEP\nEND_PROGRAM",
    "E608",
    4
)]
#[case::unknown_qualifier(
    "PROGRAM p\nVAR x, y : BOOL; END_VAR\nINITIAL_STEP S0 :\n x(y);\nEND_STEP\nEND_PROGRAM",
    "E609",
    4
)]
#[case::unknown_action(
    "PROGRAM p\nINITIAL_STEP S0 :\n nothing(N);\nEND_STEP\nEND_PROGRAM",
    "E610",
    3
)]
#[case::duration_not_time(
    "PROGRAM p\nVAR x : BOOL; END_VAR\nINITIAL_STEP S0 :\n x(D, 5);\nEND_STEP\nEND_PROGRAM",
    "E611",
    4
)]
#[case::bad_priority(
    "PROGRAM p\nVAR k : INT; END_VAR\nINITIAL_STEP S0 : END_STEP\nSTEP S1 : END_STEP\nTRANSITION (PRIORITY := k) FROM S0 TO S1 := TRUE; END_TRANSITION\nEND_PROGRAM",
    "E612",
    5
)]
#[case::action_not_bool(
    "PROGRAM p\nVAR n : INT; END_VAR\nINITIAL_STEP S0 :\n n(N);\nEND_STEP\nEND_PROGRAM",
    "E615",
    4
)]
#[case::step_written(
    "PROGRAM p\nINITIAL_STEP S0 : END_STEP\nS0.X := FALSE;\nEND_PROGRAM",
    "E",
    3
)]
#[case::chart_in_function(
    "FUNCTION f : INT\nINITIAL_STEP S0 : END_STEP\nEND_FUNCTION",
    "E601",
    1
)]
fn diagnostics_have_codes_and_lines(#[case] src: &str, #[case] code: &str, #[case] line: usize) {
    let (ok, out) = diagnostics(src);
    let wanted = format!(":{line}:");
    let found = out
        .lines()
        .zip(out.lines().skip(1))
        .any(|(a, b)| a.contains(&format!("[{code}")) && b.contains(&wanted));
    assert!(found, "expected {code} at line {line}, got:\n{out}");
    if code.starts_with('E') {
        assert!(!ok, "{out}");
    }
}
