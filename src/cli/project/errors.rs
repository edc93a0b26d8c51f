//! Errors in a project file, printed as plcrun prints diagnostics: a
//! stable code (E970-E979, docs/diagnostics.md), the message naming the
//! key, `file:line:column` and the line of the file under it.

use plcrun::{Diagnostic, SourceMap, Span};
use std::ops::Range;

/// The file cannot be read, or there is none where one was expected.
pub const UNREADABLE: &str = "E970";
/// The text is not TOML.
pub const SYNTAX: &str = "E971";
/// A key the table does not have.
pub const UNKNOWN_KEY: &str = "E972";
/// A value of the wrong type, or a required key missing.
pub const WRONG_TYPE: &str = "E973";
/// A value of the right type that is not a valid setting.
pub const BAD_VALUE: &str = "E974";
/// A source entry that names no file: missing, or a glob matching nothing.
pub const NO_SOURCE: &str = "E975";
/// A table this build cannot serve (OPC UA without the `opcua` feature).
#[cfg_attr(feature = "opcua", allow(dead_code))]
pub const NOT_BUILT: &str = "E976";

/// One error found in the file.
#[derive(Debug)]
pub struct ProjectError {
    /// Its stable code.
    pub code: &'static str,
    /// What is wrong, naming the key.
    pub message: String,
    /// The bytes of the file it is about, when known.
    pub span: Option<Range<usize>>,
    /// Help lines.
    pub notes: Vec<String>,
}

impl ProjectError {
    /// An error at `span` of the file.
    pub fn at(code: &'static str, span: Range<usize>, message: impl Into<String>) -> Self {
        ProjectError {
            code,
            message: message.into(),
            span: Some(span),
            notes: Vec::new(),
        }
    }

    /// An error about the file as a whole.
    pub fn whole(code: &'static str, message: impl Into<String>) -> Self {
        ProjectError {
            code,
            message: message.into(),
            span: None,
            notes: Vec::new(),
        }
    }

    /// Adds a help line.
    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
}

/// Renders `errors` found in the file `name` whose text is `text`, one
/// diagnostic after the other, with a closing count.
pub fn render(name: &str, text: &str, errors: &[ProjectError]) -> String {
    let mut sources = SourceMap::new();
    let file = sources.add(name, text);
    let mut out = String::new();
    for error in errors {
        match &error.span {
            Some(span) => {
                let start = span.start.min(text.len());
                let end = span.end.clamp(start, text.len());
                let mut diagnostic =
                    Diagnostic::error(error.code, Span::new(file, start, end), &error.message);
                for note in &error.notes {
                    diagnostic = diagnostic.with_note(note);
                }
                out.push_str(&diagnostic.render(&sources));
            }
            None => {
                out.push_str(&format!(
                    "error[{}]: {}\n --> {name}\n",
                    error.code, error.message
                ));
                for note in &error.notes {
                    out.push_str(&format!("  = note: {note}\n"));
                }
            }
        }
    }
    let n = errors.len();
    out.push_str(&format!(
        "error: {name}: {n} error{} in the project file\n",
        if n == 1 { "" } else { "s" }
    ));
    out
}

/// The dotted name of the key whose value starts at byte `offset` of
/// `text` (`modbus.max_clients`), found from the text: the `key =` of the
/// value's line (or of the line that opened a value spread over several
/// lines), under the last `[table]` header before it.
pub fn key_at(text: &str, offset: usize) -> Option<String> {
    let before = &text[..floor_char_boundary(text, offset)];
    let mut key = None;
    for line in before.lines().rev() {
        let line = line.trim_start();
        if line.starts_with('[') && !line.contains('=') {
            break; // a header: the value is not under a key of this table
        }
        if let Some((name, _)) = line.split_once('=')
            && is_key(name.trim())
        {
            key = Some(name.trim().trim_matches('"').to_string());
            break;
        }
    }
    let key = key?;
    Some(match table_at(text, offset) {
        Some(table) => format!("{table}.{key}"),
        None => key,
    })
}

/// The name of the `[table]` whose header is the last before byte
/// `offset` of `text` (`None` at the top level).
pub fn table_at(text: &str, offset: usize) -> Option<String> {
    let before = &text[..floor_char_boundary(text, offset)];
    before.lines().rev().find_map(|line| {
        let header = line.trim_start().strip_prefix('[')?;
        let header = header.trim_start_matches('[');
        let end = header.find(']')?;
        let name = header[..end].trim();
        (!name.is_empty() && is_key(name)).then(|| name.to_string())
    })
}

/// A bare or quoted TOML key (possibly dotted).
fn is_key(text: &str) -> bool {
    !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '"' | '\'' | ' '))
}

fn floor_char_boundary(text: &str, mut at: usize) -> usize {
    at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}
