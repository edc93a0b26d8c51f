//! A METHOD's declarations see the method's own names first, as its body
//! does: a local `VAR CONSTANT` array built from local constants, array
//! bounds and string lengths given by them, as in a PROGRAM — even when
//! the FB declares a constant of the same name.

use crate::support::plc;

use plc::{compile, lit, run};

const SRC: &str = "
FUNCTION_BLOCK FB_T
VAR_OUTPUT s, t, len : INT; END_VAR
VAR CONSTANT N : INT := 100; END_VAR
METHOD Sum : INT
VAR CONSTANT
  B : INT := A + 1;
  A : INT := 1;
  N : INT := 3;
  C : INT := 5;
  Arr : ARRAY[1..N] OF INT := [A, B, C];
END_VAR
VAR s2 : STRING[N] := 'abcdef'; END_VAR
Sum := Arr[1] + Arr[2] + Arr[N];
len := LEN(s2);
END_METHOD
s := Sum();
t := N;
END_FUNCTION_BLOCK
PROGRAM P
VAR fb : FB_T; r, q, n : INT; END_VAR
fb();
r := fb.s;
q := fb.t;
n := fb.len;
END_PROGRAM
";

#[test]
fn a_method_local_constant_array_is_built_from_the_methods_own_constants() {
    let mut plc = compile(SRC);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.r"), "8", "1 + 2 + 5");
    assert_eq!(lit(&plc, "P.n"), "3", "STRING[N] with the method's N = 3");
    assert_eq!(lit(&plc, "P.q"), "100", "the FB's own N is untouched");
}
