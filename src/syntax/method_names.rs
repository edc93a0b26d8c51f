//! Methods named like a keyword that CODESYS does not reserve (`Step`,
//! `Task`, `Transition`, `With`...): CODESYS code names methods so. Each
//! such keyword written as the name after `METHOD` (and its modifiers) is
//! an identifier, with one compatibility warning (W390) at the
//! declaration; elsewhere the same keyword is an identifier where only a
//! name can stand: after `.` (`inst.Step()`), or before `(` or `:=` (a
//! call inside the FB, the result assigned in the method). As keywords,
//! none of them is ever followed by `(` or `:=` or preceded by `.`.

use super::lexer::Spanned;
use super::token::{Kw, Tok};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};

/// Keywords of plcrun that CODESYS accepts as method names.
const SOFT: &[Kw] = &[
    Kw::Step,
    Kw::InitialStep,
    Kw::Transition,
    Kw::Task,
    Kw::Resource,
    Kw::Configuration,
    Kw::With,
    Kw::On,
    Kw::From,
];

const MODIFIERS: &[Kw] = &[
    Kw::Public,
    Kw::Private,
    Kw::Protected,
    Kw::Internal,
    Kw::Abstract,
    Kw::Final,
];

fn sig(tokens: &[Spanned], mut i: usize, forward: bool) -> Option<usize> {
    loop {
        if !forward {
            i = i.checked_sub(1)?;
        }
        let t = tokens.get(i)?;
        if t.1 != Tok::Eol {
            return Some(i);
        }
        if forward {
            i += 1;
        }
    }
}

fn kw(tokens: &[Spanned], i: usize) -> Option<Kw> {
    match tokens.get(i) {
        Some((_, Tok::Kw(k), _)) => Some(*k),
        _ => None,
    }
}

/// Turns keywords used as method names into identifiers; see the module
/// documentation.
pub fn method_names(
    file: FileId,
    text: &str,
    mut tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    let mut named: Vec<Kw> = Vec::new();
    for i in 0..tokens.len() {
        if kw(&tokens, i) != Some(Kw::Method) {
            continue;
        }
        let mut at = sig(&tokens, i + 1, true);
        while let Some(j) = at.filter(|&j| kw(&tokens, j).is_some_and(|k| MODIFIERS.contains(&k))) {
            at = sig(&tokens, j + 1, true);
        }
        let Some(j) = at else { continue };
        let Some(k) = kw(&tokens, j).filter(|k| SOFT.contains(k)) else {
            continue;
        };
        let (start, end) = (tokens[j].0, tokens[j].2);
        let Some(spelling) = text.get(start..end) else {
            continue;
        };
        diags.push(Diagnostic::warning(
            "W390",
            Span::new(file, start, end),
            format!("a method named `{spelling}` (a keyword) is a CODESYS extension"),
        ));
        tokens[j].1 = Tok::Ident(spelling.to_string());
        if !named.contains(&k) {
            named.push(k);
        }
    }
    if named.is_empty() {
        return tokens;
    }
    for i in 0..tokens.len() {
        if !kw(&tokens, i).is_some_and(|k| named.contains(&k)) {
            continue;
        }
        let after_dot = sig(&tokens, i, false).is_some_and(|p| tokens[p].1 == Tok::Dot);
        let before_call = sig(&tokens, i + 1, true)
            .is_some_and(|n| matches!(tokens[n].1, Tok::LParen | Tok::Assign));
        if !(after_dot || before_call) {
            continue;
        }
        let (start, end) = (tokens[i].0, tokens[i].2);
        if let Some(spelling) = text.get(start..end) {
            tokens[i].1 = Tok::Ident(spelling.to_string());
        }
    }
    tokens
}
