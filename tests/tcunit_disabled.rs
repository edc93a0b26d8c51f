//! TcUnit's disabled tests (issue #25, point 3): a test whose name starts
//! with `DISABLED_` (any case) is declared without the prefix and skipped,
//! as TcUnit does: its assertions are ignored, it does not hold its suite
//! open, and reports show it skipped (JUnit `<skipped/>`), not failed.

use plcrun::{SourceMap, TestOptions, TestOutcome, run_tests};

#[test]
fn a_disabled_test_is_skipped_and_its_assertions_are_ignored() {
    let suite = "FUNCTION_BLOCK FB_Disabled EXTENDS FB_TestSuite
TEST('  DISABLED_ThisShouldNotExecute ');
AssertEquals_BOOL(Expected := FALSE, Actual := TRUE, Message := 'A does not equal B');
TEST('disabled_NeverFinished');
TEST(' Runs ');
AssertTrue(TRUE, 'runs');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let mut sources = SourceMap::new();
    sources.add("suite.st", suite);
    sources.add(
        "main.st",
        "PROGRAM PRG_TEST\nVAR s : FB_Disabled; END_VAR\ns();\nEND_PROGRAM\n",
    );
    let report = run_tests(&sources, &TestOptions::default()).expect("compiles");
    let verdicts: Vec<(String, TestOutcome, u64)> = report
        .cases
        .iter()
        .map(|c| (c.full_name(), c.outcome(), c.cycles))
        .collect();
    // The names lose their blanks and the prefix; the run ends after one
    // cycle, the skipped tests never finishing.
    assert_eq!(
        verdicts,
        [
            (
                "PRG_TEST.s.ThisShouldNotExecute".into(),
                TestOutcome::Skipped,
                1
            ),
            ("PRG_TEST.s.NeverFinished".into(), TestOutcome::Skipped, 1),
            ("PRG_TEST.s.Runs".into(), TestOutcome::Passed, 1),
        ]
    );
    assert!(report.all_passed());
    assert!(report.cases[0].failures.is_empty());
    let junit = report.to_junit("plcrun");
    assert!(junit.contains("skipped=\"2\""), "{junit}");
    assert!(junit.contains("<skipped/>"), "{junit}");
    let text = report.to_text();
    assert!(text.contains("SKIP  PRG_TEST.s.NeverFinished"), "{text}");
    assert!(
        text.contains("3 tests: 1 passed, 0 failed, 0 errored, 2 skipped in "),
        "{text}"
    );
}
