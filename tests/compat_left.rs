//! Issue #11, the compatibility items of the last round: a structure that
//! refers to itself through a reference, reading a VAR_IN_OUT from
//! outside, unary `-` on bit strings, `*_TO_BCD` typed from its context,
//! and the generic-function typing found by fuzzing. Programs written
//! here; expected values worked out by hand beside each.

use crate::support::access_diags;
use crate::support::plc;

use access_diags::{codes_at, error_codes};
use plc::{compile, first_fault, lit, program, run};

const NODE: &str = "TYPE Node : STRUCT next : REF_TO Node; v : INT; END_STRUCT END_TYPE";

#[test]
fn a_linked_list_of_structures_is_walked() {
    // 1 -> 2 -> 4 -> NULL: the walk sums 7 and counts 3 nodes.
    let src = program(
        NODE,
        "a, b, c : Node; r : REF_TO Node; s : INT; n : INT;",
        "a.v := 1; b.v := 2; c.v := 4; a.next := REF(b); b.next := REF(c);\n\
         s := 0; n := 0; r := REF(a);\n\
         WHILE r <> NULL DO s := s + r^.v; n := n + 1; r := r^.next; END_WHILE",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "s"), "7");
    assert_eq!(lit(&plc, "n"), "3");
}

#[test]
fn a_node_is_one_slot_of_reference_plus_its_fields() {
    // SIZEOF counts bytes: a reference is 8 bytes (one 64-bit slot) and
    // an INT 2, so a Node is 10 bytes whatever the list behind it holds.
    let src = program(NODE, "a : Node; n : UDINT;", "n := SIZEOF(a);");
    let mut plc = compile(&src);
    run(&mut plc, 1);
    let n: u64 = lit(&plc, "n").parse().unwrap();
    let r: u64 = {
        let s = program("", "r : REF_TO INT; n : UDINT;", "n := SIZEOF(r);");
        let mut p = compile(&s);
        run(&mut p, 1);
        lit(&p, "n").parse().unwrap()
    };
    assert_eq!(n, r + 2, "Node = reference + INT");
}

#[test]
fn structures_referring_to_each_other_and_through_pointers() {
    // y.a designates x, x.b points at y: x.b^.a^.n is x.n = 7.
    let types = "TYPE A : STRUCT b : POINTER TO B; n : INT; END_STRUCT; \
                 B : STRUCT a : REF_TO A; m : INT; END_STRUCT; END_TYPE";
    let src = program(
        types,
        "x : A; y : B; r : INT;",
        "x.n := 7; y.a := REF(x); x.b := ADR(y); r := x.b^.a^.n;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "r"), "7");
}

#[test]
fn a_structure_containing_itself_is_still_e204() {
    let src = program(
        "TYPE Bad : STRUCT inner : Bad; v : INT; END_STRUCT END_TYPE",
        "x : Bad;",
        "",
    );
    assert!(error_codes(&src).contains(&"E204".to_string()));
    // Through an array of itself too (no reference in between).
    let src = program(
        "TYPE Bad2 : STRUCT inner : ARRAY[0..1] OF Bad2; END_STRUCT END_TYPE",
        "x : Bad2;",
        "",
    );
    assert!(error_codes(&src).contains(&"E204".to_string()));
}

const INC: &str =
    "FUNCTION_BLOCK Inc VAR_IN_OUT io : INT; END_VAR io := io + 1; END_FUNCTION_BLOCK";

#[test]
fn an_in_out_read_from_outside_reads_the_bound_variable() {
    // Cycle 1: f increments v (3 -> 4), y reads v through f.io (4); then
    // v := 10 and z reads 10 (the variable itself, not a copy).
    // Cycle 2: v 10 -> 11, y = 11, z = 10.
    let src = program(
        INC,
        "f : Inc; v : INT := 3; w : INT := 100; y : INT; z : INT; u : INT;",
        "f(io := v); y := f.io; v := 10; z := f.io;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "y"), lit(&plc, "z")), ("4".into(), "10".into()));
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "y"), lit(&plc, "z")), ("11".into(), "10".into()));
}

