//! Runtime faults (docs/semantics.md §3, docs/cli.md "Exit status"): the PLC
//! stops, and the fault names its kind, `file:line:col` and the cycle --
//! through the embedding API, through a `Session` writing a trace, and
//! through the `plcrun` binary (exit 3).

use crate::support::plc;

use plc::{first_fault, line_col, program};
use plcrun::FaultKind;
use plcrun::{Options, Plc};
use rstest::rstest;
use std::time::{Duration, Instant};

/// Body line 6 (after the empty prelude line) runs `stmt` when the cycle counter `c` reaches 3 (cycle 2).
fn faulty(decls: &str, stmt: &str) -> String {
    program(
        "",
        &format!("c : INT; {decls}"),
        &format!("c := c + 1; IF c = 3 THEN {stmt} END_IF;"),
    )
}

#[rstest]
#[case("a : INT := 7; z : INT;", "a := a / z;", "division by zero")]
#[case("a : DINT := 7; z : DINT;", "a := a MOD z;", "division by zero")]
#[case("a : ULINT := 7; z : ULINT;", "a := a / z;", "division by zero")]
#[case("a : TIME := T#1s; z : INT;", "a := a / z;", "division by zero")]
#[case(
    "v : ARRAY[1..3] OF INT; i : INT := 4;",
    "v[i] := 1;",
    "array index 4 out of bounds [1..3]"
)]
#[case(
    "v : ARRAY[1..3] OF INT; i : INT; x : INT;",
    "x := v[i];",
    "array index 0 out of bounds [1..3]"
)]
#[case(
    "m : ARRAY[0..1, 0..1] OF INT; i : INT := 2; x : INT;",
    "x := m[0, i];",
    "array index 2 out of bounds [0..1]"
)]
#[case(
    "r : REAL := 1.0E10; x : DINT;",
    "x := REAL_TO_DINT(r);",
    "out of the target type's range"
)]
#[case(
    "w : WORD := 16#001A; x : INT;",
    "x := WORD_BCD_TO_INT(w);",
    "invalid BCD"
)]
#[case("k : INT := -1; x : DINT;", "x := 2 ** k;", "negative exponent")]
#[case(
    "k : INT := 7; x : INT;",
    "x := MUX(k, INT#1, INT#2);",
    "MUX selector 7"
)]
fn faults_name_their_kind_place_and_cycle(
    #[case] decls: &str,
    #[case] stmt: &str,
    #[case] message: &str,
) {
    let f = first_fault(&faulty(decls, stmt));
    assert_eq!(f.cycle, 2, "the counter reaches 3 in cycle 2");
    assert!(f.location.starts_with("test.st:"), "{}", f.location);
    let (line, col) = line_col(&f.location);
    assert_eq!(line, 6, "{}", f.location);
    // The column lies inside the faulting statement, which starts after
    // "c := c + 1; IF c = 3 THEN " (26 characters), at column 27.
    assert!(
        (27..27 + stmt.len()).contains(&col),
        "{} for {stmt}",
        f.location
    );
    assert!(
        f.fault.kind.to_string().contains(message),
        "{}",
        f.fault.kind
    );
    let shown = f.to_string();
    assert!(shown.contains("cycle 2"), "{shown}");
    assert!(shown.contains(&f.location), "{shown}");
    assert_eq!(f.pou, "P");
}

#[test]
fn division_by_zero_has_its_own_kind() {
    let f = first_fault(&faulty("a : INT; z : INT;", "a := 1 / z;"));
    assert_eq!(f.fault.kind, FaultKind::DivisionByZero);
    // "c := c + 1; IF c = 3 THEN a := " is 31 characters: `1 / z` is at 32
    assert_eq!(line_col(&f.location), (6, 32));
    let f = first_fault(&faulty(
        "v : ARRAY[1..3] OF INT; i : INT := 9;",
        "v[i] := 0;",
    ));
    assert_eq!(
        f.fault.kind,
        FaultKind::IndexOutOfRange {
            index: 9,
            lo: 1,
            hi: 3
        }
    );
}

#[test]
fn a_fault_inside_a_function_points_into_the_function() {
    let src = "FUNCTION Ratio : INT
VAR_INPUT a, b : INT; END_VAR
Ratio := a / b;
END_FUNCTION
PROGRAM P
VAR x : INT; d : INT; END_VAR
x := Ratio(10, d);
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.cycle, 0);
    assert_eq!(line_col(&f.location).0, 3, "{}", f.location);
    assert_eq!(f.pou, "Ratio");
    assert!(f.excerpt.contains("Ratio := a / b;"), "{}", f.excerpt);
}

