//! The IL line-orientation pass (see `docs/adr/0001-il-line-orientation.md`).
//!
//! The lexer keeps every line break as [`Tok::Eol`]. This pass finds the
//! bodies written in Instruction List — POU bodies, ACTION bodies and
//! TRANSITION bodies introduced by `:` — and, only there, keeps one `Eol`
//! per non-empty line and retags the first word of each line as an IL
//! operator token. Everywhere else line breaks are dropped, so ST and SFC
//! stay free-form.
//!
//! A body is IL when its first word, at the start of a line, is an IL
//! operator form (`LD`, `LDN`, `ST`, `CAL`, `JMPC`, `AND(`...) not followed
//! by something only ST allows (`:=`, `.`, `[`), or a label `name:`.
//! The language is recognised from content, never from a file extension.

use crate::syntax::ast::IlOperator;
use crate::syntax::lexer::Spanned;
use crate::syntax::token::{IlOpCode, Kw, Tok};

/// Keeps or drops line breaks and retags IL operator words; see the module
/// documentation.
pub fn keep_il_lines(mut tokens: Vec<Spanned>) -> Vec<Spanned> {
    let regions = il_regions(&tokens);
    if regions.is_empty() {
        // No IL: the line breaks go, in place (a repair trial runs this
        // hundreds of times; nothing is cloned).
        tokens.retain(|t| t.1 != Tok::Eol);
        return tokens;
    }
    let mut out = Vec::with_capacity(tokens.len());
    let mut next_region = regions.iter().peekable();
    let mut i = 0;
    while i < tokens.len() {
        if let Some(&&(s, e)) = next_region.peek()
            && s == i
        {
            emit_il(&tokens[s..e], &mut out);
            next_region.next();
            i = e;
            continue;
        }
        if tokens[i].1 != Tok::Eol {
            out.push(tokens[i].clone());
        }
        i += 1;
    }
    out
}

/// What a word in IL operator position means.
pub fn il_retag(tok: &Tok) -> Option<Tok> {
    let word = match tok {
        Tok::Ident(s) => s.to_ascii_uppercase(),
        Tok::Kw(k @ (Kw::And | Kw::Or | Kw::Xor | Kw::Not | Kw::Mod)) => k.as_str().to_string(),
        Tok::Amp => "AND".to_string(),
        _ => return None,
    };
    use IlOperator as O;
    let simple = |op, negate| Some(Tok::IlOp(IlOpCode { op, negate }));
    match word.as_str() {
        "LD" => simple(O::Ld, false),
        "LDN" => simple(O::Ld, true),
        "ST" => simple(O::St, false),
        "STN" => simple(O::St, true),
        "S" => simple(O::S, false),
        "R" => simple(O::R, false),
        "AND" => simple(O::And, false),
        "ANDN" => simple(O::And, true),
        "OR" => simple(O::Or, false),
        "ORN" => simple(O::Or, true),
        "XOR" => simple(O::Xor, false),
        "XORN" => simple(O::Xor, true),
        "NOT" => simple(O::Not, false),
        "ADD" => simple(O::Add, false),
        "SUB" => simple(O::Sub, false),
        "MUL" => simple(O::Mul, false),
        "DIV" => simple(O::Div, false),
        "MOD" => simple(O::Mod, false),
        "GT" => simple(O::Gt, false),
        "GE" => simple(O::Ge, false),
        "EQ" => simple(O::Eq, false),
        "NE" => simple(O::Ne, false),
        "LE" => simple(O::Le, false),
        "LT" => simple(O::Lt, false),
        "JMP" => Some(Tok::IlJmp(None)),
        "JMPC" => Some(Tok::IlJmp(Some(true))),
        "JMPCN" => Some(Tok::IlJmp(Some(false))),
        "CAL" => Some(Tok::IlCal(None)),
        "CALC" => Some(Tok::IlCal(Some(true))),
        "CALCN" => Some(Tok::IlCal(Some(false))),
        "RET" => Some(Tok::IlRet(None)),
        "RETC" => Some(Tok::IlRet(Some(true))),
        "RETCN" => Some(Tok::IlRet(Some(false))),
        "S1" | "R1" | "CLK" | "CU" | "CD" | "PV" | "IN" | "PT" => match tok {
            Tok::Ident(s) => Some(Tok::IlFbIn(s.clone())),
            _ => None,
        },
        _ => match tok {
            Tok::Ident(s) => Some(Tok::IlFun(s.clone())),
            _ => None,
        },
    }
}

