//! CODESYS V3 / TwinCAT 3 spellings that IEC 61131-3 does not have
//! (issue #25, the dialect): each case runs through the library and
//! checks values worked out by hand beside it.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};

/// Compiles `decls`/`body` as a program after `prelude`, runs one cycle
/// and checks `(variable, literal)`.
fn check(prelude: &str, decls: &str, body: &str, expect: &[(&str, &str)]) {
    let mut plc = compile(&program(prelude, decls, body));
    run(&mut plc, 1);
    for (name, value) in expect {
        assert_eq!(lit(&plc, name), *value, "{name}\n{body}");
    }
}

/// A function that counts its calls in `n` and returns `r`.
const BUMP: &str = "FUNCTION Bump : BOOL
VAR_INPUT r : BOOL; END_VAR
VAR_IN_OUT n : INT; END_VAR
n := n + 1;
Bump := r;
END_FUNCTION";

#[test]
fn and_then_skips_the_right_operand_when_the_left_is_false() {
    // d = 0: `d <> 0 AND_THEN 10 / d > 1` never divides; i = 11 is
    // past the array: the index is never evaluated.
    check(
        "",
        "d : INT := 0; i : INT := 11; a : ARRAY[1..10] OF INT;
         r1, r2 : BOOL := TRUE; r3 : BOOL;",
        "r1 := d <> 0 AND_THEN 10 / d > 1;
         r2 := i <= 10 AND_THEN a[i] = 0;
         IF i >= 1 AND_THEN i <= 10 AND_THEN a[i] = 0 THEN r3 := FALSE; ELSE r3 := TRUE; END_IF;",
        &[("r1", "FALSE"), ("r2", "FALSE"), ("r3", "TRUE")],
    );
}

#[test]
fn and_then_and_or_else_give_the_truth_tables_and_call_the_right_operand_only_when_needed() {
    // Each line's count: AND_THEN calls Bump only after a TRUE left,
    // OR_ELSE only after a FALSE left; AND and OR always call it.
    check(
        BUMP,
        "t : BOOL := TRUE; f : BOOL;
         n1, n2, n3, n4, n5, n6 : INT;
         a1, a2, a3, a4, o1, o2, o3, o4, p, q : BOOL;",
        "a1 := t AND_THEN Bump(TRUE, n1);
         a2 := t AND_THEN Bump(FALSE, n1);
         a3 := f AND_THEN Bump(TRUE, n2);
         a4 := f AND_THEN Bump(FALSE, n2);
         o1 := t OR_ELSE Bump(TRUE, n3);
         o2 := t OR_ELSE Bump(FALSE, n3);
         o3 := f OR_ELSE Bump(TRUE, n4);
         o4 := f OR_ELSE Bump(FALSE, n4);
         p := f AND Bump(TRUE, n5);
         q := t OR Bump(TRUE, n6);",
        &[
            ("a1", "TRUE"),
            ("a2", "FALSE"),
            ("a3", "FALSE"),
            ("a4", "FALSE"),
            ("n1", "2"),
            ("n2", "0"),
            ("o1", "TRUE"),
            ("o2", "TRUE"),
            ("o3", "TRUE"),
            ("o4", "FALSE"),
            ("n3", "0"),
            ("n4", "2"),
            ("p", "FALSE"),
            ("n5", "1"),
            ("q", "TRUE"),
            ("n6", "1"),
        ],
    );
}

#[test]
fn or_else_binds_like_or_and_and_then_like_and() {
    // `t OR_ELSE f AND_THEN f` is `t OR_ELSE (f AND_THEN f)` = TRUE;
    // `NOT f AND_THEN t` is `(NOT f) AND_THEN t` = TRUE; comparisons
    // bind tighter: `1 < 2 AND_THEN 3 = 3` is TRUE; a WHILE condition
    // guards its index: the loop stops at i = 4 without reading a[4].
    check(
        "",
        "t : BOOL := TRUE; f : BOOL; r1, r2, r3 : BOOL; i : INT := 1;
         a : ARRAY[1..3] OF INT := [5, 6, 7]; s : INT;",
        "r1 := t OR_ELSE f AND_THEN f;
         r2 := NOT f AND_THEN t;
         r3 := 1 < 2 AND_THEN 3 = 3;
         WHILE i <= 3 AND_THEN a[i] > 0 DO s := s + a[i]; i := i + 1; END_WHILE;",
        &[
            ("r1", "TRUE"),
            ("r2", "TRUE"),
            ("r3", "TRUE"),
            ("i", "4"),
            ("s", "18"),
        ],
    );
}

#[test]
fn and_then_on_a_non_bool_operand_is_e302_at_the_operand() {
    let src = program("", "x : INT; r : BOOL;", "r := x AND_THEN TRUE;");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E302".to_string(), "6:6".to_string())]
    );
    let src = program("", "b : BOOL; w : WORD; r : BOOL;", "r := b OR_ELSE w;");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E302".to_string(), "6:16".to_string())]
    );
}

