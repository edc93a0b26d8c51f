//! Edition-3 references (docs/semantics.md "References and pointers"):
//! `REF_TO`, `REF()`, `^`, `NULL`, comparison, references as variables,
//! struct members, array elements and FB inputs -- values checked -- and
//! every fault and diagnostic with its code and place.

use crate::support::plc;

use plc::{compile, error_codes, first_fault, line_col, lit, program, run};
use plcrun::FaultKind;

#[test]
fn read_and_write_through_a_reference() {
    let src = program(
        "",
        "x : INT := 5; y : INT; r : REF_TO INT; same, none, was_null : BOOL;",
        "was_null := r = NULL; r := REF(x); y := r^ + 1; r^ := 40; r^ := r^ + 2;
         same := r = REF(x); none := r <> NULL;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "42");
    assert_eq!(lit(&plc, "P.y"), "6");
    assert_eq!(lit(&plc, "P.same"), "TRUE");
    assert_eq!(lit(&plc, "P.none"), "TRUE");
    assert_eq!(lit(&plc, "P.was_null"), "TRUE");
}

#[test]
fn references_to_structs_arrays_and_strings() {
    let src = program(
        "TYPE Pt : STRUCT x : DINT; y : DINT; END_STRUCT; END_TYPE",
        "pt : Pt; a : ARRAY[1..4] OF INT; s : STRING := 'ab';
         rp : REF_TO Pt; ra : REF_TO ARRAY[1..4] OF INT; rs : REF_TO STRING;
         i : INT; sum : INT; t : STRING;",
        "rp := REF(pt); rp^.x := 3; rp^.y := rp^.x * 2;
         ra := REF(a); FOR i := 1 TO 4 DO ra^[i] := i * 10; END_FOR;
         sum := 0; FOR i := 1 TO 4 DO sum := sum + ra^[i]; END_FOR;
         rs := REF(s); rs^ := CONCAT(rs^, 'cd'); t := rs^;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.pt.x"), "3");
    assert_eq!(lit(&plc, "P.pt.y"), "6");
    assert_eq!(lit(&plc, "P.a[3]"), "30");
    assert_eq!(lit(&plc, "P.sum"), "100");
    assert_eq!(lit(&plc, "P.s"), "'abcd'");
    assert_eq!(lit(&plc, "P.t"), "'abcd'");
}

#[test]
fn references_as_members_elements_and_fb_inputs() {
    let src = "
TYPE Node : STRUCT val : INT; target : REF_TO INT; END_STRUCT; END_TYPE
FUNCTION_BLOCK Bump
VAR_INPUT r : REF_TO INT; amount : INT; END_VAR
IF r <> NULL THEN r^ := r^ + amount; END_IF;
END_FUNCTION_BLOCK
PROGRAM P
VAR
  a, b : INT; n : Node; rs : ARRAY[0..1] OF REF_TO INT; k : INT; f : Bump;
  got : INT;
END_VAR
n.target := REF(a); n.target^ := 7;
rs[0] := REF(a); rs[1] := REF(b);
FOR k := 0 TO 1 DO rs[k]^ := rs[k]^ + 100; END_FOR;
f(r := REF(b), amount := 5);
f(r := NULL, amount := 1000);
got := rs[1]^;
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "107");
    assert_eq!(lit(&plc, "P.b"), "105");
    assert_eq!(lit(&plc, "P.got"), "105");
}

#[test]
fn a_reference_to_an_fb_instance_reads_its_outputs_and_calls_it() {
    let src = program(
        "FUNCTION_BLOCK Acc VAR_INPUT inc : INT; END_VAR VAR_OUTPUT total : INT; END_VAR
         total := total + inc; END_FUNCTION_BLOCK",
        "a : Acc; r : REF_TO Acc; t : INT;",
        "r := REF(a); r^(inc := 3); r^(inc := 4); t := r^.total;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.t"), "14");
}

#[test]
fn a_function_returns_a_reference() {
    let src = "
FUNCTION Pick : REF_TO INT
VAR_IN_OUT a, b : INT; END_VAR
VAR_INPUT first : BOOL; END_VAR
IF first THEN Pick := REF(a); ELSE Pick := REF(b); END_IF;
END_FUNCTION
PROGRAM P
VAR x : INT := 1; y : INT := 2; r : REF_TO INT; END_VAR
r := Pick(x, y, FALSE);
r^ := 20;
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "1");
    assert_eq!(lit(&plc, "P.y"), "20");
}

