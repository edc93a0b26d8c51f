//! The assignment attempt `target ?= value;` (edition 3): `target` gets
//! the instance `value` refers to when that instance's type implements
//! `target`'s interface, else no instance (0). The tree spells it as an
//! assignment whose value is a call of [`ATTEMPT`], a name no identifier
//! can spell, so every pass that walks assignments walks it too;
//! `src/sema/oop/assign_attempt.rs` gives it its meaning.

use crate::syntax::ast::{Arg, Call, Expr, ExprKind, Ident, Stmt, StmtKind};
use crate::syntax::construct::State;

/// The callee name of the assignment attempt in the tree.
pub const ATTEMPT: &str = "?=";

/// `target ?= value;` as a statement.
pub fn statement(st: &State, target: Expr, value: Expr, l: usize, r: usize) -> Stmt {
    let span = st.span(l, r);
    let vspan = value.span;
    let call = Call {
        callee: Box::new(Expr {
            kind: ExprKind::Name(Ident {
                name: ATTEMPT.to_string(),
                span: vspan,
            }),
            span: vspan,
        }),
        args: vec![Arg::Positional(value)],
        span: vspan,
    };
    Stmt {
        kind: StmtKind::Assign {
            target,
            value: Expr {
                kind: ExprKind::Call(call),
                span: vspan,
            },
        },
        span,
    }
}

/// The value of an assignment attempt, if `value` is one.
pub fn attempted(value: &Expr) -> Option<&Expr> {
    let ExprKind::Call(c) = &value.kind else {
        return None;
    };
    let ExprKind::Name(id) = &c.callee.kind else {
        return None;
    };
    match (id.name == ATTEMPT, c.args.as_slice()) {
        (true, [Arg::Positional(e)]) => Some(e),
        _ => None,
    }
}
