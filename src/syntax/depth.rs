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

/// Most operands in one expression counted along its longest path from
/// the root (a flat chain `a OR b OR ... ` of that many terms): later stages
/// walk expressions recursively, and this bounds how deep they go. The
/// value lets a syntax tree at the limit be dropped (a recursion per level)
/// on a 2 MiB stack even in a debug build (14 000 measured fine there,
/// 20 000 not).
pub const MAX_EXPR_TERMS: usize = 12_000;

/// Nesting depth of an expression (a leaf is 1). The left operand of a
/// binary operator does not nest: `a + b + c` is a flat chain of depth 2
/// however long, while `a + (b + (c + d))` nests. The chain's left spine is
/// walked in a loop, so a long chain costs no stack here.
pub fn expr_depth(e: &Expr) -> usize {
    let mut deepest = 0;
    let mut node = e;
    while let ExprKind::Binary(_, left, right) = &node.kind {
        deepest = deepest.max(1 + expr_depth(right));
        node = left;
    }
    deepest.max(nested_depth(node))
}

/// Height of an expression tree (a leaf is 1), without recursion: the
/// number of nested calls a recursive walk over it makes.
pub fn expr_height(e: &Expr) -> usize {
    // Most operands are small: measure them without allocating.
    if let Some(h) = small_height(e, 8) {
        return h;
    }
    let mut highest = 0;
    let mut stack = vec![(e, 1usize)];
    while let Some((node, h)) = stack.pop() {
        highest = highest.max(h);
        match &node.kind {
            ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Direct(_) => {}
            ExprKind::Member(b, _)
            | ExprKind::BitAccess(b, _)
            | ExprKind::Unary(_, b)
            | ExprKind::Paren(b)
            | ExprKind::Deref(b) => stack.push((b, h + 1)),
            ExprKind::Index(b, idx) => {
                stack.push((b, h + 1));
                stack.extend(idx.iter().map(|i| (i, h + 1)));
            }
            ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => {
                stack.push((a, h + 1));
                stack.push((b, h + 1));
            }
            ExprKind::Call(c) => {
                stack.push((&c.callee, h + 1));
                stack.extend(c.args.iter().map(|a| (arg_expr(a), h + 1)));
            }
        }
    }
    highest
}

/// The height of `e` if it is at most `budget`, by a recursion at most
/// `budget` deep; `None` for a higher tree.
fn small_height(e: &Expr, budget: usize) -> Option<usize> {
    let budget = budget.checked_sub(1)?;
    let below = |c: &Expr| small_height(c, budget);
    let children = match &e.kind {
        ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Direct(_) => 0,
        ExprKind::Member(b, _)
        | ExprKind::BitAccess(b, _)
        | ExprKind::Unary(_, b)
        | ExprKind::Paren(b)
        | ExprKind::Deref(b) => below(b)?,
        ExprKind::Index(b, idx) => {
            let mut h = below(b)?;
            for i in idx {
                h = h.max(below(i)?);
            }
            h
        }
        ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => below(a)?.max(below(b)?),
        ExprKind::Call(c) => {
            let mut h = below(&c.callee)?;
            for a in &c.args {
                h = h.max(below(arg_expr(a))?);
            }
            h
        }
    };
    Some(1 + children)
}

/// [`expr_depth`] of a node that is not a binary operation.
fn nested_depth(e: &Expr) -> usize {
    let children = match &e.kind {
        ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Direct(_) => 0,
        ExprKind::Member(b, _)
        | ExprKind::BitAccess(b, _)
        | ExprKind::Unary(_, b)
        | ExprKind::Paren(b)
        | ExprKind::Deref(b) => expr_depth(b),
        ExprKind::Index(b, idx) => idx.iter().map(expr_depth).fold(expr_depth(b), usize::max),
        ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => expr_depth(a).max(expr_depth(b)),
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
        StmtKind::Try {
            body,
            catch,
            finally,
        } => std::iter::once(body)
            .chain(catch.iter().map(|(_, c)| c))
            .chain(finally)
            .map(|b| list_depth(b))
            .max()
            .unwrap_or(0),
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
