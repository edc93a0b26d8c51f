//! `plcrun check`, `test` and `compare` given no source: the project
//! file's sources (`--project FILE`, else `./plcrun.toml`), read with the
//! file's `encoding`, `addressing` and `strict` unless the command line
//! gives them.

use super::super::args::ReadingArgs;
use super::super::given::Given;
use std::path::{Path, PathBuf};

/// The sources to read and how: `files` when there are some, else the
/// project's; the rendered errors of a project file that cannot be used.
pub fn sources_or_project(
    files: &[PathBuf],
    project: Option<&Path>,
    reading: &ReadingArgs,
    given: &Given,
) -> Result<(Vec<PathBuf>, ReadingArgs), String> {
    let copy = |r: &ReadingArgs| ReadingArgs {
        strict: r.strict,
        encoding: r.encoding,
        addressing: r.addressing,
        library_path: reading.library_path.clone(),
    };
    if !files.is_empty() {
        return Ok((reading.with_libraries(files)?, copy(reading)));
    }
    let found = super::find(project)?;
    let mut merged = copy(&found.run.reading);
    if given.has("strict") {
        merged.strict = reading.strict;
    }
    if given.has("encoding") {
        merged.encoding = reading.encoding;
    }
    if given.has("addressing") {
        merged.addressing = reading.addressing;
    }
    Ok((reading.with_libraries(&found.sources)?, merged))
}
