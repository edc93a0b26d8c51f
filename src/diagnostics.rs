//! Compile-time diagnostics: a stable code, a severity, a message and the
//! source span it concerns. Every stage reports into a [`Diagnostics`] list
//! and keeps going, so the user sees all errors at once.
//!
//! Codes are stable and documented in `docs/diagnostics.md`:
//! `E0xx` lexical, `E1xx` syntax, `E2xx` names and declarations,
//! `E3xx` types, `E4xx` statements and calls, `E5xx` IL, `E6xx` SFC,
//! `E7xx` configurations, `W...` warnings.

use crate::source::{SourceMap, Span};
use std::fmt::Write;

mod strict;
pub use strict::{STRICT_NOTE, is_compatibility_code};

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// The program is accepted; the user may want to look.
    Warning,
    /// The program cannot run.
    Error,
}

/// One message about the source.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Stable code such as `E201`.
    pub code: &'static str,
    /// Error or warning.
    pub severity: Severity,
    /// One-line description, naming what is wrong.
    pub message: String,
    /// Where it is.
    pub span: Span,
    /// Extra lines of explanation or help.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error with `code` at `span`.
    pub fn error(code: &'static str, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            code,
            severity: Severity::Error,
            message: message.into(),
            span,
            notes: Vec::new(),
        }
    }

    /// A warning with `code` at `span`.
    pub fn warning(code: &'static str, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            code,
            severity: Severity::Warning,
            message: message.into(),
            span,
            notes: Vec::new(),
        }
    }

    /// Adds a note line.
    pub fn with_note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// Renders as
    /// ```text
    /// error[E201]: undeclared variable `x`
    ///   --> prog.st:4:3
    ///    |
    ///  4 |   x := 1;
    ///    |   ^
    /// ```
    pub fn render(&self, sources: &SourceMap) -> String {
        let file = sources.file(self.span.file);
        let (line, col) = file.line_col(self.span.start);
        let (end_line, end_col) = file.line_col(self.span.end.max(self.span.start));
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        // The header gives the column in the line; the caret, the one in
        // the excerpt (a window of a long line).
        let header = format!("{}:{}:{}", file.name, line, col);
        let (text, col, end_col) = excerpt(file.line_text(line), col, end_col);
        let text = text.as_str();
        let width = line.to_string().len();
        let mut out = String::new();
        let _ = writeln!(out, "{kind}[{}]: {}", self.code, short(&self.message));
        let _ = writeln!(out, "{:width$}--> {header}", "");
        let _ = writeln!(out, "{:width$} |", "");
        let _ = writeln!(out, "{line} | {text}");
        let line_chars = text.chars().count();
        let caret_len = if end_line == line && end_col > col {
            end_col - col
        } else {
            1
        }
        .min(line_chars.saturating_sub(col - 1).max(1));
        let _ = writeln!(
            out,
            "{:width$} | {}{}",
            "",
            " ".repeat(col - 1),
            "^".repeat(caret_len)
        );
        for note in &self.notes {
            let _ = writeln!(out, "{:width$} = note: {note}", "");
        }
        out
    }
}

/// Longest source excerpt printed under a diagnostic, in characters: a
/// 10 MB line is shown as a window around the reported column.
pub const MAX_EXCERPT_CHARS: usize = 160;

/// At most this many diagnostics of one code are rendered; the rest are
/// counted in one summary line (one root cause can repeat thousands of times).
pub const MAX_RENDERED_PER_CODE: usize = 100;

