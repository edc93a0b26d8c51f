//! PROPERTY (GET/SET accessors), CLASS and access specifiers on variables
//! (docs/language.md, docs/semantics.md "Properties, classes and variable
//! access"): each feature run and its values checked after cycles, each
//! misuse a coded diagnostic (E921-E930) at its place.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};
use rstest::rstest;

/// A motor whose `Speed` is stored in tenths (`rpm`), a read-only
/// `Running`, and a child whose `Speed` doubles its parent's.
const MOTORS: &str = "
INTERFACE IMotor
  PROPERTY Speed : REAL
  END_PROPERTY
  PROPERTY Running : BOOL
    GET END_GET
  END_PROPERTY
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IMotor
  VAR_OUTPUT sets : INT; END_VAR
  VAR rpm : REAL; END_VAR
  PROPERTY Speed : REAL
    GET
      Speed := rpm / 10.0;
    END_GET
    SET
      rpm := Speed * 10.0;
      sets := sets + 1;
    END_SET
  END_PROPERTY
  PROPERTY Running : BOOL
    GET Running := rpm > 0.0; END_GET
  END_PROPERTY
END_FUNCTION_BLOCK

FUNCTION_BLOCK Fast EXTENDS Motor
  PROPERTY Speed : REAL
    GET Speed := SUPER^.Speed * 2.0; END_GET
    SET SUPER^.Speed := Speed + 1.0; END_SET
  END_PROPERTY
END_FUNCTION_BLOCK
";

#[test]
fn reading_calls_get_and_writing_calls_set() {
    let src = program(
        MOTORS,
        "m : Motor; a, r : REAL; run0, run1 : BOOL; n : INT;",
        "run0 := m.Running; m.Speed := 3.0; a := m.Speed + 0.5; r := m.rpm; run1 := m.Running; n := m.sets;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.run0"), "FALSE");
    assert_eq!(lit(&plc, "P.a"), "3.5");
    assert_eq!(lit(&plc, "P.r"), "30.0", "SET stored the value in tenths");
    assert_eq!(lit(&plc, "P.run1"), "TRUE");
    assert_eq!(lit(&plc, "P.n"), "1");
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.n"), "3", "one SET per write, per cycle");
}

#[test]
fn an_override_reaches_its_parent_through_super() {
    let src = program(
        MOTORS,
        "f : Fast; a, r : REAL;",
        "f.Speed := 2.0; a := f.Speed; r := f.rpm;",
    );
    let plc = plc::run_once(&src);
    // SET: parent gets 3.0 -> rpm 30; GET: parent's 3.0 doubled.
    assert_eq!(lit(&plc, "P.r"), "30.0");
    assert_eq!(lit(&plc, "P.a"), "6.0");
}

#[test]
fn a_property_through_an_interface_dispatches_on_the_instance() {
    let src = program(
        MOTORS,
        "m : Motor; f : Fast; i : IMotor; a, b : REAL; ra, rb : BOOL;",
        "i := m; i.Speed := 4.0; a := i.Speed; ra := i.Running;\n\
         i := f; rb := i.Running; i.Speed := 4.0; b := i.Speed;",
    );
    let plc = plc::run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "4.0");
    assert_eq!(lit(&plc, "P.ra"), "TRUE");
    assert_eq!(lit(&plc, "P.rb"), "FALSE", "f not yet set when read");
    assert_eq!(lit(&plc, "P.b"), "10.0", "Fast's accessors: (4 + 1) * 2");
    assert_eq!(lit(&plc, "P.m.rpm"), "40.0");
}

/// A message whose entry is a structure and whose arguments are another
/// object behind an interface, as Tc3_EventLogger's `FB_TcMessage`
/// (`msg.ipArguments.Clear()`, `itf.stEventEntry`).
const MESSAGES: &str = "
TYPE Entry : STRUCT id : INT; level : INT; END_STRUCT END_TYPE
INTERFACE IArgs
  METHOD Add : IArgs
    VAR_INPUT n : INT; END_VAR
  END_METHOD
  PROPERTY Sum : INT
    GET END_GET
  END_PROPERTY
