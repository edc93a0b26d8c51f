//! The words that open a reference type: `REF_TO`, `POINTER TO` and
//! `REFERENCE TO`. They are not reserved (a variable may be called
//! `pointer`), so the lexer's words become reference-type tokens only
//! where a type is written: after `:`, `OF` or another reference word.

use crate::syntax::lexer::Spanned;
use crate::syntax::token::{Kw, Tok};

/// Rewrites the reference-type words of `toks` in place.
pub fn merge(toks: &mut Vec<Spanned>) {
    let mut i = 0;
    while i < toks.len() {
        let Tok::Ident(word) = &toks[i].1 else {
            i += 1;
            continue;
        };
        let upper = word.to_ascii_uppercase();
        if upper == "REF" && is_binding(toks, i) {
            toks[i].1 = Tok::RefAssign;
            toks[i].2 = toks[i + 1].2;
            toks.remove(i + 1);
            i += 1;
            continue;
        }
        let wants_to = match upper.as_str() {
            "REF_TO" => false,
            "POINTER" | "REFERENCE" => true,
            _ => {
                i += 1;
                continue;
            }
        };
        if !in_type_position(toks, i) {
            i += 1;
            continue;
        }
        if !wants_to {
            toks[i].1 = Tok::RefTo;
            i += 1;
            continue;
        }
        let Some(to) = next_significant(toks, i + 1) else {
            i += 1;
            continue;
        };
        if toks[to].1 != Tok::Kw(Kw::To) {
            i += 1;
            continue;
        }
        let end = toks[to].2;
        toks[i].1 = if upper == "POINTER" {
            Tok::PointerTo
        } else {
            Tok::ReferenceTo
        };
        toks[i].2 = end;
        toks.drain(i + 1..=to);
        i += 1;
    }
}

/// True if the token before `i` (line ends skipped) introduces a type.
fn in_type_position(toks: &[Spanned], i: usize) -> bool {
    let prev = toks[..i].iter().rev().find(|t| t.1 != Tok::Eol);
    matches!(
        prev.map(|t| &t.1),
        Some(Tok::Colon | Tok::Kw(Kw::Of) | Tok::RefTo | Tok::PointerTo | Tok::ReferenceTo)
    )
}

/// `REF=` written without a space after the end of a variable (a name,
/// `]` or `^`): the CODESYS binding `r REF= x`.
fn is_binding(toks: &[Spanned], i: usize) -> bool {
    let adjacent_eq = toks
        .get(i + 1)
        .is_some_and(|t| t.1 == Tok::Eq && t.0 == toks[i].2);
    let after_variable =
        i > 0 && matches!(toks[i - 1].1, Tok::Ident(_) | Tok::RBracket | Tok::Caret);
    adjacent_eq && after_variable
}

fn next_significant(toks: &[Spanned], from: usize) -> Option<usize> {
    (from..toks.len()).find(|&j| toks[j].1 != Tok::Eol)
}

#[cfg(test)]
mod tests {
    use crate::diagnostics::Diagnostics;
    use crate::source::FileId;
    use crate::syntax::lexer::lex;
    use crate::syntax::token::Tok;

    fn toks(src: &str) -> Vec<Tok> {
        let mut d = Diagnostics::default();
        lex(FileId(0), src, &mut d)
            .into_iter()
            .map(|t| t.1)
            .collect()
    }

    #[test]
    fn only_in_type_position() {
        let t = toks("p : POINTER TO REF_TO INT; pointer := 1; FOR i := pointer TO 3");
        assert_eq!(t[2], Tok::PointerTo);
        assert_eq!(t[3], Tok::RefTo);
        assert!(t.contains(&Tok::Ident("pointer".into())));
        assert_eq!(t.iter().filter(|x| **x == Tok::PointerTo).count(), 1);
        let r = toks("r : ARRAY[0..1] OF REFERENCE\nTO BOOL;");
        assert!(r.contains(&Tok::ReferenceTo));
        let b = toks("r REF= x; IF ref=1 THEN a := ref = 2; END_IF");
        assert_eq!(b[1], Tok::RefAssign);
        assert_eq!(b.iter().filter(|x| **x == Tok::RefAssign).count(), 1);
    }
}
