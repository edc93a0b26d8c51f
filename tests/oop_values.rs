//! Edition-3 object orientation, second part (docs/semantics.md "Object
//! orientation: interface values, assignment attempt, method parameters"):
//! interface values in arrays, FUNCTION and METHOD results and inputs, the
//! upcast, `?=`, VAR_IN_OUT/VAR_EXTERNAL and structured results in
//! methods, methods named like keywords, an IL body next to methods, one
//! diagnostic per inherited error — each run with checked values, each
//! misuse a coded diagnostic at its place.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};
use rstest::rstest;

const DRIVES: &str = "
INTERFACE I_Drive
  METHOD Speed : INT
  END_METHOD
END_INTERFACE
INTERFACE I_Fast EXTENDS I_Drive
  METHOD Boost : INT
  END_METHOD
END_INTERFACE
INTERFACE I_Other
  METHOD Speed : INT
  END_METHOD
END_INTERFACE
FUNCTION_BLOCK Slow IMPLEMENTS I_Drive
  VAR_INPUT k : INT; END_VAR
  METHOD Speed : INT
    Speed := k;
  END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK Fast IMPLEMENTS I_Fast
  METHOD Speed : INT
    Speed := 100;
  END_METHOD
  METHOD Boost : INT
    Boost := 200;
  END_METHOD
END_FUNCTION_BLOCK
FUNCTION Pick : I_Drive
  VAR_INPUT x, y : I_Drive; first : BOOL; END_VAR
  IF first THEN Pick := x; ELSE Pick := y; END_IF;
END_FUNCTION
FUNCTION_BLOCK Holder
  VAR d : I_Drive; END_VAR
  METHOD Get : I_Drive
    Get := d;
  END_METHOD
  METHOD Put
    VAR_INPUT x : I_Drive; END_VAR
    d := x;
  END_METHOD
END_FUNCTION_BLOCK
";

#[test]
fn an_array_of_interfaces_is_assigned_and_called_with_dispatch() {
    let src = program(
        DRIVES,
        "s1, s2 : Slow; f : Fast; a : ARRAY[1..3] OF I_Drive; i : INT; j : INT := 2; total, v : INT; same, held : BOOL;",
        "s1.k := 1; s2.k := 2;
         a[1] := s1; a[j] := s2; a[j + 1] := f;
         total := 0;
         FOR i := 1 TO 3 DO total := total + a[i].Speed(); END_FOR;
         v := a[j].Speed();
         same := a[1] = a[2];
         held := a[3] <> 0;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.total"), "103");
    assert_eq!(lit(&plc, "P.v"), "2");
    assert_eq!(lit(&plc, "P.same"), "FALSE");
    assert_eq!(lit(&plc, "P.held"), "TRUE");
}

#[test]
fn an_unassigned_array_element_called_faults_r080() {
    let src = program(
        DRIVES,
        "a : ARRAY[1..3] OF I_Drive; i : INT := 2; v : INT;",
        "v := a[i].Speed();",
    );
    let mut plc = compile(&src);
    let f = plc.run_cycle().expect_err("faults");
    assert_eq!(f.code(), "R080");
}

#[test]
fn interfaces_are_function_and_method_inputs_and_results() {
    let src = program(
        DRIVES,
        "s1, s2 : Slow; f : Fast; h : Holder; d, e : I_Drive; v1, v2, v3, v4 : INT; none : BOOL;",
        "s1.k := 1; s2.k := 2;
         d := Pick(x := s1, y := s2, first := FALSE);
         v1 := d.Speed();
         v2 := Pick(x := s1, y := f, first := FALSE).Speed();
         h.Put(x := s1);
         e := h.Get();
         v3 := e.Speed();
         h.Put(x := 0);
         none := h.Get() = 0;
         h.Put(x := f);
         v4 := h.Get().Speed();",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.v1"), "2");
    assert_eq!(lit(&plc, "P.v2"), "100");
    assert_eq!(lit(&plc, "P.v3"), "1");
    assert_eq!(lit(&plc, "P.none"), "TRUE");
    assert_eq!(lit(&plc, "P.v4"), "100");
}