/// Index of the next non-`Eol` token at or after `i`.
fn next_sig(tokens: &[Spanned], mut i: usize) -> usize {
    while i < tokens.len() && tokens[i].1 == Tok::Eol {
        i += 1;
    }
    i
}

fn kw_at(tokens: &[Spanned], i: usize) -> Option<Kw> {
    match tokens.get(i) {
        Some((_, Tok::Kw(k), _)) => Some(*k),
        _ => None,
    }
}

/// Does the body whose first significant token is at `i` look like IL?
fn looks_like_il(tokens: &[Spanned], i: usize) -> bool {
    let Some((_, tok, _)) = tokens.get(i) else {
        return false;
    };
    let next = tokens.get(i + 1).map(|t| &t.1);
    if matches!(tok, Tok::Ident(_)) && next == Some(&Tok::Colon) {
        return true;
    }
    let st_only = matches!(
        next,
        Some(
            Tok::Assign
                | Tok::Dot
                | Tok::LBracket
                | Tok::Arrow
                | Tok::Semi
                | Tok::Caret
                | Tok::RefAssign
                | Tok::AssignAttempt
        )
    );
    match il_retag(tok) {
        Some(Tok::IlOp(code)) => {
            let deferrable = !matches!(
                code.op,
                IlOperator::Ld | IlOperator::St | IlOperator::S | IlOperator::R | IlOperator::Not
            );
            !st_only && (next != Some(&Tok::LParen) || deferrable)
        }
        Some(Tok::IlJmp(_) | Tok::IlCal(_) | Tok::IlRet(_)) => {
            !st_only && next != Some(&Tok::LParen)
        }
        _ => false,
    }
}

/// Finds the IL bodies: `(start, end)` token index ranges.
fn il_regions(tokens: &[Spanned]) -> Vec<(usize, usize)> {
    let mut regions = Vec::new();
    let n = tokens.len();
    let find = |from: usize, pred: &dyn Fn(Kw) -> bool| {
        (from..n)
            .find(|&j| kw_at(tokens, j).is_some_and(pred))
            .unwrap_or(n)
    };
    let mut i = 0;
    while i < n {
        match kw_at(tokens, i) {
            Some(Kw::Configuration) => i = find(i + 1, &|k| k == Kw::EndConfiguration) + 1,
            Some(Kw::Type) => i = find(i + 1, &|k| k == Kw::EndType) + 1,
            Some(Kw::Program | Kw::Function | Kw::FunctionBlock) => {
                let end = find(i + 1, &|k| {
                    matches!(
                        k,
                        Kw::EndProgram
                            | Kw::EndFunction
                            | Kw::EndFunctionBlock
                            | Kw::Program
                            | Kw::Function
                            | Kw::FunctionBlock
                            | Kw::Configuration
                            | Kw::Type
                    )
                });
                let start = match crate::syntax::method_bodies::classify_methods(
                    tokens,
                    i,
                    end,
                    &mut |s, e, r| classify_body(tokens, s, e, r),
                    &mut regions,
                ) {
                    Some(after_methods) => after_methods,
                    None => body_start(tokens, i, end),
                };
                classify_body(tokens, start, end, &mut regions);
                i = if matches!(
                    kw_at(tokens, end),
                    Some(Kw::EndProgram | Kw::EndFunction | Kw::EndFunctionBlock)
                ) {
                    end + 1
                } else {
                    end
                };
            }
            _ => i += 1,
        }
    }
    regions
}

