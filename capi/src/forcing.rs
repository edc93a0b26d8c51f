//! Forcing and soft writes, as a debug surface does them: force a variable
//! to a value that neither the program nor the host can change, release
//! it, list the forces, and write "softly" (a write a force overrides).
//!
//! The forces are listed by index (`plc_force_count`, then `plc_force_at`
//! for 0 .. count-1, in the order they were forced): C gets each path and
//! value as text in its own buffers, with nothing to free.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::status::{PLC_E_BUFFER_TOO_SMALL, PLC_E_INVALID_ARGUMENT};
use crate::text::{input, output, store};
use std::ffi::{c_char, c_int};

/// Forces the variable `path` to the IEC literal `literal` (forcing it
/// again replaces the value). The variable takes the value at once and
/// keeps it before and after every program run until unforced. An unknown
/// name is `PLC_E_UNKNOWN_VARIABLE`, a literal not of its type
/// `PLC_E_BAD_VALUE` (the message names both), a CONSTANT or an SFC step
/// or action flag `PLC_E_READ_ONLY`.
///
/// # Safety
/// `path` and `literal` are NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_force(
    plc: PlcHandle,
    path: *const c_char,
    literal: *const c_char,
) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let path = unsafe { input(path, "path") }?;
        let literal = unsafe { input(literal, "literal") }?;
        handles::with_entry(plc, |e| Ok(e.plc.force(path, literal)?))
    })
}

/// Releases the force on `path`. `*was_forced` (when `was_forced` is not
/// NULL) tells whether it was forced; releasing a variable that is not
/// forced is no error. The variable keeps the forced value, or takes the
/// last value soft-written while it was forced.
///
/// # Safety
/// `path` is NULL or NUL-terminated; `was_forced` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_unforce(
    plc: PlcHandle,
    path: *const c_char,
    was_forced: *mut bool,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let path = unsafe { input(path, "path") }?;
        let released = handles::with_entry(plc, |e| Ok(e.plc.unforce(path)?))?;
        if !was_forced.is_null() {
            // SAFETY: not NULL, writable by the caller's contract.
            unsafe { store(was_forced, "was_forced", released) }?;
        }
        Ok(())
    })
}

/// Releases every force (each as `plc_unforce` does).
#[unsafe(no_mangle)]
pub extern "C" fn plc_unforce_all(plc: PlcHandle) -> c_int {
    guard(|| {
        handles::with_entry(plc, |e| {
            e.plc.unforce_all();
            Ok(())
        })
    })
}

/// Writes `path` from an IEC literal as a soft write: a force on the
/// variable overrides it (the variable takes it when unforced). Every
/// `plc_set_*` is a soft write; this one says so.
///
/// # Safety
/// `path` and `literal` are NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_soft_write(
    plc: PlcHandle,
    path: *const c_char,
    literal: *const c_char,
) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let path = unsafe { input(path, "path") }?;
        let literal = unsafe { input(literal, "literal") }?;
        handles::with_entry(plc, |e| Ok(e.plc.soft_write(path, literal)?))
    })
}

/// The number of forced variables.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_force_count(plc: PlcHandle, out: *mut usize) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let count = handles::with_entry(plc, |e| Ok(e.plc.forces().len()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", count) }
    })
}

/// The force number `index` (0-based, in the order of forcing): its path
/// (as it was forced) into `path_buf` and its value as an IEC literal into
/// `value_buf`, each under the "text out" rules with its own capacity and
/// `*needed`. When either buffer is too small both hold "" and both
/// `*needed` are set. An index past the last force is
/// `PLC_E_INVALID_ARGUMENT`.
///
/// # Safety
/// Each buffer is NULL or holds its capacity in bytes; each `needed` is
/// NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_force_at(
    plc: PlcHandle,
    index: usize,
    path_buf: *mut c_char,
    path_capacity: usize,
    path_needed: *mut usize,
    value_buf: *mut c_char,
    value_capacity: usize,
    value_needed: *mut usize,
) -> c_int {
    guard(|| {
        let (path, value) = handles::with_entry(plc, |e| {
            let forces = e.plc.forces();
            let count = forces.len();
            let f = forces.into_iter().nth(index).ok_or_else(|| {
                Failure::new(
                    PLC_E_INVALID_ARGUMENT,
                    format!("no force number {index}: {count} variables are forced"),
                )
            })?;
            Ok((f.path, f.value.to_literal()))
        })?;
        let fits = path.len() < path_capacity && value.len() < value_capacity;
        if !fits {
            // Both sizes at once, and no half-filled pair: "" in each
            // buffer that has room, the sizes in both `needed`.
            // SAFETY (both calls): the caller's contract.
            unsafe { empty(path_buf, path_capacity, "path_buf") }?;
            unsafe { empty(value_buf, value_capacity, "value_buf") }?;
            for (needed, text) in [(path_needed, &path), (value_needed, &value)] {
                if !needed.is_null() {
                    // SAFETY: not NULL, writable by the caller's contract.
                    unsafe { needed.write(text.len() + 1) };
                }
            }
            return Err(Failure::new(
                PLC_E_BUFFER_TOO_SMALL,
                format!(
                    "the path needs {} bytes (buffer {path_capacity}), the value {} \
                     (buffer {value_capacity})",
                    path.len() + 1,
                    value.len() + 1
                ),
            ));
        }
        // SAFETY (both calls): the caller's contract.
        unsafe { output(&path, path_buf, path_capacity, path_needed) }?;
        unsafe { output(&value, value_buf, value_capacity, value_needed) }
    })
}

/// Leaves "" in `buf` when it has room.
///
/// # Safety
/// `buf` is NULL or holds `capacity` bytes.
unsafe fn empty(buf: *mut c_char, capacity: usize, what: &str) -> Result<(), Failure> {
    if capacity == 0 {
        return Ok(());
    }
    if buf.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: at least one writable byte.
    unsafe { buf.write(0) };
    Ok(())
}