END_INTERFACE
INTERFACE IMessage
  PROPERTY Info : Entry
    GET END_GET
  END_PROPERTY
  PROPERTY Args : IArgs
    GET END_GET
  END_PROPERTY
END_INTERFACE
FUNCTION_BLOCK ArgList IMPLEMENTS IArgs
  VAR total : INT; END_VAR
  METHOD Add : IArgs
    VAR_INPUT n : INT; END_VAR
    total := total + n;
    Add := THIS^;
  END_METHOD
  PROPERTY Sum : INT
    GET Sum := total; END_GET
  END_PROPERTY
END_FUNCTION_BLOCK
FUNCTION_BLOCK Message IMPLEMENTS IMessage
  VAR e : Entry := (id := 7, level := 2); list : ArgList; END_VAR
  PROPERTY Info : Entry
    GET Info := e; END_GET
  END_PROPERTY
  PROPERTY Args : IArgs
    GET Args := list; END_GET
  END_PROPERTY
END_FUNCTION_BLOCK
FUNCTION Level : INT
  VAR_INPUT x : Entry; END_VAR
  Level := x.level;
END_FUNCTION
";

#[test]
fn a_property_of_a_structure_or_an_interface_is_used_where_a_variable_is() {
    let src = program(
        MESSAGES,
        "m : Message; r : REFERENCE TO Message; i : IMessage; copy : Entry; id, lv, viaRef, sum : INT;",
        "i := m; r REF= m;\n\
         copy := i.Info; id := i.Info.id; lv := Level(i.Info);\n\
         m.Args.Add(1);\n\
         r.Args.Add(2).Add(3);\n\
         viaRef := r.Args.Add(4).Sum;\n\
         sum := i.Args.Sum;",
    );
    let plc = plc::run_once(&src);
    assert_eq!(lit(&plc, "P.copy.level"), "2");
    assert_eq!(lit(&plc, "P.id"), "7");
    assert_eq!(lit(&plc, "P.lv"), "2");
    assert_eq!(
        lit(&plc, "P.viaRef"),
        "10",
        "1 + 2 + 3 + 4, chained through the interface"
    );
    assert_eq!(lit(&plc, "P.sum"), "10");
}

#[test]
fn inside_its_fb_a_property_is_used_by_name_and_through_this() {
    let src = program(
        "FUNCTION_BLOCK Tank
           VAR_OUTPUT shown : INT; twice : INT; END_VAR
           VAR level : INT; END_VAR
           PROPERTY PRIVATE Level10 : INT
             GET Level10 := level * 10; END_GET
             SET level := Level10 / 10; END_SET
           END_PROPERTY
           METHOD Twice : INT
             Twice := THIS^.Level10 * 2;
           END_METHOD
           Level10 := Level10 + 10;
           shown := Level10;
           twice := Twice();
         END_FUNCTION_BLOCK",
        "t : Tank; s, w : INT;",
        "t(); s := t.shown; w := t.twice;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.s"), "30");
    assert_eq!(lit(&plc, "P.w"), "60");
}

#[test]
fn accessors_have_variables_of_their_own_and_may_return_strings() {
    let src = program(
        "FUNCTION_BLOCK Tag
           VAR n : INT; END_VAR
           PROPERTY Name : STRING[20]
             GET
               VAR k : INT; END_VAR
               k := n + 1;
               Name := CONCAT('tag', INT_TO_STRING(k));
             END_GET
             SET
               VAR len : INT; END_VAR
               len := LEN(Name);
               n := n + len;
             END_SET
           END_PROPERTY
         END_FUNCTION_BLOCK",
        "t : Tag; a, b : STRING[20];",
        "a := t.Name; t.Name := 'abcd'; b := t.Name;",
    );
    let plc = plc::run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "'tag1'");
    assert_eq!(lit(&plc, "P.b"), "'tag5'");
}

