//! IL: an untyped literal loaded just before a label takes the type that a
//! jump to the label brings (`LD 0` falling into `SET_OUT: ST OUT`, where
//! another path jumps to SET_OUT with an INT).

use crate::support::access_diags;
use crate::support::plc;

use access_diags::codes_at;
use plc::{compile, lit, run};

const SELECT: &str = "PROGRAM P\nVAR sel : BOOL; in1 : INT := 5; out : INT := 99; END_VAR\n\
LD sel\nJMPCN zero\nLD in1\nJMP set_out\nzero:\nLD 0\nset_out:\nST out\nEND_PROGRAM\n";

#[test]
fn the_literal_path_stores_its_value() {
    let mut plc = compile(SELECT);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "out"), "0");
}

#[test]
fn the_jump_path_stores_the_variable() {
    let mut plc = compile(&SELECT.replace("sel : BOOL;", "sel : BOOL := TRUE;"));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "out"), "5");
}

#[test]
fn a_negative_literal_and_a_real_join() {
    let src = "PROGRAM P\nVAR sel : BOOL; r : REAL := 2.5; out : REAL; END_VAR\n\
               LD sel\nJMPCN other\nLD r\nJMP done\nother:\nLD -3\ndone:\nST out\nEND_PROGRAM\n";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "out"), "-3.0");
}

#[test]
fn the_join_compiles_without_diagnostics() {
    assert_eq!(codes_at(SELECT), Vec::<String>::new());
}

#[test]
fn a_literal_that_does_not_fit_the_join_type_is_still_reported() {
    let src = SELECT.replace("LD 0", "LD 70000");
    let got = codes_at(&src);
    assert!(got.iter().any(|c| c.starts_with("E30")), "{got:?}");
}

/// The literal is stored before the label; the label is reached by a
/// `JMPC` whose BOOL nobody reads after it (the next line loads).
const STORED_BEFORE_LABEL: &str = "PROGRAM P\nVAR b : BOOL; x : INT; y : INT; END_VAR\n\
LD b\nJMPC skip\nLD 5\nST x\nskip:\nLD 7\nST y\nEND_PROGRAM\n";

#[test]
fn a_literal_that_no_path_reads_after_the_label_is_no_error() {
    assert_eq!(codes_at(STORED_BEFORE_LABEL), Vec::<String>::new());
    let mut plc = compile(STORED_BEFORE_LABEL);
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "x"), lit(&plc, "y")), ("5".into(), "7".into()));
    let mut plc = compile(&STORED_BEFORE_LABEL.replace("b : BOOL;", "b : BOOL := TRUE;"));
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "x"), lit(&plc, "y")), ("0".into(), "7".into()));
}

#[test]
fn a_literal_read_after_the_label_as_the_wrong_type_is_reported_there() {
    // The jump brings a BOOL, the literal falls through: `ST x` reads a
    // CR that is not an INT on every path.
    let src = "PROGRAM P\nVAR b : BOOL; x : INT; END_VAR\n\
               LD b\nJMPC skip\nLD 5\nskip:\nST x\nEND_PROGRAM\n";
    let got = codes_at(src);
    assert!(!got.is_empty(), "{got:?}");
    assert!(
        got.iter().all(|c| c.contains("@7:")),
        "only at `ST x`: {got:?}"
    );
}
