//! Structured Text, statement by statement and type by type, through the
//! embedding API. Every expected value is worked out by hand from
//! IEC 61131-3 and docs/semantics.md (derivations in comments where they are
//! not obvious).

use crate::support::plc;

use plc::{compile, lit, program, run, run_once};
use rstest::rstest;

/// Runs `body` once in a program with `decls`; returns `var` as a literal.
fn eval(decls: &str, body: &str, var: &str) -> String {
    lit(&run_once(&program("", decls, body)), var)
}

/// Same with types, functions or FBs declared before the program.
fn eval_with(prelude: &str, decls: &str, body: &str, var: &str) -> String {
    lit(&run_once(&program(prelude, decls, body)), var)
}

// ---------------------------------------------------------------- statements

#[rstest]
#[case(1, "1")]
#[case(2, "2")]
#[case(9, "2")]
#[case(10, "3")]
#[case(-5, "1")]
fn if_elsif_else_takes_the_first_true_branch(#[case] x: i32, #[case] expected: &str) {
    let body = "IF x < 2 THEN r := 1; ELSIF x < 10 THEN r := 2; ELSIF x < 5 THEN r := 4; \
                ELSE r := 3; END_IF;";
    assert_eq!(
        eval(&format!("x : INT := {x}; r : INT;"), body, "r"),
        expected
    );
}

#[test]
fn if_without_else_leaves_the_target_alone() {
    assert_eq!(
        eval("r : INT := 7;", "IF FALSE THEN r := 1; END_IF;", "r"),
        "7"
    );
}

#[rstest]
#[case(1, "10")]
#[case(2, "20")]
#[case(4, "20")]
#[case(5, "20")]
#[case(7, "30")]
#[case(9, "30")]
#[case(6, "99")]
#[case(0, "99")]
#[case(-3, "40")]
fn case_with_values_ranges_lists_and_else(#[case] x: i32, #[case] expected: &str) {
    let body = "CASE x OF 1: r := 10; 2..5: r := 20; 7, 9: r := 30; -4..-2: r := 40; \
                ELSE r := 99; END_CASE;";
    assert_eq!(
        eval(&format!("x : INT := {x}; r : INT;"), body, "r"),
        expected
    );
}

#[test]
fn case_arm_runs_all_its_statements_and_no_match_without_else_does_nothing() {
    let body = "CASE x OF 1: r := 1; s := 1; 3: r := 3; s := 3; s := s + 1; END_CASE;
                CASE x OF 100: r := 100; END_CASE;";
    let p = run_once(&program("", "x : INT := 3; r : INT; s : INT;", body));
    assert_eq!((lit(&p, "r"), lit(&p, "s")), ("3".into(), "4".into()));
}

#[test]
fn case_on_enumeration_values() {
    let types = "TYPE Color : (Red, Green, Blue); END_TYPE";
    let body = "CASE c OF Red: r := 1; Color#Green: r := 2; Blue: r := 3; END_CASE;";
    assert_eq!(
        eval_with(types, "c : Color := Green; r : INT;", body, "r"),
        "2"
    );
    assert_eq!(
        eval_with(types, "c : Color := Blue; r : INT;", body, "r"),
        "3"
    );
}

#[rstest]
// 1 + 2 + ... + 10
#[case("FOR i := 1 TO 10 DO s := s + i; END_FOR;", "55", "10")]
// 1, 3, 5, 7, 9
#[case("FOR i := 1 TO 10 BY 2 DO s := s + i; END_FOR;", "25", "5")]
// 10, 7, 4, 1
#[case("FOR i := 10 TO 1 BY -3 DO s := s + i; END_FOR;", "22", "4")]
// 10, 9, ..., 1 with an explicit -1
#[case("FOR i := 10 TO 1 BY -1 DO s := s + i; END_FOR;", "55", "10")]
// start past the end: no iteration
#[case("FOR i := 5 TO 1 DO s := s + i; END_FOR;", "0", "0")]
#[case("FOR i := 1 TO 5 BY -1 DO s := s + i; END_FOR;", "0", "0")]
// one iteration when start = end
#[case("FOR i := 3 TO 3 DO s := s + i; END_FOR;", "3", "1")]
// bounds are expressions evaluated once: 2*2 = 4 -> 1..4
#[case("FOR i := 1 TO k * 2 DO s := s + i; k := 100; END_FOR;", "10", "4")]
fn for_loops(#[case] body: &str, #[case] sum: &str, #[case] iterations: &str) {
    let body = format!("{body}\n").replace("s := s + i;", "s := s + i; n := n + 1;");
    let p = run_once(&program("", "i, s, n : INT; k : INT := 2;", &body));
    assert_eq!(
        (lit(&p, "s"), lit(&p, "n")),
        (sum.into(), iterations.into())
    );
}

#[test]
fn for_loop_up_to_the_largest_value_of_its_type_terminates() {
    // i : SINT runs 120..127: 8 iterations; the loop must not wrap around.
    let p = run_once(&program(
        "",
        "i : SINT; n : INT;",
        "FOR i := 120 TO 127 DO n := n + 1; END_FOR;",
    ));
    assert_eq!(lit(&p, "n"), "8");
    // Downwards to the smallest value: -125..-128 is 4 iterations.
    let p = run_once(&program(
        "",
        "i : SINT; n : INT;",
        "FOR i := -125 TO -128 BY -1 DO n := n + 1; END_FOR;",
    ));
    assert_eq!(lit(&p, "n"), "4");
}

#[test]
fn while_loop_tests_before_each_iteration() {
    assert_eq!(
        eval("i : INT;", "WHILE i < 5 DO i := i + 1; END_WHILE;", "i"),
        "5"
    );
    assert_eq!(
        eval(
            "i : INT := 9;",
            "WHILE i < 5 DO i := i + 1; END_WHILE;",
            "i"
        ),
        "9"
    );
}

#[test]
fn repeat_loop_runs_at_least_once() {
    assert_eq!(
        eval(
            "i : INT;",
            "REPEAT i := i + 1; UNTIL i >= 3 END_REPEAT;",
            "i"
        ),
        "3"
    );
    assert_eq!(
        eval(
            "i : INT := 10;",
            "REPEAT i := i + 1; UNTIL TRUE END_REPEAT;",
            "i"
        ),
        "11"
    );
}

