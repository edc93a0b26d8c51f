//! Every name a POU body mentions as a variable or calls: the walk behind
//! "does this body use ENO" (eno_uses.rs) and "which functions must be laid
//! out before this body is emitted" (declare.rs). A member name
//! (`inst.x`) and the parameter name of a formal argument (`x := ...`)
//! are not names of the body; their base and value are, except for
//! [`any_name_or_member`], which also gives the member of a bare name
//! (`GVL_TcUnit.GetCpuCounter` gives `GVL_TcUnit` and `GetCpuCounter`).

use crate::syntax::ast::{
    Arg, Body, CaseLabel, Expr, ExprKind, IlInstrKind, IlLine, SfcElement, Stmt, StmtKind,
    TransitionCondition,
};

/// True when `found` returns true for a name `body` mentions (it is
/// called for each, in order, until it does).
pub(super) fn any_name(body: &Body, found: &mut dyn FnMut(&str) -> bool) -> bool {
    Walk {
        found,
        members: false,
    }
    .body(body)
}

/// As [`any_name`], and also for the member `x` of every `Q.x` whose base
/// `Q` is a bare name: a global named through its list.
pub(super) fn any_name_or_member(body: &Body, found: &mut dyn FnMut(&str) -> bool) -> bool {
    Walk {
        found,
        members: true,
    }
    .body(body)
}

/// The walk: the callback, and whether members of bare names count.
struct Walk<'f> {
    found: &'f mut dyn FnMut(&str) -> bool,
    members: bool,
}

impl Walk<'_> {
    fn body(&mut self, body: &Body) -> bool {
        match body {
            Body::St(stmts) => stmts.iter().any(|s| self.stmt(s)),
            Body::Il(lines) => lines.iter().any(|l| self.il_line(l)),
            Body::Sfc(elems) => elems.iter().any(|e| match e {
                SfcElement::Step(_) => false,
                SfcElement::Transition(t) => match &t.condition {
                    TransitionCondition::Expr(e) => self.expr(e),
                    TransitionCondition::Il(lines) => lines.iter().any(|l| self.il_line(l)),
                },
                SfcElement::Action(a) => self.body(&a.body),
                SfcElement::Statement(s) => self.stmt(s),
            }),
        }
    }

    fn stmts(&mut self, list: &[Stmt]) -> bool {
        list.iter().any(|s| self.stmt(s))
    }

    fn stmt(&mut self, s: &Stmt) -> bool {
        match &s.kind {
            StmtKind::Assign { target, value } | StmtKind::RefAssign { target, value } => {
                self.expr(target) || self.expr(value)
            }
            StmtKind::Call(c) => self.expr(&c.callee) || self.args(&c.args),
            StmtKind::If {
                branches,
                else_branch,
            } => {
                branches
                    .iter()
                    .any(|(c, body)| self.expr(c) || self.stmts(body))
                    || else_branch.as_deref().is_some_and(|b| self.stmts(b))
            }
            StmtKind::Case {
                selector,
                arms,
                else_branch,
            } => {
                self.expr(selector)
                    || arms.iter().any(|a| {
                        a.labels.iter().any(|l| match l {
                            CaseLabel::Value(v) => self.expr(v),
                            CaseLabel::Range(a, b) => self.expr(a) || self.expr(b),
                        }) || self.stmts(&a.body)
                    })
                    || else_branch.as_deref().is_some_and(|b| self.stmts(b))
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                self.expr(var)
                    || self.expr(from)
                    || self.expr(to)
                    || by.iter().any(|b| self.expr(b))
                    || self.stmts(body)
            }
            StmtKind::While { cond, body } | StmtKind::Repeat { body, until: cond } => {
                self.expr(cond) || self.stmts(body)
            }
            StmtKind::Try {
                body,
                catch,
                finally,
            } => {
                self.stmts(body)
                    || catch
                        .as_ref()
                        .is_some_and(|(name, c)| (self.found)(&name.name) || self.stmts(c))
                    || finally.as_ref().is_some_and(|f| self.stmts(f))
            }
            StmtKind::Exit | StmtKind::Continue | StmtKind::Return | StmtKind::Empty => false,
        }
    }

    fn il_line(&mut self, l: &IlLine) -> bool {
        let Some(i) = &l.instr else { return false };
        match &i.kind {
            IlInstrKind::Simple { operand, .. } | IlInstrKind::Deferred { operand, .. } => {
                operand.iter().any(|o| self.expr(o))
            }
            IlInstrKind::Call {
                instance,
                args: a,
                outputs,
                ..
            } => {
                self.expr(instance)
                    || self.args(a)
                    || outputs
                        .iter()
                        .filter_map(|o| o.dest.as_ref())
                        .any(|d| self.expr(d))
            }
            IlInstrKind::FunctionCall { name, args: a } => (self.found)(&name.name) || self.args(a),
            IlInstrKind::FbInput { instance, .. } => self.expr(instance),
            IlInstrKind::Close | IlInstrKind::Jump { .. } | IlInstrKind::Return { .. } => false,
        }
    }

    fn args(&mut self, list: &[Arg]) -> bool {
        list.iter().any(|a| match a {
            Arg::Positional(e) | Arg::Input { value: e, .. } | Arg::Output { target: e, .. } => {
                self.expr(e)
            }
        })
    }

    fn expr(&mut self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Name(id) => (self.found)(&id.name),
            ExprKind::Literal(_) | ExprKind::Direct(_) => false,
            ExprKind::Member(base, member) => {
                self.expr(base)
                    || (self.members
                        && matches!(base.kind, ExprKind::Name(_))
                        && (self.found)(&member.name))
            }
            ExprKind::BitAccess(base, _) => self.expr(base),
            ExprKind::Index(base, idx) => self.expr(base) || idx.iter().any(|i| self.expr(i)),
            ExprKind::Unary(_, x) | ExprKind::Paren(x) | ExprKind::Deref(x) => self.expr(x),
            ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => self.expr(a) || self.expr(b),
            ExprKind::Call(c) => self.expr(&c.callee) || self.args(&c.args),
        }
    }
}
