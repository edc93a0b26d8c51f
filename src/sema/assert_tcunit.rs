//! TcUnit's typed assertions, beside the generic ones of `assert_calls`:
//! `AssertEquals_<TYPE>` (both values converted to TYPE, as TcUnit's
//! typed inputs convert them) and `AssertArrayEquals_<TYPE>`,
//! `AssertArray2dEquals_<TYPE>`, `AssertArray3dEquals_<TYPE>` (arrays of
//! TYPE with as many dimensions, compared element by element by position;
//! with a `Delta` for REAL and LREAL). Arrays of different sizes are a
//! failure when the assertion runs, as in TcUnit, not a compile error.

use super::assert_calls::{
    ASSERT_EQ_PREFIX, ASSERT_NEAR_PREFIX, E_ARRAYS, MAX_ARRAY_ELEMENTS, TCUNIT_ARRAY_ASSERT,
    formal, literal, string_literal,
};
use super::body::BodyBuilder;
use super::emit::Val;
use crate::elementary::ElemType;
use crate::ir::type_table::{Dim, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind, LiteralValue};

/// A TcUnit assertion name: `AssertEquals_<T>` gives `(T, None)`,
/// `AssertArray[2d|3d]Equals_<T>` gives `(T, Some(dimensions))`.
pub(super) fn tcunit_name(key: &str) -> Option<(ElemType, Option<usize>)> {
    if let Some(t) = key.strip_prefix("ASSERTEQUALS_") {
        return ElemType::from_name(t).map(|t| (t, None));
    }
    let (dims, t) = [
        ("ASSERTARRAYEQUALS_", 1),
        ("ASSERTARRAY2DEQUALS_", 2),
        ("ASSERTARRAY3DEQUALS_", 3),
    ]
    .iter()
    .find_map(|(prefix, n)| key.strip_prefix(prefix).map(|t| (*n, t)))?;
    ElemType::from_name(t).map(|t| (t, Some(dims)))
}

/// True for the types compared with a `Delta`.
pub(super) fn has_delta(t: ElemType) -> bool {
    matches!(t, ElemType::Real | ElemType::Lreal)
}

/// The shape of an array place: its dimensions and elementary element type.
type Shape = (Vec<Dim>, Option<ElemType>);