#[rstest]
// 1 + 2 + 3, then EXIT at 4
#[case(
    "FOR i := 1 TO 10 DO IF i = 4 THEN EXIT; END_IF; s := s + i; END_FOR;",
    "6"
)]
#[case(
    "WHILE TRUE DO i := i + 1; IF i > 3 THEN EXIT; END_IF; s := s + i; END_WHILE;",
    "6"
)]
#[case(
    "REPEAT i := i + 1; IF i = 3 THEN EXIT; END_IF; s := s + i; UNTIL FALSE END_REPEAT;",
    "3"
)]
// EXIT leaves the inner loop only: 3 outer iterations x 1 inner (j = 1)
#[case(
    "FOR i := 1 TO 3 DO FOR j := 1 TO 3 DO IF j = 2 THEN EXIT; END_IF; s := s + 1; END_FOR; END_FOR;",
    "3"
)]
fn exit_leaves_the_innermost_loop(#[case] body: &str, #[case] expected: &str) {
    assert_eq!(eval("i, j, s : INT;", body, "s"), expected);
}

#[rstest]
// odd numbers only: 1 + 3 + 5
#[case(
    "FOR i := 1 TO 5 DO IF i MOD 2 = 0 THEN CONTINUE; END_IF; s := s + i; END_FOR;",
    "9"
)]
// skips i = 3: 1 + 2 + 4 + 5
#[case(
    "WHILE i < 5 DO i := i + 1; IF i = 3 THEN CONTINUE; END_IF; s := s + i; END_WHILE;",
    "12"
)]
// CONTINUE in REPEAT still tests UNTIL: 1 + 3 + 4, stops at i = 4
#[case(
    "REPEAT i := i + 1; IF i = 2 THEN CONTINUE; END_IF; s := s + i; UNTIL i >= 4 END_REPEAT;",
    "8"
)]
// CONTINUE affects the inner loop only: 3 x (j = 1 and 3) = 6 additions
#[case(
    "FOR i := 1 TO 3 DO FOR j := 1 TO 3 DO IF j = 2 THEN CONTINUE; END_IF; s := s + 1; END_FOR; END_FOR;",
    "6"
)]
fn continue_skips_to_the_next_iteration(#[case] body: &str, #[case] expected: &str) {
    assert_eq!(eval("i, j, s : INT;", body, "s"), expected);
}

#[test]
fn return_ends_the_program_body_and_the_function() {
    assert_eq!(
        eval(
            "r : INT;",
            "r := 1; IF r = 1 THEN RETURN; END_IF; r := 2;",
            "r"
        ),
        "1"
    );
    let f = "FUNCTION F : INT VAR_INPUT x : INT; END_VAR
             F := 1; IF x > 0 THEN RETURN; END_IF; F := 2; END_FUNCTION";
    assert_eq!(
        eval_with(f, "a, b : INT;", "a := F(1); b := F(0);", "a"),
        "1"
    );
    assert_eq!(
        eval_with(f, "a, b : INT;", "a := F(1); b := F(0);", "b"),
        "2"
    );
}

#[test]
fn empty_statements_and_case_insensitive_keywords_and_names() {
    let p = run_once(&program(
        "",
        "Count : INT;",
        ";; if TRUE then COUNT := count + 1; end_if; ;",
    ));
    assert_eq!(lit(&p, "count"), "1");
    assert_eq!(lit(&p, "COUNT"), "1");
}

#[test]
fn comments_do_not_nest_and_line_comments_end_at_the_newline() {
    // The first `*)` ends the comment, so `r := 1;` is code.
    let body = "(* a (* b *) r := 1; // r := 2;\n s := 3; (* multi\nline *)";
    let p = run_once(&program("", "r, s : INT;", body));
    assert_eq!((lit(&p, "r"), lit(&p, "s")), ("1".into(), "3".into()));
}

// ---------------------------------------------------------------- expressions

#[rstest]
// ** binds tighter than unary minus: -(2 ** 2)
#[case("d := -2 ** 2;", "d", "-4")]
#[case("d := (-2) ** 2;", "d", "4")]
// ** is left-associative like every other binary operator: (2 ** 3) ** 2
#[case("d := 2 ** 3 ** 2;", "d", "64")]
#[case("d := 2 + 3 * 4;", "d", "14")]
#[case("d := (2 + 3) * 4;", "d", "20")]
#[case("d := 10 - 4 - 3;", "d", "3")]
#[case("d := 100 / 10 / 5;", "d", "2")]
#[case("d := 7 + 5 MOD 3;", "d", "9")]
#[case("d := 5 - -3;", "d", "8")]
#[case("d := -a * 3;", "d", "-15")]
// AND before XOR before OR
#[case("b := t OR t XOR t;", "b", "TRUE")]
#[case("b := t XOR t AND f;", "b", "TRUE")]
#[case("b := (t XOR t) AND f;", "b", "FALSE")]
#[case("b := f AND f OR t;", "b", "TRUE")]
#[case("b := t & f;", "b", "FALSE")]
#[case("b := NOT f AND f;", "b", "FALSE")]
#[case("b := NOT (f AND f);", "b", "TRUE")]
// arithmetic before comparison before equality before AND
#[case("b := 1 + 2 = 3;", "b", "TRUE")]
#[case("b := 3 > 2 = t;", "b", "TRUE")]
#[case("b := a > 4 AND a < 6;", "b", "TRUE")]
#[case("b := a >= 5 AND a <= 5 AND a <> 4;", "b", "TRUE")]
#[case("b := a < 5 OR a > 5;", "b", "FALSE")]
fn operator_precedence(#[case] body: &str, #[case] var: &str, #[case] expected: &str) {
    let decls = "d : DINT; b : BOOL; a : INT := 5; t : BOOL := TRUE; f : BOOL;";
    assert_eq!(eval(decls, body, var), expected);
}

#[rstest]
#[case("SINT", "127", "x + 1", "-128")]
#[case("SINT", "-128", "x - 1", "127")]
#[case("SINT", "100", "x + x", "-56")]
#[case("SINT", "-128", "-x", "-128")]
#[case("INT", "32767", "x + 1", "-32768")]
#[case("INT", "-32768", "x - 1", "32767")]
// 200 * 200 = 40000 = 40000 - 65536
#[case("INT", "200", "x * x", "-25536")]
#[case("DINT", "2147483647", "x + 1", "-2147483648")]
#[case("DINT", "-2147483648", "x - 1", "2147483647")]
#[case("LINT", "9223372036854775807", "x + 1", "-9223372036854775808")]
#[case("LINT", "-9223372036854775808", "x - 1", "9223372036854775807")]
#[case("USINT", "255", "x + 1", "0")]
#[case("USINT", "0", "x - 1", "255")]
// 16 * 16 = 256 = 0 mod 256
#[case("USINT", "16", "x * x", "0")]
#[case("UINT", "65535", "x + 1", "0")]
#[case("UINT", "0", "x - 1", "65535")]
#[case("UDINT", "4294967295", "x + 1", "0")]
#[case("UDINT", "0", "x - 1", "4294967295")]
#[case("ULINT", "18446744073709551615", "x + 1", "0")]
#[case("ULINT", "0", "x - 1", "18446744073709551615")]
fn integer_arithmetic_wraps_at_its_width(
    #[case] ty: &str,
    #[case] init: &str,
    #[case] expr: &str,
    #[case] expected: &str,
) {
    let decls = format!("x : {ty} := {init}; y : {ty};");
    assert_eq!(eval(&decls, &format!("y := {expr};"), "y"), expected);
}

