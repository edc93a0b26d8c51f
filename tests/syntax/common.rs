//! Helpers shared by the front-end tests.

use plcrun::syntax::ast::*;
use plcrun::{Diagnostics, FileId, SourceFile, format_duration};

/// Parses `src`, returning the unit and `(code, line, column)` of every diagnostic.
pub fn parse_all(src: &str) -> (CompilationUnit, Vec<(String, usize, usize)>) {
    let mut d = Diagnostics::new();
    let unit = plcrun::syntax::parse(FileId(0), src, &mut d);
    let file = SourceFile::new("t", src);
    let codes = d
        .sorted()
        .into_iter()
        .map(|x| {
            let (l, c) = file.line_col(x.span.start);
            (x.code.to_string(), l, c)
        })
        .collect();
    (unit, codes)
}

/// Parses `src` and asserts there is no diagnostic at all.
pub fn parse_ok(src: &str) -> CompilationUnit {
    let mut d = Diagnostics::new();
    let unit = plcrun::syntax::parse(FileId(0), src, &mut d);
    let msgs: Vec<String> = d
        .iter()
        .map(|x| format!("{} {:?} {}", x.code, x.span, x.message))
        .collect();
    assert!(
        msgs.is_empty(),
        "unexpected diagnostics: {msgs:#?}\nsource:\n{src}"
    );
    unit
}

/// The messages of all diagnostics.
pub fn messages(src: &str) -> Vec<String> {
    let mut d = Diagnostics::new();
    plcrun::syntax::parse(FileId(0), src, &mut d);
    d.sorted()
        .into_iter()
        .map(|x| format!("{}: {}", x.code, x.message))
        .collect()
}

/// The first POU of a unit.
pub fn pou(unit: &CompilationUnit) -> &Pou {
    unit.items
        .iter()
        .find_map(|i| match i {
            Item::Pou(p) => Some(p),
            _ => None,
        })
        .expect("a POU")
}

/// Parses ST statements wrapped in a PROGRAM.
pub fn stmts(body: &str) -> Vec<Stmt> {
    let unit = parse_ok(&format!("PROGRAM p\n{body}\nEND_PROGRAM\n"));
    match &pou(&unit).body {
        Body::St(s) => s.clone(),
        other => panic!("expected an ST body, got {other:?}"),
    }
}

/// Parses one expression (as the value of an assignment) into an S-expression.
pub fn expr(src: &str) -> String {
    match &stmts(&format!("x := {src};"))[0].kind {
        StmtKind::Assign { value, .. } => sx(value),
        other => panic!("{other:?}"),
    }
}

/// Parses IL lines wrapped in a PROGRAM.
pub fn il(body: &str) -> Vec<IlLine> {
    let unit = parse_ok(&format!(
        "PROGRAM p\nVAR x : BOOL; END_VAR\n{body}\nEND_PROGRAM\n"
    ));
    match &pou(&unit).body {
        Body::Il(lines) => lines.clone(),
        other => panic!("expected an IL body, got {other:?}"),
    }
}

fn bin(op: BinaryOp) -> &'static str {
    match op {
        BinaryOp::Pow => "**",
        BinaryOp::Mul => "*",
        BinaryOp::Div => "/",
        BinaryOp::Mod => "MOD",
        BinaryOp::Add => "+",
        BinaryOp::Sub => "-",
        BinaryOp::Lt => "<",
        BinaryOp::Gt => ">",
        BinaryOp::Le => "<=",
        BinaryOp::Ge => ">=",
        BinaryOp::Eq => "=",
        BinaryOp::Ne => "<>",
        BinaryOp::And => "AND",
        BinaryOp::Xor => "XOR",
        BinaryOp::Or => "OR",
        BinaryOp::AndThen => "AND_THEN",
        BinaryOp::OrElse => "OR_ELSE",
    }
}

/// A literal in a compact form.
pub fn lit(l: &Literal) -> String {
    let v = match &l.value {
        LiteralValue::Int(v) => v.to_string(),
        LiteralValue::Real(v) => format!("{v:?}"),
        LiteralValue::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        LiteralValue::Duration { nanos, long } => {
            format_duration(*nanos, if *long { "LT#" } else { "T#" })
        }
        LiteralValue::Date { nanos, .. } => format!("D#{nanos}"),
        LiteralValue::TimeOfDay { nanos, .. } => format!("TOD#{nanos}"),
        LiteralValue::DateTime { nanos, .. } => format!("DT#{nanos}"),
        LiteralValue::String { value, wide } => {
            if *wide {
                format!("\"{value}\"")
            } else {
                format!("'{value}'")
            }
        }
        LiteralValue::EnumValue(v) => v.name.clone(),
    };
    match &l.type_prefix {
        Some(p) => format!("{}#{v}", p.name),
        None => v,
    }
}

fn arg(a: &Arg) -> String {
    match a {
        Arg::Positional(e) => sx(e),
        Arg::Input { name, value } => format!("{} := {}", name.name, sx(value)),
        Arg::Output {
            name,
            negated,
            target,
        } => format!(
            "{}{} => {}",
            if *negated { "NOT " } else { "" },
            name.name,
            sx(target)
        ),
    }
}

/// An argument list.
pub fn args(a: &[Arg]) -> String {
    a.iter().map(arg).collect::<Vec<_>>().join(", ")
}

/// Fully parenthesised S-expression of an expression (parentheses written
/// by the user are shown as `(paren ...)`).
pub fn sx(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Literal(l) => lit(l),
        ExprKind::Name(i) => i.name.clone(),
        ExprKind::Member(b, m) => format!("{}.{}", sx(b), m.name),
        ExprKind::BitAccess(b, n) => format!("{}.%X{n}", sx(b)),
        ExprKind::Index(b, i) => format!(
            "{}[{}]",
            sx(b),
            i.iter().map(sx).collect::<Vec<_>>().join(", ")
        ),
        ExprKind::Direct(d) => d.text.clone(),
        ExprKind::Unary(op, x) => {
            let o = match op {
                UnaryOp::Neg => "-",
                UnaryOp::Plus => "+",
                UnaryOp::Not => "NOT",
            };
            format!("({o} {})", sx(x))
        }
        ExprKind::Binary(op, a, b) => format!("({} {} {})", bin(*op), sx(a), sx(b)),
        ExprKind::Call(c) => format!("{}({})", sx(&c.callee), args(&c.args)),
        ExprKind::Paren(x) => format!("(paren {})", sx(x)),
        ExprKind::Deref(x) => format!("(deref {})", sx(x)),
        ExprKind::Assign(t, v) => format!("(:= {} {})", sx(t), sx(v)),
    }
}
