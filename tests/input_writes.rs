//! Writing a VAR_INPUT inside the body of its own FUNCTION or
//! FUNCTION_BLOCK, as CODESYS and matiec accept (W321): the change is local.

use crate::support::access_diags;
use crate::support::plc;

use access_diags::codes_at;
use plc::{compile, lit, run};

#[test]
fn a_function_input_is_a_local_copy() {
    // CLAMP writes its input; the caller's variable keeps 150.
    let src = "FUNCTION Clamp : INT VAR_INPUT x : INT; END_VAR \
               IF x > 100 THEN x := 100; END_IF; Clamp := x; END_FUNCTION\n\
               PROGRAM P\nVAR v : INT := 150; r : INT; END_VAR\nr := Clamp(v);\nEND_PROGRAM\n";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r"), "100");
    assert_eq!(lit(&plc, "v"), "150");
}

#[test]
fn an_fb_input_keeps_the_written_value_until_a_call_assigns_it() {
    // The body halves `x` each call; a call without `x` goes on halving it,
    // a call with `x` starts again from the argument.
    let src = "FUNCTION_BLOCK Half VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR \
               x := x / 2; y := x; END_FUNCTION_BLOCK\n\
               PROGRAM P\nVAR h : Half; n : INT; a : INT; b : INT; c : INT; END_VAR\n\
               n := n + 1;\nIF n = 1 THEN h(x := 40); a := h.y; ELSIF n = 2 THEN h(); b := h.y; \
               ELSE h(x := 8); c := h.y; END_IF;\nEND_PROGRAM\n";
    let mut plc = compile(src);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "a"), "20");
    assert_eq!(lit(&plc, "b"), "10");
    assert_eq!(lit(&plc, "c"), "4");
}

#[test]
fn writing_an_input_warns_w321_at_the_write() {
    let src = "FUNCTION F : INT\nVAR_INPUT x : INT; END_VAR\nx := 1;\nF := x;\nEND_FUNCTION\n\
               FUNCTION_BLOCK B\nVAR_INPUT i : BOOL; END_VAR\ni := NOT i;\nEND_FUNCTION_BLOCK\n\
               PROGRAM P\nVAR b : B; r : INT; END_VAR\nb();\nr := F(1);\nEND_PROGRAM\n";
    // Sorted: FB bodies are checked before functions.
    let mut got = codes_at(src);
    got.sort();
    assert_eq!(got, vec!["W321@3:1", "W321@8:1"], "{got:?}");
}

#[test]
fn an_input_written_in_il_and_as_an_output_target_warns() {
    let src = "FUNCTION_BLOCK B\nVAR_INPUT i : INT; END_VAR\nVAR t : TON; END_VAR\n\
               LD 5\nST i\nEND_FUNCTION_BLOCK\n\
               FUNCTION_BLOCK C\nVAR_INPUT e : TIME; END_VAR\nVAR t : TON; END_VAR\n\
               t(IN := TRUE, PT := T#1s, ET => e);\nEND_FUNCTION_BLOCK\n\
               PROGRAM P\nVAR b : B; c : C; END_VAR\nb();\nc();\nEND_PROGRAM\n";
    let got = codes_at(src);
    assert_eq!(got, vec!["W321@5:4", "W321@10:33"], "{got:?}");
}

#[test]
fn reading_an_input_does_not_warn() {
    let src = "FUNCTION F : INT\nVAR_INPUT x : INT; END_VAR\nF := x + 1;\nEND_FUNCTION\n\
               PROGRAM P\nVAR r : INT; END_VAR\nr := F(1);\nEND_PROGRAM\n";
    assert_eq!(codes_at(src), Vec::<String>::new());
}
