//! Why a variable named from outside the program (API, `--set`, stimulus
//! columns, `--trace`) could not be resolved, read or written.

use std::fmt;

/// A variable access from outside the program that cannot be done.
///
/// Every variant carries the path as the caller wrote it; `Display` gives
/// the message the command line prints.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum VarError {
    /// The text is not a variable path (`x`, `inst.Q`, `arr[1,2]`, `%IX0.1`).
    BadPath {
        /// The text as given.
        path: String,
        /// What is wrong with it.
        problem: PathProblem,
    },
    /// No variable, global or program instance has this name.
    Unknown {
        /// The root name.
        name: String,
    },
    /// No variable is located at this direct address.
    NotLocated {
        /// The address as given.
        address: String,
    },
    /// A `.member` that the type does not have.
    NoMember {
        /// The full path.
        path: String,
        /// The type that lacks the member.
        ty: String,
        /// The member asked for.
        member: String,
    },
    /// `[...]` on something that is not an array.
    NotAnArray {
        /// The full path.
        path: String,
        /// Its type.
        ty: String,
    },
    /// The number of indexes differs from the number of dimensions.
    IndexCount {
        /// The full path.
        path: String,
        /// Dimensions of the array.
        dimensions: usize,
        /// Indexes given.
        given: usize,
    },
    /// An index outside the declared bounds.
    IndexOutOfBounds {
        /// The full path.
        path: String,
        /// The index given.
        index: i64,
        /// Lower bound.
        lo: i64,
        /// Upper bound.
        hi: i64,
    },
    /// The path names an aggregate (array, structure, FB instance), not a
    /// single value.
    NotAValue {
        /// The path.
        path: String,
        /// Its type.
        ty: String,
    },
    /// The literal does not decode as a value of the variable's type.
    BadValue {
        /// The literal as given (trimmed).
        literal: String,
        /// The variable's type.
        ty: String,
        /// Why.
        problem: ValueProblem,
    },
    /// The value read is not an integer (for integer accessors).
    NotAnInteger {
        /// The path.
        path: String,
    },
    /// A trace column named `cycle` or `time`, the trace's own columns.
    TraceColumn {
        /// The name as given.
        name: String,
    },
    /// A handle resolved by another PLC.
    ForeignHandle {
        /// The handle's path.
        path: String,
    },
    /// A value of another type (or outside the type's range) given to
    /// `set`.
    WrongValue {
        /// The variable's path.
        path: String,
        /// Its type.
        ty: String,
        /// The value given, as a literal.
        value: String,
    },
    /// A write from outside to a variable the program itself cannot write:
    /// reading it is fine.
    ReadOnly {
        /// The path.
        path: String,
        /// Why it cannot be written.
        why: ReadOnlyReason,
    },
    /// A literal that does not decode as a value of the variable it is
    /// meant for (a force): names both.
    ValueDoesNotFit {
        /// The variable's path.
        path: String,
        /// The literal as given (trimmed).
        literal: String,
        /// The variable's type.
        ty: String,
        /// Why (boxed to keep the error small).
        problem: Box<ValueProblem>,
    },
}

/// Why a variable cannot be written from outside the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ReadOnlyReason {
    /// It is declared CONSTANT (its uses may be folded into the code).
    Constant,
    /// An SFC step flag (`S1.X`, `S1.T`): the chart's evolution sets it.
    StepFlag,
    /// An SFC action's control flag (`A1.Q`, `A1.A`): action control sets it.
    ActionFlag,
}

impl fmt::Display for ReadOnlyReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ReadOnlyReason::Constant => "it is a CONSTANT",
            ReadOnlyReason::StepFlag => "step flags are set by the chart's evolution",
            ReadOnlyReason::ActionFlag => "action flags are set by action control",
        })
    }
}