#[rstest]
// -32768 / -1 = 32768 does not fit: wraps to -32768 like every INT operation
#[case("INT", "-32768", "-1", "-32768", "0")]
#[case("SINT", "-128", "-1", "-128", "0")]
fn dividing_the_smallest_value_by_minus_one_wraps(
    #[case] ty: &str,
    #[case] a: &str,
    #[case] b: &str,
    #[case] quotient: &str,
    #[case] remainder: &str,
) {
    let decls = format!("a : {ty} := {a}; b : {ty} := {b}; q, r : {ty};");
    let p = run_once(&program("", &decls, "q := a / b; r := a MOD b;"));
    assert_eq!(
        (lit(&p, "q"), lit(&p, "r")),
        (quotient.into(), remainder.into())
    );
}

#[rstest]
#[case(7, 2, "3", "1")]
#[case(-7, 2, "-3", "-1")]
#[case(7, -2, "-3", "1")]
#[case(-7, -2, "3", "-1")]
#[case(6, 3, "2", "0")]
#[case(-1, 5, "0", "-1")]
fn division_truncates_and_mod_takes_the_sign_of_the_dividend(
    #[case] a: i32,
    #[case] b: i32,
    #[case] quotient: &str,
    #[case] remainder: &str,
) {
    // At run time ...
    let decls = format!("a : DINT := {a}; b : DINT := {b}; q, r, qc, rc : DINT;");
    // ... and folded from constants.
    let body = format!("q := a / b; r := a MOD b; qc := {a} / ({b}); rc := {a} MOD ({b});");
    let p = run_once(&program("", &decls, &body));
    assert_eq!(lit(&p, "q"), quotient);
    assert_eq!(lit(&p, "r"), remainder);
    assert_eq!(lit(&p, "qc"), quotient);
    assert_eq!(lit(&p, "rc"), remainder);
}

#[rstest]
#[case("REAL", "r := 10.0 / 4.0;", "2.5")]
#[case("REAL", "r := 1.0;", "1.0")]
#[case("REAL", "r := -0.5;", "-0.5")]
#[case("REAL", "r := 1.5E3;", "1500.0")]
// f32: 1/3 = 0.3333333432674408, shortest text that reads back is 0.33333334
#[case("REAL", "r := 1.0 / 3.0;", "0.33333334")]
// f32: 0.1 + 0.2 rounds to the REAL nearest 0.3
#[case("REAL", "r := 0.1 + 0.2;", "0.3")]
// f64: the classic 0.30000000000000004
#[case("LREAL", "r := 0.1 + 0.2;", "0.30000000000000004")]
#[case("LREAL", "r := 1.0 / 3.0;", "0.3333333333333333")]
#[case("REAL", "r := 1.0E20;", "1.0E+20")]
#[case("LREAL", "r := 2.0 ** 10.0;", "1024.0")]
#[case("LREAL", "r := 7.0 - 10.0 * 0.5;", "2.0")]
// integer to REAL widening: INT 3 -> 3.0
#[case("REAL", "r := i;", "3.0")]
#[case("LREAL", "r := d / 2;", "3.0")]
fn real_arithmetic_and_printing(#[case] ty: &str, #[case] body: &str, #[case] expected: &str) {
    let decls = format!("r : {ty}; i : INT := 3; d : DINT := 7;");
    assert_eq!(eval(&decls, body, "r"), expected);
}

// ---------------------------------------------------------------- literals

#[rstest]
#[case("DINT", "16#FF", "255")]
#[case("DINT", "16#ff", "255")]
#[case("DINT", "2#1010", "10")]
#[case("DINT", "8#17", "15")]
#[case("DINT", "1_000", "1000")]
#[case("DINT", "16#FF_FF", "65535")]
#[case("DINT", "-16#10", "-16")]
#[case("INT", "INT#16#7FFF", "32767")]
#[case("INT", "INT#-5", "-5")]
#[case("DINT", "DINT#2#1111_0000", "240")]
#[case("USINT", "USINT#255", "255")]
#[case("BOOL", "BOOL#1", "TRUE")]
#[case("BOOL", "BOOL#FALSE", "FALSE")]
#[case("BYTE", "16#A5", "16#A5")]
#[case("WORD", "WORD#16#00FF", "16#FF")]
#[case("REAL", "REAL#2.5", "2.5")]
#[case("LREAL", "LREAL#1.0E-3", "0.001")]
#[case("LREAL", "12.5e1", "125.0")]
#[case("TIME", "T#1h2m", "T#1h2m")]
#[case("TIME", "TIME#90s", "T#1m30s")]
#[case("TIME", "T#1.5s", "T#1s500ms")]
#[case("TIME", "t#1s_500ms", "T#1s500ms")]
#[case("TIME", "T#-2ms", "T#-2ms")]
#[case("TIME", "T#0s", "T#0s")]
#[case("TIME", "T#25h", "T#1d1h")]
#[case("TIME", "T#1d2h3m4s5ms", "T#1d2h3m4s5ms")]
#[case("LTIME", "LTIME#5us", "LT#5us")]
#[case("TOD", "TOD#12:30:15", "TOD#12:30:15")]
#[case("TOD", "TIME_OF_DAY#08:00:00.5", "TOD#08:00:00.5")]
#[case("DATE", "D#2024-01-31", "D#2024-01-31")]
#[case("DATE", "DATE#1970-01-01", "D#1970-01-01")]
#[case("DT", "DT#2024-02-29-23:59:59", "DT#2024-02-29-23:59:59")]
#[case("DT", "DATE_AND_TIME#2000-01-01-00:00:00", "DT#2000-01-01-00:00:00")]
#[case("STRING", "'hello'", "'hello'")]
#[case("STRING", "'it$'s'", "'it$'s'")]
#[case("STRING", "'$41$42'", "'AB'")]
#[case("STRING", "''", "''")]
#[case("WSTRING", "\"wide\"", "\"wide\"")]
fn literals(#[case] ty: &str, #[case] literal: &str, #[case] expected: &str) {
    let decls = format!("v : {ty};");
    assert_eq!(eval(&decls, &format!("v := {literal};"), "v"), expected);
    // The same literal as an initial value.
    let decls = format!("v : {ty} := {literal};");
    assert_eq!(eval(&decls, "", "v"), expected);
}