#[test]
fn a_fault_inside_a_function_block_instance() {
    let src = "FUNCTION_BLOCK Divider
VAR_INPUT a, b : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := a / b;
END_FUNCTION_BLOCK
PROGRAM P
VAR d : Divider; n : INT; END_VAR
n := n + 1;
d(a := 10, b := 5 - n);
END_PROGRAM";
    // b = 4, 3, 2, 1, 0: the fifth call (cycle 4) divides by zero
    let f = first_fault(src);
    assert_eq!(f.cycle, 4);
    assert_eq!(line_col(&f.location).0, 4, "{}", f.location);
}

#[test]
fn watchdog_stops_an_endless_loop() {
    let src = program("", "x : INT;", "WHILE TRUE DO x := x + 1; END_WHILE;");
    let options = Options {
        watchdog: Some(Duration::from_millis(100)),
        ..Options::default()
    };
    let mut plc = Plc::compile_files(&[("test.st", &src)], &options).unwrap();
    let start = Instant::now();
    let f = plc.run_cycle().expect_err("the loop never ends");
    assert!(start.elapsed() < Duration::from_secs(10));
    assert_eq!(f.fault.kind, FaultKind::Watchdog);
    assert_eq!(f.cycle, 0);
    assert_eq!(line_col(&f.location).0, 6, "{}", f.location);
}

// ---------------------------------------------------------------- session and CLI

use crate::support::cli;
use crate::support::library;

use cli::{plcrun, temp_file};
use library::{TraceRequest, run_csv};
use plcrun::RunError;

/// The trace of the cycles before the fault, which a run still writes.
const ROWS_BEFORE_THE_FAULT: &str = "cycle,time,c\n0,T#0s,1\n1,T#10ms,2\n";

#[rstest]
#[case("div.st", "a : INT := 7; z : INT;", "a := a / z;", "division by zero")]
#[case(
    "mod.st",
    "a : INT := 7; z : INT;",
    "a := a MOD z;",
    "division by zero"
)]
#[case(
    "idx.st",
    "v : ARRAY[1..3] OF INT; i : INT := 4;",
    "v[i] := 1;",
    "out of bounds"
)]
fn a_session_stops_naming_the_place_and_the_cycle(
    #[case] file: &str,
    #[case] decls: &str,
    #[case] stmt: &str,
    #[case] message: &str,
) {
    let request = TraceRequest {
        cycles: 10,
        trace: Some("c"),
        ..TraceRequest::default()
    };
    let (csv, outcome) = run_csv(&[(file, faulty(decls, stmt))], &request);
    let Err(RunError::Fault(fault)) = outcome else {
        panic!("expected a runtime fault, got {outcome:?}");
    };
    // What the command line prints after `error: `.
    let shown = fault.to_string();
    assert!(shown.contains(&format!("{file}:6:")), "{shown}");
    assert!(shown.contains("cycle 2"), "{shown}");
    assert!(shown.contains(message), "{shown}");
    // The rows of the cycles before the fault are written.
    assert_eq!(csv, ROWS_BEFORE_THE_FAULT);
}

#[test]
fn cli_exits_3_naming_the_place_and_the_cycle() {
    let path = temp_file("div.st", faulty("a : INT := 7; z : INT;", "a := a / z;"));
    let (code, stdout, stderr) =
        plcrun(&[&path, "--cycles", "10", "--trace", "c", "--format", "csv"]);
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains(&format!("{path}:6:")), "{stderr}");
    assert!(stderr.contains("cycle 2"), "{stderr}");
    assert!(stderr.contains("division by zero"), "{stderr}");
    assert_eq!(stdout, ROWS_BEFORE_THE_FAULT);
}

#[test]
fn cli_watchdog_stops_an_endless_loop_with_exit_3() {
    let path = temp_file(
        "loop.st",
        program("", "x : INT;", "WHILE TRUE DO x := x + 1; END_WHILE;"),
    );
    let start = Instant::now();
    let (code, _, stderr) = plcrun(&[&path, "--cycles", "5", "--watchdog", "100ms"]);
    assert!(start.elapsed() < Duration::from_secs(20));
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("watchdog"), "{stderr}");
    assert!(stderr.contains(&format!("{path}:6:")), "{stderr}");
    assert!(stderr.contains("cycle 0"), "{stderr}");
}
