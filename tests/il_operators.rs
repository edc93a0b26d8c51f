//! Instruction List, operator by operator: each case runs an IL body and
//! checks the variables it writes. Expected values are worked out by hand
//! from the IL rules (docs/semantics.md §7): one current result (CR), `N`
//! negates the operand, `C`/`CN` act when the CR is TRUE/FALSE, `OP(`
//! saves the CR and `)` applies the saved operation.

use crate::support::plc;

use plc::{compile, lit, program, run};
use rstest::rstest;

/// Runs `cycles` cycles of an IL program and checks `(variable, literal)`.
fn check(prelude: &str, decls: &str, body: &str, cycles: u64, expect: &[(&str, &str)]) {
    let mut plc = compile(&program(prelude, decls, body));
    run(&mut plc, cycles);
    for (name, value) in expect {
        assert_eq!(
            lit(&plc, name),
            *value,
            "{name} after {cycles} cycle(s)\n{body}"
        );
    }
}

#[rstest]
// LD / ST and their N forms.
#[case("a : INT := 5; b : INT;", "LD a\nST b", &[("b", "5")])]
#[case("x : BOOL := TRUE; y, z : BOOL;", "LDN x\nST y\nLD x\nSTN z", &[("y", "FALSE"), ("z", "FALSE")])]
// S and R act only when the CR is TRUE.
#[case("t : BOOL := TRUE; q : BOOL; r : BOOL := TRUE;", "LD t\nS q\nR r", &[("q", "TRUE"), ("r", "FALSE")])]
#[case("f : BOOL; q : BOOL; r : BOOL := TRUE;", "LD f\nS q\nR r", &[("q", "FALSE"), ("r", "TRUE")])]
// Boolean operators with and without N.
#[case("a : BOOL := TRUE; b : BOOL; y1, y2 : BOOL;", "LD a\nAND b\nST y1\nLD a\nANDN b\nST y2", &[("y1", "FALSE"), ("y2", "TRUE")])]
#[case("a, b : BOOL; y1, y2 : BOOL;", "LD a\nOR b\nST y1\nLD a\nORN b\nST y2", &[("y1", "FALSE"), ("y2", "TRUE")])]
#[case("a, b : BOOL := TRUE; y1, y2 : BOOL;", "LD a\nXOR b\nST y1\nLD a\nXORN b\nST y2", &[("y1", "FALSE"), ("y2", "TRUE")])]
#[case("a, b : BOOL := TRUE; y1, y2 : BOOL;", "LD a\n& b\nST y1\nLD a\n&N b\nST y2", &[("y1", "TRUE"), ("y2", "FALSE")])]
#[case("a : BOOL := TRUE; y : BOOL;", "LD a\nNOT\nST y", &[("y", "FALSE")])]
// Arithmetic: 17 + 3, 17 - 20, 17 * 2, 17 / 5 (truncated), 17 MOD 5.
#[case(
    "i : INT := 17; r1, r2, r3, r4, r5 : INT;",
    "LD i\nADD 3\nST r1\nLD i\nSUB 20\nST r2\nLD i\nMUL 2\nST r3\nLD i\nDIV 5\nST r4\nLD i\nMOD 5\nST r5",
    &[("r1", "20"), ("r2", "-3"), ("r3", "34"), ("r4", "3"), ("r5", "2")]
)]
#[case("x : REAL := 1.5; y : REAL;", "LD x\nMUL 2.0\nADD 0.25\nST y", &[("y", "3.25")])]
// Comparisons of 5 with 4, 5, 5, 5, 4, 6.
#[case(
    "i : INT := 5; g1, g2, g3, g4, g5, g6 : BOOL;",
    "LD i\nGT 4\nST g1\nLD i\nGE 5\nST g2\nLD i\nEQ 5\nST g3\nLD i\nNE 5\nST g4\nLD i\nLE 4\nST g5\nLD i\nLT 6\nST g6",
    &[("g1", "TRUE"), ("g2", "TRUE"), ("g3", "TRUE"), ("g4", "FALSE"), ("g5", "FALSE"), ("g6", "TRUE")]
)]
// Deferred operations: FALSE OR (TRUE AND TRUE), operand on the same line or the next.
#[case("a : BOOL; b, c : BOOL := TRUE; y : BOOL;", "LD a\nOR( b\nAND c\n)\nST y", &[("y", "TRUE")])]
#[case("a : BOOL; b, c : BOOL := TRUE; y : BOOL;", "LD a\nOR(\nLD b\nAND c\n)\nST y", &[("y", "TRUE")])]
// Nested: 2 * (3 + 1).
#[case("i : INT := 2; r : INT;", "LD i\nMUL( 3\nADD( 1\n)\n)\nST r", &[("r", "8")])]
// ANDN(: TRUE AND NOT (TRUE AND FALSE).
#[case("a, b : BOOL := TRUE; c, y : BOOL;", "LD a\nANDN( b\nAND c\n)\nST y", &[("y", "TRUE")])]
// A backward jump: count to 10.
#[case("n, k : INT;", "LD 0\nST n\nloop: LD n\nADD 1\nST n\nLT 10\nJMPC loop\nLD n\nST k", &[("n", "10"), ("k", "10")])]
// JMPCN jumps on FALSE; a label alone on its line.
#[case("x : BOOL; y : INT;", "LD x\nJMPCN skip\nLD 1\nST y\nskip:\nLD y\nADD 5\nST y", &[("y", "5")])]
#[case("y : INT;", "LD 1\nST y\nJMP over\nLD 100\nST y\nover: LD y\nADD 1\nST y", &[("y", "2")])]
// RET, RETC (CR TRUE: returns), RETCN (CR TRUE: goes on).
#[case("y : INT;", "LD 1\nST y\nRET\nLD 2\nST y", &[("y", "1")])]
#[case("c : BOOL := TRUE; y : INT;", "LD 1\nST y\nLD c\nRETC\nLD 2\nST y", &[("y", "1")])]
#[case("c : BOOL := TRUE; y : INT;", "LD 1\nST y\nLD c\nRETCN\nLD 2\nST y", &[("y", "2")])]
// Function calls with the CR as first argument: MAX(7, 3, 9); LIMIT(0, 7, 5).
#[case("a : INT := 7; r1, r2 : INT;", "LD a\nMAX 3, 9\nST r1\nLD 0\nLIMIT a, 5\nST r2", &[("r1", "9"), ("r2", "5")])]
fn operators(#[case] decls: &str, #[case] body: &str, #[case] expect: &[(&str, &str)]) {
    check("", decls, body, 1, expect);
}

