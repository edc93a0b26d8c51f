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

#[test]
fn two_strings_of_other_lengths_are_reported_by_their_lengths_as_tcunit_does() {
    // TcUnit's AssertEquals(ANY, ANY) compares sizes first (a string's is
    // its length): other lengths print `(Data size (LEN) = n)`, one length
    // the two texts; AssertEquals_STRING always the texts.
    let suite = twincat::pou(
        "FB_Str",
        "FUNCTION_BLOCK FB_Str EXTENDS FB_TestSuite\nVAR a : STRING := 'This is a string'; \
         b : STRING := 'This is another string'; c : STRING := 'This is b string'; \
         w : WSTRING := \"ab\"; x : WSTRING := \"abc\"; END_VAR",
        "TEST('Lengths');\nAssertEquals(Expected := a, Actual := b, Message := 'Values differ');\nTEST_FINISHED();\n\
         TEST('Texts');\nAssertEquals(Expected := a, Actual := c, Message := 'Values differ');\nTEST_FINISHED();\n\
         TEST('Wide');\nAssertEquals(Expected := w, Actual := x, Message := 'Values differ');\nTEST_FINISHED();\n\
         TEST('Typed');\nAssertEquals_STRING(Expected := a, Actual := b, Message := 'Values differ');\nTEST_FINISHED();\n\
         TEST('Same');\nAssertEquals(Expected := a, Actual := a, Message := 'Values differ');\nTEST_FINISHED();",
        "",
    );
    let mut sources = SourceMap::new();
    sources.add("FB_Str.TcPOU", suite);
    sources.add(
        "main.st",
        "PROGRAM PRG_TEST\nVAR s : FB_Str; END_VAR\ns();\nEND_PROGRAM\n",
    );
    let report = run_tests(&sources, &TestOptions::default()).expect("compiles");
    let shown = |i: usize| {
        let f = &report.cases[i].failures[0];
        (f.expected.clone(), f.actual.clone())
    };
    let pair = |e: &str, a: &str| (e.to_string(), a.to_string());
    assert_eq!(
        shown(0),
        pair("'(Data size (LEN) = 16)'", "'(Data size (LEN) = 22)'")
    );
    assert_eq!(shown(1), pair("'This is a string'", "'This is b string'"));
    assert_eq!(
        shown(2),
        pair("'(Data size (WLEN) = 2)'", "'(Data size (WLEN) = 3)'")
    );
    assert_eq!(
        shown(3),
        pair("'This is a string'", "'This is another string'")
    );
    assert_eq!(report.cases[4].outcome(), TestOutcome::Passed);
}

#[test]
fn tcunit_shows_a_failing_ltime_as_twincat_s_unsigned_duration() {
    // TwinCAT's LTIME is unsigned: its largest value is no `LT#-1ns` in a
    // TcUnit message, whichever assertion compares it.
    let suite = twincat::pou(
        "FB_Lt",
        "FUNCTION_BLOCK FB_Lt EXTENDS FB_TestSuite\nVAR big : LTIME := LTIME#213503D23H34M33S709MS551US615NS; \
         small : LTIME := LTIME#1000D; a : ARRAY[1..2] OF LTIME := [LTIME#1S, LTIME#213503D23H34M33S709MS551US615NS]; \
         b : ARRAY[1..2] OF LTIME := [LTIME#1S, LTIME#2S]; END_VAR",
        "TEST('Typed');\nAssertEquals_LTIME(Expected := big, Actual := small, Message := 'differ');\nTEST_FINISHED();\n\
         TEST('Any');\nAssertEquals(Expected := small, Actual := big, Message := 'differ');\nTEST_FINISHED();\n\
         TEST('Array');\nAssertArrayEquals_LTIME(Expecteds := a, Actuals := b, Message := 'differ');\nTEST_FINISHED();",
        "",
    );
    let mut sources = SourceMap::new();
    sources.add("FB_Lt.TcPOU", suite);
    sources.add(
        "main.st",
        "PROGRAM PRG_TEST\nVAR s : FB_Lt; END_VAR\ns();\nEND_PROGRAM\n",
    );
    let report = run_tests(&sources, &TestOptions::default()).expect("compiles");
    let shown = |i: usize| {
        let f = &report.cases[i].failures[0];
        (f.expected.clone(), f.actual.clone())
    };
    let max = "LT#213503d23h34m33s709ms551us615ns".to_string();
    let small = "LT#1000d".to_string();
    assert_eq!(shown(0), (max.clone(), small.clone()));
    assert_eq!(shown(1), (small, max.clone()));
    assert_eq!(shown(2), (max, "LT#2s".to_string()));
}