#[test]
fn ten_hash_literals_are_decimal() {
    // 10#123 = 123; INT#10#5 = 5; 10#1_000 = 1000; -10#7 = -7;
    // 10#99 + 16#10 = 99 + 16 = 115; as a CASE label and array bound.
    check(
        "",
        "a : INT := 10#123; b : INT; c : DINT; d : INT; e : INT; w : WORD;
         arr : ARRAY[1..10#3] OF INT; k : INT := 2; s : INT;",
        "b := INT#10#5; c := 10#1_000; d := -10#7; e := 10#99 + 16#10; w := WORD#10#65535;
         CASE k OF 10#2: s := 1; ELSE s := 2; END_CASE; arr[10#3] := 4;",
        &[
            ("a", "123"),
            ("b", "5"),
            ("c", "1000"),
            ("d", "-7"),
            ("e", "115"),
            ("w", "16#FFFF"),
            ("s", "1"),
            ("arr[3]", "4"),
        ],
    );
}

#[test]
fn a_non_decimal_digit_after_ten_hash_is_e005() {
    let src = program("", "x : INT;", "x := 10#1A;");
    let codes = error_codes(&[("test.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E005"),
        "{codes:?}"
    );
    let src = program("", "x : INT;", "x := 12#5;");
    let codes = error_codes(&[("test.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E005"),
        "{codes:?}"
    );
}

#[test]
fn public_internal_final_abstract_on_function_block_headers() {
    // A PUBLIC and an INTERNAL FB run as plain ones; FB_C (FINAL)
    // extends the ABSTRACT FB_B and inherits its n := n + 5.
    check(
        "FUNCTION_BLOCK PUBLIC FB_X
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT b : INT; END_VAR
b := a * 2;
END_FUNCTION_BLOCK
FUNCTION_BLOCK INTERNAL FB_I
VAR_OUTPUT q : INT; END_VAR
q := 7;
END_FUNCTION_BLOCK
FUNCTION_BLOCK ABSTRACT FB_B
VAR_OUTPUT n : INT; END_VAR
METHOD PUBLIC Step : INT
n := n + 5;
Step := n;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FINAL FB_C EXTENDS FB_B
END_FUNCTION_BLOCK",
        "x : FB_X; i : FB_I; c : FB_C; r1, r2, r3 : INT;",
        "x(a := 4); r1 := x.b; i(); r2 := i.q; r3 := c.Step();",
        &[("r1", "8"), ("r2", "7"), ("r3", "5")],
    );
}

#[test]
fn an_abstract_function_block_instantiated_is_e901() {
    let src = program(
        "FUNCTION_BLOCK ABSTRACT FB_Base\nEND_FUNCTION_BLOCK",
        "b : FB_Base;",
        "b();",
    );
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E901".to_string(), "5:5".to_string())]
    );
}

#[test]
fn a_semicolon_after_a_pou_header_is_accepted() {
    // Each header ends in `;`; the configuration's `PROGRAM ... : P;`
    // keeps its own. FB_X doubles 4 (8), F adds one (9), M gives 8 + 100.
    let src = "FUNCTION_BLOCK PUBLIC FB_X;
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT b : INT; END_VAR
METHOD M : INT;
M := b + 100;
END_METHOD
b := a * 2;
END_FUNCTION_BLOCK
FUNCTION F : INT;
VAR_INPUT x : INT; END_VAR
F := x + 1;
END_FUNCTION
PROGRAM P;
VAR fb : FB_X; r1, r2 : INT; END_VAR
fb(a := 4); r1 := F(fb.b); r2 := fb.M();
END_PROGRAM
CONFIGURATION C
RESOURCE R ON PLC
TASK T (INTERVAL := T#10ms);
PROGRAM main WITH T : P;
END_RESOURCE
END_CONFIGURATION
";
    let mut plc = compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "main.r1"), "9");
    assert_eq!(lit(&plc, "main.r2"), "108");
}

#[test]
fn chained_assignment_assigns_right_to_left() {
    // `a := b := c := 7`: c = 7, b = c, a = b. `r := i := 3` stores the
    // INT 3 in i and then i (3) in the REAL r. Inside a CASE arm and an
    // IF, with array elements and structure fields as targets.
    check(
        "TYPE Pt : STRUCT x, y : INT; END_STRUCT END_TYPE",
        "a, b, c : INT; r : REAL; i : INT; arr : ARRAY[1..3] OF INT; p : Pt;
         k : INT := 2; d, e : DINT;",
        "a := b := c := 7;
         r := i := 3;
         CASE k OF 2: arr[1] := p.x := arr[3] := 4; END_CASE;
         IF k = 2 THEN d := e := k * 10; END_IF;",
        &[
            ("a", "7"),
            ("b", "7"),
            ("c", "7"),
            ("i", "3"),
            ("r", "3.0"),
            ("arr[1]", "4"),
            ("arr[3]", "4"),
            ("p.x", "4"),
            ("d", "20"),
            ("e", "20"),
        ],
    );
}

#[test]
fn chained_assignment_passes_on_the_value_the_middle_target_holds() {
    // The middle target is read after it is written: a STRING[3]
    // truncates 'abcdef' to 'abc', which is what s6 then gets; a call
    // on the right runs once.
    check(
        BUMP,
        "s3 : STRING[3]; s6 : STRING[6]; n : INT; x, y : BOOL;",
        "s6 := s3 := 'abcdef'; x := y := Bump(TRUE, n);",
        &[
            ("s3", "'abc'"),
            ("s6", "'abc'"),
            ("n", "1"),
            ("x", "TRUE"),
            ("y", "TRUE"),
        ],
    );
}

#[test]
fn chained_assignment_type_errors_point_at_the_assignment_that_fails() {
    // `b := 'x'` is the failing inner assignment (b is INT).
    let src = program("", "a, b : INT;", "a := b := 'x';");
    let codes = error_codes(&[("test.st", &src)]);
    assert_eq!(
        codes.first().map(|c| (c.0.as_str(), c.1.as_str())),
        Some(("E301", "6:11")),
        "{codes:?}"
    );
}

/// Enumerations written the CODESYS / TwinCAT way: a base type after the
/// values and before them, and one declared `qualified_only`.
const MODES: &str = "TYPE E_Small : (S0 := 0, S1, S7 := 7, S8) BYTE; END_TYPE
TYPE E_Wide : WORD (W0, W1 := 16#FF00, W2); END_TYPE
{attribute 'qualified_only'}
{attribute 'linkalways'}
TYPE E_Mode :
(
    Idle := 0,
    Run := 5,
    Stop
) INT;
END_TYPE
FUNCTION IsRun : BOOL
VAR_INPUT m : E_Mode; END_VAR
IsRun := m = E_Mode.Run;
END_FUNCTION";

/// Compiles `src` with `options`; the codes of its warnings, or the
/// rendered errors.
fn warning_codes(src: &str, options: &plcrun::Options) -> Result<Vec<String>, String> {
    match plcrun::Plc::compile_files(&[("test.st", src)], options) {
        Ok(plc) => Ok(plc.warnings().iter().map(|d| d.code.to_string()).collect()),
        Err(e) => Err(e.to_string()),
    }
}

#[test]
fn enumerations_with_a_base_type_written_after_or_before_the_values() {
    // S8 follows S7 := 7; W2 follows W1 := 16#FF00. Qualified values
    // (`E_Small.S8`) as initial values, in expressions and CASE labels.
    let mut plc = compile(&program(
        MODES,
        "a : E_Small := E_Small.S8; b : E_Small; w : E_Wide := E_Wide.W2;
         m : E_Mode := E_Mode.Stop; k : INT; r1, r2 : BOOL;",
        "b := E_Small.S1;
         CASE m OF E_Mode.Idle: k := 1; E_Mode.Stop: k := 2; END_CASE;
         r1 := IsRun(E_Mode.Run); r2 := IsRun(m);",
    ));
    run(&mut plc, 1);
    assert_eq!(plc.read_i64("a"), Ok(8));
    assert_eq!(plc.read_i64("b"), Ok(1));
    assert_eq!(plc.read_i64("w"), Ok(0xFF01));
    assert_eq!(plc.read_i64("m"), Ok(6));
    assert_eq!(lit(&plc, "a"), "S8");
    assert_eq!(lit(&plc, "m"), "Stop");
    assert_eq!(lit(&plc, "k"), "2");
    assert_eq!(lit(&plc, "r1"), "TRUE");
    assert_eq!(lit(&plc, "r2"), "FALSE");
}

#[test]
fn a_qualified_only_enumeration_value_written_alone_is_e433() {
    // MODES has 15 lines: the declarations are on line 18, the body
    // starts on line 20.
    let src = program(MODES, "m : E_Mode; b : BOOL;", "m := Run;\nb := m = Stop;");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [
            ("E433".to_string(), "20:6".to_string()),
            ("E433".to_string(), "21:10".to_string())
        ]
    );
    let src = program(MODES, "m : E_Mode := Idle;", "");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E433".to_string(), "18:15".to_string())]
    );
    // Unqualified values of the other types stay accepted.
    let src = program(MODES, "a : E_Small := S7; w : E_Wide;", "w := W1;");
    assert_eq!(error_codes(&[("test.st", &src)]), []);
}

#[test]
fn qualified_only_before_a_type_is_honoured_and_elsewhere_still_w150() {
    let src = program(MODES, "m : E_Mode;", "");
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    assert!(!codes.contains(&"W150".to_string()), "{codes:?}");
    let src = "{attribute 'qualified_only'}\nVAR_GLOBAL g : INT; END_VAR\nPROGRAM P\nVAR_EXTERNAL g : INT; END_VAR\ng := 1;\nEND_PROGRAM\n";
    let codes = warning_codes(src, &plcrun::Options::default()).unwrap();
    assert!(codes.contains(&"W150".to_string()), "{codes:?}");
}