#[test]
fn il_loads_and_stores_properties() {
    let src = format!(
        "{MOTORS}\nPROGRAM P\nVAR\n  m : Motor; a : REAL; r : REAL;\nEND_VAR\n  LD 7\n  ST m.Speed\n  LD m.Speed\n  ADD 1.0\n  ST a\n  LD m.rpm\n  ST r\nEND_PROGRAM\n"
    );
    let plc = plc::run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "8.0");
    assert_eq!(lit(&plc, "P.r"), "70.0");
}

#[test]
fn abstract_properties_are_implemented_by_the_child() {
    let src = program(
        "FUNCTION_BLOCK ABSTRACT Sensor
           PROPERTY ABSTRACT Value : INT
             GET END_GET
           END_PROPERTY
           METHOD Doubled : INT
             Doubled := Value * 2;
           END_METHOD
         END_FUNCTION_BLOCK
         FUNCTION_BLOCK Fixed EXTENDS Sensor
           PROPERTY Value : INT
             GET Value := 21; END_GET
           END_PROPERTY
         END_FUNCTION_BLOCK",
        "s : Fixed; d : INT;",
        "d := s.Doubled();",
    );
    assert_eq!(lit(&plc::run_once(&src), "P.d"), "42");
}

#[test]
fn get_and_set_stay_names_outside_properties() {
    let src = program(
        "FUNCTION_BLOCK Latch
           VAR_INPUT set, reset : BOOL; END_VAR
           VAR_OUTPUT q : BOOL; END_VAR
           q := set OR (q AND NOT reset);
         END_FUNCTION_BLOCK",
        "l : Latch; get : INT; set : BOOL; q : BOOL;",
        "get := get + 1; set := get = 1; l(set := set); q := l.q;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.get"), "2");
    assert_eq!(lit(&plc, "P.q"), "TRUE");
}

/// A counter class, a child class, and an interface they implement.
const COUNTERS: &str = "
INTERFACE ICount
  METHOD Bump : INT
  END_METHOD
  PROPERTY Count : INT
    GET END_GET
  END_PROPERTY
END_INTERFACE

CLASS Counter IMPLEMENTS ICount
  VAR n : INT; END_VAR
  METHOD Bump : INT
    n := n + 1;
    Bump := n;
  END_METHOD
  PROPERTY Count : INT
    GET Count := n; END_GET
  END_PROPERTY
END_CLASS

CLASS ByTen EXTENDS Counter
  METHOD Bump : INT
    Bump := SUPER^.Bump();
    n := n + 9;
  END_METHOD
END_CLASS
";

#[test]
fn classes_have_methods_properties_inheritance_and_interfaces() {
    let src = program(
        COUNTERS,
        "c : Counter; t : ByTen; i : ICount; a, b, x, y : INT;",
        "c.Bump(); a := c.Count;\n\
         i := t; i.Bump(); i.Bump(); b := i.Count;\n\
         i := c; x := i.Bump(); y := t.Bump();",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "1");
    assert_eq!(lit(&plc, "P.b"), "20");
    assert_eq!(lit(&plc, "P.x"), "2");
    assert_eq!(lit(&plc, "P.y"), "21");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "3", "instances keep their variables");
}

