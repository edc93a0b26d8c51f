//! Forms of the CODESYS V3 / TwinCAT dialect met in SLAC's
//! `lcls-twincat-pmps` library (issue #25): array repetitions counted by a
//! named constant, shifts of an untyped constant, initial values read from
//! global variables, LREAL stored into REAL, a structure copied into the
//! structure it extends, bit strings counting FOR loops and sizing arrays,
//! `THIS^.arr` for the block's own `ARRAY[*]`, structures at `%I*`, and a
//! call through a variable of unknown type reported once. Each program's
//! results are worked out by hand beside it.

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile_ok, declaration, method, pou, refused};

const ATTENUATOR: &str = "TYPE ST_Att : STRUCT nTran : REAL; xOK : UINT; END_STRUCT END_TYPE";

#[test]
fn an_array_repetition_may_be_counted_by_a_list_s_constant() {
    let att = declaration("DUT", "ST_Att", ATTENUATOR);
    let beam = declaration(
        "DUT",
        "ST_Beam",
        "TYPE ST_Beam : STRUCT a : ARRAY[1..G.N] OF ST_Att; n : INT; END_STRUCT END_TYPE",
    );
    let gvl = declaration(
        "GVL",
        "G",
        "{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n  N : UINT := 3;\n  stAtt : ST_Att := (nTran := 0.5, xOK := 1);\n  cst : ST_Beam := (a := [G.N(stAtt)], n := 7);\nEND_VAR",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR s : ST_Beam := G.cst; f : REAL; k : UINT; END_VAR",
        "f := s.a[1].nTran + s.a[3].nTran; k := s.a[3].xOK;",
        "",
    );
    let mut plc = compile_ok(&[
        ("Att.TcDUT", &att),
        ("Beam.TcDUT", &beam),
        ("G.TcGVL", &gvl),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "f"), lit(&plc, "k")), ("1.0".into(), "1".into()));
}

