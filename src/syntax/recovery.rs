//! Error recovery that keeps one typo to one message: a declaration the
//! parser had to skip is salvaged (its names stay declared, so their uses
//! are not reported as undeclared), and a missing `;` is reported after
//! the token it should follow rather than at the start of the next line.

use crate::diagnostics::{Diagnostic, Diagnostics, Severity};
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::ast::{CompilationUnit, Ident, Item, Step, Stmt, StmtKind, TypeSpec, VarDecl};
use crate::syntax::construct::State;
use crate::syntax::lexer;
use crate::syntax::token::{Kw, Tok};
use lalrpop_util::ErrorRecovery;

/// The name of the placeholder type given to a salvaged declaration whose
/// type could not be read: no source text can spell it, and the checker
/// types it as "error" without a message (the syntax error was reported).
pub const UNKNOWN_TYPE: &str = "";

/// Records the syntax error of a declaration skipped from `l` to `r` and
/// salvages what it declared: the names before the first `:` (or before
/// a type name), with the type written after the `:` when it is a single
/// name, else [`UNKNOWN_TYPE`].
pub fn salvage_decl(
    st: &State,
    e: ErrorRecovery<usize, Tok, ()>,
    l: usize,
    r: usize,
) -> Option<VarDecl> {
    st.recover(e);
    salvage_names(st, l, r)
}

/// The declaration salvaged from the text `l..r` skipped after a syntax
/// error already recorded (see [`salvage_decl`]).
pub fn salvage_names(st: &State, l: usize, r: usize) -> Option<VarDecl> {
    let region = st.text().get(l..r)?;
    let mut scratch = Diagnostics::new();
    let toks: Vec<(usize, Tok, usize)> = lexer::lex(st.file(), region, &mut scratch)
        .into_iter()
        .filter(|(_, t, _)| *t != Tok::Eol)
        .map(|(a, t, b)| (a + l, t, b + l))
        .collect();
    let mut names = Vec::new();
    let mut i = 0;
    while let Some((a, Tok::Ident(name), b)) = toks.get(i) {
        if crate::elementary::ElemType::from_name(name).is_some() {
            // `BOOL;` left over from a broken declaration declares nothing.
            return None;
        }
        names.push(Ident {
            name: name.clone(),
            span: st.span(*a, *b),
        });
        i += 1;
        if matches!(toks.get(i), Some((_, Tok::Comma, _))) {
            i += 1;
        } else {
            break;
        }
    }
    if names.is_empty() {
        return None;
    }
    if matches!(toks.get(i), Some((_, Tok::Kw(Kw::At), _))) {
        i += 2;
    }
    let ty = match (toks.get(i), toks.get(i + 1), toks.get(i + 2)) {
        (
            Some((_, Tok::Colon, _)),
            Some((a, Tok::Ident(ty), b)),
            Some((_, Tok::Semi | Tok::Assign, _)),
        ) => TypeSpec::Named(Ident {
            name: ty.clone(),
            span: st.span(*a, *b),
        }),
        _ => TypeSpec::Named(Ident {
            name: UNKNOWN_TYPE.to_string(),
            span: st.span(l, l),
        }),
    };
    Some(VarDecl {
        names,
        location: None,
        ty,
        init: None,
        span: st.span(l, r),
        edge: None,
        init_args: None,
    })
}

/// A compound statement (IF, CASE, FOR, WHILE) whose header had a syntax
/// error (recorded by the grammar's `Recovered`): the statement, body included, is
/// skipped (its body is checked once the header is fixed).
pub fn skipped_stmt(st: &State, l: usize, r: usize) -> Stmt {
    Stmt {
        kind: StmtKind::Empty,
        span: st.span(l, r),
    }
}

/// A step with a syntax error (recorded by the grammar's `Recovered`): kept
/// under its name (the first name after `STEP`), without actions, so
/// that transitions naming it are not reported too.
pub fn broken_step(st: &State, initial: bool, l: usize, r: usize) -> Step {
    let region = st.text().get(l..r).unwrap_or("");
    let mut scratch = Diagnostics::new();
    let name = lexer::lex(st.file(), region, &mut scratch)
        .into_iter()
        .find_map(|(a, t, b)| match t {
            Tok::Ident(name) => Some(Ident {
                name,
                span: st.span(a + l, b + l),
            }),
            _ => None,
        })
        .unwrap_or(Ident {
            name: String::new(),
            span: st.span(l, l),
        });
    Step {
        name,
        initial,
        actions: Vec::new(),
        span: st.span(l, r),
    }
}

/// Terminators whose absence is reported after the token they should
/// follow.
const TERMINATORS: [&str; 6] = ["\";\"", "\",\"", "\")\"", "\"THEN\"", "\"DO\"", "\"OF\""];

/// Tokens after which nothing is missing at the end of a line.
const OPENERS: [&str; 4] = [";", ",", "(", ":="];

