//! Reading a function block instance's internal variables from outside
//! (`x := inst.count;`), as CoDeSys 2.3 and matiec accept: W320, read-only
//! (a write is E420); VAR_TEMP (E421) stays hidden, a VAR_IN_OUT reads its bound variable (W325).

use crate::support::access_diags;
use crate::support::plc;

use access_diags::{codes_at, diags};
use plc::{compile, lit, run};
use plcrun::Severity;

/// An FB counting its calls in an internal variable, with an internal
/// instance of its own (one line, so the program's lines are fixed).
const COUNTER: &str = "FUNCTION_BLOCK Counter VAR_INPUT inc : INT := 1; END_VAR \
VAR_OUTPUT q : BOOL; END_VAR VAR count : INT; edge : R_TRIG; END_VAR \
VAR_TEMP t : INT; END_VAR count := count + inc; edge(CLK := count > 4); \
q := edge.Q; END_FUNCTION_BLOCK";

fn prog(decls: &str, body: &str) -> String {
    format!("{COUNTER}\nPROGRAM P\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n")
}

#[test]
fn an_internal_variable_is_read_from_outside() {
    let src = prog(
        "c : Counter; n : INT; inp : INT; seen : BOOL;",
        "c(inc := 2);\nn := c.count;\ninp := c.inc;\nseen := c.edge.Q;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "2");
    assert_eq!(lit(&plc, "inp"), "2");
    assert_eq!(lit(&plc, "seen"), "FALSE");
    // Third call: count 6 > 4 for the first time, the inner R_TRIG fires.
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "n"), "6");
    assert_eq!(lit(&plc, "seen"), "TRUE");
}

#[test]
fn reading_an_internal_warns_w320_at_the_member() {
    let src = prog("c : Counter; n : INT;", "c();\nn := c.count;");
    let d = diags(&src);
    // Body line 2 is line 7; `count` starts at column 8.
    assert_eq!(
        d,
        vec![("W320".to_string(), Severity::Warning, "7:8".to_string())],
        "{d:?}"
    );
}

#[test]
fn an_internal_is_read_in_il_too() {
    let src = format!(
        "{COUNTER}\nPROGRAM P\nVAR c : Counter; n : INT; END_VAR\nCAL c\nLD c.count\nADD 10\nST n\nEND_PROGRAM\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "11");
}

#[test]
fn writing_an_internal_from_outside_is_e420() {
    let got = codes_at(&prog("c : Counter;", "c.count := 3;"));
    assert_eq!(got, vec!["W320@6:3", "E420@6:1"], "{got:?}");
}

#[test]
fn a_temporary_is_e421_and_an_in_out_read_is_w325() {
    let got = codes_at(&prog("c : Counter; n : INT;", "n := c.t;"));
    assert_eq!(got, vec!["E421@6:8"], "{got:?}");
    let io = "FUNCTION_BLOCK Io VAR_IN_OUT r : INT; END_VAR r := r + 1; END_FUNCTION_BLOCK";
    let src = format!(
        "{io}\nPROGRAM P\nVAR\nb : Io; v : INT; n : INT;\nEND_VAR\nb(r := v);\nn := b.r;\nEND_PROGRAM\n"
    );
    let got = codes_at(&src);
    // Issue #11: reading an in-out from outside reads the bound variable
    // (W325, tests/in_out_outside.rs); writing it from outside stays E422.
    assert_eq!(got, vec!["W325@7:8"], "{got:?}");
    let src = format!(
        "{io}\nPROGRAM P\nVAR\nb : Io; v : INT;\nEND_VAR\nb(r := v);\nb.r := 1;\nEND_PROGRAM\n"
    );
    let got = codes_at(&src);
    assert_eq!(got, vec!["W325@7:3", "E422@7:1"], "{got:?}");
}

#[test]
fn an_unknown_member_is_still_e201() {
    let got = codes_at(&prog("c : Counter; n : INT;", "n := c.nothing;"));
    assert_eq!(got, vec!["E201@6:8"], "{got:?}");
}
