//! Writing a VAR_INPUT inside the body of its own FUNCTION or
//! FUNCTION_BLOCK (`IN := LIMIT(0, IN, 100);`).
//!
//! IEC 61131-3 treats inputs as set by the caller only. CODESYS and matiec
//! accept the write and so does plcrun, with a compatibility warning (W321).
//! The change is local: a function's input is its own copy of the argument;
//! an FB's input keeps the written value until a call assigns the input
//! again (a call that does not pass it leaves it as written).

use super::body::BodyBuilder;
use super::emit::PlaceRef;
use crate::source::Span;

/// The note carried by a writable place that is a VAR_INPUT of the current
/// FUNCTION or FUNCTION_BLOCK: writing it warns.
pub(super) const OWN_INPUT: &str = "it is a VAR_INPUT of this POU";

impl BodyBuilder<'_> {
    /// Warns (W321) when the place about to be written is an input of the
    /// POU whose body is being emitted.
    pub(super) fn note_input_write(&mut self, p: &PlaceRef, span: Span) {
        if p.writable && p.readonly_reason == Some(OWN_INPUT) {
            self.diags.warning(
                "W321",
                span,
                "writing a VAR_INPUT inside its own POU is a CODESYS/matiec extension; the \
                 change is local (a function's input is a copy, an FB's stays until the next \
                 call assigns it)",
            );
        }
    }
}
