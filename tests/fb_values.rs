//! Function block instances as values, as CODESYS and TwinCAT allow them
//! (issue #25, point 2): copy assignment, a FUNCTION returning an
//! instance, instances local to a FUNCTION (fresh at every call) and
//! passed by value. Each expected value is derived by hand from the
//! program.

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
fn a_function_returns_a_copy_of_its_local_instance() {
    let src = format!(
        "{VEC}
FUNCTION F_Add : FB_Vec
VAR_INPUT a : FB_Vec; b : FB_Vec; END_VAR
VAR tmp : FB_Vec; END_VAR
tmp.Set(a.x + b.x, a.y + b.y);
F_Add := tmp;
END_FUNCTION
PROGRAM P
VAR u : FB_Vec; w : FB_Vec; s : FB_Vec; len : LREAL; END_VAR
u.Set(3, 0);
w.Set(0, 4);
s := F_Add(u, w);
len := s.Len();
END_PROGRAM
"
    );
    let mut plc = compile(&src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "s.x"), "3.0");
    assert_eq!(lit(&plc, "s.y"), "4.0");
    assert_eq!(lit(&plc, "len"), "5.0");
    // tmp is fresh at each call: Set ran once on it, from its initial 100.
    assert_eq!(lit(&plc, "s.calls"), "101");
    // u was set twice (two cycles); passing it by value did not change it.
    assert_eq!(lit(&plc, "u.calls"), "102");
}

/// An instance holding strings, returned by a FUNCTION and passed to one
/// (lcls-twincat-math's F_EulerToQuat returns such a block): the strings
/// travel by text, each copy with its own.
#[test]
fn an_instance_holding_strings_is_returned_and_passed_with_its_text() {
    let src = "
FUNCTION_BLOCK FB_Named
VAR_OUTPUT name : STRING := 'none'; tag : STRING[4]; n : INT; END_VAR
VAR history : ARRAY[0..1] OF STRING[8]; END_VAR
METHOD Rename
VAR_INPUT newName : STRING; END_VAR
history[1] := history[0]; history[0] := name;
name := newName; tag := newName; n := n + 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION F_Make : FB_Named
VAR_INPUT base : STRING; END_VAR
VAR tmp : FB_Named; END_VAR
tmp.Rename(CONCAT(base, '-a'));
tmp.Rename(CONCAT(base, '-b'));
F_Make := tmp;
END_FUNCTION
FUNCTION F_Len : INT
VAR_INPUT v : FB_Named; END_VAR
v.Rename('changed');
F_Len := LEN(v.name) + v.n;
END_FUNCTION
PROGRAM P
VAR one : FB_Named; two : FB_Named; l : INT; END_VAR
one := F_Make('first');
two := F_Make('second');
l := F_Len(two);
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "one.name"), "'first-b'");
    assert_eq!(lit(&plc, "one.tag"), "'firs'");
    assert_eq!(lit(&plc, "one.history[0]"), "'first-a'");
    assert_eq!(lit(&plc, "one.history[1]"), "'none'");
    assert_eq!(lit(&plc, "two.name"), "'second-b'");
    assert_eq!(lit(&plc, "two.n"), "2");
    // F_Len renamed its own copy: 'changed' (7) and n 3; `two` unchanged.
    assert_eq!(lit(&plc, "l"), "10");
}

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
fn an_instance_passed_by_value_is_a_copy_the_function_may_change() {
    let src = format!(
        "{VEC}
FUNCTION F_Bump : INT
VAR_INPUT v : FB_Vec; END_VAR
v.Set(0, 0);
F_Bump := v.calls;
END_FUNCTION
PROGRAM P
VAR a : FB_Vec; seen : INT; END_VAR
seen := F_Bump(a);
END_PROGRAM
"
    );
    let mut plc = compile(&src);
    run(&mut plc, 3);
    assert_eq!(
        (lit(&plc, "seen"), lit(&plc, "a.calls")),
        ("101".into(), "100".into())
    );
}

#[test]
fn wrong_types_programs_and_layout_cycles_are_refused_with_their_codes() {
    let other = format!(
        "{VEC}
FUNCTION_BLOCK FB_Other VAR_OUTPUT x : LREAL; END_VAR END_FUNCTION_BLOCK
PROGRAM P VAR a : FB_Vec; o : FB_Other; END_VAR a := o; END_PROGRAM
"
    );
    assert_eq!(error_codes(&[("t.st", &other)])[0].0, "E301");
    let program = "PROGRAM Q END_PROGRAM
FUNCTION F : Q END_FUNCTION
PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM
";
    assert_eq!(
        error_codes(&[("t.st", program)]),
        [("E209".to_string(), "2:10".to_string())]
    );
    // FB_A's code calls F_Next, which holds an FB_A: the sizes depend on
    // each other.
    let cycle = "PROGRAM P VAR a : FB_A; END_VAR a(n := 4); END_PROGRAM
FUNCTION_BLOCK FB_A
VAR_INPUT n : INT; END_VAR
VAR_OUTPUT v : INT; END_VAR
v := F_Next(n);
END_FUNCTION_BLOCK
FUNCTION F_Next : INT
VAR_INPUT n : INT; END_VAR
VAR tmp : FB_A; END_VAR
F_Next := n + 1 + tmp.v;
END_FUNCTION
";
    let codes = error_codes(&[("t.st", cycle)]);
    assert!(codes.iter().any(|(c, _)| c == "E204"), "{codes:?}");
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
