//! Standard-name coverage (issue #11): the typed names matiec declares
//! (`ADD_INT`, `GT_DINT`, ...; W340), the edition-1 names `MULTIME` and
//! `DIVTIME` (W341), a user POU named like a standard function (it wins,
//! W343), and a variable named like a standard function (a call is not a
//! variable). Expected values are worked out by hand beside each case.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run_once};
use rstest::rstest;

const VARS: &str = "i7 : INT := 7; i3 : INT := 3; d10 : DINT := 10; r25 : REAL := 2.5;
    w : WORD := 16#00F0; t1s : TIME := T#1s; bt : BOOL := TRUE; imax : INT := 32767;";

/// The warning codes a compilation produced, in order.
fn warnings(src: &str) -> Vec<String> {
    compile(src)
        .warnings()
        .iter()
        .map(|d| d.code.to_string())
        .collect()
}

fn eval(ty: &str, expr: &str) -> (String, Vec<String>) {
    let src = program("", &format!("{VARS}\nv : {ty};"), &format!("v := {expr};"));
    (lit(&run_once(&src), "v"), warnings(&src))
}

#[rstest]
#[case("INT", "ADD_INT(i7, 2, 3)", "12")] // 7 + 2 + 3
#[case("INT", "SUB_INT(i3, i7)", "-4")] // 3 - 7
#[case("DINT", "MUL_DINT(d10, 3)", "30")]
#[case("INT", "DIV_INT(i7, 2)", "3")] // truncated toward zero
#[case("INT", "MOD_INT(i7, 4)", "3")]
#[case("BOOL", "GT_DINT(d10, 9)", "TRUE")]
#[case("BOOL", "LE_INT(i7, i3)", "FALSE")] // 7 <= 3
#[case("BOOL", "EQ_REAL(r25, 2.5)", "TRUE")]
#[case("INT", "SEL_INT(bt, i3, i7)", "7")] // G TRUE picks IN1
#[case("REAL", "MOVE_REAL(r25)", "2.5")]
#[case("INT", "MUX_INT(1, i3, i7, 9)", "7")] // K = 1 picks the second input
#[case("INT", "LIMIT_INT(0, i7, 5)", "5")]
#[case("INT", "MAX_INT(i3, i7)", "7")]
#[case("INT", "MIN_INT(i3, i7)", "3")]
#[case("INT", "ABS_INT(-5)", "5")]
#[case("WORD", "SHL_WORD(w, 4)", "16#F00")] // 16#00F0 << 4
#[case("WORD", "AND_WORD(w, 16#0030)", "16#30")]
#[case("BOOL", "NOT_BOOL(bt)", "FALSE")]
#[case("REAL", "SQRT_REAL(16.0)", "4.0")]
#[case("LREAL", "EXPT_LREAL(2.0, 3)", "8.0")]
#[case("TIME", "ADD_TIME(t1s, T#500ms)", "T#1s500ms")]
fn typed_names_are_the_generic_functions(
    #[case] ty: &str,
    #[case] expr: &str,
    #[case] expected: &str,
) {
    let (got, warns) = eval(ty, expr);
    assert_eq!(got, expected, "{expr}");
    // ADD_TIME is a standard name of its own: no warning.
    let want: &[&str] = if expr.starts_with("ADD_TIME") {
        &[]
    } else {
        &["W340"]
    };
    assert_eq!(warns, want, "{expr}");
}

#[test]
fn a_typed_name_fixes_its_inputs_to_its_type() {
    // ADD_INT of a DINT: the input is not an INT.
    let src = program("", VARS, "i7 := ADD_INT(d10, 1);");
    assert_eq!(error_codes(&[("t.st", &src)])[0].0, "E301");
    // The result is INT: 32767 + 1 wraps at 16 bits even into a DINT.
    let (got, _) = eval("DINT", "ADD_INT(imax, 1)");
    assert_eq!(got, "-32768");
    // Without the type in the name the sum is a DINT.
    let (got, _) = eval("DINT", "ADD(imax, DINT#1)");
    assert_eq!(got, "32768");
}

#[rstest]
#[case("MULTIME(t1s, 2.5)", "T#2s500ms")]
#[case("MULTIME(t1s, 3)", "T#3s")]
#[case("DIVTIME(t1s, 4)", "T#250ms")]
#[case("DIVTIME(t1s, 0.5)", "T#2s")]
fn edition_1_time_names(#[case] expr: &str, #[case] expected: &str) {
    let (got, warns) = eval("TIME", expr);
    assert_eq!(got, expected, "{expr}");
    assert_eq!(warns, ["W341"], "{expr}");
}

#[test]
fn a_user_function_named_like_a_standard_function_wins() {
    // OSCAT's TIME_TO_TOD (here one of ours that adds an hour), and a
    // MULTIME of our own that ignores the factor.
    let prelude = "
FUNCTION TIME_TO_TOD : TOD
VAR_INPUT IN : TIME; END_VAR
TIME_TO_TOD := TOD#01:00:00 + IN;
END_FUNCTION
FUNCTION MULTIME : TIME
VAR_INPUT t : TIME; M : REAL; END_VAR
MULTIME := t;
END_FUNCTION";
    let src = program(
        prelude,
        "t : TIME := T#2s; d : TOD; m : TIME;",
        "d := TIME_TO_TOD(t); m := MULTIME(t, 3.0);",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "d"), "TOD#01:00:02");
    assert_eq!(lit(&plc, "m"), "T#2s");
    let w: Vec<_> = plc.warnings().iter().collect();
    assert_eq!(w.len(), 2, "{w:?}");
    for (d, name) in w.iter().zip(["TIME_TO_TOD", "MULTIME"]) {
        assert_eq!(d.code, "W343");
        assert!(
            d.message.contains(&format!("FUNCTION `{name}`")),
            "{}",
            d.message
        );
        assert!(d.message.contains("standard function"), "{}", d.message);
    }
}

#[test]
fn a_user_pou_named_like_a_standard_function_block_is_still_refused() {
    let src = "FUNCTION_BLOCK TON VAR_INPUT IN : BOOL; END_VAR END_FUNCTION_BLOCK
PROGRAM P END_PROGRAM";
    assert_eq!(error_codes(&[("t.st", src)])[0].0, "E202");
}

#[test]
fn a_variable_named_like_a_standard_function_does_not_hide_it() {
    // #13: `sel` the variable and SEL the function.
    let src = program(
        "",
        "sel : INT; mux : BOOL; limit : REAL;",
        "sel := SEL(TRUE, 10, 20); mux := SEL(sel = 20, FALSE, TRUE); limit := LIMIT(0.0, 7.5, 5.0);",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "sel"), "20");
    assert_eq!(lit(&plc, "mux"), "TRUE");
    assert_eq!(lit(&plc, "limit"), "5.0");
    assert!(plc.warnings().iter().next().is_none());
}
