//! Edition-3 object orientation (docs/language.md, docs/semantics.md
//! "Object orientation"): methods, EXTENDS, SUPER^/THIS^, interfaces with
//! dispatch, ABSTRACT/FINAL, access specifiers; every feature run and
//! checked after cycles, every misuse a coded diagnostic at its place.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};
use rstest::rstest;

const SHAPES: &str = "
INTERFACE IShape
  METHOD Area : REAL
  END_METHOD
  METHOD Scale
    VAR_INPUT k : REAL; END_VAR
  END_METHOD
END_INTERFACE

FUNCTION_BLOCK Rect IMPLEMENTS IShape
  VAR_INPUT w, h : REAL; END_VAR
  VAR_OUTPUT calls : INT; END_VAR
  METHOD Area : REAL
    Area := w * h;
    calls := calls + 1;
  END_METHOD
  METHOD Scale
    VAR_INPUT k : REAL := 2.0; END_VAR
    w := w * k;
    h := h * k;
  END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Square EXTENDS Rect
  METHOD Area : REAL
    Area := SUPER^.Area() + 1000.0;
  END_METHOD
END_FUNCTION_BLOCK
";

#[test]
fn methods_run_on_their_instance_and_return_values() {
    let src = program(
        SHAPES,
        "r : Rect; a, b : REAL; n : INT;",
        "r.w := 2.0; r.h := 3.0; a := r.Area() + r.Area(); r.Scale(k := 10.0); b := r.Area(); n := r.calls;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "12.0");
    assert_eq!(lit(&plc, "P.b"), "600.0");
    assert_eq!(lit(&plc, "P.n"), "3");
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.n"), "9", "the instance keeps its variables");
}

#[test]
fn an_input_not_given_takes_its_declared_initial_value_at_every_call() {
    let src = program(
        SHAPES,
        "r : Rect; a : REAL;",
        "r.w := 1.0; r.h := 1.0; r.Scale(k := 3.0); r.Scale(); a := r.Area();",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "36.0");
}

#[test]
fn a_child_overrides_and_calls_its_parent_through_super() {
    let src = program(
        SHAPES,
        "s : Square; a : REAL; w : REAL;",
        "s.w := 4.0; s.h := 4.0; a := s.Area(); s.Scale(k := 0.5); w := s.w;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "1016.0");
    assert_eq!(
        lit(&plc, "P.w"),
        "2.0",
        "the inherited method runs on the child"
    );
    assert_eq!(lit(&plc, "P.s.calls"), "1", "SUPER^.Area ran once");
}

#[test]
fn calls_through_an_interface_reach_the_assigned_instances_type() {
    let src = program(
        SHAPES,
        "r : Rect; s : Square; sh : IShape; a1, a2, a3 : REAL; held, empty : BOOL; none : IShape;",
        "r.w := 2.0; r.h := 3.0; s.w := 1.0; s.h := 1.0;
         sh := r; a1 := sh.Area();
         sh := s; a2 := sh.Area(); sh.Scale(k := 3.0); a3 := sh.Area();
         held := sh <> 0; empty := none = 0;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a1"), "6.0");
    assert_eq!(lit(&plc, "P.a2"), "1001.0");
    assert_eq!(lit(&plc, "P.a3"), "1009.0");
    assert_eq!(lit(&plc, "P.s.w"), "3.0");
    assert_eq!(lit(&plc, "P.held"), "TRUE");
    assert_eq!(lit(&plc, "P.empty"), "TRUE");
}

#[test]
fn an_unassigned_interface_called_faults_r080_at_the_call() {
    let src = program(SHAPES, "sh : IShape; a : REAL;", "a := sh.Area();");
    let mut plc = compile(&src);
    let f = plc.run_cycle().expect_err("faults");
    assert_eq!(f.code(), "R080");
    // `a := sh.Area();` is the body's line (34); the call starts at column 6.
    assert!(f.location.ends_with("test.st:34:6"), "{}", f.location);
    assert_eq!(f.pou, "P");
}

#[test]
fn an_interface_set_back_to_zero_holds_no_instance() {
    let src = program(
        SHAPES,
        "r : Rect; sh : IShape; held : BOOL;",
        "sh := r; sh := 0; held := sh <> 0;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.held"), "FALSE");
}

const MACHINES: &str = "
INTERFACE IStart
  METHOD Start
  END_METHOD
END_INTERFACE
INTERFACE IStop
  METHOD Stop : INT
    VAR_INPUT code : INT; END_VAR
  END_METHOD
END_INTERFACE
INTERFACE IMachine EXTENDS IStart, IStop
  METHOD Speed : INT
  END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IMachine
  VAR running : BOOL; last : INT; END_VAR
  METHOD Start
    running := TRUE;
  END_METHOD
  METHOD Stop : INT
    VAR_INPUT code : INT; END_VAR
    running := FALSE;
    last := code;
    Stop := code * 2;
  END_METHOD
  METHOD Speed : INT
    IF running THEN Speed := 100; ELSE Speed := 0; END_IF;
  END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Line
  VAR_INPUT m : IMachine; END_VAR
  VAR_OUTPUT speed : INT; END_VAR
  m.Start();
  speed := m.Speed();
END_FUNCTION_BLOCK
";

#[test]
fn an_interface_extends_others_and_is_passed_as_an_input() {
    let src = program(
        MACHINES,
        "mo : Motor; line : Line; st : IStop; s1, r : INT;",
        "line(m := mo); s1 := line.speed; st := mo; r := st.Stop(code := 21);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.s1"), "100");
    assert_eq!(lit(&plc, "P.r"), "42");
    assert_eq!(lit(&plc, "P.mo.last"), "21");
}

#[test]
fn this_and_unqualified_calls_reach_the_override_in_inherited_code() {
    let src = program(
        "
FUNCTION_BLOCK Base
  VAR_OUTPUT log : INT; END_VAR
  METHOD Part : INT
    Part := 1;
  END_METHOD
  METHOD Run
    log := log * 10 + Part() + THIS^.Part();
  END_METHOD
  log := log + 1000;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Child EXTENDS Base
  METHOD Part : INT
    Part := 4;
  END_METHOD
  SUPER^();
  THIS^.log := THIS^.log + 1;
END_FUNCTION_BLOCK",
        "b : Base; c : Child; x, y : INT;",
        "b.Run(); c.Run(); c(); x := b.log; y := c.log;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "2");
    assert_eq!(
        lit(&plc, "P.y"),
        "1009",
        "8 from Run, 1000 from SUPER^(), 1 from Child"
    );
}

#[test]
fn method_temporaries_and_outputs_are_reset_at_every_call() {
    let src = program(
        "
FUNCTION_BLOCK Counter
  VAR total : INT; END_VAR
  METHOD Add : INT
    VAR_INPUT n : INT; END_VAR
    VAR_OUTPUT before : INT; END_VAR
    VAR t : INT := 5; END_VAR
    VAR_TEMP u : INT; END_VAR
    before := total;
    t := t + n;
    u := u + 1;
    total := total + t + u;
    Add := total;
  END_METHOD
END_FUNCTION_BLOCK",
        "c : Counter; a, b, prev : INT;",
        "a := c.Add(n := 1); b := c.Add(n := 1, before => prev);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "7");
    assert_eq!(lit(&plc, "P.b"), "14");
    assert_eq!(lit(&plc, "P.prev"), "7");
}

#[test]
fn il_calls_a_method_with_cal() {
    let src = "
FUNCTION_BLOCK Acc
  VAR_OUTPUT sum : INT; END_VAR
  METHOD Add
    VAR_INPUT n : INT; END_VAR
    sum := sum + n;
  END_METHOD
END_FUNCTION_BLOCK
PROGRAM P
  VAR a : Acc; s : INT; END_VAR
  CAL a.Add(n := 5)
  CAL a.Add(n := 2)
  LD a.sum
  ST s
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.s"), "14");
}

#[test]
fn a_method_passes_its_own_instance_as_an_interface() {
    let src = program(
        MACHINES,
        "mo : Motor; line : Line; held : IMachine; s : INT;",
        "line(m := mo); held := mo; s := held.Speed();",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.s"), "100");
}

#[test]
fn the_child_layout_starts_with_the_parents_variables() {
    // An instance of the child is usable where the parent's code runs:
    // the parent's variables come first, at the same offsets.
    let src = program(
        SHAPES,
        "s : Square; sh : IShape; a : REAL;",
        "s.w := 5.0; s.h := 2.0; sh := s; a := sh.Area();",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "1010.0");
    assert_eq!(lit(&plc, "P.s.w"), "5.0");
}

/// Every misuse is refused with its code at its place.
#[rstest]
#[case::unknown_method(
    "FUNCTION_BLOCK F METHOD M END_METHOD END_FUNCTION_BLOCK",
    "f : F;",
    "f.N();",
    "E900",
    "7:3"
)]
#[case::abstract_instance(
    "FUNCTION_BLOCK ABSTRACT F METHOD ABSTRACT M END_METHOD END_FUNCTION_BLOCK",
    "f : F;",
    "",
    "E901",
    "5:5"
)]
#[case::extends_a_non_fb(
    "FUNCTION_BLOCK F EXTENDS INT END_FUNCTION_BLOCK",
    "",
    "",
    "E902",
    "2:26"
)]
#[case::extends_cycle(
    "FUNCTION_BLOCK F EXTENDS G END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F END_FUNCTION_BLOCK",
    "",
    "",
    "E903",
    "2:26"
)]
#[case::extends_final(
    "FUNCTION_BLOCK FINAL F END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F END_FUNCTION_BLOCK",
    "",
    "",
    "E904",
    "3:26"
)]
#[case::overrides_final(
    "FUNCTION_BLOCK F METHOD FINAL M END_METHOD END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F METHOD M END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E905",
    "3:35"
)]
#[case::override_signature(
    "FUNCTION_BLOCK F METHOD M : INT END_METHOD END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F METHOD M : REAL END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E906",
    "3:35"
)]
#[case::super_of_abstract(
    "FUNCTION_BLOCK ABSTRACT F METHOD ABSTRACT M END_METHOD END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F METHOD M SUPER^.M(); END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E907",
    "3:37"
)]
#[case::abstract_left(
    "FUNCTION_BLOCK ABSTRACT F METHOD ABSTRACT M END_METHOD END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F END_FUNCTION_BLOCK",
    "",
    "",
    "E908",
    "3:16"
)]
#[case::missing_implementation(
    "INTERFACE I METHOD M END_METHOD END_INTERFACE\nFUNCTION_BLOCK F IMPLEMENTS I END_FUNCTION_BLOCK",
    "",
    "",
    "E909",
    "3:16"
)]
#[case::implementation_signature(
    "INTERFACE I METHOD M : INT END_METHOD END_INTERFACE\nFUNCTION_BLOCK F IMPLEMENTS I METHOD M : BOOL END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E910",
    "3:38"
)]
#[case::implements_a_non_interface(
    "FUNCTION_BLOCK F IMPLEMENTS Nothing END_FUNCTION_BLOCK",
    "",
    "",
    "E911",
    "2:29"
)]
#[case::super_without_parent_method(
    "FUNCTION_BLOCK F END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F METHOD M SUPER^.M(); END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E912",
    "3:37"
)]
#[case::private_from_outside(
    "FUNCTION_BLOCK F METHOD PRIVATE M END_METHOD END_FUNCTION_BLOCK",
    "f : F;",
    "f.M();",
    "E913",
    "7:1"
)]
#[case::protected_from_outside(
    "FUNCTION_BLOCK F METHOD PROTECTED M END_METHOD END_FUNCTION_BLOCK",
    "f : F;",
    "f.M();",
    "E913",
    "7:1"
)]
#[case::assigning_a_non_implementing_instance(
    "INTERFACE I METHOD M END_METHOD END_INTERFACE\nFUNCTION_BLOCK F METHOD M END_METHOD END_FUNCTION_BLOCK",
    "f : F; i : I;",
    "i := f;",
    "E914",
    "8:6"
)]
#[case::global_block_in_a_method(
    "FUNCTION_BLOCK F METHOD M VAR_GLOBAL x : INT; END_VAR END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E915",
    "2:27"
)]
#[case::method_twice(
    "FUNCTION_BLOCK F METHOD M END_METHOD METHOD M END_METHOD END_FUNCTION_BLOCK",
    "",
    "",
    "E916",
    "2:45"
)]
#[case::prototype_with_statements(
    "INTERFACE I METHOD M : INT M := 1; END_METHOD END_INTERFACE",
    "",
    "",
    "E917",
    "2:20"
)]
#[case::this_outside_an_fb("", "x : INT;", "THIS^.x := 1;", "E918", "7:1")]
#[case::no_result(
    "FUNCTION_BLOCK F METHOD M END_METHOD END_FUNCTION_BLOCK",
    "f : F; x : INT;",
    "x := f.M();",
    "E919",
    "7:6"
)]
#[case::interface_compared_with_a_number(
    "INTERFACE I METHOD M END_METHOD END_INTERFACE",
    "i : I; b : BOOL;",
    "b := i = 1;",
    "E920",
    "7:10"
)]
fn misuse_is_a_coded_diagnostic(
    #[case] prelude: &str,
    #[case] decls: &str,
    #[case] body: &str,
    #[case] code: &str,
    #[case] at: &str,
) {
    let src = program(&format!("\n{prelude}"), decls, body);
    let codes = error_codes(&[("t.st", &src)]);
    assert!(
        codes.iter().any(|(c, l)| c == code && l.starts_with(at)),
        "expected {code} at {at}, got {codes:?}\n{src}"
    );
}

