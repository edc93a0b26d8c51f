//! `EN` and `ENO` declared by the user. `EN` is the enable input every
//! FUNCTION and FUNCTION_BLOCK has implicitly: a parameter named `EN` (any
//! case) would never get the value a call gives it, so it is refused,
//! E432, in FUNCTIONs, FUNCTION_BLOCKs and METHODs (a local variable of
//! that name is fine). An own `VAR_OUTPUT ENO : BOOL` is the implicit ENO
//! output itself: TRUE at each call, written by the body, read by the
//! caller's `ENO =>`.

#[path = "support/plc.rs"]
mod plc;

use plc::{compile, error_codes, lit, run};

#[test]
fn a_parameter_named_en_is_e432_at_its_declaration() {
    let src = "\
FUNCTION F : INT
VAR_INPUT en : BOOL; v : INT; END_VAR
IF en THEN F := v; ELSE F := -1; END_IF
END_FUNCTION
FUNCTION_BLOCK FB
VAR_OUTPUT En : BOOL; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB2 VAR_IN_OUT eN : INT; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_M
METHOD M
VAR_INPUT EN : BOOL; END_VAR
END_METHOD
END_FUNCTION_BLOCK
PROGRAM P
VAR r : INT; END_VAR
r := F(en := TRUE, v := 5);
END_PROGRAM
";
    let got = error_codes(&[("test.st", src)]);
    let got: Vec<(&str, &str)> = got.iter().map(|(c, a)| (c.as_str(), a.as_str())).collect();
    assert_eq!(
        got,
        [
            ("E432", "2:11"),
            ("E432", "6:12"),
            ("E432", "8:31"),
            ("E432", "12:11")
        ],
        "one error per declaration, none at the call"
    );
}

#[test]
fn a_local_variable_named_en_is_an_ordinary_variable() {
    let src = "
FUNCTION F : INT
VAR_INPUT v : INT; END_VAR
VAR en : INT; END_VAR
en := v * 2;
F := en;
END_FUNCTION
PROGRAM P
VAR r, s : INT; END_VAR
r := F(v := 4);
s := F(EN := FALSE, v := 5);
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.r"), "8");
    assert_eq!(lit(&plc, "P.s"), "0", "EN := FALSE still skips the call");
}

#[test]
fn an_own_eno_output_is_the_eno_the_caller_reads() {
    let src = "
FUNCTION Safe : INT
VAR_INPUT a, b : INT; END_VAR
VAR_OUTPUT ENO : BOOL; END_VAR
IF b = 0 THEN ENO := FALSE; ELSE Safe := a / b; END_IF
END_FUNCTION
PROGRAM P
VAR r : INT; ok1, ok2, ok3 : BOOL := TRUE; END_VAR
r := Safe(a := 6, b := 3, ENO => ok1);
Safe(a := 1, b := 0, ENO => ok2);
Safe(EN := FALSE, a := 1, b := 1, ENO => ok3);
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.r"), "2");
    assert_eq!(lit(&plc, "P.ok1"), "TRUE");
    assert_eq!(lit(&plc, "P.ok2"), "FALSE");
    assert_eq!(lit(&plc, "P.ok3"), "FALSE");
}