impl BodyBuilder<'_> {
    /// Under a TcUnit run, tells the runner an array assertion of `elem`
    /// arrays sized `ne`, `na` starts (TcUnit counts array assertions by
    /// the arrays' sizes and type, message and test).
    fn announce_array_assertion(
        &mut self,
        elem: ElemType,
        (ne, na): (&[i64], &[i64]),
        message: &Expr,
        loc: &Expr,
        span: Span,
    ) {
        if !self.in_tcunit_run() {
            return;
        }
        let shape = |n: &[i64]| format!("{} x{}", elem.name(), n.iter().product::<i64>());
        let args = vec![
            formal("Loc", loc.clone()),
            formal("Expecteds", string_literal(&shape(ne), span)),
            formal("Actuals", string_literal(&shape(na), span)),
            formal("Message", message.clone()),
        ];
        self.host_assert(TCUNIT_ARRAY_ASSERT, args, span, false);
    }

    /// `AssertArray[2d|3d]Equals_<T>(Expecteds, Actuals, [Delta,] Message)`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn tcunit_array_equals(
        &mut self,
        (elem, rank): (ElemType, usize),
        (e, a): (Expr, Expr),
        delta: Option<Expr>,
        message: Expr,
        loc: Expr,
        span: Span,
        want: bool,
    ) -> Val {
        let shape = |s: &mut Self, x: &Expr| -> Option<Shape> {
            let id = s.probe_in(x, true, None).id()?;
            match &s.types.get(id).kind {
                TypeKind::Array { dims, elem } => Some((dims.clone(), s.elementary(*elem))),
                _ => None,
            }
        };
        let (se, sa) = (shape(self, &e), shape(self, &a));
        let fits = |s: &Option<Shape>| {
            s.as_ref()
                .is_some_and(|(d, t)| d.len() == rank && *t == Some(elem))
        };
        // An argument whose type is unknown (an array sized by a constant
        // of a missing library) has its error already.
        let unknown = |s: &mut Self, x: &Expr| {
            s.probe_in(x, true, None).id() == Some(crate::ir::type_table::TypeTable::error())
        };
        if unknown(self, &e) || unknown(self, &a) {
            return Val::error();
        }
        if !fits(&se) || !fits(&sa) {
            self.diags.error(
                E_ARRAYS,
                span,
                format!(
                    "this assertion compares two {rank}-dimensional arrays of {}",
                    elem.name()
                ),
            );
            return Val::error();
        }
        if want {
            self.diags.error(
                E_ARRAYS,
                span,
                "an array assertion returns no value: call it as a statement",
            );
            return Val::error();
        }
        let (de, da) = (
            se.map(|s| s.0).unwrap_or_default(),
            sa.map(|s| s.0).unwrap_or_default(),
        );
        let sizes = |d: &[Dim]| d.iter().map(|x| x.hi - x.lo + 1).collect::<Vec<_>>();
        let (ne, na) = (sizes(&de), sizes(&da));
        self.announce_array_assertion(elem, (&ne, &na), &message, &loc, span);
        if ne != na {
            // A size mismatch fails when the assertion runs, naming both sizes.
            let show = |n: &[i64]| n.iter().map(i64::to_string).collect::<Vec<_>>().join("x");
            let args = self.eq_args(
                string_literal(&format!("{} elements", show(&ne)), span),
                string_literal(&format!("{} elements", show(&na)), span),
                message,
                loc,
                None,
            );
            let name = format!("{ASSERT_EQ_PREFIX}STRING");
            self.host_assert(&name, args, span, false);
            return Val::None(TypeTable::void());
        }
        let count: i64 = ne.iter().product();
        if count > MAX_ARRAY_ELEMENTS {
            self.diags.error(
                E_ARRAYS,
                span,
                format!("array assertions compare at most {MAX_ARRAY_ELEMENTS} elements"),
            );
            return Val::error();
        }
        let host = match (&delta, has_delta(elem)) {
            (Some(_), true) => format!("{ASSERT_NEAR_PREFIX}{}", elem.name()),
            _ => self.equality_host(elem),
        };
        for k in 0..count {
            // Position k in storage order (last index fastest).
            let mut rest = k;
            let mut offsets = vec![0; rank];
            for d in (0..rank).rev() {
                offsets[d] = rest % ne[d];
                rest /= ne[d];
            }
            let index = |dims: &[Dim], x: &Expr| Expr {
                span: x.span,
                kind: ExprKind::Index(
                    Box::new(x.clone()),
                    dims.iter()
                        .zip(&offsets)
                        .map(|(d, o)| literal(LiteralValue::Int((d.lo + o) as i128), None, x.span))
                        .collect(),
                ),
            };
            let first = de.first().map_or(0, |d| d.lo);
            let mut args = self.eq_args(
                index(&de, &e),
                index(&da, &a),
                message.clone(),
                loc.clone(),
                (rank == 1).then_some(first + offsets[0]),
            );
            if rank > 1
                && let Some(last) = args.last_mut()
            {
                let path: Vec<String> = de
                    .iter()
                    .zip(&offsets)
                    .map(|(d, o)| (d.lo + o).to_string())
                    .collect();
                *last = formal(
                    "Element",
                    string_literal(&format!("[{}]", path.join(",")), span),
                );
            }
            if let (Some(d), true) = (&delta, has_delta(elem)) {
                args.insert(2, formal("Delta", d.clone()));
            }
            let ok = self.host_assert(&host, args, span, false);
            if ok.is_error() {
                return ok;
            }
        }
        Val::None(TypeTable::void())
    }
}