#[test]
fn isvalidref_tells_null_from_valid() {
    let src = program(
        "",
        "x : REAL; r : REF_TO REAL; before, after : BOOL;",
        "before := __ISVALIDREF(r); r := REF(x); after := ISVALIDREF(r);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.before"), "FALSE");
    assert_eq!(lit(&plc, "P.after"), "TRUE");
}

#[test]
fn null_dereference_is_r030_with_its_place_and_cycle() {
    let src = program(
        "",
        "c : INT; r : REF_TO INT; x : INT;",
        "c := c + 1;\nIF c = 3 THEN x := r^; END_IF;",
    );
    let f = first_fault(&src);
    assert_eq!(f.fault.kind, FaultKind::NullReference);
    assert_eq!(f.fault.kind.code(), "R030");
    assert_eq!(f.cycle, 2);
    // Line 7 of the file: the IF; `r^` starts at column 20.
    assert_eq!(line_col(&f.location), (7, 20), "{}", f.location);
    let shown = f.to_string();
    assert!(shown.contains("NULL"), "{shown}");
}

#[test]
fn null_write_faults_too() {
    let src = program("", "r : REF_TO DINT;", "r^ := 1;");
    let f = first_fault(&src);
    assert_eq!(f.fault.kind.code(), "R030");
    assert_eq!(line_col(&f.location), (6, 1), "{}", f.location);
}

#[test]
fn type_mismatch_and_misuse_are_refused_with_codes() {
    let cases: &[(&str, &str, &str, &str)] = &[
        // REF_TO INT := REF(real)
        ("r : REF_TO INT; x : REAL;", "r := REF(x);", "E301", "6:6"),
        // ^ on a non-reference
        ("x : INT; y : INT;", "y := x^;", "E250", "6:6"),
        // REF of a constant
        ("k : INT := 1;", "", "", ""),
        // arithmetic on REF_TO
        (
            "r : REF_TO INT; x : INT;",
            "r := REF(x); r := r + 2;",
            "E252",
            "6:19",
        ),
        // NULL cannot be dereferenced
        ("x : INT;", "x := NULL^;", "E250", "6:6"),
        // REF of an expression
        (
            "r : REF_TO INT; x : INT;",
            "r := REF(x + 1);",
            "E402",
            "6:10",
        ),
        // two arguments
        ("r : REF_TO INT; x : INT;", "r := REF(x, x);", "E251", "6:6"),
        // an integer is not a reference
        ("r : REF_TO INT;", "r := 5;", "E301", "6:6"),
    ];
    for (decls, body, code, at) in cases {
        if code.is_empty() {
            continue;
        }
        let src = program("", decls, body);
        let errs = error_codes(&[("test.st", &src)]);
        assert_eq!(
            errs.first().map(|(c, l)| (c.as_str(), l.as_str())),
            Some((*code, *at)),
            "{body}: {errs:?}"
        );
    }
    let src = "PROGRAM P VAR CONSTANT k : INT := 1; END_VAR VAR r : REF_TO INT; END_VAR
r := REF(k);
END_PROGRAM";
    let errs = error_codes(&[("test.st", src)]);
    assert_eq!(errs[0].0, "E254", "{errs:?}");
}

#[test]
fn a_reference_to_a_temporary_may_not_outlive_it() {
    let src = "
FUNCTION_BLOCK Keep
VAR_TEMP t : INT; END_VAR
VAR kept : REF_TO INT; local : REF_TO INT; END_VAR
kept := REF(t);
END_FUNCTION_BLOCK
FUNCTION Leak : REF_TO INT
VAR v : INT; p : REF_TO INT; END_VAR
p := REF(v);
Leak := REF(v);
END_FUNCTION
PROGRAM P VAR k : Keep; END_VAR k(); END_PROGRAM";
    let errs = error_codes(&[("test.st", src)]);
    let codes: Vec<&str> = errs.iter().map(|(c, _)| c.as_str()).collect();
    assert_eq!(codes, ["E253", "E253"], "{errs:?}");
    assert_eq!(errs[0].1, "5:9");
    assert_eq!(errs[1].1, "10:9");
}

