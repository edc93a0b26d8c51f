//! What can go wrong when setting up or running a comparison.

use crate::runtime::var_error::VarError;
use std::fmt;

/// Program A or program B.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The first program (before `--`).
    A,
    /// The second program (after `--`).
    B,
}

impl fmt::Display for Side {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Side::A => "A",
            Side::B => "B",
        })
    }
}

/// Why two programs cannot be compared as asked.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum CompareError {
    /// A `--map` item is not `X=Y`.
    BadMap {
        /// The item as written.
        item: String,
    },
    /// A name (of `--map`, `--ignore` or a stimulus column) does not name a
    /// value of the program.
    UnknownName {
        /// Which program.
        side: Side,
        /// The name as written.
        name: String,
        /// Why it does not resolve.
        error: VarError,
    },
    /// A `--map` pairs an input of one program with a variable that is not
    /// an input of the other.
    InputMappedToNonInput {
        /// A's name.
        a: String,
        /// B's name.
        b: String,
    },
    /// Two paired inputs have different types.
    InputTypesDiffer {
        /// A's name and type.
        a: (String, String),
        /// B's name and type.
        b: (String, String),
    },
    /// A name was mapped twice.
    MappedTwice {
        /// The name.
        name: String,
    },
    /// `--ignore NAME` names no input and no compared output.
    UnknownIgnore {
        /// The name.
        name: String,
    },
    /// The programs read inputs, but none of them is common (after mapping).
    NoCommonInputs {
        /// A's inputs.
        a: Vec<String>,
        /// B's inputs.
        b: Vec<String>,
    },
    /// No output is left to compare.
    NoComparedOutputs {
        /// A's outputs.
        a: Vec<String>,
        /// B's outputs.
        b: Vec<String>,
    },
    /// The programs' base ticks differ, so cycles do not line up.
    TicksDiffer {
        /// A's base tick in nanoseconds.
        a: i64,
        /// B's base tick in nanoseconds.
        b: i64,
    },
    /// A stimulus column names no input both programs read.
    NotAnInput {
        /// The column.
        column: String,
    },
    /// A stimulus value does not fit an input.
    BadValue {
        /// Which program refused it.
        side: Side,
        /// The input.
        input: String,
        /// The refusal.
        error: VarError,
    },
    /// The stimulus CSV itself is malformed.
    Stimulus(crate::runtime::stimulus::StimulusError),
    /// The random generator's settings are out of range.
    BadRandomSettings {
        /// What is wrong.
        problem: String,
    },
    /// A pair could not be made for a worker thread.
    Worker {
        /// The pair builder's error, as text.
        message: String,
    },
}

impl fmt::Display for CompareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompareError::BadMap { item } => write!(
                f,
                "--map `{item}`: expected A_NAME=B_NAME (e.g. `A.x=B.y` or `x=y`)"
            ),
            CompareError::UnknownName { side, name, error } => {
                write!(f, "`{name}` is not a variable of program {side}: {error}")
            }
            CompareError::InputMappedToNonInput { a, b } => write!(
                f,
                "--map {a}={b}: one side is an input (VAR_INPUT or %I) and the other is not"
            ),
            CompareError::InputTypesDiffer { a, b } => write!(
                f,
                "inputs A.{} ({}) and B.{} ({}) have different types: one stimulus cannot drive both",
                a.0, a.1, b.0, b.1
            ),
            CompareError::MappedTwice { name } => write!(f, "--map names `{name}` twice"),
            CompareError::UnknownIgnore { name } => write!(
                f,
                "--ignore {name}: not an input or compared output of either program"
            ),
            CompareError::NoCommonInputs { a, b } => write!(
                f,
                "the programs have no common input (A reads {}; B reads {}): pair them with --map A_NAME=B_NAME",
                list(a),
                list(b)
            ),
            CompareError::NoComparedOutputs { a, b } => write!(
                f,
                "no output to compare (A's outputs: {}; B's outputs: {}): pair them with --map A_NAME=B_NAME",
                list(a),
                list(b)
            ),
            CompareError::TicksDiffer { a, b } => write!(
                f,
                "the programs' base ticks differ ({} vs {}): compare runs them cycle by cycle",
                crate::value::literal::format_duration(*a, "T#"),
                crate::value::literal::format_duration(*b, "T#")
            ),
            CompareError::NotAnInput { column } => write!(
                f,
                "stimulus column `{column}` is not an input both programs read"
            ),
            CompareError::BadValue { side, input, error } => {
                write!(f, "input `{input}` of program {side}: {error}")
            }
            CompareError::Stimulus(e) => write!(f, "stimulus: {e}"),
            CompareError::BadRandomSettings { problem } => write!(f, "{problem}"),
            CompareError::Worker { message } => write!(f, "{message}"),
        }
    }
}

impl std::error::Error for CompareError {}

fn list(names: &[String]) -> String {
    if names.is_empty() {
        "nothing".to_string()
    } else {
        names.join(", ")
    }
}
