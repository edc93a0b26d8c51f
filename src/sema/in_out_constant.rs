//! `VAR_IN_OUT CONSTANT` (CODESYS / TwinCAT): an in-out the body may not
//! write (E401), passed by reference as any in-out, so its argument may be
//! a variable the caller cannot write either (a CONSTANT, an input). Its
//! declaration is a compatibility warning (W353, layout.rs); an in-out
//! without CONSTANT still needs a writable variable (E412).

use super::body::BodyBuilder;
use super::calls::Param;
use super::emit::PlaceRef;
use crate::source::Span;

/// Why an output of a function block instance is read-only from outside.
pub(super) const FB_OUTPUT: &str = "outputs of a function block are written only by the block";

impl BodyBuilder<'_> {
    /// Whether `arg` may be bound to in-out `p`: a variable the caller may
    /// write, or any variable for a CONSTANT in-out (E412 otherwise). The
    /// binding counts as a write of `arg` unless `p` is CONSTANT (the
    /// callee does not write it).
    pub(super) fn in_out_bindable(&mut self, p: &Param, arg: &PlaceRef, at: Span) -> bool {
        // CODESYS connects another instance's output to an in-out, which
        // the callee then may write (`bEnable := fbAxis.bEnabled`).
        if !arg.writable
            && !p.constant
            && arg.readonly_reason == Some(FB_OUTPUT)
            && self.model.codesys_files.contains(&at.file)
        {
            self.diags.warning(
                "W492",
                at,
                format!(
                    "VAR_IN_OUT `{}` connected to an output of another instance (CODESYS): the called block may write that output",
                    p.name
                ),
            );
            return true;
        }
        if !arg.writable && !p.constant {
            self.in_out_not_writable(p, at);
            return false;
        }
        if !p.constant {
            self.note_input_write(arg, at);
        }
        true
    }

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
