//! `EN` and `ENO` declared by the user. `EN` is the enable input every
//! FUNCTION and FUNCTION_BLOCK has implicitly; a POU that declares its own
//! `EN` parameter is read as CODESYS and TwinCAT read it: `EN :=` in a
//! call sets that parameter (warning W432 for a FUNCTION's or
//! FUNCTION_BLOCK's input; a METHOD has no enable, so its `EN` is plainly
//! a parameter; a local variable of that name is fine). An own `VAR_OUTPUT ENO : BOOL` is the implicit ENO
//! output itself: TRUE at each call, written by the body, read by the
//! caller's `ENO =>`.

use crate::support::plc;

use plc::{compile, error_codes, lit, run};

#[test]
fn a_declared_en_parameter_takes_the_argument_of_the_call() {
    let src = "\
FUNCTION F : INT
VAR_INPUT en : BOOL; v : INT; END_VAR
IF en THEN F := v; ELSE F := -1; END_IF
END_FUNCTION
FUNCTION_BLOCK FB
VAR_INPUT En : BOOL; END_VAR
VAR_OUTPUT q : INT; END_VAR
IF En THEN q := q + 1; END_IF
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_M
VAR_OUTPUT seen : BOOL; END_VAR
METHOD M
VAR_INPUT EN : BOOL; END_VAR
seen := EN;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM P
VAR r, s : INT; fb : FB; m : FB_M; END_VAR
r := F(en := TRUE, v := 5);
s := F(en := FALSE, v := 5);
fb(En := TRUE);
fb(En := FALSE);
m.M(EN := TRUE);
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    // The body ran both times: EN is the function's own input.
    assert_eq!(
        (lit(&plc, "P.r"), lit(&plc, "P.s")),
        ("5".into(), "-1".into())
    );
    assert_eq!(lit(&plc, "P.fb.q"), "1");
    assert_eq!(lit(&plc, "P.m.seen"), "TRUE");
    let warned: Vec<(&str, String)> = plc
        .warnings()
        .iter()
        .filter(|d| d.code == "W432")
        .map(|d| (d.code, d.message.clone()))
        .collect();
    assert_eq!(
        warned.len(),
        2,
        "the FUNCTION's and the FB's inputs: {warned:?}"
    );
    assert!(error_codes(&[("test.st", src)]).is_empty());
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
