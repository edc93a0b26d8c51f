//! `UNION ... END_UNION` (CODESYS V3, TwinCAT 3): members share the
//! union's bytes, little-endian, as TwinCAT lays them out
//! (docs/semantics.md §27). Expected values worked out by hand from the
//! byte layout: 16#11223344 is the bytes 44 33 22 11.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};

const TYPES: &str = "
TYPE U_Word32 :
UNION
    dw : DWORD;
    b : ARRAY[0..3] OF BYTE;
    w : ARRAY[0..1] OF WORD;
    i : INT;
    r : REAL;
    x : BOOL;
END_UNION
END_TYPE
TYPE U_Wide :
UNION
    lr : LREAL;
    li : LINT;
    t : TIME;
END_UNION
END_TYPE";

#[test]
fn members_read_the_bytes_another_member_wrote() {
    let mut plc = compile(&program(
        TYPES,
        "u : U_Word32; b0, b3 : BYTE; w1 : WORD; i : INT; k : INT; x : BOOL;",
        "u.dw := 16#11223344;
         b0 := u.b[0]; b3 := u.b[3]; w1 := u.w[1]; i := u.i; x := u.x;
         k := 2;
         u.b[k] := 16#FF;",
    ));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "b0"), "16#44");
    assert_eq!(lit(&plc, "b3"), "16#11");
    assert_eq!(lit(&plc, "w1"), "16#1122");
    assert_eq!(lit(&plc, "i"), "13124"); // 16#3344
    assert_eq!(lit(&plc, "x"), "TRUE");
    // Writing one byte changed only that byte of the DWORD.
    assert_eq!(lit(&plc, "u.__UNION_BYTES[0]"), "16#11FF3344");
}

#[test]
fn a_signed_member_is_sign_extended_and_a_real_is_its_bit_pattern() {
    let mut plc = compile(&program(
        TYPES,
        "u : U_Word32; v : U_Wide; i : INT; dw : DWORD; li : LINT; t : TIME;",
        "u.w[0] := 16#FFFE; i := u.i;
         u.r := 1.0; dw := u.dw;
         v.lr := -2.0; li := v.li;
         v.li := 1500000000; t := v.t;",
    ));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "i"), "-2");
    assert_eq!(lit(&plc, "dw"), "16#3F800000");
    assert_eq!(lit(&plc, "li"), "-4611686018427387904");
    // TIME is 64-bit nanoseconds: 1.5 s.
    assert_eq!(lit(&plc, "t"), "T#1s500ms");
}

#[test]
fn unions_copy_pass_and_return_as_whole_values() {
    let src = format!(
        "{TYPES}
FUNCTION F_Swap : U_Word32
VAR_INPUT u : U_Word32; END_VAR
F_Swap.b[0] := u.b[3]; F_Swap.b[1] := u.b[2];
F_Swap.b[2] := u.b[1]; F_Swap.b[3] := u.b[0];
END_FUNCTION
PROGRAM P
VAR a, c : U_Word32; d : DWORD; n : UDINT; END_VAR
a.dw := 16#11223344;
c := F_Swap(a);
d := c.dw;
n := SIZEOF(a);
END_PROGRAM"
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "d"), "16#44332211");
    // SIZEOF: the largest member, 4 bytes, as TwinCAT counts it.
    assert_eq!(lit(&plc, "n"), "4");
}

#[test]
fn memcpy_through_the_address_of_a_member_fills_the_union() {
    // TcUnit's F_AnyToUnionValue: MEMCPY from a value's address into
    // ADR(union.member), then a read of that member. (Tc2_System's MEMCPY
    // comes with TwinCAT projects; a plain source writes its own.)
    let src = "
FUNCTION MEMCPY : UDINT
VAR_INPUT destAddr, srcAddr : POINTER TO BYTE; n : UDINT; END_VAR
VAR i : UDINT; END_VAR
FOR i := 1 TO n DO destAddr^ := srcAddr^; destAddr := destAddr + 1; srcAddr := srcAddr + 1; END_FOR
MEMCPY := n;
END_FUNCTION
TYPE U_Value :
UNION
    lrealValue : LREAL;
    intValue : INT;
    bytes : ARRAY[0..7] OF BYTE;
    text : STRING;
END_UNION
END_TYPE
PROGRAM P
VAR u : U_Value; source : LREAL := 2.5; i : INT := -300; r : LREAL; j : INT;
    s : STRING := 'abc'; t : STRING; p : POINTER TO INT; j2 : INT; b0, b7 : BYTE; END_VAR
MEMCPY(destAddr := ADR(u.lrealValue), srcAddr := ADR(source), n := SIZEOF(source));
r := u.lrealValue;
MEMCPY(destAddr := ADR(u.intValue), srcAddr := ADR(i), n := SIZEOF(i));
j := u.intValue;
p := ADR(u.intValue);
p^ := p^ + 1;
j2 := u.intValue; b0 := u.bytes[0]; b7 := u.bytes[7];
MEMCPY(destAddr := ADR(u.text), srcAddr := ADR(s), n := SIZEOF(s));
t := u.text;
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r"), "2.5");
    assert_eq!(lit(&plc, "j"), "-300");
    assert_eq!(lit(&plc, "j2"), "-299");
    assert_eq!(lit(&plc, "t"), "'abc'");
    // The INT overwrote the low two bytes of 2.5 (16#4004000000000000).
    assert_eq!(lit(&plc, "b7"), "16#40");
    assert_eq!(lit(&plc, "b0"), "16#D5");
}

#[test]
fn a_string_member_warns_that_it_does_not_overlay() {
    let src = "TYPE U : UNION n : DINT; s : STRING(20); END_UNION END_TYPE
PROGRAM P VAR u : U; END_VAR u.s := 'x'; u.n := 5; END_PROGRAM";
    let plc = compile(src);
    let codes: Vec<String> = plc.warnings().iter().map(|d| d.code.to_string()).collect();
    assert!(codes.contains(&"W318".to_string()), "{codes:?}");
}

#[test]
fn an_array_index_outside_a_union_member_is_a_runtime_fault() {
    let src = program(
        TYPES,
        "u : U_Word32; k : INT := 4; b : BYTE;",
        "b := u.b[k];",
    );
    let f = plc::first_fault(&src);
    assert!(f.to_string().contains("index"), "{f}");
}

#[test]
fn members_without_a_byte_layout_and_initial_values_are_refused() {
    let codes = |decl: &str| {
        let src = format!(
            "TYPE ST : STRUCT a : INT; END_STRUCT END_TYPE
TYPE U : UNION {decl} END_UNION END_TYPE
PROGRAM P VAR u : U; END_VAR END_PROGRAM"
        );
        error_codes(&[("t.st", &src)])
            .into_iter()
            .map(|(c, _)| c)
            .collect::<Vec<_>>()
    };
    assert_eq!(codes("a : DINT; s : ST;"), ["E219"]);
    assert_eq!(codes("a : DINT; t : TON;"), ["E219"]);
    assert_eq!(codes("a : DINT := 3; b : BYTE;"), ["E218"]);
    assert_eq!(codes("a : DINT; a : BYTE;"), ["E202"]);
    assert_eq!(codes("a : DINT; r : INT(0..10);"), ["E219"]);
    // A name no member has.
    let src = format!("{TYPES}\nPROGRAM P VAR u : U_Word32; END_VAR u.nothing := 1; END_PROGRAM");
    assert_eq!(
        error_codes(&[("t.st", &src)])
            .into_iter()
            .map(|(c, _)| c)
            .collect::<Vec<_>>(),
        ["E201"]
    );
}
