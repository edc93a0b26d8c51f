//! TcUnit's `AssertEquals(ANY, ANY)` given values of two types, and
//! TwinCAT's largest LTIME, as TcUnit's own verifier uses them (issue #25,
//! point 3): the suite compiles (W480, W022) and the assertions behave as
//! in TcUnit.

use crate::support::twincat;
use plcrun::{SourceMap, TestOptions, TestOutcome, run_tests};

#[test]
fn values_of_two_types_fail_when_the_assertion_runs_naming_their_type_classes() {
    let suite = twincat::pou(
        "FB_Any",
        "FUNCTION_BLOCK FB_Any EXTENDS FB_TestSuite\nVAR a : INT := 5; b : UINT := 5; END_VAR",
        "TEST('Differ_DataType');\nAssertEquals(Expected := a, Actual := b, Message := 'Values differ');\nTEST_FINISHED();\n\
         TEST('LTIME_Max');\nAssertEquals_LTIME(Expected := LTIME#213503D23H34M33S709MS551US615NS,\n    Actual := LTIME#213503d23h34m33s709ms551us615ns, Message := 'same bits');\n\
         AssertFalse(LTIME#213503D23H34M33S709MS551US615NS = LTIME#1000D, 'differ');\nTEST_FINISHED();",
        "",
    );
    let mut sources = SourceMap::new();
    sources.add("FB_Any.TcPOU", suite);
    sources.add(
        "main.st",
        "PROGRAM PRG_TEST\nVAR s : FB_Any; END_VAR\ns();\nEND_PROGRAM\n",
    );
    let report = run_tests(&sources, &TestOptions::default()).expect("compiles");
    let codes: Vec<&str> = report.warnings.iter().map(|d| d.code).collect();
    assert!(
        codes.contains(&"W480") && codes.contains(&"W022"),
        "{codes:?}"
    );
    let differ = &report.cases[0];
    assert_eq!(differ.outcome(), TestOutcome::Failed);
    let f = &differ.failures[0];
    assert_eq!(
        (f.expected.as_str(), f.actual.as_str(), f.message.as_str()),
        (
            "'(Type class = INT)'",
            "'(Type class = UINT)'",
            "Values differ"
        )
    );
    assert_eq!(
        report.cases[1].outcome(),
        TestOutcome::Passed,
        "{:?}",
        report.cases[1]
    );
}

#[test]
fn the_largest_twincat_ltime_is_out_of_range_in_an_iec_file() {
    let src =
        "PROGRAM P VAR t : LTIME := LTIME#213503D23H34M33S709MS551US615NS; END_VAR END_PROGRAM";
    let codes = crate::support::plc::error_codes(&[("p.st", src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E006"),
        "{codes:?}"
    );
}
