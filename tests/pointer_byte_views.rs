//! Byte views through pointers (docs/semantics.md "Byte views through
//! pointers"): a `POINTER TO BYTE` over a STRING, a `POINTER TO DWORD`
//! over a REAL, arrays seen with another element type, pointers kept in
//! integers and compared -- values worked out by hand from CODESYS's
//! little-endian layout (written beside each), and the faults of a view
//! that leaves its object.

use crate::support::plc;

use plc::{compile, error_codes, first_fault, line_col, lit, program, run};
use plcrun::FaultKind;

fn run_once(src: &str) -> plcrun::Plc {
    let mut plc = compile(src);
    run(&mut plc, 1);
    plc
}

fn warnings(src: &str) -> Vec<String> {
    compile(src)
        .warnings()
        .iter()
        .map(|d| d.code.to_string())
        .collect()
}

#[test]
fn string_bytes_are_read_as_codesys_lays_them_out() {
    // STRING(10) 'HELLO' is 11 bytes: 'H'=16#48 'E'=16#45 'L' 'L' 'O'=16#4F,
    // the NUL at byte 5, then zeros up to byte 10.
    let src = program(
        "",
        "s : STRING(10) := 'HELLO'; ps : POINTER TO BYTE;
         pa : POINTER TO ARRAY[1..250] OF BYTE; w : POINTER TO WORD;
         b0, b1, b4, b5, b10 : BYTE; w01 : WORD; n : INT;",
        "ps := ADR(s); b0 := ps^; ps := ps + 1; b1 := ps^;
         pa := ADR(s); b4 := pa^[5]; b5 := pa^[6]; b10 := pa^[11];
         w := ADR(s); w01 := w^;
         ps := ADR(s); n := 0;
         WHILE ps^ <> 0 DO n := n + 1; ps := ps + 1; END_WHILE;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.b0"), "16#48");
    assert_eq!(lit(&plc, "P.b1"), "16#45");
    assert_eq!(lit(&plc, "P.b4"), "16#4F");
    assert_eq!(lit(&plc, "P.b5"), "16#0");
    assert_eq!(lit(&plc, "P.b10"), "16#0");
    // little-endian: byte 0 'H' low, byte 1 'E' high -> 16#4548
    assert_eq!(lit(&plc, "P.w01"), "16#4548");
    assert_eq!(lit(&plc, "P.n"), "5");
    assert!(warnings(&src).iter().any(|c| c == "W306"));
}

#[test]
fn string_bytes_written_change_and_end_the_text() {
    let src = program(
        "",
        "s : STRING(10) := 'HELLO'; t : STRING(10) := 'ABCDE'; u : STRING(10);
         pa : POINTER TO ARRAY[0..250] OF BYTE; len_t : INT;",
        // 'a' = 16#61 over 'E'; a NUL at byte 3 ends 'HaLLO' after 'HaL';
        // putting 'l' = 16#6C back at byte 3 brings the kept 'O' back.
        "pa := ADR(s); pa^[1] := 16#61; pa^[3] := 0;
         u := s;
         pa^[3] := 16#6C;
         pa := ADR(t); pa^[2] := 0; len_t := LEN(t);",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.u"), "'HaL'");
    assert_eq!(lit(&plc, "P.s"), "'HaLlO'");
    assert_eq!(lit(&plc, "P.t"), "'AB'");
    assert_eq!(lit(&plc, "P.len_t"), "2");
}

/// A string built byte by byte as OSCAT does (`pto := ADR(result)`,
/// characters, then `pto^ := 0`): the digits of a number, written into
/// the function's result.
const DIGITS: &str = "
FUNCTION Digits : STRING(20)
VAR_INPUT x : UDINT; END_VAR
VAR pto : POINTER TO BYTE; buf : ARRAY[0..9] OF BYTE; n, i : INT; END_VAR
REPEAT
  buf[n] := 48 + UDINT_TO_BYTE(x MOD 10);
  x := x / 10; n := n + 1;
UNTIL x = 0 END_REPEAT;
pto := ADR(Digits);
FOR i := n - 1 TO 0 BY -1 DO pto^ := buf[i]; pto := pto + 1; END_FOR;
pto^ := 0;
END_FUNCTION
";

#[test]
fn a_string_built_byte_by_byte() {
    let src = program(
        DIGITS,
        "a, b : STRING(20);",
        "a := Digits(40960); b := Digits(7);",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "'40960'");
    assert_eq!(lit(&plc, "P.b"), "'7'");
}