/// First token of a POU body: after the last END_VAR, else after the header.
pub(crate) fn body_start(tokens: &[Spanned], pou: usize, end: usize) -> usize {
    if let Some(last) = (pou..end)
        .rev()
        .find(|&j| kw_at(tokens, j) == Some(Kw::EndVar))
    {
        return last + 1;
    }
    // Header: keyword, name, and for a FUNCTION `: type`.
    let mut j = next_sig(tokens, pou + 1);
    j = next_sig(tokens, j + 1);
    if tokens.get(j).map(|t| &t.1) == Some(&Tok::Colon) {
        j = next_sig(tokens, j + 1);
        match tokens.get(j).map(|t| &t.1) {
            Some(Tok::Kw(Kw::Array)) => {
                let of = (j..end).find(|&k| kw_at(tokens, k) == Some(Kw::Of));
                j = of.map(|k| next_sig(tokens, k + 1) + 1).unwrap_or(end);
            }
            Some(Tok::Kw(Kw::String | Kw::WString)) => {
                let k = next_sig(tokens, j + 1);
                j = match tokens.get(k).map(|t| &t.1) {
                    Some(Tok::LBracket | Tok::LParen) => (k..end)
                        .find(|&q| matches!(tokens[q].1, Tok::RBracket | Tok::RParen))
                        .map(|q| q + 1)
                        .unwrap_or(end),
                    _ => j + 1,
                };
            }
            _ => j += 1,
        }
    }
    j.min(end)
}

/// Decides the language of the body `start..end`; for ST/SFC bodies, looks
/// into ACTION and TRANSITION bodies.
fn classify_body(tokens: &[Spanned], start: usize, end: usize, regions: &mut Vec<(usize, usize)>) {
    let first = next_sig(tokens, start);
    if first >= end {
        return;
    }
    if looks_like_il(tokens, first) {
        regions.push((first, end));
        return;
    }
    let mut q = first;
    while q < end {
        match kw_at(tokens, q) {
            Some(Kw::Action) => {
                let a_end = (q + 1..end)
                    .find(|&j| kw_at(tokens, j) == Some(Kw::EndAction))
                    .unwrap_or(end);
                let colon = (q + 1..a_end.min(q + 4)).find(|&j| tokens[j].1 == Tok::Colon);
                if let Some(c) = colon {
                    let b = next_sig(tokens, c + 1);
                    if b < a_end && looks_like_il(tokens, b) {
                        regions.push((b, a_end));
                    }
                }
                q = a_end + 1;
            }
            Some(Kw::Transition) => {
                let t_end = (q + 1..end)
                    .find(|&j| kw_at(tokens, j) == Some(Kw::EndTransition))
                    .unwrap_or(end);
                let mut depth = 0i32;
                let mut colon = None;
                for (j, t) in tokens.iter().enumerate().take(t_end).skip(q + 1) {
                    match t.1 {
                        Tok::LParen => depth += 1,
                        Tok::RParen => depth -= 1,
                        Tok::Assign if depth == 0 => break,
                        Tok::Colon if depth == 0 => {
                            colon = Some(j);
                            break;
                        }
                        _ => {}
                    }
                }
                if let Some(c) = colon {
                    let b = next_sig(tokens, c + 1);
                    if b < t_end {
                        regions.push((b, t_end));
                    }
                }
                q = t_end + 1;
            }
            _ => q += 1,
        }
    }
}

