//! A runtime fault names the POU instance where it happened (its path from
//! the program instance down) and the chain of calls that led there,
//! innermost first, in the library's fault type and in its message.

use crate::support::plc;

use plc::{compile, compile_files, first_fault, line_col, program};
use plcrun::{FaultFrame, FaultKind, Options, Plc, RuntimeFault};

/// `(instance, pou, line)` of each caller.
fn chain(f: &RuntimeFault) -> Vec<(String, String, usize)> {
    f.callers()
        .iter()
        .map(|c: &FaultFrame| (c.instance.clone(), c.pou.clone(), line_col(&c.location).0))
        .collect()
}

fn owned(rows: &[(&str, &str, usize)]) -> Vec<(String, String, usize)> {
    rows.iter()
        .map(|(i, p, l)| (i.to_string(), p.to_string(), *l))
        .collect()
}

const LINE: &str = "FUNCTION_BLOCK MOTOR
VAR_INPUT speed, load : INT; END_VAR
VAR_OUTPUT torque : INT; END_VAR
torque := speed / load;
END_FUNCTION_BLOCK
FUNCTION_BLOCK CONVEYOR
VAR motor : MOTOR; END_VAR
motor(speed := 100, load := 0);
END_FUNCTION_BLOCK
FUNCTION_BLOCK LINE
VAR spare : INT; conveyor1 : CONVEYOR; END_VAR
conveyor1();
END_FUNCTION_BLOCK
PROGRAM Main
VAR line : LINE; END_VAR
line();
END_PROGRAM";

#[test]
fn a_fault_three_fbs_deep_names_the_instance_and_every_caller() {
    let f = first_fault(LINE);
    assert_eq!(f.fault.kind, FaultKind::DivisionByZero);
    assert_eq!(f.pou, "MOTOR");
    assert_eq!(f.instance(), "Main.line.conveyor1.motor");
    assert_eq!(line_col(&f.location).0, 4);
    assert_eq!(
        chain(&f),
        owned(&[
            ("Main.line.conveyor1", "CONVEYOR", 8),
            ("Main.line", "LINE", 12),
            ("Main", "Main", 16),
        ])
    );
    // Each caller's location is the call itself.
    assert_eq!(f.callers()[0].location, "test.st:8:1");
    let shown = f.to_string();
    assert!(
        shown.starts_with(
            "error[R001]: runtime fault in cycle 0 at test.st:4:11 \
             (in Main.line.conveyor1.motor : MOTOR): division by zero\n    torque := speed / load;\n"
        ),
        "{shown}"
    );
    assert!(
        shown.ends_with(
            "\n  = note: called from Main.line.conveyor1 : CONVEYOR at test.st:8:1\
             \n  = note: called from Main.line : LINE at test.st:12:1\
             \n  = note: called from Main at test.st:16:1"
        ),
        "{shown}"
    );
}

#[test]
fn a_fault_in_the_program_body_has_no_callers_and_the_same_message_as_before() {
    let f = first_fault(&program("", "a, z : INT;", "a := a / z;"));
    assert_eq!(f.instance(), "P");
    assert!(f.callers().is_empty());
    let shown = f.to_string();
    assert!(shown.contains("(in P): division by zero"), "{shown}");
    assert!(!shown.contains("note:"), "{shown}");
}

#[test]
fn a_function_is_named_with_the_instance_that_called_it() {
    let src = "FUNCTION Ratio : INT
VAR_INPUT a, b : INT; END_VAR
Ratio := a / b;
END_FUNCTION
FUNCTION_BLOCK Scaler
VAR_INPUT d : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := Ratio(10, d);
END_FUNCTION_BLOCK
PROGRAM P
VAR sc : ARRAY[1..3] OF Scaler; grid : ARRAY[0..1, 0..2] OF Scaler; END_VAR
sc[1](d := 1);
grid[1, 2](d := 0);
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.pou, "Ratio");
    assert_eq!(f.instance(), "Ratio");
    assert_eq!(
        chain(&f),
        owned(&[("P.grid[1,2]", "Scaler", 8), ("P", "P", 13)])
    );
    let shown = f.to_string();
    assert!(shown.contains("(in Ratio): division by zero"), "{shown}");
    assert!(
        shown.contains("= note: called from P.grid[1,2] : Scaler at test.st:8:6"),
        "{shown}"
    );
}