#[test]
fn the_in_out_follows_the_last_call() {
    // Bound to v, then to w: f.io reads w (101) after the second call.
    let src = program(
        INC,
        "f : Inc; v : INT := 3; w : INT := 100; y : INT; z : INT;",
        "f(io := v); y := f.io; f(io := w); z := f.io;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!((lit(&plc, "y"), lit(&plc, "z")), ("4".into(), "101".into()));
}

#[test]
fn an_in_out_read_before_the_first_call_is_r030() {
    let src = program(INC, "f : Inc; y : INT;", "y := f.io;");
    let f = first_fault(&src);
    assert_eq!(f.code(), "R030");
    let (line, col) = plc::line_col(&f.location);
    assert_eq!((line, col), (6, 6), "{}", f.location);
}

#[test]
fn an_in_out_array_element_is_read_through_the_binding() {
    // The sorted-array pattern of OSCAT (_ARRAY_SORT.PT): the in-out is
    // an array; inst.pt[2] reads element 2 of the array bound.
    let fb = "FUNCTION_BLOCK Fill VAR_IN_OUT pt : ARRAY[1..3] OF INT; END_VAR \
              pt[2] := 42; END_FUNCTION_BLOCK";
    let src = program(
        fb,
        "f : Fill; a : ARRAY[1..3] OF INT; e : INT;",
        "f(pt := a); e := f.pt[2];",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "e"), "42");
}

#[test]
fn an_in_out_read_warns_w325_and_writing_it_from_outside_is_e422() {
    let src = program(INC, "f : Inc; v : INT; y : INT;", "f(io := v);\ny := f.io;");
    assert_eq!(codes_at(&src), vec!["W325@7:8"]);
    let src = program(INC, "f : Inc; v : INT;", "f(io := v);\nf.io := 1;");
    assert_eq!(codes_at(&src), vec!["W325@7:3", "E422@7:1"]);
}

