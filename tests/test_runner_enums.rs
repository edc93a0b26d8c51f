//! `AssertEquals` of two values of one enumeration under `plcrun test`
//! (docs/testing.md): compared as the integers they are stored as, a
//! failure reported with the values' names; a bare value (`Run`) is read
//! as a value of the other argument's enumeration. Two different
//! enumerations, or an enumeration and a number, stay E480.

use plcrun::{SourceMap, TestError, TestOptions, TestOutcome, TestReport, run_tests};

fn run(text: &str) -> Result<TestReport, TestError> {
    let mut sources = SourceMap::new();
    sources.add("t.st", text);
    run_tests(&sources, &TestOptions::default())
}

const TYPES: &str = "
TYPE E_Mode : (Idle, Run, Stop); END_TYPE
TYPE E_Lvl : INT (Low := 1, High := 10); END_TYPE
TYPE E_Other : (Up, Down); END_TYPE
";

#[test]
fn two_values_of_one_enumeration_are_compared_and_reported_by_name() {
    let src = format!(
        "{TYPES}
PROGRAM TEST_enums
VAR m : E_Mode := Run; l : E_Lvl := High; ok : BOOL; END_VAR
AssertEquals(E_Mode#Run, m, 'typed');
AssertEquals(Run, m, 'bare');
ok := AssertEquals(Expected := m, Actual := Run);
AssertTrue(ok, 'as a value');
AssertEquals(m, E_Mode#Stop, 'mode differs');
AssertEquals(E_Lvl#Low, l, 'level differs');
END_PROGRAM
"
    );
    let r = run(&src).unwrap_or_else(|e| panic!("{e}"));
    let c = &r.cases[0];
    assert_eq!(c.outcome(), TestOutcome::Failed);
    let got: Vec<String> = c
        .failures
        .iter()
        .map(|f| format!("{} {} {} {}", f.location, f.expected, f.actual, f.message))
        .collect();
    assert_eq!(
        got,
        [
            "t.st:12:1 E_Mode#Run E_Mode#Stop mode differs",
            "t.st:13:1 E_Lvl#Low E_Lvl#High level differs",
        ]
    );
}

#[test]
fn values_of_different_enumerations_or_an_enumeration_and_a_number_are_e480() {
    let src = format!(
        "{TYPES}
PROGRAM TEST_mixed
VAR m : E_Mode; o : E_Other; i : INT; END_VAR
AssertEquals(m, o, 'two enums');
AssertEquals(m, i, 'enum and int');
AssertEquals(m, 1, 'enum and literal');
END_PROGRAM
"
    );
    let Err(TestError::Compile(e)) = run(&src) else {
        panic!("expected a compile error");
    };
    let got: Vec<String> = e
        .diagnostics
        .iter()
        .map(|d| format!("{} {}", d.code, e.sources.location(d.span)))
        .collect();
    assert_eq!(got, ["E480 t.st:8:1", "E480 t.st:9:1", "E480 t.st:10:1"]);
}
