//! `plcrun test` reports the sources' errors as `plcrun check` does: a
//! syntax error in one file does not hide the checker's errors in the
//! others (it used to stop at the parse errors), and the runner's own
//! E483 comes with them.

use crate::support::cli;

use cli::{plcrun, temp_file};
use plcrun::{SourceMap, TestError, TestOptions, run_tests};

const BROKEN: &str = "PROGRAM TEST_a\nVAR x : INT; END_VAR\nx := ;\nEND_PROGRAM\n";
const UNDECLARED: &str = "PROGRAM TEST_b\nVAR y : INT; END_VAR\ny := undeclared + 1;\nAssertEquals(1, y);\nEND_PROGRAM\n";
const CYCLES: &str =
    "PROGRAM TEST_c\nVAR CONSTANT N : INT := 3; TEST_CYCLES : INT := N; END_VAR\nEND_PROGRAM\n";

fn error_lines(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with("error[")).collect()
}

#[test]
fn every_files_errors_are_reported_after_a_syntax_error() {
    let mut sources = SourceMap::new();
    sources.add("a.st", BROKEN);
    sources.add("b.st", UNDECLARED);
    sources.add("c.st", CYCLES);
    let Err(TestError::Compile(e)) = run_tests(&sources, &TestOptions::default()) else {
        panic!("expected compile errors");
    };
    let got: Vec<String> = e
        .diagnostics
        .iter()
        .map(|d| format!("{} {}", d.code, e.sources.location(d.span)))
        .collect();
    assert_eq!(got, ["E101 a.st:3:6", "E201 b.st:3:6", "E483 c.st:2:28"]);
}

#[test]
fn plcrun_test_prints_the_errors_check_prints() {
    let a = temp_file("a.st", BROKEN);
    let b = temp_file("b.st", UNDECLARED);
    let (check_code, _, check_err) = plcrun(&["check", &a, &b]);
    let (test_code, _, test_err) = plcrun(&["test", &a, &b]);
    assert_eq!((check_code, test_code), (1, 1));
    let check = error_lines(&check_err);
    // `check` does not know the assertions; `test` does.
    let check: Vec<&str> = check
        .into_iter()
        .filter(|l| !l.contains("AssertEquals"))
        .collect();
    assert_eq!(check.len(), 2, "{check_err}");
    assert_eq!(error_lines(&test_err), check, "{test_err}");
}
