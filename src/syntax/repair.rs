//! One typo, one error: after a syntax error, the parser's own recovery
//! skips text, and what it skipped (a declaration block, the end of an
//! `IF`) turns into more errors further on. Before settling for that, the
//! single-token edits near the place the parser stopped are tried —
//! delete a token, insert one, replace one — and when one of them lets
//! the whole top-level item parse, the file is read as so repaired: one
//! error is reported, at the edit, and the repaired text is what the
//! checker sees (it is most often the text the typo damaged). The program
//! is still refused: the repair only decides what else gets reported.
//!
//! Only punctuation and structural keywords are inserted (never a name, a
//! literal or a type, which would give the program a meaning it does not
//! have), and a trial parses only the item holding the error (from the
//! last `END_PROGRAM`/`END_FUNCTION`/... before it to the next one after
//! it), so the search stays cheap on large files.

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};
use crate::syntax::ast::CompilationUnit;
use crate::syntax::construct::{Failure, State};
use crate::syntax::il_lines::keep_il_lines;
use crate::syntax::lexer::Spanned;
use crate::syntax::parser;
use crate::syntax::token::{Kw, Tok};

/// Most errors repaired per file (each is reported once).
const MAX_REPAIRS: usize = 4;

/// Tokens before the one the parser stopped at where an edit is tried
/// (a typo is often found a token or two after it was made).
const LOOK_BACK: usize = 3;

/// Largest item (in tokens) searched for a repair; beyond it the parser's
/// recovery alone reports.
const MAX_ITEM_TOKENS: usize = 20_000;

/// Tokens tried at every place, in order of preference: the terminators,
/// brackets and block keywords a typo most often loses.
const STRUCTURAL: [&str; 34] = [
    ";",
    ":=",
    ":",
    ",",
    ")",
    "(",
    "]",
    "[",
    ".",
    "..",
    "=>",
    "THEN",
    "DO",
    "OF",
    "TO",
    "ELSE",
    "END_IF",
    "END_VAR",
    "END_FOR",
    "END_WHILE",
    "END_CASE",
    "END_REPEAT",
    "END_STEP",
    "END_TRANSITION",
    "END_ACTION",
    "END_STRUCT",
    "END_TYPE",
    "VAR",
    "IF",
    "FROM",
    "STEP",
    "TRANSITION",
    "end of line",
    "END_PROGRAM",
];

/// Words never inserted: they would change what the program means (a
/// type, an operand, an operator) rather than restore its shape.
const NEVER_INSERTED: [&str; 17] = [
    "STRING",
    "WSTRING",
    "ARRAY",
    "NOT",
    "AND",
    "OR",
    "XOR",
    "MOD",
    "RETURN",
    "EXIT",
    "CONTINUE",
    "THIS^",
    "SUPER^",
    "REF_TO",
    "POINTER TO",
    "REFERENCE TO",
    "AT",
];

/// Parses a file's tokens (after the lexer's passes, before the IL line
/// pass), repairing single-token typos as described in the module comment.
/// `tokens_of` makes the tokens: once for the parse, reporting into
/// `diags`, and again only if a repair is searched for (so that a large
/// file that parses is not held twice while it is parsed).
pub fn parse_repairing(
    file: FileId,
    text: &str,
    tokens_of: &dyn Fn(&mut Diagnostics) -> Vec<Spanned>,
    diags: &mut Diagnostics,
) -> CompilationUnit {
    // The tokens as edited so far, once a repair has been searched for.
    let mut edited: Option<Vec<Spanned>> = None;
    let mut repairs: Vec<Diagnostic> = Vec::new();
    loop {
        let tokens = match &edited {
            Some(t) => t.clone(),
            None => tokens_of(diags),
        };
        let mut found = Diagnostics::new();
        let (unit, failure) =
            parser::parse_tokens_noting(State::new(file, text), keep_il_lines(tokens), &mut found);
        let repaired = match failure {
            Some(f) if repairs.len() < MAX_REPAIRS => {
                let tokens = edited.get_or_insert_with(|| tokens_of(&mut Diagnostics::new()));
                find_repair(file, text, tokens, &f)
            }
            _ => None,
        };
        match repaired {
            Some((next, d)) => {
                edited = Some(next);
                repairs.push(d);
            }
            None => {
                // Earlier repairs first, in file order with the rest.
                let sort = !repairs.is_empty();
                let mut all: Vec<Diagnostic> = repairs;
                all.extend(found.iter().cloned());
                if sort {
                    all.sort_by_key(|d| d.span.start);
                }
                for d in all {
                    diags.push(d);
                }
                return unit;
            }
        }
    }
}

