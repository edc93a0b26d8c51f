//! The ST the instance-call pass writes: the hidden methods and function,
//! the loops over arrays of instances, and the expressions and calls in
//! them (spans: the declaration each call comes from, so that a fault or
//! an error points there).

use super::Phase;
use crate::source::Span;
use crate::syntax::ast::{
    Arg, BinaryOp, Body, Call, Expr, ExprKind, Ident, Literal, LiteralValue, Pou, PouKind, Stmt,
    StmtKind, VarBlock, VarDecl, VarKind,
};
use crate::syntax::oop::{Method, Modifiers};

/// The name of the `k`-th loop counter (no identifier can spell it).
fn counter(k: usize) -> String {
    format!("FB_init@i{k}")
}

/// `body` for each instance a declaration declares: each name, and each
/// element of an array (one loop a dimension, the last innermost), with
/// `loops` raised to the counters it uses.
pub(super) fn all_elements(
    d: &VarDecl,
    dims: &[&(Expr, Expr)],
    loops: &mut usize,
    body: impl Fn(Expr) -> Vec<Stmt>,
) -> Vec<Stmt> {
    let span = d.span;
    let mut out = Vec::new();
    for n in &d.names {
        let counters: Vec<String> = (0..dims.len()).map(counter).collect();
        let mut target = named(n, span);
        if !dims.is_empty() {
            let at = counters.iter().map(|c| name(c, span)).collect();
            target = index(target, at, span);
        }
        let mut stmts = body(target);
        for (k, (lo, hi)) in dims.iter().enumerate().rev() {
            stmts = vec![for_loop(
                counters[k].clone(),
                lo.clone(),
                hi.clone(),
                stmts,
                span,
            )];
        }
        out.extend(stmts);
    }
    *loops = (*loops).max(dims.len());
    out
}

/// `target[lo + k]` for `k` in `0..n`, then a loop over the elements from
/// `lo + n` to `hi` (one dimension; one counter).
pub(super) fn listed_elements(
    n: &Ident,
    (lo, hi): &(Expr, Expr),
    listed: usize,
    loops: &mut usize,
    mut body: impl FnMut(Expr, Option<usize>) -> Vec<Stmt>,
    span: Span,
) -> Vec<Stmt> {
    let mut out = Vec::new();
    for k in 0..listed {
        let at = offset(lo, k as i128, span);
        out.extend(body(index(named(n, span), vec![at], span), Some(k)));
    }
    let rest = offset(lo, listed as i128, span);
    let target = index(named(n, span), vec![name(&counter(0), span)], span);
    let stmts = body(target, None);
    out.push(for_loop(counter(0), rest, hi.clone(), stmts, span));
    *loops = (*loops).max(1);
    out
}

/// `target.<hidden>(<flag> := <flag>);`: the member's own members.
pub(super) fn members_call(target: Expr, phase: Phase, span: Span) -> Stmt {
    let callee = member(target, phase.members, span);
    call_stmt(
        callee,
        vec![input(phase.flag, name(phase.flag, span))],
        span,
    )
}

/// `SUPER^.<hidden>(<flag> := <flag>);`: the parent's members.
pub(super) fn super_members(phase: Phase, span: Span) -> Stmt {
    members_call(name(crate::syntax::oop::SUPER, span), phase, span)
}

/// The hidden method of `phase` (`<flag> : BOOL` input, `loops`
/// counters).
pub(super) fn members_method(phase: Phase, stmts: Vec<Stmt>, loops: usize, span: Span) -> Method {
    Method {
        name: Ident {
            name: phase.members.to_string(),
            span,
        },
        mods: Modifiers::default(),
        return_type: None,
        var_blocks: parameters(phase, loops, span),
        body: Body::St(stmts),
        span,
        property: None,
        call_after_init: false,
        no_check: false,
    }
}

/// `VAR_INPUT <flag> : BOOL; END_VAR VAR counters : DINT; END_VAR`.
fn parameters(phase: Phase, loops: usize, span: Span) -> Vec<VarBlock> {
    let decl = |n: String, ty: &str| VarDecl::simple(&n, ty, span);
    let block = |kind, decls| VarBlock {
        kind,
        constant: false,
        retain: None,
        decls,
        span,
    };
    let mut out = vec![block(
        VarKind::Input,
        vec![decl(phase.flag.to_string(), "BOOL")],
    )];
    if loops > 0 {
        out.push(block(VarKind::Local, counters(loops, span)));
    }
    out
}

/// The DINT loop counters the calls over `loops` array dimensions use.
pub(super) fn counters(loops: usize, span: Span) -> Vec<VarDecl> {
    (0..loops)
        .map(|k| VarDecl::simple(&counter(k), "DINT", span))
        .collect()
}

/// The hidden FUNCTION of the global lists for `phase`.
pub(super) fn globals_function(phase: Phase, stmts: Vec<Stmt>, loops: usize) -> Pou {
    let span = stmts.first().map(|s| s.span).unwrap_or_default();
    Pou {
        kind: PouKind::Function,
        name: Ident {
            name: phase.globals.to_string(),
            span,
        },
        return_type: None,
        var_blocks: parameters(phase, loops, span),
        body: Body::St(stmts),
        span,
        oop: None,
        no_check: false,
    }
}

pub(super) fn named(n: &Ident, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(n.clone()),
        span,
    }
}

pub(super) fn index(base: Expr, at: Vec<Expr>, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Index(Box::new(base), at),
        span,
    }
}

/// `lo + k`.
pub(super) fn offset(lo: &Expr, k: i128, span: Span) -> Expr {
    let k = Expr {
        kind: ExprKind::Literal(Literal {
            value: LiteralValue::Int(k),
            type_prefix: None,
        }),
        span,
    };
    Expr {
        kind: ExprKind::Binary(BinaryOp::Add, Box::new(lo.clone()), Box::new(k)),
        span,
    }
}

pub(super) fn for_loop(var: String, from: Expr, to: Expr, body: Vec<Stmt>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::For {
            var: Box::new(name(&var, span)),
            from,
            to,
            by: None,
            body,
        },
        span,
    }
}

pub(super) fn name(n: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(Ident {
            name: n.to_string(),
            span,
        }),
        span,
    }
}

pub(super) fn member(base: Expr, m: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Member(
            Box::new(base),
            Ident {
                name: m.to_string(),
                span,
            },
        ),
        span,
    }
}

pub(super) fn bool_lit(b: bool, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Literal(Literal {
            value: LiteralValue::Bool(b),
            type_prefix: None,
        }),
        span,
    }
}

pub(super) fn input(n: &str, value: Expr) -> Arg {
    Arg::Input {
        name: Ident {
            name: n.to_string(),
            span: value.span,
        },
        value,
    }
}

pub(super) fn call_stmt(callee: Expr, args: Vec<Arg>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::Call(Call {
            callee: Box::new(callee),
            args,
            span,
        }),
        span,
    }
}
