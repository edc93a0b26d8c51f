//! A failed call: the status code the caller gets and the message
//! `plc_last_error` returns, made from the library's typed errors.

use crate::status::*;
use plcrun::{AddressError, CompileError, RetainError, RuntimeFault, UnknownTask, VarError};
use std::ffi::c_int;

/// Why an entry point failed.
#[derive(Debug)]
pub(crate) struct Failure {
    /// One of the `PLC_E_*` codes.
    pub code: c_int,
    /// The text for `plc_last_error`.
    pub message: String,
}

impl Failure {
    pub fn new(code: c_int, message: impl Into<String>) -> Failure {
        Failure {
            code,
            message: message.into(),
        }
    }

    pub fn null(what: &str) -> Failure {
        Failure::new(PLC_E_NULL_ARGUMENT, format!("`{what}` is NULL"))
    }
}

impl From<VarError> for Failure {
    fn from(e: VarError) -> Failure {
        let code = match &e {
            VarError::BadValue { .. }
            | VarError::WrongValue { .. }
            | VarError::ValueDoesNotFit { .. } => PLC_E_BAD_VALUE,
            VarError::ReadOnly { .. } => PLC_E_READ_ONLY,
            VarError::NotAnInteger { .. } => PLC_E_WRONG_TYPE,
            VarError::ForeignHandle { .. } => PLC_E_INVALID_HANDLE,
            // Every other variant says the path does not name a value.
            _ => PLC_E_UNKNOWN_VARIABLE,
        };
        Failure::new(code, e.to_string())
    }
}

impl From<CompileError> for Failure {
    fn from(e: CompileError) -> Failure {
        Failure::new(PLC_E_COMPILE, e.to_string())
    }
}

impl From<&RuntimeFault> for Failure {
    fn from(f: &RuntimeFault) -> Failure {
        Failure::new(PLC_E_RUNTIME_FAULT, f.to_string())
    }
}

impl From<AddressError> for Failure {
    fn from(e: AddressError) -> Failure {
        let code = match &e {
            AddressError::OutOfRange { .. } => PLC_E_ADDRESS_OUT_OF_RANGE,
            AddressError::WrongWidth { .. } => PLC_E_WRONG_TYPE,
            AddressError::NotWritable { .. } => PLC_E_READ_ONLY,
            // Syntax, a bit over 7, a non-zero leading field (and any
            // later variant): the text names no place in the image.
            _ => PLC_E_BAD_ADDRESS,
        };
        Failure::new(code, e.to_string())
    }
}

impl From<RetainError> for Failure {
    fn from(e: RetainError) -> Failure {
        let code = match &e {
            RetainError::Mismatch { .. } => PLC_E_RETAIN_MISMATCH,
            _ => PLC_E_RETAIN_FILE,
        };
        Failure::new(code, e.to_string())
    }
}

impl From<UnknownTask> for Failure {
    fn from(e: UnknownTask) -> Failure {
        Failure::new(PLC_E_UNKNOWN_TASK, e.to_string())
    }
}
