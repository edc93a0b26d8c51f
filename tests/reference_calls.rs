//! Calls through references and `REFERENCE TO` parameters (CODESYS):
//! a METHOD called through a `REFERENCE TO` variable or input (`r.M()`)
//! or through a dereferenced `REF_TO` (`p^.M()`), as a statement and inside
//! an expression; and a `REFERENCE TO` input of a FUNCTION, FUNCTION_BLOCK
//! or METHOD bound by the call to the variable given (an FB instance or an
//! elementary variable), as `r REF= x` would; a PROPERTY read and
//! written through a reference; the body of an instance called through
//! a `REFERENCE TO` bound to it.

use crate::support::plc;

use plc::{compile, error_codes, lit, run};

const FB_X: &str = "
FUNCTION_BLOCK FB_X
VAR_OUTPUT n : INT; END_VAR
METHOD M : INT
n := n + 1;
M := n;
END_METHOD
METHOD Twice : INT
VAR_INPUT other : REFERENCE TO FB_X; END_VAR
Twice := other.M() + other.M();
END_METHOD
END_FUNCTION_BLOCK
";

#[test]
fn a_method_is_called_through_a_reference_and_a_dereferenced_ref_to() {
    let src = format!(
        "{FB_X}
FUNCTION UseRef : INT
VAR_INPUT r : REFERENCE TO FB_X; END_VAR
UseRef := r.M() * 100;
END_FUNCTION
PROGRAM P
VAR x, y : FB_X; r : REFERENCE TO FB_X; px : REF_TO FB_X; a, b, c, d : INT; END_VAR
r REF= x;
a := r.M();
r.M();
px := REF(x);
b := px^.M();
px^.M();
c := UseRef(r := x);
d := y.Twice(x);
END_PROGRAM
"
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "1");
    assert_eq!(lit(&plc, "P.b"), "3");
    assert_eq!(lit(&plc, "P.c"), "500", "UseRef's r is bound to x");
    assert_eq!(lit(&plc, "P.d"), "13", "6 + 7, on x");
    assert_eq!(lit(&plc, "P.x.n"), "7");
    assert_eq!(lit(&plc, "P.y.n"), "0");
}

#[test]
fn a_reference_to_input_is_bound_to_an_elementary_variable() {
    let src = "
FUNCTION Inc : INT
VAR_INPUT r : REFERENCE TO INT; END_VAR
r := r + 1;
Inc := r;
END_FUNCTION
FUNCTION_BLOCK FB_R
VAR_INPUT r : REFERENCE TO INT; END_VAR
r := r + 10;
END_FUNCTION_BLOCK
PROGRAM P
VAR i, j, k : INT; f : FB_R; rr : REFERENCE TO INT; pk : REF_TO INT; END_VAR
j := Inc(r := i);
j := Inc(i);
f(r := i);
rr REF= i;
j := Inc(rr);
pk := REF(k);
k := Inc(pk) + Inc(REF(k));
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.i"), "13");
    assert_eq!(lit(&plc, "P.j"), "13");
    assert_eq!(
        lit(&plc, "P.k"),
        "3",
        "a REF_TO value still converts: 1 + 2"
    );
}

#[test]
fn a_reference_to_input_needs_a_writable_variable_of_its_target_type() {
    let src = "
FUNCTION Inc : INT
VAR_INPUT r : REFERENCE TO INT; END_VAR
Inc := r;
END_FUNCTION
PROGRAM P
VAR CONSTANT c : INT := 1; END_VAR
VAR i : INT; d : DINT; END_VAR
i := Inc(c);
i := Inc(d);
i := Inc(i + 1);
END_PROGRAM
";
    let got = error_codes(&[("test.st", src)]);
    let got: Vec<(&str, &str)> = got.iter().map(|(c, a)| (c.as_str(), a.as_str())).collect();
    assert_eq!(
        got,
        [("E412", "9:10"), ("E301", "10:10"), ("E301", "11:10")]
    );
}

#[test]
fn a_property_is_read_and_written_through_a_reference() {
    let src = "
FUNCTION_BLOCK FB_P
VAR v : INT := 7; END_VAR
PROPERTY Val : INT
GET
Val := v;
END_GET
SET
v := Val;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM P
VAR x : FB_P; r : REFERENCE TO FB_P; px : REF_TO FB_P; a, b, c : INT; END_VAR
r REF= x;
a := r.Val;
r.Val := 9;
px := REF(x);
b := px^.Val;
px^.Val := b + 1;
c := x.Val;
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "7");
    assert_eq!(lit(&plc, "P.b"), "9");
    assert_eq!(lit(&plc, "P.c"), "10");
}

/// The body of the instance a `REFERENCE TO FB` is bound to, called
/// through it (`fbCurrentSegment(fbElectronEnergy := e);` in PMPS), with
/// inputs and outputs; bound again to another instance, the next call
/// runs that one.
#[test]
fn an_instance_is_called_through_a_reference_bound_to_it() {
    let src = "
FUNCTION_BLOCK FB_Seg
VAR_INPUT e : REAL; END_VAR
VAR_OUTPUT p : REAL; calls : INT; END_VAR
p := e * 2.0;
calls := calls + 1;
END_FUNCTION_BLOCK
PROGRAM main
VAR
  segs : ARRAY[1..2] OF FB_Seg;
  cur : REFERENCE TO FB_Seg;
  x, y : REAL;
END_VAR
cur REF= segs[1];
cur(e := 3.0, p => x);
cur REF= segs[2];
cur(e := 5.0);
y := cur.p;
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "x"), "6.0");
    assert_eq!(lit(&plc, "y"), "10.0");
    assert_eq!(lit(&plc, "segs[1].calls"), "2");
    assert_eq!(lit(&plc, "segs[2].calls"), "2");
}
