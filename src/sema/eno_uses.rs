//! Whether a body mentions the name `ENO`: only FUNCTIONs and
//! FUNCTION_BLOCKs whose body reads or writes their own ENO get the
//! implicit ENO output (eno_body.rs), so every other POU keeps its layout
//! and code unchanged. `ENO =>` in a call names the callee's output and is
//! not a mention; its target is.

use crate::syntax::ast::{
    Arg, Body, CaseLabel, Expr, ExprKind, IlInstrKind, IlLine, SfcElement, Stmt, StmtKind,
    TransitionCondition,
};

/// True when `body` mentions `ENO` as a variable.
pub(super) fn body_mentions_eno(body: &Body) -> bool {
    match body {
        Body::St(stmts) => stmts.iter().any(stmt),
        Body::Il(lines) => lines.iter().any(il_line),
        Body::Sfc(elems) => elems.iter().any(|e| match e {
            SfcElement::Step(_) => false,
            SfcElement::Transition(t) => match &t.condition {
                TransitionCondition::Expr(e) => expr(e),
                TransitionCondition::Il(lines) => lines.iter().any(il_line),
            },
            SfcElement::Action(a) => body_mentions_eno(&a.body),
            SfcElement::Statement(s) => stmt(s),
        }),
    }
}

fn stmt(s: &Stmt) -> bool {
    match &s.kind {
        StmtKind::Assign { target, value } | StmtKind::RefAssign { target, value } => {
            expr(target) || expr(value)
        }
        StmtKind::Call(c) => expr(&c.callee) || args(&c.args),
        StmtKind::If {
            branches,
            else_branch,
        } => {
            branches
                .iter()
                .any(|(c, body)| expr(c) || body.iter().any(stmt))
                || else_branch.iter().flatten().any(stmt)
        }
        StmtKind::Case {
            selector,
            arms,
            else_branch,
        } => {
            expr(selector)
                || arms.iter().any(|a| {
                    a.labels.iter().any(|l| match l {
                        CaseLabel::Value(v) => expr(v),
                        CaseLabel::Range(a, b) => expr(a) || expr(b),
                    }) || a.body.iter().any(stmt)
                })
                || else_branch.iter().flatten().any(stmt)
        }
        StmtKind::For {
            var,
            from,
            to,
            by,
            body,
        } => {
            is_eno(&var.name)
                || expr(from)
                || expr(to)
                || by.iter().any(expr)
                || body.iter().any(stmt)
        }
        StmtKind::While { cond, body } | StmtKind::Repeat { body, until: cond } => {
            expr(cond) || body.iter().any(stmt)
        }
        StmtKind::Exit | StmtKind::Continue | StmtKind::Return | StmtKind::Empty => false,
    }
}

fn il_line(l: &IlLine) -> bool {
    let Some(i) = &l.instr else { return false };
    match &i.kind {
        IlInstrKind::Simple { operand, .. } | IlInstrKind::Deferred { operand, .. } => {
            operand.iter().any(expr)
        }
        IlInstrKind::Call {
            instance,
            args: a,
            outputs,
            ..
        } => expr(instance) || args(a) || outputs.iter().filter_map(|o| o.dest.as_ref()).any(expr),
        IlInstrKind::FunctionCall { args: a, .. } => args(a),
        IlInstrKind::FbInput { instance, .. } => expr(instance),
        IlInstrKind::Close | IlInstrKind::Jump { .. } | IlInstrKind::Return { .. } => false,
    }
}

fn args(list: &[Arg]) -> bool {
    list.iter().any(|a| match a {
        Arg::Positional(e) | Arg::Input { value: e, .. } | Arg::Output { target: e, .. } => expr(e),
    })
}

fn expr(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Name(id) => is_eno(&id.name),
        ExprKind::Literal(_) | ExprKind::Direct(_) => false,
        // `inst.ENO` names another instance's output, not our own.
        ExprKind::Member(base, _) | ExprKind::BitAccess(base, _) => expr(base),
        ExprKind::Index(base, idx) => expr(base) || idx.iter().any(expr),
        ExprKind::Unary(_, x) | ExprKind::Paren(x) | ExprKind::Deref(x) => expr(x),
        ExprKind::Binary(_, a, b) => expr(a) || expr(b),
        ExprKind::Call(c) => expr(&c.callee) || args(&c.args),
    }
}

fn is_eno(name: &str) -> bool {
    name.eq_ignore_ascii_case("ENO")
}

#[cfg(test)]
mod tests {
    use super::body_mentions_eno;
    use crate::syntax::ast::{Item, Pou};

    fn first_pou(src: &str) -> Pou {
        let mut diags = crate::diagnostics::Diagnostics::new();
        let unit = crate::syntax::parse(crate::source::FileId(0), src, &mut diags);
        assert!(!diags.has_errors(), "the test source parses");
        unit.items
            .into_iter()
            .find_map(|i| match i {
                Item::Pou(p) => Some(p),
                _ => None,
            })
            .expect("one POU")
    }

    #[test]
    fn st_and_il_mentions_are_found() {
        let st = first_pou(
            "FUNCTION f : INT VAR_INPUT a : INT; END_VAR IF a < 0 THEN ENO := FALSE; END_IF; f := a; END_FUNCTION",
        );
        assert!(body_mentions_eno(&st.body));
        let il = first_pou(
            "FUNCTION_BLOCK fb VAR_INPUT a : BOOL; END_VAR\nLD a\nST ENO\nEND_FUNCTION_BLOCK",
        );
        assert!(body_mentions_eno(&il.body));
    }

    #[test]
    fn eno_of_a_callee_is_not_a_mention() {
        let p = first_pou(
            "FUNCTION_BLOCK fb VAR t : TON; ok : BOOL; END_VAR t(IN := TRUE, ENO => ok); ok := t.ENO; END_FUNCTION_BLOCK",
        );
        assert!(!body_mentions_eno(&p.body));
    }
}
