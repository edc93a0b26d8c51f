//! `FB_init` (CODESYS V3, TwinCAT 3): called for every instance before the
//! first cycle and at every reset, with the arguments of the instance's
//! declaration (`fb : FB_X(a := 1)`, positional ones by rank after
//! `bInitRetains` and `bInCopyCode`); members before their container; a
//! derived block's after its parent's. Expected values derived by hand in
//! each test's comment.

use crate::support::plc;

use plc::{compile, error_codes, lit, run};

/// An interface and a block implementing it that sums what it is given.
const LOGGER: &str = "
INTERFACE I_Log
METHOD Log : INT
VAR_INPUT n : INT; END_VAR
END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Logger IMPLEMENTS I_Log
VAR total : INT; END_VAR
METHOD Log : INT
VAR_INPUT n : INT; END_VAR
total := total + n;
Log := total;
END_METHOD
END_FUNCTION_BLOCK
";

/// FB_Counter's FB_init sets `count` from its arguments and counts its
/// own calls; FB_Pair's reads its members' counts, so it must run after
/// theirs: 100 + 10 = 110. Each cycle adds `inc` (1 for `a`, 5 for `b`).
const COUNTERS: &str = "
FUNCTION_BLOCK FB_Counter
VAR_INPUT inc : INT; END_VAR
VAR count, inits : INT; retains : BOOL; END_VAR
METHOD FB_init : BOOL
VAR_INPUT
  bInitRetains : BOOL;
  bInCopyCode : BOOL;
  start : INT;
  incBy : INT := 1;
END_VAR
count := start;
inc := incBy;
inits := inits + 1;
retains := bInitRetains;
END_METHOD
count := count + inc;
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB_Pair
VAR a : FB_Counter(start := 100); b : FB_Counter(10, 5); order : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR
order := a.count + b.count;
END_METHOD
a(); b();
END_FUNCTION_BLOCK

VAR_GLOBAL
  g : FB_Counter(start := 7);
END_VAR

PROGRAM Main
VAR
  p : FB_Pair;
  arr : ARRAY[1..3, 0..1] OF FB_Counter;
  plain : FB_Counter;
  n : INT;
END_VAR
VAR RETAIN kept : INT; END_VAR
n := n + 1;
kept := kept + 1;
p();
END_PROGRAM
";

#[test]
fn every_instance_is_initialised_with_its_declaration_arguments_members_first() {
    let mut plc = compile(COUNTERS);
    // Before any cycle: FB_init has run everywhere.
    assert_eq!(lit(&plc, "p.a.count"), "100");
    assert_eq!(lit(&plc, "p.b.count"), "10");
    assert_eq!(lit(&plc, "p.b.inc"), "5");
    assert_eq!(lit(&plc, "p.a.inc"), "1"); // the input's default
    assert_eq!(lit(&plc, "p.order"), "110");
    assert_eq!(lit(&plc, "g.count"), "7");
    assert_eq!(lit(&plc, "p.a.retains"), "TRUE");
    // Every element of an array, and an instance without arguments, once.
    for name in ["arr[1, 0]", "arr[3, 1]", "arr[2, 1]", "plain"] {
        assert_eq!(lit(&plc, &format!("{name}.inits")), "1", "{name}");
    }
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "p.a.count"), "103");
    assert_eq!(lit(&plc, "p.b.count"), "25");
    assert_eq!(lit(&plc, "p.order"), "110");
}

/// A cold reset starts over (bInitRetains TRUE); a warm reset keeps the
/// RETAIN `kept` and runs FB_init with bInitRetains FALSE. Either way
/// FB_init runs once more on fresh instances (`inits` is 1 again).
#[test]
fn resets_run_fb_init_again_retains_true_when_cold_and_false_when_warm() {
    let mut plc = compile(COUNTERS);
    run(&mut plc, 2);
    plc.reset_warm();
    assert_eq!(lit(&plc, "kept"), "2");
    assert_eq!(lit(&plc, "n"), "0");
    assert_eq!(lit(&plc, "p.a.count"), "100");
    assert_eq!(lit(&plc, "p.a.inits"), "1");
    assert_eq!(lit(&plc, "p.a.retains"), "FALSE");
    assert_eq!(lit(&plc, "g.retains"), "FALSE");
    plc.reset_cold();
    assert_eq!(lit(&plc, "kept"), "0");
    assert_eq!(lit(&plc, "p.a.retains"), "TRUE");
    assert_eq!(lit(&plc, "p.b.count"), "10");
}

