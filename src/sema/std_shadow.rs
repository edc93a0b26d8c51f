//! A user POU that has the name of a standard function: the user's
//! definition wins (OSCAT defines its own `TIME_TO_TOD`, `DATE_TO_DT`,
//! `TOD_TO_TIME` and `MULTIME`), and a warning names both so that a reader
//! knows which one a call runs.

use crate::diagnostics::Diagnostic;
use crate::syntax::ast::{Pou, PouKind};

/// W343: `pou` hides the standard function of the same name.
pub(super) fn shadow_warning(pou: &Pou) -> Diagnostic {
    let kind = match pou.kind {
        PouKind::Function => "FUNCTION",
        PouKind::FunctionBlock => "FUNCTION_BLOCK",
        PouKind::Program => "PROGRAM",
        #[allow(unreachable_patterns)]
        _ => "POU",
    };
    let name = &pou.name.name;
    Diagnostic::warning(
        "W343",
        pou.name.span,
        format!(
            "{kind} `{name}` has the name of the standard function {}; calls of `{name}` run this {kind}, not the standard function",
            name.to_ascii_uppercase()
        ),
    )
    .with_note("IEC 61131-3 reserves the standard function names; rename the POU to keep both")
}
