//! `ON` and `STEP` as names. They are keywords (`RESOURCE r ON cpu`,
//! `STEP s1 : ... END_STEP`), but CODESYS code uses them as variable
//! names. As keywords each is always followed by a name; a name never is,
//! so a keyword token not followed by a name is turned back into an
//! identifier (with a compatibility warning, W356).

use super::lexer::Spanned;
use super::token::{Kw, Tok};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};

/// Turns each `ON`/`STEP` that is not followed by a name into an
/// identifier spelled as written.
pub fn names_from_keywords(
    file: FileId,
    text: &str,
    mut tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    for i in 0..tokens.len() {
        if !matches!(tokens[i].1, Tok::Kw(Kw::On | Kw::Step)) {
            continue;
        }
        let next_is_name = tokens[i + 1..]
            .iter()
            .find(|t| t.1 != Tok::Eol)
            .is_some_and(|t| matches!(t.1, Tok::Ident(_)));
        if next_is_name {
            continue;
        }
        let (start, end) = (tokens[i].0, tokens[i].2);
        let Some(spelling) = text.get(start..end) else {
            continue;
        };
        diags.push(Diagnostic::warning(
            "W356",
            Span::new(file, start, end),
            format!("`{spelling}` is a keyword; using it as a name is a CODESYS extension"),
        ));
        tokens[i].1 = Tok::Ident(spelling.to_string());
    }
    tokens
}
