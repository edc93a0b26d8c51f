//! CODESYS 2.3 spellings of keywords: `FUNCTIONBLOCK` and
//! `END_FUNCTIONBLOCK` for `FUNCTION_BLOCK` and `END_FUNCTION_BLOCK`.
//! Read as the IEC keyword with a compatibility warning (W357).

use super::lexer::Spanned;
use super::token::{Kw, Tok};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};

/// Turns the identifiers `FUNCTIONBLOCK` / `END_FUNCTIONBLOCK` (any case)
/// into the IEC keywords.
pub fn iec_keywords(
    file: FileId,
    mut tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    for t in tokens.iter_mut() {
        let Tok::Ident(word) = &t.1 else {
            continue;
        };
        let (kw, iec) = if word.eq_ignore_ascii_case("FUNCTIONBLOCK") {
            (Kw::FunctionBlock, "FUNCTION_BLOCK")
        } else if word.eq_ignore_ascii_case("END_FUNCTIONBLOCK") {
            (Kw::EndFunctionBlock, "END_FUNCTION_BLOCK")
        } else {
            continue;
        };
        diags.push(Diagnostic::warning(
            "W357",
            Span::new(file, t.0, t.2),
            format!("`{word}` is CODESYS's spelling of `{iec}`"),
        ));
        t.1 = Tok::Kw(kw);
    }
    tokens
}
