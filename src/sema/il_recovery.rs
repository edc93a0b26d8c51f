//! IL after a line with a syntax error: the current result that line would
//! have left is unknown, so the checker waits for a fresh load (or a
//! label) before it reports again (see `il_body`).

use crate::diagnostics::{Diagnostics, Severity};
use crate::syntax::ast::{IlInstr, IlInstrKind, IlOperator};

/// True for an instruction that sets the current result regardless of
/// what it held: `LD` and `LDN`.
pub(super) fn is_load(instr: &IlInstr) -> bool {
    matches!(
        instr.kind,
        IlInstrKind::Simple {
            op: IlOperator::Ld,
            ..
        }
    )
}

/// True when an error was reported after the first `mark` diagnostics.
pub(super) fn has_error_since(diags: &Diagnostics, mark: usize) -> bool {
    diags
        .iter()
        .skip(mark)
        .any(|d| d.severity == Severity::Error)
}
