//! Typing beyond edition 3 for CODESYS/matiec code (issue #11): SEL's
//! selector as 0/1 (W342), results typed from context (`BCD_TO_INT`
//! W344, `TRUNC`), FUNCTIONs returning structures and arrays, arrays and
//! structures holding STRINGs copied and passed by value, `inst(...).Q`
//! (W345), and the conversions added to the tables (REAL_TO_BOOL, and the
//! CODESYS date/time counts, W346). Expected values are worked out by hand
//! beside each case.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run, run_once};
use rstest::rstest;

/// The warning codes of a compilation, in order.
fn warnings(src: &str) -> Vec<String> {
    compile(src)
        .warnings()
        .iter()
        .map(|d| d.code.to_string())
        .collect()
}

const VARS: &str = "b42 : BYTE := 16#42; w1234 : WORD := 16#1234; r37 : REAL := 3.7;
    rm37 : REAL := -3.7; lo : REAL := 0.0; hi : REAL := 10.0; x : REAL := 5.0;
    z : REAL := 0.0; nz : REAL := -0.0; small : LREAL := 1.0E-300; big : REAL := 70000.0;";

fn eval(ty: &str, expr: &str) -> (String, Vec<String>) {
    let src = program("", &format!("{VARS}\nv : {ty};"), &format!("v := {expr};"));
    (lit(&run_once(&src), "v"), warnings(&src))
}

#[rstest]
#[case("SEL(1, 10, 20)", "20", "W342")] // 1 is TRUE: IN1
#[case("SEL(0, 10, 20)", "10", "W342")] // 0 is FALSE: IN0
#[case("SEL(TRUE, 10, 20)", "20", "")]
fn sel_selector_literal_0_or_1(#[case] expr: &str, #[case] v: &str, #[case] w: &str) {
    let (got, warns) = eval("INT", expr);
    assert_eq!(got, v);
    assert_eq!(warns.join(","), w);
}

#[test]
fn sel_selector_other_integers_are_still_refused() {
    // 2 is no BOOL, and neither is an INT variable.
    for body in ["i := SEL(2, 10, 20);", "i := SEL(i, 10, 20);"] {
        let src = program("", "i : INT;", body);
        assert_eq!(error_codes(&[("t.st", &src)])[0].0, "E301", "{body}");
    }
}

#[rstest]
// 16#42 as BCD is 42, whatever integer type receives it.
#[case("USINT", "BCD_TO_INT(b42)", "42", "W344")]
#[case("UINT", "BCD_TO_INT(w1234)", "1234", "W344")]
#[case("INT", "BCD_TO_INT(w1234)", "1234", "")]
#[case("DINT", "BCD_TO_INT(w1234)", "1234", "W344")]
// TRUNC (ANY_REAL to ANY_INT) takes the type the context expects.
#[case("SINT", "TRUNC(r37)", "3", "")]
#[case("INT", "TRUNC(rm37)", "-3", "")]
// The argument of INT_TO_WORD is an INT: TRUNC gives one. 5/10*65535 = 32767.5.
#[case(
    "WORD",
    "INT_TO_WORD(TRUNC((LIMIT(lo, x, hi) - lo) * 65535.0 / (hi - lo)))",
    "16#7FFF",
    ""
)]
fn generic_results_typed_from_context(
    #[case] ty: &str,
    #[case] expr: &str,
    #[case] v: &str,
    #[case] w: &str,
) {
    let (got, warns) = eval(ty, expr);
    assert_eq!(got, v, "{expr}");
    assert_eq!(warns.join(","), w, "{expr}");
}

#[test]
fn typed_bcd_names_keep_their_type() {
    // WORD_BCD_TO_INT names its result: an INT does not go into a SINT.
    let src = program("", "w : WORD; s : SINT;", "s := WORD_BCD_TO_INT(w);");
    assert_eq!(error_codes(&[("t.st", &src)])[0].0, "E301");
}

#[test]
fn a_trunc_result_that_does_not_fit_the_context_faults() {
    // TRUNC into SINT of 70000.0: R004, as any conversion that does not fit.
    let src = program("", "big : REAL := 70000.0; s : SINT;", "s := TRUNC(big);");
    let mut plc = compile(&src);
    assert_eq!(plc.run_cycle().unwrap_err().code(), "R004");
}

