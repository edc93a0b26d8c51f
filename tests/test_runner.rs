//! The unit-test runner (`plcrun::run_tests`, docs/testing.md): the
//! convention, every assertion, failures with their location and values,
//! faults, reports, and the seed programs' own ST tests.

use plcrun::{SourceMap, TestError, TestOptions, TestOutcome, TestReport, run_tests};
use std::time::Duration;

fn run(files: &[(&str, &str)]) -> Result<TestReport, TestError> {
    run_with(files, &TestOptions::default())
}

fn run_with(files: &[(&str, &str)], options: &TestOptions) -> Result<TestReport, TestError> {
    let mut sources = SourceMap::new();
    for (name, text) in files {
        sources.add(*name, *text);
    }
    run_tests(&sources, options)
}

fn report(text: &str) -> TestReport {
    match run(&[("t.st", text)]) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    }
}

/// The compile error codes of a source that must not compile.
fn compile_errors(text: &str) -> Vec<String> {
    match run(&[("t.st", text)]) {
        Err(TestError::Compile(e)) => e.diagnostics.iter().map(|d| d.code.to_string()).collect(),
        other => panic!("expected a compile error, got {other:?}"),
    }
}

fn file(path: &str) -> String {
    std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).expect("readable")
}

#[test]
fn a_passing_program_test() {
    let r = report(
        "PROGRAM TEST_Sum VAR s : INT; END_VAR
           s := 2 + 3;
           AssertEquals(INT#5, s, 'sum');
           AssertTrue(s > 4, 'greater');
           AssertFalse(s > 5, 'not greater');
         END_PROGRAM",
    );
    assert_eq!(r.cases.len(), 1);
    let c = &r.cases[0];
    assert_eq!((c.name.as_str(), c.file.as_str()), ("TEST_Sum", "t.st"));
    assert_eq!(c.outcome(), TestOutcome::Passed);
    assert_eq!(c.cycles, 1);
    assert!(r.all_passed());
    assert!(r.to_text().starts_with("PASS  TEST_Sum (t.st, 1 cycle)\n"));
    assert!(
        r.to_text()
            .contains("1 test: 1 passed, 0 failed, 0 errored in ")
    );
}

#[test]
fn a_failing_test_reports_every_failure_with_location_values_message_and_cycle() {
    let r = report(
        "PROGRAM TEST_Fail VAR n : INT; END_VAR
  VAR CONSTANT TEST_CYCLES : INT := 3; END_VAR
  n := n + 1;
  AssertEquals(INT#2, n, 'n is two');
  AssertTrue(n < 3, 'n stays small');
END_PROGRAM",
    );
    let c = &r.cases[0];
    assert_eq!(c.outcome(), TestOutcome::Failed);
    assert_eq!(c.cycles, 3, "a failure does not stop the test");
    let got: Vec<_> = c
        .failures
        .iter()
        .map(|f| {
            format!(
                "{} {} {} {} {}",
                f.location, f.cycle, f.expected, f.actual, f.message
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            "t.st:4:3 0 2 1 n is two",
            "t.st:4:3 2 2 3 n is two",
            "t.st:5:3 2 TRUE FALSE n stays small",
        ]
    );
    let text = r.to_text();
    assert!(
        text.starts_with("FAIL  TEST_Fail (t.st, 3 cycles)\n"),
        "{text}"
    );
    assert!(
        text.contains("      t.st:4:3: cycle 0: expected 2, actual 1: n is two\n"),
        "{text}"
    );
    assert!(text.contains("1 test: 0 passed, 1 failed, 0 errored"));
    assert!(!r.all_passed());
}

#[test]
fn assert_equals_covers_every_elementary_type() {
    // (type, a value, another value); one passing and one failing call each.
    let cases = [
        ("BOOL", "TRUE", "FALSE"),
        ("SINT", "SINT#-5", "SINT#6"),
        ("INT", "INT#-300", "INT#301"),
        ("DINT", "DINT#70000", "DINT#-70001"),
        ("LINT", "LINT#-5000000000", "LINT#5000000001"),
        ("USINT", "USINT#200", "USINT#201"),
        ("UINT", "UINT#60000", "UINT#60001"),
        ("UDINT", "UDINT#4000000000", "UDINT#1"),
        ("ULINT", "ULINT#18000000000000000000", "ULINT#2"),
        ("BYTE", "BYTE#16#A5", "BYTE#16#5A"),
        ("WORD", "WORD#16#BEEF", "WORD#16#CAFE"),
        ("DWORD", "DWORD#16#DEADBEEF", "DWORD#0"),
        ("LWORD", "LWORD#16#0123456789ABCDEF", "LWORD#1"),
        ("REAL", "REAL#1.5", "REAL#2.5"),
        ("LREAL", "LREAL#-0.25", "LREAL#0.75"),
        ("TIME", "T#1s", "T#2s"),
        ("LTIME", "LTIME#5ms", "LTIME#6ms"),
        ("DATE", "D#2024-01-02", "D#2024-01-03"),
        ("LDATE", "LDATE#2024-01-02", "LDATE#2025-01-02"),
        ("TOD", "TOD#12:00:00", "TOD#12:00:01"),
        ("LTOD", "LTOD#01:02:03", "LTOD#01:02:04"),
        ("DT", "DT#2024-01-02-03:04:05", "DT#2024-01-02-03:04:06"),
        ("LDT", "LDT#2024-01-02-03:04:05", "LDT#2024-01-02-03:04:07"),
        ("CHAR", "CHAR#'a'", "CHAR#'b'"),
        ("WCHAR", "WCHAR#\"a\"", "WCHAR#\"b\""),
        ("STRING", "'abc'", "'abd'"),
        ("WSTRING", "\"abc\"", "\"abd\""),
    ];
    let mut vars = String::new();
    let mut body = String::new();
    for (i, (ty, a, b)) in cases.iter().enumerate() {
        vars.push_str(&format!("v{i} : {ty} := {a};\n"));
        body.push_str(&format!("AssertEquals({a}, v{i}, '{ty} same');\n"));
        body.push_str(&format!("AssertEquals({b}, v{i}, '{ty} differs');\n"));
    }
    let src = format!("PROGRAM TEST_Types VAR\n{vars}END_VAR\n{body}END_PROGRAM\n");
    let r = report(&src);
    let c = &r.cases[0];
    assert_eq!(c.failures.len(), cases.len(), "{}", r.to_text());
    for (f, (ty, _, _)) in c.failures.iter().zip(cases.iter()) {
        assert_eq!(f.message, format!("{ty} differs"));
        assert_ne!(f.expected, f.actual);
    }
    let by_type = |ty: &str| {
        let f = c
            .failures
            .iter()
            .find(|f| f.message == format!("{ty} differs"))
            .unwrap();
        (f.expected.clone(), f.actual.clone())
    };
    assert_eq!(by_type("BOOL"), ("FALSE".into(), "TRUE".into()));
    assert_eq!(by_type("STRING"), ("'abd'".into(), "'abc'".into()));
    assert_eq!(by_type("TIME"), ("T#2s".into(), "T#1s".into()));
}

#[test]
fn untyped_literals_take_the_other_values_type() {
    let r = report(
        "PROGRAM TEST_Lit VAR b : BYTE := 7; r : REAL := 0.5; END_VAR
           AssertEquals(7, b, 'byte');
           AssertEquals(r, 0.5, 'real');
           AssertEquals(3, 4, 'two literals');
         END_PROGRAM",
    );
    let f = &r.cases[0].failures;
    assert_eq!(f.len(), 1);
    assert_eq!((f[0].expected.as_str(), f[0].actual.as_str()), ("3", "4"));
}

#[test]
fn mismatched_types_are_compile_errors() {
    let prog = |call: &str| {
        format!(
            "PROGRAM TEST_Bad VAR i : INT; d : DINT; r : REAL; s : STRING;
               a : ARRAY[1..3] OF INT; a0 : ARRAY[0..2] OF INT; ad : ARRAY[1..3] OF DINT; END_VAR
             {call};
             END_PROGRAM"
        )
    };
    assert_eq!(compile_errors(&prog("AssertEquals(i, d, 'x')")), ["E480"]);
    assert_eq!(compile_errors(&prog("AssertEquals(r, i)")), ["E480"]);
    assert_eq!(compile_errors(&prog("AssertEquals(s, i, 'x')")), ["E480"]);
    assert_eq!(compile_errors(&prog("AssertEquals(a, a, 'x')")), ["E480"]);
    assert_eq!(
        compile_errors(&prog("AssertArrayEquals(a, a0, 'x')")),
        ["E482"]
    );
    assert_eq!(
        compile_errors(&prog("AssertArrayEquals(a, ad, 'x')")),
        ["E482"]
    );
    assert_eq!(
        compile_errors(&prog("AssertArrayEquals(i, i, 'x')")),
        ["E482"]
    );
    assert_eq!(compile_errors(&prog("AssertEquals(i)")), ["E481"]);
    assert_eq!(compile_errors(&prog("AssertTrue(Cond := TRUE)")), ["E481"]);
    // A fixed-type assertion checks its arguments as any function does.
    assert!(!compile_errors(&prog("AssertEquals_REAL(s, r, 0.1, 'x')")).is_empty());
    assert!(!compile_errors(&prog("AssertTrue(i, 'x')")).is_empty());
}

#[test]
fn assertions_exist_only_in_test_mode() {
    let src = "PROGRAM P VAR x : INT; END_VAR AssertTrue(x = 0); END_PROGRAM";
    let Err(err) = plcrun::Plc::compile_files(&[("p.st", src)], &plcrun::Options::default()) else {
        panic!("AssertTrue is unknown outside plcrun test");
    };
    assert!(err.diagnostics.iter().any(|d| d.code == "E201"), "{err}");
}

#[test]
fn real_and_lreal_with_a_delta() {
    let r = report(
        "PROGRAM TEST_Near VAR r : REAL := 1.0; l : LREAL := 2.0; END_VAR
           AssertEquals_REAL(1.05, r, 0.1, 'close');
           AssertEquals_REAL(Expected := 1.5, Actual := r, Delta := 0.1, Message := 'far');
           AssertEquals_LREAL(2.0000001, l, 0.000001, 'close');
           AssertEquals_LREAL(2.1, l, 0.01, 'far');
           AssertEquals_REAL(1.0, r / 0.0, 1.0E30, 'inf');
         END_PROGRAM",
    );
    let f = &r.cases[0].failures;
    let got: Vec<_> = f
        .iter()
        .map(|f| format!("{} {} {} {}", f.location, f.expected, f.actual, f.message))
        .collect();
    assert_eq!(
        got,
        [
            "t.st:3:12 1.5 1.0 far",
            "t.st:5:12 2.1 2.0 far",
            "t.st:6:12 1.0 INF inf"
        ],
        "{}",
        r.to_text()
    );
}

#[test]
fn assert_array_equals_reports_each_differing_element() {
    let r = report(
        "PROGRAM TEST_Arr
           VAR a : ARRAY[-1..2] OF INT := [1, 2, 3, 4]; b : ARRAY[-1..2] OF INT := [1, 5, 3, 6];
               c : ARRAY[-1..2] OF INT := [1, 2, 3, 4]; END_VAR
           AssertArrayEquals(a, c, 'same');
           AssertArrayEquals(a, b, 'differ');
         END_PROGRAM",
    );
    let f = &r.cases[0].failures;
    let got: Vec<_> = f
        .iter()
        .map(|f| (f.index, f.expected.clone(), f.actual.clone()))
        .collect();
    assert_eq!(
        got,
        [
            (Some(0), "2".into(), "5".into()),
            (Some(2), "4".into(), "6".into())
        ]
    );
    assert!(
        r.to_text()
            .contains("t.st:5:12: cycle 0: element [0]: expected 2, actual 5: differ")
    );
}

#[test]
fn function_block_tests_run_until_test_done() {
    let r = report(
        "FUNCTION_BLOCK Test_Timer VAR t : TON; TEST_DONE : BOOL; n : INT; END_VAR
           t(IN := TRUE, PT := T#50ms);
           n := n + 1;
           IF t.Q THEN AssertEquals(6, n, 'cycles'); TEST_DONE := TRUE; END_IF
         END_FUNCTION_BLOCK
         FUNCTION_BLOCK TEST_Never VAR TEST_DONE : BOOL; END_VAR
           VAR CONSTANT TEST_CYCLES : INT := 7; END_VAR
         END_FUNCTION_BLOCK
         FUNCTION_BLOCK NotATest AssertTrue(FALSE); END_FUNCTION_BLOCK
         PROGRAM Main END_PROGRAM",
    );
    let names: Vec<_> = r.cases.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["Test_Timer", "TEST_Never"]);
    assert_eq!(r.cases[0].outcome(), TestOutcome::Passed);
    assert_eq!(r.cases[0].cycles, 6);
    assert_eq!(r.cases[1].outcome(), TestOutcome::Failed);
    assert!(r.cases[1].unfinished);
    assert_eq!(r.cases[1].cycles, 7);
    assert!(
        r.to_text()
            .contains("TEST_DONE was not set within 7 cycles")
    );
}

#[test]
fn each_test_runs_on_a_fresh_runtime() {
    let r = report(
        "VAR_GLOBAL g : INT; END_VAR
         PROGRAM TEST_A g := g + 1; AssertEquals(INT#1, g, 'fresh'); END_PROGRAM
         PROGRAM TEST_B g := g + 1; AssertEquals(INT#1, g, 'fresh'); END_PROGRAM",
    );
    assert!(r.all_passed(), "{}", r.to_text());
}

#[test]
fn faults_fail_the_test_and_the_run_goes_on() {
    let options = TestOptions {
        watchdog: Some(Duration::from_millis(50)),
        ..TestOptions::default()
    };
    let r = run_with(
        &[(
            "f.st",
            "PROGRAM TEST_Div VAR CONSTANT TEST_CYCLES : INT := 5; END_VAR VAR n, z : INT; END_VAR
  n := n + 1;
  IF n = 3 THEN n := n / z; END_IF
END_PROGRAM
PROGRAM TEST_Index VAR a : ARRAY[1..3] OF INT; i : INT := 4; END_VAR
  AssertTrue(FALSE, 'before the fault');
  a[i] := 1;
END_PROGRAM
PROGRAM TEST_Loop VAR x : INT; END_VAR
  WHILE TRUE DO x := x + 1; END_WHILE
END_PROGRAM
PROGRAM TEST_After AssertTrue(TRUE); END_PROGRAM",
        )],
        &options,
    )
    .expect("runs");
    let outcome: Vec<_> = r
        .cases
        .iter()
        .map(|c| {
            (
                c.outcome(),
                c.fault
                    .as_ref()
                    .map(|f| (f.code(), f.cycle, f.location.clone())),
            )
        })
        .collect();
    assert_eq!(
        outcome,
        [
            (
                TestOutcome::Errored,
                Some(("R001", 2, "f.st:3:22".to_string()))
            ),
            (
                TestOutcome::Errored,
                Some(("R002", 0, "f.st:7:3".to_string()))
            ),
            (
                TestOutcome::Errored,
                Some(("R008", 0, outcome_location(&r, 2)))
            ),
            (TestOutcome::Passed, None),
        ]
    );
    assert_eq!(
        r.cases[1].failures.len(),
        1,
        "failures before the fault are kept"
    );
    let text = r.to_text();
    assert!(text.contains("ERROR TEST_Div (f.st, 3 cycles)\n      error[R001]: runtime fault in cycle 2 at f.st:3:22"), "{text}");
    assert!(
        text.contains("4 tests: 1 passed, 0 failed, 3 errored"),
        "{text}"
    );
}

/// Where the watchdog stopped test `i` (somewhere in its loop).
fn outcome_location(r: &TestReport, i: usize) -> String {
    let loc = r.cases[i].fault.as_ref().expect("a fault").location.clone();
    assert!(loc.starts_with("f.st:10:"), "{loc}");
    loc
}

#[test]
fn filter_selects_tests_and_no_test_is_an_error() {
    let files = [(
        "t.st",
        "PROGRAM TEST_One END_PROGRAM PROGRAM TEST_Two END_PROGRAM PROGRAM Other END_PROGRAM",
    )];
    let options = TestOptions {
        filter: Some("two".into()),
        ..TestOptions::default()
    };
    let r = run_with(&files, &options).expect("runs");
    assert_eq!(r.cases.len(), 1);
    assert_eq!(r.cases[0].name, "TEST_Two");
    let none = TestOptions {
        filter: Some("three".into()),
        ..TestOptions::default()
    };
    assert!(matches!(run_with(&files, &none), Err(TestError::NoTests)));
    assert!(matches!(
        run(&[("t.st", "PROGRAM Main END_PROGRAM")]),
        Err(TestError::NoTests)
    ));
}

#[test]
fn locations_point_into_the_right_file() {
    let r = run(&[
        ("lib.st", "FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR Twice := 2 * x; END_FUNCTION"),
        ("twice_test.st", "PROGRAM TEST_Twice\n\n    AssertEquals(INT#5, Twice(2), 'wrong on purpose');\nEND_PROGRAM"),
    ])
    .expect("runs");
    assert_eq!(r.cases[0].file, "twice_test.st");
    assert_eq!(r.cases[0].failures[0].location, "twice_test.st:3:5");
}

#[test]
fn junit_xml_has_the_standard_elements_and_escapes() {
    let r = run(&[(
        "a&b.st",
        "PROGRAM TEST_Ok END_PROGRAM
PROGRAM TEST_Bad AssertEquals('<x>', 'y&z', 'say \"hi\"'); END_PROGRAM
PROGRAM TEST_Div VAR z : INT; END_VAR z := 1 / z; END_PROGRAM",
    )])
    .expect("runs");
    let xml = r.to_junit("plcrun");
    assert!(xml.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"plcrun\" tests=\"3\" failures=\"1\" errors=\"1\" time=\""), "{xml}");
    assert!(
        xml.contains("<testsuite name=\"plcrun\" tests=\"3\" failures=\"1\" errors=\"1\" time=\"")
    );
    assert!(xml.contains("<testcase name=\"TEST_Ok\" classname=\"a&amp;b.st\" time=\""));
    assert!(xml.contains(
        "<failure message=\"a&amp;b.st:2:18: cycle 0: expected &apos;&lt;x&gt;&apos;, actual &apos;y&amp;z&apos;: say &quot;hi&quot;\" type=\"AssertionFailure\">"
    ), "{xml}");
    assert!(xml.contains("<error message=\"division by zero in cycle 0 at a&amp;b.st:3:44\" type=\"R001\">error[R001]: runtime fault in cycle 0"), "{xml}");
    assert!(xml.trim_end().ends_with("</testsuite>\n</testsuites>"));
    assert_eq!(xml.matches("<testcase ").count(), 3);
}

#[test]
fn seed_comparator_passes_its_st_tests() {
    let (prog, tests) = (
        file("programs/comparator.st"),
        file("tests/plc/comparator_test.st"),
    );
    let r = run(&[("comparator.st", &prog), ("comparator_test.st", &tests)]).expect("runs");
    assert_eq!(r.cases.len(), 2);
    assert!(r.all_passed(), "{}", r.to_text());
    // The seed's own logic error (plcrun fix 4 undone) is caught.
    let broken = prog.replace(
        "Vi[5] := Vi[4] AND (NOT Vi[1]);",
        "Vi[5] := (NOT Vi[4]) AND (NOT Vi[1]);",
    );
    assert_ne!(broken, prog);
    let r = run(&[("comparator.st", &broken), ("comparator_test.st", &tests)]).expect("runs");
    assert_eq!(r.cases[0].outcome(), TestOutcome::Failed);
    assert!(
        r.cases[0]
            .failures
            .iter()
            .any(|f| f.message == "A=1 B=0: Sup is A>B")
    );
}

#[test]
fn seed_cmd_monitor_passes_its_timing_tests() {
    let (prog, tests) = (
        file("programs/cmd_monitor.st"),
        file("tests/plc/cmd_monitor_test.st"),
    );
    let r = run(&[("cmd_monitor.st", &prog), ("cmd_monitor_test.st", &tests)]).expect("runs");
    assert_eq!(r.cases.len(), 4);
    assert!(r.all_passed(), "{}", r.to_text());
    // Without the alarm latch's set dominance the ACK at cycle 13 clears it.
    let reset_dominant = prog.replace("ALRM_FF : SR ;", "ALRM_FF : RS ;").replace(
        "S1 := CMD_TMR.Q & NOT FDBK, R := ACK",
        "S := CMD_TMR.Q & NOT FDBK, R1 := ACK",
    );
    assert_ne!(reset_dominant, prog);
    let r = run(&[
        ("cmd_monitor.st", &reset_dominant),
        ("cmd_monitor_test.st", &tests),
    ])
    .expect("runs");
    let latched = r
        .cases
        .iter()
        .find(|c| c.name.ends_with("latched_until_ack"))
        .unwrap();
    assert_eq!(latched.outcome(), TestOutcome::Failed, "{}", r.to_text());
    assert_eq!(latched.failures[0].cycle, 13);
}

#[test]
fn a_program_ends_with_test_done_and_il_calls_assertions_too() {
    let r = report(
        "PROGRAM TEST_Count VAR TEST_DONE : BOOL; n : INT; END_VAR
           n := n + 1;
           TEST_DONE := n = 4;
           AssertTrue(n <= 4, 'never past the end');
         END_PROGRAM
         FUNCTION_BLOCK TEST_Il
         VAR x : INT := 3; ok : BOOL; END_VAR
           LD INT#3
           AssertEquals x
           ST ok
           LD INT#4
           AssertEquals x
         END_FUNCTION_BLOCK",
    );
    assert_eq!(r.cases[0].outcome(), TestOutcome::Passed, "{}", r.to_text());
    assert_eq!(r.cases[0].cycles, 4);
    let f = &r.cases[1].failures;
    assert_eq!(f.len(), 1, "{}", r.to_text());
    assert_eq!((f[0].expected.as_str(), f[0].actual.as_str()), ("4", "3"));
}

#[test]
fn test_cycles_set_by_anything_but_a_literal_is_refused_not_ignored() {
    let errors = compile_errors(
        "PROGRAM TEST_Named
           VAR CONSTANT N : INT := 50; TEST_CYCLES : INT := N; END_VAR
           AssertTrue(TRUE);
         END_PROGRAM",
    );
    assert_eq!(errors, ["E483"]);
}
