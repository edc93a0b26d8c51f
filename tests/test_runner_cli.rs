//! `plcrun test` on the command line (docs/testing.md, docs/cli.md): text
//! report, `--junit`, `--filter`, options and exit statuses.

use crate::support::cli;

use cli::{plcrun, temp_file};

const TESTS: &str = "FUNCTION Half : INT VAR_INPUT x : INT; END_VAR Half := x / 2; END_FUNCTION
PROGRAM TEST_Half_even AssertEquals(INT#2, Half(4), 'four'); END_PROGRAM
PROGRAM TEST_Half_odd AssertEquals(INT#2, Half(5), 'rounds down'); AssertEquals(INT#3, Half(5), 'rounds up?'); END_PROGRAM
PROGRAM TEST_Half_zero VAR z : INT; END_VAR z := 1 / z; END_PROGRAM
";

#[test]
fn the_seed_programs_st_tests_pass() {
    for (prog, tests) in [
        ("programs/comparator.st", "tests/plc/comparator_test.st"),
        ("programs/cmd_monitor.st", "tests/plc/cmd_monitor_test.st"),
    ] {
        let (code, out, err) = plcrun(&["test", prog, tests]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(out.contains(" 0 failed, 0 errored"), "{out}");
    }
}

#[test]
fn failures_and_faults_give_status_1_with_text_and_junit() {
    let src = temp_file("half_test.st", TESTS);
    let junit = temp_file("report.xml", "");
    let (code, out, _) = plcrun(&["test", &src, "--junit", &junit]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("PASS  TEST_Half_even ("), "{out}");
    assert!(out.contains("FAIL  TEST_Half_odd ("), "{out}");
    assert!(
        out.contains("half_test.st:3:68: cycle 0: expected 3, actual 2: rounds up?\n"),
        "{out}"
    );
    assert!(out.contains("ERROR TEST_Half_zero ("), "{out}");
    assert!(
        out.contains("error[R001]: runtime fault in cycle 0 at "),
        "{out}"
    );
    assert!(
        out.contains("3 tests: 1 passed, 1 failed, 1 errored in "),
        "{out}"
    );
    let xml = std::fs::read_to_string(&junit).expect("junit written");
    assert!(
        xml.contains("tests=\"3\" failures=\"1\" errors=\"1\""),
        "{xml}"
    );
    assert!(
        xml.contains("expected 3, actual 2: rounds up?\" type=\"AssertionFailure\">"),
        "{xml}"
    );
    assert!(xml.contains("type=\"R001\">"), "{xml}");
}

#[test]
fn filter_and_all_passing_give_status_0() {
    let src = temp_file("half_test.st", TESTS);
    let (code, out, err) = plcrun(&["test", &src, "--filter", "EVEN"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.starts_with("PASS  TEST_Half_even"), "{out}");
    assert!(out.contains("1 test: 1 passed"), "{out}");
}

#[test]
fn compile_errors_no_tests_and_usage_errors() {
    let bad = temp_file(
        "bad.st",
        "PROGRAM TEST_X VAR i : INT; d : DINT; END_VAR AssertEquals(i, d); END_PROGRAM",
    );
    let (code, _, err) = plcrun(&["test", &bad]);
    assert_eq!(code, 1);
    assert!(err.contains("error[E480]"), "{err}");
    let none = temp_file("none.st", "PROGRAM Main END_PROGRAM");
    let (code, _, err) = plcrun(&["test", &none]);
    assert_eq!(code, 1);
    assert!(err.contains("no test found"), "{err}");
    let src = temp_file("half_test.st", TESTS);
    assert_eq!(plcrun(&["test", &src, "--cycle-time", "0ms"]).0, 2);
    assert_eq!(plcrun(&["test", &src, "--watchdog", "soon"]).0, 2);
    assert_eq!(plcrun(&["test", "/nonexistent/file.st"]).0, 2);
    assert_eq!(plcrun(&["test"]).0, 2);
}

#[test]
fn cycle_time_and_watchdog_options() {
    // 5 cycles of 20 ms: the clock reads 80 ms in the last one.
    let src = temp_file(
        "clock_test.st",
        "PROGRAM TEST_Clock VAR CONSTANT TEST_CYCLES : INT := 5; END_VAR VAR n : INT; END_VAR
           n := n + 1;
           IF n = 5 THEN AssertEquals(T#80ms, PLC_CLOCK(), 'clock'); END_IF
         END_PROGRAM
         PROGRAM TEST_Spin VAR x : INT; END_VAR WHILE TRUE DO x := x + 1; END_WHILE END_PROGRAM",
    );
    let (code, out, _) = plcrun(&["test", &src, "--cycle-time", "20ms", "--watchdog", "50ms"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("PASS  TEST_Clock (") && out.contains("5 cycles"),
        "{out}"
    );
    assert!(
        out.contains("ERROR TEST_Spin (") && out.contains("error[R008]"),
        "{out}"
    );
}

#[test]
fn check_accepts_the_assertions_of_sources_that_hold_tests() {
    // `plcrun check` compiles test sources as `plcrun test` does: the
    // assertions are declared (the test file and the program it tests).
    let (code, _, err) = plcrun(&[
        "check",
        "programs/comparator.st",
        "tests/plc/comparator_test.st",
    ]);
    assert_eq!((code, err.as_str()), (0, "ok: 2 files checked\n"));
    let file = temp_file("half_test.st", TESTS);
    let (code, _, err) = plcrun(&["check", &file]);
    assert_eq!((code, err.as_str()), (0, "ok: 1 file checked\n"));
    // Without a TEST_ POU the assertions are unknown functions, as before.
    let plain = temp_file(
        "plain.st",
        "PROGRAM P\nAssertEquals(INT#1, INT#1, 'x');\nEND_PROGRAM\n",
    );
    let (code, _, err) = plcrun(&["check", &plain]);
    assert_eq!(code, 1);
    assert!(
        err.contains("E201") && err.contains("AssertEquals"),
        "{err}"
    );
}
