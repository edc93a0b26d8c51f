//! CODESYS's set and reset assignments in ST (CODESYS V3, TwinCAT 3):
//! `x S= cond;` sets `x` to TRUE when `cond` is TRUE and leaves it alone
//! otherwise; `x R= cond;` resets it. A token pass spells each as the IF
//! statement it stands for, `IF cond THEN x := TRUE; END_IF;`, before
//! parsing; the words it adds point at the `S=` / `R=`.

use super::lexer::{self, Spanned};
use super::token::{Kw, Tok};
use crate::diagnostics::Diagnostics;
use crate::source::FileId;

/// Rewrites every `place S= expr;` and `place R= expr;` statement.
pub fn set_reset_assignments(tokens: Vec<Spanned>) -> Vec<Spanned> {
    let mut out = tokens;
    let mut i = 1;
    while i + 1 < out.len() {
        let value = match (&out[i].1, &out[i + 1].1) {
            (Tok::Ident(w), Tok::Eq) if w.eq_ignore_ascii_case("S") => "TRUE",
            (Tok::Ident(w), Tok::Eq) if w.eq_ignore_ascii_case("R") => "FALSE",
            _ => {
                i += 1;
                continue;
            }
        };
        let (Some(start), Some(end)) = (place_start(&out, i), statement_end(&out, i + 2)) else {
            i += 1;
            continue;
        };
        if end == i + 2 {
            // `x S= ;`: no condition; left for the parser to report.
            i += 1;
            continue;
        }
        let (l, r) = (out[i].0, out[i + 1].2);
        let word = |text: &str| -> Vec<Spanned> {
            lexer::lex(FileId(0), text, &mut Diagnostics::new())
                .into_iter()
                .filter(|t| t.1 != Tok::Eol)
                .map(|(_, t, _)| (l, t, r))
                .collect()
        };
        let mut stmt: Vec<Spanned> = Vec::with_capacity(end - start + 8);
        stmt.extend(word("IF"));
        stmt.extend(out[i + 2..end].iter().cloned());
        stmt.extend(word("THEN"));
        stmt.extend(out[start..i].iter().cloned());
        stmt.extend(word(":="));
        stmt.extend(word(value));
        stmt.extend(word(";"));
        stmt.extend(word("END_IF"));
        let added = stmt.len();
        out.splice(start..end, stmt);
        i = start + added;
    }
    out
}

/// The first token of the variable that ends just before `op`, when it
/// starts a statement: names, `.member`, `[index]` and `^`, after a `;`,
/// a keyword, a label's `:` or the start.
fn place_start(t: &[Spanned], op: usize) -> Option<usize> {
    let mut k = op;
    loop {
        let prev = k.checked_sub(1)?;
        match &t[prev].1 {
            Tok::Ident(_) => {
                k = prev;
                // `a.b`: the member's base comes before the dot.
                match k.checked_sub(1).map(|p| &t[p].1) {
                    Some(Tok::Dot) => k -= 1,
                    _ => break,
                }
            }
            Tok::Caret => k = prev,
            Tok::RBracket => {
                let mut depth = 0usize;
                let mut j = prev;
                loop {
                    match t[j].1 {
                        Tok::RBracket => depth += 1,
                        Tok::LBracket => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                    j = j.checked_sub(1)?;
                }
                k = j;
            }
            _ => return None,
        }
    }
    if !matches!(t[k].1, Tok::Ident(_)) {
        return None;
    }
    let boundary = match k.checked_sub(1).map(|p| &t[p].1) {
        None => true,
        Some(Tok::Semi | Tok::Colon | Tok::Eol | Tok::Kw(_)) => true,
        Some(_) => false,
    };
    boundary.then_some(k)
}

/// The index of the `;` that ends the statement whose condition starts
/// at `from` (outside parentheses and brackets).
fn statement_end(t: &[Spanned], from: usize) -> Option<usize> {
    let mut depth = 0i32;
    for (j, tok) in t.iter().enumerate().skip(from) {
        match tok.1 {
            Tok::LParen | Tok::LBracket => depth += 1,
            Tok::RParen | Tok::RBracket => depth -= 1,
            Tok::Semi if depth == 0 => return Some(j),
            Tok::Kw(Kw::EndIf | Kw::EndCase | Kw::EndFor | Kw::EndWhile | Kw::Else) => return None,
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spelled(src: &str) -> String {
        let toks = lexer::lex(FileId(0), src, &mut Diagnostics::new());
        set_reset_assignments(toks)
            .iter()
            .filter(|t| t.1 != Tok::Eol)
            .map(|t| match &t.1 {
                Tok::Ident(s) => s.clone(),
                Tok::Kw(k) => k.as_str().to_string(),
                Tok::Lit(_) => "lit".into(),
                Tok::Semi => ";".into(),
                Tok::Assign => ":=".into(),
                Tok::Dot => ".".into(),
                Tok::LBracket => "[".into(),
                Tok::RBracket => "]".into(),
                Tok::Eq => "=".into(),
                other => format!("{other:?}"),
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    #[test]
    fn set_and_reset_become_if_statements() {
        assert_eq!(
            spelled("x S= a AND b;"),
            "IF a AND b THEN x := lit ; END_IF ;"
        );
        assert_eq!(
            spelled("y := 1; fb.o[i] R= c;"),
            "y := lit ; IF c THEN fb . o [ i ] := lit ; END_IF ;"
        );
        // A comparison with a variable named S is left alone.
        assert_eq!(spelled("b := a AND S = c;"), "b := a AND S = c ;");
    }
}
