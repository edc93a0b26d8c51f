//! Retained data from C: save the RETAIN and PERSISTENT values to a file
//! (atomically) and restore them from one (a warm start).

use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::text::{input, store};
use plcrun::RestoreMode;
use std::ffi::{c_char, c_int};

/// Writes the retained values to the file `path` now, atomically (a
/// temporary file, fsync, rename): the file holds the old or the new
/// values, never a mix. `PLC_E_RETAIN_FILE` when it cannot be written.
///
/// # Safety
/// `path` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_retain_save(plc: PlcHandle, path: *const c_char) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let path = unsafe { input(path, "path") }?;
        handles::with_entry(plc, |e| Ok(e.plc.save_retain(path)?))
    })
}

/// Restores the retained values from the file `path`. A file whose
/// retained variables (names and types) differ from the program's is
/// refused with `PLC_E_RETAIN_MISMATCH`, the message saying what differs
/// and nothing restored; with `partial` true the values that still fit are
/// restored instead. `*restored` (when `restored` is not NULL) gets how
/// many values were. A file that cannot be read or is damaged is
/// `PLC_E_RETAIN_FILE`.
///
/// # Safety
/// `path` is NULL or NUL-terminated; `restored` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_retain_restore(
    plc: PlcHandle,
    path: *const c_char,
    partial: bool,
    restored: *mut usize,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let path = unsafe { input(path, "path") }?;
        let mode = if partial {
            RestoreMode::Partial
        } else {
            RestoreMode::Exact
        };
        let report = handles::with_entry(plc, |e| Ok(e.plc.restore_retain(path, mode)?))?;
        if !restored.is_null() {
            // SAFETY: not NULL, writable by the caller's contract.
            unsafe { store(restored, "restored", report.restored) }?;
        }
        Ok(())
    })
}