#[test]
fn a_method_calling_itself_is_recursion() {
    let src = program(
        "FUNCTION_BLOCK F METHOD M M(); END_METHOD END_FUNCTION_BLOCK",
        "f : F;",
        "f.M();",
    );
    let codes = error_codes(&[("t.st", &src)]);
    assert!(codes.iter().any(|(c, _)| c == "E409"), "{codes:?}");
}

#[test]
fn a_long_extends_chain_compiles_without_deep_recursion() {
    let mut src = String::from(
        "FUNCTION_BLOCK F0 VAR_OUTPUT v : INT; END_VAR METHOD M : INT M := 0; END_METHOD END_FUNCTION_BLOCK\n",
    );
    for i in 1..200 {
        src.push_str(&format!(
            "FUNCTION_BLOCK F{i} EXTENDS F{} END_FUNCTION_BLOCK\n",
            i - 1
        ));
    }
    let src = program(&src, "f : F199; x : INT;", "x := f.M() + 3;");
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "3");
}

#[test]
fn namespaces_stay_unsupported_by_name() {
    let codes = error_codes(&[("t.st", "NAMESPACE N\nEND_NAMESPACE\n")]);
    assert!(
        codes.iter().any(|(c, l)| c == "E110" && l == "1:1"),
        "{codes:?}"
    );
}

fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).expect("readable")
}

fn run_machine_tests(model: &str) -> plcrun::TestReport {
    let mut sources = plcrun::SourceMap::new();
    sources.add("oop_machine.st", model);
    sources.add(
        "oop_machine_test.st",
        read("tests/plc/oop_machine_test.st").as_str(),
    );
    plcrun::run_tests(&sources, &plcrun::TestOptions::default()).expect("compiles")
}

#[test]
fn the_machine_example_passes_its_st_tests_and_they_catch_a_broken_press() {
    let model = read("programs/oop_machine.st");
    let r = run_machine_tests(&model);
    assert_eq!(r.cases.len(), 4);
    assert!(r.all_passed(), "{}", r.to_text());
    // A press whose Reset forgets the parent's (SUPER^) part stays faulted.
    let broken = model.replace("    SUPER^.Reset();\n", "");
    assert_ne!(broken, model);
    let r = run_machine_tests(&broken);
    assert!(
        !r.all_passed(),
        "the tests must see the missing SUPER^ call"
    );
}
