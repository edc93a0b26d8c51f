//! Runtime faults: conditions that stop the PLC.

use crate::value::convert::ConvError;
use std::fmt;

/// Why execution stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum FaultKind {
    /// Integer division or MOD by zero.
    DivisionByZero,
    /// An array index outside the declared bounds.
    IndexOutOfRange {
        /// The index value.
        index: i64,
        /// Lower bound.
        lo: i64,
        /// Upper bound.
        hi: i64,
    },
    /// A value stored into a subrange variable lies outside the subrange.
    SubrangeViolation {
        /// The value.
        value: i64,
        /// Lower bound.
        lo: i64,
        /// Upper bound.
        hi: i64,
    },
    /// A conversion whose result does not fit the target type (or NaN).
    ConversionOverflow,
    /// MUX selector out of range.
    MuxOutOfRange {
        /// Selector value.
        k: i64,
        /// Number of inputs.
        n: u32,
    },
    /// A BCD value with a nibble above 9.
    InvalidBcd,
    /// A negative exponent in an integer `**`.
    NegativeExponent,
    /// A task ran longer than its watchdog allows (the runtime's
    /// `RuntimeFault::watchdog` says which task, the limit and the time).
    Watchdog,
    /// The cycle was interrupted through a stop handle's `abort`.
    Aborted,
    /// A computed address fell outside memory (an internal error).
    BadAddress,
    /// A host-registered FUNCTION or FUNCTION_BLOCK failed: it returned
    /// an error or panicked (boxed: faults stay small).
    HostFunction(Box<HostFailure>),
    /// IEC 60848 evolution (`--grafcet`) found no stable situation within
    /// its bound: the chart's transitions keep firing (boxed: faults stay
    /// small).
    UnstableChart(Box<UnstableCycle>),
    /// A dereference of `NULL` (R030).
    NullReference,
    /// A dereference outside the object the reference or pointer was
    /// taken from (R031).
    OutsideObject {
        /// The reference's offset in its object, in slots.
        offset: i64,
        /// The slots the dereference reads or writes.
        width: u32,
        /// The object's size in slots.
        len: u32,
    },
    /// A reference taken before the memory was laid out anew (R032).
    StaleReference,
    /// More distinct objects referenced than a reference can number (R033).
    TooManyReferencedObjects,
    /// A method was called through an interface variable that holds no
    /// instance (never assigned, or assigned 0).
    NullInterface,
    /// A method was called on an instance where it is still running: a
    /// cycle of calls through interfaces came back to it (R081).
    MethodReentered,
    /// `F_RaiseException` (Tc2_System) raised the exception with this code
    /// (R082): a `__CATCH` receives it; uncaught, it stops the PLC.
    Raised(u32),
    /// A byte view (a pointer of another element type than its object's)
    /// read or wrote outside the object's bytes (R031, as for slots).
    OutsideBytes {
        /// The view's offset in its object, in bytes.
        offset: i64,
        /// The bytes the dereference reads or writes.
        width: u32,
        /// The object's size in bytes.
        len: u32,
    },
    /// A byte view dereferenced as a STRING, structure, array or FB: only
    /// elementary values are read and written through one (R034).
    ByteViewAggregate,
    /// A pointer made from an integer that no pointer gave (R035).
    NotFromPointer,
    /// A pointer outside its object, or into an object too large or too
    /// many, turned into an integer (R036).
    NoIntegerImage,
    /// A byte view of an object without a byte layout: an FB instance, or
    /// a structure holding one (R037).
    NoByteLayout,
}

/// A chart that did not reach a stable situation under IEC 60848 evolution.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnstableCycle {
    /// The POU whose chart it is.
    pub chart: String,
    /// The bound that was reached: successive firings in one call.
    pub bound: usize,
    /// The transitions of the unstable cycle (`FROM -> TO`), in firing
    /// order.
    pub transitions: Vec<String>,
}

/// Which host body failed, and how.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HostFailure {
    /// The POU's name.
    pub name: String,
    /// The error's text, or `panicked: ` and the panic's message.
    pub message: String,
}

impl FaultKind {
    /// The fault of a failed host body.
    pub(crate) fn host(name: impl Into<String>, message: impl Into<String>) -> FaultKind {
        FaultKind::HostFunction(Box::new(HostFailure {
            name: name.into(),
            message: message.into(),
        }))
    }
}

impl From<ConvError> for FaultKind {
    fn from(e: ConvError) -> Self {
        match e {
            ConvError::Overflow => FaultKind::ConversionOverflow,
            ConvError::InvalidBcd => FaultKind::InvalidBcd,
        }
    }
}

impl FaultKind {
    /// The fault's stable code (`R001`...), listed with an explanation in
    /// docs/diagnostics.md; never reused for another kind of fault.
    ///
    /// ```
    /// assert_eq!(plcrun::FaultKind::DivisionByZero.code(), "R001");
    /// assert_eq!(plcrun::FaultKind::Watchdog.code(), "R008");
    /// ```
    pub fn code(&self) -> &'static str {
        match self {
            FaultKind::DivisionByZero => "R001",
            FaultKind::IndexOutOfRange { .. } => "R002",
            FaultKind::SubrangeViolation { .. } => "R003",
            FaultKind::ConversionOverflow => "R004",
            FaultKind::MuxOutOfRange { .. } => "R005",
            FaultKind::InvalidBcd => "R006",
            FaultKind::NegativeExponent => "R007",
            FaultKind::Watchdog => "R008",
            FaultKind::Aborted => "R009",
            FaultKind::HostFunction(_) => "R010",
            FaultKind::UnstableChart(_) => "R020",
            FaultKind::NullReference => "R030",
            FaultKind::OutsideObject { .. } => "R031",
            FaultKind::StaleReference => "R032",
            FaultKind::TooManyReferencedObjects => "R033",
            FaultKind::BadAddress => "R999",
            FaultKind::NullInterface => "R080",
            FaultKind::MethodReentered => "R081",
            FaultKind::Raised(_) => "R082",
            FaultKind::OutsideBytes { .. } => "R031",
            FaultKind::ByteViewAggregate => "R034",
            FaultKind::NotFromPointer => "R035",
            FaultKind::NoIntegerImage => "R036",
            FaultKind::NoByteLayout => "R037",
        }
    }
}