#[rstest]
#[case("REAL_TO_BOOL(z)", "FALSE")]
#[case("REAL_TO_BOOL(nz)", "FALSE")] // -0.0 is zero
#[case("REAL_TO_BOOL(r37)", "TRUE")]
#[case("LREAL_TO_BOOL(small)", "TRUE")] // 1e-300 is not zero
#[case("LREAL_TO_BOOL(0.0)", "FALSE")]
fn real_to_bool(#[case] expr: &str, #[case] v: &str) {
    let (got, warns) = eval("BOOL", expr);
    assert_eq!(got, v, "{expr}");
    assert!(warns.is_empty());
}

#[rstest]
// 2024-01-31 is day 19753 after 1970-01-01: 19753 * 86400 = 1706659200 s.
#[case("UDINT", "DATE_TO_UDINT(D#2024-01-31)", "1706659200")]
#[case("DWORD", "DT_TO_DWORD(DT#2024-01-31-12:00:00)", "16#65BA3640")] // 1706702400 = 16#65BA3640
#[case("DINT", "TOD_TO_DINT(TOD#12:34:56.789)", "45296789")] // ms since midnight
#[case("TOD", "DWORD_TO_TOD(45296789)", "TOD#12:34:56.789")]
#[case("DATE", "UDINT_TO_DATE(1706702400)", "D#2024-01-31")] // noon rounds down to the day
#[case("DT", "UDINT_TO_DT(1706702400)", "DT#2024-01-31-12:00:00")]
#[case("TOD", "DINT_TO_TOD(90000000)", "TOD#01:00:00")] // 25 h wraps around midnight
#[case("TOD", "TIME_TO_TOD(T#25h30m)", "TOD#01:30:00")]
#[case("TIME", "TOD_TO_TIME(TOD#01:00:00)", "T#1h")]
#[case("BOOL", "TIME_TO_BOOL(T#1ms)", "TRUE")]
#[case("LINT", "LDT_TO_LINT(LDT#1970-01-01-00:00:01)", "1000000000")] // ns
fn codesys_date_and_time_conversions(#[case] ty: &str, #[case] expr: &str, #[case] v: &str) {
    let (got, warns) = eval(ty, expr);
    assert_eq!(got, v, "{expr}");
    assert_eq!(warns, ["W346"], "{expr}");
}

#[test]
fn date_conversions_without_a_meaning_are_refused() {
    for conv in [
        "TIME_TO_DATE(T#1s)",
        "DATE_TO_TOD(D#2024-01-01)",
        "DT_TO_TIME(DT#2024-01-01-00:00:00)",
    ] {
        let src = program("", "v : TIME;", &format!("v := {conv};"));
        let codes = error_codes(&[("t.st", &src)]);
        assert_eq!(codes[0].0, "E302", "{conv}");
    }
}

const SHAPES: &str = "
TYPE S : STRUCT a : INT; n : STRING[10]; r : REAL; m : STRING[3]; END_STRUCT; END_TYPE
FUNCTION MAKE : S
VAR_INPUT x : INT; END_VAR
MAKE.a := x; MAKE.r := 2.5; MAKE.n := INT_TO_STRING(x); MAKE.m := 'abc';
END_FUNCTION
FUNCTION TOTAL : INT
VAR_INPUT p, q : S; END_VAR
TOTAL := p.a * 10 + q.a + LEN(p.n) * 1000;
END_FUNCTION
FUNCTION_BLOCK KEEP
VAR_INPUT s : S; END_VAR VAR_OUTPUT n : STRING[10]; END_VAR
n := s.n;
END_FUNCTION_BLOCK
FUNCTION SPLIT : ARRAY[1..3] OF STRING[5]
VAR_INPUT t : STRING; END_VAR
SPLIT[1] := LEFT(t, 1); SPLIT[2] := MID(t, 1, 2); SPLIT[3] := RIGHT(t, 1);
END_FUNCTION
";

