//! `ADR` of an array element is a pointer into the whole array (CODESYS
//! code walks arrays from `ADR(a[0])` and copies whole buffers from the
//! address of their first element), and the distance between two
//! pointers is their difference in bytes (lcls-twincat-physics measures a
//! table's row size as `ADR(t[1,0]) - ADR(t[0,0])`). Both stay inside the
//! array: walking past its end faults (R031).

use crate::support::plc::{compile, first_fault, lit, run};

#[test]
fn a_pointer_to_an_element_moves_along_its_array() {
    let src = "
PROGRAM main
VAR
  t : ARRAY[0..5, 0..2] OF LREAL;
  row, next : POINTER TO ARRAY[0..2] OF LREAL;
  p : POINTER TO LREAL;
  size : DINT;
  x, y : LREAL;
  i : INT;
END_VAR
FOR i := 0 TO 5 DO
  t[i, 0] := i; t[i, 1] := i * 10; t[i, 2] := i * 100;
END_FOR
size := ADR(t[1, 0]) - ADR(t[0, 0]);
row := ADR(t[0, 0]);
next := row + size * 4;
x := next^[1];
p := ADR(t[2, 0]);
p := p + 8;
y := p^;
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    // A row is three LREALs; four rows on, element 1 of row 4.
    assert_eq!(lit(&plc, "size"), "24");
    assert_eq!(lit(&plc, "x"), "40.0");
    assert_eq!(lit(&plc, "y"), "20.0");
}

#[test]
fn a_whole_buffer_is_copied_from_the_address_of_its_first_element() {
    // A byte copy as TwinCAT's MEMCPY makes it (Tc2_System).
    let src = "
FUNCTION COPY_BYTES : UDINT
VAR_INPUT dst, src : ULINT; n : UDINT; END_VAR
VAR d, s : POINTER TO BYTE; i : UDINT; END_VAR
d := dst; s := src;
FOR i := 1 TO n DO d^ := s^; d := d + 1; s := s + 1; END_FOR
COPY_BYTES := n;
END_FUNCTION
PROGRAM main
VAR
  a : ARRAY[1..4] OF INT := [1, -2, 300, 4];
  b : ARRAY[1..4] OF INT;
  n : UDINT;
END_VAR
n := COPY_BYTES(ADR(b[1]), ADR(a[1]), SIZEOF(a));
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "8");
    assert_eq!(lit(&plc, "b[2]"), "-2");
    assert_eq!(lit(&plc, "b[3]"), "300");
    assert_eq!(lit(&plc, "b[4]"), "4");
}

#[test]
fn walking_past_the_array_faults_at_the_dereference() {
    let src = "
PROGRAM main
VAR
  a : ARRAY[0..3] OF DINT;
  guard : DINT;
  p : POINTER TO DINT;
  v : DINT;
END_VAR
p := ADR(a[3]);
v := p^;
p := p + 4;
v := p^;
END_PROGRAM";
    let fault = first_fault(src);
    assert_eq!(fault.code(), "R031", "{fault}");
}

#[test]
fn a_distance_between_pointers_to_structures_is_refused() {
    let src = "
TYPE S : STRUCT a : INT; b : REAL; END_STRUCT END_TYPE
PROGRAM main
VAR s : ARRAY[0..1] OF S; d : DINT; END_VAR
d := ADR(s[1]) - ADR(s[0]);
END_PROGRAM";
    let codes = crate::support::plc::error_codes(&[("test.st", src)]);
    assert_eq!(codes, [("E252".to_string(), "5:6".to_string())]);
}
