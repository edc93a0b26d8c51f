//! CODESYS pointers (docs/semantics.md "References and pointers"):
//! `POINTER TO`, `ADR`, `p^`, `SIZEOF`, byte arithmetic -- values checked,
//! the W30x compatibility warnings, and the faults of a pointer that
//! leaves the object it was taken from.

use crate::support::plc;

use plc::{compile, error_codes, first_fault, line_col, lit, program, run};
use plcrun::FaultKind;

fn warning_codes(src: &str) -> Vec<String> {
    let plc = compile(src);
    plc.warnings().iter().map(|d| d.code.to_string()).collect()
}

#[test]
fn adr_and_dereference() {
    let src = program(
        "",
        "x : DINT := 9; q : POINTER TO DINT; y : DINT; pp : POINTER TO POINTER TO DINT;",
        "q := ADR(x); y := q^ * 2; q^ := 1; pp := ADR(q); pp^^ := pp^^ + 10;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.y"), "18");
    assert_eq!(lit(&plc, "P.x"), "11");
}

#[test]
fn byte_arithmetic_walks_an_array() {
    // Sum of a BYTE array by a pointer stepping one byte, and of a DINT
    // array by a pointer stepping SIZEOF(DINT) = 4 bytes.
    let src = program(
        "",
        "b : ARRAY[0..4] OF BYTE := [1, 2, 3, 4, 5]; d : ARRAY[1..3] OF DINT := [10, 20, 30];
         pb : POINTER TO BYTE; pd : POINTER TO DINT; i : INT; sb : INT; sd : DINT;",
        "pb := ADR(b); sb := 0;
         FOR i := 0 TO 4 DO sb := sb + BYTE_TO_INT(pb^); pb := pb + 1; END_FOR;
         pd := ADR(d); sd := 0;
         FOR i := 1 TO 3 DO sd := sd + pd^; pd := pd + SIZEOF(DINT); END_FOR;
         pd := pd - 4; pd^ := -1;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.sb"), "15");
    assert_eq!(lit(&plc, "P.sd"), "60");
    assert_eq!(lit(&plc, "P.d[3]"), "-1");
}

#[test]
fn sizeof_counts_bytes() {
    let src = program(
        "TYPE Rec : STRUCT a : INT; b : LREAL; c : BOOL; END_STRUCT; END_TYPE",
        "r : Rec; arr : ARRAY[1..10] OF WORD; s : STRING(20); x : LINT;
         n1, n2, n3, n4, n5, n6 : UDINT;",
        "n1 := SIZEOF(r); n2 := SIZEOF(arr); n3 := SIZEOF(s); n4 := SIZEOF(INT);
         n5 := SIZEOF(x); n6 := SIZEOF(Rec);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    // INT 2 + LREAL 8 + BOOL 1, no padding
    assert_eq!(lit(&plc, "P.n1"), "11");
    assert_eq!(lit(&plc, "P.n2"), "20");
    assert_eq!(lit(&plc, "P.n3"), "21");
    assert_eq!(lit(&plc, "P.n4"), "2");
    assert_eq!(lit(&plc, "P.n5"), "8");
    assert_eq!(lit(&plc, "P.n6"), "11");
}

/// The OSCAT calling convention: `F(ADR(buffer), SIZEOF(buffer))` with
/// the buffer seen as `POINTER TO ARRAY[0..32767] OF BYTE`.
const BUFFER_FN: &str = "
FUNCTION Fill : INT
VAR_INPUT pt : POINTER TO ARRAY[0..32767] OF BYTE; size : UINT; v : BYTE; extra : INT; END_VAR
VAR i : INT; END_VAR
FOR i := 0 TO UINT_TO_INT(size) - 1 + extra DO pt^[i] := v; END_FOR;
Fill := i;
END_FUNCTION
";

#[test]
fn a_long_array_pointer_walks_a_short_buffer() {
    let src = program(
        BUFFER_FN,
        "buf : ARRAY[1..10] OF BYTE; n : INT;",
        "n := Fill(ADR(buf), SIZEOF(buf), 16#AA, 0);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.buf[1]"), "16#AA");
    assert_eq!(lit(&plc, "P.buf[10]"), "16#AA");
    assert_eq!(lit(&plc, "P.n"), "10");
}

#[test]
fn one_element_past_the_buffer_is_r031_not_the_next_variable() {
    let src = program(
        BUFFER_FN,
        "buf : ARRAY[1..10] OF BYTE; after : BYTE := 7; n : INT;",
        "n := Fill(ADR(buf), SIZEOF(buf), 1, 1);",
    );
    let f = first_fault(&src);
    assert_eq!(
        f.fault.kind,
        FaultKind::OutsideObject {
            offset: 10,
            width: 1,
            len: 10
        }
    );
    assert_eq!(f.fault.kind.code(), "R031");
    assert_eq!(f.pou, "Fill");
    // Line 5: the FOR loop; `pt^[i]` starts at column 48.
    assert_eq!(line_col(&f.location), (5, 48), "{}", f.location);
}

#[test]
fn arithmetic_out_of_the_object_faults_at_the_dereference() {
    let src = program(
        "",
        "x : INT; y : INT := 3; p : POINTER TO INT; c : INT;",
        "p := ADR(x) + 2; c := c + 1;\nIF c = 2 THEN y := p^; END_IF;",
    );
    let f = first_fault(&src);
    assert_eq!(f.fault.kind.code(), "R031");
    assert_eq!(f.cycle, 1);
    assert_eq!(line_col(&f.location), (7, 20), "{}", f.location);
    // Backwards too.
    let src = program(
        "",
        "x : INT; p : POINTER TO INT;",
        "p := ADR(x) - 2; p^ := 1;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R031");
}

#[test]
fn a_step_that_is_not_a_whole_element_faults() {
    let src = program(
        "",
        "d : ARRAY[0..3] OF DINT; p : POINTER TO DINT;",
        "p := ADR(d) + 2; p^ := 1;",
    );
    let f = first_fault(&src);
    assert_eq!(f.fault.kind.code(), "R031");
}

#[test]
fn codesys_forms_warn_with_their_codes() {
    let src = program(
        "",
        "x : INT; p : POINTER TO INT; n : UDINT; ok : BOOL;",
        "p := ADR(x); p := p + 2; p := p - 2; n := SIZEOF(x); ok := __ISVALIDREF(p);",
    );
    let codes = warning_codes(&src);
    for c in ["W300", "W301", "W302", "W303", "W305"] {
        assert!(codes.iter().any(|x| x == c), "{c} missing in {codes:?}");
    }
    // Edition-3 forms get none.
    let src = program(
        "",
        "x : INT; r : REF_TO INT;",
        "r := REF(x); IF r <> NULL THEN r^ := 1; END_IF;",
    );
    assert!(
        warning_codes(&src).iter().all(|c| !c.starts_with("W3")),
        "{:?}",
        warning_codes(&src)
    );
}

#[test]
fn pointer_misuse_is_refused() {
    let cases: &[(&str, &str, &str)] = &[
        // a byte view is not read as a structure
        ("p : POINTER TO BYTE; q : POINTER TO T;", "q := p;", "E256"),
        // nor may a byte view be read as a STRING
        (
            "s : STRING; p : POINTER TO STRING; b : BYTE;",
            "p := ADR(b);",
            "E256",
        ),
        // a pointer needs 32 bits
        ("p : POINTER TO INT; w : WORD;", "w := p;", "E301"),
        // ordering references (edition 3)
        (
            "x : INT; p, q : REF_TO INT; b : BOOL;",
            "b := p < q;",
            "E252",
        ),
        // the distance between pointers to structures (between pointers
        // to elementary values it is a number of bytes: element_addresses.rs)
        ("p, q : POINTER TO T; n : DINT;", "n := p - q;", "E252"),
        // moving by a REAL
        ("p : POINTER TO INT;", "p := p + 1.5;", "E252"),
    ];
    for (decls, body, code) in cases {
        let src = program("TYPE T : STRUCT a : INT; END_STRUCT; END_TYPE", decls, body);
        let errs = error_codes(&[("test.st", &src)]);
        assert_eq!(
            errs.first().map(|(c, _)| c.as_str()),
            Some(*code),
            "{body}: {errs:?}"
        );
    }
    // Refused before byte views and integer images (tests/pointer_byte_views.rs
    // checks what they do): now accepted, each with its warning.
    let accepted: &[(&str, &str, &str)] = &[
        ("x : INT; p : POINTER TO DINT;", "p := ADR(x);", "W306"),
        ("s : STRING; p : POINTER TO BYTE;", "p := ADR(s);", "W306"),
        (
            "x : INT; p, q : POINTER TO INT; b : BOOL;",
            "b := p < q;",
            "W307",
        ),
        ("p : POINTER TO INT; d : DWORD;", "d := p;", "W307"),
        ("p : POINTER TO INT; d : DWORD;", "p := d;", "W308"),
    ];
    for (decls, body, code) in accepted {
        let src = program("", decls, body);
        let errs = error_codes(&[("test.st", &src)]);
        assert!(errs.is_empty(), "{body}: {errs:?}");
        assert!(warning_codes(&src).iter().any(|c| c == code), "{body}");
    }
}
