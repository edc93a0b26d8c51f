//! Assignment inside an expression, `(x := v)` (CODESYS, TwinCAT; issue
//! #25): the value is stored and the expression has the value stored.
//! Values worked out by hand beside each case.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};

fn check(prelude: &str, decls: &str, body: &str, cycles: u64, expect: &[(&str, &str)]) {
    let mut plc = compile(&program(prelude, decls, body));
    run(&mut plc, cycles);
    for (name, value) in expect {
        assert_eq!(lit(&plc, name), *value, "{name}\n{body}");
    }
}

#[test]
fn a_counter_stepped_and_tested_in_one_condition() {
    // lcls-twincat-general's listener: `IF (i := i + 1) = n THEN i := 0;`
    // Cycles 1..7 leave i = 1, 2, 0, 1, 2, 0, 1; the wrap happens twice.
    check(
        "",
        "i : INT; n : INT := 3; wraps : INT;",
        "IF (i := i + 1) = n THEN i := 0; wraps := wraps + 1; END_IF",
        7,
        &[("i", "1"), ("wraps", "2")],
    );
}

#[test]
fn a_while_loop_steps_its_index_in_its_condition() {
    // k takes 1, 2, 3 inside the loop; the test that fails stores 4.
    check(
        "",
        "k : INT; a : ARRAY[1..4] OF INT; runs : INT;",
        "WHILE (k := k + 1) <= 3 DO a[k] := k * 10; runs := runs + 1; END_WHILE",
        1,
        &[
            ("k", "4"),
            ("runs", "3"),
            ("a[1]", "10"),
            ("a[3]", "30"),
            ("a[4]", "0"),
        ],
    );
}

#[test]
fn the_value_is_the_one_stored_in_the_target() {
    // s3 keeps 'abc' of 'abcdef', and that is what CONCAT gets; d is a
    // DINT, so `(d := 7) * 2` is a DINT product.
    check(
        "",
        "s3 : STRING[3]; s6 : STRING[6]; d, r : DINT;",
        "s6 := CONCAT((s3 := 'abcdef'), 'X'); r := (d := 7) * 2;",
        1,
        &[("s3", "'abc'"), ("s6", "'abcX'"), ("d", "7"), ("r", "14")],
    );
}

#[test]
fn a_later_assignment_in_the_same_expression_does_not_change_an_earlier_value() {
    // Left to right: the first operand is 5 although k is 7 when the sum
    // is taken.
    check(
        "",
        "k, r : INT;",
        "r := (k := 5) * 10 + (k := 7);",
        1,
        &[("k", "7"), ("r", "57")],
    );
}

#[test]
fn elements_fields_and_bits_are_targets() {
    check(
        "TYPE Pt : STRUCT x, y : INT; END_STRUCT END_TYPE",
        "a : ARRAY[0..2] OF INT; i : INT := 2; p : Pt; w : WORD; b, q : BOOL; r : INT;",
        "r := (a[i] := 4) + (p.y := 5); q := (w.3 := TRUE) AND (b := TRUE);",
        1,
        &[
            ("a[2]", "4"),
            ("p.y", "5"),
            ("r", "9"),
            ("w", "16#8"),
            ("b", "TRUE"),
            ("q", "TRUE"),
        ],
    );
}

#[test]
fn a_skipped_operand_stores_nothing() {
    // AND_THEN does not evaluate its right operand after a FALSE left.
    check(
        "",
        "f : BOOL; t : BOOL := TRUE; k : INT := 1; m : INT := 1; x, y : BOOL;",
        "x := f AND_THEN (k := 9) > 0; y := t AND_THEN (m := 9) > 0;",
        1,
        &[("k", "1"), ("m", "9"), ("x", "FALSE"), ("y", "TRUE")],
    );
}

#[test]
fn structure_initialisers_of_one_field_still_initialise() {
    // `(x := 1)` after a declaration's `:=` is a structure initialiser,
    // also nested and with an array value.
    check(
        "TYPE Pt : STRUCT x, y : INT; END_STRUCT END_TYPE
         TYPE Box : STRUCT corner : Pt; v : ARRAY[0..1] OF INT; END_STRUCT END_TYPE",
        "p : Pt := (x := 1); q : Pt := (x := 2, y := 3);
         b : Box := (corner := (y := 4)); c : Box := (v := [5, 6]);
         t : TON := (PT := T#5S);",
        "",
        1,
        &[
            ("p.x", "1"),
            ("q.y", "3"),
            ("b.corner.y", "4"),
            ("c.v[1]", "6"),
            ("t.PT", "T#5s"),
        ],
    );
}

#[test]
fn aggregates_constants_and_non_names_are_refused() {
    let cases = [
        // A structure: one value is stored, a structure is copied.
        (
            program(
                "TYPE Pt : STRUCT x, y : INT; END_STRUCT END_TYPE",
                "p, q : Pt; b : BOOL;",
                "b := (p := q) = q;",
            ),
            "E414",
        ),
        // A constant is not written.
        (
            program("", "i : INT;", "i := (c := 1);").replace(
                "END_VAR\ni",
                "END_VAR\nVAR CONSTANT c : INT := 0; END_VAR\ni",
            ),
            "E401",
        ),
        // A structure initialiser names fields, not places.
        (
            program(
                "TYPE Pt : STRUCT x, y : INT; END_STRUCT END_TYPE",
                "p : Pt := (p.x := 1, y := 2);",
                "",
            ),
            "E113",
        ),
    ];
    for (src, code) in cases {
        let codes = error_codes(&[("test.st", &src)]);
        assert!(
            codes.iter().any(|c| c.0 == code),
            "{code}: {codes:?}\n{src}"
        );
    }
}
