//! CODESYS V3 / TwinCAT forms in ST: set and reset assignments (`x S= c;`
//! sets x when c is TRUE and keeps it otherwise, `x R= c;` resets it;
//! derived by hand below, cycle by cycle), the `BIT` type, and formal
//! arguments left empty.

use crate::support::plc;

use plc::{compile, error_codes, lit, run};

#[test]
fn set_keeps_the_variable_true_until_reset() {
    let src = "
FUNCTION_BLOCK FB_Latch
VAR_OUTPUT q : BOOL; flags : ARRAY[1..2] OF BOOL; END_VAR
VAR_INPUT s1 : BOOL; r1 : BOOL; END_VAR
q S= s1;
q R= r1 AND NOT s1;
flags[2] S= q;
END_FUNCTION_BLOCK
PROGRAM P
VAR latch : FB_Latch; n : INT; trace : INT; END_VAR
n := n + 1;
latch(s1 := n = 2, r1 := n = 4);
IF latch.q THEN trace := trace + 1; END_IF
END_PROGRAM
";
    let mut plc = compile(src);
    // Cycle 1: nothing; 2: set; 3: held; 4: reset; 5: stays reset.
    let mut seen = Vec::new();
    for _ in 0..5 {
        run(&mut plc, 1);
        seen.push(lit(&plc, "latch.q"));
    }
    assert_eq!(seen, ["FALSE", "TRUE", "TRUE", "FALSE", "FALSE"]);
    assert_eq!(lit(&plc, "trace"), "2");
    // flags[2] was set once and is never reset.
    assert_eq!(lit(&plc, "latch.flags[2]"), "TRUE");
}

#[test]
fn a_set_without_a_condition_or_of_a_non_bool_is_an_error() {
    let codes = |body: &str| {
        let src = format!("PROGRAM P VAR x : BOOL; i : INT; END_VAR {body} END_PROGRAM");
        error_codes(&[("t.st", &src)])
            .into_iter()
            .map(|(c, _)| c)
            .collect::<Vec<_>>()
    };
    assert!(!codes("x S= ;").is_empty());
    // The condition must be BOOL, as IF's.
    assert_eq!(codes("x S= i;"), ["E303"]);
}

#[test]
fn bit_members_are_bools_with_a_compatibility_warning() {
    let src = "TYPE ST_Flags : STRUCT bReady : BIT; bError : BIT; n : INT; END_STRUCT END_TYPE
PROGRAM P VAR s : ST_Flags; END_VAR
s.bReady S= s.n = 0;
s.bError := NOT s.bReady;
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(
        (lit(&plc, "s.bReady"), lit(&plc, "s.bError")),
        ("TRUE".into(), "FALSE".into())
    );
    assert_eq!(
        plc.warnings().iter().filter(|d| d.code == "W309").count(),
        2
    );
}

#[test]
fn an_empty_formal_argument_leaves_the_input_unconnected() {
    let src = "PROGRAM P
VAR t : TON; go : BOOL := TRUE; n : INT; q : BOOL; END_VAR
n := n + 1;
IF n = 1 THEN
  t(IN := go, PT := T#20ms);
ELSE
  (* IN keeps TRUE from the first call; ET is not read *)
  t(IN := , PT := T#20ms, ET => , Q => q);
END_IF
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 3);
    // Cycle 0 starts the timer at 0 ms, cycle 2 (20 ms) sees Q.
    assert_eq!(
        (lit(&plc, "t.IN"), lit(&plc, "q")),
        ("TRUE".into(), "TRUE".into())
    );
}

/// `trig : R_TRIG();` calls FB_init with no arguments: the instance is
/// declared as without the parentheses. A CASE arm's `Reset();` stays a
/// call. Cycle 1: the rising edge; 2: none; the CASE called Reset once.
#[test]
fn an_instance_declared_with_empty_parentheses_is_a_plain_instance() {
    let src = "
FUNCTION_BLOCK FB_Counter
VAR_OUTPUT n : INT := 5; END_VAR
METHOD Reset
n := 0;
END_METHOD
n := n + 1;
END_FUNCTION_BLOCK
PROGRAM P
VAR
  trig : R_TRIG();
  counter : FB_Counter();
  ton1 : TON() := (PT := T#1s);
  edges : INT; step : INT := 1;
END_VAR
trig(CLK := TRUE);
IF trig.Q THEN edges := edges + 1; END_IF
CASE step OF
  1: counter.Reset(); step := 2;
  2: counter();
END_CASE
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "edges"), "1");
    assert_eq!(lit(&plc, "counter.n"), "2");
    assert_eq!(lit(&plc, "ton1.PT"), "T#1s");
}