#[test]
fn public_and_internal_variables_are_read_and_written_without_warning() {
    let src = program(
        "FUNCTION_BLOCK Box
           VAR PUBLIC size : INT; END_VAR
           VAR INTERNAL tag : INT := 7; END_VAR
           VAR PROTECTED kept : INT := 1; END_VAR
           VAR_OUTPUT area : INT; END_VAR
           area := size * size + kept;
         END_FUNCTION_BLOCK
         FUNCTION_BLOCK BigBox EXTENDS Box
           VAR_OUTPUT k : INT; END_VAR
           kept := 100;
           SUPER^();
           k := kept;
         END_FUNCTION_BLOCK",
        "b : Box; g : BigBox; a, t, s, ga, gk : INT;",
        "b.size := 3; b(); a := b.area; t := b.tag; b.tag := 8; s := b.size;\n\
         g.size := 2; g(); ga := g.area; gk := g.k;",
    );
    let plc = plc::run_once(&src);
    assert_eq!(lit(&plc, "P.a"), "10");
    assert_eq!(lit(&plc, "P.t"), "7");
    assert_eq!(lit(&plc, "P.b.tag"), "8");
    assert_eq!(lit(&plc, "P.s"), "3");
    assert_eq!(
        lit(&plc, "P.ga"),
        "104",
        "the child writes the protected variable"
    );
    assert_eq!(lit(&plc, "P.gk"), "100");
    let w320 = plc.warnings().iter().filter(|d| d.code == "W320").count();
    assert_eq!(
        w320, 0,
        "PUBLIC and INTERNAL are part of the FB's interface"
    );
}

#[test]
fn a_private_variable_is_used_by_its_own_code_on_any_instance() {
    let src = program(
        "FUNCTION_BLOCK Acc
           VAR PRIVATE total : INT; END_VAR
           METHOD Add
             VAR_INPUT v : INT; END_VAR
             total := total + v;
           END_METHOD
           METHOD Sum : INT
             Sum := total;
           END_METHOD
         END_FUNCTION_BLOCK",
        "a : Acc; s : INT;",
        "a.Add(v := 5); a.Add(v := 6); s := a.Sum();",
    );
    assert_eq!(lit(&plc::run_once(&src), "P.s"), "11");
}

