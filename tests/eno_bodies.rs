//! `EN` and `ENO` inside FUNCTION and FUNCTION_BLOCK bodies (edition 3):
//! a POU whose body mentions ENO has a BOOL output ENO, TRUE at the start of
//! every call, which its body may reset and its caller reads with
//! `ENO => x`; a call skipped by `EN := FALSE` gives FALSE. POUs that do not
//! mention ENO are unchanged.

use crate::support::access_diags;
use crate::support::plc;

use access_diags::error_codes;
use plc::{compile, lit, run, run_once};

/// ST function: ENO FALSE on a negative input (and the result 0).
const SQRT_ST: &str = "FUNCTION CheckedSqrt : REAL\nVAR_INPUT x : REAL; END_VAR\n\
IF x < 0.0 THEN ENO := FALSE; CheckedSqrt := 0.0; ELSE CheckedSqrt := SQRT(x); END_IF;\n\
END_FUNCTION\n";

/// IL function: ENO := (a <> 0), result 100 / a when a is not zero.
const DIV_IL: &str = "FUNCTION SafeDiv : INT\nVAR_INPUT a : INT; END_VAR\n\
LD a\nNE 0\nST ENO\nJMPCN zero\nLD 100\nDIV a\nST SafeDiv\nRET\n\
zero: LD 0\nST SafeDiv\nEND_FUNCTION\n";

/// IL FB: `S ENO` / `R ENO` and `LD ENO`; `seen` copies ENO as the body saw it.
const LIMITER_IL: &str = "FUNCTION_BLOCK Limiter\nVAR_INPUT v : INT; END_VAR\n\
VAR_OUTPUT q : INT; seen : BOOL; was_en : BOOL; END_VAR\n\
LD EN\nST was_en\nLD v\nGT 10\nR ENO\nLD ENO\nST seen\nLD v\nST q\nEND_FUNCTION_BLOCK\n";

#[test]
fn an_st_function_resets_eno() {
    let src = format!(
        "{SQRT_ST}PROGRAM P\nVAR ok1 : BOOL; ok2 : BOOL := TRUE; r1 : REAL; r2 : REAL; END_VAR\n\
         r1 := CheckedSqrt(x := 16.0, ENO => ok1);\nr2 := CheckedSqrt(x := -1.0, ENO => ok2);\nEND_PROGRAM\n"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "ok1"), "TRUE");
    assert_eq!(lit(&plc, "r1"), "4.0");
    assert_eq!(lit(&plc, "ok2"), "FALSE");
    // ENO is TRUE again at the start of the next call.
    let src = format!(
        "{SQRT_ST}PROGRAM P\nVAR ok : BOOL; r : REAL; END_VAR\n\
         r := CheckedSqrt(x := -1.0);\nr := CheckedSqrt(x := 9.0, ENO => ok);\nEND_PROGRAM\n"
    );
    assert_eq!(lit(&run_once(&src), "ok"), "TRUE");
}

#[test]
fn an_il_function_stores_eno() {
    let src = format!(
        "{DIV_IL}PROGRAM P\nVAR ok1 : BOOL; ok2 : BOOL := TRUE; q1 : INT; q2 : INT := 7; END_VAR\n\
         q1 := SafeDiv(a := 4, ENO => ok1);\nq2 := SafeDiv(a := 0, ENO => ok2);\nEND_PROGRAM\n"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "ok1"), "TRUE");
    assert_eq!(lit(&plc, "q1"), "25");
    assert_eq!(lit(&plc, "ok2"), "FALSE");
    assert_eq!(lit(&plc, "q2"), "0");
}

#[test]
fn an_il_block_sets_resets_and_reads_eno() {
    let src = format!(
        "{LIMITER_IL}PROGRAM P\nVAR f : Limiter; ok_small : BOOL; ok_big : BOOL := TRUE; outside : BOOL; END_VAR\n\
         f(v := 3, ENO => ok_small);\nf(v := 50, ENO => ok_big);\noutside := f.ENO;\nEND_PROGRAM\n"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "ok_small"), "TRUE");
    assert_eq!(lit(&plc, "ok_big"), "FALSE");
    assert_eq!(lit(&plc, "outside"), "FALSE");
    assert_eq!(lit(&plc, "f.seen"), "FALSE");
    assert_eq!(lit(&plc, "f.was_en"), "TRUE");
    assert_eq!(lit(&plc, "f.q"), "50");
}

#[test]
fn an_st_block_keeps_eno_per_call_not_per_instance() {
    // The FB resets ENO on odd counts; ENO is TRUE again on the next call.
    let src = "FUNCTION_BLOCK Counter\nVAR_OUTPUT n : INT; END_VAR\n\
         n := n + 1;\nIF n MOD 2 = 1 THEN ENO := FALSE; END_IF;\nEND_FUNCTION_BLOCK\n\
         PROGRAM P\nVAR c : Counter; ok : BOOL; trues : INT; END_VAR\n\
         c(ENO => ok);\nIF ok THEN trues := trues + 1; END_IF;\nEND_PROGRAM\n";
    let mut plc = compile(src);
    run(&mut plc, 5);
    assert_eq!(lit(&plc, "c.n"), "5");
    assert_eq!(lit(&plc, "trues"), "2");
    assert_eq!(lit(&plc, "c.ENO"), "FALSE");
}

#[test]
fn a_skipped_call_gives_false_and_runs_no_body() {
    let src = format!(
        "{LIMITER_IL}PROGRAM P\nVAR f : Limiter; ok : BOOL := TRUE; before : BOOL; END_VAR\n\
         f(v := 1);\nbefore := f.ENO;\nf(EN := FALSE, v := 2, ENO => ok);\nEND_PROGRAM\n"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "before"), "TRUE");
    assert_eq!(lit(&plc, "ok"), "FALSE");
    // The instance's own ENO is FALSE after a skipped call; the body did not run.
    assert_eq!(lit(&plc, "f.ENO"), "FALSE");
    assert_eq!(lit(&plc, "f.q"), "1");
}