/// An initial value may read the variables declared before it in the same
/// VAR block (CODESYS initialises them in order): statics once, a
/// method's temporaries at every call. By hand: `list` starts [3, 6] and
/// its first element grows by one a cycle; M's `buf` is [18, 4] at every
/// call, so M returns 19 + 4 + LEN('x') = 24 each time.
#[test]
fn an_initial_value_reads_the_variables_declared_before_it_in_its_block() {
    let src = "
FUNCTION_BLOCK FB_T
VAR_OUTPUT sum : INT; total : INT; END_VAR
VAR
  base : INT := 3;
  twice : INT := base * 2;
  list : ARRAY[1..2] OF INT := [base, twice];
END_VAR
METHOD M : INT
VAR
  a : BYTE := 2#0001_0010;
  b : BYTE := 4;
  buf : ARRAY[1..2] OF BYTE := [a, b];
  s : STRING := 'x';
  t : STRING := s;
END_VAR
buf[1] := buf[1] + 1;
M := BYTE_TO_INT(buf[1]) + BYTE_TO_INT(buf[2]) + LEN(t);
END_METHOD
sum := M();
list[1] := list[1] + 1;
total := list[1] + list[2];
END_FUNCTION_BLOCK
PROGRAM P
VAR fb : FB_T; END_VAR
fb();
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "fb.sum"), "24");
    assert_eq!(lit(&plc, "fb.total"), "12");
}

/// An FB's static variable may read the inputs, outputs and variables
/// of its earlier blocks: their declared initial values, what they hold
/// when the instance starts (lcls-twincat-general's `FB_Index` starts
/// its counter at `LowerLimit`). Later calls with other inputs do not
/// change it.
#[test]
fn an_instance_variable_starts_from_an_earlier_blocks_initial_value() {
    let src = "
TYPE E_Sub : (Vacuum, Motion, Optics); END_TYPE
FUNCTION_BLOCK FB_Log
VAR_INPUT eSub : E_Sub; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Index
VAR_INPUT LowerLimit : INT := 4; Step : INT := 1; eSub : E_Sub := E_Sub.Optics; END_VAR
VAR_OUTPUT first : INT := LowerLimit * 10; END_VAR
VAR
  nVal : INT := LowerLimit;
  seed : INT := first + Step;
  logger : FB_Log := (eSub := eSub);
END_VAR
nVal := nVal + Step;
END_FUNCTION_BLOCK
PROGRAM P
VAR fb : FB_Index; END_VAR
fb(LowerLimit := 100, Step := 2);
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "fb.nVal"), "8");
    assert_eq!(lit(&plc, "fb.first"), "40");
    assert_eq!(lit(&plc, "fb.seed"), "41");
    assert_eq!(lit(&plc, "fb.logger.eSub"), "Optics");
}

/// A FUNCTION's variables, a METHOD's and a VAR_TEMP start afresh at each
/// call, so their initial values may read the call's inputs, call
/// functions and read the block's state as it is then (lcls-twincat-vacuum's valve
/// interlock: `rMaxRatioAllowed : LREAL := EXPT(10, i_iOrdersMagnitude)`),
/// in declaration order; the body computes them before its first
/// statement.
#[test]
fn a_per_call_initial_value_reads_the_inputs_and_state_of_that_call() {
    let src = "
VAR_GLOBAL calls : INT := 5; END_VAR
FUNCTION F_Ratio : LREAL
VAR_INPUT n : INT; END_VAR
VAR
  rMax : LREAL := EXPT(10, n);
  rMin : LREAL := 1.0 / rMax;
  k : INT := 3;
END_VAR
F_Ratio := rMax + rMin + k;
END_FUNCTION
FUNCTION F_Calls : INT
VAR seen : INT := calls; END_VAR
F_Calls := seen;
END_FUNCTION
FUNCTION_BLOCK FB
VAR s : INT := 1; END_VAR
VAR_OUTPUT seen, got : INT; END_VAR
VAR_TEMP x : INT := s * 10; END_VAR
METHOD M : INT
VAR_INPUT n : INT; END_VAR
VAR a : INT := n; b : INT := a + s; END_VAR
M := b;
END_METHOD
seen := x;
s := s + 1;
got := M(n := 5);
END_FUNCTION_BLOCK
PROGRAM P
VAR r2, r0 : LREAL; fb : FB; c : INT; END_VAR
r2 := F_Ratio(2);
r0 := F_Ratio(0);
fb();
calls := calls + 1;
c := F_Calls();
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    // 100 + 0.01 + 3, and 1 + 1 + 3
    assert_eq!(lit(&plc, "r2"), "103.01");
    assert_eq!(lit(&plc, "r0"), "5.0");
    // The second cycle's call reads s = 2; its method call the argument
    // 5 and s = 3, not their declared initial values.
    assert_eq!(lit(&plc, "fb.seen"), "20");
    assert_eq!(lit(&plc, "fb.got"), "8");
    // A global as it is at the call (7 after two cycles), not its
    // initial value.
    assert_eq!(lit(&plc, "c"), "7");
}

