//! Edition-3 partial access (`w.%X3`, `d.%B1`, `l.%W0`, `l.%D1`) and `.n`
//! bit access: read and written in place, on bit strings (IEC 61131-3
//! edition 3) and on integers (CODESYS, warning W322); a part beyond the
//! variable's width is E423 at compile time. Every expected value is worked
//! out by hand: part `n` of width `w` is bits `n*w .. n*w+w-1`.

use crate::support::access_diags;
use crate::support::plc;

use access_diags::{codes_at, diags};
use plc::{lit, program, run_once};
use plcrun::Severity;
use rstest::rstest;

fn eval(decls: &str, body: &str, var: &str) -> String {
    lit(&run_once(&program("", decls, body)), var)
}

#[rstest]
// 16#1234: byte 0 is 16#34, byte 1 is 16#12.
#[case("w : WORD := 16#1234; r : BYTE;", "r := w.%B0;", "16#34")]
#[case("w : WORD := 16#1234; r : BYTE;", "r := w.%B1;", "16#12")]
#[case("w : WORD := 16#1234; r : BYTE;", "r := w.%b1;", "16#12")]
// 16#12345678: word 1 is the high half, byte 3 the top byte.
#[case("d : DWORD := 16#12345678; r : WORD;", "r := d.%W1;", "16#1234")]
#[case("d : DWORD := 16#12345678; r : WORD;", "r := d.%W0;", "16#5678")]
#[case("d : DWORD := 16#12345678; r : BYTE;", "r := d.%B3;", "16#12")]
#[case(
    "l : LWORD := 16#0123456789ABCDEF; r : DWORD;",
    "r := l.%D1;",
    "16#1234567"
)]
#[case(
    "l : LWORD := 16#0123456789ABCDEF; r : DWORD;",
    "r := l.%D0;",
    "16#89ABCDEF"
)]
#[case("l : LWORD := 16#0123456789ABCDEF; r : WORD;", "r := l.%W3;", "16#123")]
#[case(
    "l : LWORD := 16#0123456789ABCDEF; r : LWORD;",
    "r := l.%L0;",
    "16#123456789ABCDEF"
)]
// 16#0008 has bit 3 set and bit 2 clear.
#[case("w : WORD := 16#0008; r : BOOL;", "r := w.%X3;", "TRUE")]
#[case("w : WORD := 16#0008; r : BOOL;", "r := w.%X2;", "FALSE")]
#[case("b : BYTE := 16#80; r : BOOL;", "r := b.%X7;", "TRUE")]
#[case("b : BYTE := 16#01; r : BOOL;", "r := b.%X0;", "TRUE")]
fn parts_are_read(#[case] decls: &str, #[case] body: &str, #[case] expected: &str) {
    assert_eq!(eval(decls, body, "r"), expected);
}

#[rstest]
// Only the part changes: 16#1234 with byte 1 := 16#AB is 16#AB34.
#[case("w : WORD := 16#1234;", "w.%B1 := 16#AB;", "w", "16#AB34")]
#[case("w : WORD := 16#1234;", "w.%B0 := 16#CD;", "w", "16#12CD")]
#[case("d : DWORD;", "d.%W1 := 16#FFFF;", "d", "16#FFFF0000")]
#[case("d : DWORD := 16#FFFFFFFF;", "d.%B2 := 0;", "d", "16#FF00FFFF")]
#[case("l : LWORD;", "l.%D1 := 16#DEADBEEF;", "l", "16#DEADBEEF00000000")]
#[case("l : LWORD := 1;", "l.%W2 := 16#00FF;", "l", "16#FF00000001")]
#[case("w : WORD;", "w.%X15 := TRUE;", "w", "16#8000")]
#[case("w : WORD := 16#FFFF;", "w.%X0 := FALSE;", "w", "16#FFFE")]
#[case("b : BYTE; one : BOOL := TRUE;", "b.%X6 := one;", "b", "16#40")]
fn parts_are_written_in_place(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] var: &str,
    #[case] expected: &str,
) {
    assert_eq!(eval(decls, body, var), expected);
}

#[rstest]
// Bit 15 of an INT is its sign bit: 16#8000 is -32768.
#[case("i : INT;", "i.15 := TRUE;", "i", "-32768")]
#[case("i : INT := -32768; r : BOOL;", "r := i.15;", "r", "TRUE")]
// -1 is all ones: each byte is 16#FF.
#[case("i : INT := -1; r : BYTE;", "r := i.%B1;", "r", "16#FF")]
// -1 with its high byte cleared is 16#00FF = 255.
#[case("i : INT := -1;", "i.%B1 := 0;", "i", "255")]
// 16#80000005 as a DINT: -2147483648 + 5.
#[case("d : DINT := 5;", "d.31 := TRUE;", "d", "-2147483643")]
#[case("u : UINT := 16#0100; r : BOOL;", "r := u.8;", "r", "TRUE")]
#[case("s : SINT := 0;", "s.%X7 := TRUE;", "s", "-128")]
#[case("li : LINT := -1; r : DWORD;", "r := li.%D1;", "r", "16#FFFFFFFF")]
fn integers_take_partial_access_like_codesys(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] var: &str,
    #[case] expected: &str,
) {
    assert_eq!(eval(decls, body, var), expected);
}