#[test]
fn functions_returning_structures_and_arrays() {
    let src = program(
        SHAPES,
        "s : S; k, m : INT; parts : ARRAY[1..3] OF STRING[5]; c : STRING;",
        "s := MAKE(3); k := MAKE(4).a + MAKE(5).a; m := TOTAL(MAKE(12), MAKE(2));
         parts := SPLIT('xyz'); c := SPLIT('pqr')[3];",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "s.a"), "3");
    assert_eq!(lit(&plc, "s.n"), "'3'");
    assert_eq!(lit(&plc, "s.m"), "'abc'");
    assert_eq!(lit(&plc, "s.r"), "2.5");
    assert_eq!(lit(&plc, "k"), "9"); // 4 + 5
    // Both arguments keep their own result: 12 * 10 + 2 + LEN('12') * 1000.
    assert_eq!(lit(&plc, "m"), "2122");
    assert_eq!(lit(&plc, "parts[1]"), "'x'");
    assert_eq!(lit(&plc, "parts[2]"), "'y'");
    assert_eq!(lit(&plc, "parts[3]"), "'z'");
    assert_eq!(lit(&plc, "c"), "'r'");
}

#[test]
fn a_function_result_is_not_writable() {
    // Not a variable a VAR_IN_OUT could be connected to.
    let prelude = format!(
        "{SHAPES}\nFUNCTION_BLOCK EDIT VAR_IN_OUT io : S; END_VAR io.a := 1; END_FUNCTION_BLOCK"
    );
    let src = program(&prelude, "ed : EDIT;", "ed(io := MAKE(1));");
    assert_eq!(error_codes(&[("t.st", &src)])[0].0, "E412");
}

#[test]
fn structures_and_arrays_holding_strings_are_copied_by_value() {
    let src = program(
        SHAPES,
        "s, t : S; a, b : ARRAY[1..6] OF STRING; c, e : ARRAY[0..6] OF S;
         g : ARRAY[1..2, 1..3] OF STRING[4]; h : ARRAY[1..2, 1..3] OF STRING[4];
         k : INT; kp : KEEP; kn : STRING[10];",
        "s.a := 7; s.n := 'hello'; s.r := 1.5; s.m := 'xyz';
         t := s; t.n := 'other';
         b[1] := 'one'; b[6] := 'six'; a := b; b[1] := 'uno';
         c[6] := s; c[0].m := 'q'; e := c; c[6].n := 'changed';
         g[2, 3] := 'corn'; h := g; g[2, 3] := 'x';
         k := TOTAL(s, t);
         kp(s := s); s.n := 'later'; kn := kp.n;",
    );
    let plc = run_once(&src);
    // The copy has its own strings: changing one side leaves the other.
    assert_eq!(lit(&plc, "t.n"), "'other'");
    assert_eq!(lit(&plc, "t.m"), "'xyz'");
    assert_eq!(lit(&plc, "t.a"), "7");
    assert_eq!(lit(&plc, "t.r"), "1.5");
    assert_eq!(lit(&plc, "a[1]"), "'one'");
    assert_eq!(lit(&plc, "a[6]"), "'six'");
    assert_eq!(lit(&plc, "b[1]"), "'uno'");
    assert_eq!(lit(&plc, "e[6].n"), "'hello'");
    assert_eq!(lit(&plc, "e[0].m"), "'q'");
    assert_eq!(lit(&plc, "c[6].n"), "'changed'");
    assert_eq!(lit(&plc, "h[2, 3]"), "'corn'");
    assert_eq!(lit(&plc, "g[2, 3]"), "'x'");
    // By value into a function: 7 * 10 + 7 + LEN('hello') * 1000.
    assert_eq!(lit(&plc, "k"), "5077");
    // By value into an FB input: the FB kept 'hello'.
    assert_eq!(lit(&plc, "kn"), "'hello'");
}

#[test]
fn calling_an_instance_and_reading_its_output_in_one_expression() {
    let src = program(
        "FUNCTION_BLOCK TWICE
VAR_INPUT i : INT; END_VAR VAR_OUTPUT Q : INT; END_VAR
Q := i * 2;
END_FUNCTION_BLOCK",
        "t : TON; q : BOOL; f : TWICE; z : INT;",
        "q := t(IN := TRUE, PT := T#20ms).Q; z := f(i := 21).Q + 1;",
    );
    assert_eq!(warnings(&src), ["W345", "W345"]);
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "z"), "43"); // 21 * 2 + 1
    assert_eq!(lit(&plc, "q"), "FALSE"); // cycle 0: t = 0 ms
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "q"), "TRUE"); // cycle 2: 20 ms elapsed
    // The instance ran: its elapsed time is visible after the expression.
    assert_eq!(lit(&plc, "t.ET"), "T#20ms");
}

#[test]
fn a_function_block_called_in_an_expression_without_member_is_still_refused() {
    let src = program("", "t : TON; q : BOOL;", "q := t(IN := TRUE, PT := T#1s);");
    assert_eq!(error_codes(&[("t.st", &src)])[0].0, "E406");
}