#[test]
fn a_function_calling_a_function_keeps_both() {
    let src = "FUNCTION Inner : INT
VAR_INPUT a : INT; END_VAR
Inner := 10 / a;
END_FUNCTION
FUNCTION Outer : INT
VAR_INPUT a : INT; END_VAR
Outer := Inner(a) + 1;
END_FUNCTION
PROGRAM P
VAR z, r : INT; END_VAR
r := Outer(z);
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.instance(), "Inner");
    assert_eq!(chain(&f), owned(&[("Outer", "Outer", 7), ("P", "P", 11)]));
}

const MACHINE: &str = "INTERFACE IDrive
  METHOD Start : INT
    VAR_INPUT ramp : INT; END_VAR
  END_METHOD
END_INTERFACE
FUNCTION_BLOCK Drive IMPLEMENTS IDrive
  VAR rate : INT; END_VAR
  METHOD Start : INT
    VAR_INPUT ramp : INT; END_VAR
    Start := rate / ramp;
  END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK Cell
  VAR_INPUT r : INT; END_VAR
  VAR d1, d2 : Drive; itf : IDrive; x : INT; END_VAR
  itf := d2;
  x := itf.Start(ramp := r);
END_FUNCTION_BLOCK
PROGRAM P
VAR cell : Cell; END_VAR
cell(r := 0);
END_PROGRAM";

#[test]
fn a_method_called_through_an_interface_names_the_instance_behind_it() {
    let f = first_fault(MACHINE);
    assert_eq!(f.pou, "Drive.Start");
    assert_eq!(f.instance(), "P.cell.d2.Start");
    assert_eq!(chain(&f), owned(&[("P.cell", "Cell", 17), ("P", "P", 21)]));
    assert!(
        f.to_string()
            .contains("(in P.cell.d2.Start : Drive.Start): division by zero"),
        "{f}"
    );
}

#[test]
fn a_method_calling_a_method_is_a_caller_too() {
    let src = "FUNCTION_BLOCK Axis
  VAR pos, gear : INT; END_VAR
  METHOD Move
    pos := pos / gear;
  END_METHOD
  METHOD Home
    THIS^.Move();
  END_METHOD
END_FUNCTION_BLOCK
PROGRAM P
VAR ax : ARRAY[1..2] OF Axis; END_VAR
ax[2].Home();
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.instance(), "P.ax[2].Move");
    assert_eq!(
        chain(&f),
        owned(&[("P.ax[2].Home", "Axis.Home", 7), ("P", "P", 12)])
    );
}