/// What is wrong with a variable path's text.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum PathProblem {
    /// Nothing but blanks.
    Empty,
    /// A part that should be an identifier is not one.
    NotAName,
    /// `[` without its `]`.
    MissingBracket,
    /// An array index that is not a whole number.
    IndexNotAnInteger(String),
    /// A character that cannot follow.
    Unexpected(char),
}

impl fmt::Display for ValueProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ValueProblem::NotAString => f.write_str("a string literal is needed (write 'text')"),
            ValueProblem::NotAnEnumValue => f.write_str("not a value of the enumeration"),
            ValueProblem::Invalid => f.write_str("not a valid literal of the type"),
            ValueProblem::OutsideSubrange(v) => write!(f, "{v} is outside the subrange"),
        }
    }
}

/// Why a literal does not fit a variable.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum ValueProblem {
    /// A STRING variable needs a quoted literal.
    NotAString,
    /// Not a value of the enumeration.
    NotAnEnumValue,
    /// Not a literal of the type (or it does not fit the type's range).
    Invalid,
    /// A whole number outside a subrange.
    OutsideSubrange(i64),
}

impl fmt::Display for VarError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VarError::BadPath { path, problem } => match problem {
                PathProblem::Empty => f.write_str("empty variable name"),
                PathProblem::NotAName => write!(f, "`{path}` is not a variable name"),
                PathProblem::MissingBracket => write!(f, "`{path}`: missing `]`"),
                PathProblem::IndexNotAnInteger(i) => {
                    write!(f, "`{path}`: array index `{i}` is not an integer")
                }
                PathProblem::Unexpected(c) => write!(f, "`{path}`: unexpected `{c}`"),
            },
            VarError::Unknown { name } => write!(f, "unknown variable `{name}`"),
            VarError::NotLocated { address } => {
                write!(f, "no variable is located at `{address}`")
            }
            VarError::NoMember { path, ty, member } => {
                write!(f, "`{path}`: {ty} has no member `{member}`")
            }
            VarError::NotAnArray { path, ty } => write!(f, "`{path}`: {ty} is not an array"),
            VarError::IndexCount {
                path,
                dimensions,
                given,
            } => write!(
                f,
                "`{path}`: the array has {dimensions} dimension(s), {given} index(es) given"
            ),
            VarError::IndexOutOfBounds {
                path,
                index,
                lo,
                hi,
            } => write!(f, "`{path}`: index {index} is outside [{lo}..{hi}]"),
            VarError::NotAValue { path, ty } => {
                write!(f, "`{path}` is a {ty}, not a single value")
            }
            VarError::BadValue {
                literal,
                ty,
                problem,
            } => match problem {
                ValueProblem::NotAString => {
                    write!(f, "`{literal}` is not a string literal (write 'text')")
                }
                ValueProblem::NotAnEnumValue => write!(f, "`{literal}` is not a value of {ty}"),
                ValueProblem::Invalid => write!(f, "`{literal}` is not a valid {ty} value"),
                ValueProblem::OutsideSubrange(v) => write!(f, "{v} is outside {ty}"),
            },
            VarError::NotAnInteger { path } => write!(f, "`{path}` is not an integer"),
            VarError::TraceColumn { name } => write!(
                f,
                "`{name}` is the trace's own column: name the variable by its path, \
                 e.g. `P.{name}` with its program instance"
            ),
            VarError::ForeignHandle { path } => {
                write!(f, "`{path}` was resolved by another PLC")
            }
            VarError::WrongValue { path, ty, value } => {
                write!(f, "`{path}` is of type {ty} and cannot hold {value}")
            }
            VarError::ReadOnly { path, why } => {
                write!(
                    f,
                    "`{path}` cannot be written from outside: {why} (it can be read)"
                )
            }
            VarError::ValueDoesNotFit {
                path,
                literal,
                ty,
                problem,
            } => write!(
                f,
                "`{path}` is of type {ty} and cannot take `{literal}`: {problem}"
            ),
        }
    }
}

impl std::error::Error for VarError {}