#[test]
fn an_enumeration_and_an_integer_convert_implicitly_with_a_warning() {
    // E_Mode.Run is 5: n = 5 + 1; i (7) stored in a gives S7; a compared
    // with 7; x becomes E_Small 0 from a literal.
    let body = "n := E_Mode.Run + 1; a := i; r := a = 7; x := 0; d := m; y := 3;";
    let decls = "n : INT; i : BYTE := 7; a : E_Small; r : BOOL; x : E_Small := E_Small.S8;
                 m : E_Mode := E_Mode.Stop; d : DINT; y : E_Small;";
    let mut plc = compile(&program(MODES, decls, body));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "6");
    assert_eq!(lit(&plc, "a"), "S7");
    assert_eq!(lit(&plc, "r"), "TRUE");
    assert_eq!(lit(&plc, "x"), "S0");
    assert_eq!(lit(&plc, "d"), "6");
    assert_eq!(plc.read_i64("y"), Ok(3));
    let src = program(MODES, decls, body);
    let mut codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    codes.retain(|c| c == "W485" || c == "W486");
    assert_eq!(codes, ["W485", "W486", "W485", "W486", "W485", "W486"]);
    // Under --strict each is an error with the same code.
    let strict = plcrun::Options {
        strict: true,
        ..Default::default()
    };
    let err = warning_codes(&src, &strict).unwrap_err();
    assert!(
        err.contains("error[W485]") && err.contains("error[W486]"),
        "{err}"
    );
}

#[test]
fn an_integer_that_does_not_fit_the_base_type_or_another_enumeration_is_e301() {
    // A DINT does not widen to BYTE; two enumerations never mix.
    let src = program(
        MODES,
        "a : E_Small; d : DINT; m : E_Mode;",
        "a := d;\nm := a;",
    );
    let codes = error_codes(&[("test.st", &src)]);
    assert_eq!(
        codes,
        [
            ("E301".to_string(), "20:6".to_string()),
            ("E301".to_string(), "21:6".to_string())
        ]
    );
}

#[test]
fn a_qualified_name_of_a_missing_value_is_e201() {
    let src = program(MODES, "m : E_Mode;", "m := E_Mode.Running;");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E201".to_string(), "20:13".to_string())]
    );
}

#[test]
fn var_inst_keeps_a_methods_variable_per_instance_between_calls() {
    // Count's VAR_INST n starts at 10 and grows by one a call, per
    // instance; its VAR t is fresh at every call (always 0 + 1). FB_D
    // inherits Count: its instance has its own n.
    let prelude = "FUNCTION_BLOCK FB_C
METHOD Count : INT
VAR_INST n : INT := 10; END_VAR
VAR t : INT; END_VAR
n := n + 1;
t := t + 1;
Count := n * 100 + t;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_D EXTENDS FB_C
END_FUNCTION_BLOCK";
    let mut plc = compile(&program(
        prelude,
        "c1, c2 : FB_C; d : FB_D; r1, r2, r3 : INT;",
        "r1 := c1.Count(); r1 := c1.Count(); r2 := c2.Count(); r3 := d.Count();",
    ));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r1"), "1201");
    assert_eq!(lit(&plc, "r2"), "1101");
    assert_eq!(lit(&plc, "r3"), "1101");
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "r1"), "1601");
    assert_eq!(lit(&plc, "r2"), "1301");
    assert_eq!(lit(&plc, "r3"), "1301");
}

#[test]
fn var_inst_outside_a_method_is_e434() {
    let src = "FUNCTION_BLOCK FB_X\nVAR_INST n : INT; END_VAR\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR x : FB_X; END_VAR\nx();\nEND_PROGRAM\n";
    assert_eq!(
        error_codes(&[("test.st", src)]),
        [("E434".to_string(), "2:1".to_string())]
    );
}

/// A function of three inputs that shows which went where.
const ABC: &str = "FUNCTION F : INT
VAR_INPUT a, b : INT; c : INT := 7; END_VAR
F := a * 100 + b * 10 + c;
END_FUNCTION
FUNCTION_BLOCK FB_S
VAR_INPUT x, y : INT; END_VAR
VAR_OUTPUT s : INT; END_VAR
s := x - y;
END_FUNCTION_BLOCK";

#[test]
fn positional_arguments_then_formal_ones_bind_in_declaration_order() {
    // F(1, 2, c := 3): a = 1, b = 2 (positional), c = 3 (formal);
    // F(4, c := 5, b := 6); F(8, b := 9) leaves c at its default 7;
    // an FB call too: x = 10 (positional), y = 3 (formal).
    check(
        ABC,
        "r1, r2, r3, r4 : INT; fb : FB_S;",
        "r1 := F(1, 2, c := 3); r2 := F(4, c := 5, b := 6); r3 := F(8, b := 9);
         fb(10, y := 3); r4 := fb.s;",
        &[("r1", "123"), ("r2", "465"), ("r3", "897"), ("r4", "7")],
    );
    let src = program(ABC, "r : INT;", "r := F(1, b := 2);");
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    assert_eq!(codes, ["W487"]);
}

#[test]
fn a_positional_argument_after_a_formal_one_is_e411_and_too_many_e404() {
    // After the 9-line ABC the body is on line 14.
    let src = program(ABC, "r : INT;", "r := F(a := 1, 2);");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E411".to_string(), "14:16".to_string())]
    );
    let src = program(ABC, "r : INT;", "r := F(1, 2, 3, 4, c := 5);");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E404".to_string(), "14:6".to_string())]
    );
    let src = program(ABC, "r : INT;", "r := F(1, a := 2);");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E404".to_string(), "14:11".to_string())]
    );
}

#[test]
fn new_and_delete_are_refused_by_name() {
    let src = program("", "p : POINTER TO INT;", "p := __NEW(INT);\n__DELETE(p);");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [
            ("E435".to_string(), "6:6".to_string()),
            ("E435".to_string(), "7:1".to_string())
        ]
    );
}

#[test]
fn bit_operators_on_integers_of_every_width() {
    // Bitwise on the two's complement of the width: SINT NOT 5 = -6,
    // USINT NOT 5 = 250, INT -1 AND 16#0F = 15, UDINT 16#F0 OR 1, LINT
    // XOR, ULINT NOT 0 = 18446744073709551615, DINT constants folded.
    check(
        "",
        "s : SINT := 5; us : USINT := 5; i : INT := -1; ud : UDINT := 16#F0;
         l : LINT := 12; ul : ULINT; di : DINT;
         r1 : SINT; r2 : USINT; r3 : INT; r4 : UDINT; r5 : LINT; r6 : ULINT; r7 : DINT; r8 : UINT;",
        "r1 := NOT s; r2 := NOT us; r3 := i AND 16#0F; r4 := ud OR 1; r5 := l XOR 10;
         r6 := NOT ul; r7 := DINT#6 AND DINT#3 OR DINT#8; r8 := NOT UINT#1;",
        &[
            ("r1", "-6"),
            ("r2", "250"),
            ("r3", "15"),
            ("r4", "241"),
            ("r5", "6"),
            ("r6", "18446744073709551615"),
            ("r7", "10"),
            ("r8", "65534"),
        ],
    );
    let src = program("", "i, j : INT;", "j := i AND 3;\nj := NOT i;");
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    assert_eq!(codes, ["W488", "W488"]);
    let strict = plcrun::Options {
        strict: true,
        ..Default::default()
    };
    assert!(
        warning_codes(&src, &strict)
            .unwrap_err()
            .contains("error[W488]")
    );
}

