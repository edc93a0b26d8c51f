//! Function block instances as values, as CODESYS and TwinCAT allow them
//! (issue #25, point 2): copy assignment and the initial values of an
//! instance's declaration; a FUNCTION still cannot hold or return one
//! (E209). Each expected value is derived by hand from the program.

use crate::support::plc;

use plc::{compile, error_codes, lit, run};

/// A vector block with state (`calls`) and methods, as lcls-twincat-math
/// writes its FB_Vec3.
const VEC: &str = "
FUNCTION_BLOCK FB_Vec
VAR_OUTPUT x : LREAL; y : LREAL; calls : INT := 100; END_VAR
METHOD Set
VAR_INPUT nx : LREAL; ny : LREAL; END_VAR
x := nx; y := ny; calls := calls + 1;
END_METHOD
METHOD Len : LREAL
Len := SQRT(x * x + y * y);
END_METHOD
END_FUNCTION_BLOCK
";

#[test]
fn copy_assignment_copies_the_whole_state_and_the_copies_then_go_their_own_way() {
    let src = format!(
        "{VEC}
PROGRAM P
VAR a : FB_Vec; b : FB_Vec; t1 : TON; t2 : TON; started : BOOL; END_VAR
IF NOT started THEN
  a.Set(1, 2);
  b := a;
  a.Set(5, 6);
  started := TRUE;
END_IF
t1(IN := TRUE, PT := T#100ms);
t2 := t1;
END_PROGRAM
"
    );
    let mut plc = compile(&src);
    run(&mut plc, 3);
    assert_eq!(
        [
            lit(&plc, "b.x"),
            lit(&plc, "b.calls"),
            lit(&plc, "a.x"),
            lit(&plc, "a.calls")
        ],
        ["1.0", "101", "5.0", "102"]
    );
    // A standard block copies too: t2 holds t1's elapsed time.
    assert_eq!(lit(&plc, "t2.ET"), lit(&plc, "t1.ET"));
    assert_eq!(lit(&plc, "t1.ET"), "T#20ms");
}

#[test]
fn an_instance_declaration_sets_the_initial_values_of_its_variables_and_pins() {
    let src = "
FUNCTION_BLOCK FB_C
VAR_INPUT inc : INT := 1; END_VAR
VAR_OUTPUT n : INT; END_VAR
VAR label : STRING := 'x'; END_VAR
n := n + inc;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Outer
VAR_OUTPUT inner : FB_C := (inc := 10); END_VAR
inner();
END_FUNCTION_BLOCK
PROGRAM P
VAR
  t : TON := (PT := T#30ms);
  c : FB_C := (inc := 5, label := 'five');
  d : FB_C;
  o : FB_Outer;
  q : BOOL;
END_VAR
t(IN := TRUE);
q := t.Q;
c();
d();
o();
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 3);
    // The TON's PT came from the declaration: Q after 30 ms, in cycle 3.
    assert_eq!(
        (lit(&plc, "t.PT"), lit(&plc, "q")),
        ("T#30ms".into(), "FALSE".into())
    );
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "q"), "TRUE");
    assert_eq!(
        [
            lit(&plc, "c.n"),
            lit(&plc, "c.label"),
            lit(&plc, "d.n"),
            lit(&plc, "o.inner.n")
        ],
        ["20", "'five'", "4", "40"]
    );
    let bad = "PROGRAM P VAR t : TON := (PX := T#1s); END_VAR END_PROGRAM";
    assert_eq!(
        error_codes(&[("t.st", bad)]),
        [("E201".to_string(), "1:27".to_string())]
    );
}

#[test]
fn a_function_holding_or_returning_an_instance_is_still_e209() {
    let src = format!(
        "{VEC}
FUNCTION F_Add : FB_Vec
VAR_INPUT a : INT; END_VAR
VAR tmp : FB_Vec; END_VAR
tmp.Set(1, 2);
END_FUNCTION
PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM
"
    );
    let codes: Vec<String> = error_codes(&[("t.st", &src)])
        .into_iter()
        .map(|(c, _)| c)
        .collect();
    assert_eq!(codes, ["E209", "E209"]);
}