#[test]
fn unary_minus_on_bit_strings_is_the_twos_complement_in_their_width() {
    // -1 in 8/16/32/64 bits: all ones; -16#8000 in a WORD is 16#8000
    // itself; -0 is 0; a constant folds the same way.
    let src = program(
        "",
        "b : BYTE := 1; w : WORD := 16#8000; d : DWORD := 1; l : LWORD := 1; z : WORD;\n\
         rb : BYTE; rw : WORD; rd : DWORD; rl : LWORD; rz : WORD; rc : DWORD;",
        "rb := -b; rw := -w; rd := -d; rl := -l; rz := -z; rc := -DWORD#2;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "rb"), "16#FF");
    assert_eq!(lit(&plc, "rw"), "16#8000");
    assert_eq!(lit(&plc, "rd"), "16#FFFFFFFF");
    assert_eq!(lit(&plc, "rl"), "16#FFFFFFFFFFFFFFFF");
    assert_eq!(lit(&plc, "rz"), "16#0");
    assert_eq!(lit(&plc, "rc"), "16#FFFFFFFE");
}

#[test]
fn unary_minus_on_a_bit_string_warns_w324_and_not_on_unsigned_integers() {
    let src = program("", "d : DWORD; r : DWORD;", "r := -d;");
    assert_eq!(codes_at(&src), vec!["W324@6:6"]);
    // Unsigned integers stay refused (E302), as before.
    let src = program("", "u : UINT; r : UINT;", "r := -u;");
    assert_eq!(error_codes(&src), vec!["E302"]);
}

#[test]
fn int_to_bcd_takes_the_width_of_its_target() {
    // 12 in BCD is 16#12 in any width; 1234 is 16#1234 in a WORD.
    let src = program(
        "",
        "i : INT := 12; k : INT := 1234; b : BYTE; w : WORD; d : DWORD;",
        "b := INT_TO_BCD(i); w := INT_TO_BCD(k); d := INT_TO_BCD(k);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "b"), "16#12");
    assert_eq!(lit(&plc, "w"), "16#1234");
    assert_eq!(lit(&plc, "d"), "16#1234");
    // The source's own width (WORD for INT) needs no warning; the others W347.
    let codes = codes_at(&src);
    assert_eq!(codes, vec!["W347@6:6", "W347@6:46"], "{codes:?}");
}

#[test]
fn int_to_bcd_into_a_byte_too_small_for_the_value_faults() {
    // 1234 has four BCD digits: it does not fit a BYTE.
    let src = program("", "k : INT := 1234; b : BYTE;", "b := INT_TO_BCD(k);");
    let f = first_fault(&src);
    assert!(f.code().starts_with('R'), "{}", f.code());
}

#[test]
fn sel_of_a_literal_only_limit_is_typed_from_the_other_operand() {
    // The fuzzing finding (docs/robustness.md): LIMIT(9, -1, -14) of
    // literals only, beside an INT, in every context the generator uses.
    // LIMIT(9, -1, -14) = MIN(MAX(9, -1), -14) = -14.
    let src = program(
        "",
        "b : BOOL; i : INT := 5; r : LREAL; j : INT; k : INT;",
        "r := INT_TO_LREAL(SEL(b, LIMIT(9, -1, -14), i));\n\
         i := SEL(b, LIMIT(9, -1, -14), i);\n\
         j := SEL(TRUE, LIMIT(9, -1, -14), i) * 2;\n\
         k := ABS(SEL(TRUE, i, LIMIT(9, -1, -14)));",
    );
    assert_eq!(error_codes(&src), Vec::<String>::new());
    let mut plc = compile(&src);
    run(&mut plc, 1);
    // b is FALSE: SEL gives IN0, the LIMIT, -14.
    assert_eq!(lit(&plc, "r"), "-14.0");
    assert_eq!(lit(&plc, "i"), "-14");
    assert_eq!(lit(&plc, "j"), "-28");
    assert_eq!(lit(&plc, "k"), "14");
}

const HOLDER: &str = "FUNCTION_BLOCK Holder VAR x : INT := 5; r : REF_TO INT := REF(x); END_VAR \
VAR_OUTPUT q : INT; END_VAR q := r^; x := x + 1; END_FUNCTION_BLOCK\n\
FUNCTION Twice : INT VAR a : INT := 40; p : POINTER TO INT := ADR(a); END_VAR \
p^ := p^ + 2; Twice := a; END_FUNCTION";

#[test]
fn reference_initial_values_are_evaluated_before_the_body() {
    // The program's r and p designate its x (5, then 6, 7 after x := x + 1);
    // the FB's r its own x; the function's p its fresh a at every call
    // (40 + 2 = 42 every time, not 42, 44, ...); NULL stays NULL.
    let src = program(
        HOLDER,
        "x : INT := 5; r : REF_TO INT := REF(x); p : POINTER TO INT := ADR(x); \
         n : REF_TO INT := NULL; y : INT; z : INT; h : Holder; hq : INT; f : INT; \
         isnull : BOOL;",
        "y := r^; z := p^; x := x + 1; h(); hq := h.q; f := Twice(); isnull := n = NULL;",
    );
    let mut plc = compile(&src);
    for expected in ["5", "6", "7"] {
        run(&mut plc, 1);
        assert_eq!(lit(&plc, "y"), expected);
        assert_eq!(lit(&plc, "z"), expected);
        assert_eq!(lit(&plc, "hq"), expected);
        assert_eq!(lit(&plc, "f"), "42");
        assert_eq!(lit(&plc, "isnull"), "TRUE");
    }
}

#[test]
fn a_reference_set_by_the_body_is_not_set_again_by_its_initial_value() {
    // Once per initialisation: after r := REF(b) the next cycle reads b
    // (an initial value evaluated at every call would read a again).
    let src = program(
        "",
        "a : INT := 1; b : INT := 2; r : REF_TO INT := REF(a); y : INT;",
        "y := r^; r := REF(b);",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "y"), "1");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "y"), "2");
}

#[test]
fn a_temporary_reference_is_initialised_at_every_call() {
    // VAR_TEMP is fresh at every call: its REF(g) is evaluated each time.
    let fb = "FUNCTION_BLOCK U VAR g : INT := 3; END_VAR VAR_TEMP t : REF_TO INT := REF(g); \
              END_VAR VAR_OUTPUT q : INT; END_VAR q := t^; g := g + 1; END_FUNCTION_BLOCK";
    let src = program(fb, "u : U; q : INT;", "u(); q := u.q;");
    let mut plc = compile(&src);
    for expected in ["3", "4", "5"] {
        run(&mut plc, 1);
        assert_eq!(lit(&plc, "q"), expected);
    }
}