/// What a static variable's initial value may not read: a variable
/// declared after it, or anything that is no constant (an FB's `VAR` is
/// set once, when the instance starts).
#[test]
fn a_static_initial_value_from_a_later_variable_or_a_call_is_refused() {
    for (decls, why) in [
        (
            "VAR x : INT := later; later : INT := 1; END_VAR",
            "declared later",
        ),
        ("VAR x : LREAL := EXPT(10, 2); END_VAR", "a call"),
    ] {
        let src = format!("FUNCTION_BLOCK FB {decls} x := x + 1; END_FUNCTION_BLOCK");
        let codes: Vec<String> = error_codes(&[("t.st", &src)])
            .into_iter()
            .map(|(code, _)| code)
            .collect();
        assert_eq!(codes, ["E205"], "{why}: {src}");
    }
}

/// An enumeration's value initialises an integer, as CODESYS converts it
/// (W485): a structured initial value of an FB instance
/// (lcls-twincat-motion's `fbFF : FB_FastFault := (i_TypeCode :=
/// E_MotionFFType.PNEUMATIC_MOVE)`) and a plain variable.
#[test]
fn an_enumeration_value_initialises_an_integer() {
    let src = "
{attribute 'qualified_only'}
TYPE E_Kind : (Stop := 16#1000, Move := 16#1010) UINT; END_TYPE
TYPE E_Color : (Red, Green); END_TYPE
FUNCTION_BLOCK FB_Fault
VAR_INPUT code : UINT; name : STRING; END_VAR
END_FUNCTION_BLOCK
PROGRAM P
VAR
  ff : FB_Fault := (name := 'move', code := E_Kind.Move);
  w : WORD := E_Kind.Stop;
  g : INT := Green;
END_VAR
END_PROGRAM
";
    let plc = compile(src);
    assert_eq!(lit(&plc, "ff.code"), "4112");
    assert_eq!(lit(&plc, "w"), "16#1000");
    assert_eq!(lit(&plc, "g"), "1");
    let warned: Vec<String> = plc.warnings().iter().map(|d| d.code.to_string()).collect();
    assert_eq!(
        warned.iter().filter(|c| *c == "W485").count(),
        3,
        "{warned:?}"
    );
}

/// `TYPE ST_B EXTENDS ST_A : STRUCT` has ST_A's fields (and their initial
/// values) first, then its own, through a chain of extensions; the errors
/// name what is wrong.
#[test]
fn a_structure_extends_another_with_its_fields_and_their_initial_values() {
    let src = "
TYPE ST_A : STRUCT x : INT := 5; s : STRING[8] := 'a'; END_STRUCT END_TYPE
TYPE ST_B EXTENDS ST_A : STRUCT y : INT := 7; END_STRUCT END_TYPE
TYPE ST_C EXTENDS ST_B :
STRUCT
  z : REAL;
END_STRUCT
END_TYPE
PROGRAM P
VAR b : ST_B; c : ST_C; copy : ST_C; END_VAR
c.x := c.x + 1; c.z := 1.5; c.s := 'c';
copy := c;
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    assert_eq!(
        [lit(&plc, "b.x"), lit(&plc, "b.s"), lit(&plc, "b.y")],
        ["5", "'a'", "7"]
    );
    assert_eq!(
        [
            lit(&plc, "copy.x"),
            lit(&plc, "copy.s"),
            lit(&plc, "copy.y"),
            lit(&plc, "copy.z")
        ],
        ["7", "'c'", "7", "1.5"]
    );
    for (types, code) in [
        (
            "TYPE ST_B EXTENDS INT : STRUCT y : INT; END_STRUCT END_TYPE",
            "E438",
        ),
        (
            "TYPE ST_D EXTENDS ST_Q : STRUCT y : INT; END_STRUCT END_TYPE",
            "E203",
        ),
        (
            "TYPE ST_E EXTENDS ST_E : STRUCT y : INT; END_STRUCT END_TYPE",
            "E204",
        ),
        (
            "TYPE ST_F EXTENDS ST_G : STRUCT x : INT; END_STRUCT END_TYPE
             TYPE ST_G : STRUCT x : INT; END_STRUCT END_TYPE",
            "E202",
        ),
    ] {
        let name = types.split_whitespace().nth(1).unwrap();
        let src = format!("{types}\nPROGRAM P VAR v : {name}; END_VAR END_PROGRAM");
        let codes: Vec<String> = error_codes(&[("t.st", &src)])
            .into_iter()
            .map(|(code, _)| code)
            .collect();
        assert_eq!(codes, [code], "{src}");
    }
}

/// An enumeration value indexes an array as its base type's integer
/// (CODESYS; W485, refused by `--strict`): SOUTH is 2, TOP 3.
#[test]
fn an_enumeration_value_indexes_an_array_as_its_integer() {
    let src = "
TYPE E_Blade : (NORTH := 1, SOUTH, TOP); END_TYPE
PROGRAM P
VAR a : ARRAY[1..3] OF INT; x : INT; b : E_Blade := E_Blade.TOP; END_VAR
a[E_Blade.SOUTH] := 7; a[b] := 9;
x := a[2] + a[3];
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "x"), "16");
    let codes: Vec<&str> = plc.warnings().iter().map(|d| d.code).collect();
    assert_eq!(codes, ["W485", "W485"]);
}