// ---------------------------------------------------------------- enumerations

const ENUMS: &str = "TYPE
    Color : (Red, Green, Blue);
    Level : (Low := 10, Mid := 20, High := 30);
    Mode : INT (Off := 0, Auto := 5, Manual := 9) := Auto;
END_TYPE";

#[rstest]
#[case("c : Color;", "", "c", "Red")] // first value by default
#[case("c : Color := Blue;", "", "c", "Blue")]
#[case("c : Color;", "c := Color#Green;", "c", "Green")]
#[case("l : Level;", "", "l", "Low")]
#[case("l : Level;", "l := High;", "l", "High")]
#[case("m : Mode;", "", "m", "Auto")] // the type's declared default
#[case("m : Mode;", "m := Mode#Manual;", "m", "Manual")]
#[case("c : Color := Green; b : BOOL;", "b := c = Color#Green;", "b", "TRUE")]
#[case("c : Color := Green; b : BOOL;", "b := c <> Green;", "b", "FALSE")]
#[case(
    "l : Level := Mid; b : BOOL;",
    "b := l = Level#Mid AND l <> Low;",
    "b",
    "TRUE"
)]
fn enumerations(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] var: &str,
    #[case] expected: &str,
) {
    assert_eq!(eval_with(ENUMS, decls, body, var), expected);
}

#[test]
fn valued_enumeration_keeps_its_numeric_value() {
    let p = run_once(&program(ENUMS, "l : Level := High; m : Mode;", ""));
    assert_eq!(p.read_i64("l"), Ok(30));
    assert_eq!(p.read_i64("m"), Ok(5));
}

// ---------------------------------------------------------------- subranges

const PERCENT: &str = "TYPE Percent : INT (0..100); END_TYPE";

#[test]
fn subrange_accepts_values_inside_its_range() {
    let p = run_once(&program(
        PERCENT,
        "p : Percent; q : Percent := 100; i : INT := 42; r : INT (-5..5) := -5;",
        "p := i; i := p + 1;",
    ));
    assert_eq!(lit(&p, "p"), "42");
    assert_eq!(lit(&p, "q"), "100");
    assert_eq!(lit(&p, "i"), "43");
    assert_eq!(lit(&p, "r"), "-5");
}

#[rstest]
#[case("i := 101; p := i;")]
#[case("i := -1; p := i;")]
#[case("p := 100; p := p + 1;")]
fn subrange_out_of_range_at_run_time_is_a_fault(#[case] body: &str) {
    let mut plc = compile(&program(PERCENT, "p : Percent; i : INT;", body));
    let fault = plc.run_cycle().expect_err("out of range must fault");
    assert_eq!(fault.cycle, 0);
    assert!(fault.location.starts_with("test.st:"), "{}", fault.location);
}

// ---------------------------------------------------------------- arrays

#[test]
fn two_dimensional_array_with_nonzero_bounds() {
    let body = "FOR i := 1 TO 3 DO FOR j := -1 TO 2 DO m[i, j] := i * 10 + j; END_FOR; END_FOR;
                s := 0; FOR i := 1 TO 3 DO FOR j := -1 TO 2 DO s := s + m[i, j]; END_FOR; END_FOR;";
    let p = run_once(&program(
        "",
        "m : ARRAY[1..3, -1..2] OF INT; i, j, s : INT;",
        body,
    ));
    assert_eq!(lit(&p, "m[2,1]"), "21");
    assert_eq!(lit(&p, "m[3,-1]"), "29");
    assert_eq!(lit(&p, "m[1, 2]"), "12");
    // sum over i of (4 * 10 * i + (-1 + 0 + 1 + 2)) = 40 * 6 + 3 * 2 = 246
    assert_eq!(lit(&p, "s"), "246");
}

#[test]
fn array_initializers_with_repetition() {
    let p = run_once(&program(
        "",
        "a : ARRAY[0..4] OF INT := [1, 2, 3(7)]; b : ARRAY[-2..2] OF BOOL := [2(TRUE)];
         c : ARRAY[1..2, 1..2] OF DINT := [11, 12, 21, 22]; s : INT;",
        "s := a[0] + a[1] + a[2] + a[3] + a[4];",
    ));
    assert_eq!(lit(&p, "s"), "24"); // 1 + 2 + 7 + 7 + 7
    assert_eq!(lit(&p, "b[-2]"), "TRUE");
    assert_eq!(lit(&p, "b[-1]"), "TRUE");
    assert_eq!(lit(&p, "b[0]"), "FALSE"); // not initialised: default
    assert_eq!(lit(&p, "c[1,2]"), "12"); // row-major order
    assert_eq!(lit(&p, "c[2,1]"), "21");
}

#[test]
fn array_copy_and_array_of_arrays() {
    let p = run_once(&program(
        "",
        "a : ARRAY[1..3] OF INT := [1, 2, 3]; b : ARRAY[1..3] OF INT;
         g : ARRAY[0..1] OF ARRAY[0..2] OF INT;",
        "b := a; a[1] := 100; g[1][2] := 5; g[0][0] := b[1] + g[1][2];",
    ));
    assert_eq!(lit(&p, "b[1]"), "1"); // a copy, not an alias
    assert_eq!(lit(&p, "a[1]"), "100");
    assert_eq!(lit(&p, "g[0][0]"), "6");
}

const POINT: &str = "TYPE
    Point : STRUCT x : INT; y : INT := 5; END_STRUCT;
    Line : STRUCT a : Point; b : Point := (x := 3, y := 4); tag : STRING[10] := 'line'; END_STRUCT;
END_TYPE";

#[test]
fn array_of_structs() {
    let p = run_once(&program(
        POINT,
        "pts : ARRAY[0..2] OF Point; s : INT; i : INT;",
        "FOR i := 0 TO 2 DO pts[i].x := i * 2; pts[i].y := 1; END_FOR; pts[1].y := 7;
         s := pts[2].x + pts[1].y;",
    ));
    assert_eq!(lit(&p, "pts[1].x"), "2");
    assert_eq!(lit(&p, "pts[0].y"), "1");
    assert_eq!(lit(&p, "s"), "11"); // 4 + 7
}

// ---------------------------------------------------------------- structs

#[test]
fn nested_structs_with_initializers_and_copies() {
    let p = run_once(&program(
        POINT,
        "m : Line := (a := (x := 1, y := 2), b := (x := 3, y := 4), tag := 'm'); q : Point; s : INT;",
        "q := m.b; q.x := q.x + 10; m.a.y := m.a.y * 10; s := m.a.x + m.a.y + m.b.x + m.b.y;",
    ));
    assert_eq!(lit(&p, "m.tag"), "'m'");
    assert_eq!(lit(&p, "m.a.y"), "20");
    assert_eq!(lit(&p, "q.x"), "13"); // copied, then changed
    assert_eq!(lit(&p, "q.y"), "4");
    assert_eq!(lit(&p, "m.b.x"), "3"); // the original is unchanged
    assert_eq!(lit(&p, "s"), "28"); // 1 + 20 + 3 + 4
}

