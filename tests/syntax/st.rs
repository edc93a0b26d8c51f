//! Structured Text: statements, expressions, declarations, types, configurations.

use super::common::*;
use plcrun::syntax::ast::*;
use rstest::rstest;

#[rstest]
#[case("1 + 2 * 3", "(+ 1 (* 2 3))")]
#[case("1 - 2 - 3", "(- (- 1 2) 3)")]
#[case("a / b / c", "(/ (/ a b) c)")]
#[case("-2 ** 2", "(- (** 2 2))")]
#[case("-x ** 2", "(- (** x 2))")]
#[case("2 ** 3 ** 2", "(** (** 2 3) 2)")]
#[case("NOT a AND b", "(AND (NOT a) b)")]
#[case("a OR b AND c", "(OR a (AND b c))")]
#[case("a XOR b OR c", "(OR (XOR a b) c)")]
#[case("a OR b XOR c AND d", "(OR a (XOR b (AND c d)))")]
#[case("a & b", "(AND a b)")]
#[case("a = b AND c <> d", "(AND (= a b) (<> c d))")]
#[case("a < b = c > d", "(= (< a b) (> c d))")]
#[case("a + b < c * d", "(< (+ a b) (* c d))")]
#[case("a MOD b + c", "(+ (MOD a b) c)")]
#[case("(1 + 2) * 3", "(* (paren (+ 1 2)) 3)")]
#[case("-5", "-5")]
#[case("- 2.5", "-2.5")]
#[case("-T#2ms", "T#-2ms")]
#[case("-a", "(- a)")]
#[case("+a", "(+ a)")]
#[case("a * -b", "(* a (- b))")]
#[case("NOT NOT a", "(NOT (NOT a))")]
#[case("f(a, b)", "f(a, b)")]
#[case("f()", "f()")]
#[case(
    "LIMIT(MN := 0, IN := x, MX := 10)",
    "LIMIT(MN := 0, IN := x, MX := 10)"
)]
#[case("a.b[2].c", "a.b[2].c")]
#[case("arr[i, j + 1]", "arr[i, (+ j 1)]")]
#[case("inst.Q", "inst.Q")]
#[case("w.3", "w.%X3")]
#[case("s.w.15", "s.w.%X15")]
#[case("%IX0.1 AND %MX2.7", "(AND %IX0.1 %MX2.7)")]
#[case("ATT.T >= t#10s", "(>= ATT.T T#10s)")]
#[case("f(x).y", "f(x).y")]
#[case("trig[i].Q", "trig[i].Q")]
#[case("SHR(lfsr, 1) XOR 16#B400", "(XOR SHR(lfsr, 1) 46080)")]
#[case("INT#-3 + WORD#16#F", "(+ INT#-3 WORD#15)")]
#[case("Color#Red = c", "(= Color#Red c)")]
fn expressions(#[case] src: &str, #[case] expected: &str) {
    assert_eq!(expr(src), expected);
}

#[test]
fn assignment_and_call_statements() {
    let s = stmts(
        "x := 1; f(1, 2); inst(IN := a, PT := T#1s); arr[i](CLK := b); a.b(x := 1, Q => y, NOT Q2 => z); \
         t(EN := TRUE, ENO => ok);",
    );
    assert_eq!(s.len(), 6);
    let calls: Vec<String> = s
        .iter()
        .filter_map(|s| match &s.kind {
            StmtKind::Call(c) => Some(format!("{}({})", sx(&c.callee), args(&c.args))),
            _ => None,
        })
        .collect();
    assert_eq!(
        calls,
        [
            "f(1, 2)",
            "inst(IN := a, PT := T#1s)",
            "arr[i](CLK := b)",
            "a.b(x := 1, Q => y, NOT Q2 => z)",
            "t(EN := TRUE, ENO => ok)"
        ]
    );
}

#[test]
fn if_elsif_else() {
    let s =
        stmts("IF a THEN x := 1; ELSIF b THEN x := 2; ELSIF c THEN ; ELSE x := 3; y := 4; END_IF;");
    assert_eq!(
        s.len(),
        1,
        "the `;` after END_IF is not a separate statement"
    );
    let StmtKind::If {
        branches,
        else_branch,
    } = &s[0].kind
    else {
        panic!()
    };
    assert_eq!(branches.len(), 3);
    assert_eq!(sx(&branches[1].0), "b");
    assert_eq!(branches[2].1[0].kind, StmtKind::Empty);
    assert_eq!(else_branch.as_ref().unwrap().len(), 2);
}