/// `VAR_STAT` (CODESYS, TwinCAT): one copy for every instance and call,
/// initialised once. By hand: `shared` starts at 100 and both instances
/// add 1 a cycle (102, 104, 106); `own` is per instance; a FUNCTION's
/// static `n` keeps its value while its VAR `t` is reset at every call
/// (n * 10 + t: 11, 21, 31); a METHOD's static `calls` is shared by the
/// two instances (1 + 2, 3 + 4, 5 + 6). A cold reset starts them over.
#[test]
fn static_variables_are_shared_by_every_instance_and_call() {
    let src = "
FUNCTION_BLOCK FB_Count
VAR_STAT shared : INT := 100; name : STRING := 'x'; END_VAR
VAR own : INT; END_VAR
METHOD GetShared : INT
GetShared := shared;
END_METHOD
METHOD Hit : INT
VAR_STAT calls : INT; END_VAR
calls := calls + 1;
Hit := calls;
END_METHOD
shared := shared + 1;
own := own + 1;
name := CONCAT(name, 'y');
END_FUNCTION_BLOCK
FUNCTION F : INT
VAR_STAT n : INT; END_VAR
VAR t : INT; END_VAR
n := n + 1; t := t + 1;
F := n * 10 + t;
END_FUNCTION
PROGRAM P
VAR a, b : FB_Count; s, oa, f, h : INT; END_VAR
a(); b();
s := b.GetShared(); oa := a.own; f := F(); h := a.Hit() + b.Hit();
END_PROGRAM
";
    let mut plc = compile(src);
    let mut seen = Vec::new();
    for _ in 0..3 {
        run(&mut plc, 1);
        seen.push(["s", "oa", "f", "h"].map(|n| lit(&plc, n)).join(","));
    }
    assert_eq!(seen, ["102,1,11,3", "104,2,21,7", "106,3,31,11"]);
    plc.reset_cold();
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "s"), "102");
    assert_eq!(lit(&plc, "f"), "11");
}