#[test]
fn struct_field_defaults_from_the_type_declaration() {
    let p = run_once(&program(
        POINT,
        "p : Point; q : Point := (x := 1); pts : ARRAY[0..1] OF Point; l : Line;",
        "",
    ));
    assert_eq!(lit(&p, "p.y"), "5");
    assert_eq!(lit(&p, "q.x"), "1");
    assert_eq!(lit(&p, "q.y"), "5"); // a field missing from the initializer keeps its default
    assert_eq!(lit(&p, "pts[1].y"), "5");
    assert_eq!(lit(&p, "l.a.y"), "5");
    assert_eq!(lit(&p, "l.b.x"), "3"); // the field's own initializer wins over Point's
    assert_eq!(lit(&p, "l.b.y"), "4");
    assert_eq!(lit(&p, "l.tag"), "'line'");
}

// ---------------------------------------------------------------- strings

#[rstest]
#[case("s := 'abc'; n := LEN(s);", "n", "3")]
#[case("s := CONCAT('ab', 'cd', 'ef');", "s", "'abcdef'")]
#[case("s := 'abc'; b := s = 'abc';", "b", "TRUE")]
#[case("b := 'abc' < 'abd';", "b", "TRUE")]
#[case("b := 'b' > 'abc';", "b", "TRUE")]
#[case("b := 'ab' < 'abc';", "b", "TRUE")]
#[case("s := 'x'; t := s; s := 'y';", "t", "'x'")]
#[case("s := ''; n := LEN(s);", "n", "0")]
fn string_operations(#[case] body: &str, #[case] var: &str, #[case] expected: &str) {
    assert_eq!(
        eval("s, t : STRING; n : DINT; b : BOOL;", body, var),
        expected
    );
}

#[test]
fn string_assignment_truncates_to_the_declared_length() {
    let p = run_once(&program(
        "",
        "s : STRING[5]; t : STRING := 'abcdefgh';",
        "s := t;",
    ));
    assert_eq!(lit(&p, "s"), "'abcde'");
}

// ---------------------------------------------------------------- FB instances

const COUNTER: &str = "FUNCTION_BLOCK Counter
VAR_INPUT inc : INT := 1; END_VAR
VAR_OUTPUT n : INT; END_VAR
n := n + inc;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Pair
VAR_OUTPUT total : INT; END_VAR
VAR a, b : Counter; END_VAR
a(); b(inc := 10);
total := a.n + b.n;
END_FUNCTION_BLOCK
TYPE Holder : STRUCT c : Counter; END_STRUCT; END_TYPE";

#[test]
fn fb_instances_keep_their_state_between_calls_and_cycles() {
    let mut p = compile(&program(
        COUNTER,
        "c1, c2 : Counter; x : INT;",
        "c1(); c1(inc := 2); c2(inc := 5); x := c1.n;",
    ));
    run(&mut p, 3);
    // c1: +1 then +2 per cycle (inc keeps the last value given? no: the
    // first call gives no step, so it keeps 2 from the previous cycle's
    // second call, except in cycle 0 where it is the default 1):
    // cycle 0: 1 + 2 = 3; cycles 1, 2: 2 + 2 = 4 each -> 11.
    assert_eq!(lit(&p, "c1.n"), "11");
    assert_eq!(lit(&p, "x"), "11");
    assert_eq!(lit(&p, "c2.n"), "15");
}

#[test]
fn fb_instances_inside_fbs_structs_and_arrays() {
    let mut p = compile(&program(
        COUNTER,
        "pr : Pair; h : Holder; arr : ARRAY[1..3] OF Counter; i : INT;",
        "pr(); h.c(inc := 3); FOR i := 1 TO 3 DO arr[i](inc := i); END_FOR; arr[2]();",
    ));
    run(&mut p, 4);
    assert_eq!(lit(&p, "pr.a.n"), "4");
    assert_eq!(lit(&p, "pr.b.n"), "40");
    assert_eq!(lit(&p, "pr.total"), "44");
    assert_eq!(lit(&p, "h.c.n"), "12");
    assert_eq!(lit(&p, "arr[1].n"), "4");
    // arr[2] is called twice per cycle with inc 2 (kept from the first call)
    assert_eq!(lit(&p, "arr[2].n"), "16");
    assert_eq!(lit(&p, "arr[3].n"), "12");
}

#[test]
fn fb_outputs_read_after_the_call() {
    let p = run_once(&program(
        COUNTER,
        "arr : ARRAY[0..1] OF Counter; c : Counter; x, y : INT;",
        "c(inc := 7); x := c.n; arr[1](inc := 4); y := arr[1].n;",
    ));
    assert_eq!(lit(&p, "x"), "7");
    assert_eq!(lit(&p, "y"), "4");
}

#[test]
fn fb_outputs_with_arrow_and_positional_inputs() {
    let fb = "FUNCTION_BLOCK Acc
VAR_INPUT a : INT; b : INT; END_VAR
VAR_OUTPUT sum : INT; diff : INT; END_VAR
sum := a + b; diff := a - b;
END_FUNCTION_BLOCK";
    let p = run_once(&program(
        fb,
        "f : Acc; s, d : INT; e : BOOL;",
        "f(a := 10, b := 3, sum => s, diff => d);",
    ));
    assert_eq!((lit(&p, "s"), lit(&p, "d")), ("13".into(), "7".into()));
}

/// `=>` of a structure or array output copies all of it (a regression:
/// only its first slot was copied), from a block and from a function.
#[test]
fn structure_and_array_outputs_are_copied_whole() {
    let prelude = "TYPE E_K : (a := 0, b := 1) USINT; END_TYPE
TYPE ST_R : STRUCT k : E_K; code : UINT; text : STRING[8]; END_STRUCT END_TYPE
FUNCTION_BLOCK FB_Parse
VAR_OUTPUT r : ST_R; bytes : ARRAY[1..3] OF BYTE; END_VAR
r.k := E_K.b; r.code := 30000; r.text := 'ok';
bytes[1] := 16#11; bytes[3] := 16#33;
END_FUNCTION_BLOCK
FUNCTION F_Parse : BOOL
VAR_OUTPUT r : ST_R; END_VAR
r.code := 7; r.text := 'fn';
F_Parse := TRUE;
END_FUNCTION";
    let p = run_once(&program(
        prelude,
        "fb : FB_Parse; got : ST_R; raw : ARRAY[1..3] OF BYTE; fromFn : ST_R; ok : BOOL;",
        "fb(r => got, bytes => raw); ok := F_Parse(r => fromFn);",
    ));
    assert_eq!(
        [
            lit(&p, "got.k"),
            lit(&p, "got.code"),
            lit(&p, "got.text"),
            lit(&p, "raw[3]"),
            lit(&p, "fromFn.code"),
            lit(&p, "fromFn.text")
        ],
        ["b", "30000", "'ok'", "16#33", "7", "'fn'"]
    );
}

