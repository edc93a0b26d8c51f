//! A function block that refers to its own type through a pointer slot:
//! a `VAR_IN_OUT` of one of its METHODs or of the block itself, and a
//! `REF_TO` variable (a linked structure of blocks). Each is one slot, so
//! the block's size stays finite; only an instance of the block inside
//! itself is E204 (docs/diagnostics.md).

use crate::support::plc;

use plc::{compile, error_codes, lit, run};

const VEC: &str = "
FUNCTION_BLOCK FB_Vec
VAR_INPUT x : INT; END_VAR
VAR next : REF_TO FB_Vec; END_VAR
METHOD Add
VAR_IN_OUT other : FB_Vec; END_VAR
VAR CONSTANT Lim : INT := 10; END_VAR
x := x + other.x;
IF x > Lim THEN x := Lim; END_IF
END_METHOD
METHOD Link
VAR_IN_OUT other : FB_Vec; END_VAR
next := REF(other);
END_METHOD
METHOD NextX : INT
IF next <> NULL THEN NextX := next^.x; END_IF
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB_Pair
VAR_INPUT x : INT; END_VAR
VAR_IN_OUT partner : FB_Pair; END_VAR
VAR_OUTPUT sum : INT; END_VAR
sum := x + partner.x;
END_FUNCTION_BLOCK

PROGRAM P
VAR a, b : FB_Vec; c, d : FB_Pair; r, s, t, u : INT; END_VAR
a.x := 3; b.x := 4;
a.Add(b);
r := a.x;
a.Add(b); a.Add(b);
s := a.x;
b.Link(a);
t := b.NextX();
c.x := 20; d.x := 22;
c(partner := d);
u := c.sum;
END_PROGRAM
";

#[test]
fn a_method_in_out_and_a_reference_of_the_blocks_own_type_run() {
    let mut plc = compile(VEC);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.r"), "7");
    assert_eq!(
        lit(&plc, "P.s"),
        "10",
        "the method's local constant limits x"
    );
    assert_eq!(lit(&plc, "P.t"), "10", "b.next designates a");
    assert_eq!(lit(&plc, "P.u"), "42");
}

#[test]
fn an_instance_of_the_block_inside_itself_is_still_e204() {
    let src = "FUNCTION_BLOCK A\nVAR inner : A; END_VAR\nEND_FUNCTION_BLOCK\n";
    let got = error_codes(&[("test.st", src)]);
    assert_eq!(got, [("E204".to_string(), "1:16".to_string())]);
}
