//! Formal arguments left empty, as CODESYS and TwinCAT write them
//! (`tRecover(IN := , PT := t);`, `fb(q => , done => bDone);`): an input
//! given nothing is not connected (an FB input keeps its value, a
//! function's takes its default), an output sent nowhere is not read. A
//! token pass drops each such `name :=` / `name =>` (with one comma) so
//! the call reads as if the argument were not written.

use super::lexer::Spanned;
use super::token::Tok;

/// Removes the empty formal arguments of every call.
pub fn drop_empty_arguments(tokens: Vec<Spanned>) -> Vec<Spanned> {
    let mut drop = vec![false; tokens.len()];
    let mut any = false;
    for i in 0..tokens.len().saturating_sub(2) {
        let (Tok::Ident(_), Tok::Assign | Tok::Arrow) = (&tokens[i].1, &tokens[i + 1].1) else {
            continue;
        };
        // Only inside an argument list: after `(` or `,`.
        if !matches!(
            i.checked_sub(1).map(|p| &tokens[p].1),
            Some(Tok::LParen | Tok::Comma)
        ) {
            continue;
        }
        match tokens[i + 2].1 {
            Tok::Comma => {
                drop[i] = true;
                drop[i + 1] = true;
                drop[i + 2] = true;
                any = true;
            }
            Tok::RParen => {
                drop[i] = true;
                drop[i + 1] = true;
                // `f(a := 1, b := )`: the comma before goes too.
                if tokens[i - 1].1 == Tok::Comma {
                    drop[i - 1] = true;
                }
                any = true;
            }
            _ => {}
        }
    }
    if !any {
        return tokens;
    }
    tokens
        .into_iter()
        .zip(drop)
        .filter(|(_, d)| !d)
        .map(|(t, _)| t)
        .collect()
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
    }
}