/// Where a syntax error found at token `l..r` is reported: when `;`, `,`,
/// `)`, `THEN`, `DO` or `OF` could have come next and the token stands on a later line than
/// the token before it (which does not itself leave the line open), the
/// terminator is what is missing, and the message goes right after that
/// previous token, on its line.
pub fn error_span(st: &State, expected: &[String], l: usize, r: usize) -> Span {
    let fallback = Span::new(st.file(), l, r.max(l));
    if !expected.iter().any(|e| TERMINATORS.contains(&e.as_str())) {
        return fallback;
    }
    // Before `END_...` or at an IL line end, the place is already right.
    let found = st.text().get(l..r).unwrap_or("");
    if found.is_empty() || found.contains('\n') || found.to_ascii_uppercase().starts_with("END_") {
        return fallback;
    }
    let Some((pl, pr)) = st.token_before(l) else {
        return fallback;
    };
    let text = st.text();
    let between = text.get(pr..l).unwrap_or("");
    if text.get(pl..pr).is_none_or(|t| OPENERS.contains(&t)) || !between.contains('\n') {
        return fallback;
    }
    Span::new(st.file(), pr, pr)
}

/// Errors about names (undeclared, unknown type, unknown action...) and
/// about the IL current result and parentheses, which
/// a syntax error earlier in the same POU explains: the text the parser
/// skipped may have declared the name.
const NAME_CODES: [&str; 10] = [
    "E201", "E203", "E403", "E501", "E505", "E506", "E602", "E610", "E613", "E615",
];

/// Of [`NAME_CODES`], the names an SFC chart declares (steps, actions).
const CHART_NAME_CODES: [&str; 4] = ["E602", "E610", "E613", "E615"];

/// Drops the semantic errors that a syntax error explains: those on the
/// same line, and errors about names later in the same POU. The syntax
/// error is the cause, the rest its consequence; once it is fixed, a
/// remaining error is reported by the next check.
pub fn drop_cascades(sources: &SourceMap, units: &[CompilationUnit], diags: &mut Diagnostics) {
    let line = |d: &Diagnostic| {
        let file = sources.files().get(d.span.file.0 as usize)?;
        Some((d.span.file, file.line_col(d.span.start).0))
    };
    let is_syntax = |d: &Diagnostic| parse_error_code(d.code);
    let broken: Vec<_> = diags
        .iter()
        .filter(|d| is_syntax(d))
        .filter_map(line)
        .collect();
    if broken.is_empty() {
        return;
    }
    let syntax: Vec<Span> = diags
        .iter()
        .filter(|d| is_syntax(d))
        .map(|d| d.span)
        .collect();
    // The POUs with a syntax error, as (file, start, end).
    let broken_pous: Vec<(FileId, u32, u32)> = units
        .iter()
        .enumerate()
        .flat_map(|(i, u)| u.items.iter().map(move |it| (FileId(i as u32), it)))
        .filter_map(|(f, it)| match it {
            Item::Pou(p) => Some((f, p.span.start, p.span.end)),
            _ => None,
        })
        .filter(|&(f, a, b)| {
            syntax
                .iter()
                .any(|s| s.file == f && s.start >= a && s.start < b)
        })
        .collect();
    // A chart names its steps and actions anywhere in its body: a step
    // lost to a syntax error explains a transition before it as well.
    let anywhere = |d: &Diagnostic| CHART_NAME_CODES.contains(&d.code);
    let explained = |d: &Diagnostic| {
        NAME_CODES.contains(&d.code)
            && broken_pous.iter().any(|&(f, a, b)| {
                d.span.file == f
                    && d.span.start >= a
                    && d.span.start < b
                    && syntax.iter().any(|s| {
                        s.file == f && s.start >= a && (s.start <= d.span.start || anywhere(d))
                    })
            })
    };
    let all: Vec<Diagnostic> = diags.iter().cloned().collect();
    diags.truncate(0);
    for d in all {
        // Lexical (E0xx) and syntax (E1xx) errors are causes, never dropped.
        let semantic = d.code.as_bytes().get(1).is_some_and(|&b| b >= b'2');
        let cascade = d.severity == Severity::Error
            && semantic
            && (line(&d).is_some_and(|at| broken.contains(&at)) || explained(&d));
        if !cascade {
            diags.push(d);
        }
    }
}

/// Codes of syntax errors.
pub const SYNTAX_CODES: [&str; 3] = ["E101", "E102", "E110"];

/// True for the codes the parser reports (E100–E149): the syntax errors
/// above, and the forms it reads but refuses (`x;` alone, E103, ...).
fn parse_error_code(code: &str) -> bool {
    code.strip_prefix("E1")
        .and_then(|n| n.parse::<u32>().ok())
        .is_some_and(|n| n < 50)
}