const PLANT: &str = "FUNCTION_BLOCK Valve
VAR_INPUT open_pct : INT; END_VAR
VAR_OUTPUT flow : INT; END_VAR
flow := 1000 / open_pct;
END_FUNCTION_BLOCK
PROGRAM Filling
VAR_INPUT level : INT; END_VAR
VAR inlet : Valve; END_VAR
inlet(open_pct := level);
END_PROGRAM
CONFIGURATION Plant
  VAR_GLOBAL shared : Valve; END_VAR
  RESOURCE Cpu ON PLC
    TASK fast(INTERVAL := T#10ms, PRIORITY := 1);
    TASK slow(INTERVAL := T#20ms, PRIORITY := 2);
    PROGRAM tank1 WITH fast : Filling(level := 5);
    PROGRAM tank2 WITH slow : Filling(level := 0);
  END_RESOURCE
END_CONFIGURATION";

#[test]
fn a_fault_in_a_configuration_task_names_the_program_instance() {
    let f = first_fault(PLANT);
    assert_eq!(f.pou, "Valve");
    assert_eq!(f.instance(), "tank2.inlet");
    assert_eq!(chain(&f), owned(&[("tank2", "Filling", 9)]));
    let shown = f.to_string();
    assert!(shown.contains("(in tank2.inlet : Valve)"), "{shown}");
    assert!(
        shown.contains("= note: called from tank2 : Filling at test.st:9:1"),
        "{shown}"
    );
}

#[test]
fn a_global_instance_is_named_by_its_global_name() {
    let src = "FUNCTION_BLOCK Valve
VAR_INPUT open_pct : INT; END_VAR
VAR_OUTPUT flow : INT; END_VAR
flow := 1000 / open_pct;
END_FUNCTION_BLOCK
PROGRAM Filling
VAR_EXTERNAL shared : Valve; END_VAR
shared(open_pct := 0);
END_PROGRAM
CONFIGURATION Plant
  VAR_GLOBAL shared : Valve; END_VAR
  RESOURCE Cpu ON PLC
    TASK fast(INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM tank1 WITH fast : Filling;
  END_RESOURCE
END_CONFIGURATION";
    let f = first_fault(src);
    assert_eq!(f.instance(), "shared");
    assert_eq!(chain(&f), owned(&[("tank1", "Filling", 8)]));
}

#[test]
fn an_sfc_action_names_the_action_and_its_program() {
    let src = "FUNCTION_BLOCK Pump
VAR_INPUT k : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := 10 / k;
END_FUNCTION_BLOCK
PROGRAM Seq
VAR pump : Pump; zero : INT; END_VAR
INITIAL_STEP Idle : Fill(N); END_STEP
ACTION Fill :
  pump(k := zero);
END_ACTION
STEP Done : END_STEP
TRANSITION FROM Idle TO Done := FALSE; END_TRANSITION
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.instance(), "Seq.pump");
    let rows = chain(&f);
    assert_eq!(rows[0].0, "Seq.Fill");
    assert_eq!(rows[0].1, "Seq.Fill");
    assert_eq!(rows[0].2, 10);
    assert_eq!(rows.last().map(|r| r.0.as_str()), Some("Seq"));
}

#[test]
fn a_transition_condition_is_named() {
    let src = "PROGRAM Seq
VAR a, z : INT; END_VAR
INITIAL_STEP Idle : END_STEP
STEP Done : END_STEP
TRANSITION Check FROM Idle TO Done := a / z > 1; END_TRANSITION
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.pou, "Seq.Check");
    assert_eq!(f.instance(), "Seq.Check");
    assert_eq!(f.callers().last().map(|c| c.instance.as_str()), Some("Seq"));
}

#[test]
fn the_chain_is_the_same_when_the_fault_repeats_and_after_a_reset() {
    let mut plc = compile(LINE);
    let first = plc.run_cycle().expect_err("faults");
    // The PLC stays stopped on the same fault.
    assert_eq!(plc.run_cycle().expect_err("still faulted"), first);
    plc.reset_cold();
    let again = plc.run_cycle().expect_err("faults again");
    assert_eq!(again.callers(), first.callers());
    assert_eq!(again.instance(), first.instance());
}

#[test]
fn a_watchdog_fault_deep_in_calls_has_its_chain() {
    let src = "FUNCTION_BLOCK Spin
VAR i : DINT; END_VAR
WHILE TRUE DO i := i + 1; END_WHILE
END_FUNCTION_BLOCK
PROGRAM P
VAR s : Spin; END_VAR
s();
END_PROGRAM";
    let options = Options {
        watchdog: Some(std::time::Duration::from_millis(20)),
        ..Options::default()
    };
    let mut plc = Plc::compile_files(&[("test.st", src)], &options).expect("compiles");
    let f = plc.run_cycle().expect_err("watchdog");
    assert_eq!(f.code(), "R008");
    assert_eq!(f.instance(), "P.s");
    assert_eq!(chain(&f), owned(&[("P", "P", 7)]));
}

#[test]
fn two_files_give_each_location_its_file() {
    let lib = "FUNCTION_BLOCK Div
VAR_INPUT a, b : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := a / b;
END_FUNCTION_BLOCK";
    let main = "PROGRAM Main
VAR d : Div; END_VAR
d(a := 1, b := 0);
END_PROGRAM";
    let mut plc = compile_files(&[("lib.st", lib), ("main.st", main)]);
    let f = plc.run_cycle().expect_err("faults");
    assert!(f.location.starts_with("lib.st:4:"), "{}", f.location);
    assert_eq!(f.callers()[0].location, "main.st:3:1");
}

#[test]
fn a_faulting_unit_test_reports_the_instance_and_its_callers() {
    let mut sources = plcrun::SourceMap::new();
    sources.add(
        "t.st",
        "FUNCTION_BLOCK Avg
VAR_INPUT sum, n : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := sum / n;
END_FUNCTION_BLOCK
PROGRAM TEST_Avg
VAR a : Avg; END_VAR
a(sum := 10, n := 0);
END_PROGRAM",
    );
    let report = plcrun::run_tests(&sources, &plcrun::TestOptions::default()).expect("runs");
    let fault = report.cases[0].fault.as_ref().expect("faulted");
    assert_eq!(fault.instance(), "TEST_Avg.a");
    let text = report.to_text();
    assert!(
        text.contains("(in TEST_Avg.a : Avg): division by zero"),
        "{text}"
    );
    assert!(
        text.contains("= note: called from TEST_Avg at t.st:8:1"),
        "{text}"
    );
    let xml = report.to_junit("s");
    assert!(
        xml.contains("= note: called from TEST_Avg at t.st:8:1"),
        "{xml}"
    );
}

#[test]
fn an_instance_local_to_a_method_is_named_method_dot_variable() {
    let src = "FUNCTION_BLOCK Divider
VAR_INPUT n, d : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := n / d;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Cell
METHOD Share : INT
VAR_INPUT total, parts : INT; END_VAR
VAR cut : Divider; END_VAR
cut(n := total, d := parts);
Share := cut.q;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM P
VAR parts, r : INT; c : Cell; END_VAR
r := c.Share(100, parts);
END_PROGRAM";
    let f = first_fault(src);
    assert_eq!(f.fault.kind, FaultKind::DivisionByZero);
    assert_eq!(f.pou, "Divider");
    // Not the hidden member `Cell__Share__cut` the method's local lives in.
    assert_eq!(f.instance(), "P.c.Share.cut");
    assert_eq!(
        chain(&f),
        owned(&[("P.c.Share", "Cell.Share", 10), ("P", "P", 16)])
    );
    // The name the fault gives is one the library resolves.
    let mut plc = compile(src);
    plc.write("parts", "4").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read_i64("c.Share.cut.q").unwrap(), 25);
    assert_eq!(plc.read_i64("c.Share.parts").unwrap(), 4);
    let listed: Vec<String> = plc.variables().into_iter().map(|v| v.path).collect();
    assert!(listed.contains(&"c.Share.cut.q".to_string()), "{listed:?}");
    let err = plc.read_i64("c.Share.nothing").unwrap_err().to_string();
    assert!(err.contains("has no member `Share`"), "{err}");
}

#[test]
fn a_name_written_with_double_underscores_is_not_taken_for_a_methods_local() {
    let src = "FUNCTION_BLOCK F
VAR_OUTPUT a__b__c : INT; END_VAR
a__b__c := 7;
END_FUNCTION_BLOCK
PROGRAM P
VAR f : F; END_VAR
f();
END_PROGRAM";
    let mut plc = compile(src);
    plc.run_cycle().unwrap();
    let listed: Vec<String> = plc.variables().into_iter().map(|v| v.path).collect();
    assert!(listed.contains(&"f.a__b__c".to_string()), "{listed:?}");
    assert_eq!(plc.read_i64("f.a__b__c").unwrap(), 7);
}
