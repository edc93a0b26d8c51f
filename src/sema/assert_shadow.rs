//! A user POU named like one of `plcrun test`'s assertions (`AssertTrue`,
//! `AssertEquals`, ...). TcUnit projects bring their own assertions in a
//! library, so the user's definition wins, as a user FUNCTION named like a
//! standard function does (std_shadow.rs); under `plcrun test` a warning
//! (W484) says that calls of that name run the user's POU, whose failures
//! the runner does not count. Outside `plcrun test` the assertions do not
//! exist and nothing is said.

use super::assert_calls::{ASSERT_TRUE_HOST, is_assertion_name};
use crate::diagnostics::Diagnostic;
use crate::syntax::ast::{Pou, PouKind};

/// W484 when `pou` hides an assertion of the test runner (`host_pous`,
/// upper case, holds the runner's host functions when it is on).
pub(super) fn assertion_shadow_warning(pou: &Pou, host_pous: &[String]) -> Option<Diagnostic> {
    if !host_pous.iter().any(|h| h == ASSERT_TRUE_HOST) || !is_assertion_name(&pou.name.key()) {
        return None;
    }
    let kind = match pou.kind {
        PouKind::Function => "FUNCTION",
        PouKind::FunctionBlock => "FUNCTION_BLOCK",
        PouKind::Program => "PROGRAM",
    };
    let name = &pou.name.name;
    Some(
        Diagnostic::warning(
            "W484",
            pou.name.span,
            format!(
                "{kind} `{name}` has the name of a plcrun test assertion; calls of `{name}` run this {kind}, and plcrun test does not count its failures"
            ),
        )
        .with_note("rename the POU to use plcrun's assertion, or keep it to use your own"),
    )
}