#[test]
fn an_untyped_constant_shifts_in_32_bits() {
    // `SHL(1, n)` builds a 32-bit mask: bit 31 too.
    let main = pou(
        "P",
        "PROGRAM P\nVAR m : DWORD; n : INT := 31; r : DWORD; END_VAR",
        "m := m + SHL(1, n); r := ROL(16#80000001, 1);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "m"), "16#80000000");
    assert_eq!(lit(&plc, "r"), "16#3");
}

#[test]
fn an_initial_value_reads_a_global_variable_and_its_elements() {
    let gvl = declaration(
        "GVL",
        "G",
        "{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n  c : INT := 3;\nEND_VAR\nVAR_GLOBAL\n  arr : ARRAY[0..c] OF REAL := [1.5, 2.5];\n  nLimit : INT := 40;\nEND_VAR",
    );
    let f = pou(
        "F",
        "FUNCTION F : REAL\nVAR a : REAL := G.arr[1]; b : REAL := G.arr[G.c]; n : INT := G.nLimit + 2; END_VAR",
        "F := a + b + INT_TO_REAL(n);",
        "",
    );
    let main = pou("P", "PROGRAM P\nVAR x : REAL; END_VAR", "x := F();", "");
    let mut plc = compile_ok(&[("F.TcPOU", &f), ("G.TcGVL", &gvl), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    // 2.5 + 0.0 (an element past the values given) + 42.
    assert_eq!(lit(&plc, "x"), "44.5");
    // An index outside the array is no value to read (a FUNCTION's
    // variable computes it at each call, and the constant index is
    // refused there).
    let out = pou(
        "F",
        "FUNCTION F : REAL\nVAR a : REAL := G.arr[9]; END_VAR",
        "F := a;",
        "",
    );
    let e = refused(&[("F.TcPOU", &out), ("G.TcGVL", &gvl), ("P.TcPOU", &main)]);
    assert!(e.contains("E304"), "{e}");
}

#[test]
fn an_lreal_stored_into_a_real_is_rounded_with_a_warning() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR r : REAL; l : LREAL := 0.1; END_VAR",
        "r := l;",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r"), "0.1");
    // IEC text keeps the rule: an explicit LREAL_TO_REAL.
    let st = "PROGRAM P\nVAR r : REAL; l : LREAL := 0.1; END_VAR\nr := l;\nEND_PROGRAM\n";
    let e = match plcrun::Plc::compile_files(&[("p.st", st)], &plcrun::Options::default()) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("error[E301]"), "{e}");
    // The warning, and --strict refusing it.
    let strict = plcrun::Options {
        program: Some("P".into()),
        strict: true,
        ..Default::default()
    };
    let e = match plcrun::Plc::compile_files(&[("P.TcPOU", &main)], &strict) {
        Ok(_) => panic!("compiled under --strict"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.contains("error[W491]: implicit conversion of LREAL to REAL"),
        "{e}"
    );
}

#[test]
fn a_structure_copies_into_the_structure_it_extends() {
    let att = declaration("DUT", "ST_Att", ATTENUATOR);
    let ext = declaration(
        "DUT",
        "ST_AttInternal",
        "TYPE ST_AttInternal EXTENDS ST_Att : STRUCT nId : INT; END_STRUCT END_TYPE",
    );
    let deeper = declaration(
        "DUT",
        "ST_AttDeep",
        "TYPE ST_AttDeep EXTENDS ST_AttInternal : STRUCT b : BOOL; END_STRUCT END_TYPE",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR a : ST_Att; d : ST_AttDeep; END_VAR",
        "d.nTran := 0.25; d.xOK := 3; d.nId := 9; a := d;",
        "",
    );
    let files = [
        ("Att.TcDUT", att.as_str()),
        ("Int.TcDUT", ext.as_str()),
        ("Deep.TcDUT", deeper.as_str()),
        ("P.TcPOU", main.as_str()),
    ];
    let mut plc = compile_ok(&files);
    run(&mut plc, 1);
    assert_eq!(
        (lit(&plc, "a.nTran"), lit(&plc, "a.xOK")),
        ("0.25".into(), "3".into())
    );
    // Not the other way: a base lacks the derived structure's fields.
    let back = pou(
        "P",
        "PROGRAM P\nVAR a : ST_Att; d : ST_AttDeep; END_VAR",
        "d := a;",
        "",
    );
    let e = refused(&[files[0], files[1], files[2], ("P.TcPOU", &back)]);
    assert!(
        e.contains("error[E301]: assignment: expected ST_AttDeep, found ST_Att"),
        "{e}"
    );
}

#[test]
fn bit_strings_count_for_loops_and_size_arrays() {
    // MAXL is declared after the array it sizes, and is a BYTE.
    let main = pou(
        "P",
        "PROGRAM P\nVAR arr : ARRAY[1..MAXL] OF BOOL; i : BYTE; d : DWORD; n : INT; END_VAR\nVAR CONSTANT MAXL : BYTE := 4; END_VAR",
        "FOR i := 1 TO MAXL DO arr[i] := TRUE; END_FOR\nFOR d := 2 TO 6 BY 2 DO n := n + 1; END_FOR",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "arr[4]"), "TRUE");
    assert_eq!(lit(&plc, "n"), "3");
    assert_eq!(lit(&plc, "i"), "16#5");
}

#[test]
fn this_names_the_block_s_own_open_array_in_its_methods() {
    let fb = pou(
        "FB_D",
        "FUNCTION_BLOCK FB_D\nVAR_IN_OUT arr : ARRAY[*] OF INT; END_VAR",
        "M();",
        &method(
            "METHOD M : BOOL\nVAR i : INT; END_VAR",
            "FOR i := LOWER_BOUND(THIS^.arr, 1) TO UPPER_BOUND(arr, 1) DO THIS^.arr[i] := THIS^.arr[i] + i; END_FOR",
        ),
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR d : FB_D; a : ARRAY[0..2] OF INT; END_VAR",
        "d(arr := a);",
        "",
    );
    let mut plc = compile_ok(&[("D.TcPOU", &fb), ("P.TcPOU", &main)]);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "a[2]"), "4");
}

#[test]
fn a_call_through_a_variable_of_unknown_type_is_reported_once() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR fbXml : FB_XmlDomParser; b : BOOL; END_VAR",
        "b := fbXml.HasMember(1);",
        "",
    );
    let e = refused(&[("P.TcPOU", &main)]);
    assert!(
        e.contains("error[E203]: unknown type `FB_XmlDomParser`"),
        "{e}"
    );
    assert!(!e.contains("E406"), "{e}");
}

