//! Edition-3 edge-qualified inputs: `clk : BOOL R_EDGE;` reads TRUE inside
//! the FB only on the call where the value passed rises (R_EDGE) or falls
//! (F_EDGE); the memory is per instance and starts FALSE.

use crate::support::access_diags;
use crate::support::plc;

use access_diags::codes_at;
use plc::{compile, lit, run};

/// Counts the edges each instance sees, and passes the input it saw out.
const EDGES: &str = "FUNCTION_BLOCK Edges\nVAR_INPUT up : BOOL R_EDGE; down : BOOL F_EDGE; END_VAR\n\
VAR_OUTPUT ups : INT; downs : INT; saw : BOOL; END_VAR\n\
IF up THEN ups := ups + 1; END_IF;\nIF down THEN downs := downs + 1; END_IF;\nsaw := up;\n\
END_FUNCTION_BLOCK\n";

#[test]
fn edges_are_seen_once_per_change_and_per_instance() {
    // Cycle n (1-based) passes x = pattern[n-1] to `a`, and NOT x to `b`.
    // pattern: F T T F T F F  -> rising at 2 and 5, falling at 4 and 6.
    let src = format!(
        "{EDGES}PROGRAM P\nVAR a : Edges; b : Edges; n : INT; x : BOOL; firstsaw : BOOL; END_VAR\n\
         n := n + 1;\n\
         CASE n OF 2, 3, 5: x := TRUE; ELSE x := FALSE; END_CASE;\n\
         a(up := x, down := x);\nb(up := NOT x, down := NOT x);\n\
         IF n = 2 THEN firstsaw := a.saw; END_IF;\nEND_PROGRAM\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 7);
    assert_eq!(lit(&plc, "a.ups"), "2");
    assert_eq!(lit(&plc, "a.downs"), "2");
    assert_eq!(lit(&plc, "firstsaw"), "TRUE");
    // b sees NOT x: T F F T F T T -> rising at 1 (memory starts FALSE), 4, 6;
    // falling at 2, 5.
    assert_eq!(lit(&plc, "b.ups"), "3");
    assert_eq!(lit(&plc, "b.downs"), "2");
}

#[test]
fn a_call_without_the_input_sees_no_new_edge() {
    // TRUE passed once, then calls without `up`: the raw input stays TRUE,
    // so only the first call is an edge.
    let src = format!(
        "{EDGES}PROGRAM P\nVAR a : Edges; n : INT; END_VAR\n\
         n := n + 1;\nIF n = 1 THEN a(up := TRUE); ELSE a(); END_IF;\nEND_PROGRAM\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 4);
    assert_eq!(lit(&plc, "a.ups"), "1");
}

#[test]
fn the_raw_input_is_what_the_caller_wrote() {
    let src = format!(
        "{EDGES}PROGRAM P\nVAR a : Edges; r : BOOL; END_VAR\na(up := TRUE);\na(up := TRUE);\nr := a.up;\nEND_PROGRAM\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r"), "TRUE");
    assert_eq!(lit(&plc, "a.ups"), "1");
}

#[test]
fn edge_qualifiers_in_il_bodies() {
    let src = "FUNCTION_BLOCK Cnt\nVAR_INPUT clk : BOOL R_EDGE; END_VAR\nVAR_OUTPUT n : INT; END_VAR\n\
               LD clk\nJMPCN done\nLD n\nADD 1\nST n\ndone:\nEND_FUNCTION_BLOCK\n\
               PROGRAM P\nVAR c : Cnt; k : INT; END_VAR\nk := k + 1;\nc(clk := k MOD 3 = 0);\nEND_PROGRAM\n";
    let mut plc = compile(src);
    run(&mut plc, 9);
    // k MOD 3 = 0 at k = 3, 6, 9: three separate rising edges.
    assert_eq!(lit(&plc, "c.n"), "3");
}

#[test]
fn misplaced_or_mistyped_qualifiers_have_codes() {
    let f = "FUNCTION F : INT\nVAR_INPUT x : BOOL R_EDGE; END_VAR\nF := 1;\nEND_FUNCTION\n";
    assert_eq!(codes_at(f), vec!["E426@2:11"]);
    let fb = "FUNCTION_BLOCK B\nVAR_INPUT x : INT R_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n";
    assert_eq!(codes_at(fb), vec!["E427@2:15"]);
    let local = "FUNCTION_BLOCK B\nVAR x : BOOL F_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n";
    assert_eq!(codes_at(local), vec!["E426@2:5"]);
    let other = "FUNCTION_BLOCK B\nVAR_INPUT x : BOOL EDGY; END_VAR\nEND_FUNCTION_BLOCK\n";
    assert_eq!(codes_at(other), vec!["E425@2:20"]);
}