/// One single-token edit.
#[derive(Debug, Clone)]
enum Edit {
    Delete(usize),
    Insert(usize, Tok),
    Replace(usize, Tok),
}

/// The first edit (nearest the failure, in the order of [`STRUCTURAL`])
/// after which the item holding the failure parses cleanly: the edited
/// token list and the error to report.
fn find_repair(
    file: FileId,
    text: &str,
    tokens: &[Spanned],
    failure: &Failure,
) -> Option<(Vec<Spanned>, Diagnostic)> {
    let k = tokens.partition_point(|t| t.0 < failure.at);
    let places = places_before(tokens, k);
    let first = *places.last()?;
    let start = item_start(tokens, first);
    let end = item_end(tokens, k);
    if end - start > MAX_ITEM_TOKENS {
        return None;
    }
    let at_failure = candidates(&failure.expected);
    let anywhere = candidates(&[]);
    let base = State::new(file, text);
    let parses = |edit: &Edit| {
        let trial = apply(&tokens[start..end], edit, start);
        let st = base.trial();
        parser::parses_cleanly(&st, keep_il_lines(trial)) && st.finish().is_empty()
    };
    let at_line_end = candidates(&[
        String::from("\")\""),
        String::from("\";\""),
        String::from("\",\""),
    ]);
    for &p in &places {
        let words = if p == k {
            &at_failure
        } else if tokens[p].1 == Tok::Eol {
            // In IL, what a line lacks at its end; elsewhere the same as
            // before the next token.
            &at_line_end
        } else {
            &anywhere
        };
        for edit in edits_at(tokens, p, words) {
            if parses(&edit) {
                let edit = match edit {
                    Edit::Insert(p, tok) => {
                        Edit::Insert(where_indented(tokens, p, &tok, &parses), tok)
                    }
                    other => other,
                };
                let d = report(text, file, tokens, k, &edit, failure);
                return Some((apply(tokens, &edit, 0), d));
            }
        }
    }
    None
}

/// The edits tried at token `p`, most likely first: a token written
/// twice is deleted first; otherwise a token is inserted before it, then
/// it is replaced, then deleted. Before a line end only insertions are
/// tried.
fn edits_at(tokens: &[Spanned], p: usize, words: &[Tok]) -> Vec<Edit> {
    let mut edits = Vec::with_capacity(2 * words.len() + 1);
    let here = tokens.get(p).map(|t| &t.1).filter(|t| **t != Tok::Eol);
    let twice = here.is_some_and(|t| {
        tokens[..p]
            .iter()
            .rev()
            .find(|t| t.1 != Tok::Eol)
            .map(|t| &t.1)
            == Some(t)
    });
    if twice {
        edits.push(Edit::Delete(p));
    }
    edits.extend(words.iter().map(|t| Edit::Insert(p, t.clone())));
    if let Some(here) = here {
        edits.extend(
            words
                .iter()
                .filter(|t| *t != here)
                .map(|t| Edit::Replace(p, t.clone())),
        );
        if !twice {
            edits.push(Edit::Delete(p));
        }
    }
    edits
}

/// Where a missing block end (`END_IF`, `END_STEP`...) found missing at
/// token `p` goes: a block is usually written indented, so the first line
/// after its opening line that starts no deeper than the opening line is
/// where its end was left out, when the end fits there; else `p`.
fn where_indented(
    tokens: &[Spanned],
    p: usize,
    end: &Tok,
    parses: &dyn Fn(&Edit) -> bool,
) -> usize {
    let Some(opener) = opening_of(tokens, p, end) else {
        return p;
    };
    let Some(depth) = indent(tokens, opener) else {
        return p;
    };
    let mut q = opener + 1;
    while q < p {
        if tokens[q].1 != Tok::Eol
            && indent(tokens, q).is_some_and(|d| d <= depth)
            && parses(&Edit::Insert(q, end.clone()))
        {
            return q;
        }
        q += 1;
    }
    p
}

