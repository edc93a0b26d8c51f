//! Formal arguments left empty, as CODESYS and TwinCAT write them
//! (`tRecover(IN := , PT := t);`, `fb(q => , done => bDone);`): an input
//! given nothing is not connected (an FB input keeps its value, a
//! function's takes its default), an output sent nowhere is not read. A
//! token pass drops each such `name :=` / `name =>` (with one comma) so
//! the call reads as if the argument were not written.

use super::lexer::Spanned;
use super::token::Tok;

/// The index of the nearest token before `i` that is not a line end.
fn before(t: &[Spanned], i: usize) -> Option<usize> {
    (0..i).rev().find(|&k| t[k].1 != Tok::Eol)
}

/// The index of the nearest token after `i` that is not a line end.
fn after(t: &[Spanned], i: usize) -> Option<usize> {
    (i + 1..t.len()).find(|&k| t[k].1 != Tok::Eol)
}

/// Removes the empty formal arguments of every call (line ends between
/// the words do not matter: such calls are often one argument a line).
pub fn drop_empty_arguments(tokens: Vec<Spanned>) -> Vec<Spanned> {
    let mut drop = vec![false; tokens.len()];
    let mut any = false;
    for i in 0..tokens.len() {
        let Tok::Ident(_) = tokens[i].1 else { continue };
        let Some(op) =
            after(&tokens, i).filter(|&k| matches!(tokens[k].1, Tok::Assign | Tok::Arrow))
        else {
            continue;
        };
        let Some(next) = after(&tokens, op) else {
            continue;
        };
        // Only inside an argument list: after `(` or `,`.
        if before(&tokens, i).is_none_or(|k| !matches!(tokens[k].1, Tok::LParen | Tok::Comma)) {
            continue;
        }
        match tokens[next].1 {
            Tok::Comma => {
                drop[i] = true;
                drop[op] = true;
                drop[next] = true;
                any = true;
            }
            Tok::RParen => {
                drop[i] = true;
                drop[op] = true;
                // `f(a := 1, b := )`: the comma before goes too (the
                // nearest one still kept).
                let kept = (0..i).rev().find(|&k| tokens[k].1 != Tok::Eol && !drop[k]);
                if let Some(k) = kept.filter(|&k| tokens[k].1 == Tok::Comma) {
                    drop[k] = true;
                }
                any = true;
            }
            _ => {}
        }
    }
    if !any {
        return tokens;
    }
    super::lexer::without_marked(tokens, drop)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::Diagnostics;
    use crate::source::FileId;

    fn spelled(src: &str) -> String {
        let toks = crate::syntax::lexer::lex(FileId(0), src, &mut Diagnostics::new());
        drop_empty_arguments(toks)
            .iter()
            .filter(|t| t.1 != Tok::Eol)
            .map(|t| match &t.1 {
                Tok::Ident(s) => s.clone(),
                Tok::Assign => ":=".into(),
                Tok::Arrow => "=>".into(),
                Tok::Comma => ",".into(),
                Tok::LParen => "(".into(),
                Tok::RParen => ")".into(),
                Tok::Semi => ";".into(),
                _ => "?".into(),
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    #[test]
    fn empty_inputs_and_outputs_are_dropped_with_one_comma() {
        assert_eq!(spelled("t(IN := , PT := p);"), "t ( PT := p ) ;");
        assert_eq!(spelled("t(IN := x, q => );"), "t ( IN := x ) ;");
        assert_eq!(spelled("t(q => , d => , e => y);"), "t ( e => y ) ;");
        assert_eq!(spelled("t(a := );"), "t ( ) ;");
        // A statement `x := ;` is not an argument: left for the parser.
        assert_eq!(spelled("x := ;"), "x := ;");
        assert_eq!(
            spelled("t(\n  IN := x,\n  q => ,\n  d =>\n);"),
            "t ( IN := x ) ;"
        );
    }
}