#[test]
fn partial_access_on_an_integer_warns_w322_and_on_a_bit_string_does_not() {
    let src = program("", "i : INT; w : WORD; x : BOOL;", "x := i.3;\nx := w.3;");
    let d = diags(&src);
    assert_eq!(
        d,
        vec![("W322".to_string(), Severity::Warning, "6:6".to_string())],
        "{d:?}"
    );
}

#[test]
fn il_loads_and_stores_parts() {
    let src = "PROGRAM P\nVAR w : WORD := 16#1234; b : BYTE; x : BOOL; END_VAR\n\
               LD w.%B1\nST b\nLD 16#FF\nST w.%B0\nLD TRUE\nST w.%X15\nLD w.%X12\nST x\n\
               END_PROGRAM\n";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "b"), "16#12");
    // 16#12FF with bit 15 set: 16#92FF; bit 12 of 16#1234 is 1.
    assert_eq!(lit(&plc, "w"), "16#92FF");
    assert_eq!(lit(&plc, "x"), "TRUE");
}

#[test]
fn parts_of_array_elements_and_struct_fields() {
    let prelude = "TYPE S : STRUCT d : DWORD; END_STRUCT; END_TYPE";
    let decls = "a : ARRAY[0..2] OF WORD; i : INT := 2; s : S;";
    let body = "a[i].%B1 := 16#7F; s.d.%W1 := a[2]; a[0].%X0 := s.d.%X16;";
    let plc = run_once(&program(prelude, decls, body));
    assert_eq!(lit(&plc, "a[2]"), "16#7F00");
    assert_eq!(lit(&plc, "s.d"), "16#7F000000");
    assert_eq!(lit(&plc, "a[0]"), "16#0");
}

#[rstest]
// Line 6 is the body; columns point at the partial access.
#[case("w : WORD; x : BOOL;", "x := w.%X16;", "E423@6:6")]
#[case("w : WORD; x : BYTE;", "x := w.%B2;", "E423@6:6")]
#[case("b : BYTE; x : WORD;", "x := b.%W0;", "E423@6:6")]
#[case("d : DWORD; x : DWORD;", "x := d.%D1;", "E423@6:6")]
#[case("w : WORD; x : BOOL;", "x := w.16;", "E423@6:6")]
#[case("w : WORD;", "w.%B2 := 1;", "E423@6:1")]
#[case("w : WORD;", "w.16 := TRUE;", "E423@6:1")]
#[case("l : LWORD; x : BYTE;", "x := l.%B99999999999999999999;", "E423@6:6")]
#[case("r : REAL; x : BOOL;", "x := r.%X0;", "E302@6:6")]
#[case("t : TIME; x : BYTE;", "x := t.%B0;", "E302@6:6")]
#[case("b : BOOL; x : BOOL;", "x := b.%X0;", "E302@6:6")]
fn partial_access_errors_have_a_code_and_a_place(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] expected: &str,
) {
    let got = codes_at(&program("", decls, body));
    assert_eq!(got, vec![expected.to_string()], "{got:?}");
}

#[test]
fn a_part_of_a_constant_cannot_be_written() {
    let src = "PROGRAM P\nVAR CONSTANT c : WORD := 1; END_VAR\nc.%B0 := 2;\nEND_PROGRAM\n";
    assert_eq!(codes_at(src), vec!["E401@3:1".to_string()]);
}

#[test]
fn a_malformed_partial_access_keeps_a_lexical_error() {
    let got = codes_at(&program("", "w : WORD; x : BOOL;", "x := w.%X;"));
    assert!(got.iter().any(|c| c.starts_with("E009@6:8")), "{got:?}");
}

/// CODESYS's bit access with an integer constant: `w.en` with
/// `en : INT := 3` is bit 3 (W323).
const BIT_CONSTANTS: &str = "VAR_GLOBAL CONSTANT en : INT := 3; big : INT := 16; END_VAR TYPE S : STRUCT en : BOOL; END_STRUCT; END_TYPE";

#[test]
fn a_bit_named_by_a_constant_is_read_and_written() {
    let decls = "w : WORD := 16#0008; x : BOOL; y : WORD; s : S;";
    let body = "x := w.en;\ny.en := TRUE;\ns.en := TRUE;";
    let plc = run_once(&program(BIT_CONSTANTS, decls, body));
    assert_eq!(lit(&plc, "x"), "TRUE");
    assert_eq!(lit(&plc, "y"), "16#8");
    // A field of that name stays a field.
    assert_eq!(lit(&plc, "s.en"), "TRUE");
}

#[test]
fn a_bit_named_by_a_constant_warns_w323_and_is_checked_against_the_width() {
    let decls = "w : WORD; x : BOOL; s : S;";
    let got = codes_at(&program(BIT_CONSTANTS, decls, "x := w.en;\ns.en := x;"));
    assert_eq!(got, vec!["W323@6:8"], "{got:?}");
    let got = codes_at(&program(BIT_CONSTANTS, decls, "x := w.big;"));
    assert_eq!(got, vec!["W323@6:8", "E423@6:6"], "{got:?}");
}
