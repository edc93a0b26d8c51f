//! plcrun: an IEC 61131-3 runtime.
//!
//! Instruction List, Structured Text and textual SFC are parsed into one AST,
//! checked, lowered into one typed IR and executed by one interpreter under a
//! cyclic scheduler on a virtual clock.

#![warn(missing_docs)]

pub mod diagnostics;
pub mod ir;
pub mod runtime;
pub mod sema;
pub mod source;
pub mod stdlib;
pub mod syntax;
pub mod types;
pub mod vm;

pub use runtime::engine::{CompileError, Options, Plc, RuntimeFault, Value};