#[test]
fn real_bit_patterns_through_dword_pointers() {
    // 1.0 = 16#3F800000 (sign 0, exponent 127, mantissa 0); subtracting
    // 2**23 = 8388608 lowers the exponent by one: 2.0 -> 1.0 (OSCAT's
    // TEMP_PT halves its step so). 16#40490FDB is pi rounded to f32.
    let src = program(
        "",
        "r : REAL := 1.0; h : REAL := 2.0; pi : REAL; d : DWORD := 16#40490FDB;
         pd : POINTER TO DWORD; pr : POINTER TO REAL; bits : DWORD;",
        "pd := ADR(r); bits := pd^;
         pd := ADR(h); pd^ := pd^ - 8388608;
         pr := ADR(d); pi := pr^;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.bits"), "16#3F800000");
    assert_eq!(lit(&plc, "P.h"), "1.0");
    assert_eq!(lit(&plc, "P.pi"), "3.1415927");
}

#[test]
fn integers_seen_byte_by_byte_little_endian() {
    // 16#11223344 is stored 44 33 22 11; writing 16#AA at byte 1 gives
    // 16#1122AA44. An INT over the bytes FF FF is -1; a DWORD over the
    // bytes 01 02 03 04 of an array is 16#04030201.
    let src = program(
        "",
        "d : DWORD := 16#11223344; pb : POINTER TO BYTE; b0, b3 : BYTE;
         arr : ARRAY[0..3] OF BYTE := [1, 2, 3, 4]; pd : POINTER TO DWORD; da : DWORD;
         ws : ARRAY[1..2] OF WORD := [16#FFFF, 16#0102]; pi : POINTER TO INT; i1 : INT;
         pa : POINTER TO ARRAY[0..3] OF BYTE; hi : BYTE;",
        "pb := ADR(d); b0 := pb^; pb := pb + 3; b3 := pb^;
         pb := ADR(d); pb := pb + 1; pb^ := 16#AA;
         pd := ADR(arr); da := pd^;
         pi := ADR(ws); i1 := pi^;
         pa := ADR(ws); hi := pa^[3];",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.b0"), "16#44");
    assert_eq!(lit(&plc, "P.b3"), "16#11");
    assert_eq!(lit(&plc, "P.d"), "16#1122AA44");
    assert_eq!(lit(&plc, "P.da"), "16#4030201");
    assert_eq!(lit(&plc, "P.i1"), "-1");
    // ws[2] = 16#0102 is bytes 02 01 at 2 and 3
    assert_eq!(lit(&plc, "P.hi"), "16#1");
}

#[test]
fn a_view_stays_in_its_type() {
    // 16#FF into the low byte of INT 0: bytes FF 00 = 16#00FF = 255; into
    // the high byte: bytes 00 FF = 16#FF00 = -256 (sign-extended, as the
    // INT's own arithmetic then sees it). A BOOL written 16#40 reads TRUE.
    let src = program(
        "",
        "a, b : INT; c : BOOL; pb : POINTER TO BYTE; d : INT;",
        "pb := ADR(a); pb^ := 16#FF;
         pb := ADR(b); pb := pb + 1; pb^ := 16#FF; d := b + 1;
         pb := ADR(c); pb^ := 16#40;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "255");
    assert_eq!(lit(&plc, "P.b"), "-256");
    assert_eq!(lit(&plc, "P.d"), "-255");
    assert_eq!(lit(&plc, "P.c"), "TRUE");
}

#[test]
fn wide_strings_have_two_bytes_a_character() {
    // WSTRING(3) "AB": bytes 41 00 42 00 00 00 then zeros, 8 in all.
    let src = program(
        "",
        "w : WSTRING(3) := \"AB\"; pb : POINTER TO BYTE; b1, b2 : BYTE; n : UDINT;",
        "pb := ADR(w); pb := pb + 1; b1 := pb^; pb := pb + 1; b2 := pb^;
         pb := pb + 2; pb^ := 16#43; n := SIZEOF(w);",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.b1"), "16#0");
    assert_eq!(lit(&plc, "P.b2"), "16#42");
    assert_eq!(lit(&plc, "P.w"), "\"ABC\"");
    assert_eq!(lit(&plc, "P.n"), "8");
}

#[test]
fn one_byte_past_the_object_faults_with_its_location() {
    // STRING(5) has bytes 0..5: byte 6 is outside.
    let src = program(
        "",
        "s : STRING(5) := 'ABCDE'; pa : POINTER TO ARRAY[0..250] OF BYTE; b : BYTE; i : INT;",
        "pa := ADR(s);\nFOR i := 0 TO 6 DO b := pa^[i]; END_FOR;",
    );
    let f = first_fault(&src);
    assert_eq!(
        f.fault.kind,
        FaultKind::OutsideBytes {
            offset: 6,
            width: 1,
            len: 6
        }
    );
    assert_eq!(f.fault.kind.code(), "R031");
    // body line 2, `pa^[i]` at column 25
    assert_eq!(line_col(&f.location), (7, 25), "{}", f.location);

    // A REAL has 4 bytes: a DWORD read at byte 1 needs bytes 1..4.
    let src = program(
        "",
        "r : REAL; pb : POINTER TO BYTE; pd : POINTER TO DWORD; d : DWORD;",
        "pb := ADR(r); pb := pb + 1; pd := pb; d := pd^;",
    );
    assert_eq!(
        first_fault(&src).fault.kind,
        FaultKind::OutsideBytes {
            offset: 1,
            width: 4,
            len: 4
        }
    );

    // Before the start, and a write past the end.
    let src = program(
        "",
        "s : STRING(3); pb : POINTER TO BYTE;",
        "pb := ADR(s); pb := pb - 1; pb^ := 1;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R031");
    let src = program(
        "",
        "x : ARRAY[1..3] OF WORD; y : WORD; pb : POINTER TO BYTE;",
        "pb := ADR(x); pb := pb + 6; pb^ := 1;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R031");
}

/// OSCAT's `_BUFFER_CLEAR`, written here the same way: a pointer kept in
/// a DWORD, its low bits tested for alignment, a DWORD pointer moved by
/// 4 over a byte buffer, pointers compared with integers.
const CLEAR: &str = "
FUNCTION Clear : BOOL
VAR_INPUT pt : POINTER TO BYTE; size : UINT; END_VAR
VAR ptw : POINTER TO DWORD; temp, end, end32 : DWORD; END_VAR
temp := pt;
end := temp + UINT_TO_DWORD(size);
end32 := end - 3;
WHILE (pt < end) AND ((temp AND 16#00000003) > 0) DO
  pt^ := 0; pt := pt + 1; temp := temp + 1;
END_WHILE;
ptw := pt;
WHILE ptw < end32 DO ptw^ := 0; ptw := ptw + 4; END_WHILE;
pt := ptw;
WHILE pt < end DO pt^ := 0; pt := pt + 1; END_WHILE;
Clear := TRUE;
END_FUNCTION
";

#[test]
fn a_buffer_cleared_through_integer_images() {
    let src = program(
        CLEAR,
        "before : BYTE := 7; buf : ARRAY[0..9] OF BYTE := [1,2,3,4,5,6,7,8,9,10]; after : BYTE := 7;
         s : STRING(6) := 'ABCDEF'; ok : BOOL; sum : INT; i : INT;",
        "ok := Clear(ADR(buf), SIZEOF(buf)); ok := ok AND Clear(ADR(s), 3);
         FOR i := 0 TO 9 DO sum := sum + buf[i]; END_FOR;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.ok"), "TRUE");
    assert_eq!(lit(&plc, "P.sum"), "0");
    assert_eq!(lit(&plc, "P.before"), "16#7");
    assert_eq!(lit(&plc, "P.after"), "16#7");
    // the first 3 bytes cleared: the text ends at once ('DEF' stays past the NUL)
    assert_eq!(lit(&plc, "P.s"), "''");
    for w in ["W306", "W307"] {
        assert!(warnings(&src).iter().any(|c| c == w), "{w}");
    }
}

#[test]
fn pointers_compared_and_kept_in_integers() {
    let src = program(
        "",
        "a : ARRAY[0..7] OF BYTE; px, q, r : POINTER TO BYTE; d : DWORD; l : LWORD;
         lt, eq0, back, aligned, isnull : BOOL;",
        "px := ADR(a); q := px + 5; lt := px < q;
         d := q; r := d; back := r = q;
         l := px; r := l; r^ := 9;
         eq0 := px = 0; r := 0; isnull := r = 0;
         aligned := (d AND 16#FFFFF) = 5;",
    );
    let plc = run_once(&src);
    for name in ["lt", "back", "aligned", "isnull"] {
        assert_eq!(lit(&plc, &format!("P.{name}")), "TRUE", "{name}");
    }
    assert_eq!(lit(&plc, "P.eq0"), "FALSE");
    assert_eq!(lit(&plc, "P.a[0]"), "16#9");
    assert!(warnings(&src).iter().any(|c| c == "W308"));
}

#[test]
fn an_integer_no_pointer_gave_faults() {
    // 16#12345678 names object 16#123, which no ADR made.
    let src = program(
        "",
        "x : DWORD; d : DWORD := 16#12345678; px : POINTER TO BYTE; b : BYTE;",
        "px := ADR(x); px := d; b := px^;",
    );
    let f = first_fault(&src);
    assert_eq!(f.fault.kind, FaultKind::NotFromPointer);
    assert_eq!(f.fault.kind.code(), "R035");
    // 0 is NULL
    let src = program(
        "",
        "d : DWORD; px : POINTER TO BYTE; b : BYTE;",
        "px := d; b := px^;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R030");
}

#[test]
fn what_a_byte_view_cannot_do_faults() {
    // A pointer outside its object has no integer image (R036).
    let src = program(
        "",
        "a : ARRAY[0..3] OF BYTE; px : POINTER TO BYTE; d : DWORD;",
        "px := ADR(a) + 5; d := px;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R036");
    // A function block instance kept in an integer and read back as
    // bytes: no byte layout (R037); a structure read back as another
    // structure: a byte view is read as elementary values only (R034).
    // Read back as its own type, it is the structure again
    // (`a_structure_kept_in_an_integer_is_read_back`).
    let prelude = "TYPE T : STRUCT a : INT; b : REAL; END_STRUCT; END_TYPE\nTYPE U : STRUCT a : INT; b : REAL; END_STRUCT; END_TYPE\nFUNCTION_BLOCK FB_X\nVAR a : INT; END_VAR\nEND_FUNCTION_BLOCK";
    let src = program(
        prelude,
        "fb : FB_X; pf : POINTER TO FB_X; d : DWORD; pb : POINTER TO BYTE; b : BYTE;",
        "pf := ADR(fb); d := pf; pb := d; b := pb^;",
    );
    assert_eq!(first_fault(&src).fault.kind, FaultKind::NoByteLayout);
    let src = program(
        prelude,
        "t : T; pt : POINTER TO T; pu : POINTER TO U; d : DWORD; i : INT;",
        "pt := ADR(t); d := pt; pu := d; i := pu^.a;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R034");
    // A structure's bytes end where SIZEOF says (R031 past them).
    let src = program(
        prelude,
        "t : T; pb : POINTER TO BYTE; b : BYTE;",
        "pb := ADR(t) + SIZEOF(t); b := pb^;",
    );
    assert_eq!(first_fault(&src).fault.kind.code(), "R031");
}

#[test]
fn a_structure_kept_in_an_integer_is_read_back() {
    let src = program(
        "TYPE T : STRUCT a : INT; s : STRING; END_STRUCT; END_TYPE",
        "t : ARRAY[0..2] OF T; pt : POINTER TO T; d : LWORD; i : INT; s : STRING;",
        "t[1].a := 12; t[1].s := 'one'; pt := ADR(t[1]); d := pt; pt := 0; pt := d; i := pt^.a; s := pt^.s;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.i"), "12");
    assert_eq!(lit(&plc, "P.s"), "'one'");
}

#[test]
fn byte_views_are_refused_where_they_cannot_work() {
    let cases: &[(&str, &str, &str)] = &[
        ("fb : FB_X; px : POINTER TO BYTE;", "px := ADR(fb);", "E256"),
        ("h : H; px : POINTER TO BYTE;", "px := ADR(h);", "E256"),
        ("b : BYTE; px : POINTER TO STRING;", "px := ADR(b);", "E256"),
        ("b : BYTE; px : POINTER TO T;", "px := ADR(b);", "E256"),
        ("px : POINTER TO BYTE; i : INT;", "i := px;", "E301"),
    ];
    for (decls, body, code) in cases {
        // A function block instance, and a structure holding one, have no
        // bytes of their own.
        let prelude = "TYPE T : STRUCT a : INT; END_STRUCT; END_TYPE\nFUNCTION_BLOCK FB_X\nVAR a : INT; END_VAR\nEND_FUNCTION_BLOCK\nTYPE H : STRUCT a : INT; fb : FB_X; END_STRUCT; END_TYPE";
        let src = program(prelude, decls, body);
        let errs = error_codes(&[("test.st", &src)]);
        assert_eq!(
            errs.first().map(|(c, _)| c.as_str()),
            Some(*code),
            "{body}: {errs:?}"
        );
    }
}

#[test]
fn structure_bytes_are_its_fields_one_after_another() {
    // ST: INT a (bytes 0-1), STRING(5) s (2-7), REAL r (8-11), a pointer
    // (12-19): SIZEOF 20, no padding, as plcrun's SIZEOF counts.
    let prelude = "TYPE ST : STRUCT a : INT; s : STRING(5); r : REAL; p : POINTER TO INT; END_STRUCT; END_TYPE";
    let src = program(
        prelude,
        "x : ST := (a := 258, s := 'hi', r := 1.0); y : ST; n : INT; i : INT;
         ps, pd : POINTER TO BYTE; b0, b1, b2, b4, b11 : BYTE; w : POINTER TO WORD; w01 : WORD;",
        "x.p := ADR(n);
         ps := ADR(x); b0 := ps^; ps := ps + 1; b1 := ps^; ps := ps + 1; b2 := ps^;
         ps := ps + 2; b4 := ps^; ps := ps + 7; b11 := ps^;
         w := ADR(x); w01 := w^;
         n := SIZEOF(x);
         ps := ADR(x); pd := ADR(y);
         FOR i := 1 TO SIZEOF(x) DO pd^ := ps^; ps := ps + 1; pd := pd + 1; END_FOR;
         y.p^ := 5;",
    );
    let plc = run_once(&src);
    // 258 = 16#0102, little-endian; 'h' = 16#68; the NUL after 'hi';
    // REAL 1.0 = 16#3F800000, its high byte 16#3F at byte 11.
    let got: Vec<String> = ["b0", "b1", "b2", "b4", "b11", "w01", "n"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    assert_eq!(
        got,
        ["16#2", "16#1", "16#68", "16#0", "16#3F", "16#102", "5"]
    );
    // The copy by bytes is the structure, its pointer included (`y.p^`
    // wrote `n`, whose SIZEOF was 20 before).
    assert_eq!(lit(&plc, "P.y.a"), "258");
    assert_eq!(lit(&plc, "P.y.s"), "'hi'");
    assert_eq!(lit(&plc, "P.y.r"), "1.0");
    assert!(warnings(&src).iter().any(|c| c == "W306"));
}

#[test]
fn bytes_written_into_a_structure_change_its_fields() {
    // Byte 0 of a DINT field, a character of a STRING field, and the
    // elements of an array of structures at SIZEOF(ST) steps.
    let prelude = "TYPE ST : STRUCT d : DINT; s : STRING(3); END_STRUCT; END_TYPE";
    let src = program(
        prelude,
        "x : ST := (d := -1, s := 'abc'); arr : ARRAY[0..2] OF ST; pb : POINTER TO BYTE; k : INT;",
        "pb := ADR(x); pb^ := 0; pb := pb + 5; pb^ := 16#5A;
         pb := ADR(arr);
         FOR k := 0 TO 2 DO pb^ := INT_TO_BYTE(k + 1); pb := pb + SIZEOF(ST); END_FOR;",
    );
    let plc = run_once(&src);
    // -1 is 16#FFFFFFFF; its low byte cleared: 16#FFFFFF00 = -256.
    assert_eq!(lit(&plc, "P.x.d"), "-256");
    assert_eq!(lit(&plc, "P.x.s"), "'aZc'");
    assert_eq!(lit(&plc, "P.arr[0].d"), "1");
    assert_eq!(lit(&plc, "P.arr[2].d"), "3");
}

#[test]
fn a_pointer_to_an_element_of_structures_kept_in_an_integer_moves_by_bytes() {
    // `d + SIZEOF(ST)` is the next element, read back as a typed pointer.
    let prelude = "TYPE ST : STRUCT a : INT; s : STRING(7); END_STRUCT; END_TYPE";
    let src = program(
        prelude,
        "arr : ARRAY[0..2] OF ST; d : LWORD; pst : POINTER TO ST; a : INT; s : STRING;",
        "arr[2].a := 42; arr[2].s := 'two';
         d := ADR(arr); d := d + 2 * SIZEOF(ST); pst := d; a := pst^.a; s := pst^.s;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "42");
    assert_eq!(lit(&plc, "P.s"), "'two'");
}

#[test]
fn typed_pointers_keep_their_path() {
    // Same element type: no view, no warning beyond W300/W301.
    let src = program(
        "",
        "x : ARRAY[1..3] OF DINT := [1, 2, 3]; px : POINTER TO DINT; s : DINT;",
        "px := ADR(x); s := px^; px := px + 4; s := s + px^; px^ := 20;",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.s"), "3");
    assert_eq!(lit(&plc, "P.x[2]"), "20");
    let w = warnings(&src);
    assert!(!w.iter().any(|c| c == "W306" || c == "W307"), "{w:?}");
}