#[test]
fn a_function_or_method_may_return_a_subrange() {
    // TcUnit's `METHOD GetTestOrder : UINT(0..N)`.
    let src = "
FUNCTION_BLOCK FB_Order
METHOD Next : UINT(0..3)
VAR_INPUT k : UINT; END_VAR
Next := k MOD 4;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION Clip : INT(-5..5)
VAR_INPUT x : INT; END_VAR
Clip := LIMIT(-5, x, 5);
END_FUNCTION
PROGRAM P
VAR o : FB_Order; a : UINT; b : INT; END_VAR
a := o.Next(7);
b := Clip(-9);
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "a"), "3");
    assert_eq!(lit(&plc, "b"), "-5");
}

#[test]
fn a_reference_is_bound_to_what_a_method_returns_by_reference() {
    // TcUnit: `UnitTestResults REF= TestResults.GetTestSuiteResults();`,
    // through an interface.
    let src = "
INTERFACE I_Get
METHOD Get : REFERENCE TO INT
END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Store IMPLEMENTS I_Get
VAR data : INT := 7; END_VAR
METHOD Get : REFERENCE TO INT
Get REF= data;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION Plain : INT
Plain := 1;
END_FUNCTION
PROGRAM P
VAR s : FB_Store; itf : I_Get; r : REFERENCE TO INT; v : INT; END_VAR
itf := s;
r REF= itf.Get();
v := r;
r := 42;
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "v"), "7");
    assert_eq!(lit(&plc, "s.data"), "42");
    let bad = src.replace("r REF= itf.Get();", "r REF= Plain();");
    assert_eq!(
        error_codes(&[("t.st", &bad)]),
        [("E301".to_string(), "18:8".to_string())]
    );
}

/// `THIS` without `^` is a `POINTER TO` the instance (E918 outside a
/// function block); a standard function takes a positional argument after
/// a formal one at its own position (W487), and a parameter given both
/// ways is E404.
#[test]
fn this_is_a_pointer_and_standard_functions_take_mixed_arguments_by_position() {
    let src = "
FUNCTION_BLOCK FB_Node
VAR_INPUT v : INT; END_VAR
VAR self : POINTER TO FB_Node; END_VAR
self := THIS;
END_FUNCTION_BLOCK
PROGRAM P
VAR a, b : FB_Node; va, vb : INT; same : BOOL; pos : INT; END_VAR
a(v := 3); b(v := 4);
va := a.self^.v; vb := b.self^.v;
same := a.self = ADR(a);
pos := FIND(IN1 := 'a.b', '.');
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "va"), "3");
    assert_eq!(lit(&plc, "vb"), "4");
    assert_eq!(lit(&plc, "same"), "TRUE");
    assert_eq!(lit(&plc, "pos"), "2");
    let codes = |body: &str| {
        let src = format!("PROGRAM P VAR p : POINTER TO INT; n : INT; END_VAR {body} END_PROGRAM");
        error_codes(&[("t.st", &src)])
            .into_iter()
            .map(|(c, _)| c)
            .collect::<Vec<_>>()
    };
    assert_eq!(codes("p := THIS;"), ["E918"]);
    assert_eq!(codes("n := FIND(IN2 := 'a', 'b.');"), ["E404"]);
}

/// `SIZEOF` in an array bound (TcUnit sizes its message buffer so): of a
/// structure declared further down, of an elementary type, of a constant;
/// the bytes are those `SIZEOF` gives in code.
#[test]
fn sizeof_sizes_an_array_in_its_bounds() {
    let src = "
PROGRAM P
VAR CONSTANT N : INT := 3; END_VAR
VAR
    buffer : ARRAY[0..(N * SIZEOF(ST_Message)) - 1] OF BYTE;
    words : ARRAY[1..SIZEOF(DWORD)] OF WORD;
    again : ARRAY[1..SIZEOF(N)] OF BOOL;
    last, n1, n2 : DINT;
END_VAR
last := UPPER_BOUND(buffer, 1);
n1 := UPPER_BOUND(words, 1);
n2 := UPPER_BOUND(again, 1);
END_PROGRAM
TYPE ST_Message : STRUCT id : DINT; text : STRING(10); END_STRUCT END_TYPE";
    let mut plc = compile(src);
    run(&mut plc, 1);
    // ST_Message: 4 + 11 bytes; three of them: 45 bytes, 0..44.
    assert_eq!(lit(&plc, "last"), "44");
    assert_eq!(lit(&plc, "n1"), "4");
    assert_eq!(lit(&plc, "n2"), "2");
}
