//! CODESYS's implicit bounds check: when a project declares the FUNCTION
//! `CheckBounds(index, lower, upper : DINT) : DINT` (TwinCAT projects
//! carry one in `ImplicitChecks`), every array access with a computed
//! index in a file of the CODESYS V3 / TwinCAT 3 dialect (plcrun's own
//! TwinCAT library aside, as CODESYS leaves libraries out) goes through it,
//! and the element it returns is the one accessed — the usual one clamps
//! the index to the bounds, so `a[4]` of an `ARRAY[1..3]` is `a[3]`. The
//! runtime's own check (R002) still guards what the function returns.

use super::body::BodyBuilder;
use crate::ir::type_table::Dim;
use crate::syntax::ast::{Arg, Call, Expr, ExprKind, Ident, LiteralValue};

impl BodyBuilder<'_> {
    /// `indexes` of an array with `dims`, each index that is not a literal
    /// wrapped in a call of the project's `CheckBounds` when one applies
    /// here; `None` when none does.
    pub(super) fn bounds_checked(&self, indexes: &[Expr], dims: &[Dim]) -> Option<Vec<Expr>> {
        let first = indexes.first()?;
        let check = self.implicit_check(super::implicit_checks::CHECK_BOUNDS, first.span)?;
        let name = self.model.pous[check].name.clone();
        let wrapped = indexes
            .iter()
            .zip(dims)
            .map(|(ix, d)| match ix.kind {
                ExprKind::Literal(_) => ix.clone(),
                _ => call_check(&name, ix, d),
            })
            .collect();
        Some(wrapped)
    }
}

/// `CheckBounds(ix, lo, hi)`.
fn call_check(name: &str, ix: &Expr, d: &Dim) -> Expr {
    let span = ix.span;
    let named = |n: &str| Ident {
        name: n.to_string(),
        span,
    };
    let bound = |v: i64| super::assert_calls::literal(LiteralValue::Int(i128::from(v)), None, span);
    Expr {
        kind: ExprKind::Call(Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(named(name)),
                span,
            }),
            // By position: the inputs may be named otherwise.
            args: vec![
                Arg::Positional(ix.clone()),
                Arg::Positional(bound(d.lo)),
                Arg::Positional(bound(d.hi)),
            ],
            span,
        }),
        span,
    }
}
