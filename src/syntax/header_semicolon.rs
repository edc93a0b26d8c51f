//! A `;` right after a POU header, as CODESYS and TwinCAT write it
//! (`FUNCTION_BLOCK FB_X;`, `PROGRAM P;`, `FUNCTION F : INT;`,
//! `METHOD M : BOOL;`): dropped before parsing, since nothing else can
//! follow a header's last word there.

use super::lexer::Spanned;
use super::token::{Kw, Tok};

/// Removes the `;` that ends a POU header. A header is the keyword, then
/// only names, `.`, `,`, the modifiers, `EXTENDS`/`IMPLEMENTS` and (for
/// FUNCTION and METHOD) one `:`, then the `;`. A PROGRAM header has no
/// `:`, which keeps a configuration's `PROGRAM inst WITH t : P;` whole.
pub fn drop_header_semicolons(tokens: Vec<Spanned>) -> Vec<Spanned> {
    let mut drop = Vec::new();
    for (k, t) in tokens.iter().enumerate() {
        let colon_ok = match t.1 {
            Tok::Kw(Kw::Program | Kw::FunctionBlock) => false,
            Tok::Kw(Kw::Function | Kw::Method) => true,
            _ => continue,
        };
        if let Some(semi) = header_end(&tokens[k + 1..], colon_ok) {
            drop.push(k + 1 + semi);
        }
    }
    if drop.is_empty() {
        return tokens;
    }
    tokens
        .into_iter()
        .enumerate()
        .filter(|(k, _)| !drop.contains(k))
        .map(|(_, t)| t)
        .collect()
}

/// The index in `rest` of the `;` ending a header whose words are
/// `rest[..that]`, if they form one: on the keyword's line, at least a
/// name, and never two names in a row (`PROGRAM p x;` is a statement
/// gone wrong, not a header).
fn header_end(rest: &[Spanned], colon_ok: bool) -> Option<usize> {
    let mut names = 0;
    let mut after_name = false;
    for (k, t) in rest.iter().enumerate() {
        let is_name = matches!(t.1, Tok::Ident(_));
        if is_name && after_name {
            return None;
        }
        after_name = is_name;
        match &t.1 {
            Tok::Semi => return (names > 0).then_some(k),
            Tok::Ident(_) => names += 1,
            Tok::Dot | Tok::Comma => {}
            Tok::Colon if colon_ok && names > 0 => {
                return type_end(&rest[k + 1..]).map(|e| k + 1 + e);
            }
            Tok::Kw(
                Kw::Abstract
                | Kw::Final
                | Kw::Public
                | Kw::Private
                | Kw::Protected
                | Kw::Internal
                | Kw::Extends
                | Kw::Implements,
            ) => {}
            _ => return None,
        }
    }
    None
}

/// The index in `rest` of the `;` that ends a result type written at
/// its start: a name, or a subrange, string, array or reference type
/// (`UINT(0..N)`, `STRING(80)`, `ARRAY[1..N] OF INT`, `REFERENCE TO T`).
fn type_end(rest: &[Spanned]) -> Option<usize> {
    let mut depth = 0usize;
    for (k, t) in rest.iter().enumerate() {
        // Two words in a row are a statement after the header (`F : INT
        // Reset;`), not one type.
        let word = |t: &Tok| matches!(t, Tok::Ident(_) | Tok::Lit(_) | Tok::RParen | Tok::RBracket);
        if matches!(t.1, Tok::Ident(_) | Tok::Lit(_)) && k > 0 && word(&rest[k - 1].1) {
            return None;
        }
        match &t.1 {
            Tok::Semi if depth == 0 && k > 0 => return Some(k),
            Tok::LParen | Tok::LBracket => depth += 1,
            Tok::RParen | Tok::RBracket => depth = depth.checked_sub(1)?,
            Tok::Comma if depth > 0 => {}
            Tok::Ident(_)
            | Tok::Dot
            | Tok::Lit(_)
            | Tok::DotDot
            | Tok::Plus
            | Tok::Minus
            | Tok::Star
            | Tok::Slash
            | Tok::RefTo
            | Tok::PointerTo
            | Tok::ReferenceTo
            | Tok::Kw(Kw::Array | Kw::Of | Kw::String | Kw::WString) => {}
            _ => return None,
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(words: &[Tok]) -> Vec<Spanned> {
        words.iter().cloned().map(|t| (0, t, 0)).collect()
    }

    #[test]
    fn only_a_header_semicolon_goes() {
        let name = |s: &str| Tok::Ident(s.to_string());
        let fb = toks(&[Tok::Kw(Kw::FunctionBlock), name("F"), Tok::Semi]);
        assert_eq!(drop_header_semicolons(fb).len(), 2);
        // PROGRAM inst WITH t : P; in a configuration keeps its `;`.
        let cfg = toks(&[
            Tok::Kw(Kw::Program),
            name("inst"),
            Tok::Colon,
            name("P"),
            Tok::Semi,
        ]);
        assert_eq!(drop_header_semicolons(cfg).len(), 5);
        // A one-line FB whose first `;` ends a declaration keeps it.
        let one = toks(&[
            Tok::Kw(Kw::FunctionBlock),
            name("F"),
            Tok::Kw(Kw::Var),
            name("x"),
            Tok::Colon,
            name("INT"),
            Tok::Semi,
        ]);
        assert_eq!(drop_header_semicolons(one).len(), 7);
        // `PROGRAM p` then a bare statement `x;`: not a header.
        let bare = toks(&[
            Tok::Kw(Kw::Program),
            name("p"),
            Tok::Eol,
            name("x"),
            Tok::Semi,
        ]);
        assert_eq!(drop_header_semicolons(bare).len(), 5);
        let two = toks(&[Tok::Kw(Kw::Program), name("p"), name("x"), Tok::Semi]);
        assert_eq!(drop_header_semicolons(two).len(), 4);
        // `METHOD M : UINT(0..N);` (TcUnit) loses its `;`.
        let sub = toks(&[
            Tok::Kw(Kw::Method),
            name("M"),
            Tok::Colon,
            name("UINT"),
            Tok::LParen,
            name("LO"),
            Tok::DotDot,
            name("N"),
            Tok::RParen,
            Tok::Semi,
        ]);
        assert_eq!(drop_header_semicolons(sub).len(), 9);
        // `FUNCTION F : INT` then the statement `Reset;` keeps it.
        let stmt = toks(&[
            Tok::Kw(Kw::Function),
            name("F"),
            Tok::Colon,
            name("INT"),
            name("Reset"),
            Tok::Semi,
        ]);
        assert_eq!(drop_header_semicolons(stmt).len(), 6);
    }
}