#[test]
fn reference_initial_values_where_no_body_runs_them_are_refused_by_name() {
    let input = "FUNCTION_BLOCK T VAR_INPUT i : REF_TO INT := REF(g); END_VAR \
                 VAR g : INT; END_VAR END_FUNCTION_BLOCK";
    assert_eq!(error_codes(&program(input, "t : T;", "")), vec!["E429"]);
    let global = "VAR_GLOBAL x : INT; g : REF_TO INT := REF(x); END_VAR";
    assert_eq!(error_codes(&program(global, "y : INT;", "")), vec!["E430"]);
    let field = "VAR_GLOBAL x : INT; END_VAR TYPE S : STRUCT r : REF_TO INT := REF(x); \
                 END_STRUCT END_TYPE";
    assert_eq!(error_codes(&program(field, "s : S;", "")), vec!["E430"]);
    // NULL is every reference's initial value: accepted anywhere.
    let ok = "VAR_GLOBAL g : REF_TO INT := NULL; END_VAR TYPE S : STRUCT r : REF_TO INT := NULL; \
              END_STRUCT END_TYPE";
    assert_eq!(
        error_codes(&program(ok, "s : S;", "")),
        Vec::<String>::new()
    );
}

#[test]
fn an_online_change_evaluates_the_reference_initial_values_again() {
    // References start again from NULL after an online change (semantics
    // §16); the initial value is evaluated again at the next call, so the
    // program goes on reading x through r.
    let src = program(
        "",
        "x : INT := 5; r : REF_TO INT := REF(x); y : INT;",
        "y := r^; x := x + 1;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 2);
    let new = plcrun::Plc::compile_files(&[("test.st", src.as_str())], &plcrun::Options::default())
        .expect("compiles");
    plc.online_change(new).expect("online change applies");
    run(&mut plc, 1);
    // x was 7 after two cycles and kept: y reads 7.
    assert_eq!(lit(&plc, "y"), "7");
}

#[test]
fn a_literal_too_large_for_the_other_operand_widens_the_operation() {
    // OSCAT's CALENDAR_CALC: off * 60000 with off : INT is done in DINT
    // (2 * 60000 = 120000, more than an INT holds); W348.
    let src = program(
        "",
        "off : INT := 2; d : DINT; big : BOOL;",
        "d := off * 60000 + 5; big := off < 40000;",
    );
    assert_eq!(codes_at(&src), vec!["W348@6:6", "W348@6:30"]);
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "d"), "120005");
    assert_eq!(lit(&plc, "big"), "TRUE");
    // A literal that fits keeps the IEC typing (INT, no warning); an INT
    // result assigned from the widened DINT is refused as any DINT would be.
    let src = program("", "off : INT := 2; i : INT;", "i := off * 600;");
    assert_eq!(codes_at(&src), Vec::<String>::new());
    let src = program("", "off : INT := 2; i : INT;", "i := off * 60000;");
    assert_eq!(error_codes(&src), vec!["E301"]);
}

#[test]
fn an_il_call_of_a_function_returning_a_structure_is_refused_by_name() {
    // Before, the CR was left at 0 and `ST p` stored 0 into p.x silently.
    let src = "TYPE Pt : STRUCT x : INT; y : INT; END_STRUCT END_TYPE\n\
               FUNCTION MakePt : Pt\nVAR_INPUT a : INT; END_VAR\nMakePt.x := a; MakePt.y := a * 2;\nEND_FUNCTION\n\
               PROGRAM P\nVAR p : Pt; END_VAR\n  LD 3\n  MakePt\n  ST p\nEND_PROGRAM\n";
    assert_eq!(codes_at(src), vec!["E431@9:3"]);
    // ST calls it.
    let st = program(
        "TYPE Pt : STRUCT x : INT; y : INT; END_STRUCT END_TYPE\n\
         FUNCTION MakePt : Pt VAR_INPUT a : INT; END_VAR MakePt.x := a; MakePt.y := a * 2; END_FUNCTION",
        "p : Pt; y : INT;",
        "p := MakePt(3); y := p.y;",
    );
    let mut plc = compile(&st);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "y"), "6");
}
