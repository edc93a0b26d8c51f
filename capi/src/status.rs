//! The status codes every entry point returns (`PLC_OK` or a negative
//! `PLC_E_*`), with their one-line descriptions. `include/plcrun.h` holds
//! the same values; a test checks that they agree.

use std::ffi::{c_char, c_int};

/// The call succeeded.
pub const PLC_OK: c_int = 0;
/// A pointer argument that must not be NULL was NULL.
pub const PLC_E_NULL_ARGUMENT: c_int = -1;
/// The PLC or variable handle is not (or no longer) valid.
pub const PLC_E_INVALID_HANDLE: c_int = -2;
/// An argument is out of its domain (text that is not UTF-8, a negative
/// cycle time, no source file).
pub const PLC_E_INVALID_ARGUMENT: c_int = -3;
/// The sources did not compile; `plc_last_error` holds the diagnostics.
pub const PLC_E_COMPILE: c_int = -4;
/// The path names no variable, or an aggregate rather than a single value.
pub const PLC_E_UNKNOWN_VARIABLE: c_int = -5;
/// The literal is not a value of the variable's type.
pub const PLC_E_BAD_VALUE: c_int = -6;
/// A typed accessor was used on a variable of another type, or an image
/// accessor on an address of another width (`%IX0.1` as a word).
pub const PLC_E_WRONG_TYPE: c_int = -7;
/// The number does not fit the variable's type.
pub const PLC_E_OUT_OF_RANGE: c_int = -8;
/// The cycle stopped on a runtime fault (division by zero, ...).
pub const PLC_E_RUNTIME_FAULT: c_int = -9;
/// The PLC is stopped on an earlier fault and runs no more cycles.
pub const PLC_E_FAULTED: c_int = -10;
/// The output buffer is too small; `*needed` says how large it must be.
pub const PLC_E_BUFFER_TOO_SMALL: c_int = -11;
/// A bug inside plcrun was caught at the boundary (a Rust panic).
pub const PLC_E_PANIC: c_int = -12;
/// The variable or image area cannot be written from outside: a
/// CONSTANT, an SFC step or action flag, the `%Q` area.
pub const PLC_E_READ_ONLY: c_int = -13;
/// The text is not a process image address (`%IX0.3`, `%QW4`), or maps
/// to no place in the image (bit over 7, a non-zero leading field).
pub const PLC_E_BAD_ADDRESS: c_int = -14;
/// The address or byte range lies past the end of its image area.
pub const PLC_E_ADDRESS_OUT_OF_RANGE: c_int = -15;
/// A retain file could not be read or written, or is damaged.
pub const PLC_E_RETAIN_FILE: c_int = -16;
/// A retain file's variables (names, types) differ from the program's;
/// nothing was restored.
pub const PLC_E_RETAIN_MISMATCH: c_int = -17;
/// No task of the configuration has that name.
pub const PLC_E_UNKNOWN_TASK: c_int = -18;
/// The operating system refused a real-time setting (SCHED_FIFO, memory
/// lock) to this process; `plc_last_error` says what would permit it.
pub const PLC_E_NOT_PERMITTED: c_int = -19;
/// The OPC UA server could not start (address, port in use, users file,
/// certificate directory); `plc_last_error` gives the E95x code and why.
pub const PLC_E_SERVER: c_int = -20;

/// Every status with its name and description, in the header's order.
pub(crate) const STATUSES: &[(c_int, &str, &str)] = &[
    (PLC_OK, "PLC_OK", "success\0"),
    (
        PLC_E_NULL_ARGUMENT,
        "PLC_E_NULL_ARGUMENT",
        "a required pointer argument is NULL\0",
    ),
    (
        PLC_E_INVALID_HANDLE,
        "PLC_E_INVALID_HANDLE",
        "invalid or freed handle\0",
    ),
    (
        PLC_E_INVALID_ARGUMENT,
        "PLC_E_INVALID_ARGUMENT",
        "invalid argument\0",
    ),
    (
        PLC_E_COMPILE,
        "PLC_E_COMPILE",
        "the sources do not compile\0",
    ),
    (
        PLC_E_UNKNOWN_VARIABLE,
        "PLC_E_UNKNOWN_VARIABLE",
        "no such variable\0",
    ),
    (
        PLC_E_BAD_VALUE,
        "PLC_E_BAD_VALUE",
        "not a value of the variable's type\0",
    ),
    (
        PLC_E_WRONG_TYPE,
        "PLC_E_WRONG_TYPE",
        "the variable or address is of another type or width\0",
    ),
    (
        PLC_E_OUT_OF_RANGE,
        "PLC_E_OUT_OF_RANGE",
        "the number does not fit the variable's type\0",
    ),
    (
        PLC_E_RUNTIME_FAULT,
        "PLC_E_RUNTIME_FAULT",
        "runtime fault\0",
    ),
    (
        PLC_E_FAULTED,
        "PLC_E_FAULTED",
        "the PLC is stopped on an earlier fault\0",
    ),
    (
        PLC_E_BUFFER_TOO_SMALL,
        "PLC_E_BUFFER_TOO_SMALL",
        "the output buffer is too small\0",
    ),
    (
        PLC_E_PANIC,
        "PLC_E_PANIC",
        "internal error (panic caught at the C boundary)\0",
    ),
    (
        PLC_E_READ_ONLY,
        "PLC_E_READ_ONLY",
        "cannot be written from outside the program\0",
    ),
    (
        PLC_E_BAD_ADDRESS,
        "PLC_E_BAD_ADDRESS",
        "not a process image address\0",
    ),
    (
        PLC_E_ADDRESS_OUT_OF_RANGE,
        "PLC_E_ADDRESS_OUT_OF_RANGE",
        "outside the process image area\0",
    ),
    (
        PLC_E_RETAIN_FILE,
        "PLC_E_RETAIN_FILE",
        "the retain file cannot be read or written, or is damaged\0",
    ),
    (
        PLC_E_RETAIN_MISMATCH,
        "PLC_E_RETAIN_MISMATCH",
        "the retain file does not fit the program\0",
    ),
    (PLC_E_UNKNOWN_TASK, "PLC_E_UNKNOWN_TASK", "no such task\0"),
    (
        PLC_E_NOT_PERMITTED,
        "PLC_E_NOT_PERMITTED",
        "the system refused a real-time setting\0",
    ),
    (
        PLC_E_SERVER,
        "PLC_E_SERVER",
        "the OPC UA server could not start\0",
    ),
];

/// A static, NUL-terminated description of `status` ("unknown status" for
/// a value that is not one). Never NULL; never to be freed.
#[unsafe(no_mangle)]
pub extern "C" fn plc_status_text(status: c_int) -> *const c_char {
    STATUSES
        .iter()
        .find(|(code, _, _)| *code == status)
        .map_or("unknown status\0", |(_, _, text)| text)
        .as_ptr()
        .cast()
}
