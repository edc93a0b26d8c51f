//! The compile pipeline: source files → parse → check and lower → link and
//! verify. Everything that turns text into a runnable program goes through
//! here; the runtime, the command line and embedders call these functions
//! instead of assembling the stages themselves.

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::ir::image::Image;
use crate::sema::{self, CompileOptions};
use crate::source::{FileId, SourceMap, Span};
use std::fmt;
use std::path::{Path, PathBuf};

/// Diagnostic code of a file that is not valid UTF-8.
const INVALID_UTF8: &str = "E011";

/// Diagnostic code of "several PROGRAMs and none chosen".
pub(crate) const AMBIGUOUS_PROGRAM: &str = "E208";

/// A source file could not be read.
#[derive(Debug)]
pub struct LoadError {
    /// The path as given.
    pub path: PathBuf,
    /// What the operating system said.
    pub error: std::io::Error,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot read `{}`: {}", self.path.display(), self.error)
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// Reads every file into a source map, named by its path as given. A file
/// that is not valid UTF-8 is kept (invalid bytes replaced by U+FFFD) and
/// reported as an `E011` diagnostic in `diags`, so that its other errors are
/// still found; a file that cannot be read at all is a [`LoadError`].
pub fn load_files<P: AsRef<Path>>(
    paths: &[P],
    diags: &mut Diagnostics,
) -> Result<SourceMap, LoadError> {
    let mut sources = SourceMap::new();
    for path in paths {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|error| LoadError {
            path: path.to_path_buf(),
            error,
        })?;
        let name = path.display().to_string();
        match String::from_utf8(bytes) {
            Ok(text) => {
                sources.add(name, text);
            }
            Err(e) => {
                let offset = e.utf8_error().valid_up_to();
                let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
                let id = sources.add(name, text);
                diags.push(invalid_utf8(id, offset));
            }
        }
    }
    Ok(sources)
}

/// The diagnostic for a file that is not valid UTF-8 at byte `offset`.
fn invalid_utf8(file: FileId, offset: usize) -> Diagnostic {
    Diagnostic::error(
        INVALID_UTF8,
        Span::new(file, offset, offset + 1),
        "the file is not valid UTF-8 (invalid bytes replaced by U+FFFD)",
    )
}

/// What to build from the sources.
#[derive(Debug, Clone, Default)]
pub(crate) struct Build {
    /// The PROGRAM to run when there is no configuration.
    pub program: Option<String>,
    /// Cycle time of the implicit task, in nanoseconds.
    pub cycle_time: i64,
    /// Only check the sources: no runnable program is required.
    pub check_only: bool,
}

/// Parses and checks every file of `sources`, reporting into `diags`;
/// returns the linked image when there is no error.
pub(crate) fn compile(
    sources: &SourceMap,
    build: &Build,
    diags: &mut Diagnostics,
) -> Option<Image> {
    let mut units = Vec::with_capacity(sources.files().len());
    for (i, file) in sources.files().iter().enumerate() {
        units.push(crate::syntax::parse(FileId(i as u32), &file.text, diags));
    }
    let options = CompileOptions {
        program: build.program.clone(),
        cycle_time: build.cycle_time,
        check_only: build.check_only,
    };
    let image = sema::compile(&units, &options, diags);
    if diags.has_errors() { None } else { image }
}

/// What `plcrun check` does.
#[derive(Debug, Clone, Default)]
pub struct CheckOptions {
    /// The PROGRAM to build when the sources hold several (matters only
    /// with `ir_listing`).
    pub program: Option<String>,
    /// Also build the runnable program and list its IR (a debugging aid;
    /// the sources must then hold one runnable program).
    pub ir_listing: bool,
}

/// The outcome of [`check`].
#[derive(Debug, Clone)]
pub struct CheckReport {
    /// Every error and warning, in the order found.
    pub diagnostics: Diagnostics,
    /// The IR listing of every code block, when asked for and the sources
    /// have no error.
    pub ir_listing: Option<String>,
}

impl CheckReport {
    /// True when there is no error (warnings allowed).
    pub fn is_ok(&self) -> bool {
        !self.diagnostics.has_errors()
    }
}

/// Parses and checks sources without running them. Without
/// `ir_listing`, a set of declarations with no PROGRAM is fine.
pub fn check(sources: &SourceMap, options: &CheckOptions) -> CheckReport {
    let mut diagnostics = Diagnostics::new();
    let build = Build {
        program: options.program.clone(),
        cycle_time: 10_000_000,
        check_only: !options.ir_listing,
    };
    let image = compile(sources, &build, &mut diagnostics);
    let ir_listing = match (options.ir_listing, image) {
        (true, Some(image)) => Some(image.dump()),
        _ => None,
    };
    CheckReport {
        diagnostics,
        ir_listing,
    }
}
