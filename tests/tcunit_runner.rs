//! TcUnit suites under `plcrun test` (issue #25, point 3): a
//! FUNCTION_BLOCK extending `FB_TestSuite` is a suite, `TEST`/
//! `TEST_ORDERED` declare its tests, `TEST_FINISHED` ends them, the typed
//! `AssertEquals_<TYPE>` / `AssertArray[2d|3d]Equals_<TYPE>` check, and
//! each test is reported as `Suite.Test`. The suites of
//! `tests/plc/tcunit_suites.st` each show one rule; the expected verdicts
//! are derived by hand from TcUnit's documented behaviour.

use crate::support::cli;

use plcrun::{SourceMap, TestCase, TestOptions, TestOutcome, run_tests};

fn run(files: &[(&str, &str)]) -> Vec<TestCase> {
    let mut sources = SourceMap::new();
    for (name, text) in files {
        sources.add(*name, *text);
    }
    run_tests(&sources, &TestOptions::default())
        .expect("the suites compile")
        .cases
}

fn suites() -> Vec<TestCase> {
    let text = std::fs::read_to_string("tests/plc/tcunit_suites.st").unwrap();
    run(&[("suites.st", &text)])
}

fn case<'a>(cases: &'a [TestCase], name: &str) -> &'a TestCase {
    cases
        .iter()
        .find(|c| c.full_name() == name)
        .unwrap_or_else(|| {
            panic!(
                "no test {name} in {:?}",
                cases.iter().map(TestCase::full_name).collect::<Vec<_>>()
            )
        })
}

#[test]
fn each_test_of_each_declared_suite_instance_is_reported_as_suite_dot_test() {
    let cases = suites();
    let names: Vec<String> = cases.iter().map(TestCase::full_name).collect();
    assert_eq!(
        names,
        [
            "PRG_TEST.fbMath.TestAdd",
            "PRG_TEST.fbMath.TestSlowFailure",
            "PRG_TEST.fbMath.TestArrays",
            "PRG_TEST.fbOrder.First",
            "PRG_TEST.fbOrder.Second",
        ]
    );
    let add = case(&cases, "PRG_TEST.fbMath.TestAdd");
    assert_eq!(add.outcome(), TestOutcome::Passed);
    // Four assertions ran; the one after TEST_FINISHED is ignored.
    assert_eq!((add.assertions, add.cycles), (4, 1));
}

#[test]
fn a_failing_assertion_is_reported_once_at_its_line_though_it_runs_every_cycle() {
    let cases = suites();
    let slow = case(&cases, "PRG_TEST.fbMath.TestSlowFailure");
    assert_eq!(slow.outcome(), TestOutcome::Failed);
    assert_eq!(slow.cycles, 3);
    assert_eq!(slow.failures.len(), 1, "{:?}", slow.failures);
    let f = &slow.failures[0];
    assert_eq!(
        (
            f.location.as_str(),
            f.expected.as_str(),
            f.actual.as_str(),
            f.cycle
        ),
        ("suites.st:20:1", "7", "8", 0)
    );
}