impl fmt::Display for FaultKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FaultKind::DivisionByZero => write!(f, "division by zero"),
            FaultKind::IndexOutOfRange { index, lo, hi } => {
                write!(f, "array index {index} out of bounds [{lo}..{hi}]")
            }
            FaultKind::SubrangeViolation { value, lo, hi } => {
                write!(f, "value {value} outside the subrange {lo}..{hi}")
            }
            FaultKind::ConversionOverflow => {
                write!(f, "conversion result out of the target type's range")
            }
            FaultKind::MuxOutOfRange { k, n } => {
                write!(
                    f,
                    "MUX selector {k} out of range (0..{})",
                    n.saturating_sub(1)
                )
            }
            FaultKind::InvalidBcd => write!(f, "invalid BCD value"),
            FaultKind::NegativeExponent => write!(f, "negative exponent in integer `**`"),
            FaultKind::Watchdog => write!(f, "watchdog: cycle exceeded its time limit"),
            FaultKind::Aborted => write!(f, "aborted: the cycle was interrupted by a stop handle"),
            FaultKind::BadAddress => write!(
                f,
                "address outside memory: a VAR_IN_OUT used before a call of its block connected it \
                 (in a METHOD or an action), or an internal error"
            ),
            FaultKind::NullReference => write!(f, "dereference of a NULL reference"),
            FaultKind::OutsideObject { offset, width, len } => write!(
                f,
                "dereference outside the object the reference was taken from \
                 (slot {offset}, {width} slot(s) wide, object of {len} slot(s))"
            ),
            FaultKind::StaleReference => write!(
                f,
                "dereference of a reference taken before an online change"
            ),
            FaultKind::TooManyReferencedObjects => {
                write!(f, "too many distinct objects referenced")
            }
            FaultKind::NullInterface => write!(
                f,
                "method called through an interface variable that holds no instance (assign an instance first, or test `itf <> 0`)"
            ),
            FaultKind::MethodReentered => write!(
                f,
                "method called again on an instance where it is still running (a cycle of calls \
                 through interfaces came back to it): plcrun keeps a method's variables in its instance"
            ),
            FaultKind::Raised(code) => match crate::ir::exception_codes::name_of(*code) {
                Some(name) => write!(
                    f,
                    "exception {name} (16#{code:X}) raised by F_RaiseException"
                ),
                None => write!(f, "exception 16#{code:X} raised by F_RaiseException"),
            },
            FaultKind::OutsideBytes { offset, width, len } => write!(
                f,
                "dereference outside the object the pointer was taken from \
                 (byte {offset}, {width} byte(s) wide, object of {len} byte(s))"
            ),
            FaultKind::ByteViewAggregate => write!(
                f,
                "a pointer of another element type than its object, or made from an integer, \
                 reads and writes elementary values only (not a STRING, structure, array or FB)"
            ),
            FaultKind::NotFromPointer => write!(
                f,
                "dereference of a pointer made from an integer that no pointer gave"
            ),
            FaultKind::NoIntegerImage => write!(
                f,
                "a pointer outside its object, or into an object over 1 MiB or beyond the 4095th, \
                 has no integer image"
            ),
            FaultKind::NoByteLayout => write!(
                f,
                "byte view of an object without a byte layout (an FB instance, or a structure holding one)"
            ),
            FaultKind::HostFunction(h) => {
                write!(f, "host function `{}` failed: {}", h.name, h.message)
            }
            FaultKind::UnstableChart(u) => write!(
                f,
                "unstable GRAFCET: the chart of `{}` is still evolving after {} successive firings; unstable cycle of transitions: {}",
                u.chart,
                u.bound,
                u.transitions.join(", ")
            ),
        }
    }
}

/// A fault with the instruction that raised it.
#[derive(Debug, Clone, PartialEq)]
pub struct Fault {
    /// What happened.
    pub kind: FaultKind,
    /// Code block (the runtime turns it and `pc` into the source location
    /// that `RuntimeFault` carries).
    pub(crate) code: crate::ir::op::CodeIdx,
    /// Instruction index inside the block.
    pub(crate) pc: u32,
}

/// A call that was under way when a fault unwound through it: the calling
/// block, its call instruction and the caller's own frame base. Recorded
/// only while a fault unwinds (see [`Machine::take_callers`]), innermost
/// first, so the normal path pays nothing for it; the callee's base follows
/// from the call instruction (`runtime::fault_path`).
///
/// [`Machine::take_callers`]: super::Machine::take_callers
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CallSite {
    /// The calling block.
    pub code: crate::ir::op::CodeIdx,
    /// The call instruction's index in it.
    pub pc: u32,
    /// The frame base the caller ran at.
    pub base: usize,
}