#[test]
fn an_interface_receives_a_value_of_an_interface_extending_it() {
    let src = program(
        DRIVES,
        "f : Fast; fi : I_Fast; d : I_Drive; v : INT; same : BOOL;",
        "fi := f; d := fi; v := d.Speed(); same := d = fi;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.v"), "100");
    assert_eq!(lit(&plc, "P.same"), "TRUE");
}

#[test]
fn an_assignment_attempt_keeps_an_implementing_instance_and_else_gives_zero() {
    let src = program(
        DRIVES,
        "s : Slow; f : Fast; d, d2 : I_Drive; fi, fi2, fi3 : I_Fast; o : I_Other;
         v1, v2 : INT; ok1, ok2, ok3, ok4 : BOOL;",
        "s.k := 7;
         d := f;
         fi ?= d;
         ok1 := fi <> 0;
         v1 := fi.Boost();
         d := s;
         fi2 := f;
         fi2 ?= d;
         ok2 := fi2 = 0;
         fi3 ?= f;
         d2 ?= fi3;
         ok3 := d2 = fi3;
         v2 := d2.Speed();
         o ?= d;
         ok4 := o = 0;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.ok1"), "TRUE");
    assert_eq!(lit(&plc, "P.v1"), "200");
    assert_eq!(lit(&plc, "P.ok2"), "TRUE", "a Slow is no I_Fast: 0");
    assert_eq!(lit(&plc, "P.ok3"), "TRUE");
    assert_eq!(lit(&plc, "P.v2"), "100");
    assert_eq!(
        lit(&plc, "P.ok4"),
        "TRUE",
        "Slow does not implement I_Other"
    );
}

#[test]
fn an_assignment_attempt_from_this_and_from_an_empty_interface() {
    let src = "
INTERFACE I_A METHOD M : INT END_METHOD END_INTERFACE
INTERFACE I_B METHOD N : INT END_METHOD END_INTERFACE
FUNCTION_BLOCK Both IMPLEMENTS I_A, I_B
  VAR_OUTPUT b : I_B; END_VAR
  METHOD M : INT M := 1; END_METHOD
  METHOD N : INT N := 2; END_METHOD
  b ?= THIS^;
END_FUNCTION_BLOCK
PROGRAM P
VAR x : Both; a : I_A; b : I_B; n : INT; empty : BOOL; END_VAR
x();
n := x.b.N();
b ?= a;
empty := b = 0;
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.n"), "2");
    assert_eq!(lit(&plc, "P.empty"), "TRUE");
}

const ACC: &str = "
VAR_GLOBAL gCount : INT := 100; gName : STRING := 'x'; END_VAR
INTERFACE I_Acc
  METHOD AddTo
    VAR_IN_OUT acc : INT; END_VAR
    VAR_INPUT k : INT; END_VAR
  END_METHOD
END_INTERFACE
FUNCTION_BLOCK Acc IMPLEMENTS I_Acc
  VAR_INPUT base : INT; END_VAR
  VAR_OUTPUT n : INT; END_VAR
  METHOD AddTo
    VAR_IN_OUT acc : INT; END_VAR
    VAR_INPUT k : INT; END_VAR
    VAR_EXTERNAL gCount : INT; END_VAR
    acc := acc + k + base;
    gCount := gCount + 1;
  END_METHOD
  METHOD Swap
    VAR_IN_OUT a, b : STRING; END_VAR
    VAR t : STRING; END_VAR
    VAR_EXTERNAL gCount : INT; gName : STRING; END_VAR
    t := a; a := b; b := t;
    gCount := gCount + 10;
    gName := b;
  END_METHOD
  n := n + 1;
END_FUNCTION_BLOCK
";

#[test]
fn methods_have_in_outs_and_externals_also_through_interfaces() {
    let src = program(
        ACC,
        "a : Acc; i : I_Acc; x, y : INT; s1 : STRING := 'one'; s2 : STRING := 'two'; g, calls : INT; gn : STRING;",
        "a.base := 1;
         a();
         a.AddTo(acc := x, k := 5);
         i := a;
         i.AddTo(acc := y, k := 10);
         i.AddTo(acc := x, k := 100);
         a.Swap(a := s1, b := s2);
         g := gCount; gn := gName; calls := a.n;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "107");
    assert_eq!(lit(&plc, "P.y"), "11");
    assert_eq!(lit(&plc, "P.s1"), "'two'");
    assert_eq!(lit(&plc, "P.s2"), "'one'");
    assert_eq!(lit(&plc, "P.g"), "113");
    assert_eq!(lit(&plc, "P.gn"), "'one'");
    assert_eq!(
        lit(&plc, "P.calls"),
        "1",
        "calling the FB does not ask for its methods' in-outs"
    );
}

#[test]
fn methods_return_structures_arrays_and_strings_also_through_interfaces() {
    let src = program(
        "
TYPE Pt : STRUCT x, y : INT; END_STRUCT; END_TYPE
INTERFACE I_Geo
  METHOD Origin : Pt
  END_METHOD
  METHOD Shift : Pt
    VAR_INPUT p : Pt; END_VAR
  END_METHOD
END_INTERFACE
FUNCTION_BLOCK G IMPLEMENTS I_Geo
  VAR_INPUT dx : INT; END_VAR
  METHOD Origin : Pt
    Origin.x := dx; Origin.y := 2 * dx;
  END_METHOD
  METHOD Shift : Pt
    VAR_INPUT p : Pt; END_VAR
    Shift.x := p.x + dx; Shift.y := p.y + dx;
  END_METHOD
  METHOD Row : ARRAY[1..3] OF INT
    Row[1] := dx; Row[2] := dx + 1; Row[3] := dx + 2;
  END_METHOD
  METHOD Name : STRING
    Name := CONCAT('g', INT_TO_STRING(dx));
  END_METHOD
END_FUNCTION_BLOCK",
        "g, h : G; i : I_Geo; q, r : Pt; arr : ARRAY[1..3] OF INT; ox, oy, a3, sx, sy, iy, two : INT; n : STRING;",
        "g.dx := 5; h.dx := 7;
         q := g.Origin(); ox := q.x; oy := g.Origin().y;
         arr := g.Row(); a3 := arr[3];
         n := g.Name();
         i := g;
         r := i.Shift(p := q); sx := r.x; sy := r.y;
         iy := i.Origin().y;
         two := g.Origin().x + h.Origin().x;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.ox"), "5");
    assert_eq!(lit(&plc, "P.oy"), "10");
    assert_eq!(lit(&plc, "P.a3"), "7");
    assert_eq!(lit(&plc, "P.n"), "'g5'");
    assert_eq!(lit(&plc, "P.sx"), "10");
    assert_eq!(lit(&plc, "P.sy"), "15");
    assert_eq!(lit(&plc, "P.iy"), "10");
    assert_eq!(lit(&plc, "P.two"), "12");
}

#[rstest]
#[case::step("Step")]
#[case::transition("Transition")]
#[case::task("Task")]
#[case::with("With")]
#[case::on("On")]
#[case::resource("Resource")]
fn a_method_is_named_like_a_keyword_codesys_does_not_reserve(#[case] name: &str) {
    let src = format!(
        "
FUNCTION_BLOCK M
  VAR_OUTPUT n : INT; END_VAR
  METHOD PUBLIC {name} : INT
    VAR_INPUT k : INT; END_VAR
    n := n + k; {name} := n;
  END_METHOD
  METHOD Twice
    {name}(k := 1); THIS^.{name}(k := 1);
  END_METHOD
END_FUNCTION_BLOCK
PROGRAM P
VAR m : M; x, y : INT; END_VAR
m.{name}(k := 1); x := m.{name}(k := 2); m.Twice(); y := m.n;
END_PROGRAM
"
    );
    let mut plc = compile(&src);
    let w: Vec<String> = plc.warnings().iter().map(|d| d.code.to_string()).collect();
    assert_eq!(w, ["W390"], "one warning, at the declaration");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "3");
    assert_eq!(lit(&plc, "P.y"), "5");
}

#[test]
fn an_il_body_runs_next_to_st_and_il_methods() {
    let src = "
FUNCTION_BLOCK M
  VAR_OUTPUT n : INT; END_VAR
  METHOD Inc
    n := n + 1;
  END_METHOD
  METHOD Dbl
    LD n
    MUL 2
    ST n
  END_METHOD
  LD n
  ADD 10
  ST n
END_FUNCTION_BLOCK
PROGRAM P
VAR m : M; x : INT; END_VAR
m(); m.Inc(); m.Dbl(); x := m.n;
END_PROGRAM
";
    let mut plc = compile(src);
    run(&mut plc, 2);
    // (0 + 10 + 1) * 2 = 22, then (22 + 10 + 1) * 2 = 66.
    assert_eq!(lit(&plc, "P.x"), "66");
}

#[test]
fn an_error_in_inherited_code_is_reported_once() {
    let src = "
FUNCTION_BLOCK Base
  VAR_OUTPUT n : INT; END_VAR
  METHOD Bump
    n := n + TRUE;
  END_METHOD
  n := 1.5;
END_FUNCTION_BLOCK
FUNCTION_BLOCK C1 EXTENDS Base END_FUNCTION_BLOCK
FUNCTION_BLOCK C2 EXTENDS Base END_FUNCTION_BLOCK
FUNCTION_BLOCK C3 EXTENDS C2 END_FUNCTION_BLOCK
PROGRAM P
VAR a : C1; b : C2; c : C3; d : Base; END_VAR
a(); b(); c(); d();
END_PROGRAM
";
    let codes = error_codes(&[("t.st", src)]);
    assert_eq!(
        codes,
        [
            ("E306".to_string(), "5:10".to_string()),
            ("E304".to_string(), "7:8".to_string())
        ],
        "each error once, at its place in Base"
    );
}

#[rstest]
#[case::downcast_refused("d : I_Drive; fi : I_Fast;", "fi := d;", "E940", "47:7")]
#[case::unrelated_interfaces_refused("d : I_Drive; o : I_Other;", "o := d;", "E940", "47:6")]
#[case::attempt_into_a_non_interface("x : INT; d : I_Drive;", "x ?= d;", "E941", "47:1")]
#[case::attempt_from_a_number("d : I_Drive; x : INT;", "d ?= x;", "E942", "47:6")]
#[case::function_input_not_implementing(
    "o : I_Other; v : I_Drive; f : Fast;",
    "v := Pick(x := f, y := o, first := TRUE);",
    "E940",
    "47:24"
)]
#[case::in_out_unconnected("a : Acc2;", "a.AddTo(k := 1);", "E404", "47:1")]
#[case::in_out_of_another_type(
    "a : Acc2; r : REAL;",
    "a.AddTo(acc := r, k := 1);",
    "E301",
    "47:16"
)]
fn misuse_is_a_coded_diagnostic(
    #[case] decls: &str,
    #[case] body: &str,
    #[case] code: &str,
    #[case] at: &str,
) {
    let prelude = format!(
        "{DRIVES}FUNCTION_BLOCK Acc2 METHOD AddTo VAR_IN_OUT acc : INT; END_VAR VAR_INPUT k : INT; END_VAR acc := acc + k; END_METHOD END_FUNCTION_BLOCK"
    );
    let src = program(&prelude, decls, body);
    let codes = error_codes(&[("t.st", &src)]);
    assert!(
        codes.iter().any(|(c, l)| c == code && l.starts_with(at)),
        "expected {code} at {at}, got {codes:?}\n{src}"
    );
}