/// The unmatched opening keyword before `p` of the block `end` closes.
fn opening_of(tokens: &[Spanned], p: usize, end: &Tok) -> Option<usize> {
    let Tok::Kw(end) = end else {
        return None;
    };
    let opens = |k: Kw| match end {
        Kw::EndIf => k == Kw::If,
        Kw::EndFor => k == Kw::For,
        Kw::EndWhile => k == Kw::While,
        Kw::EndCase => k == Kw::Case,
        Kw::EndRepeat => k == Kw::Repeat,
        Kw::EndTry => k == Kw::Try,
        Kw::EndStep => matches!(k, Kw::Step | Kw::InitialStep),
        Kw::EndTransition => k == Kw::Transition,
        Kw::EndAction => k == Kw::Action,
        _ => false,
    };
    let mut depth = 0usize;
    for i in (0..p.min(tokens.len())).rev() {
        match &tokens[i].1 {
            Tok::Kw(k) if *k == *end => depth += 1,
            Tok::Kw(k) if opens(*k) => {
                if depth == 0 {
                    return Some(i);
                }
                depth -= 1;
            }
            _ => {}
        }
    }
    None
}

/// The indentation (in bytes) of token `i` when it is the first token of
/// its line.
fn indent(tokens: &[Spanned], i: usize) -> Option<usize> {
    let first_on_line = i == 0 || tokens[i - 1].1 == Tok::Eol;
    first_on_line.then(|| {
        let line_start = if i == 0 { 0 } else { tokens[i - 1].2 };
        tokens[i].0.saturating_sub(line_start)
    })
}

/// Where edits are tried: the failing token, then the tokens before it
/// up to [`LOOK_BACK`] of them (line ends are places too, to insert a
/// token at the end of a line, but do not count).
fn places_before(tokens: &[Spanned], k: usize) -> Vec<usize> {
    let mut places = vec![k];
    let mut back = 0;
    let mut i = k;
    while back < LOOK_BACK && i > 0 {
        i -= 1;
        places.push(i);
        if tokens[i].1 != Tok::Eol {
            back += 1;
        }
    }
    places
}

/// `tokens` (which start at index `offset` of the file's tokens) with `edit` made.
fn apply(tokens: &[Spanned], edit: &Edit, offset: usize) -> Vec<Spanned> {
    let mut out = Vec::with_capacity(tokens.len() + 1);
    let at = |p: usize| p.checked_sub(offset);
    for (i, t) in tokens.iter().enumerate() {
        match edit {
            Edit::Delete(p) if at(*p) == Some(i) => {}
            Edit::Replace(p, tok) if at(*p) == Some(i) => out.push((t.0, tok.clone(), t.2)),
            Edit::Insert(p, tok) if at(*p) == Some(i) => {
                out.push((t.0, tok.clone(), t.0));
                out.push(t.clone());
            }
            _ => out.push(t.clone()),
        }
    }
    if let Edit::Insert(p, tok) = edit
        && at(*p) == Some(tokens.len())
    {
        let end = tokens.last().map(|t| t.2).unwrap_or(0);
        out.push((end, tok.clone(), end));
    }
    out
}

/// The tokens to try: those the parser expected (when it said), then the
/// structural ones, each once.
fn candidates(expected: &[String]) -> Vec<Tok> {
    let mut out: Vec<Tok> = Vec::new();
    let names = STRUCTURAL
        .iter()
        .map(|s| s.to_string())
        .filter(|s| expected.is_empty() || expected.contains(&format!("\"{s}\"")));
    let rest = expected.iter().map(|e| e.trim_matches('"').to_string());
    for name in names.chain(rest) {
        if let Some(tok) = terminal(&name)
            && !out.contains(&tok)
        {
            out.push(tok);
        }
    }
    if expected.is_empty() || expected.iter().any(|e| e.trim_matches('"') == "identifier") {
        out.push(Tok::Ident(PLACEHOLDER.to_string()));
    }
    out
}

/// The name put where a name was lost: no source text can spell it, and
/// the checker reports nothing about it beyond the line of the error.
const PLACEHOLDER: &str = crate::syntax::recovery::UNKNOWN_TYPE;

/// The token a grammar terminal stands for, when one can be made up
/// without inventing a name or a value.
fn terminal(name: &str) -> Option<Tok> {
    if NEVER_INSERTED.contains(&name) {
        return None;
    }
    let tok = match name {
        ";" => Tok::Semi,
        ":=" => Tok::Assign,
        ":" => Tok::Colon,
        "," => Tok::Comma,
        "(" => Tok::LParen,
        ")" => Tok::RParen,
        "[" => Tok::LBracket,
        "]" => Tok::RBracket,
        "." => Tok::Dot,
        ".." => Tok::DotDot,
        "=>" => Tok::Arrow,
        "+" => Tok::Plus,
        "-" => Tok::Minus,
        "*" => Tok::Star,
        "/" => Tok::Slash,
        "=" => Tok::Eq,
        "<>" => Tok::Ne,
        "<" => Tok::Lt,
        "<=" => Tok::Le,
        ">" => Tok::Gt,
        ">=" => Tok::Ge,
        "end of line" => Tok::Eol,
        word => Tok::Kw(Kw::lookup(word)?),
    };
    Some(tok)
}

