//! Nesting-depth measures and limits. The parser never builds a node deeper
//! than these limits, so the AST handed to later stages is shallow enough for
//! them to walk recursively, and dropping it never overflows the stack,
//! whatever the input. The measures recurse, but only over trees already
//! bounded by the limits.

use crate::syntax::ast::*;

/// Maximum nesting of expressions (operators, parentheses, calls, members).
pub const MAX_EXPR_DEPTH: usize = 200;
/// Maximum nesting of statements (IF inside FOR inside ...).
pub const MAX_STMT_DEPTH: usize = 100;
/// Maximum nesting of initializers and of ARRAY types.
pub const MAX_INIT_DEPTH: usize = 64;

fn arg_expr(a: &Arg) -> &Expr {
    match a {
        Arg::Positional(e) | Arg::Input { value: e, .. } | Arg::Output { target: e, .. } => e,
    }
}

/// Nesting depth of an expression (a leaf is 1).
pub fn expr_depth(e: &Expr) -> usize {
    let children = match &e.kind {
        ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Direct(_) => 0,
        ExprKind::Member(b, _)
        | ExprKind::BitAccess(b, _)
        | ExprKind::Unary(_, b)
        | ExprKind::Paren(b) => expr_depth(b),
        ExprKind::Index(b, idx) => idx.iter().map(expr_depth).fold(expr_depth(b), usize::max),
        ExprKind::Binary(_, a, b) => expr_depth(a).max(expr_depth(b)),
        ExprKind::Call(c) => c
            .args
            .iter()
            .map(|a| expr_depth(arg_expr(a)))
            .fold(expr_depth(&c.callee), usize::max),
    };
    1 + children
}

fn list_depth(body: &[Stmt]) -> usize {
    body.iter().map(stmt_depth).max().unwrap_or(0)
}

/// Statement nesting depth (a simple statement is 1).
pub fn stmt_depth(s: &Stmt) -> usize {
    let inner = match &s.kind {
        StmtKind::If {
            branches,
            else_branch,
        } => branches
            .iter()
            .map(|(_, b)| list_depth(b))
            .chain(else_branch.iter().map(|b| list_depth(b)))
            .max()
            .unwrap_or(0),
        StmtKind::Case {
            arms, else_branch, ..
        } => arms
            .iter()
            .map(|a| list_depth(&a.body))
            .chain(else_branch.iter().map(|b| list_depth(b)))
            .max()
            .unwrap_or(0),
        StmtKind::For { body, .. }
        | StmtKind::While { body, .. }
        | StmtKind::Repeat { body, .. } => list_depth(body),
        _ => 0,
    };
    1 + inner
}

/// Nesting depth of an initializer (a plain expression is 1).
pub fn init_depth(i: &Initializer) -> usize {
    1 + match i {
        Initializer::Expr(_) => 0,
        Initializer::Array(elems, _) => elems
            .iter()
            .filter_map(|e| e.value.as_ref())
            .map(init_depth)
            .max()
            .unwrap_or(0),
        Initializer::Struct(fields, _) => {
            fields.iter().map(|(_, i)| init_depth(i)).max().unwrap_or(0)
        }
    }
}

/// Nesting depth of ARRAY types (a non-array type is 1).
pub fn type_depth(t: &TypeSpec) -> usize {
    match t {
        TypeSpec::Array { elem, .. } => 1 + type_depth(elem),
        _ => 1,
    }
}
