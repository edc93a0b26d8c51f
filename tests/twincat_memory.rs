//! `MEMSET`, `MEMCPY` and `MEMMOVE` over whole structures and arrays of
//! them, and pointers to structures kept in `PVOID`s, as TwinCAT code
//! writes them (docs/twincat.md, "Memory functions"): done on the typed
//! values, as the bytes would have come out in TwinCAT.

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile, declaration, pou};

/// An item with a default the clear must not restore, and a base
/// structure with a derived one.
fn types() -> Vec<(&'static str, String)> {
    vec![
        (
            "ST_Item.TcDUT",
            declaration(
                "DUT",
                "ST_Item",
                "TYPE ST_Item :\nSTRUCT\n  n : INT := 5;\n  r : REAL := 1.5;\n  s : STRING(20) := 'init';\n  pInt : POINTER TO INT;\n  a : ARRAY[0..2] OF BOOL;\nEND_STRUCT\nEND_TYPE",
            ),
        ),
        (
            "ST_Derived.TcDUT",
            declaration(
                "DUT",
                "ST_Derived",
                "TYPE ST_Derived EXTENDS ST_Item :\nSTRUCT\n  id : DWORD;\n  name : STRING;\nEND_STRUCT\nEND_TYPE",
            ),
        ),
    ]
}

/// The types and P declaring `declarations` and running `body`,
/// compiled.
fn compile_main(declarations: &str, body: &str) -> Result<plcrun::Plc, plcrun::CompileError> {
    let main = pou(
        "P",
        &format!("PROGRAM P\nVAR\n{declarations}\nEND_VAR"),
        body,
        "",
    );
    let owned = types();
    let mut files: Vec<(&str, &str)> = owned.iter().map(|(n, t)| (*n, t.as_str())).collect();
    files.push(("P.TcPOU", &main));
    compile(&files)
}

/// [`compile_main`], run one cycle.
fn run_main(declarations: &str, body: &str) -> plcrun::Plc {
    let mut plc = compile_main(declarations, body).unwrap_or_else(|e| panic!("{e}"));
    run(&mut plc, 1);
    plc
}

