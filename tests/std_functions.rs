//! Every standard function of `src/sema/stdfuncs.rs` at least once, with
//! results computed by hand from IEC 61131-3 and docs/semantics.md.
//!
//! Each case assigns `expr` to `v : ty` in a one-cycle program and compares
//! `v` printed as an IEC literal. Inputs that come from variables are
//! declared in `VARS` so that the functions also run (not only fold).

use crate::support::plc;

use plc::{compile, lit, program, run_once};
use rstest::rstest;

const VARS: &str = "i7 : INT := 7; im7 : INT := -7; i3 : INT := 3; d10 : DINT := 10;
    r25 : REAL := 2.5; rm25 : REAL := -2.5; l2 : LREAL := 2.0; bt : BOOL := TRUE; bf : BOOL;
    b81 : BYTE := 16#81; w : WORD := 16#8001; s : STRING := 'ABCDE';
    t1s : TIME := T#1s; k : INT := 2;";

fn eval(ty: &str, expr: &str) -> String {
    let decls = format!("{VARS}\nv : {ty};");
    lit(
        &run_once(&program("", &decls, &format!("v := {expr};"))),
        "v",
    )
}

#[rstest]
#[case("INT", "ADD(1, 2)", "3")]
#[case("INT", "ADD(i7, 2, 3, 4)", "16")]
#[case("LREAL", "ADD(l2, 0.5)", "2.5")]
#[case("INT", "MUL(i3, 4, 5)", "60")]
#[case("INT", "SUB(i7, 10)", "-3")]
#[case("INT", "DIV(im7, 2)", "-3")]
#[case("REAL", "DIV(r25, 2.0)", "1.25")]
#[case("LREAL", "EXPT(l2, 3)", "8.0")]
#[case("LREAL", "EXPT(l2, -1)", "0.5")]
#[case("LREAL", "EXPT(l2, 0.5) * EXPT(l2, 0.5)", "2.0000000000000004")]
#[case("INT", "MOVE(i7)", "7")]
#[case("TIME", "MOVE(t1s)", "T#1s")]
fn arithmetic(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
#[case("INT", "ABS(im7)", "7")]
#[case("INT", "ABS(i7)", "7")]
#[case("REAL", "ABS(rm25)", "2.5")]
#[case("LREAL", "SQRT(16.0)", "4.0")]
#[case("REAL", "SQRT(r25 * r25)", "2.5")]
#[case("LREAL", "LN(1.0)", "0.0")]
#[case("LREAL", "LOG(100.0)", "2.0")]
#[case("LREAL", "EXP(0.0)", "1.0")]
#[case("LREAL", "SIN(0.0)", "0.0")]
#[case("LREAL", "COS(0.0)", "1.0")]
#[case("LREAL", "TAN(0.0)", "0.0")]
// pi / 2 as f64 and as f32
#[case("LREAL", "ASIN(1.0)", "1.5707963267948966")]
#[case("REAL", "ASIN(REAL#1.0)", "1.5707964")]
#[case("LREAL", "ACOS(1.0)", "0.0")]
// pi / 4
#[case("LREAL", "ATAN(1.0)", "0.7853981633974483")]
#[case("DINT", "TRUNC(2.7)", "2")]
#[case("DINT", "TRUNC(-2.7)", "-2")]
#[case("INT", "REAL_TRUNC_INT(rm25)", "-2")]
#[case("INT", "TRUNC_INT(r25)", "2")]
fn numeric_functions(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
#[case("INT", "SEL(bf, i3, i7)", "3")]
#[case("INT", "SEL(bt, i3, i7)", "7")]
#[case("STRING", "SEL(bt, 'no', 'yes')", "'yes'")]
#[case("INT", "MAX(i3, i7, im7)", "7")]
#[case("INT", "MIN(i3, i7, im7)", "-7")]
#[case("REAL", "MAX(r25, rm25)", "2.5")]
#[case("TIME", "MIN(t1s, T#200ms)", "T#200ms")]
#[case("INT", "LIMIT(0, i7, 5)", "5")]
#[case("INT", "LIMIT(0, im7, 5)", "0")]
#[case("INT", "LIMIT(0, i3, 5)", "3")]
// K counts from 0: K = 2 selects the third input
#[case("INT", "MUX(k, i3, i7, im7)", "-7")]
#[case("INT", "MUX(0, i3, i7, im7)", "3")]
fn selection(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
#[case("MAX(1, 2)", "2")]
#[case("MIN(1, 2)", "1")]
#[case("SEL(TRUE, 1, 2)", "2")]
#[case("LIMIT(0, 50, 10)", "10")]
#[case("MUX(1, 10, 20)", "20")]
fn selection_of_untyped_literals_takes_the_target_type(#[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval("INT", expr), expected);
}

#[test]
fn mux_with_k_out_of_range_is_a_runtime_fault() {
    let mut plc = compile(&program(
        "",
        "k : INT := 3; v : INT;",
        "v := MUX(k, INT#1, INT#2, INT#3);",
    ));
    let f = plc.run_cycle().expect_err("K = 3 selects no input");
    assert_eq!(f.cycle, 0);
}

#[rstest]
// extensible comparisons: a chain, IN1 > IN2 AND IN2 > IN3 ...
#[case("GT(i7, i3, 1)", "TRUE")]
#[case("GT(i7, 1, i3)", "FALSE")]
#[case("GE(i3, 3, 2)", "TRUE")]
#[case("GE(i3, 4)", "FALSE")]
#[case("EQ(i3, 3, 3)", "TRUE")]
#[case("EQ(i3, 3, 4)", "FALSE")]
#[case("LE(1, i3, 3)", "TRUE")]
#[case("LT(1, i3, 3)", "FALSE")]
#[case("LT(im7, i3, i7)", "TRUE")]
#[case("NE(i3, i7)", "TRUE")]
#[case("NE(i3, 3)", "FALSE")]
#[case("GT(r25, rm25)", "TRUE")]
#[case("LT(s, 'ABCDF')", "TRUE")]
#[case("EQ(t1s, T#1000ms)", "TRUE")]
fn comparison(#[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval("BOOL", expr), expected);
}

#[rstest]
// 1000_0001 << 1 = 0000_0010 (the top bit falls off)
#[case("BYTE", "SHL(b81, 1)", "16#2")]
#[case("BYTE", "SHR(b81, 1)", "16#40")]
#[case("BYTE", "ROL(b81, 1)", "16#3")]
#[case("BYTE", "ROR(b81, 1)", "16#C0")]
#[case("BYTE", "SHL(b81, 8)", "16#0")]
// rotation by 9 on 8 bits = rotation by 1
#[case("BYTE", "ROL(b81, 9)", "16#3")]
// 1000_0000_0000_0001 rotated left by 4 = 0000_0000_0001_1000
#[case("WORD", "ROL(w, 4)", "16#18")]
#[case("WORD", "ROR(w, 4)", "16#1800")]
#[case("WORD", "SHR(w, 15)", "16#1")]
#[case("DWORD", "SHL(DWORD#1, 31)", "16#80000000")]
#[case("BOOL", "NOT(bf)", "TRUE")]
#[case("WORD", "NOT(w)", "16#7FFE")]
fn bit_string_functions(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
// REAL/LREAL -> integer: nearest, halves away from zero
#[case("INT", "REAL_TO_INT(r25)", "3")]
#[case("INT", "REAL_TO_INT(rm25)", "-3")]
#[case("INT", "REAL_TO_INT(REAL#2.4)", "2")]
#[case("INT", "REAL_TO_INT(REAL#-2.6)", "-3")]
#[case("INT", "REAL_TO_INT(REAL#3.5)", "4")]
#[case("DINT", "LREAL_TO_DINT(0.5)", "1")]
#[case("DINT", "LREAL_TO_DINT(-0.5)", "-1")]
#[case("SINT", "LREAL_TO_SINT(-128.4)", "-128")]
#[case("INT", "TO_INT(r25)", "3")]
#[case("REAL", "INT_TO_REAL(im7)", "-7.0")]
#[case("LREAL", "DINT_TO_LREAL(d10)", "10.0")]
#[case("LREAL", "REAL_TO_LREAL(r25)", "2.5")]
#[case("REAL", "LREAL_TO_REAL(l2)", "2.0")]
#[case("SINT", "INT_TO_SINT(im7)", "-7")]
#[case("USINT", "INT_TO_USINT(i7)", "7")]
#[case("LINT", "INT_TO_LINT(im7)", "-7")]
#[case("UDINT", "DINT_TO_UDINT(d10)", "10")]
#[case("INT", "BOOL_TO_INT(bt)", "1")]
#[case("BOOL", "INT_TO_BOOL(0)", "FALSE")]
#[case("BOOL", "INT_TO_BOOL(1)", "TRUE")]
#[case("USINT", "BYTE_TO_USINT(b81)", "129")]
#[case("WORD", "UINT_TO_WORD(UINT#65535)", "16#FFFF")]
#[case("DWORD", "WORD_TO_DWORD(w)", "16#8001")]
#[case("BYTE", "WORD_TO_BYTE(WORD#16#00FF)", "16#FF")]
#[case("STRING", "INT_TO_STRING(im7)", "'-7'")]
#[case("INT", "STRING_TO_INT('123')", "123")]
fn conversions(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
#[case("x : REAL := 40000.0; v : INT;", "v := REAL_TO_INT(x);")]
#[case("x : REAL := -32768.6; v : INT;", "v := REAL_TO_INT(x);")]
#[case("x : LREAL := 1.0E30; v : DINT;", "v := LREAL_TO_DINT(x);")]
#[case("x : REAL := -0.6; v : UINT;", "v := REAL_TO_UINT(x);")]
// NaN: 0.0 / 0.0
#[case("x : REAL; v : INT;", "v := REAL_TO_INT(x / x);")]
fn real_to_integer_out_of_range_is_a_runtime_fault(#[case] decls: &str, #[case] body: &str) {
    let mut plc = compile(&program("", decls, body));
    let f = plc.run_cycle().expect_err("conversion must fault");
    assert_eq!(f.cycle, 0);
    assert!(f.location.starts_with("test.st:6:"), "{}", f.location);
}

#[rstest]
#[case("x : DINT := 70000; v : INT;", "v := DINT_TO_INT(x);")]
#[case("x : INT := -1; v : UINT;", "v := INT_TO_UINT(x);")]
#[case("x : INT := 200; v : SINT;", "v := INT_TO_SINT(x);")]
fn integer_narrowing_out_of_range_is_a_runtime_fault(#[case] decls: &str, #[case] body: &str) {
    let mut plc = compile(&program("", decls, body));
    assert!(plc.run_cycle().is_err(), "conversion must fault");
}

#[rstest]
#[case("INT", "WORD_BCD_TO_INT(WORD#16#1234)", "1234")]
#[case("INT", "BCD_TO_INT(WORD#16#0042)", "42")]
#[case("WORD", "INT_TO_BCD_WORD(1234)", "16#1234")]
#[case("BYTE", "USINT_TO_BCD_BYTE(USINT#99)", "16#99")]
#[case("UDINT", "DWORD_BCD_TO_UDINT(DWORD#16#12345678)", "12345678")]
fn bcd_conversions(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
#[case("TIME", "ADD_TIME(t1s, T#2s500ms)", "T#3s500ms")]
#[case("TIME", "SUB_TIME(t1s, T#3s)", "T#-2s")]
#[case("TIME", "MUL_TIME(T#1s500ms, 3)", "T#4s500ms")]
#[case("TIME", "DIV_TIME(T#10s, 4)", "T#2s500ms")]
#[case("TOD", "ADD_TOD_TIME(TOD#12:00:00, T#1h30m)", "TOD#13:30:00")]
#[case("TOD", "SUB_TOD_TIME(TOD#12:00:00, T#30s)", "TOD#11:59:30")]
#[case("TIME", "SUB_TOD_TOD(TOD#10:00:00, TOD#08:30:00)", "T#1h30m")]
// 2024 is a leap year: 28 Feb 23:00 + 2 h = 29 Feb 01:00
#[case(
    "DT",
    "ADD_DT_TIME(DT#2024-02-28-23:00:00, T#2h)",
    "DT#2024-02-29-01:00:00"
)]
#[case(
    "DT",
    "SUB_DT_TIME(DT#2024-03-01-00:00:00, T#1s)",
    "DT#2024-02-29-23:59:59"
)]
#[case(
    "TIME",
    "SUB_DT_DT(DT#2024-01-02-00:00:00, DT#2024-01-01-12:00:00)",
    "T#12h"
)]
// February 2024 has 29 days
#[case("TIME", "SUB_DATE_DATE(D#2024-03-01, D#2024-02-01)", "T#29d")]
#[case(
    "DT",
    "CONCAT_DATE_TOD(D#2024-05-06, TOD#07:08:09)",
    "DT#2024-05-06-07:08:09"
)]
#[case("LTIME", "ADD_LTIME(LTIME#1ms, LTIME#1us)", "LT#1ms1us")]
#[case("TIME", "PLC_CLOCK()", "T#0s")]
fn time_functions(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[rstest]
#[case("DINT", "LEN(s)", "5")]
#[case("DINT", "LEN('')", "0")]
#[case("STRING", "LEFT(s, 3)", "'ABC'")]
#[case("STRING", "RIGHT(s, 2)", "'DE'")]
// MID(IN, L, P): L characters from position P (1-based)
#[case("STRING", "MID(s, 2, 2)", "'BC'")]
#[case("STRING", "CONCAT(s, 'F', 'GH')", "'ABCDEFGH'")]
// INSERT(IN1, IN2, P): IN2 after the P-th character
#[case("STRING", "INSERT('ABC', 'XY', 2)", "'ABXYC'")]
// DELETE(IN, L, P): L characters from position P
#[case("STRING", "DELETE('ABXYC', 2, 3)", "'ABC'")]
// REPLACE(IN1, IN2, L, P): L characters from P replaced by IN2
#[case("STRING", "REPLACE(s, 'X', 2, 3)", "'ABXE'")]
#[case("DINT", "FIND('ABCBC', 'BC')", "2")]
#[case("DINT", "FIND(s, 'Z')", "0")]
#[case("WSTRING", "CONCAT(\"ab\", \"c\")", "\"abc\"")]
fn string_functions(#[case] ty: &str, #[case] expr: &str, #[case] expected: &str) {
    assert_eq!(eval(ty, expr), expected);
}

#[test]
fn plc_clock_follows_the_virtual_clock() {
    let mut plc = compile(&program("", "t : TIME;", "t := PLC_CLOCK();"));
    plc::run(&mut plc, 151);
    // the last cycle run is cycle 150, at 150 x 10 ms
    assert_eq!(lit(&plc, "t"), "T#1s500ms");
}

/// `AND`, `OR`, `XOR` and `MOD` are operators in ST (their functional form
/// `AND(a, b)` does not parse there); in IL they are operators too, and the
/// other standard functions take the current result as first argument.
#[test]
fn il_operators_and_function_calls_with_the_current_result() {
    let src = "PROGRAM P
VAR i7 : INT := 7; bt : BOOL := TRUE; a, m, x, l, s : INT; b, c : BOOL; w : WORD; END_VAR
    LD bt
    AND bt
    ANDN bt
    ST b          (* TRUE AND TRUE AND NOT TRUE *)
    LD bt
    XOR bt
    XOR bt
    ST c          (* TRUE XOR TRUE XOR TRUE *)
    LD i7
    MOD 4
    ST m          (* 7 MOD 4 *)
    LD i7
    ADD 2
    ST a
    LD i7
    MAX 3, 20
    ST x          (* MAX(7, 3, 20) *)
    LD INT#0
    LIMIT i7, 5
    ST l          (* LIMIT(0, 7, 5) *)
    LD WORD#16#00F0
    OR WORD#16#0F00
    ST w
    LD 'abc'
    LEN
    DINT_TO_INT
    ST s
END_PROGRAM";
    let p = run_once(src);
    assert_eq!(lit(&p, "b"), "FALSE");
    assert_eq!(lit(&p, "c"), "TRUE");
    assert_eq!(lit(&p, "m"), "3");
    assert_eq!(lit(&p, "a"), "9");
    assert_eq!(lit(&p, "x"), "20");
    assert_eq!(lit(&p, "l"), "5");
    assert_eq!(lit(&p, "w"), "16#FF0");
    assert_eq!(lit(&p, "s"), "3");
}

/// An untyped literal loaded in IL takes the type of where it goes, as in
/// ST (`x := 1` with `x : INT`; docs/semantics.md §3).
#[test]
fn il_untyped_literal_takes_the_type_of_its_store() {
    let src = "PROGRAM P
VAR x : INT; b : BYTE; END_VAR
    LD 1
    ST x
    LD 16#0F
    ST b
END_PROGRAM";
    let p = run_once(src);
    assert_eq!(lit(&p, "x"), "1");
    assert_eq!(lit(&p, "b"), "16#F");
}

#[rstest]
// Functional forms of the operator words in ST (extensible AND/OR/XOR).
#[case(
    "a, b, c, y : BOOL; ",
    "a := TRUE; b := TRUE; c := FALSE; y := AND(a, b, c);",
    "y",
    "FALSE"
)]
#[case("a, b, c, y : BOOL;", "c := TRUE; y := OR(a, b, c);", "y", "TRUE")]
#[case("y : BOOL;", "y := XOR(TRUE, TRUE, TRUE);", "y", "TRUE")]
#[case("w : WORD;", "w := AND(WORD#16#0FF0, WORD#16#00FF);", "w", "16#F0")]
#[case("i : INT;", "i := MOD(17, 5);", "i", "2")]
fn operator_words_called_as_functions(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] var: &str,
    #[case] expected: &str,
) {
    let mut plc = compile(&program("", decls, body));
    plc.run_cycle().expect("cycle");
    assert_eq!(lit(&plc, var), expected);
}
