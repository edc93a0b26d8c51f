//! The names written in a METHOD's declarations — array bounds, string
//! lengths, subrange limits, initial values — are looked up in the method
//! first, as in its body: `VAR CONSTANT N : INT := 4; a : ARRAY[1..N] OF
//! INT := [N, N]; END_VAR`. The method's variables become hidden variables
//! of its FB (`Origin__Method__var`, lower.rs), so each of those names is
//! rewritten to its hidden name before the declaration phase reads it;
//! other names (the FB's, globals, enumeration values) are left as written.

use crate::syntax::ast::{Arg, ArrayInitElem, Expr, ExprKind, Initializer, TypeSpec, VarDecl};
use std::collections::HashMap;

/// `decl` with the method's own names (`locals`: key → hidden key) in its
/// type and initial value renamed to their hidden names.
pub(super) fn in_method_scope(decl: &VarDecl, locals: &HashMap<String, String>) -> VarDecl {
    let mut d = decl.clone();
    spec(&mut d.ty, locals);
    if let Some(init) = &mut d.init {
        initializer(init, locals);
    }
    d
}

fn spec(t: &mut TypeSpec, locals: &HashMap<String, String>) {
    match t {
        TypeSpec::Named(_) => {}
        TypeSpec::String { len, .. } => {
            if let Some(e) = len {
                expr(e, locals);
            }
        }
        TypeSpec::Array { ranges, elem, .. } => {
            for (lo, hi) in ranges {
                expr(lo, locals);
                expr(hi, locals);
            }
            spec(elem, locals);
        }
        TypeSpec::OpenArray { elem, .. } => spec(elem, locals),
        TypeSpec::Subrange { lo, hi, .. } => {
            expr(lo, locals);
            expr(hi, locals);
        }
        TypeSpec::Enum { values, .. } => {
            for e in values.iter_mut().filter_map(|(_, v)| v.as_mut()) {
                expr(e, locals);
            }
        }
        TypeSpec::Struct { fields, .. } => {
            for f in fields {
                *f = in_method_scope(f, locals);
            }
        }
        TypeSpec::Ref { target, .. } => spec(target, locals),
    }
}

fn initializer(init: &mut Initializer, locals: &HashMap<String, String>) {
    match init {
        Initializer::Expr(e) => expr(e, locals),
        Initializer::Array(elems, _) => {
            for ArrayInitElem { repeat, value, .. } in elems {
                if let Some(r) = repeat {
                    expr(r, locals);
                }
                if let Some(v) = value {
                    initializer(v, locals);
                }
            }
        }
        Initializer::Struct(fields, _) => {
            for (_, v) in fields {
                initializer(v, locals);
            }
        }
    }
}

/// Renames the variable names of `e` (not member names, not the names of
/// called functions or of formal parameters).
fn expr(e: &mut Expr, locals: &HashMap<String, String>) {
    match &mut e.kind {
        ExprKind::Name(id) => {
            if let Some(hidden) = locals.get(&id.key()) {
                id.name = hidden.clone();
            }
        }
        ExprKind::Literal(_) | ExprKind::Direct(_) => {}
        ExprKind::Member(base, _) | ExprKind::BitAccess(base, _) => expr(base, locals),
        ExprKind::Index(base, index) => {
            expr(base, locals);
            for i in index {
                expr(i, locals);
            }
        }
        ExprKind::Unary(_, x) | ExprKind::Paren(x) | ExprKind::Deref(x) => expr(x, locals),
        ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => {
            expr(a, locals);
            expr(b, locals);
        }
        ExprKind::Call(call) => {
            for a in &mut call.args {
                match a {
                    Arg::Positional(v) | Arg::Input { value: v, .. } => expr(v, locals),
                    Arg::Output { target, .. } => expr(target, locals),
                }
            }
        }
    }
}