#[test]
fn pointer_indexing_reads_and_writes_the_ith_element_after_the_pointer() {
    // p points at arr[0]: p[2] is arr[2] (30), p[i] with i = 3 is 40,
    // p[4] := 7 writes arr[4]; q moves one element on and indexes from
    // there (q[1] = arr[2]); a LREAL pointer strides by 8 bytes.
    check(
        "",
        "arr : ARRAY[0..4] OF INT := [10, 20, 30, 40, 50]; p, q : POINTER TO INT;
         lr : ARRAY[1..3] OF LREAL := [1.5, 2.5, 3.5]; pl : POINTER TO LREAL;
         x, y, z : INT; i : INT := 3; r : LREAL;",
        "p := ADR(arr); x := p[2]; y := p[i]; p[4] := 7;
         q := p + SIZEOF(arr[0]); z := q[1];
         pl := ADR(lr); r := pl[2];",
        &[
            ("x", "30"),
            ("y", "40"),
            ("arr[4]", "7"),
            ("z", "30"),
            ("r", "3.5"),
        ],
    );
}

#[test]
fn pointer_indexing_past_the_object_faults_and_two_indexes_are_e404() {
    let src = program(
        "",
        "arr : ARRAY[0..4] OF INT; p : POINTER TO INT; x : INT; i : INT := 5;",
        "p := ADR(arr); x := p[i];",
    );
    let fault = plc::first_fault(&src);
    assert!(fault.to_string().contains("R031"), "{fault}");
    let src = program("", "p : POINTER TO INT; x : INT;", "x := p[1, 2];");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E404".to_string(), "6:6".to_string())]
    );
}

#[test]
fn this_call_in_a_method_runs_the_instances_body() {
    // Twice runs the body with step 1 (n = 1), then with step := 10
    // (n = 11); the input keeps 10 afterwards. A child FB's instance runs
    // its own body (n + step * 2).
    let prelude = "FUNCTION_BLOCK FB_X
VAR_INPUT step : INT := 1; END_VAR
VAR_OUTPUT n : INT; END_VAR
METHOD Twice
THIS^();
THIS^(step := 10);
END_METHOD
n := n + step;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Y EXTENDS FB_X
n := n + step * 2;
END_FUNCTION_BLOCK";
    check(
        prelude,
        "f : FB_X; y : FB_Y; r, s, t : INT;",
        "f.Twice(); r := f.n; s := f.step; y.Twice(); t := y.n;",
        &[("r", "11"), ("s", "10"), ("t", "22")],
    );
}

#[test]
fn this_call_in_the_fbs_own_body_or_back_through_a_method_is_e409() {
    let src = program(
        "FUNCTION_BLOCK FB_X\nMETHOD M\n;\nEND_METHOD\nTHIS^();\nEND_FUNCTION_BLOCK",
        "f : FB_X;",
        "f();",
    );
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E409".to_string(), "5:1".to_string())]
    );
    let src = program(
        "FUNCTION_BLOCK FB_X\nMETHOD M\nTHIS^();\nEND_METHOD\nM();\nEND_FUNCTION_BLOCK",
        "f : FB_X;",
        "f();",
    );
    let codes = error_codes(&[("test.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E409"),
        "{codes:?}"
    );
}

#[test]
fn fb_instances_take_structured_initial_values() {
    // `a` starts with k = 3, n = 100, s = 'abc' (b keeps the declared
    // k = 1, n = 0); the TON starts with PT = T#5S and is done after
    // three 2 s cycles; an FB inside an FB gets its own values too.
    let prelude = "FUNCTION_BLOCK FB_A
VAR_INPUT k : INT := 1; s : STRING := 'x'; END_VAR
VAR_OUTPUT q : INT; END_VAR
VAR n : INT; END_VAR
q := k * 2 + n;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_B
VAR inner : FB_A := (k := 20); END_VAR
VAR_OUTPUT q : INT; END_VAR
inner();
q := inner.q;
END_FUNCTION_BLOCK";
    let src = program(
        prelude,
        "t : TON := (PT := T#5S); a : FB_A := (k := 3, n := 100, s := 'abc'); b : FB_A;
         c : FB_B; r1, r2, r3 : INT; s : STRING;",
        "a(); b(); c(); r1 := a.q; r2 := b.q; r3 := c.q; s := a.s; t(IN := TRUE);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r1"), "106");
    assert_eq!(lit(&plc, "r2"), "2");
    assert_eq!(lit(&plc, "r3"), "40");
    assert_eq!(lit(&plc, "s"), "'abc'");
    assert_eq!(lit(&plc, "t.PT"), "T#5s");
    // A cold restart starts them with the same values.
    plc.reset_cold();
    assert_eq!(lit(&plc, "a.k"), "3");
    assert_eq!(lit(&plc, "t.PT"), "T#5s");
}

#[test]
fn an_initial_value_for_an_in_out_or_a_missing_member_of_an_instance_is_refused() {
    let prelude = "FUNCTION_BLOCK FB_A
VAR_IN_OUT io : INT; END_VAR
VAR_INPUT k : INT; END_VAR
END_FUNCTION_BLOCK";
    // The declarations are on line 7; RUNNING is TON's hidden state.
    let src = program(
        prelude,
        "a : FB_A := (io := 1, kk := 2); t : TON := (RUNNING := TRUE);",
        "",
    );
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [
            ("E436".to_string(), "7:14".to_string()),
            ("E201".to_string(), "7:23".to_string()),
            ("E436".to_string(), "7:45".to_string())
        ]
    );
}

#[test]
fn an_fb_instance_is_copied_by_assignment_strings_by_text() {
    // b := a copies n (5), k (5) and s ('abc') and the nested TON; a is
    // called again with k = 1 and s = 'zz': the copies go their own way
    // (b's string keeps its own buffer).
    let prelude = "FUNCTION_BLOCK FB_A
VAR_INPUT k : INT; s : STRING := 'x'; END_VAR
VAR_OUTPUT q : INT; END_VAR
VAR n : INT; t : TON; END_VAR
n := n + k;
q := n;
t(IN := TRUE, PT := T#1H);
END_FUNCTION_BLOCK";
    let body = "a(k := 5, s := 'abc'); b := a; a(k := 1, s := 'zz'); b();
        r1 := a.q; r2 := b.q; s1 := a.s; s2 := b.s; tc := tn; tn := a.t;";
    check(
        prelude,
        "a, b : FB_A; r1, r2 : INT; s1, s2 : STRING; tn, tc : TON;",
        body,
        &[
            ("r1", "6"),
            ("r2", "10"),
            ("s1", "'zz'"),
            ("s2", "'abc'"),
            ("b.t.PT", "T#1h"),
            ("tn.PT", "T#1h"),
        ],
    );
    let src = program(prelude, "a, b : FB_A; t1, t2 : TON;", "b := a; t1 := t2;");
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    assert_eq!(codes, ["W489", "W489"]);
}

#[test]
fn instances_of_different_fb_types_are_not_copied() {
    let src = program(
        "FUNCTION_BLOCK FB_A\nEND_FUNCTION_BLOCK",
        "a : FB_A; t : TON;",
        "a := t;",
    );
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E301".to_string(), "7:6".to_string())]
    );
}