/// FB_Base's FB_init runs before FB_Derived's (trail 1 then 2: 12), with
/// the same arguments; a derived FB_init may add parameters. The
/// arguments bind an interface to a sibling instance and a reference to
/// an array element, which the body then uses every cycle.
#[test]
fn a_derived_block_runs_its_parents_fb_init_first_with_interface_and_reference_arguments() {
    let src = LOGGER.to_string()
        + "
FUNCTION_BLOCK FB_Base
VAR trail : INT; log : I_Log; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; itf : I_Log; END_VAR
log := itf;
trail := trail * 10 + 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Derived EXTENDS FB_Base
VAR ax : REFERENCE TO INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; itf : I_Log; axis : REFERENCE TO INT; END_VAR
trail := trail * 10 + 2;
ax REF= axis;
END_METHOD
log.Log(1);
ax := ax + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
  logger : FB_Logger;
  axes : ARRAY[1..2] OF INT := [5, 50];
  d : FB_Derived(itf := logger, axis := axes[2]);
END_VAR
d();
END_PROGRAM
";
    let mut plc = compile(&src);
    assert_eq!(lit(&plc, "d.trail"), "12");
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "axes[2]"), "53");
    assert_eq!(lit(&plc, "logger.total"), "3");
}

/// A fault in FB_init stops the PLC before its first cycle, at the
/// statement's line, and a reset does not hide it.
#[test]
fn a_fault_in_fb_init_stops_the_plc_before_the_first_cycle() {
    let src = "
FUNCTION_BLOCK FB_Div
VAR q : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; d : INT; END_VAR
q := 10 / d;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : FB_Div(d := 0); n : INT; END_VAR
n := n + 1;
END_PROGRAM
";
    let mut plc = compile(src);
    let fault = plc.run_cycle().expect_err("FB_init divides by zero");
    assert_eq!(fault.code(), "R001", "{fault:?}");
    assert_eq!(fault.cycle, 0);
    assert!(fault.location.ends_with(":6:6"), "{}", fault.location);
    assert_eq!(lit(&plc, "n"), "0");
    plc.reset_cold();
    assert!(plc.run_cycle().is_err());
}

#[test]
fn arguments_a_block_cannot_take_are_errors_at_the_declaration() {
    let fb = "
FUNCTION_BLOCK FB_A
VAR x : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; a : INT; END_VAR
x := a;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Plain
VAR x : INT; END_VAR
END_FUNCTION_BLOCK
";
    let errors = |decls: &str| {
        let main = format!("PROGRAM Main\nVAR\n{decls}\nEND_VAR\nEND_PROGRAM\n");
        error_codes(&[("fb.st", fb), ("main.st", &main)])
    };
    // A block without FB_init takes no arguments.
    assert_eq!(errors("p : FB_Plain(1);"), [("E931".into(), "3:5".into())]);
    assert_eq!(errors("t : TON(T#1s);"), [("E931".into(), "3:5".into())]);
    // One input after the two implicit ones: a second positional is E932.
    assert_eq!(errors("a : FB_A(1, 2);"), [("E932".into(), "3:13".into())]);
    // A name FB_init does not declare: the call's own error.
    assert!(!errors("a : FB_A(b := 1);").is_empty());
    assert!(errors("a : FB_A(a := 1);").is_empty());
    // A PROGRAM's VAR_TEMP, and a FUNCTION's input: no instance of theirs
    // is started (a FUNCTION's VAR is, at every call: below).
    assert_eq!(
        errors("x : INT; END_VAR VAR_TEMP t : FB_A(a := 1);"),
        [("E931".into(), "3:31".into())]
    );
    let input = format!(
        "{fb}FUNCTION F : INT\nVAR_INPUT a : FB_A(a := 1); END_VAR\nF := 1;\nEND_FUNCTION\n"
    );
    assert_eq!(
        error_codes(&[("f.st", &input)]),
        [("E931".into(), "13:15".into())]
    );
}