#[test]
fn reference_words_stay_usable_as_names() {
    let src = program(
        "",
        "pointer : INT; reference : INT; ref_to : INT; i : INT;",
        "pointer := 2; reference := 3; ref_to := 4; FOR i := pointer TO reference DO ref_to := ref_to + i; END_FOR;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.ref_to"), "9");
}

#[test]
fn an_online_change_restarts_references_from_null() {
    let v1 = program("", "x : INT; r : REF_TO INT;", "r := REF(x); r^ := r^ + 1;");
    let v2 = program(
        "",
        "x : INT; r : REF_TO INT; seen_null : BOOL; extra : INT;",
        "seen_null := r = NULL; r := REF(extra); r^ := r^ + 1;",
    );
    let mut plc = compile(&v1);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.x"), "3");
    let report = plc
        .online_change_files(&[("v2.st", &v2)], &plcrun::Options::default())
        .expect("online change applies");
    assert!(report.initialised.contains(&"P.r".to_string()), "{report}");
    assert!(report.kept.contains(&"P.x".to_string()), "{report}");
    run(&mut plc, 2);
    assert_eq!(
        lit(&plc, "P.seen_null"),
        "FALSE",
        "set again in the first new cycle"
    );
    assert_eq!(lit(&plc, "P.x"), "3");
    assert_eq!(lit(&plc, "P.extra"), "2");
}

#[test]
fn the_first_cycle_after_an_online_change_sees_null() {
    let v1 = program("", "x : INT; r : REF_TO INT;", "r := REF(x);");
    let v2 = program(
        "",
        "x : INT; r : REF_TO INT; seen_null : BOOL;",
        "seen_null := r = NULL;",
    );
    let mut plc = compile(&v1);
    run(&mut plc, 1);
    plc.online_change_files(&[("v2.st", &v2)], &plcrun::Options::default())
        .expect("online change applies");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.seen_null"), "TRUE");
}

#[test]
fn reference_to_names_its_target_once_bound() {
    let src = "
FUNCTION_BLOCK Counter
VAR_INPUT target : REFERENCE TO INT; END_VAR
target := target + 1;
END_FUNCTION_BLOCK
PROGRAM P
VAR
  a : INT := 10; b : INT; r : REFERENCE TO INT; c : Counter;
  before, after : BOOL; seen : INT;
END_VAR
before := __ISVALIDREF(r);
r REF= a;
after := __ISVALIDREF(r);
r := r * 2;
seen := r;
c.target REF= b;
c();
c();
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "20");
    assert_eq!(lit(&plc, "P.seen"), "20");
    assert_eq!(lit(&plc, "P.b"), "2");
    assert_eq!(lit(&plc, "P.before"), "FALSE");
    assert_eq!(lit(&plc, "P.after"), "TRUE");
}

#[test]
fn an_unbound_reference_to_faults_r030() {
    let src = program("", "r : REFERENCE TO DINT; x : DINT;", "x := r;");
    let f = first_fault(&src);
    assert_eq!(f.fault.kind, FaultKind::NullReference);
    assert_eq!(line_col(&f.location), (6, 6), "{}", f.location);
}

#[test]
fn ref_binding_is_checked() {
    let cases: &[(&str, &str, &str)] = &[
        ("x : INT; y : INT;", "x REF= y;", "E255"),
        ("r : REFERENCE TO INT; y : REAL;", "r REF= y;", "E301"),
    ];
    for (decls, body, code) in cases {
        let src = program("", decls, body);
        let errs = error_codes(&[("test.st", &src)]);
        assert_eq!(
            errs.first().map(|(c, _)| c.as_str()),
            Some(*code),
            "{body}: {errs:?}"
        );
    }
}

#[test]
fn references_are_not_values_from_outside() {
    let src = program("", "x : INT; r : REF_TO INT;", "r := REF(x);");
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert!(
        plc.read("P.r").is_err(),
        "a reference cannot be read or forged by name"
    );
}