/// Emits one IL body: one `Eol` per non-empty line, labels and operator
/// words retagged, line breaks inside `CAL inst( ... )` and function-call
/// argument parentheses ignored.
fn emit_il(body: &[Spanned], out: &mut Vec<Spanned>) {
    let mut line_start = true;
    let mut op_pos = false;
    let mut track_parens = false;
    let mut depth = 0u32;
    let mut last_end = body.first().map(|t| t.0).unwrap_or(0);
    let mut i = 0;
    while i < body.len() {
        let (s, tok, e) = &body[i];
        if *tok == Tok::Eol {
            if !(line_start || (track_parens && depth > 0)) {
                out.push((*s, Tok::Eol, *e));
                line_start = true;
                op_pos = false;
                track_parens = false;
                depth = 0;
            }
            i += 1;
            continue;
        }
        last_end = *e;
        if line_start {
            line_start = false;
            op_pos = true;
            if let Tok::Ident(name) = tok
                && body.get(i + 1).map(|t| &t.1) == Some(&Tok::Colon)
            {
                out.push((*s, Tok::IlLabel(name.clone()), *e));
                let colon = &body[i + 1];
                out.push((colon.0, Tok::Colon, colon.2));
                last_end = colon.2;
                i += 2;
                continue;
            }
        }
        if op_pos {
            op_pos = false;
            // `&N` is written without a space.
            if *tok == Tok::Amp
                && let Some((ns, Tok::Ident(n), ne)) = body.get(i + 1)
                && *ns == *e
                && n.eq_ignore_ascii_case("N")
            {
                let code = IlOpCode {
                    op: IlOperator::And,
                    negate: true,
                };
                out.push((*s, Tok::IlOp(code), *ne));
                last_end = *ne;
                i += 2;
                continue;
            }
            if let Some(t) = il_retag(tok) {
                track_parens = matches!(t, Tok::IlCal(_) | Tok::IlFun(_));
                out.push((*s, t, *e));
                i += 1;
                continue;
            }
        }
        if track_parens {
            match tok {
                Tok::LParen => depth += 1,
                Tok::RParen => depth = depth.saturating_sub(1),
                _ => {}
            }
        }
        out.push((*s, tok.clone(), *e));
        i += 1;
    }
    if !line_start {
        out.push((last_end, Tok::Eol, last_end));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::Diagnostics;
    use crate::source::FileId;
    use crate::syntax::lexer::lex;

    fn kinds(src: &str) -> Vec<String> {
        let toks = keep_il_lines(lex(FileId(0), src, &mut Diagnostics::new()));
        toks.into_iter()
            .map(|(_, t, _)| match t {
                Tok::Eol => "EOL".to_string(),
                Tok::IlOp(c) => format!("op:{:?}{}", c.op, if c.negate { "N" } else { "" }),
                Tok::IlLabel(l) => format!("label:{l}"),
                Tok::IlCal(_) => "cal".to_string(),
                Tok::IlFun(f) => format!("fun:{f}"),
                Tok::Ident(i) => i,
                Tok::Kw(k) => k.as_str().to_string(),
                other => format!("{other:?}"),
            })
            .collect()
    }

    #[test]
    fn il_body_keeps_line_ends_and_retags_operators() {
        let k = kinds(
            "PROGRAM p\nVAR END_VAR\n\n  l1: LDN a (* c *)\n\n  AND( b\n  )\n  MAX c\nEND_PROGRAM",
        );
        assert_eq!(
            k.join(" "),
            "PROGRAM p VAR END_VAR label:l1 Colon op:LdN a EOL op:And LParen b EOL RParen EOL fun:MAX c EOL END_PROGRAM"
        );
    }

    #[test]
    fn st_body_drops_line_ends() {
        let k = kinds("PROGRAM p\nST := 1;\nLD\n:= 2;\nEND_PROGRAM");
        assert!(!k.contains(&"EOL".to_string()), "{k:?}");
        assert!(k.contains(&"ST".to_string()));
    }

    #[test]
    fn multi_line_cal_is_one_line() {
        let k = kinds("PROGRAM p\nCAL t(\n IN := x\n |\n q := Q\n)\nLD q\nEND_PROGRAM");
        assert_eq!(k.iter().filter(|t| *t == "EOL").count(), 2, "{k:?}");
    }

    #[test]
    fn il_transition_and_action_bodies() {
        let k = kinds(
            "PROGRAM p\nSTEP s : END_STEP\nTRANSITION FROM s TO s : LD a\nAND b\nEND_TRANSITION\n\
             ACTION a :\nLD x\nST y\nEND_ACTION\nACTION b : x := 1;\nEND_ACTION\nEND_PROGRAM",
        );
        assert_eq!(k.iter().filter(|t| *t == "EOL").count(), 4, "{k:?}");
    }

    #[test]
    fn configuration_programs_are_not_pous() {
        let k = kinds("CONFIGURATION c\nPROGRAM i : LD;\nEND_CONFIGURATION");
        assert!(!k.contains(&"EOL".to_string()), "{k:?}");
    }
}