/// The instances a METHOD or a FUNCTION declares in VAR live for one
/// call, as in CODESYS: FB_init runs at the start of every call, with the
/// declaration's arguments (`bInitRetains` FALSE), array elements too.
#[test]
fn a_method_s_or_function_s_local_instance_is_started_at_every_call() {
    let src = "
FUNCTION_BLOCK FB_Cnt
VAR n : INT; inits : INT; retains : BOOL; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; s : INT; END_VAR
n := s; inits := inits + 1; retains := bInitRetains;
END_METHOD
n := n + 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_User
VAR_OUTPUT last : INT; inits : INT; retains : BOOL; END_VAR
METHOD M : INT
VAR c : FB_Cnt(s := 10); arr : ARRAY[1..2] OF FB_Cnt[(s := 1), (s := 2)]; END_VAR
c(); c(); arr[2]();
last := c.n + arr[2].n;
inits := c.inits + arr[1].inits + arr[2].inits;
retains := c.retains;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION F : INT
VAR c : FB_Cnt(s := 100); END_VAR
c();
F := c.n;
END_FUNCTION
PROGRAM Main
VAR u : FB_User; a : INT; b : INT; f : INT; END_VAR
u.M(); u.M(); a := u.last; b := u.inits; f := F() + F();
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    // Each call: c from 10 to 12, arr[2] from 2 to 3; one FB_init each.
    assert_eq!(lit(&plc, "a"), "15");
    assert_eq!(lit(&plc, "b"), "3");
    assert_eq!(lit(&plc, "u.retains"), "FALSE");
    assert_eq!(lit(&plc, "f"), "202");
}

/// A block whose FB_init names it and sets a step (`fDelta`, 9 unless given).
const FB_S: &str = "
FUNCTION_BLOCK FB_S
VAR nm : STRING; d : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; sName : STRING; fDelta : INT := 9; END_VAR
nm := sName; d := fDelta;
END_METHOD
END_FUNCTION_BLOCK
";

/// `ARRAY[1..4] OF FB_S[(...), (...)]`: one argument list per element, in
/// order (formal or positional); the elements after the list get FB_init
/// without arguments (fDelta's default 9, an empty name).
#[test]
fn an_array_of_instances_takes_one_argument_list_per_element() {
    let src = format!(
        "{FB_S}
PROGRAM Main
VAR
  a : ARRAY[1..4] OF FB_S[
      (sName := 'OUT', fDelta := 1),
      ('T1')
  ];
END_VAR
END_PROGRAM
"
    );
    let plc = compile(&src);
    let got: Vec<String> = [
        "a[1].nm", "a[1].d", "a[2].nm", "a[2].d", "a[3].nm", "a[4].d",
    ]
    .iter()
    .map(|n| lit(&plc, n))
    .collect();
    assert_eq!(got, ["'OUT'", "1", "'T1'", "9", "''", "9"]);
}

/// A METHOD's `VAR_INST` instance lives in the block's instance, so it
/// takes FB_init arguments as the block's own do (PMPS's tests declare
/// `fbArbiter : FB_Arbiter(1);` there), initialised before the first
/// cycle; a METHOD's `VAR` instance lives for one call: E931.
#[test]
fn a_methods_instance_variable_takes_fb_init_arguments() {
    let fb = FB_S;
    let src = format!(
        "{fb}
FUNCTION_BLOCK FB_T
VAR_OUTPUT seen : INT; name : STRING; END_VAR
METHOD M : INT
VAR_INST inst : FB_S(sName := 'kept', fDelta := 4); END_VAR
M := inst.d;
name := inst.nm;
END_METHOD
seen := M();
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : FB_T; END_VAR
t();
END_PROGRAM
"
    );
    let mut plc = compile(&src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "t.seen"), "4");
    assert_eq!(lit(&plc, "t.name"), "'kept'");
    // A method's VAR_INPUT takes none.
    let input = format!(
        "{fb}FUNCTION_BLOCK FB_U
METHOD M : INT
VAR_INPUT inst : FB_S(sName := 'x'); END_VAR
M := inst.d;
END_METHOD
END_FUNCTION_BLOCK
"
    );
    let codes: Vec<String> = error_codes(&[("u.st", &input)])
        .into_iter()
        .map(|(c, _)| c)
        .collect();
    assert_eq!(codes, ["E931"]);
}

