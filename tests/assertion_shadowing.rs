//! A user POU named like one of `plcrun test`'s assertions: the user's
//! definition wins (TcUnit projects bring their own `AssertTrue`,
//! `AssertEquals`, ... in a library), and a warning, W484, says so under
//! `plcrun test` — in the report (library) and on standard error (CLI).
//! Outside `plcrun test` the name is an ordinary POU name.

use crate::support::cli;

use cli::{plcrun, temp_file};
use plcrun::{CheckOptions, SourceMap, TestOptions, TestOutcome, check, run_tests};

const SRC: &str = "FUNCTION AssertTrue : BOOL
VAR_INPUT Condition : BOOL; Message : STRING; END_VAR
AssertTrue := Condition;
count := count + 1;
END_FUNCTION
VAR_GLOBAL count : INT; END_VAR
PROGRAM TEST_shadow
AssertTrue(FALSE, 'this AssertTrue records nothing');
AssertEquals(1, count, 'this AssertTrue ran');
END_PROGRAM
";

fn sources() -> SourceMap {
    let mut s = SourceMap::new();
    s.add("t.st", SRC);
    s
}

#[test]
fn the_users_function_runs_and_the_report_carries_w484() {
    let r = run_tests(&sources(), &TestOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.cases[0].outcome(), TestOutcome::Passed, "{}", r.to_text());
    let w: Vec<String> = r
        .warnings
        .iter()
        .map(|d| format!("{} {}", d.code, sources().location(d.span)))
        .collect();
    assert_eq!(w, ["W484 t.st:1:10"]);
}

#[test]
fn plcrun_test_prints_w484_on_standard_error() {
    let file = temp_file("shadow_test.st", SRC);
    let (code, out, err) = plcrun(&["test", &file]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        err.contains(
            "warning[W484]: FUNCTION `AssertTrue` has the name of a plcrun test assertion"
        ),
        "{err}"
    );
    assert!(out.contains("PASS  TEST_shadow"), "{out}");
}

#[test]
fn outside_plcrun_test_the_name_is_an_ordinary_name() {
    let mut s = SourceMap::new();
    s.add(
        "t.st",
        "FUNCTION AssertTrue : BOOL VAR_INPUT c : BOOL; END_VAR AssertTrue := c; END_FUNCTION",
    );
    let report = check(&s, &CheckOptions::default());
    assert!(report.diagnostics.is_empty(), "{:?}", report.diagnostics);
}