#[test]
fn tc2_system_s_default_ads_timeout_is_five_seconds() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR t : TIME := DEFAULT_ADS_TIMEOUT; END_VAR",
        "",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "t"), "T#5s");
}

#[test]
fn a_structure_field_default_copies_a_list_s_structure_constant() {
    // The TYPE is read before the list, which declares the constant from
    // another one and a plain constant.
    let att = declaration("DUT", "ST_Att", ATTENUATOR);
    let state = declaration(
        "DUT",
        "ST_State",
        "TYPE ST_State : STRUCT stAtt : ST_Att := G.cstDefault; nId : INT; END_STRUCT END_TYPE",
    );
    let gvl = declaration(
        "GVL",
        "G",
        "{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n  cstDefault : ST_Att := (nTran := G.SCALE, xOK := 2);\n  SCALE : REAL := 0.5;\nEND_VAR",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR s : ST_State; f : REAL; k : UINT; END_VAR",
        "f := s.stAtt.nTran; k := s.stAtt.xOK;",
        "",
    );
    let mut plc = compile_ok(&[
        ("Att.TcDUT", &att),
        ("State.TcDUT", &state),
        ("G.TcGVL", &gvl),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "f"), lit(&plc, "k")), ("0.5".into(), "2".into()));
    // A constant that does not exist is said to be undeclared.
    let bad = declaration(
        "DUT",
        "ST_State",
        "TYPE ST_State : STRUCT stAtt : ST_Att := G.cstNone; END_STRUCT END_TYPE",
    );
    let e = refused(&[
        ("Att.TcDUT", &att),
        ("State.TcDUT", &bad),
        ("G.TcGVL", &gvl),
        ("P.TcPOU", &main),
    ]);
    assert!(
        e.contains("error[E201]: undeclared variable `G.cstNone`"),
        "{e}"
    );
}