/// Keywords that end a top-level item.
fn ends_item(tok: &Tok) -> bool {
    matches!(
        tok,
        Tok::Kw(
            Kw::EndProgram
                | Kw::EndFunction
                | Kw::EndFunctionBlock
                | Kw::EndType
                | Kw::EndConfiguration
                | Kw::EndInterface
        )
    )
}

/// Keywords that start a top-level item.
fn starts_item(tok: &Tok) -> bool {
    matches!(
        tok,
        Tok::Kw(
            Kw::Program
                | Kw::Function
                | Kw::FunctionBlock
                | Kw::Type
                | Kw::Configuration
                | Kw::Interface
                | Kw::VarGlobal
        )
    )
}

/// True when token `i` starts a top-level item: an item keyword right
/// after the end of the previous item (or first in the file).
fn item_boundary(tokens: &[Spanned], i: usize) -> bool {
    if !starts_item(&tokens[i].1) {
        return false;
    }
    match tokens[..i].iter().rev().find(|t| t.1 != Tok::Eol) {
        None => true,
        Some(prev) => ends_item(&prev.1),
    }
}

/// The start of the item holding token `i`.
fn item_start(tokens: &[Spanned], i: usize) -> usize {
    (0..=i.min(tokens.len().saturating_sub(1)))
        .rev()
        .find(|&j| item_boundary(tokens, j))
        .unwrap_or(0)
}

/// The end (exclusive) of the item holding token `i`: the next item's start.
fn item_end(tokens: &[Spanned], i: usize) -> usize {
    (i + 1..tokens.len())
        .find(|&j| item_boundary(tokens, j))
        .unwrap_or(tokens.len())
}

/// The error reported for a repair: at the failing token, the parser's
/// own message; before it, what the edit says was wrong.
fn report(
    text: &str,
    file: FileId,
    tokens: &[Spanned],
    k: usize,
    edit: &Edit,
    failure: &Failure,
) -> Diagnostic {
    let (Edit::Delete(p) | Edit::Insert(p, _) | Edit::Replace(p, _)) = edit;
    let (l, r) = tokens
        .get(*p)
        .map_or((text.len(), text.len()), |t| (t.0, t.2));
    if *p == k {
        // The parser's message; its place guessed a missing terminator,
        // which the edit confirms or corrects.
        let mut d = failure.diagnostic.clone();
        if !matches!(edit, Edit::Insert(_, t) if is_terminator(t)) && *p < tokens.len() {
            d.span = Span::new(file, l, r);
        }
        return d;
    }
    let written = match tokens.get(*p) {
        Some((_, Tok::Eol, _)) => "the end of the line".to_string(),
        _ => format!("`{}`", text.get(l..r).unwrap_or("?")),
    };
    match edit {
        Edit::Delete(_) => Diagnostic::error(
            "E101",
            Span::new(file, l, r),
            format!("unexpected {written}"),
        ),
        Edit::Replace(_, tok) => Diagnostic::error(
            "E101",
            Span::new(file, l, r),
            format!("expected {}, found {written}", shown(tok)),
        ),
        Edit::Insert(_, tok) => {
            // A missing terminator at a line end belongs to that line.
            let prev = tokens[..*p].iter().rev().find(|t| t.1 != Tok::Eol);
            let at = match prev {
                Some(prev)
                    if is_terminator(tok)
                        && text.get(prev.2..l).is_some_and(|g| g.contains('\n')) =>
                {
                    Span::new(file, prev.2, prev.2)
                }
                _ => Span::new(file, l, r),
            };
            Diagnostic::error(
                "E101",
                at,
                format!("expected {} before {written}", shown(tok)),
            )
        }
    }
}

/// Tokens whose absence is reported after the token they should follow.
fn is_terminator(tok: &Tok) -> bool {
    matches!(
        tok,
        Tok::Semi | Tok::Comma | Tok::RParen | Tok::Kw(Kw::Then | Kw::Do | Kw::Of)
    )
}

/// A token as messages show it.
fn shown(tok: &Tok) -> String {
    match tok {
        Tok::Ident(_) => "a name".to_string(),
        t => t.to_string(),
    }
}