/// `{attribute 'call_after_init'}` before a METHOD: called on every
/// instance right after FB_init (order 1 then 2; x = 21 * 2); other
/// methods are not; no W151 for the honoured attribute.
#[test]
fn a_call_after_init_method_runs_right_after_fb_init() {
    let src = "
{attribute 'call_after_init'}
FUNCTION_BLOCK FB_C
VAR x, order : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; v : INT; END_VAR
x := v;
order := order * 10 + 1;
END_METHOD
{attribute 'call_after_init'}
METHOD AfterInit
x := x * 2;
order := order * 10 + 2;
END_METHOD
METHOD NotCalled
x := -1;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR c : FB_C(21); END_VAR
END_PROGRAM
";
    let plc = compile(src);
    assert_eq!(lit(&plc, "c.x"), "42");
    assert_eq!(lit(&plc, "c.order"), "12");
    assert!(plc.warnings().iter().all(|d| d.code != "W151"));
}

/// FB_exit when the program is unloaded: the derived block's first, then
/// its parent's (TwinCAT's order), then the members' (the reverse of the
/// start). Each appends its digit to `log`: d's 2 then 1, then the member
/// `inner`'s 1: 211. Cycles do not call it.
const EXITS: &str = "
FUNCTION_BLOCK FB_Base
METHOD FB_exit : BOOL
VAR_INPUT bInCopyCode : BOOL; END_VAR
G_log := G_log * 10 + 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_D EXTENDS FB_Base
VAR inner : FB_Base; END_VAR
METHOD FB_exit : BOOL
VAR_INPUT bInCopyCode : BOOL; END_VAR
G_log := G_log * 10 + 2;
END_METHOD
END_FUNCTION_BLOCK
VAR_GLOBAL RETAIN
  G_log : DINT;
END_VAR
PROGRAM Main
VAR d : FB_D; n : INT; END_VAR
VAR_OUTPUT out : DINT; END_VAR
n := n + 1;
out := G_log;
END_PROGRAM
";

#[test]
fn unloading_runs_fb_exit_derived_first_then_parent_then_members() {
    let mut plc = compile(EXITS);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "G_log"), "0");
    plc.unload().expect("FB_exit runs");
    assert_eq!(lit(&plc, "G_log"), "211");
}

/// `plcrun` unloads the program after the last cycle and before the last
/// retain save, so what FB_exit writes to a RETAIN variable is there at
/// the next start: the second run's first cycle reads 211.
#[cfg(feature = "cli")]
#[test]
fn the_command_line_runs_fb_exit_before_the_last_retain_save() {
    use crate::support::cli::{plcrun, temp_file};
    let src = temp_file("exit.st", EXITS);
    let retain = temp_file("exit.json", "");
    std::fs::remove_file(&retain).unwrap();
    let (code, _, err) = plcrun(&[&src, "--cycles", "2", "--retain", &retain]);
    assert_eq!(code, 0, "{err}");
    let (code, out, err) = plcrun(&[&src, "--cycles", "1", "--retain", &retain]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "cycle,time,out\n0,T#0s,211\n");
}

