//! `plcrun run` and `plcrun test` show a runtime fault's instance path and
//! its callers, one `note:` line each (docs/diagnostics.md, "Where a runtime
//! fault happened").

use crate::support::cli;

use cli::{plcrun, temp_file};

const LIB: &str = "FUNCTION_BLOCK MOTOR
VAR_INPUT speed, load : INT; END_VAR
VAR_OUTPUT torque : INT; END_VAR
torque := speed / load;
END_FUNCTION_BLOCK
FUNCTION_BLOCK CONVEYOR
VAR motor : MOTOR; END_VAR
motor(speed := 100, load := 0);
END_FUNCTION_BLOCK
FUNCTION_BLOCK LINE
VAR conveyor1 : CONVEYOR; END_VAR
conveyor1();
END_FUNCTION_BLOCK
";

const MAIN: &str = "PROGRAM Main
VAR line : LINE; n : INT; END_VAR
n := n + 1;
IF n = 3 THEN line(); END_IF;
END_PROGRAM
";

#[test]
fn run_prints_the_instance_path_and_one_note_per_caller() {
    let lib = temp_file("fault_lib.st", LIB);
    let main = temp_file("fault_main.st", MAIN);
    let (code, _out, err) = plcrun(&["run", &lib, &main, "--cycles", "5", "--trace", "n"]);
    assert_eq!(code, 3, "{err}");
    let expected = format!(
        "error[R001]: runtime fault in cycle 2 at {lib}:4:11 \
(in Main.line.conveyor1.motor : MOTOR): division by zero
    torque := speed / load;
  = note: called from Main.line.conveyor1 : CONVEYOR at {lib}:8:1
  = note: called from Main.line : LINE at {lib}:12:1
  = note: called from Main at {main}:4:15
"
    );
    assert!(err.contains(&expected), "{err}");
}

#[test]
fn test_reports_the_callers_of_a_faulting_test() {
    let tests = temp_file(
        "fault_test.st",
        "PROGRAM TEST_Line VAR line : LINE; END_VAR line(); END_PROGRAM",
    );
    let lib = temp_file("fault_lib2.st", LIB);
    let (code, out, _) = plcrun(&["test", &lib, &tests]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("(in TEST_Line.line.conveyor1.motor : MOTOR): division by zero"),
        "{out}"
    );
    assert!(
        out.contains(&format!(
            "= note: called from TEST_Line.line : LINE at {lib}:12:1"
        )),
        "{out}"
    );
    assert!(
        out.contains(&format!("= note: called from TEST_Line at {tests}:1:44")),
        "{out}"
    );
}
