//! Glue to the lalrpop-generated parser (`grammars/plc.lalrpop`) and the
//! conversion of its errors into `E1xx` diagnostics worded in user terms.

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::Span;
use crate::syntax::ast::CompilationUnit;
use crate::syntax::construct::{Failure, State};
use crate::syntax::lexer::Spanned;
use crate::syntax::token::Tok;
use lalrpop_util::ParseError;

lalrpop_util::lalrpop_mod!(
    #[allow(
        clippy::all,
        clippy::pedantic,
        unused,
        missing_docs,
        unused_qualifications
    )]
    grammar,
    "/plc.rs"
);

/// Words that other dialects use and plcrun does not support; named
/// explicitly in messages (`E110`).
const UNSUPPORTED: [&str; 4] = ["VAR_ACCESS", "NAMESPACE", "USING", "OVERLAP"];

/// Parses a token stream whose line breaks were kept or dropped by
/// [`crate::syntax::il_lines`] (`text` is the source it came from).
pub fn parse_tokens(
    st: State<'_>,
    tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> CompilationUnit {
    parse_tokens_noting(st, tokens, diags).0
}

/// [`parse_tokens`], which also returns where the parser first failed
/// (for [`crate::syntax::repair`]).
pub fn parse_tokens_noting(
    mut st: State<'_>,
    tokens: Vec<Spanned>,
    diags: &mut Diagnostics,
) -> (CompilationUnit, Option<Failure>) {
    // Name unsupported constructs wherever they stand (e.g. `REF_TO INT`,
    // where the grammar would only see an unexpected `INT`).
    for (l, tok, r) in &tokens {
        if let Tok::Ident(word) = tok
            && UNSUPPORTED.contains(&word.to_ascii_uppercase().as_str())
        {
            st.syntax_error(Diagnostic::error(
                "E110",
                Span::new(st.file(), *l, *r),
                format!("`{word}` is not supported by plcrun"),
            ));
        }
    }
    st.set_token_spans(tokens.iter().map(|(l, _, r)| (*l, *r)).collect());
    let parser = grammar::UnitParser::new();
    let result = parser.parse(&st, tokens.into_iter().map(Ok::<Spanned, ()>));
    let mut unit = match result {
        Ok(unit) => unit,
        Err(e) => {
            let d = st.note_failure(e);
            st.syntax_error(d);
            CompilationUnit::default()
        }
    };
    crate::syntax::oop_var_access::attach(&st, &mut unit);
    let failure = st.first_failure();
    for d in st.finish() {
        diags.push(d);
    }
    (unit, failure)
}

/// True when `tokens` parse with no error at all (the parse stops at the
/// first one): a trial of [`crate::syntax::repair`].
pub fn parses_cleanly(st: &State<'_>, tokens: Vec<Spanned>) -> bool {
    let stream = tokens.into_iter().map(|t| {
        if st.failures() > 0 {
            Err(())
        } else {
            Ok::<Spanned, ()>(t)
        }
    });
    grammar::UnitParser::new().parse(st, stream).is_ok() && st.failures() == 0
}

/// How a found token is named in messages.
fn found(st: &State, tok: &Tok, l: usize, r: usize) -> String {
    match tok {
        Tok::Eol => "end of line".to_string(),
        _ => {
            let text: String = st
                .text()
                .get(l..r)
                .unwrap_or("?")
                .chars()
                .take(40)
                .collect();
            format!("`{text}`")
        }
    }
}

/// How an expected terminal is named in messages.
fn expected_name(raw: &str) -> String {
    let name = raw.trim_matches('"').replace("\\\"", "\"");
    match name.as_str() {
        "identifier" => "a name".to_string(),
        "literal" => "a literal".to_string(),
        "direct address" => "a direct address".to_string(),
        "end of line" => "end of line".to_string(),
        "label" => "a label".to_string(),
        "IL operator" => "an IL operator".to_string(),
        "function name" => "a function name".to_string(),
        "FB input operator" => "an FB input operator".to_string(),
        _ => format!("`{name}`"),
    }
}

const OPERATORS: [&str; 20] = [
    "`+`",
    "`-`",
    "`*`",
    "`/`",
    "`**`",
    "`=`",
    "`<>`",
    "`<`",
    "`>`",
    "`<=`",
    "`>=`",
    "`&`",
    "`AND`",
    "`OR`",
    "`XOR`",
    "`MOD`",
    "`.`",
    "`[`",
    "`AND_THEN`",
    "`OR_ELSE`",
];

/// Summarises an expected-token list: operators are folded into "an
/// operator", `END_...` keywords come first, at most six items are shown.
fn expected_text(expected: &[String]) -> String {
    let names: Vec<String> = expected.iter().map(|e| expected_name(e)).collect();
    let mut shown: Vec<String> = names
        .iter()
        .filter(|n| !OPERATORS.contains(&n.as_str()))
        .cloned()
        .collect();
    let had_ops = shown.len() < names.len();
    if shown.is_empty() {
        shown = names;
    } else if had_ops && shown.len() > 1 {
        shown.push("an operator".to_string());
    }
    shown.sort_by_key(|n| {
        if n.starts_with("`END_") {
            0
        } else if n == "`;`" {
            1
        } else if n.starts_with('`') {
            2
        } else {
            3
        }
    });
    shown.dedup();
    let more = shown.len() > 6;
    shown.truncate(6);
    match shown.len() {
        0 => "something else".to_string(),
        1 => shown.remove(0),
        _ => {
            let last = shown.pop().unwrap_or_default();
            let list = format!("{} or {last}", shown.join(", "));
            if more {
                format!("one of {list}, ...")
            } else {
                list
            }
        }
    }
}

/// Converts a parse error into a diagnostic.
pub fn recovery_diagnostic(st: &State, e: ParseError<usize, Tok, ()>) -> Diagnostic {
    let span = |l: usize, r: usize| Span::new(st.file(), l, r.max(l));
    match e {
        ParseError::UnrecognizedToken {
            token: (l, tok, r),
            expected,
        } => {
            if let Tok::Ident(word) = &tok
                && UNSUPPORTED.contains(&word.to_ascii_uppercase().as_str())
            {
                return Diagnostic::error(
                    "E110",
                    span(l, r),
                    format!("`{word}` is not supported by plcrun"),
                );
            }
            let d = Diagnostic::error(
                "E101",
                crate::syntax::recovery::error_span(st, &expected, l, r),
                format!(
                    "expected {}, found {}",
                    expected_text(&expected),
                    found(st, &tok, l, r)
                ),
            );
            if tok == Tok::Eq {
                d.with_note("assignment and parameter passing are written `:=`")
            } else {
                d
            }
        }
        ParseError::UnrecognizedEof { expected, .. } => Diagnostic::error(
            "E102",
            span(st.text().len(), st.text().len()),
            format!(
                "unexpected end of file: expected {}",
                expected_text(&expected)
            ),
        ),
        ParseError::ExtraToken { token: (l, tok, r) } => Diagnostic::error(
            "E101",
            span(l, r),
            format!("unexpected {}", found(st, &tok, l, r)),
        ),
        ParseError::InvalidToken { location } => {
            Diagnostic::error("E101", span(location, location), "invalid token")
        }
        ParseError::User { .. } => Diagnostic::error("E101", span(0, 0), "syntax error"),
    }
}
