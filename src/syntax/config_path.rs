//! The path of a `VAR_CONFIG` line, which may go through array elements:
//! `R.main.valves[2].coil AT %QX1.0 : BOOL;` (an element of an array of
//! function block instances) or `R.main.fb.lamps[3] AT %QX2.3 : BOOL;` (an
//! element of an array declared `AT %Q*`).

use super::ast::{ConfigInit, DirectAddress, Expr, Ident, Initializer, TypeSpec};
use crate::source::Span;

/// One segment of the path: a name, with the subscripts that follow it.
pub type ConfigSegment = (Ident, Option<Vec<Expr>>);

/// A VAR_CONFIG line from its parsed parts.
pub fn config_init(
    first: ConfigSegment,
    rest: Vec<ConfigSegment>,
    location: Option<DirectAddress>,
    ty: TypeSpec,
    init: Option<Initializer>,
    span: Span,
) -> ConfigInit {
    let mut path = Vec::with_capacity(rest.len() + 1);
    let mut subscripts = Vec::new();
    for (i, (name, index)) in std::iter::once(first).chain(rest).enumerate() {
        path.push(name);
        if let Some(index) = index {
            subscripts.push((i, index));
        }
    }
    ConfigInit {
        path,
        subscripts,
        location,
        ty,
        init,
        span,
    }
}
