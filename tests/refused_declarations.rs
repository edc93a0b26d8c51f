//! A declaration refused for its type (E209: a PROGRAM instance as a
//! parameter, a function returning a PROGRAM; E203: an unknown type) still declares its name, with the error type: the
//! function keeps its interface, so calls bind their arguments as written
//! and the body finds the name. One error per cause, at the declaration;
//! the calls and the body add none of their own (no "takes 0 arguments",
//! no "undeclared variable", no "expected <error>").

use crate::support::plc;

use plc::error_codes;

const SRC: &str = "\
FUNCTION_BLOCK FB_Counter
VAR_INPUT inc : INT; END_VAR
VAR_OUTPUT n : INT; END_VAR
n := n + inc;
END_FUNCTION_BLOCK
FUNCTION Peek : INT
VAR_INPUT c : Q; k : INT; END_VAR
Peek := c.n + k;
END_FUNCTION
FUNCTION Make : Q
VAR_INPUT k : INT; END_VAR
Make.inc := k;
END_FUNCTION
FUNCTION Both : INT
VAR_INPUT u : Unknwn; END_VAR
VAR_IN_OUT v : Unknwn; END_VAR
Both := u.n + v.n;
END_FUNCTION
PROGRAM P
VAR ctr : FB_Counter; r, i : INT; END_VAR
r := Peek(ctr, 1);
r := Peek(c := ctr, k := 2);
r := Make(3).n + Make(k := 4).inc;
r := Both(i, i);
r := Both(u := i, v := i);
END_PROGRAM
PROGRAM Q
VAR_INPUT inc : INT; END_VAR
VAR_OUTPUT n : INT; END_VAR
END_PROGRAM
";

#[test]
fn a_refused_parameter_or_result_type_is_reported_once_at_its_declaration() {
    let got = error_codes(&[("test.st", SRC)]);
    let want = [
        ("E209", "7:15"),
        ("E209", "10:10"),
        ("E203", "15:15"),
        ("E203", "16:16"),
    ];
    let want: Vec<(String, String)> = want
        .iter()
        .map(|(c, at)| (c.to_string(), at.to_string()))
        .collect();
    assert_eq!(got, want);
}

#[test]
fn the_calls_of_such_a_function_still_check_their_arity_and_their_arguments() {
    let src = SRC.replace(
        "r := Both(u := i, v := i);",
        "r := Peek(ctr, 1, 2); r := Peek(c := nope, k := 2);",
    );
    let got = error_codes(&[("test.st", &src)]);
    let tail: Vec<(&str, &str)> = got[4..]
        .iter()
        .map(|(c, at)| (c.as_str(), at.as_str()))
        .collect();
    assert_eq!(tail, [("E404", "25:6"), ("E201", "25:38")], "{got:?}");
}