/// An interface variable whose initial value is an instance
/// (`out : I_Log := logger;`, CODESYS) is bound at start, before any
/// FB_init: the member and the global interfaces call their instances
/// (2 and 5 a cycle).
#[test]
fn an_interface_initialised_with_an_instance_is_bound_at_start() {
    let src = LOGGER.to_string()
        + "
FUNCTION_BLOCK FB_User
VAR logger : FB_Logger; out : I_Log := logger; END_VAR
out.Log(2);
END_FUNCTION_BLOCK
VAR_GLOBAL
  gl : FB_Logger;
  gi : I_Log := gl;
END_VAR
PROGRAM Main
VAR u : FB_User; END_VAR
u();
gi.Log(5);
END_PROGRAM
";
    let mut plc = compile(&src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "u.logger.total"), "4");
    assert_eq!(lit(&plc, "gl.total"), "10");
}

/// An axis whose FB_exit (in a copy) saves its position in a global and
/// whose FB_reinit takes it back, as a block written for online change
/// does; the second version adds a variable to the block.
const AXIS_V1: &str = "
VAR_GLOBAL saved : INT; exits : INT; reinits : INT; END_VAR
FUNCTION_BLOCK FB_Axis
VAR pos : INT; END_VAR
METHOD FB_exit : BOOL
VAR_INPUT bInCopyCode : BOOL; END_VAR
IF bInCopyCode THEN saved := pos; exits := exits + 1; END_IF
END_METHOD
METHOD FB_reinit : BOOL
pos := saved + 1000;
reinits := reinits + 1;
END_METHOD
pos := pos + 1;
END_FUNCTION_BLOCK
PROGRAM P
VAR a : FB_Axis; b : FB_Axis; n : INT; END_VAR
a(); n := n + 1;
END_PROGRAM
";

#[test]
fn online_change_calls_fb_exit_and_fb_reinit_on_the_instances_it_copies() {
    let mut plc = compile(AXIS_V1);
    run(&mut plc, 3); // a.pos = 3, b.pos = 0
    // The body alone changes: the instances stay, nothing is called.
    let body_only = AXIS_V1.replace(
        "pos := pos + 1;\nEND_FUNCTION_BLOCK",
        "pos := pos + 2;\nEND_FUNCTION_BLOCK",
    );
    let report = plc
        .online_change(compile(&body_only))
        .expect("the change applies");
    assert!(report.copied.is_empty(), "{report:?}");
    assert_eq!(lit(&plc, "exits"), "0");
    run(&mut plc, 1); // a.pos = 5
    // The declaration changes: both instances are copied. FB_exit runs on
    // each old instance (b last, so saved = b's 0), then the copy carries
    // pos (5 and 0), then FB_reinit sets pos := saved + 1000 on each.
    let declared = body_only.replace(
        "VAR pos : INT; END_VAR",
        "VAR pos : INT; speed : REAL; END_VAR",
    );
    let report = plc
        .online_change(compile(&declared))
        .expect("the change applies");
    assert_eq!(report.copied, ["P.a", "P.b"]);
    assert!(
        report.to_string().contains("copied P.a\ncopied P.b\n"),
        "{report}"
    );
    assert_eq!(lit(&plc, "exits"), "2");
    assert_eq!(lit(&plc, "reinits"), "2");
    assert_eq!(lit(&plc, "saved"), "0");
    assert_eq!(lit(&plc, "P.a.pos"), "1000");
    assert_eq!(lit(&plc, "P.b.pos"), "1000");
    assert_eq!(lit(&plc, "P.n"), "4"); // the program's own state is kept
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a.pos"), "1002");
}

#[test]
fn a_fault_in_fb_reinit_stops_the_plc_after_the_change() {
    let mut plc = compile(AXIS_V1);
    run(&mut plc, 1);
    let faulty = AXIS_V1
        .replace(
            "VAR pos : INT; END_VAR",
            "VAR pos : INT; zero : INT; END_VAR",
        )
        .replace("pos := saved + 1000;", "pos := saved / zero;");
    let err = plc
        .online_change(compile(&faulty))
        .expect_err("FB_reinit divides by zero");
    let text = err.to_string();
    assert!(text.contains("FB_reinit"), "{text}");
    assert!(text.contains("R001"), "{text}");
    let fault = plc.run_cycle().expect_err("the PLC stays stopped");
    assert_eq!(fault.code(), "R001");
}