#[test]
fn standard_fb_pin_names_and_instances_in_arrays() {
    let mut p = compile(&program(
        "",
        "trig : ARRAY[1..2] OF R_TRIG; n : INT; x : BOOL; sr1 : SR; rs1 : RS;",
        "x := NOT x; trig[1](CLK := x); trig[2](CLK := TRUE);
         IF trig[1].Q THEN n := n + 1; END_IF;
         sr1(SET1 := TRUE, RESET := TRUE); rs1(SET := TRUE, RESET1 := TRUE);",
    ));
    run(&mut p, 5);
    // x: TRUE, FALSE, TRUE, FALSE, TRUE -> rises at cycles 0, 2, 4
    assert_eq!(lit(&p, "n"), "3");
    assert_eq!(lit(&p, "trig[2].Q"), "FALSE");
    assert_eq!(lit(&p, "sr1.Q1"), "TRUE");
    assert_eq!(lit(&p, "rs1.Q1"), "FALSE");
}

// ---------------------------------------------------------------- functions

const FUNCS: &str = "FUNCTION Calls : INT
VAR k : INT; END_VAR
k := k + 1; Calls := k;
END_FUNCTION
FUNCTION Inc : BOOL
VAR_IN_OUT v : INT; END_VAR
VAR_INPUT dv : INT := 1; END_VAR
v := v + dv; Inc := TRUE;
END_FUNCTION
FUNCTION DivMod : BOOL
VAR_INPUT a, b : DINT; END_VAR
VAR_OUTPUT q, r : DINT; END_VAR
q := a / b; r := a MOD b; DivMod := b <> 0;
END_FUNCTION
FUNCTION Hyp : LREAL
VAR_INPUT x, y : LREAL; END_VAR
Hyp := SQRT(x * x + y * y);
END_FUNCTION
FUNCTION_BLOCK TempUser
VAR_OUTPUT out : INT; END_VAR
VAR_TEMP t : INT; END_VAR
VAR kept : INT; END_VAR
t := t + 1; kept := kept + 1; out := t * 100 + kept;
END_FUNCTION_BLOCK";

#[test]
fn function_locals_are_fresh_at_every_call() {
    let mut p = compile(&program(
        FUNCS,
        "a, b : INT;",
        "a := Calls(); b := Calls();",
    ));
    run(&mut p, 3);
    assert_eq!((lit(&p, "a"), lit(&p, "b")), ("1".into(), "1".into()));
}

#[test]
fn var_temp_of_an_fb_is_reset_at_every_call() {
    let mut p = compile(&program(FUNCS, "u : TempUser;", "u();"));
    run(&mut p, 3);
    // t is 1 at each call, kept counts 3 calls
    assert_eq!(lit(&p, "u.out"), "103");
}

#[test]
fn var_in_out_is_passed_by_reference() {
    let p = run_once(&program(
        FUNCS,
        "x : INT := 5; arr : ARRAY[1..2] OF INT; ok : BOOL;",
        "ok := Inc(v := x); Inc(v := x, dv := 10); Inc(v := arr[2], dv := 3);",
    ));
    assert_eq!(lit(&p, "x"), "16");
    assert_eq!(lit(&p, "arr[2]"), "3");
    assert_eq!(lit(&p, "ok"), "TRUE");
}

#[test]
fn function_outputs_with_arrow() {
    let p = run_once(&program(
        FUNCS,
        "qq, rr : DINT; ok : BOOL; h : LREAL;",
        "ok := DivMod(a := -17, b := 5, q => qq, r => rr); h := Hyp(3.0, 4.0);",
    ));
    assert_eq!(lit(&p, "qq"), "-3");
    assert_eq!(lit(&p, "rr"), "-2");
    assert_eq!(lit(&p, "ok"), "TRUE");
    assert_eq!(lit(&p, "h"), "5.0");
}

#[test]
fn en_false_skips_the_call_and_clears_eno() {
    let p = run_once(&program(
        &format!("{FUNCS}\n{COUNTER}"),
        "c : Counter; x : INT := 5; e1, e2, e3 : BOOL := TRUE; go : BOOL;",
        "c(EN := go, ENO => e1); Inc(EN := go, v := x, ENO => e2); c(EN := TRUE, ENO => e3);",
    ));
    assert_eq!(lit(&p, "c.n"), "1"); // only the EN := TRUE call counted
    assert_eq!(lit(&p, "x"), "5"); // Inc was not executed
    assert_eq!(lit(&p, "e1"), "FALSE");
    assert_eq!(lit(&p, "e2"), "FALSE");
    assert_eq!(lit(&p, "e3"), "TRUE");
}

// ---------------------------------------------------------------- constants

#[test]
fn constants_fold_into_types_and_expressions() {
    let src = "VAR_GLOBAL CONSTANT SIZE : INT := 4; END_VAR
PROGRAM P
VAR CONSTANT HALF : INT := SIZE / 2; LIMIT : DINT := SIZE * 1000 + 7; END_VAR
VAR a : ARRAY[1..SIZE] OF INT; b : ARRAY[0..HALF - 1] OF BOOL; n, h : INT; l : DINT; END_VAR
FOR n := 1 TO SIZE DO a[n] := n; END_FOR;
h := HALF; l := LIMIT;
END_PROGRAM";
    let p = run_once(src);
    assert_eq!(lit(&p, "a[4]"), "4");
    assert_eq!(lit(&p, "h"), "2");
    assert_eq!(lit(&p, "l"), "4007");
    assert_eq!(lit(&p, "b[1]"), "FALSE");
    assert!(p.read("a[5]").is_err(), "a has 4 elements");
    assert!(p.read("b[2]").is_err(), "b has 2 elements");
}

// ---------------------------------------------------------------- globals, located

#[test]
fn globals_shared_through_var_external() {
    let src = "VAR_GLOBAL g : INT; END_VAR
FUNCTION_BLOCK Bump VAR_EXTERNAL g : INT; END_VAR g := g + 1; END_FUNCTION_BLOCK
PROGRAM P VAR b : Bump; END_VAR VAR_EXTERNAL g : INT; END_VAR b(); b(); g := g * 10; END_PROGRAM";
    let mut p = compile(src);
    run(&mut p, 2);
    // cycle 0: (0 + 2) * 10 = 20; cycle 1: (20 + 2) * 10 = 220
    assert_eq!(lit(&p, "g"), "220");
}

