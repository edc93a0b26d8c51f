//! A `;` standing alone in a declaration block (`x : INT := 2;;`, or right
//! after `VAR`), which CODESYS and TwinCAT accept as an empty declaration:
//! dropped before parsing, with a compatibility warning (W360).

use super::empty_init_call::opens_declarations;
use super::lexer::Spanned;
use super::token::{Kw, Tok};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};

/// Removes each `;` of a declaration block that follows another `;` or
/// the block's opening line (`VAR`, `VAR CONSTANT`, `VAR RETAIN`...).
pub fn drop_empty_declarations(
    file: FileId,
    tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    let mut drop = Vec::new();
    let mut in_declarations = false;
    // Whether the last token kept (line ends aside) ends a declaration
    // or opens the block, so that a `;` now would declare nothing.
    let mut at_start = false;
    for (k, t) in tokens.iter().enumerate() {
        match &t.1 {
            Tok::Eol => continue,
            tok if opens_declarations(tok) => {
                in_declarations = true;
                at_start = true;
                continue;
            }
            Tok::Kw(Kw::EndVar) => in_declarations = false,
            Tok::Semi if in_declarations && at_start => {
                diags.push(Diagnostic::warning(
                    "W360",
                    Span::new(file, t.0, t.2),
                    "an empty declaration (`;` alone) is a CODESYS extension",
                ));
                drop.push(k);
                continue;
            }
            _ => {}
        }
        at_start = match &t.1 {
            Tok::Semi => true,
            // `VAR CONSTANT`, `VAR RETAIN`, `VAR_GLOBAL PERSISTENT`...
            Tok::Kw(Kw::Constant | Kw::Retain | Kw::NonRetain | Kw::Persistent) => at_start,
            _ => false,
        };
    }
    if drop.is_empty() {
        return tokens;
    }
    tokens
        .into_iter()
        .enumerate()
        .filter(|(k, _)| drop.binary_search(k).is_err())
        .map(|(_, t)| t)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(src: &str) -> (Vec<Tok>, usize) {
        let mut diags = Diagnostics::new();
        let toks = crate::syntax::lexer::lex(FileId(0), src, &mut Diagnostics::new());
        let toks = drop_empty_declarations(FileId(0), toks, &mut diags);
        (toks.into_iter().map(|t| t.1).collect(), diags.len())
    }

    #[test]
    fn doubled_and_leading_semicolons_in_a_block_are_dropped() {
        let (toks, warnings) = kept("VAR ; x : INT;; y : INT; END_VAR");
        assert_eq!(warnings, 2);
        assert_eq!(toks.iter().filter(|t| **t == Tok::Semi).count(), 2);
    }

    #[test]
    fn empty_statements_in_a_body_are_left_alone() {
        let (toks, warnings) = kept("VAR x : INT; END_VAR x := 1;; ;");
        assert_eq!(warnings, 0);
        assert_eq!(toks.iter().filter(|t| **t == Tok::Semi).count(), 4);
    }
}
