//! Chained assignment `a := b := c;` (CODESYS / TwinCAT): `c` is
//! assigned to `b`, then `b` to `a`. The parser spells it as the plain
//! assignments it stands for, innermost first, so every later pass sees
//! only ordinary statements.

use crate::syntax::ast::{Expr, Stmt, StmtKind};
use crate::syntax::construct::State;

/// A statement as the grammar reads it: one statement, or the several
/// assignments of a chain. Short-lived (the parser flattens it at once),
/// so the plain statement is not boxed.
#[allow(clippy::large_enum_variant)]
pub enum Stmts {
    /// A plain statement.
    One(Stmt),
    /// The assignments a chain stands for, in execution order.
    Chain(Vec<Stmt>),
}

/// `first := rest[0] := ... := value;` as its assignments: `value` to
/// the last target, then each target to the one before it. The last
/// assignment's span is the whole statement; an inner one's runs from
/// its target to the end of the value.
pub fn statements(
    st: &State,
    first: Expr,
    rest: Vec<Expr>,
    value: Expr,
    l: usize,
    r: usize,
) -> Vec<Stmt> {
    let mut targets = Vec::with_capacity(rest.len() + 1);
    targets.push(first);
    targets.extend(rest);
    let end = value.span.end as usize;
    let mut out = Vec::with_capacity(targets.len());
    let mut value = value;
    while let Some(target) = targets.pop() {
        let start = if targets.is_empty() {
            l
        } else {
            target.span.start as usize
        };
        let next = target.clone();
        let span = st.span(start, if targets.is_empty() { r } else { end });
        out.push(Stmt {
            kind: StmtKind::Assign { target, value },
            span,
        });
        value = next;
    }
    out
}

/// The statements of `items`, chains spelt out in place.
pub fn flatten(items: Vec<Stmts>) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(items.len());
    for item in items {
        match item {
            Stmts::One(s) => out.push(s),
            Stmts::Chain(v) => out.extend(v),
        }
    }
    out
}