#[test]
fn located_variables_are_readable_by_address_and_name() {
    let mut p = compile(&program(
        "",
        "in1 AT %IX0.1 : BOOL; out1 AT %QX0.2 : BOOL; w AT %QW4 : WORD; m AT %M0.0.0.0.3 : BOOL;",
        "out1 := NOT in1; w := WORD#16#00F0; m := in1;",
    ));
    p.write("%IX0.1", "TRUE").unwrap();
    run(&mut p, 1);
    assert_eq!(lit(&p, "%QX0.2"), "FALSE");
    assert_eq!(lit(&p, "out1"), "FALSE");
    assert_eq!(lit(&p, "%QW4"), "16#F0");
    assert_eq!(lit(&p, "%M0.0.0.0.3"), "TRUE");
}

// ---------------------------------------------------------------- configurations

#[test]
fn configuration_with_one_cyclic_task() {
    let src = "PROGRAM Ticker VAR n : INT; now : TIME; END_VAR n := n + 1; now := PLC_CLOCK(); END_PROGRAM
CONFIGURATION Cfg
  RESOURCE Res ON PLC
    TASK Fast (INTERVAL := T#20ms, PRIORITY := 1);
    PROGRAM main WITH Fast : Ticker;
  END_RESOURCE
END_CONFIGURATION";
    let mut p = compile(src);
    assert_eq!(
        p.cycle_time(),
        20_000_000,
        "the cycle is the task's INTERVAL"
    );
    run(&mut p, 5);
    assert_eq!(lit(&p, "main.n"), "5");
    // the 5th run is cycle 4, at 4 x 20 ms
    assert_eq!(lit(&p, "main.now"), "T#80ms");
}

#[test]
fn two_tasks_run_on_the_gcd_of_their_intervals_by_priority() {
    let src = "VAR_GLOBAL log : DINT; END_VAR
PROGRAM A VAR_EXTERNAL log : DINT; END_VAR VAR n : INT; END_VAR n := n + 1; log := log * 10 + 1; END_PROGRAM
PROGRAM B VAR_EXTERNAL log : DINT; END_VAR VAR n : INT; END_VAR n := n + 1; log := log * 10 + 2; END_PROGRAM
CONFIGURATION Cfg
  RESOURCE Res ON PLC
    TASK T20 (INTERVAL := T#20ms, PRIORITY := 1);
    TASK T30 (INTERVAL := T#30ms, PRIORITY := 0);
    PROGRAM a1 WITH T20 : A;
    PROGRAM b1 WITH T30 : B;
  END_RESOURCE
END_CONFIGURATION";
    let mut p = compile(src);
    // gcd(20 ms, 30 ms) = 10 ms
    assert_eq!(p.cycle_time(), 10_000_000);
    run(&mut p, 1);
    // at t = 0 both are due; T30 has priority 0 and runs first: log = 2, then 21
    assert_eq!(lit(&p, "log"), "21");
    run(&mut p, 11);
    // 12 ticks, t = 0 .. 110 ms: T20 at 0, 20, 40, 60, 80, 100 (6 runs);
    // T30 at 0, 30, 60, 90 (4 runs)
    assert_eq!(lit(&p, "a1.n"), "6");
    assert_eq!(lit(&p, "b1.n"), "4");
}

/// `PROGRAM p1 WITH t : Main(in1 := %IX0.0, out1 => %QX0.1)` (IEC 61131-3
/// program configuration: a data source or sink may be a direct variable):
/// the input is read from the process image at each run of the program,
/// the output written to it after the run (issue #13).
#[test]
fn program_parameters_connected_to_direct_addresses() {
    let src = "PROGRAM Main
VAR_INPUT in1 : BOOL; level : INT; END_VAR
VAR_OUTPUT out1 : BOOL; twice : WORD; END_VAR
VAR runs : INT; END_VAR
runs := runs + 1;
out1 := NOT in1;
twice := INT_TO_WORD(level * 2);
END_PROGRAM
PROGRAM Watch
VAR_OUTPUT seen : WORD; END_VAR
seen := %QW4;
END_PROGRAM
CONFIGURATION Cfg
  RESOURCE Res ON PLC
    TASK Slow (INTERVAL := T#20ms, PRIORITY := 1);
    TASK Fast (INTERVAL := T#10ms, PRIORITY := 2);
    PROGRAM p1 WITH Slow : Main(in1 := %IX0.0, level := %IW2, out1 => %QX0.1, twice => %QW4);
    PROGRAM w WITH Fast : Watch;
  END_RESOURCE
END_CONFIGURATION";
    let mut p = compile(src);
    run(&mut p, 1);
    assert!(p.process_image().read_bit("%QX0.1").unwrap());
    p.process_image_mut().write_bit("%IX0.0", true).unwrap();
    p.process_image_mut().write_word("%IW2", 21).unwrap();
    // Tick 1 (10 ms): Main does not run, so nothing it connects changes.
    run(&mut p, 1);
    assert!(p.process_image().read_bit("%QX0.1").unwrap());
    assert_eq!(lit(&p, "p1.in1"), "FALSE");
    // Tick 2 (20 ms): Main reads the inputs, its outputs reach the image;
    // Watch (after it, lower priority) reads %QW4 by address.
    run(&mut p, 1);
    assert_eq!(lit(&p, "p1.runs"), "2");
    assert_eq!(lit(&p, "p1.in1"), "TRUE");
    assert!(!p.process_image().read_bit("%QX0.1").unwrap());
    assert_eq!(p.process_image().read_word("%QW4").unwrap(), 42);
    assert_eq!(lit(&p, "%QW4"), "16#2A");
    assert_eq!(lit(&p, "w.seen"), "16#2A");
}

// ---------------------------------------------------------------- bit strings, durations

#[rstest]
// F0F0 AND 0FF0 = 00F0 (printed without leading zeros)
#[case("w := w AND WORD#16#0FF0;", "w", "16#F0")]
#[case("w := w OR WORD#16#0F00;", "w", "16#FFF0")]
#[case("w := w XOR WORD#16#FFFF;", "w", "16#F0F")]
#[case("w := NOT w;", "w", "16#F0F")]
// bit 4 of 16#F0F0 is 1, bit 3 is 0
#[case("b := w.4;", "b", "TRUE")]
#[case("b := w.3;", "b", "FALSE")]
#[case("y := BYTE#16#81 AND 16#0F;", "y", "16#1")]
#[case("t := T#1s + T#250ms;", "t", "T#1s250ms")]
#[case("t := T#1s - T#1500ms;", "t", "T#-500ms")]
#[case("t := d * 3;", "t", "T#600ms")]
#[case("t := d / 4;", "t", "T#50ms")]
#[case("b := d < T#1s AND d >= T#200ms;", "b", "TRUE")]
#[case("b := TOD#12:00:00 > TOD#11:59:59.9;", "b", "TRUE")]
#[case("b := D#2024-01-01 < D#2024-01-02;", "b", "TRUE")]
fn bit_string_and_duration_operators(
    #[case] body: &str,
    #[case] var: &str,
    #[case] expected: &str,
) {
    let decls = "w : WORD := 16#F0F0; y : BYTE; b : BOOL; t : TIME; d : TIME := T#200ms;";
    assert_eq!(eval(decls, body, var), expected);
}

#[rstest]
// Setting bit 3 of 16#00F0 gives 16#00F8; clearing bit 4 gives 16#00E0.
#[case("w : WORD := 16#00F0;", "w.3 := TRUE;", "w", "16#F8")]
#[case("w : WORD := 16#00F0;", "w.4 := FALSE;", "w", "16#E0")]
// The top bit of a BYTE, from a BOOL variable.
#[case("b : BYTE; one : BOOL := TRUE;", "b.7 := one;", "b", "16#80")]
// IL: ST into a bit.
#[case(
    "d : DWORD := 16#FFFFFFFF; f : BOOL;",
    "LD f\nST d.31",
    "d",
    "16#7FFFFFFF"
)]
fn single_bits_of_bit_strings_can_be_assigned(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] var: &str,
    #[case] expected: &str,
) {
    let mut plc = compile(&program("", decls, body));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, var), expected);
}