/// The part of `text` shown under a diagnostic at columns `col..end_col`
/// (1-based, characters) and those columns within it. Lines of at most
/// [`MAX_EXCERPT_CHARS`] are shown whole; longer ones as a window starting a
/// little before `col`, with `...` marking the cut ends.
fn excerpt(text: &str, col: usize, end_col: usize) -> (String, usize, usize) {
    if text.len() <= MAX_EXCERPT_CHARS || text.chars().nth(MAX_EXCERPT_CHARS).is_none() {
        return (text.to_string(), col, end_col);
    }
    let lead = 40;
    let first = col.saturating_sub(1).saturating_sub(lead);
    let mut window: String = text.chars().skip(first).take(MAX_EXCERPT_CHARS).collect();
    let more_after = text.chars().nth(first + MAX_EXCERPT_CHARS).is_some();
    let (mut col, mut end_col) = (col - first, end_col.saturating_sub(first));
    if first > 0 {
        window.insert_str(0, "...");
        col += 3;
        end_col += 3;
    }
    if more_after {
        window.push_str("...");
    }
    (window, col, end_col.min(col + MAX_EXCERPT_CHARS))
}

/// `message` cut to [`MAX_EXCERPT_CHARS`] characters (a message may quote a
/// 10 000-digit literal).
fn short(message: &str) -> std::borrow::Cow<'_, str> {
    match message.char_indices().nth(MAX_EXCERPT_CHARS) {
        None => message.into(),
        Some((cut, _)) => format!("{}...", &message[..cut]).into(),
    }
}

/// An ordered collection of diagnostics.
#[derive(Debug, Clone, Default)]
pub struct Diagnostics {
    items: Vec<Diagnostic>,
}

impl Diagnostics {
    /// An empty list.
    pub fn new() -> Diagnostics {
        Diagnostics::default()
    }

    /// Adds one diagnostic.
    pub fn push(&mut self, d: Diagnostic) {
        self.items.push(d);
    }

    /// Shorthand for pushing an error.
    pub fn error(&mut self, code: &'static str, span: Span, message: impl Into<String>) {
        self.push(Diagnostic::error(code, span, message));
    }

    /// Shorthand for pushing a warning.
    pub fn warning(&mut self, code: &'static str, span: Span, message: impl Into<String>) {
        self.push(Diagnostic::warning(code, span, message));
    }

    /// Appends all of `other`.
    pub fn extend(&mut self, other: Diagnostics) {
        self.items.extend(other.items);
    }

    /// True if at least one error is present.
    pub fn has_errors(&self) -> bool {
        self.items.iter().any(|d| d.severity == Severity::Error)
    }

    /// Number of errors.
    pub fn error_count(&self) -> usize {
        self.items
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .count()
    }

    /// All diagnostics, sorted by file and position (stable for equal positions).
    pub fn sorted(&self) -> Vec<&Diagnostic> {
        let mut v: Vec<&Diagnostic> = self.items.iter().collect();
        v.sort_by_key(|d| (d.span.file, d.span.start));
        v
    }

    /// The diagnostics in the order they were reported.
    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.items.iter()
    }

    /// Drops the diagnostics reported after the first `n` (used when a
    /// speculative check is abandoned and the real one reports again).
    pub fn truncate(&mut self, n: usize) {
        self.items.truncate(n);
    }

    /// Number of diagnostics.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Renders every diagnostic (sorted), followed by a summary line.
    pub fn render(&self, sources: &SourceMap) -> String {
        let mut out = String::new();
        let mut per_code: std::collections::BTreeMap<&str, usize> = Default::default();
        for d in self.sorted() {
            let seen = per_code.entry(d.code).or_default();
            *seen += 1;
            if *seen <= MAX_RENDERED_PER_CODE {
                out.push_str(&d.render(sources));
                out.push('\n');
            }
        }
        for (code, seen) in per_code {
            if seen > MAX_RENDERED_PER_CODE {
                let _ = writeln!(
                    out,
                    "... and {} more {code} (only the first {MAX_RENDERED_PER_CODE} of each code are shown)",
                    seen - MAX_RENDERED_PER_CODE
                );
            }
        }
        let errors = self.error_count();
        let warnings = self.items.len() - errors;
        if errors > 0 {
            let _ = writeln!(
                out,
                "{errors} error{}, {warnings} warning{}",
                if errors == 1 { "" } else { "s" },
                if warnings == 1 { "" } else { "s" }
            );
        }
        out
    }
}