#[test]
fn memset_of_a_whole_structure_clears_every_field() {
    let plc = run_main(
        "  x : ST_Item;\n  i : INT;\n  nBytes : UDINT;\n  nSize : UDINT;\n  bNull : BOOL;",
        "x.n := 7; x.s := 'kept?'; x.pInt := ADR(i); x.a[1] := TRUE;\nnBytes := MEMSET(ADR(x), 0, SIZEOF(x));\nnSize := SIZEOF(x);\nbNull := x.pInt = 0;\n",
    );
    let got: Vec<String> = ["x.n", "x.r", "x.s", "x.a[1]", "bNull"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    // Zero, not the declared initial values (5, 1.5, 'init').
    assert_eq!(got, ["0", "0.0", "''", "FALSE", "TRUE"]);
    // The count comes back, as from the byte-by-byte function.
    assert_eq!(lit(&plc, "P.nBytes"), lit(&plc, "P.nSize"));
    assert_ne!(lit(&plc, "P.nBytes"), "0");
}

#[test]
fn memcpy_copies_structures_arrays_of_them_and_a_base_part() {
    let plc = run_main(
        "  a : ST_Item;\n  b : ST_Item;\n  src : ARRAY[0..9] OF ST_Item;\n  dst : ARRAY[1..4] OF ST_Item;\n  d : ST_Derived;\n  k : INT;",
        "a.n := 3; a.s := 'copied';\n\
         MEMCPY(destAddr := ADR(b), srcAddr := ADR(a), n := SIZEOF(a));\n\
         a.s := 'changed after';\n\
         FOR k := 0 TO 9 DO src[k].n := k * 10; src[k].s := INT_TO_STRING(k); END_FOR\n\
         MEMMOVE(ADR(dst), ADR(src), 4 * SIZEOF(ST_Item));\n\
         MEMSET(ADR(src[2]), 0, SIZEOF(src[2]));\n\
         d.id := 16#AB; d.name := 'own';\n\
         MEMCPY(ADR(d), ADR(a), SIZEOF(a));\n",
    );
    let got: Vec<String> = [
        "b.n", "b.s", "dst[1].s", "dst[4].n", "dst[4].s", "src[2].s", "src[3].s", "d.n", "d.s",
        "d.id", "d.name",
    ]
    .iter()
    .map(|v| lit(&plc, &format!("P.{v}")))
    .collect();
    assert_eq!(
        got,
        [
            "3",
            "'copied'",
            "'0'",
            "30",
            "'3'",
            "''",
            "'3'",
            "3",
            "'changed after'",
            "16#AB",
            "'own'"
        ]
    );
}

#[test]
fn a_memory_call_over_part_of_a_structure_works_on_its_bytes() {
    // ST_Item: n INT (bytes 0-1), r REAL (2-5), s STRING(20) (6-26),
    // pInt (27-34), a ARRAY[0..2] OF BOOL (35-37).
    let plc = run_main(
        "  x : ST_Item;\n  y : ST_Item;\n  n : UDINT;",
        "x.s := 'abc';\n\
         MEMSET(ADR(x), 0, 2);\n\
         MEMSET(ADR(x) + 35, 1, 3);\n\
         n := 6 + 2;\n\
         MEMCPY(ADR(y), ADR(x), n);\n",
    );
    let got: Vec<String> = ["x.n", "x.r", "x.a[2]", "y.n", "y.s"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    // y.s gets 'ab' over its 'init' (bytes 6 and 7): 'abit'.
    assert_eq!(got, ["0", "1.5", "TRUE", "0", "'abit'"]);
}

#[test]
fn a_memory_call_past_a_structure_faults() {
    let decls = "  x : ST_Item;\n  arr : ARRAY[0..3] OF ST_Item;";
    let body = "MEMCPY(ADR(x), ADR(arr), 2 * SIZEOF(x));";
    let mut plc = compile_main(decls, body).unwrap_or_else(|e| panic!("{e}"));
    let fault = plc.run_cycle().expect_err(body);
    assert_eq!(fault.code(), "R031", "{fault}");
}

#[test]
fn a_pointer_kept_in_a_pvoid_designates_its_structure_again() {
    let plc = run_main(
        "  items : ARRAY[0..3] OF ST_Item;\n  pv : PVOID;\n  pItem : POINTER TO ST_Item;\n  copy : ST_Item;\n  ps : POINTER TO STRING(20);",
        "items[2].n := 42; items[2].s := 'two';\n\
         pv := ADR(items[2]);\n\
         pItem := pv;\n\
         copy := pItem^;\n\
         pItem^.s := 'deux';\n\
         pv := ADR(items[1].s);\n\
         ps := pv;\n\
         ps^ := 'one';\n",
    );
    let got: Vec<String> = ["copy.n", "copy.s", "items[2].s", "items[1].s"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    assert_eq!(got, ["42", "'two'", "'deux'", "'one'"]);
}

#[test]
fn a_pvoid_made_into_a_pointer_to_another_structure_stays_a_byte_view() {
    // An ST_Item is not an ST_Derived: reading one through that pointer
    // would read its STRING slot as a number.
    let mut plc = compile_main(
        "  item : ST_Item;\n  other : ST_Derived;\n  pv : PVOID;\n  pDerived : POINTER TO ST_Derived;\n  x : DWORD;",
        "pv := ADR(item);\npDerived := pv;\nx := pDerived^.id;\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let fault = plc.run_cycle().expect_err("a byte view of a structure");
    assert_eq!(fault.code(), "R034", "{fault}");
}

#[test]
fn a_pointer_kept_in_a_pvoid_finds_its_structure_after_a_method_s_in_out() {
    // lcls-twincat-motion's FB_MotionBPTM_Test: a METHOD's VAR_IN_OUT of an
    // FB type (one slot, an address) comes before the VAR_INST instance
    // holding the structure; the walk to the address must not descend
    // into the in-out as if it held the block.
    let holder = pou(
        "FB_Holder",
        "FUNCTION_BLOCK FB_Holder\nVAR_INPUT\n  items : ARRAY[0..3] OF ST_Item;\nEND_VAR",
        "",
        "",
    );
    let suite = pou(
        "FB_Suite",
        "FUNCTION_BLOCK FB_Suite\nVAR_OUTPUT n : INT; s : STRING(20); END_VAR",
        "",
        &format!(
            "{}{}",
            crate::support::twincat::method(
                "METHOD Peek\nVAR_IN_OUT other : FB_Holder; END_VAR",
                "n := other.items[0].n;"
            ),
            "<Method Name=\"Keep\" Id=\"{00000000-0000-0000-0000-000000000029}\"><Declaration><![CDATA[METHOD Keep\nVAR_INST\n  holder : FB_Holder;\nEND_VAR\nVAR\n  p : POINTER TO ST_Item;\n  pv : PVOID;\n  copy : ST_Item;\nEND_VAR]]></Declaration><Implementation><ST><![CDATA[holder.items[2].n := 42;\nholder.items[2].s := 'kept';\npv := ADR(holder.items[2]);\np := pv;\ncopy := p^;\nn := copy.n;\ns := copy.s;]]></ST></Implementation></Method>\n"
        ),
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  suite : FB_Suite;\n  n : INT;\n  s : STRING(20);\nEND_VAR",
        "suite.Keep();\nn := suite.n;\ns := suite.s;",
        "",
    );
    let owned = types();
    let mut files: Vec<(&str, &str)> = owned.iter().map(|(n, t)| (*n, t.as_str())).collect();
    files.push(("FB_Holder.TcPOU", &holder));
    files.push(("FB_Suite.TcPOU", &suite));
    files.push(("P.TcPOU", &main));
    let mut plc = compile(&files).unwrap_or_else(|e| panic!("{e}"));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.n"), "42");
    assert_eq!(lit(&plc, "P.s"), "'kept'");
}