#[test]
fn eno_of_one_call_feeds_en_of_the_next() {
    // -1 fails the first step, so the second and third never run (what a
    // skipped function's result is, the standard leaves open).
    let chain = |x: &str| {
        format!(
            "{SQRT_ST}PROGRAM P\nVAR a : REAL; b : REAL; c : REAL; e1 : BOOL; e2 : BOOL; e3 : BOOL; END_VAR\n\
             a := CheckedSqrt(x := {x}, ENO => e1);\n\
             b := CheckedSqrt(EN := e1, x := a, ENO => e2);\n\
             c := CheckedSqrt(EN := e2, x := b, ENO => e3);\nEND_PROGRAM\n"
        )
    };
    let plc = run_once(&chain("256.0"));
    assert_eq!(lit(&plc, "c"), "2.0");
    assert_eq!(lit(&plc, "e3"), "TRUE");
    let plc = run_once(&chain("-1.0"));
    assert_eq!(lit(&plc, "e1"), "FALSE");
    assert_eq!(lit(&plc, "e2"), "FALSE");
    assert_eq!(lit(&plc, "e3"), "FALSE");
}

#[test]
fn a_pou_not_using_eno_is_unchanged() {
    // No ENO member, and `ENO =>` reads TRUE as before.
    let fb = "FUNCTION_BLOCK Plain\nVAR_OUTPUT q : INT; END_VAR\nq := q + 1;\nEND_FUNCTION_BLOCK\n";
    let src =
        format!("{fb}PROGRAM P\nVAR p : Plain; ok : BOOL; END_VAR\np(ENO => ok);\nEND_PROGRAM\n");
    assert_eq!(lit(&run_once(&src), "ok"), "TRUE");
    let src =
        format!("{fb}PROGRAM P\nVAR p : Plain; ok : BOOL; END_VAR\nok := p.ENO;\nEND_PROGRAM\n");
    assert!(!error_codes(&src).is_empty(), "Plain has no ENO");
    // A PROGRAM has no ENO.
    let src = "PROGRAM P\nVAR x : BOOL; END_VAR\nENO := x;\nEND_PROGRAM\n";
    assert_eq!(error_codes(src), vec!["E201".to_string()]);
}

#[test]
fn an_own_bool_output_eno_is_that_slot() {
    let src = "FUNCTION_BLOCK Own\nVAR_INPUT v : INT; END_VAR\nVAR_OUTPUT ENO : BOOL; END_VAR\n\
         IF v < 0 THEN ENO := FALSE; END_IF;\nEND_FUNCTION_BLOCK\n\
         PROGRAM P\nVAR o : Own; a : BOOL; b : BOOL := TRUE; END_VAR\n\
         o(v := 1, ENO => a);\no(v := -1, ENO => b);\nEND_PROGRAM\n";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "a"), "TRUE");
    assert_eq!(lit(&plc, "b"), "FALSE");
}

#[test]
fn eno_declared_otherwise_is_an_error() {
    for decl in [
        "VAR ENO : BOOL; END_VAR",
        "VAR_OUTPUT ENO : INT; END_VAR",
        "VAR_INPUT ENO : BOOL; END_VAR",
    ] {
        let src = format!(
            "FUNCTION_BLOCK Bad\n{decl}\nENO := ENO;\nEND_FUNCTION_BLOCK\n\
             PROGRAM P\nVAR b : Bad; END_VAR\nb();\nEND_PROGRAM\n"
        );
        assert!(
            error_codes(&src).contains(&"E428".to_string()),
            "{decl}: {:?}",
            error_codes(&src)
        );
    }
}

#[test]
fn en_reads_true_in_a_function_body() {
    let src = "FUNCTION Twice : INT\nVAR_INPUT a : INT; END_VAR\n\
         IF EN THEN Twice := 2 * a; END_IF;\nEND_FUNCTION\n\
         PROGRAM P\nVAR r : INT; END_VAR\nr := Twice(a := 21);\nEND_PROGRAM\n";
    assert_eq!(lit(&run_once(src), "r"), "42");
}

#[test]
fn instances_in_an_array_report_their_eno() {
    // Element i fails when v > 10; element 2 is skipped.
    let src = format!(
        "{LIMITER_IL}PROGRAM P\nVAR fs : ARRAY[1..3] OF Limiter; ok : ARRAY[1..3] OF BOOL; i : INT; END_VAR\n\
         FOR i := 1 TO 3 DO fs[i](EN := i <> 2, v := i * 10, ENO => ok[i]); END_FOR;\nEND_PROGRAM\n"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "ok[1]"), "TRUE");
    assert_eq!(lit(&plc, "ok[2]"), "FALSE");
    assert_eq!(lit(&plc, "ok[3]"), "FALSE");
    assert_eq!(lit(&plc, "fs[3].q"), "30");
    assert_eq!(lit(&plc, "fs[2].q"), "0");
}

#[test]
fn il_set_makes_eno_true_again() {
    let src = "FUNCTION_BLOCK Retry\nVAR_INPUT fail : BOOL; again : BOOL; END_VAR\n\
         LD fail\nR ENO\nLD again\nS ENO\nEND_FUNCTION_BLOCK\n\
         PROGRAM P\nVAR r : Retry; a : BOOL := TRUE; b : BOOL; END_VAR\n\
         r(fail := TRUE, ENO => a);\nr(fail := TRUE, again := TRUE, ENO => b);\nEND_PROGRAM\n";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "a"), "FALSE");
    assert_eq!(lit(&plc, "b"), "TRUE");
}