#[test]
fn array_assertions_compare_by_position_with_a_delta_and_fail_on_different_sizes() {
    let cases = suites();
    let arrays = case(&cases, "PRG_TEST.fbMath.TestArrays");
    let got: Vec<(String, Option<String>, String, String)> = arrays
        .failures
        .iter()
        .map(|f| {
            (
                f.location.clone(),
                f.element.clone(),
                f.expected.clone(),
                f.actual.clone(),
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            (
                "suites.st:35:1".to_string(),
                Some("[1,0]".to_string()),
                "3.0".to_string(),
                "3.5".to_string()
            ),
            (
                "suites.st:36:1".to_string(),
                None,
                "'3 elements'".to_string(),
                "'4 elements'".to_string()
            ),
        ]
    );
}

#[test]
fn ordered_tests_run_one_after_the_other_and_logs_go_to_their_test() {
    let cases = suites();
    let first = case(&cases, "PRG_TEST.fbOrder.First");
    assert_eq!((first.outcome(), first.cycles), (TestOutcome::Passed, 3));
    let second = case(&cases, "PRG_TEST.fbOrder.Second");
    // It starts in the cycle First finished in (cycle 2, its 3rd), so only
    // the second assertion fails; TEST_FINISHED_NAMED ends it there.
    assert_eq!(second.cycles, 3);
    assert_eq!(second.failures.len(), 1);
    assert_eq!(
        second.failures[0].message,
        "fails in the first cycle Second runs"
    );
    assert_eq!(second.output, ["second ran in cycle 3"]);
}

#[test]
fn suites_run_in_sequence_when_a_program_calls_run_in_sequence() {
    let suite = |name: &str| {
        format!(
            "FUNCTION_BLOCK {name} EXTENDS FB_TestSuite\nVAR n : INT; END_VAR\nTEST('T');\nn := n + 1;\nIF n = 2 THEN TEST_FINISHED(); END_IF\nEND_FUNCTION_BLOCK\n"
        )
    };
    let parallel = "PROGRAM PRG_TEST\nVAR a : FB_A; b : FB_B; END_VAR\nRUN();\nEND_PROGRAM\n";
    let sequence =
        "PROGRAM PRG_TEST\nVAR a : FB_A; b : FB_B; END_VAR\nRUN_IN_SEQUENCE();\nEND_PROGRAM\n";
    let cycles = |program: &str| -> Vec<u64> {
        run(&[
            ("a.st", &suite("FB_A")),
            ("b.st", &suite("FB_B")),
            ("p.st", program),
        ])
        .iter()
        .map(|c| c.cycles)
        .collect()
    };
    assert_eq!(cycles(parallel), [2, 2]);
    // B is called from the cycle A finished in (its 2nd) on, so it
    // finishes in the 3rd.
    assert_eq!(cycles(sequence), [2, 3]);
}

#[test]
fn a_test_that_never_finishes_times_out_and_suites_without_a_program_still_run() {
    let cases = run(&[(
        "never.st",
        "FUNCTION_BLOCK FB_Never EXTENDS FB_TestSuite\nTEST('Forever');\nAssertTrue(TRUE, '');\nEND_FUNCTION_BLOCK\n",
    )]);
    let forever = case(&cases, "FB_Never.Forever");
    assert!(forever.unfinished);
    assert_eq!(forever.outcome(), TestOutcome::Failed);
    assert_eq!(forever.cycles, 100_000);
}

#[test]
fn typed_assertions_convert_their_arguments_and_refuse_wrong_arrays() {
    let cases = run(&[(
        "typed.st",
        "FUNCTION_BLOCK FB_T EXTENDS FB_TestSuite\nVAR s : SINT := 5; b : BYTE := 16#0F; t : TIME := T#2s; END_VAR\nTEST('Conversions');\nAssertEquals_DINT(Expected := 5, Actual := s, Message := 'SINT to DINT');\nAssertEquals_WORD(Expected := 16#000F, Actual := b, Message := 'BYTE to WORD');\nAssertEquals_TIME(Expected := T#2000ms, Actual := t, Message := 'time');\nAssertEquals_BOOL(Expected := TRUE, Actual := FALSE, Message := 'fails');\nTEST_FINISHED();\nEND_FUNCTION_BLOCK\n",
    )]);
    let c = case(&cases, "FB_T.Conversions");
    assert_eq!(c.assertions, 4);
    assert_eq!(c.failures.len(), 1);
    assert_eq!(c.failures[0].message, "fails");
    let mut sources = SourceMap::new();
    sources.add(
        "bad.st",
        "FUNCTION_BLOCK FB_T EXTENDS FB_TestSuite\nVAR a : ARRAY[0..1] OF INT; r : ARRAY[0..1] OF REAL; END_VAR\nTEST('Bad');\nAssertArrayEquals_INT(Expecteds := a, Actuals := r, Message := '');\nAssertArrayEquals_REAL(Expecteds := r, Actuals := r, Message := '');\nEND_FUNCTION_BLOCK\n",
    );
    let err = run_tests(&sources, &TestOptions::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("E482") && err.contains("bad.st:4:1"), "{err}");
    assert!(
        err.contains("E481") && err.contains("needs its argument `DELTA`"),
        "{err}"
    );
}

#[test]
fn the_junit_report_names_the_suite_as_the_class_of_each_test() {
    let junit = cli::temp_file("junit.xml", "");
    let (code, out, _) = cli::plcrun(&["test", "tests/plc/tcunit_suites.st", "--junit", &junit]);
    assert_eq!(code, 1);
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(
        xml.contains("<testcase name=\"TestAdd\" classname=\"PRG_TEST.fbMath\""),
        "{xml}"
    );
    assert!(
        out.contains(
            "FAIL  PRG_TEST.fbMath.TestArrays (tests/plc/tcunit_suites.st, 1 cycle, 3 assertions)"
        ),
        "{out}"
    );
}

#[test]
fn check_accepts_what_the_test_runner_accepts() {
    let (code, _, err) = cli::plcrun(&["check", "tests/plc/tcunit_suites.st"]);
    assert_eq!((code, err.as_str()), (0, "ok: 1 file checked\n"));
    // Without a suite, TEST is an unknown function as before.
    let plain = cli::temp_file("plain.st", "PROGRAM P\nTEST('x');\nEND_PROGRAM\n");
    let (code, _, err) = cli::plcrun(&["check", &plain]);
    assert_eq!(code, 1);
    assert!(err.contains("E201") && err.contains("TEST"), "{err}");
}

/// The report of `plcrun test --keep-going` on `files` (which do not
/// compile whole: without it nothing runs), and each case's verdict.
fn kept_going(files: &[(&str, &str)]) -> (plcrun::TestReport, Vec<(String, TestOutcome)>) {
    let mut sources = SourceMap::new();
    for (name, text) in files {
        sources.add(*name, *text);
    }
    assert!(run_tests(&sources, &TestOptions::default()).is_err());
    let options = TestOptions {
        keep_going: true,
        ..TestOptions::default()
    };
    let report = run_tests(&sources, &options).expect("the rest compiles");
    let verdicts = report
        .cases
        .iter()
        .map(|c| (c.full_name(), c.outcome()))
        .collect();
    (report, verdicts)
}

/// `--keep-going` (`TestOptions::keep_going`): a file that does not
/// compile (here a block of a library plcrun does not have) is left out,
/// then the files that needed it; the suites of the others run, the
/// suites left out are errors naming the first error of their file, and
/// the report lists the files left out. Without it nothing runs.
#[test]
fn keep_going_runs_the_suites_that_compile_and_reports_the_others() {
    let motion = "
FUNCTION_BLOCK FB_Axis
VAR ref : AXIS_REF; power : MC_Power; END_VAR
power(Axis := ref, Enable := TRUE);
END_FUNCTION_BLOCK";
    let motion_test = "
FUNCTION_BLOCK FB_AxisTest EXTENDS FB_TestSuite
VAR axis : FB_Axis; END_VAR
TEST('Powers');
axis();
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let math_test = "
FUNCTION_BLOCK FB_MathTest EXTENDS FB_TestSuite
TEST('Adds');
AssertEquals_INT(Expected := 4, Actual := 2 + 2, Message := 'sum');
TEST_FINISHED();
TEST('Fails');
AssertEquals_INT(Expected := 5, Actual := 2 + 2, Message := 'wrong on purpose');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let prg = "
PROGRAM PRG_TEST
VAR fbAxis : FB_AxisTest; fbMath : FB_MathTest; END_VAR
TcUnit.RUN();
END_PROGRAM";
    let (report, verdicts) = kept_going(&[
        ("FB_Axis.st", motion),
        ("FB_AxisTest.st", motion_test),
        ("FB_MathTest.st", math_test),
        ("PRG_TEST.st", prg),
    ]);
    assert_eq!(
        verdicts,
        [
            ("PRG_TEST.fbAxis".to_string(), TestOutcome::Errored),
            ("PRG_TEST.fbMath.Adds".to_string(), TestOutcome::Passed),
            ("PRG_TEST.fbMath.Fails".to_string(), TestOutcome::Failed),
        ]
    );
    let why = report.cases[0].left_out.as_deref().unwrap_or_default();
    assert!(why.contains("FB_AxisTest.st"), "{why}");
    let files: Vec<&str> = report.left_out.iter().map(|(f, _)| f.as_str()).collect();
    assert_eq!(files, ["FB_Axis.st", "FB_AxisTest.st", "PRG_TEST.st"]);
    assert!(
        report.left_out[0].1.starts_with("E203"),
        "{:?}",
        report.left_out
    );
}

/// `--keep-going` in a global variable list: the variable of a library
/// plcrun does not have is left out, not its list; the suite using the
/// list's other variables runs, the one using the variable left out is an
/// error, and the report names the variable.
#[test]
fn keep_going_leaves_out_a_global_not_its_list() {
    let globals = "VAR_GLOBAL\n  nLimit : INT := 7;\n  jsonDoc : SJsonValue;\n  fScale : REAL := 2.5;\nEND_VAR\n";
    let uses_limit = "
FUNCTION_BLOCK FB_LimitTest EXTENDS FB_TestSuite
TEST('Limit');
AssertEquals_INT(Expected := 7, Actual := nLimit, Message := 'limit');
AssertEquals_REAL(Expected := 2.5, Actual := fScale, Delta := 0.0, Message := 'scale');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let uses_json = "
FUNCTION_BLOCK FB_JsonTest EXTENDS FB_TestSuite
TEST('Json');
jsonDoc.x := 1;
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let prg =
        "PROGRAM PRG_TEST\nVAR a : FB_LimitTest; b : FB_JsonTest; END_VAR\nRUN();\nEND_PROGRAM\n";
    let (report, verdicts) = kept_going(&[
        ("GVL.st", globals),
        ("FB_LimitTest.st", uses_limit),
        ("FB_JsonTest.st", uses_json),
        ("PRG_TEST.st", prg),
    ]);
    assert_eq!(
        verdicts,
        [
            ("PRG_TEST.b".to_string(), TestOutcome::Errored),
            ("PRG_TEST.a.Limit".to_string(), TestOutcome::Passed),
        ]
    );
    let left: Vec<&str> = report.left_out.iter().map(|(f, _)| f.as_str()).collect();
    assert_eq!(
        left,
        ["FB_JsonTest.st", "PRG_TEST.st", "GVL.st, global `jsonDoc`"]
    );
    assert!(
        report.left_out[2]
            .1
            .starts_with("E203: unknown type `SJsonValue`"),
        "{:?}",
        report.left_out
    );
}

#[test]
fn tc2_system_s_adslogstr_writes_into_the_test_s_log() {
    // A TwinCAT file: plcrun's Tc2_System brings the message kinds.
    let suite = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n<POU Name=\"FB_Log\" Id=\"{00000000-0000-0000-0000-000000000001}\" SpecialFunc=\"None\">\n<Declaration><![CDATA[FUNCTION_BLOCK FB_Log EXTENDS FB_TestSuite\nVAR nResult : DINT := -1; END_VAR]]></Declaration>\n<Implementation><ST><![CDATA[TEST('Logs');\nnResult := ADSLOGSTR(msgCtrlMask := ADSLOG_MSGTYPE_HINT OR ADSLOG_MSGTYPE_LOG, msgFmtStr := 'valve %s closed', strArg := 'V1');\nAssertEquals_DINT(Expected := 0, Actual := nResult, Message := 'ADSLOGSTR returns 0');\nAssertEquals_DWORD(Expected := 16#11, Actual := ADSLOG_MSGTYPE_HINT OR ADSLOG_MSGTYPE_LOG, Message := 'kinds');\nTEST_FINISHED();]]></ST></Implementation>\n</POU>\n</TcPlcObject>\n";
    let program = "PROGRAM PRG_TEST\nVAR s : FB_Log; END_VAR\nRUN();\nEND_PROGRAM\n";
    let cases = run(&[("FB_Log.TcPOU", suite), ("p.st", program)]);
    let logs = case(&cases, "PRG_TEST.s.Logs");
    assert_eq!(logs.outcome(), TestOutcome::Passed, "{:?}", logs.failures);
    assert_eq!(logs.output, ["valve V1 closed"]);
}

#[test]
fn adslogdint_and_adslogreal_also_write_into_the_test_s_log() {
    let suite = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n<POU Name=\"FB_Log\" Id=\"{00000000-0000-0000-0000-000000000001}\" SpecialFunc=\"None\">\n<Declaration><![CDATA[FUNCTION_BLOCK FB_Log EXTENDS FB_TestSuite\nVAR nResult : DINT := -1; END_VAR]]></Declaration>\n<Implementation><ST><![CDATA[TEST('Logs');\nnResult := ADSLOGDINT(ADSLOG_MSGTYPE_WARN, 'count %d', 42) + ADSLOGLREAL(ADSLOG_MSGTYPE_HINT, 'level %f', 0.5);\nAssertEquals_DINT(Expected := 0, Actual := nResult, Message := 'both return 0');\nTEST_FINISHED();]]></ST></Implementation>\n</POU>\n</TcPlcObject>\n";
    let program = "PROGRAM PRG_TEST\nVAR s : FB_Log; END_VAR\nRUN();\nEND_PROGRAM\n";
    let cases = run(&[("FB_Log.TcPOU", suite), ("p.st", program)]);
    let logs = case(&cases, "PRG_TEST.s.Logs");
    assert_eq!(logs.outcome(), TestOutcome::Passed, "{:?}", logs.failures);
    assert_eq!(logs.output, ["count 42", "level 0.500000"]);
}

/// A suite whose initialisation faults (its FB_init divides by zero): the
/// fault is reported as an error of that suite, before its first TEST;
/// under `--keep-going` the suite is left out and the others run, as a
/// file that does not compile is.
#[test]
fn a_suite_whose_initialisation_faults_is_reported_and_left_out_under_keep_going() {
    let bad = "
FUNCTION_BLOCK FB_BadTest EXTENDS FB_TestSuite
VAR n : INT; d : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR
n := 10 / d;
END_METHOD
TEST('Never');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let good = "
FUNCTION_BLOCK FB_GoodTest EXTENDS FB_TestSuite
TEST('Adds');
AssertEquals_INT(Expected := 4, Actual := 2 + 2, Message := 'sum');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let prg = "
PROGRAM PRG_TEST
VAR fbBad : FB_BadTest; fbGood : FB_GoodTest; END_VAR
TcUnit.RUN();
END_PROGRAM";
    let mut sources = SourceMap::new();
    for (name, text) in [("bad.st", bad), ("good.st", good), ("prg.st", prg)] {
        sources.add(name, text);
    }
    let verdicts = |options: &TestOptions| -> Vec<(String, TestOutcome, Option<&'static str>)> {
        run_tests(&sources, options)
            .expect("the suites compile")
            .cases
            .iter()
            .map(|c| {
                (
                    c.full_name(),
                    c.outcome(),
                    c.fault.as_ref().map(|f| f.code()),
                )
            })
            .collect()
    };
    let fault = (
        "PRG_TEST.fbBad.(before its first TEST)".to_string(),
        TestOutcome::Errored,
        // R001: division by zero.
        Some("R001"),
    );
    assert_eq!(
        verdicts(&TestOptions::default()),
        std::slice::from_ref(&fault)
    );
    let options = TestOptions {
        keep_going: true,
        ..TestOptions::default()
    };
    assert_eq!(
        verdicts(&options),
        [
            fault,
            (
                "PRG_TEST.fbGood.Adds".to_string(),
                TestOutcome::Passed,
                None
            )
        ]
    );
}
