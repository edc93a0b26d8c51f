//! Cycles of method calls through interfaces (docs/language.md, "OOP"):
//! a veto arbiter asks its higher authority, an interface its own block
//! implements too. The call graph has a cycle; at run time the calls go
//! to other instances. plcrun accepts such a cycle, runs it, and stops
//! the PLC (R081) if a method is entered again on an instance where it
//! is still running; a cycle that must come back to the same instance is
//! still E409, and one that could nest deeper than the executor allows
//! is E181.

use crate::support::plc::{error_codes, first_fault, line_col, lit, program, run_once};

/// An interface, a block that passes the question on unless it vetoes,
/// and a top block that answers it. `local` checks that a method's
/// variables survive the nested calls of the same method on other
/// instances; `calls` counts the calls of each instance.
const AUTHORITIES: &str = "INTERFACE I_Auth
METHOD Check : BOOL
VAR_INPUT n : INT; END_VAR
END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Veto IMPLEMENTS I_Auth
VAR_INPUT higher : I_Auth; veto : BOOL; END_VAR
VAR_OUTPUT calls : INT; END_VAR
METHOD Check : BOOL
VAR_INPUT n : INT; END_VAR
VAR local : INT; END_VAR
local := n * 2;
calls := calls + 1;
IF veto THEN
  Check := TRUE;
  RETURN;
END_IF
Check := higher.Check(n + 1) AND local = n * 2;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Top IMPLEMENTS I_Auth
VAR_OUTPUT seen : INT; END_VAR
METHOD Check : BOOL
VAR_INPUT n : INT; END_VAR
seen := n;
Check := n > 2;
END_METHOD
END_FUNCTION_BLOCK";

#[test]
fn a_cycle_through_an_interface_runs_on_other_instances() {
    let src = program(
        AUTHORITIES,
        "v1, v2, v3 : FB_Veto; top : FB_Top; ok, again : BOOL;",
        "v1.higher := v2; v2.higher := v3; v3.higher := top;\n\
         ok := v1.Check(1);\n\
         v2.veto := TRUE;\n\
         again := v1.Check(1) AND v1.Check(1);",
    );
    let plc = run_once(&src);
    let got: Vec<String> = ["ok", "top.seen", "v1.calls", "v3.calls", "again"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    // 1 -> 2 -> 3 -> top asked with 4; then v2 vetoes (and RETURNs: its
    // guard is released, so the third call enters it again).
    assert_eq!(got, ["TRUE", "4", "3", "1", "TRUE"]);
}

#[test]
fn the_same_instance_reached_again_stops_the_plc() {
    let src = program(
        AUTHORITIES,
        "v1, v2 : FB_Veto; ok : BOOL;",
        "v1.higher := v2; v2.higher := v1;\nok := v1.Check(1);",
    );
    let fault = first_fault(&src);
    assert_eq!(fault.code(), "R081", "{fault}");
    assert_eq!(fault.pou, "FB_Veto.Check");
    // At the method's declaration, line 9 of the sources.
    assert_eq!(line_col(&fault.location).0, 9, "{fault}");
    assert!(fault.to_string().contains("still running"), "{fault}");
}

#[test]
fn a_cycle_that_must_come_back_to_the_same_instance_is_e409() {
    // Two methods calling each other on their own instance.
    let src = program(
        "FUNCTION_BLOCK F\nMETHOD A\nB();\nEND_METHOD\nMETHOD B\nTHIS^.A();\nEND_METHOD\nEND_FUNCTION_BLOCK",
        "f : F;",
        "f.A();",
    );
    let codes = error_codes(&[("t.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E409"),
        "{codes:?}"
    );
    // A FUNCTION in the cycle: its frame is static, so it cannot be
    // re-entered even through an interface.
    let src = program(
        &format!(
            "{}\nFUNCTION Ask : BOOL\nVAR_INPUT a : I_Auth; END_VAR\nAsk := a.Check(0);\nEND_FUNCTION\nFUNCTION_BLOCK FB_Via IMPLEMENTS I_Auth\nVAR_INPUT next : I_Auth; END_VAR\nMETHOD Check : BOOL\nVAR_INPUT n : INT; END_VAR\nCheck := Ask(next);\nEND_METHOD\nEND_FUNCTION_BLOCK",
            AUTHORITIES
        ),
        "v : FB_Via; top : FB_Top; ok : BOOL;",
        "v.next := top; ok := v.Check(0);",
    );
    let codes = error_codes(&[("t.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E409"),
        "{codes:?}"
    );
}

#[test]
fn a_cycle_with_more_instances_than_the_nesting_limit_is_e181() {
    let src = program(
        AUTHORITIES,
        "chain : ARRAY[1..1200] OF FB_Veto; top : FB_Top; ok : BOOL;",
        "ok := chain[1].Check(1);",
    );
    let codes = error_codes(&[("t.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E181"),
        "{codes:?}"
    );
    // Within the limit the chain runs (kept short: a debug build's
    // frames are large).
    let src = program(
        AUTHORITIES,
        "chain : ARRAY[1..40] OF FB_Veto; top : FB_Top; ok : BOOL; i : INT;",
        "FOR i := 1 TO 39 DO chain[i].higher := chain[i + 1]; END_FOR\n\
         chain[40].higher := top;\nok := chain[1].Check(1);",
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "P.top.seen"), "41");
}
