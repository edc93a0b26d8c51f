//! Paths in a project file: relative to the file's folder, and the
//! `sources` entries, which may be globs (`src/**/*.st`).

use super::errors::{NO_SOURCE, ProjectError};
use std::path::{Component, Path, PathBuf};
use toml::Spanned;

/// `path` taken relative to `folder` unless absolute, with `.` and
/// `inner/..` removed from the text (so messages show
/// `programs/chariot.sfc`, not `examples/chariot/../../programs/chariot.sfc`).
pub fn resolve(folder: &Path, path: &str) -> PathBuf {
    let joined = folder.join(path);
    let mut out = PathBuf::new();
    for part in joined.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => {
                let last_is_name =
                    matches!(out.components().next_back(), Some(Component::Normal(_)));
                if last_is_name {
                    out.pop();
                } else {
                    out.push("..");
                }
            }
            other => out.push(other.as_os_str()),
        }
    }
    if out.as_os_str().is_empty() {
        out.push(".");
    }
    out
}

/// True when `entry` is a glob pattern rather than a plain path.
fn is_glob(entry: &str) -> bool {
    entry.contains(['*', '?', '['])
}

/// The files the `sources` entries stand for, in the order written (the
/// matches of one glob sorted by path). A plain path must exist (a file,
/// a folder or a `.plcproj`, which the loader expands); a glob may match
/// nothing. Errors are pushed, one per bad entry.
pub fn sources(
    folder: &Path,
    entries: &[Spanned<String>],
    errors: &mut Vec<ProjectError>,
) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in entries {
        let text = entry.get_ref().as_str();
        let span = entry.span();
        if text.trim().is_empty() {
            errors.push(ProjectError::at(
                NO_SOURCE,
                span,
                "`sources`: an empty entry",
            ));
            continue;
        }
        if !is_glob(text) {
            let path = resolve(folder, text);
            if path.exists() {
                files.push(path);
            } else {
                errors.push(ProjectError::at(
                    NO_SOURCE,
                    span,
                    format!("`sources`: `{}` does not exist", path.display()),
                ));
            }
            continue;
        }
        match expand(folder, text) {
            // A glob may match nothing (`*.il` in an all-ST project); the
            // list as a whole must name a file (checked by the caller).
            Ok(found) => files.extend(found),
            Err(why) => errors.push(ProjectError::at(
                NO_SOURCE,
                span,
                format!("`sources`: `{text}` is not a valid pattern: {why}"),
            )),
        }
    }
    // Named twice (`main.st` and `*.st`): read once, where first named.
    let mut seen = std::collections::BTreeSet::new();
    files.retain(|f| seen.insert(f.clone()));
    files
}

/// The files matching `pattern` under `folder`, sorted; folders the
/// pattern matches are left out (a folder source is named plainly).
fn expand(folder: &Path, pattern: &str) -> Result<Vec<PathBuf>, String> {
    let absolute = Path::new(pattern).is_absolute();
    let full = if absolute {
        pattern.to_string()
    } else {
        // The folder's own name may hold `[` or `*`: only the pattern's
        // part is a pattern.
        let base = glob::Pattern::escape(&folder.to_string_lossy());
        if base.is_empty() {
            pattern.to_string()
        } else {
            format!("{base}/{pattern}")
        }
    };
    let options = glob::MatchOptions {
        case_sensitive: true,
        require_literal_separator: true,
        require_literal_leading_dot: true,
    };
    let walk = glob::glob_with(&full, options).map_err(|e| e.msg.to_string())?;
    let mut found = Vec::new();
    for item in walk {
        let path = item.map_err(|e| e.to_string())?;
        if path.is_file() {
            found.push(resolve(Path::new(""), &path.to_string_lossy()));
        }
    }
    found.sort();
    Ok(found)
}