#[rstest]
// Lower bound 1, filling 2..4 only; i ends one past the limit.
#[case("a : ARRAY[1..5] OF INT; i : INT;", "FOR i := 2 TO 4 DO a[i] := 7; END_FOR;", &[("a[1]", "0"), ("a[2]", "7"), ("a[4]", "7"), ("a[5]", "0"), ("i", "5")])]
// Empty range: nothing written, i keeps its start value.
#[case("a : ARRAY[0..3] OF INT; i : INT;", "FOR i := 5 TO 2 DO a[i] := 7; END_FOR;", &[("a[0]", "0"), ("a[3]", "0"), ("i", "5")])]
// A variable as the value.
#[case("a : ARRAY[0..3] OF INT; i : INT; v : INT := 3;", "FOR i := 0 TO 3 DO a[i] := v; END_FOR;", &[("a[0]", "3"), ("a[3]", "3"), ("i", "4")])]
// Up to the type's maximum: the loop ends and i wraps past it.
#[case("a : ARRAY[120..127] OF SINT; i : SINT;", "FOR i := 120 TO 127 DO a[i] := 1; END_FOR;", &[("a[120]", "1"), ("a[127]", "1"), ("i", "-128")])]
fn for_loops_that_fill_arrays(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] expect: &[(&str, &str)],
) {
    let mut plc = compile(&program("", decls, body));
    run(&mut plc, 1);
    for (name, value) in expect {
        assert_eq!(lit(&plc, name), *value, "{name}");
    }
}

#[test]
fn a_fill_loop_running_off_the_array_writes_up_to_the_bad_index_then_faults() {
    let src = program(
        "",
        "a : ARRAY[0..3] OF INT; i : INT;",
        "FOR i := 2 TO 5 DO a[i] := 9; END_FOR;",
    );
    let mut plc = compile(&src);
    let fault = plc.run_cycle().expect_err("index 4 is out of bounds");
    assert!(
        fault
            .to_string()
            .contains("array index 4 out of bounds [0..3]"),
        "{fault}"
    );
    assert_eq!(lit(&plc, "a[1]"), "0");
    assert_eq!(lit(&plc, "a[2]"), "9");
    assert_eq!(lit(&plc, "a[3]"), "9");
    assert_eq!(lit(&plc, "i"), "4");
}

#[test]
fn configuration_connects_program_parameters_to_globals() {
    // Each run: x is copied in from `source` (or the constant 5), y copied
    // out to `sink` after the program ran.
    let src = "
PROGRAM Doubler
VAR_INPUT x : INT; k : INT; END_VAR
VAR_OUTPUT y : INT; END_VAR
y := x * 2 + k;
END_PROGRAM
CONFIGURATION Cell
  VAR_GLOBAL source : INT := 20; sink : INT; END_VAR
  RESOURCE R ON PLC
    TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM d WITH Fast : Doubler (x := source, k := 5, y => sink);
  END_RESOURCE
END_CONFIGURATION
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "sink"), "45");
    plc.write("source", "1").expect("write source");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "sink"), "7");
    assert_eq!(lit(&plc, "d.y"), "7");
}

/// A variable named like a standard function does not hide the function:
/// a call is not a variable.
#[test]
fn a_variable_named_like_a_standard_function_does_not_hide_it() {
    let plc = run_once(&program(
        "",
        "sel : INT; max : INT; limit : REAL;",
        "sel := SEL(TRUE, 10, 20); max := MAX(3, 9); limit := LIMIT(0.0, 7.5, 5.0);",
    ));
    assert_eq!(lit(&plc, "sel"), "20");
    assert_eq!(lit(&plc, "max"), "9");
    assert_eq!(lit(&plc, "limit"), "5.0");
}

#[test]
fn a_block_held_by_a_structure_reads_a_global_variable() {
    // The block's body is built while the structure's type is resolved,
    // which came before the globals were declared (E201 on `g`), for a
    // structure holding an instance or an array of them.
    let prelude = "VAR_GLOBAL
  g : INT;
  s : STRING := 'x';
END_VAR
FUNCTION_BLOCK FB_Count
VAR_OUTPUT n : INT; END_VAR
g := g + 1;
n := g;
s := CONCAT(s, 'y');
END_FUNCTION_BLOCK
TYPE ST_Holder : STRUCT f : FB_Count; END_STRUCT END_TYPE
TYPE ST_Many : STRUCT a : ARRAY[1..2] OF FB_Count; END_STRUCT END_TYPE";
    let mut plc = compile(&program(
        prelude,
        "h : ST_Holder; m : ST_Many; n : INT; k : INT; t : STRING;",
        "h.f();\nn := h.f.n;\nm.a[2]();\nk := m.a[2].n;\nt := s;",
    ));
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.n"), "5");
    assert_eq!(lit(&plc, "P.k"), "6");
    assert_eq!(lit(&plc, "P.t"), "'xyyyyyy'");
}
