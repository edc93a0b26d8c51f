//! `VAR_IN_OUT CONSTANT` (CODESYS / TwinCAT): an in-out the body may not
//! write (E401), passed by reference as any in-out, so its argument may be
//! a variable the caller cannot write either (a CONSTANT, an input). Its
//! declaration is a compatibility warning (W353, layout.rs); an in-out
//! without CONSTANT still needs a writable variable (E412).

use super::body::BodyBuilder;
use super::calls::Param;
use crate::source::Span;

impl BodyBuilder<'_> {
    /// E412: the variable given to in-out `p` cannot be written.
    pub(super) fn in_out_not_writable(&mut self, p: &Param, at: Span) {
        self.diags.push(
            crate::diagnostics::Diagnostic::error(
                "E412",
                at,
                format!("VAR_IN_OUT `{}` needs a writable variable", p.name),
            )
            .with_note(
                "a VAR_IN_OUT CONSTANT (CODESYS) takes any variable: the callee only reads it",
            ),
        );
    }
}