#[test]
fn var_in_out_constant_takes_any_variable_and_is_read_only_in_the_body() {
    // G reads s ('abcd', 4 characters) and n (21) through references to
    // the program's CONSTANTs; FB_R doubles v; an FB's input passed on.
    let prelude = "FUNCTION G : INT
VAR_IN_OUT CONSTANT s : STRING; n : INT; END_VAR
G := LEN(s) + n;
END_FUNCTION
FUNCTION_BLOCK FB_R
VAR_IN_OUT CONSTANT v : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := v * 2;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_W
VAR_INPUT k : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
VAR inner : FB_R; END_VAR
inner(v := k);
q := inner.q;
END_FUNCTION_BLOCK";
    let src = format!(
        "{prelude}\nPROGRAM P\nVAR CONSTANT c : INT := 21; txt : STRING := 'abcd'; END_VAR\n\
         VAR r, r2, r3 : INT; fb : FB_R; w : FB_W; x : INT := 5; END_VAR\n\
         r := G(txt, c); fb(v := c); r2 := fb.q; w(k := x); r3 := w.q;\nEND_PROGRAM\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r"), "25");
    assert_eq!(lit(&plc, "r2"), "42");
    assert_eq!(lit(&plc, "r3"), "10");
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    assert_eq!(codes, ["W353", "W353", "W353"]);
}

#[test]
fn var_in_out_constant_takes_a_value_and_a_string_of_any_length() {
    // As TwinCAT's libraries are called (`fbJson.AddObjectMember(v,
    // 'name')`): a literal, an expression, a function's result, a longer
    // literal than the parameter's STRING and a STRING(255) variable are
    // passed whole; a method and an FB take them as a function does.
    let prelude = "FUNCTION G : INT
VAR_IN_OUT CONSTANT s : STRING(4); n : INT; END_VAR
G := LEN(s) * 100 + n;
END_FUNCTION
FUNCTION_BLOCK FB_R
VAR_IN_OUT CONSTANT v : INT; t : STRING; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := v * 2 + LEN(t);
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_M
METHOD M : STRING(255)
VAR_IN_OUT CONSTANT a : STRING; END_VAR
M := CONCAT(a, '!');
END_METHOD
END_FUNCTION_BLOCK";
    let src = format!(
        "{prelude}\nPROGRAM P\nVAR r1, r2, r3, r4 : INT; fb : FB_R; m : FB_M; k : INT := 4;\n\
         long : STRING(255) := 'abcdefghij'; said : STRING(255); END_VAR\n\
         r1 := G('abc', 7);\nr2 := G('abcdefgh', k * 2);\nr3 := G(long, LEN(long));\n\
         fb(v := k + 1, t := CONCAT('x', 'yz'));\nr4 := fb.q;\nsaid := m.M('hello');\nEND_PROGRAM\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r1"), "307");
    assert_eq!(lit(&plc, "r2"), "808");
    assert_eq!(lit(&plc, "r3"), "1010");
    assert_eq!(lit(&plc, "r4"), "13");
    assert_eq!(lit(&plc, "said"), "'hello!'");
    // A BOOL given to an INT: still a type error.
    let bad = src.replace("LEN(long))", "k = 4)");
    let codes = error_codes(&[("test.st", &bad)]);
    assert_eq!(codes.len(), 1, "{codes:?}");
    assert_eq!(codes[0].0, "E301");
}

#[test]
fn writing_a_var_in_out_constant_is_e401_and_a_plain_in_out_still_needs_a_writable_variable() {
    let src = "FUNCTION G : INT\nVAR_IN_OUT CONSTANT n : INT; END_VAR\nn := 1;\nG := n;\nEND_FUNCTION\n\
               PROGRAM P\nVAR r : INT; END_VAR\nr := G(r);\nEND_PROGRAM\n";
    assert_eq!(
        error_codes(&[("test.st", src)]),
        [("E401".to_string(), "3:1".to_string())]
    );
    let src = "FUNCTION G : INT\nVAR_IN_OUT n : INT; END_VAR\nG := n;\nEND_FUNCTION\n\
               PROGRAM P\nVAR CONSTANT c : INT := 1; END_VAR\nVAR r : INT; END_VAR\nr := G(c);\nEND_PROGRAM\n";
    assert_eq!(
        error_codes(&[("test.st", src)]),
        [("E412".to_string(), "8:8".to_string())]
    );
}

#[test]
fn a_type_named_with_its_librarys_namespace_is_that_type() {
    // Tc2_Standard.TON is TON, MyLib.FB_Base the FB_Base declared here:
    // in declarations, arrays, a FUNCTION's result, EXTENDS and IMPLEMENTS.
    let prelude = "INTERFACE I_X
METHOD M : INT
END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Base
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Child EXTENDS MyLib.FB_Base IMPLEMENTS MyLib.I_X
METHOD M : INT
M := n * 10;
END_METHOD
SUPER^();
END_FUNCTION_BLOCK
FUNCTION Twice : Standard.INT
VAR_INPUT x : INT; END_VAR
Twice := x * 2;
END_FUNCTION";
    check(
        prelude,
        "t : Tc2_Standard.TON; c : FB_Child; i : I_X; r1, r2 : INT;
         e : ARRAY[1..2] OF Tc2_Standard.R_TRIG; q : BOOL;",
        "t(IN := TRUE, PT := T#1S); c(); i := c; r1 := i.M(); r2 := Twice(3);
         e[2](CLK := TRUE); q := e[2].Q;",
        &[("r1", "10"), ("r2", "6"), ("t.PT", "T#1s"), ("q", "TRUE")],
    );
    // The type must still exist.
    let src = program("", "t : Tc2_Standard.TONN;", "");
    let codes = error_codes(&[("test.st", &src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E203"),
        "{codes:?}"
    );
}

#[test]
fn a_function_called_with_its_librarys_namespace_is_that_function() {
    // Tc2_Standard.CONCAT and .LEN are the standard functions, MyLib.F_Add
    // the FUNCTION declared here; a method call on an instance is not
    // touched, and a misspelt instance before a method's name is an
    // unknown name (E201: nothing is called `mm`), not a namespace.
    let prelude = "FUNCTION F_Add : INT
VAR_INPUT a, b : INT; END_VAR
F_Add := a + b;
END_FUNCTION
FUNCTION_BLOCK FB_M
METHOD Get : INT
Get := 42;
END_METHOD
END_FUNCTION_BLOCK";
    check(
        prelude,
        "s : STRING; r1, r2, r3 : INT; m : FB_M;",
        "s := Tc2_Standard.CONCAT('ab', 'cd'); r1 := MyLib.F_Add(2, 3);
         r2 := Tc2_Standard.LEN(s); r3 := m.Get(); MyLib.F_Add(1, 1);",
        &[("s", "'abcd'"), ("r1", "5"), ("r2", "4"), ("r3", "42")],
    );
    let src = program(prelude, "m : FB_M; r : INT;", "r := mm.Get();");
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [("E201".to_string(), "14:6".to_string())]
    );
}

/// A PROGRAM with a METHOD (with VAR_INST) and a PROPERTY.
const PRG_METHODS: &str = "PROGRAM P
VAR x : INT; r : INT; calls : INT; END_VAR
METHOD Twice : INT
VAR_INPUT a : INT; END_VAR
VAR_INST n : INT; END_VAR
n := n + 1;
calls := n;
Twice := a * 2;
END_METHOD
PROPERTY Value : INT
GET Value := x; END_GET
SET x := Value + 1; END_SET
END_PROPERTY
Value := 20;
r := Twice(Value);
r := THIS^.Twice(r);
END_PROGRAM
";

#[test]
fn methods_and_properties_in_a_program() {
    // Value := 20 stores 21 in x; Twice(21) = 42, Twice(42) = 84; the
    // method's VAR_INST counts 2 calls a cycle.
    let mut plc = compile(PRG_METHODS);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "x"), "21");
    assert_eq!(lit(&plc, "r"), "84");
    assert_eq!(lit(&plc, "calls"), "4");
}