#[rstest]
// CAL with formal inputs and `=>` outputs: PT = 0 gives Q in the same call.
#[case("t : TON; q : BOOL; e : TIME;", "CAL t(IN := TRUE, PT := T#0s, Q => q, ET => e)", 1, &[("q", "TRUE"), ("e", "T#0s")])]
// Moeller output list: PT = 20 ms at 10 ms cycles, Q in cycle 2.
#[case("t : TON; q : BOOL;", "CAL t(\n  IN := TRUE,\n  PT := T#20ms\n  |\n  q := Q,\n  := ET\n)", 2, &[("q", "FALSE")])]
#[case("t : TON; q : BOOL;", "CAL t(\n  IN := TRUE,\n  PT := T#20ms\n  |\n  q := Q,\n  := ET\n)", 3, &[("q", "TRUE")])]
// CALC with CR FALSE does not call; CALCN does.
#[case("c : BOOL; n : CTU; cv : INT;", "LD c\nCALC n(CU := TRUE)\nLD n.CV\nST cv", 1, &[("cv", "0")])]
#[case("c : BOOL; n : CTU; cv : INT;", "LD c\nCALCN n(CU := TRUE)\nLD n.CV\nST cv", 1, &[("cv", "1")])]
// FB input operators (Table 53): S1 on an SR; S then R1 on an RS.
#[case("ff : SR; t : BOOL := TRUE; q : BOOL;", "LD t\nS1 ff\nLD ff.Q1\nST q", 1, &[("q", "TRUE")])]
#[case("rs1 : RS; t : BOOL := TRUE; q1, q2 : BOOL;", "LD t\nS rs1\nLD rs1.Q1\nST q1\nLD t\nR1 rs1\nLD rs1.Q1\nST q2", 1, &[("q1", "TRUE"), ("q2", "FALSE")])]
// R on a counter resets it: CU counts 1, then R clears CV.
#[case("c : CTU; t : BOOL := TRUE; a, b : INT;", "LD t\nCU c\nLD c.CV\nST a\nLD t\nR c\nLD c.CV\nST b", 1, &[("a", "1"), ("b", "0")])]
#[case("trig : R_TRIG; t : BOOL := TRUE; p : BOOL;", "LD t\nCLK trig\nLD trig.Q\nST p", 1, &[("p", "TRUE")])]
// PV then CU: PV = 2, one rising edge, CV = 1, Q FALSE.
#[case("c : CTU; t : BOOL := TRUE; q : BOOL; cv : INT;", "LD 2\nPV c\nLD t\nCU c\nLD c.CV\nST cv\nLD c.Q\nST q", 1, &[("cv", "1"), ("q", "FALSE")])]
// LD on a down counter loads PV into CV.
#[case("d : CTD; t : BOOL := TRUE; cv : INT;", "LD 5\nPV d\nLD t\nLD d\nLD d.CV\nST cv", 1, &[("cv", "5")])]
// PT then IN on a timer.
#[case("tm : TON; t : BOOL := TRUE; q : BOOL;", "LD T#0s\nPT tm\nLD t\nIN tm\nLD tm.Q\nST q", 1, &[("q", "TRUE")])]
fn calls_and_fb_inputs(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] cycles: u64,
    #[case] expect: &[(&str, &str)],
) {
    check("", decls, body, cycles, expect);
}

