//! `plcrun.toml`, the project file (docs/project-file.md): read with serde
//! and the `toml` crate, checked key by key, and mapped onto the options
//! the command line fills ([`RunArgs`]), so that `plcrun serve` runs a
//! project through the same path as `plcrun run`.

mod errors;
mod fallback;
mod paths;
mod schema;
mod settings;

pub use fallback::sources_or_project;
pub use settings::{Assignment, default_run_args};

use super::args::RunArgs;
use errors::{ProjectError, SYNTAX, UNKNOWN_KEY, UNREADABLE, WRONG_TYPE};
use std::path::{Path, PathBuf};

/// The name `serve`, `check`, `test` and `compare` look for in the
/// current folder.
pub const DEFAULT_NAME: &str = "plcrun.toml";

/// A project file read and checked.
#[derive(Debug)]
pub struct Project {
    /// The file, as it was named.
    pub path: PathBuf,
    /// The source files (globs expanded, relative to the file's folder).
    pub sources: Vec<PathBuf>,
    /// Everything the file says, as the options of `plcrun run` (its
    /// `files` are [`Self::sources`]).
    pub run: RunArgs,
    /// Whether the file has a `[trace]` table (without one, `serve`
    /// writes no trace).
    pub traced: bool,
    /// The `[set]` and `[force]` lines, with their places.
    pub assignments: Vec<settings::Assignment>,
}

/// Checks the `[set]` and `[force]` lines of the project file at `path`
/// against `plc` (compiled from the project) as the run will apply them: a
/// name the program does not have, or a value that does not fit, is
/// reported at its place in the file (E974). `Err` holds the rendered
/// errors.
pub fn check_assignments(
    path: &Path,
    assignments: &[settings::Assignment],
    plc: &mut plcrun::Plc,
) -> Result<(), String> {
    let mut found = Vec::new();
    for a in assignments {
        let result = match a.table {
            "force" => plc.force(&a.name, &a.literal),
            _ => plc.write(&a.name, &a.literal),
        };
        if let Err(e) = result {
            found.push(ProjectError::at(
                errors::BAD_VALUE,
                a.span.clone(),
                format!("`{}.{}`: {e}", a.table, a.name),
            ));
        }
    }
    if found.is_empty() {
        return Ok(());
    }
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).unwrap_or_default();
    Err(errors::render(&name, &text, &found))
}

/// Reads and checks the project file at `path`. On error, every problem
/// found, rendered as diagnostics.
pub fn load(path: &Path) -> Result<Project, String> {
    let name = path.display().to_string();
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) => {
            let error =
                ProjectError::whole(UNREADABLE, format!("cannot read the project file: {e}"));
            let error = if e.kind() == std::io::ErrorKind::NotFound {
                error.note("`plcrun init` writes one; `check`, `test` and `compare` also take source files instead")
            } else {
                error
            };
            return Err(errors::render(&name, "", &[error]));
        }
    };
    parse(path, &text).map_err(|found| errors::render(&name, &text, &found))
}

/// The project file for a command given no source: `explicit` (from
/// `--project`) or `./plcrun.toml`.
pub fn find(explicit: Option<&Path>) -> Result<Project, String> {
    load(explicit.unwrap_or(Path::new(DEFAULT_NAME)))
}

/// Parses `text`, the contents of the project file at `path`.
fn parse(path: &Path, text: &str) -> Result<Project, Vec<ProjectError>> {
    // Syntax first: a TOML error is reported as such, not as a missing key.
    if let Err(e) = text.parse::<toml::Table>() {
        return Err(vec![from_toml(SYNTAX, &e, text)]);
    }
    let file: schema::ProjectFile = toml::from_str(text).map_err(|e| {
        let code = if e.message().starts_with("unknown field") {
            UNKNOWN_KEY
        } else {
            WRONG_TYPE
        };
        vec![from_toml(code, &e, text)]
    })?;
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    settings::resolve(path, &folder, file)
}

/// A serde or syntax error of the `toml` crate as one of ours: its
/// message in the file's words (keys, not fields; the table named) at its
/// place.
fn from_toml(code: &'static str, e: &toml::de::Error, text: &str) -> ProjectError {
    let message = e
        .message()
        .trim()
        .replace("expected i64", "expected an integer");
    let Some(span) = e.span() else {
        return ProjectError::whole(code, message);
    };
    let in_table = |at: usize| match errors::table_at(text, at) {
        Some(table) => format!(" in `[{table}]`"),
        None => String::new(),
    };
    if let Some(rest) = message.strip_prefix("unknown field ") {
        // "unknown field `x`, expected one of `a`, `b`": the list, which
        // can be long, goes to a note.
        let (name, expected) = rest.split_once(", expected ").unwrap_or((rest, ""));
        let error = ProjectError::at(
            UNKNOWN_KEY,
            span.clone(),
            format!("unknown key {name}{}", in_table(span.start)),
        );
        let error = match expected.strip_prefix("one of ") {
            Some(list) => error.note(format!("the keys here: {}", list.replace('`', ""))),
            None if !expected.is_empty() => error.note(format!("expected {expected}")),
            None => error,
        };
        return error.note("docs/project-file.md lists every key");
    }
    if let Some(name) = message.strip_prefix("missing field ") {
        // The span is the table's header (or the file's start).
        let table = if text[span.start.min(text.len())..].starts_with('[') {
            in_table(span.end)
        } else {
            String::new()
        };
        return ProjectError::at(code, span, format!("missing key {name}{table}"));
    }
    let message = match errors::key_at(text, span.start) {
        Some(key) if !message.contains(&format!("`{key}`")) => format!("`{key}`: {message}"),
        _ => message,
    };
    ProjectError::at(code, span, message)
}