#[rstest]
#[case::write_without_set(
    "FUNCTION_BLOCK F PROPERTY P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "f : F;",
    "f.P := 2;",
    "E922",
    "7:3"
)]
#[case::read_without_get(
    "FUNCTION_BLOCK F VAR n : INT; END_VAR PROPERTY P : INT SET n := P; END_SET END_PROPERTY END_FUNCTION_BLOCK",
    "f : F; x : INT;",
    "x := f.P;",
    "E921",
    "7:8"
)]
#[case::il_store_without_set(
    "FUNCTION_BLOCK F PROPERTY P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "f : F;",
    "LD 1\nST f.P",
    "E922",
    "8:6"
)]
#[case::write_through_an_interface_without_set(
    "INTERFACE I PROPERTY P : INT GET END_GET END_PROPERTY END_INTERFACE",
    "i : I;",
    "i.P := 1;",
    "E922",
    "7:3"
)]
#[case::two_gets(
    "FUNCTION_BLOCK F PROPERTY P : INT GET P := 1; END_GET GET P := 2; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E923",
    "2:55"
)]
#[case::no_accessor(
    "FUNCTION_BLOCK F PROPERTY P : INT END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E923",
    "2:27"
)]
#[case::named_like_a_variable(
    "FUNCTION_BLOCK F VAR p : INT; END_VAR PROPERTY P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E924",
    "2:48"
)]
#[case::named_like_a_method(
    "FUNCTION_BLOCK F METHOD P : INT END_METHOD PROPERTY P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E924",
    "2:53"
)]
#[case::private_property_from_outside(
    "FUNCTION_BLOCK F PROPERTY PRIVATE P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "f : F; x : INT;",
    "x := f.P;",
    "E913",
    "7:8"
)]
#[case::private_set_from_outside(
    "FUNCTION_BLOCK F VAR n : INT; END_VAR PROPERTY P : INT GET P := n; END_GET SET PRIVATE n := P; END_SET END_PROPERTY END_FUNCTION_BLOCK",
    "f : F;",
    "f.P := 1;",
    "E913",
    "7:3"
)]
#[case::final_property_overridden(
    "FUNCTION_BLOCK F PROPERTY FINAL P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F PROPERTY P : INT GET P := 2; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E905",
    "3:37"
)]
#[case::override_of_another_type(
    "FUNCTION_BLOCK F PROPERTY P : INT GET P := 1; END_GET END_PROPERTY END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F PROPERTY P : REAL GET P := 2.0; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E906",
    "3:37"
)]
#[case::abstract_property_not_implemented(
    "FUNCTION_BLOCK ABSTRACT F PROPERTY ABSTRACT P : INT GET END_GET END_PROPERTY END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F END_FUNCTION_BLOCK",
    "",
    "",
    "E908",
    "3:16"
)]
#[case::interface_property_missing(
    "INTERFACE I PROPERTY P : INT GET END_GET END_PROPERTY END_INTERFACE\nFUNCTION_BLOCK F IMPLEMENTS I END_FUNCTION_BLOCK",
    "",
    "",
    "E909",
    "3:16"
)]
#[case::super_without_parent_property(
    "FUNCTION_BLOCK F END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F PROPERTY P : INT GET P := SUPER^.P; END_GET END_PROPERTY END_FUNCTION_BLOCK",
    "",
    "",
    "E912",
    "3:61"
)]
#[case::class_instance_called(
    "CLASS C VAR n : INT; END_VAR END_CLASS",
    "c : C;",
    "c();",
    "E925",
    "7:1"
)]
#[case::class_instance_called_in_il(
    "CLASS C VAR n : INT; END_VAR END_CLASS",
    "c : C;",
    "CAL c",
    "E925",
    "7:1"
)]
#[case::class_extending_an_fb(
    "FUNCTION_BLOCK F END_FUNCTION_BLOCK\nCLASS C EXTENDS F END_CLASS",
    "",
    "",
    "E926",
    "3:17"
)]
#[case::class_with_inputs("CLASS C VAR_INPUT x : INT; END_VAR END_CLASS", "", "", "E927", "2:9")]
#[case::access_on_an_input_section(
    "FUNCTION_BLOCK F VAR_INPUT PRIVATE x : INT; END_VAR END_FUNCTION_BLOCK",
    "",
    "",
    "E928",
    "2:18"
)]
#[case::access_in_a_program("", "x : INT;", "", "E928", "")]
#[case::property_outside_an_fb(
    "PROPERTY P : INT GET P := 1; END_GET END_PROPERTY",
    "",
    "",
    "E110",
    "2:1"
)]
#[case::private_variable_from_outside(
    "FUNCTION_BLOCK F VAR PRIVATE n : INT; END_VAR END_FUNCTION_BLOCK",
    "f : F; x : INT;",
    "x := f.n;",
    "E929",
    "7:8"
)]
#[case::private_variable_in_a_child(
    "FUNCTION_BLOCK F VAR PRIVATE n : INT; END_VAR END_FUNCTION_BLOCK\nFUNCTION_BLOCK G EXTENDS F n := 1; END_FUNCTION_BLOCK",
    "",
    "",
    "E929",
    "3:28"
)]
#[case::protected_variable_from_outside(
    "FUNCTION_BLOCK F VAR PROTECTED n : INT; END_VAR END_FUNCTION_BLOCK",
    "f : F;",
    "f.n := 1;",
    "E930",
    "7:3"
)]
fn misuse_is_a_coded_diagnostic(
    #[case] prelude: &str,
    #[case] decls: &str,
    #[case] body: &str,
    #[case] code: &str,
    #[case] at: &str,
) {
    let mut src = program(&format!("\n{prelude}"), decls, body);
    if prelude.is_empty() && body.is_empty() {
        // The program itself declares a section with an access specifier.
        src = src.replacen("VAR\n", "VAR PRIVATE\n", 1);
    }
    let codes = error_codes(&[("t.st", &src)]);
    assert!(
        codes.iter().any(|(c, l)| c == code && l.starts_with(at)),
        "expected {code} at {at}, got {codes:?}\n{src}"
    );
}