#[test]
fn each_instance_of_a_program_with_methods_keeps_its_own_state() {
    // Two instances of P under one task: each counts its own calls.
    let src = format!(
        "{PRG_METHODS}CONFIGURATION C\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\n\
         PROGRAM a WITH T : P;\nPROGRAM b WITH T : P;\nEND_RESOURCE\nEND_CONFIGURATION\n"
    );
    let mut plc = compile(&src);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "a.calls"), "6");
    assert_eq!(lit(&plc, "b.calls"), "6");
    assert_eq!(lit(&plc, "b.r"), "84");
}

#[test]
fn a_strict_enumeration_takes_no_integer_and_no_arithmetic_but_reads_as_one() {
    // TwinCAT's default for a new enumeration: qualified_only and strict.
    let prelude = "{attribute 'qualified_only'}
{attribute 'strict'}
TYPE E_S : (A, B := 5); END_TYPE";
    let src = program(
        prelude,
        "e : E_S; n : INT; d : DINT;",
        "n := E_S.B + 1;\ne := 1;\nd := e;\ne := E_S.B;\ne := n;",
    );
    // TwinCAT's manual lists what strict refuses: arithmetic, a constant
    // and a value of another type stored in the enumeration. Reading it as
    // an integer (`d := e`) stays allowed, with W485.
    assert_eq!(
        error_codes(&[("test.st", &src)]),
        [
            ("E306".to_string(), "8:6".to_string()),
            ("E301".to_string(), "9:6".to_string()),
            ("E301".to_string(), "12:6".to_string())
        ]
    );
    // The attribute is honoured there: neither W001 nor W150.
    let src = program(prelude, "e : E_S;", "e := E_S.B;");
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    assert_eq!(codes, Vec::<String>::new());
}

