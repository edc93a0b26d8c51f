//! `ON`, `STEP` and `TRANSITION` as names. They are keywords (`RESOURCE r
//! ON cpu`, `STEP s1 : ... END_STEP`, `TRANSITION FROM s1 TO s2`), but
//! CODESYS code uses them as variable names and enumeration values. As
//! keywords each is followed by a name (a `TRANSITION` also by `FROM` or
//! its `(PRIORITY := n)`); a name never is, so a keyword token followed by
//! anything else is turned back into an identifier (with a compatibility
//! warning, W356).

use super::lexer::Spanned;
use super::token::{Kw, Tok};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};

/// Turns each `ON`/`STEP`/`TRANSITION` that does not start what the
/// keyword starts into an identifier spelled as written.
pub fn names_from_keywords(
    file: FileId,
    text: &str,
    mut tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    for i in 0..tokens.len() {
        let transition = match tokens[i].1 {
            Tok::Kw(Kw::On | Kw::Step) => false,
            Tok::Kw(Kw::Transition) => true,
            _ => continue,
        };
        let next = tokens[i + 1..].iter().find(|t| t.1 != Tok::Eol);
        let keyword = next.is_some_and(|t| match t.1 {
            Tok::Ident(_) => true,
            Tok::Kw(Kw::From) | Tok::LParen => transition,
            _ => false,
        });
        if keyword {
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