#[test]
fn if_without_trailing_semicolon_and_empty_branches() {
    let s = stmts("IF a THEN END_IF x := 1;");
    assert_eq!(s.len(), 2);
}

#[test]
fn case_forms() {
    let s = stmts(
        "CASE n OF 1: x := 1; 2, 3: x := 2; y := 3; 4..6, 8: ; Red: x := 4; -1: x := 5; Color#Blue: ; ELSE x := 0; END_CASE;",
    );
    let StmtKind::Case {
        selector,
        arms,
        else_branch,
    } = &s[0].kind
    else {
        panic!()
    };
    assert_eq!(sx(selector), "n");
    assert_eq!(arms.len(), 6);
    let labels: Vec<String> = arms
        .iter()
        .map(|a| {
            a.labels
                .iter()
                .map(|l| match l {
                    CaseLabel::Value(v) => sx(v),
                    CaseLabel::Range(a, b) => format!("{}..{}", sx(a), sx(b)),
                })
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect();
    assert_eq!(labels, ["1", "2,3", "4..6,8", "Red", "-1", "Color#Blue"]);
    assert_eq!(arms[1].body.len(), 2);
    assert_eq!(else_branch.as_ref().unwrap().len(), 1);
}

#[test]
fn loops_and_jumps() {
    let s = stmts(
        "FOR i := 1 TO 10 BY 2 DO x := x + i; IF x > 5 THEN EXIT; END_IF; END_FOR; \
         FOR i := 10 TO 0 DO CONTINUE; END_FOR; \
         WHILE i < 5 DO i := i + 1; END_WHILE; \
         REPEAT i := i - 1; UNTIL i = 0 END_REPEAT; RETURN; ;",
    );
    let kinds: Vec<&'static str> = s
        .iter()
        .map(|s| match &s.kind {
            StmtKind::For { by: Some(_), .. } => "for-by",
            StmtKind::For { by: None, .. } => "for",
            StmtKind::While { .. } => "while",
            StmtKind::Repeat { .. } => "repeat",
            StmtKind::Return => "return",
            StmtKind::Empty => "empty",
            _ => "other",
        })
        .collect();
    assert_eq!(
        kinds,
        ["for-by", "for", "while", "repeat", "return", "empty"]
    );
    let StmtKind::For { var, body, .. } = &s[0].kind else {
        panic!()
    };
    assert!(
        matches!(&var.kind, ExprKind::Name(n) if n.name == "i"),
        "{var:?}"
    );
    let StmtKind::If { branches, .. } = &body[1].kind else {
        panic!()
    };
    assert_eq!(branches[0].1[0].kind, StmtKind::Exit);
    let StmtKind::For { body, .. } = &s[1].kind else {
        panic!()
    };
    assert_eq!(body[0].kind, StmtKind::Continue);
}

#[test]
fn keywords_are_case_insensitive() {
    let s = stmts("if A then b := TrUe; end_if; Case x OF 1: ; eNd_CaSe");
    assert_eq!(s.len(), 2);
}

#[test]
fn comments_pragmas_and_spans() {
    let src = "PROGRAM p // line comment\n(* block (* not nested *)\nVAR x : INT; END_VAR\n x := 1; (* é ☃ *)\nEND_PROGRAM";
    let unit = parse_ok(src);
    let p = pou(&unit);
    assert_eq!(p.name.name, "p");
    let Body::St(s) = &p.body else { panic!() };
    assert_eq!(
        &src[s[0].span.start as usize..s[0].span.end as usize],
        "x := 1;"
    );
    assert_eq!(p.span.start, 0);
    assert_eq!(p.span.end as usize, src.len());
}

#[test]
fn edition_3_slash_star_comments_are_comments() {
    // `/* */` in ST, in IL (where a multi-line one is a line break) and
    // between the operands of an expression; `(* /* *)` stays one comment.
    let src = "PROGRAM p /* a\ncomment */ VAR x : INT; END_VAR\n\
               x := 1 /* one */ + /* two */ 2; (* /* *) x := x + 1; // /*\nEND_PROGRAM";
    let unit = parse_ok(src);
    let Body::St(s) = &pou(&unit).body else {
        panic!()
    };
    assert_eq!(s.len(), 2);
    let il = "FUNCTION_BLOCK f VAR_INPUT a : BOOL; END_VAR VAR_OUTPUT q : BOOL; END_VAR\n\
              LD a /* load */\n/* a\ntwo-line comment */\nST q\nEND_FUNCTION_BLOCK";
    let unit = parse_ok(il);
    assert!(matches!(pou(&unit).body, Body::Il(_)));
}

#[test]
fn pou_kinds() {
    let unit = parse_ok(
        "FUNCTION f : INT VAR_INPUT a : INT; END_VAR f := a; END_FUNCTION \
         FUNCTION g VAR_INPUT a : INT; END_VAR END_FUNCTION \
         FUNCTION h : STRING[20] h := 'x'; END_FUNCTION \
         FUNCTION_BLOCK fb VAR_INPUT i : BOOL; END_VAR VAR_OUTPUT q : BOOL; END_VAR VAR_IN_OUT io : INT; END_VAR \
           VAR_TEMP t : INT; END_VAR VAR_EXTERNAL e : INT; END_VAR q := i; END_FUNCTION_BLOCK \
         PROGRAM main VAR CONSTANT c : INT := 5; END_VAR VAR RETAIN r : INT; END_VAR \
           VAR NON_RETAIN CONSTANT n : INT := 1; END_VAR END_PROGRAM",
    );
    let pous: Vec<&Pou> = unit
        .items
        .iter()
        .map(|i| match i {
            Item::Pou(p) => p,
            _ => panic!(),
        })
        .collect();
    assert_eq!(pous.len(), 5);
    assert_eq!(pous[0].kind, PouKind::Function);
    assert!(matches!(&pous[0].return_type, Some(TypeSpec::Named(n)) if n.name == "INT"));
    assert!(pous[1].return_type.is_none());
    assert!(matches!(
        &pous[2].return_type,
        Some(TypeSpec::String {
            wide: false,
            len: Some(_),
            ..
        })
    ));
    assert_eq!(pous[3].kind, PouKind::FunctionBlock);
    let kinds: Vec<VarKind> = pous[3].var_blocks.iter().map(|b| b.kind).collect();
    assert_eq!(
        kinds,
        [
            VarKind::Input,
            VarKind::Output,
            VarKind::InOut,
            VarKind::Temp,
            VarKind::External
        ]
    );
    let b = &pous[4].var_blocks;
    assert!(b[0].constant && b[0].retain.is_none());
    assert_eq!(b[1].retain, Some(Retain::Retain));
    assert!(b[2].constant && b[2].retain == Some(Retain::NonRetain));
}

fn decl_types(src: &str) -> Vec<VarDecl> {
    let unit = parse_ok(&format!("PROGRAM p VAR {src} END_VAR END_PROGRAM"));
    pou(&unit).var_blocks[0].decls.clone()
}

#[test]
fn var_declarations() {
    let d = decl_types(
        "a, b : INT := 5; sw AT %I0.0.0.0.0: BOOL; s : STRING; s2 : STRING(10); w : WSTRING[5]; \
         arr : ARRAY[1..3] OF INT := [1, 2, 3(0)]; m : ARRAY[0..N-1, 1..2] OF ARRAY[0..1] OF BOOL; \
         r : INT (0..100) := 5; e : (Red, Green := 2, Blue) := Red; te : INT (A := 1, B := 5); \
         pt : Point := (x := 1, y := (z := 2)); big : ARRAY[0..9] OF INT := [2(1), 3(), 5]; \
         t1 : TON; dt1 : TIME := T#5S;",
    );
    assert_eq!(d[0].names.len(), 2);
    assert!(matches!(&d[0].init, Some(Initializer::Expr(_))));
    assert_eq!(d[1].location.as_ref().unwrap().fields, [0, 0, 0, 0, 0]);
    assert!(matches!(
        &d[2].ty,
        TypeSpec::String {
            wide: false,
            len: None,
            ..
        }
    ));
    assert!(matches!(&d[3].ty, TypeSpec::String { len: Some(_), .. }));
    assert!(matches!(&d[4].ty, TypeSpec::String { wide: true, .. }));
    let Some(Initializer::Array(elems, _)) = &d[5].init else {
        panic!()
    };
    assert_eq!(elems.len(), 3);
    assert!(elems[2].repeat.is_some());
    let TypeSpec::Array { ranges, elem, .. } = &d[6].ty else {
        panic!()
    };
    assert_eq!(ranges.len(), 2);
    assert_eq!(sx(&ranges[0].1), "(- N 1)");
    assert!(matches!(**elem, TypeSpec::Array { .. }));
    assert!(matches!(&d[7].ty, TypeSpec::Subrange { base, .. } if base.name == "INT"));
    let TypeSpec::Enum {
        base: None, values, ..
    } = &d[8].ty
    else {
        panic!()
    };
    assert_eq!(values.len(), 3);
    assert!(values[1].1.is_some());
    assert!(matches!(&d[9].ty, TypeSpec::Enum { base: Some(_), .. }));
    let Some(Initializer::Struct(fields, _)) = &d[10].init else {
        panic!()
    };
    assert!(matches!(&fields[1].1, Initializer::Struct(..)));
    let Some(Initializer::Array(elems, _)) = &d[11].init else {
        panic!()
    };
    assert!(elems[1].repeat.is_some() && elems[1].value.is_none());
    assert!(matches!(&d[12].ty, TypeSpec::Named(n) if n.name == "TON"));
}

#[test]
fn type_declarations() {
    let unit = parse_ok(
        "TYPE \
           MyInt : INT; \
           Color : (Red, Green, Blue) := Green; \
           Level : INT (Low := 1, High := 5); \
           Pct : INT (0..100) := 50; \
           Vec3 : ARRAY[1..3] OF REAL := [3(0.0)]; \
           Name : STRING[32]; \
           Point : STRUCT x : REAL; y : REAL := 1.0; tags : ARRAY[0..1] OF BOOL; END_STRUCT; \
           Nested : STRUCT p : Point; END_STRUCT \
         END_TYPE",
    );
    let Item::Types(t) = &unit.items[0] else {
        panic!()
    };
    assert_eq!(t.len(), 8);
    assert!(matches!(&t[0].ty, TypeSpec::Named(_)));
    assert!(matches!(&t[1].ty, TypeSpec::Enum { .. }) && t[1].init.is_some());
    assert!(matches!(&t[2].ty, TypeSpec::Enum { base: Some(_), .. }));
    assert!(matches!(&t[3].ty, TypeSpec::Subrange { .. }));
    assert!(matches!(&t[4].ty, TypeSpec::Array { .. }));
    assert!(matches!(&t[5].ty, TypeSpec::String { .. }));
    let TypeSpec::Struct { fields, .. } = &t[6].ty else {
        panic!()
    };
    assert_eq!(fields.len(), 3);
    assert!(matches!(&t[7].ty, TypeSpec::Struct { .. }));
}

#[test]
fn configuration_with_resource() {
    let unit = parse_ok(
        "CONFIGURATION plant \
           VAR_GLOBAL g : INT; END_VAR \
           RESOURCE cpu ON PLC \
             VAR_GLOBAL RETAIN r : BOOL; END_VAR \
             TASK fast (INTERVAL := T#10ms, PRIORITY := 1); \
             TASK trig (SINGLE := start, PRIORITY := 2); \
             PROGRAM p1 WITH fast : Main (x := g, y => g); \
             PROGRAM p2 : Other; \
           END_RESOURCE \
         END_CONFIGURATION",
    );
    let Item::Configuration(c) = &unit.items[0] else {
        panic!()
    };
    assert_eq!(c.name.name, "plant");
    assert_eq!(c.globals.len(), 1);
    let r = &c.resources[0];
    assert_eq!(r.on.as_ref().unwrap().name, "PLC");
    assert_eq!(r.globals.len(), 1);
    assert_eq!(r.tasks.len(), 2);
    assert_eq!(r.tasks[0].settings[0].0.name, "INTERVAL");
    assert_eq!(sx(&r.tasks[0].settings[0].1), "T#10ms");
    assert_eq!(r.programs[0].task.as_ref().unwrap().name, "fast");
    assert_eq!(r.programs[0].type_name.name, "Main");
    assert_eq!(args(&r.programs[0].args), "x := g, y => g");
    assert!(r.programs[1].task.is_none());
}

#[test]
fn configuration_without_resource_gets_implicit_one() {
    let unit = parse_ok(
        "CONFIGURATION cfg TASK t (INTERVAL := T#20ms); PROGRAM inst WITH t : Main; END_CONFIGURATION",
    );
    let Item::Configuration(c) = &unit.items[0] else {
        panic!()
    };
    assert_eq!(c.resources.len(), 1);
    assert_eq!(c.resources[0].name.name, "cfg");
    assert_eq!(c.resources[0].tasks.len(), 1);
    assert_eq!(c.resources[0].programs.len(), 1);
}

#[test]
fn top_level_globals() {
    let unit =
        parse_ok("VAR_GLOBAL g1 : INT := 3; g2 AT %QX0.0 : BOOL; END_VAR PROGRAM p END_PROGRAM");
    assert!(matches!(&unit.items[0], Item::Globals(b) if b.decls.len() == 2));
    assert!(matches!(&unit.items[1], Item::Pou(_)));
}