/// The string functions' inputs under CODESYS's names (W359), at the same
/// place as the IEC ones: by hand, 'ab' + 'cde' = 'abcde' (5 characters),
/// MID of 3 from position 2 'bcd', LEFT 2 'ab', FIND 'cd' at 3,
/// INSERT 'X' after 1 'aXbcde', DELETE 2 from 2 'ade', REPLACE 2 from 2
/// by 'Z' 'aZde', RIGHT 2 'de'.
#[test]
fn string_function_inputs_take_codesys_s_names_with_a_warning() {
    let src = program(
        "",
        "s, m, l, ins, del, rep, r : STRING; n, f : INT;",
        "s := CONCAT(STR1 := 'ab', STR2 := 'cde');
         n := LEN(STR := s);
         m := MID(STR := s, LEN := 3, POS := 2);
         l := LEFT(STR := s, SIZE := 2);
         f := FIND(STR1 := s, STR2 := 'cd');
         ins := INSERT(STR1 := s, STR2 := 'X', POS := 1);
         del := DELETE(STR := s, LEN := 2, POS := 2);
         rep := REPLACE(STR1 := s, STR2 := 'Z', L := 2, P := 2);
         r := RIGHT(STR := s, SIZE := 2);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(
        ["s", "n", "m", "l", "f", "ins", "del", "rep", "r"].map(|v| lit(&plc, v)),
        [
            "'abcde'", "5", "'bcd'", "'ab'", "3", "'aXbcde'", "'ade'", "'aZde'", "'de'"
        ]
    );
    let codes = warning_codes(&src, &plcrun::Options::default()).unwrap();
    // Every name but REPLACE's `L` and `P` (also the IEC names) warns.
    assert_eq!(
        codes.iter().filter(|c| *c == "W359").count(),
        20,
        "{codes:?}"
    );
    // An input neither name knows is still E403.
    let bad = program("", "n : INT;", "n := LEN(TEXT := 'x');");
    let codes: Vec<String> = error_codes(&[("t.st", &bad)])
        .into_iter()
        .map(|(code, _)| code)
        .collect();
    assert_eq!(codes, ["E403"]);
}

/// An enumeration of the default base type (DINT in plcrun, INT in
/// CODESYS) goes into a narrower integer that holds all its values, strict
/// or not (PMPS: `nAperture : INT := L_Apertures.SL1L0`), with W485; one
/// whose values do not all fit is still E301.
#[test]
fn an_enumeration_goes_into_an_integer_that_holds_all_its_values() {
    let types = "
{attribute 'qualified_only'}
{attribute 'strict'}
TYPE L_Apertures : (SL1L0 := 1, SL2L0 := 2); END_TYPE
TYPE E_Big : (Small := 1, Huge := 100000); END_TYPE";
    let src = program(
        types,
        "n : INT; u : USINT; e : L_Apertures := L_Apertures.SL2L0;",
        "n := L_Apertures.SL1L0; u := e;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "1");
    assert_eq!(lit(&plc, "u"), "2");
    let big = program(types, "n : INT;", "n := E_Big.Small;");
    let codes: Vec<String> = error_codes(&[("test.st", &big)])
        .into_iter()
        .map(|(c, _)| c)
        .collect();
    assert_eq!(codes, ["E301"]);
}

/// Runs of underscores between the digits of an integer literal, as
/// CODESYS and TwinCAT accept them (lcls-twincat-general writes
/// `16#7f_ff_ff_ff__ff_ff_ff_ff`): W349, read as single ones; refused by
/// `--strict`; an underscore at an end is still E005.
#[test]
fn consecutive_underscores_in_an_integer_literal_are_w349() {
    let src = program(
        "",
        "x : LWORD; n : DINT;",
        "x := 16#7f_ff_ff_ff__ff_ff_ff_ff; n := 1__000;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "x"), "16#7FFFFFFFFFFFFFFF");
    assert_eq!(lit(&plc, "n"), "1000");
    let codes: Vec<&str> = plc.warnings().iter().map(|d| d.code).collect();
    assert_eq!(
        codes.iter().filter(|c| **c == "W349").count(),
        2,
        "{codes:?}"
    );
    let strict = plcrun::Options {
        strict: true,
        ..Default::default()
    };
    let err = plcrun::Plc::compile_files(&[("test.st", &src)], &strict)
        .err()
        .expect("strict refuses");
    assert!(err.to_string().contains("error[W349]"), "{err}");
    let end = program("", "n : DINT;", "n := 16#FF__;");
    let codes: Vec<String> = error_codes(&[("test.st", &end)])
        .into_iter()
        .map(|(c, _)| c)
        .collect();
    assert_eq!(codes.first().map(String::as_str), Some("E005"), "{codes:?}");
}

/// `__ISVALIDREF` of a VAR_IN_OUT in a METHOD of its block, as LCLS
/// General's FB_EPS guards its accesses: FALSE until a call of the block
/// connects it; used unguarded before that, it faults instead of writing
/// into whatever variable lies at some address.
#[test]
fn isvalidref_of_an_in_out_tells_whether_a_call_connected_it() {
    let prelude = "TYPE DUT_EPS : STRUCT nFlags : UDINT; END_STRUCT END_TYPE\n\
        FUNCTION_BLOCK FB_EPS\nVAR_IN_OUT eps : DUT_EPS; END_VAR\n\
        METHOD setBit : BOOL\nVAR_INPUT n : BYTE; END_VAR\n\
        IF NOT __ISVALIDREF(eps) THEN RETURN; END_IF\n\
        eps.nFlags := eps.nFlags OR SHL(UDINT#1, n);\nsetBit := TRUE;\nEND_METHOD\n\
        METHOD unguarded\neps.nFlags := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK";
    // `e` first: the variable at the program's first address.
    let src = program(
        prelude,
        "e : DUT_EPS; fb : FB_EPS; before, after : BOOL;",
        "before := fb.setBit(2);\nfb(eps := e);\nafter := fb.setBit(3);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.before"), "FALSE");
    assert_eq!(lit(&plc, "P.after"), "TRUE");
    assert_eq!(lit(&plc, "P.e.nFlags"), "8");
    let src = program(prelude, "e : DUT_EPS; fb : FB_EPS;", "fb.unguarded();");
    let fault = plc::first_fault(&src);
    assert_eq!(fault.code(), "R999", "{fault}");
    assert!(fault.to_string().contains("VAR_IN_OUT"), "{fault}");
}

/// A `POINTER TO STRING` over a longer STRING, as LCLS General's logger
/// passes `ADR(sJsonDoc)` of a `STRING(10000)`: the string itself, read
/// whole and written within its own length.
#[test]
fn a_pointer_to_string_takes_a_string_of_any_length() {
    let src = program(
        "",
        "big : STRING(1000); ps : POINTER TO STRING; s : STRING(5); n : INT;",
        "big := 'hello world';\nps := ADR(big);\ns := ps^;\nps^ := 'written';\nn := LEN(big);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.s"), "'hello'");
    assert_eq!(lit(&plc, "P.big"), "'written'");
    assert_eq!(lit(&plc, "P.n"), "7");
}

#[test]
fn an_initial_value_may_read_a_constant_declared_further_down() {
    // FB_MotionHoming of lcls-twincat-motion: the state variable starts
    // at a constant of the POU's later VAR CONSTANT block.
    let prelude = "FUNCTION_BLOCK FB_Homing
VAR
  nState : INT := IDLE;
  nNext : INT := IDLE + STEP;
END_VAR
VAR CONSTANT
  IDLE : INT := 7;
  STEP : INT := 3;
END_VAR
END_FUNCTION_BLOCK";
    check(
        prelude,
        "fb : FB_Homing; a : INT; b : INT;",
        "a := fb.nState; b := fb.nNext;",
        &[("P.a", "7"), ("P.b", "10")],
    );
}

#[test]
fn min_and_max_take_an_enumeration_as_its_integer_beside_an_integer() {
    use crate::support::twincat::{compile_ok, declaration, pou};
    // FB_NCErrorFFO: `MIN(nErrorTypeCode, E_MotionFFType.HIGH_RESERVED_NC)`.
    let kind = declaration(
        "DUT",
        "E_Kind",
        "TYPE E_Kind : (LOW := 2, HIGH := 40) UINT; END_TYPE",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR n : UINT := 100; m : UINT := 1; a : UINT; b : UINT; c : UINT; END_VAR",
        "a := MIN(n, E_Kind.HIGH); b := MAX(m, E_Kind.LOW); c := LIMIT(E_Kind.LOW, n, E_Kind.HIGH);",
        "",
    );
    let mut plc = compile_ok(&[("E_Kind.TcDUT", &kind), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "40");
    assert_eq!(lit(&plc, "P.b"), "2");
    assert_eq!(lit(&plc, "P.c"), "40");
    // In an IEC file the types do not mix.
    let iec = program(
        "TYPE E_Kind : (LOW := 2, HIGH := 40) UINT; END_TYPE",
        "n : UINT; a : UINT;",
        "a := MIN(n, E_Kind.HIGH);",
    );
    let codes = error_codes(&[("iec.st", &iec)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E306"),
        "{codes:?}"
    );
}

#[test]
fn a_global_named_with_its_library_namespace_and_list() {
    use crate::support::twincat::{compile_ok, declaration, pou};
    // lcls-twincat-motion: `lcls_twincat_math.GVL_Constants.PI`.
    let gvl = declaration(
        "GVL",
        "GVL_Constants",
        "VAR_GLOBAL CONSTANT\n  PI : LREAL := 3.5;\nEND_VAR",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR x : LREAL; y : LREAL; END_VAR",
        "x := lcls_twincat_math.GVL_Constants.PI * 2.0;\ny := GVL_Constants.PI;",
        "",
    );
    let mut plc = compile_ok(&[("GVL_Constants.TcGVL", &gvl), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.x"), "7.0");
    assert_eq!(lit(&plc, "P.y"), "3.5");
}

#[test]
fn pouname_is_the_name_of_the_running_pou() {
    use crate::support::twincat::{compile_ok, method, pou};
    let fb = pou(
        "FB_Log",
        "FUNCTION_BLOCK FB_Log\nVAR_OUTPUT sBody : STRING; sMethod : STRING; END_VAR",
        "sBody := __POUNAME();",
        &method("METHOD M\n", "sMethod := __POUNAME();"),
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR fb : FB_Log; s : STRING; END_VAR",
        "fb(); fb.M(); s := __POUNAME();",
        "",
    );
    let mut plc = compile_ok(&[("FB_Log.TcPOU", &fb), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.s"), "'P'");
    assert_eq!(lit(&plc, "P.fb.sBody"), "'FB_Log'");
    assert_eq!(lit(&plc, "P.fb.sMethod"), "'FB_Log.M'");
}

#[test]
fn an_input_given_twice_takes_the_last_value_in_codesys_files_only() {
    use crate::support::twincat::{compile, compile_ok, pou};
    // FB_HaltNC of lcls-twincat-motion names `Execute` twice.
    let fb = "FUNCTION_BLOCK FB_Take\nVAR_INPUT x : INT; END_VAR\nVAR_OUTPUT y : INT; END_VAR\ny := x;\nEND_FUNCTION_BLOCK";
    let main = pou(
        "P",
        "PROGRAM P\nVAR fb : FB_Take; END_VAR",
        "fb(x := 1, x := 2);",
        "",
    );
    let lib = fb.to_string();
    let mut plc = compile_ok(&[("take.st", &lib), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.fb.y"), "2");
    let warned = match compile(&[("take.st", &lib), ("P.TcPOU", &main)]) {
        Ok(plc) => plc.warnings().iter().any(|d| d.code == "W493"),
        Err(e) => panic!("{e}"),
    };
    assert!(warned);
    let iec = program(fb, "fb : FB_Take;", "fb(x := 1, x := 2);");
    let codes = error_codes(&[("iec.st", &iec)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E404"),
        "{codes:?}"
    );
}

#[test]
fn a_project_s_check_bounds_function_clamps_computed_indexes() {
    use crate::support::twincat::{compile_ok, pou};
    // TwinCAT's implicit check, as SLAC's libraries carry it;
    // lcls-twincat-motion's FB_PositionStateRead_Test runs a FOR loop one
    // element past its ARRAY[1..3].
    let check = pou(
        "CheckBounds",
        "FUNCTION CheckBounds : DINT\nVAR_INPUT\n  index, lower, upper : DINT;\nEND_VAR",
        "IF index < lower THEN\n  CheckBounds := lower;\nELSIF index > upper THEN\n  CheckBounds := upper;\nELSE\n  CheckBounds := index;\nEND_IF",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  a : ARRAY[1..3] OF INT;\n  i : DINT;\n  low : INT;\n  last : INT;\nEND_VAR",
        "FOR i := 0 TO 4 DO\n  a[i] := DINT_TO_INT(i * 10);\nEND_FOR\nlow := a[1];\nlast := a[3];",
        "",
    );
    let mut plc = compile_ok(&[("CheckBounds.TcPOU", &check), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    // a[0] went to a[1] and a[4] to a[3]: each kept the last value written.
    assert_eq!(lit(&plc, "P.low"), "10");
    assert_eq!(lit(&plc, "P.last"), "40");
    // Without the function (or in an IEC file) the access is a fault.
    let mut plain = compile_ok(&[("P.TcPOU", &main)]);
    let fault = plain.run_cycle().expect_err("out of bounds");
    assert!(fault.to_string().contains("R002"), "{fault}");
}

#[test]
fn a_pou_declared_no_check_calls_no_check_bounds() {
    use crate::support::twincat::{compile_ok, pou};
    // `{attribute 'no_check'}` before the POU: its accesses keep plcrun's
    // own check (R002) where the project's CheckBounds would clamp, and
    // the pragma is honoured, not reported as ignored.
    let check = pou(
        "CheckBounds",
        "FUNCTION CheckBounds : DINT\nVAR_INPUT\n  index, lower, upper : DINT;\nEND_VAR",
        "IF index < lower THEN\n  CheckBounds := lower;\nELSIF index > upper THEN\n  CheckBounds := upper;\nELSE\n  CheckBounds := index;\nEND_IF",
        "",
    );
    let raw = pou(
        "Raw",
        "{attribute 'no_check'}\nFUNCTION_BLOCK Raw\nVAR_INPUT\n  i : DINT;\nEND_VAR\nVAR\n  a : ARRAY[1..3] OF INT;\nEND_VAR",
        "a[i] := 1;",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  r : Raw;\n  k : DINT := 2;\nEND_VAR",
        "r(i := k);\nk := k + 2;",
        "",
    );
    let mut plc = compile_ok(&[
        ("CheckBounds.TcPOU", &check),
        ("Raw.TcPOU", &raw),
        ("P.TcPOU", &main),
    ]);
    let ignored: Vec<String> = plc
        .warnings()
        .iter()
        .filter(|d| d.code == "W001")
        .map(|d| d.message.clone())
        .collect();
    assert!(ignored.is_empty(), "{ignored:?}");
    run(&mut plc, 1);
    let fault = plc.run_cycle().expect_err("a[4] out of bounds");
    assert!(fault.to_string().contains("R002"), "{fault}");
}

#[test]
fn this_names_the_instance_s_variable_where_a_method_declares_the_same_name() {
    use crate::support::twincat::{compile_ok, pou};
    // `THIS^.AxisRef REF= AxisRef;` in an FB_init whose input is
    // `AxisRef` (lcls-twincat-motion's FB_MoveAbsoluteNC), and the setter
    // idiom `THIS^.nSpeed := nSpeed;`.
    let methods = "<Method Name=\"FB_Init\" Id=\"{00000000-0000-0000-0000-000000000019}\"><Declaration><![CDATA[METHOD FB_Init : BOOL\nVAR_INPUT\n  bInitRetains : BOOL;\n  bInCopyCode : BOOL;\n  AxisRef : REFERENCE TO INT;\nEND_VAR]]></Declaration><Implementation><ST><![CDATA[THIS^.AxisRef REF= AxisRef;]]></ST></Implementation></Method>\n<Method Name=\"SetSpeed\" Id=\"{00000000-0000-0000-0000-000000000029}\"><Declaration><![CDATA[METHOD SetSpeed\nVAR_INPUT\n  nSpeed : INT;\nEND_VAR]]></Declaration><Implementation><ST><![CDATA[THIS^.nSpeed := nSpeed;]]></ST></Implementation></Method>\n";
    let fb = pou(
        "FB_Axis",
        "FUNCTION_BLOCK FB_Axis\nVAR\n  AxisRef : REFERENCE TO INT;\nEND_VAR\nVAR_OUTPUT\n  nSpeed : INT;\n  nSeen : INT;\nEND_VAR",
        "IF __ISVALIDREF(AxisRef) THEN\n  nSeen := AxisRef;\nEND_IF",
        methods,
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  n : INT := 42;\n  fb : FB_Axis(AxisRef := n);\nEND_VAR",
        "fb.SetSpeed(7);\nfb();",
        "",
    );
    let mut plc = compile_ok(&[("FB_Axis.TcPOU", &fb), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.fb.nSeen"), "42");
    assert_eq!(lit(&plc, "P.fb.nSpeed"), "7");
}

#[test]
fn an_fb_instance_output_is_copied_whole() {
    // lcls-twincat-motion's FB_MotionVirtualFrame: a METHOD's
    // `VAR_OUTPUT fbNewFramePositionVec3 : FB_Vec3` read with `=>`; only
    // its first variable came out.
    let prelude = "FUNCTION_BLOCK FB_V
VAR_INPUT fx : LREAL; fy : LREAL; fz : LREAL; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_R
VAR_OUTPUT o : FB_V; END_VAR
METHOD Rot
VAR_INPUT g : LREAL; END_VAR
VAR_OUTPUT m : FB_V; END_VAR
m.fx := g;
m.fy := g * 2.0;
m.fz := g * 3.0;
END_METHOD
o.fx := 1.0;
o.fy := 2.0;
o.fz := 3.0;
END_FUNCTION_BLOCK";
    check(
        prelude,
        "fb : FB_R; a : FB_V; b : FB_V; y : LREAL; z : LREAL; y2 : LREAL;",
        "fb.Rot(g := 5.0, m => a);\nfb(o => b);\ny := a.fy; z := a.fz; y2 := b.fy;",
        &[("P.y", "10.0"), ("P.z", "15.0"), ("P.y2", "2.0")],
    );
}

#[test]
fn a_strict_enumeration_takes_a_literal_that_is_one_of_its_values() {
    use crate::support::twincat::{compile_ok, declaration, pou, refused};
    // lcls-twincat-motion's FB_PositionStatePMPSND_Test: `eSetPos := 2;`
    // with `TARGET1 := 2` in a strict enumeration.
    let states = declaration(
        "DUT",
        "E_States",
        "{attribute 'qualified_only'}\n{attribute 'strict'}\nTYPE E_States :\n(\n  Unknown := 0,\n  OUT := 1,\n  TARGET1 := 2\n) UINT;\nEND_TYPE",
    );
    let main = |body: &str| {
        pou(
            "P",
            "PROGRAM P\nVAR e : E_States; ok : BOOL; END_VAR",
            body,
            "",
        )
    };
    let good = main("e := 2;\nok := e = E_States.TARGET1;");
    let mut plc = compile_ok(&[("E_States.TcDUT", &states), ("P.TcPOU", &good)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.ok"), "TRUE");
    // A literal that is no value of the type stays refused.
    let bad = main("e := 5;");
    let err = refused(&[("E_States.TcDUT", &states), ("P.TcPOU", &bad)]);
    assert!(err.contains("E301"), "{err}");
}