#[test]
fn a_strict_enumeration_connects_to_an_in_out_of_its_base_type() {
    // lcls-twincat-motion's tests hand a strict enumeration to a block's
    // `VAR_IN_OUT eEnumSet : UINT`: the same memory, written through.
    let states = declaration(
        "DUT",
        "E_T",
        "{attribute 'qualified_only'}\n{attribute 'strict'}\nTYPE E_T : (Unknown := 0, OUT := 1, IN := 2) UINT; END_TYPE",
    );
    let fb = pou(
        "FB_D",
        "FUNCTION_BLOCK FB_D\nVAR_IN_OUT eEnumSet : UINT; END_VAR",
        "eEnumSet := eEnumSet + 1;",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR d : FB_D; e : E_T := E_T.OUT; n : UINT; END_VAR",
        "d(eEnumSet := e); IF e = E_T.IN THEN n := 1; END_IF",
        "",
    );
    let mut plc = compile_ok(&[("E.TcDUT", &states), ("D.TcPOU", &fb), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "1");
    // An integer variable into a strict enumeration's VAR_IN_OUT stays E301.
    let fb = pou(
        "FB_D",
        "FUNCTION_BLOCK FB_D\nVAR_IN_OUT eState : E_T; END_VAR",
        "",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR d : FB_D; k : UINT; END_VAR",
        "d(eState := k);",
        "",
    );
    let e = refused(&[("E.TcDUT", &states), ("D.TcPOU", &fb), ("P.TcPOU", &main)]);
    assert!(e.contains("error[E301]"), "{e}");
}

#[test]
fn enumerations_of_a_bit_string_base_compute_and_give_their_bits() {
    let module = declaration(
        "DUT",
        "E_Module",
        "{attribute 'qualified_only'}\nTYPE E_Module : (CHAN1 := 1, CHAN2 := 2) WORD; END_TYPE",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR e : E_Module := E_Module.CHAN2; n : WORD; b : BOOL; f : E_Module; END_VAR",
        "n := 16#10 + ((e - 1) * 16#800); b := e.1; f.0 := TRUE;",
        "",
    );
    let mut plc = compile_ok(&[("E.TcDUT", &module), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "16#810");
    assert_eq!(lit(&plc, "b"), "TRUE");
    assert_eq!(lit(&plc, "f"), "CHAN1");
}

#[test]
fn another_instance_s_output_connects_to_an_in_out() {
    let a = pou(
        "FB_A",
        "FUNCTION_BLOCK FB_A\nVAR_OUTPUT bOut : BOOL; END_VAR",
        "",
        "",
    );
    let b = pou(
        "FB_B",
        "FUNCTION_BLOCK FB_B\nVAR_IN_OUT b : BOOL; END_VAR",
        "b := TRUE;",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR a : FB_A; bb : FB_B; x : BOOL; END_VAR",
        "a(); bb(b := a.bOut); x := a.bOut;",
        "",
    );
    let files = [("A.TcPOU", a.as_str()), ("B.TcPOU", b.as_str())];
    let mut plc = compile_ok(&[files[0], files[1], ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "x"), "TRUE");
    // In IEC text it stays E412.
    let st = "FUNCTION_BLOCK FB_A\nVAR_OUTPUT bOut : BOOL; END_VAR\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK FB_B\nVAR_IN_OUT b : BOOL; END_VAR\nb := TRUE;\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR a : FB_A; bb : FB_B; END_VAR\nbb(b := a.bOut);\nEND_PROGRAM\n";
    let e = refused(&[("p.st", st)]);
    assert!(e.contains("error[E412]"), "{e}");
}

#[test]
fn a_string_is_indexed_by_its_bytes() {
    // `s[i]` is the i-th byte from 0 (a WSTRING's the i-th WORD), read and
    // written in place; past the buffer the PLC stops.
    let main = pou(
        "P",
        "PROGRAM P\nVAR s : STRING(10) := 'ABC'; b0, b2, b3 : BYTE; i : INT := 1; n : INT; w : WSTRING(4) := \"xy\"; wc : WORD; END_VAR",
        "b0 := s[0]; b2 := s[i + 1]; b3 := s[3]; s[1] := 16#7A;\nFOR i := 0 TO LEN(s) - 1 DO IF s[i] = 16#41 THEN n := n + 1; END_IF END_FOR\nwc := w[1];",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let got: Vec<String> = ["b0", "b2", "b3", "s", "n", "wc"]
        .iter()
        .map(|v| lit(&plc, v))
        .collect();
    assert_eq!(got, ["16#41", "16#43", "16#0", "'AzC'", "1", "16#79"]);
    let past = pou(
        "P",
        "PROGRAM P\nVAR s : STRING(3) := 'ABC'; b : BYTE; i : INT := 9; END_VAR",
        "b := s[i];",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &past)]);
    let fault = plc.run_cycle().expect_err("outside the string");
    assert!(fault.to_string().contains("R031"), "{fault}");
    // IEC text has no such index.
    let st = "PROGRAM P\nVAR s : STRING := 'A'; b : BYTE; END_VAR\nb := s[0];\nEND_PROGRAM\n";
    assert!(refused(&[("p.st", st)]).contains("error[E302]"));
}

#[test]
fn a_positional_argument_after_a_formal_one_takes_the_input_of_its_position() {
    // PMPS: `fbJson.CopyDocument(pDoc := fbLogger.sJson, SIZEOF(fbLogger.sJson));`,
    // which TwinCAT compiles: the second argument goes to the second input.
    let f = pou(
        "F",
        "FUNCTION F : INT\nVAR_INPUT a : INT; b : INT; c : INT := 7; END_VAR",
        "F := a * 100 + b * 10 + c;",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR r1, r2 : INT; END_VAR",
        "r1 := F(a := 1, 2);\nr2 := F(c := 3, 4);",
        "",
    );
    let mut plc = compile_ok(&[("F.TcPOU", &f), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!([lit(&plc, "r1"), lit(&plc, "r2")], ["127", "43"]);
    // The input of its position named as well is given twice.
    let twice = pou(
        "P",
        "PROGRAM P\nVAR r : INT; END_VAR",
        "r := F(b := 1, 2);",
        "",
    );
    let err = refused(&[("F.TcPOU", &f), ("P.TcPOU", &twice)]);
    assert!(err.contains("E404"), "{err}");
}
