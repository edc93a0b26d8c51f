//! Retained data: the values of RETAIN and PERSISTENT variables, kept over
//! a restart in a file.
//!
//! - [`layout`]: what is retained, and the snapshot taken between cycles;
//! - [`fingerprint`]: the hash of the retained names and types, and what
//!   differs between a file and a program;
//! - [`format`]: the file's JSON text;
//! - [`file`]: replacing the file atomically;
//! - [`restore`]: saving and restoring from the [`crate::Plc`];
//! - [`saver`]: saving in the background, off the cycle's path;
//! - [`reset`]: the warm reset.
//!
//! The format and the rules are documented in docs/runtime.md.

pub mod file;
pub mod fingerprint;
pub mod format;
pub mod layout;
pub mod reset;
pub mod restore;
pub mod saver;

pub use fingerprint::{RetainDiff, TypeChange};

use super::var_error::VarError;
use std::fmt;
use std::io;
use std::path::PathBuf;

/// What [`crate::Plc::restore_retain`] does with a file that does not fit
/// the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RestoreMode {
    /// Refuse it: nothing is restored ([`RetainError::Mismatch`]).
    #[default]
    Exact,
    /// Restore the variables whose name and type still fit, and name the
    /// others in the [`RestoreReport`].
    Partial,
}

/// What a restore did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RestoreReport {
    /// How many values were restored.
    pub restored: usize,
    /// The cycle number at which the file's snapshot was taken.
    pub cycle: u64,
    /// What differs between the file and the program (empty for an exact
    /// fit; with [`RestoreMode::Partial`] these were not restored).
    pub differences: RetainDiff,
}

/// One retained value, as [`crate::Plc::retained`] lists it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RetainedVariable {
    /// Its path from outside (`P.counter`, `P.fb.t.ET`, `g_total`, `P.arr[3]`).
    pub name: String,
    /// Its type as the retain file spells it (`DINT`, `STRING[80]`).
    pub type_name: String,
    /// Declared PERSISTENT.
    pub persistent: bool,
}

/// What is wrong with a retain file's contents.
#[derive(Debug, Clone, PartialEq)]
pub enum Damage {
    /// Not JSON, or not the expected fields.
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// Its `format` field is not `plcrun-retain`.
    NotRetainData {
        /// What it says instead.
        format: String,
    },
    /// A version of the format this build does not read.
    Version {
        /// The file's version.
        version: u32,
    },
    /// Its fingerprint is not that of the variables it lists (edited or
    /// damaged).
    Fingerprint,
    /// A variable listed twice.
    Duplicate {
        /// The variable.
        name: String,
    },
    /// A value that is not a literal of the variable's type.
    BadValue {
        /// The variable.
        name: String,
        /// Why.
        error: Box<VarError>,
    },
}

impl fmt::Display for Damage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Damage::Json { message, .. } => write!(f, "not a valid retain file: {message}"),
            Damage::NotRetainData { format } => {
                write!(f, "not a plcrun retain file (its format is `{format}`)")
            }
            Damage::Version { version } => write!(
                f,
                "format version {version} is not supported (this plcrun reads version {})",
                format::VERSION
            ),
            Damage::Fingerprint => f.write_str(
                "its fingerprint does not match the variables it lists (the file was edited or damaged)",
            ),
            Damage::Duplicate { name } => write!(f, "`{name}` is listed twice"),
            Damage::BadValue { name, error } => write!(f, "the value of `{name}`: {error}"),
        }
    }
}

/// Why retained data could not be saved or restored.
#[derive(Debug)]
pub enum RetainError {
    /// The file could not be read (see [`Self::is_missing_file`]).
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        error: io::Error,
    },
    /// The file could not be written.
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        error: io::Error,
    },
    /// The file is not a valid retain file.
    Damaged {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        damage: Damage,
    },
    /// The file was saved by a program whose retained variables differ
    /// ([`RestoreMode::Exact`]); nothing was restored.
    Mismatch {
        /// The file.
        path: PathBuf,
        /// What differs.
        differences: RetainDiff,
        /// How many variables would fit (a partial restore restores them).
        fitting: usize,
    },
    /// A [`saver::RetainSaver`] was handed another PLC than its own.
    ForeignPlc,
}

impl RetainError {
    /// True when the file does not exist (a first start: the command line
    /// starts cold).
    pub fn is_missing_file(&self) -> bool {
        matches!(self, RetainError::Read { error, .. } if error.kind() == io::ErrorKind::NotFound)
    }
}

impl fmt::Display for RetainError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RetainError::Read { path, error } => {
                write!(f, "cannot read retain file `{}`: {error}", path.display())
            }
            RetainError::Write { path, error } => {
                write!(f, "cannot write retain file `{}`: {error}", path.display())
            }
            RetainError::Damaged { path, damage } => match damage {
                Damage::Json { line, column, .. } => write!(
                    f,
                    "retain file `{}` line {line} column {column}: {damage}",
                    path.display()
                ),
                _ => write!(f, "retain file `{}`: {damage}", path.display()),
            },
            RetainError::Mismatch {
                path,
                differences,
                fitting,
            } => write!(
                f,
                "retain file `{}` does not fit this program: {differences} \
                 (nothing restored; a partial restore would restore the {fitting} that fit)",
                path.display()
            ),
            RetainError::ForeignPlc => f.write_str("this retain saver belongs to another PLC"),
        }
    }
}

impl std::error::Error for RetainError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            RetainError::Read { error, .. } | RetainError::Write { error, .. } => Some(error),
            _ => None,
        }
    }
}
