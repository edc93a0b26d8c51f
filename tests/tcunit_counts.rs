//! What a TcUnit suite reads of TcUnit itself (issue #25, point 3):
//! `AssertResults.TotalAsserts` and `AssertArrayResults.TotalArrayAsserts`
//! (the suite's distinct assertions, counted as TcUnit counts them),
//! `IS_TEST_FINISHED`, and the parameters of `GVL_Param_TcUnit`. The
//! counts are worked out by hand from TcUnit's rules beside each case.

use plcrun::{SourceMap, TestCase, TestOptions, TestOutcome, run_tests};

fn run(suite: &str) -> Vec<TestCase> {
    let mut sources = SourceMap::new();
    sources.add("suite.st", suite);
    sources.add(
        "main.st",
        "PROGRAM PRG_TEST\nVAR s : FB_Counts; END_VAR\ns();\nEND_PROGRAM\n",
    );
    run_tests(&sources, &TestOptions::default())
        .expect("the suite compiles")
        .cases
}

fn passed(cases: &[TestCase], name: &str) -> bool {
    let case = cases
        .iter()
        .find(|c| c.full_name() == format!("PRG_TEST.s.{name}"))
        .unwrap_or_else(|| panic!("no test {name}"));
    assert_eq!(case.outcome(), TestOutcome::Passed, "{name}: {case:?}");
    true
}

#[test]
fn total_asserts_counts_each_distinct_assertion_once_across_cycles() {
    // Cycle 1: a(1) and a(2) are two assertions. Cycles 2 and 3 repeat
    // them: the same two. Cycle 3 also makes two identical calls of a(5):
    // both count, having never been seen twice in a cycle: 4. The count
    // is read in cycle 4, before that cycle's assertions.
    let suite = "FUNCTION_BLOCK FB_Counts EXTENDS FB_TestSuite
VAR n : INT; seen : UINT; END_VAR
TEST('Counts');
n := n + 1;
IF n = 4 THEN
    seen := AssertResults.TotalAsserts;
    AssertEquals_UINT(Expected := 4, Actual := seen, Message := 'distinct assertions');
    TEST_FINISHED();
ELSE
    AssertEquals_INT(Expected := 1, Actual := 1, Message := 'a');
    AssertEquals_INT(Expected := 2, Actual := 2, Message := 'a');
    IF n = 3 THEN
        AssertEquals_INT(Expected := 5, Actual := 5, Message := 'a');
        AssertEquals_INT(Expected := 5, Actual := 5, Message := 'a');
    END_IF
END_IF
END_FUNCTION_BLOCK";
    assert!(passed(&run(suite), "Counts"));
}

#[test]
fn array_assertions_have_their_own_total_and_the_count_stops_at_the_limit() {
    // 1 100 identical value assertions in one cycle: 1 000 counted (the
    // limit, with one log line); two array assertions of different
    // messages: 2, and they add nothing to TotalAsserts.
    let suite = "FUNCTION_BLOCK FB_Counts EXTENDS FB_TestSuite
VAR i : INT; a : ARRAY[1..3] OF DINT := [1, 2, 3]; END_VAR
TEST('Limit');
FOR i := 1 TO 1100 DO
    AssertEquals_DINT(Expected := 7, Actual := 7, Message := 'same');
END_FOR
AssertEquals_UINT(Expected := GVL_Param_TcUnit.MaxNumberOfAssertsForEachTestSuite,
                  Actual := AssertResults.TotalAsserts, Message := 'capped');
TEST_FINISHED();
TEST('Arrays');
AssertArrayEquals_DINT(Expecteds := a, Actuals := a, Message := 'one');
AssertArrayEquals_DINT(Expecteds := a, Actuals := a, Message := 'two');
AssertEquals_UINT(Expected := 2, Actual := AssertArrayResults.TotalArrayAsserts, Message := 'arrays');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let cases = run(suite);
    assert!(passed(&cases, "Limit"));
    assert!(passed(&cases, "Arrays"));
    let limit = cases
        .iter()
        .find(|c| c.full_name().ends_with("Limit"))
        .unwrap();
    assert_eq!(
        limit.output,
        ["Max number of assertions exceeded. Check parameter MaxNumberOfAssertsForEachTestSuite."]
    );
}

#[test]
fn is_test_finished_says_whether_a_test_of_the_suite_has_finished() {
    let suite = "FUNCTION_BLOCK FB_Counts EXTENDS FB_TestSuite
VAR before, other, unknown : BOOL := TRUE; END_VAR
TEST('First');
before := IS_TEST_FINISHED('First');
TEST_FINISHED();
TEST('Second');
AssertFalse(before, 'First was running');
AssertTrue(IS_TEST_FINISHED('First'), 'First has finished');
AssertFalse(IS_TEST_FINISHED('Nowhere'), 'no such test');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    let cases = run(suite);
    assert!(passed(&cases, "First"));
    assert!(passed(&cases, "Second"));
}

#[test]
fn tcunit_parameters_are_constants_even_qualified_with_the_library() {
    // The TcUnit-Verifier sizes a loop with the library-qualified name.
    let suite = "FUNCTION_BLOCK FB_Counts EXTENDS FB_TestSuite
VAR CONSTANT
    MAX_INDEX : UINT := (TcUnit.GVL_Param_TcUnit.MaxNumberOfAssertsForEachTestSuite + 100);
END_VAR
TEST('Parameters');
AssertEquals_UINT(Expected := 1100, Actual := MAX_INDEX, Message := 'limit + 100');
AssertEquals_UINT(Expected := 100, Actual := GVL_Param_TcUnit.MaxNumberOfTestsForEachTestSuite, Message := 'tests');
AssertEquals_TIME(Expected := T#0MS, Actual := GVL_Param_TcUnit.TimeBetweenTestSuitesExecution, Message := 'pause');
TEST_FINISHED();
END_FUNCTION_BLOCK";
    assert!(passed(&run(suite), "Parameters"));
}
