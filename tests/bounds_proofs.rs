//! Bounds checks the compiler proves unnecessary are removed: inside
//! `FOR i := a TO b BY k` with constants, `arr[i]` needs no index check
//! when `a..b` lies inside the array and the body cannot change `i`
//! (docs/performance.md). Everything else keeps its check and faults.

use crate::support::plc;

use plc::{compile, lit, program, run};
use plcrun::Plc;

/// How many element accesses of each kind the program's blocks hold:
/// (checked, proved in range).
fn accesses(plc: &Plc) -> (usize, usize) {
    let count = |name| {
        plc.image()
            .instruction_count(name)
            .expect("an instruction name")
    };
    (
        count("LoadElem") + count("StoreElem"),
        count("LoadElemU") + count("StoreElemU"),
    )
}

#[test]
fn a_loop_over_the_array_range_runs_without_index_checks() {
    let src = program(
        "",
        "a : ARRAY[1..10] OF DINT; b : ARRAY[-5..20] OF DINT; i : INT; s : DINT;",
        "FOR i := 1 TO 10 DO a[i] := i * i; b[i] := a[i] + 1; END_FOR;
         FOR i := 10 TO 1 BY -3 DO s := s + a[i] + b[i]; END_FOR;",
    );
    let mut plc = compile(&src);
    assert_eq!(accesses(&plc), (0, 5));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "a[10]"), "100");
    assert_eq!(lit(&plc, "b[3]"), "10");
    assert_eq!(lit(&plc, "b[11]"), "0");
    // i = 10, 7, 4, 1: (100 + 101) + (49 + 50) + (16 + 17) + (1 + 2)
    assert_eq!(lit(&plc, "s"), "336");
    assert_eq!(lit(&plc, "i"), "-2");
}

#[test]
fn an_fb_body_loop_over_its_own_array_is_proved_too() {
    let prelude = "FUNCTION_BLOCK Acc
VAR_INPUT x : REAL; END_VAR
VAR_OUTPUT total : REAL; END_VAR
VAR hist : ARRAY[0..3] OF REAL; k : INT; END_VAR
FOR k := 3 TO 1 BY -1 DO hist[k] := hist[k - 1]; END_FOR;
hist[0] := x;
total := 0.0;
FOR k := 0 TO 3 DO total := total + hist[k]; END_FOR;
END_FUNCTION_BLOCK";
    let src = program(prelude, "f : Acc; n : REAL;", "n := n + 1.0; f(x := n);");
    let mut plc = compile(&src);
    // hist[k - 1] has a computed index: checked; hist[k] in both loops is
    // proved (hist[0] is a plain slot).
    assert_eq!(accesses(&plc), (1, 2));
    run(&mut plc, 5);
    // The last four inputs: 5 + 4 + 3 + 2.
    assert_eq!(lit(&plc, "f.total"), "14.0");
}

#[test]
fn a_range_reaching_past_the_array_keeps_the_check_and_faults() {
    let src = program(
        "",
        "a : ARRAY[0..9] OF INT; i : INT;",
        "FOR i := 0 TO 10 DO a[i] := 1; a[i] := a[i] + i; END_FOR;",
    );
    let mut plc = compile(&src);
    assert_eq!(accesses(&plc), (3, 0));
    let f = plc.run_cycle().expect_err("a[10] is outside the array");
    assert!(
        f.fault
            .kind
            .to_string()
            .contains("array index 10 out of bounds [0..9]"),
        "{f}"
    );
    assert_eq!(lit(&plc, "a[9]"), "10");
}

#[test]
fn a_body_that_can_change_the_index_keeps_the_check() {
    // `Jump` moves the index through VAR_IN_OUT: the loop bound proves
    // nothing about the value seen after the call.
    let prelude = "FUNCTION Jump : BOOL
VAR_IN_OUT k : INT; END_VAR
k := k + 7;
Jump := TRUE;
END_FUNCTION";
    let src = program(
        prelude,
        "a : ARRAY[0..9] OF INT; i : INT; ok : BOOL;",
        "FOR i := 0 TO 9 DO a[i] := 1; ok := Jump(k := i); a[i] := 2; END_FOR;",
    );
    let mut plc = compile(&src);
    assert_eq!(accesses(&plc), (2, 0));
    // i = 0: a[0] := 1, i becomes 7, a[7] := 2; next i = 8: a[8] := 1,
    // i becomes 15, a[15] faults.
    let f = plc.run_cycle().expect_err("a[15] is outside the array");
    assert!(
        f.fault
            .kind
            .to_string()
            .contains("array index 15 out of bounds [0..9]"),
        "{f}"
    );
    assert_eq!(lit(&plc, "a[7]"), "2");
    assert_eq!(lit(&plc, "a[8]"), "1");
}

#[test]
fn a_loop_with_a_variable_bound_keeps_the_check() {
    let src = program(
        "",
        "a : ARRAY[0..9] OF INT; i : INT; n : INT := 12;",
        "FOR i := 0 TO n DO a[i] := i; END_FOR;",
    );
    let mut plc = compile(&src);
    assert_eq!(accesses(&plc), (1, 0));
    assert!(plc.run_cycle().is_err());
}
