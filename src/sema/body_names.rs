//! Every name a POU body mentions as a variable or calls: the walk behind
//! "does this body use ENO" (eno_uses.rs) and "which functions must be laid
//! out before this body is emitted" (declare.rs). A member name
//! (`inst.x`) and the parameter name of a formal argument (`x := ...`)
//! are not names of the body; their base and value are.

use crate::syntax::ast::{
    Arg, Body, CaseLabel, Expr, ExprKind, IlInstrKind, IlLine, SfcElement, Stmt, StmtKind,
    TransitionCondition,
};

/// True when `found` returns true for a name `body` mentions (it is
/// called for each, in order, until it does).
pub(super) fn any_name(body: &Body, found: &mut dyn FnMut(&str) -> bool) -> bool {
    match body {
        Body::St(stmts) => stmts.iter().any(|s| stmt(s, found)),
        Body::Il(lines) => lines.iter().any(|l| il_line(l, found)),
        Body::Sfc(elems) => elems.iter().any(|e| match e {
            SfcElement::Step(_) => false,
            SfcElement::Transition(t) => match &t.condition {
                TransitionCondition::Expr(e) => expr(e, found),
                TransitionCondition::Il(lines) => lines.iter().any(|l| il_line(l, found)),
            },
            SfcElement::Action(a) => any_name(&a.body, found),
            SfcElement::Statement(s) => stmt(s, found),
        }),
    }
}

fn stmts(list: &[Stmt], found: &mut dyn FnMut(&str) -> bool) -> bool {
    list.iter().any(|s| stmt(s, found))
}

fn stmt(s: &Stmt, found: &mut dyn FnMut(&str) -> bool) -> bool {
    match &s.kind {
        StmtKind::Assign { target, value } | StmtKind::RefAssign { target, value } => {
            expr(target, found) || expr(value, found)
        }
        StmtKind::Call(c) => expr(&c.callee, found) || args(&c.args, found),
        StmtKind::If {
            branches,
            else_branch,
        } => {
            branches
                .iter()
                .any(|(c, body)| expr(c, found) || stmts(body, found))
                || else_branch.as_deref().is_some_and(|b| stmts(b, found))
        }
        StmtKind::Case {
            selector,
            arms,
            else_branch,
        } => {
            expr(selector, found)
                || arms.iter().any(|a| {
                    a.labels.iter().any(|l| match l {
                        CaseLabel::Value(v) => expr(v, found),
                        CaseLabel::Range(a, b) => expr(a, found) || expr(b, found),
                    }) || stmts(&a.body, found)
                })
                || else_branch.as_deref().is_some_and(|b| stmts(b, found))
        }
        StmtKind::For {
            var,
            from,
            to,
            by,
            body,
        } => {
            expr(var, found)
                || expr(from, found)
                || expr(to, found)
                || by.iter().any(|b| expr(b, found))
                || stmts(body, found)
        }
        StmtKind::While { cond, body } | StmtKind::Repeat { body, until: cond } => {
            expr(cond, found) || stmts(body, found)
        }
        StmtKind::Exit | StmtKind::Continue | StmtKind::Return | StmtKind::Empty => false,
    }
}

fn il_line(l: &IlLine, found: &mut dyn FnMut(&str) -> bool) -> bool {
    let Some(i) = &l.instr else { return false };
    match &i.kind {
        IlInstrKind::Simple { operand, .. } | IlInstrKind::Deferred { operand, .. } => {
            operand.iter().any(|o| expr(o, found))
        }
        IlInstrKind::Call {
            instance,
            args: a,
            outputs,
            ..
        } => {
            expr(instance, found)
                || args(a, found)
                || outputs
                    .iter()
                    .filter_map(|o| o.dest.as_ref())
                    .any(|d| expr(d, found))
        }
        IlInstrKind::FunctionCall { name, args: a } => found(&name.name) || args(a, found),
        IlInstrKind::FbInput { instance, .. } => expr(instance, found),
        IlInstrKind::Close | IlInstrKind::Jump { .. } | IlInstrKind::Return { .. } => false,
    }
}

fn args(list: &[Arg], found: &mut dyn FnMut(&str) -> bool) -> bool {
    list.iter().any(|a| match a {
        Arg::Positional(e) | Arg::Input { value: e, .. } | Arg::Output { target: e, .. } => {
            expr(e, found)
        }
    })
}

fn expr(e: &Expr, found: &mut dyn FnMut(&str) -> bool) -> bool {
    match &e.kind {
        ExprKind::Name(id) => found(&id.name),
        ExprKind::Literal(_) | ExprKind::Direct(_) => false,
        ExprKind::Member(base, _) | ExprKind::BitAccess(base, _) => expr(base, found),
        ExprKind::Index(base, idx) => expr(base, found) || idx.iter().any(|i| expr(i, found)),
        ExprKind::Unary(_, x) | ExprKind::Paren(x) | ExprKind::Deref(x) => expr(x, found),
        ExprKind::Binary(_, a, b) => expr(a, found) || expr(b, found),
        ExprKind::Call(c) => expr(&c.callee, found) || args(&c.args, found),
    }
}