#[test]
fn il_function_returns_through_its_name() {
    let prelude = "FUNCTION twice : INT\nVAR_INPUT x : INT; END_VAR\n    LD x\n    MUL 2\n    ST twice\nEND_FUNCTION";
    check(prelude, "r : INT;", "LD 21\ntwice\nST r", 1, &[("r", "42")]);
}

#[test]
fn il_function_block_keeps_state_and_mixes_with_st() {
    let prelude = "FUNCTION_BLOCK acc\nVAR_INPUT inc : INT; END_VAR\nVAR_OUTPUT total : INT; END_VAR\n    LD total\n    ADD inc\n    ST total\nEND_FUNCTION_BLOCK";
    // Called from IL: 3 per cycle.
    check(
        prelude,
        "a : acc; r : INT;",
        "CAL a(inc := 3)\nLD a.total\nST r",
        2,
        &[("r", "6")],
    );
    // Called from ST in the same project.
    check(
        prelude,
        "a : acc; r : INT;",
        "a(inc := 4); r := a.total;",
        3,
        &[("r", "12")],
    );
}

#[test]
fn the_current_result_is_typed_and_mismatches_are_reported_at_the_operator() {
    let src = program("", "n : INT; a, y : BOOL;", "LD n\nAND a\nST y");
    let err = match plcrun::Plc::compile_files(&[("il.st", &src)], &plcrun::Options::default()) {
        Ok(_) => panic!("INT AND BOOL must not compile"),
        Err(e) => e,
    };
    let d = err
        .diagnostics
        .iter()
        .find(|d| d.code == "E306")
        .unwrap_or_else(|| panic!("no E306 in\n{err}"));
    // program(): line 1 prelude, 2 PROGRAM, 3 VAR, 4 decls, 5 END_VAR, 6 LD, 7 AND.
    assert_eq!(err.sources.location(d.span), "il.st:7:1");
}

#[test]
fn formal_function_calls_name_every_input() {
    // LIMIT(MN, IN, MX) = 5 for IN = 7; the CR (here 1) is not an argument.
    // (A body is recognised as IL by its first instruction, an IL operator.)
    check(
        "",
        "a : INT := 7; r : INT;",
        "LD 1\nLIMIT(MN := 0, IN := a, MX := 5)\nST r",
        1,
        &[("r", "5")],
    );
    // Over several lines, with the CR loaded before (and replaced).
    check(
        "",
        "a : INT := -3; r : INT;",
        "LD 100\nLIMIT(\n  MN := 0,\n  IN := a,\n  MX := 5\n)\nST r",
        1,
        &[("r", "0")],
    );
}
