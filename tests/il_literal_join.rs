//! IL: an untyped literal loaded just before a label takes the type that a
//! jump to the label brings (`LD 0` falling into `SET_OUT: ST OUT`, where
//! another path jumps to SET_OUT with an INT).

#[path = "support/access_diags.rs"]
mod access_diags;
#[path = "support/plc.rs"]
mod plc;

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
