//! The watchdog, and stopping a running cycle from another thread.
//!
//! Calls on one PLC wait for its lock, which `plc_run_cycle` holds for the
//! whole cycle: an abort that took it would wait for the runaway cycle it
//! is meant to end. A stop token (`plc_stop`) is therefore a handle of its
//! own, backed by the library's lock-free `StopHandle`, in a table of its
//! own: `plc_abort` never touches the PLC's lock.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::slot_table::SlotTable;
use crate::status::{PLC_E_INVALID_ARGUMENT, PLC_E_INVALID_HANDLE};
use crate::text::{input, store};
use plcrun::StopHandle;
use std::ffi::{c_char, c_int};
use std::time::Duration;

/// A stop token (`plc_stop`): aborts its PLC's cycle from any thread.
/// Zero is never valid.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlcStop {
    /// Generation and slot, as for a PLC handle.
    pub id: u64,
}

/// Sets the watchdog limit of the task named `task` (case-insensitive;
/// `default` is the implicit task of a program without configuration), or
/// of every task when `task` is NULL, to `limit_ms` milliseconds; 0 turns
/// it off. A cycle that runs longer is stopped with a watchdog fault
/// (R008, `PLC_E_RUNTIME_FAULT`). `PLC_E_UNKNOWN_TASK` for a name that
/// is not a task; a negative limit is `PLC_E_INVALID_ARGUMENT`.
///
/// # Safety
/// `task` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_set_watchdog_ms(
    plc: PlcHandle,
    task: *const c_char,
    limit_ms: i64,
) -> c_int {
    guard(|| {
        let task = if task.is_null() {
            None
        } else {
            // SAFETY: not NULL, NUL-terminated by the caller's contract.
            Some(unsafe { input(task, "task") }?)
        };
        let limit = match u64::try_from(limit_ms) {
            Ok(0) => None,
            Ok(ms) => Some(Duration::from_millis(ms)),
            Err(_) => {
                return Err(Failure::new(
                    PLC_E_INVALID_ARGUMENT,
                    format!("limit_ms must be 0 (off) or positive, not {limit_ms}"),
                ));
            }
        };
        handles::with_entry(plc, |e| match task {
            Some(name) => Ok(e.plc.set_task_watchdog(name, limit)?),
            None => {
                e.plc.set_watchdog(limit);
                Ok(())
            }
        })
    })
}

/// Every stop token not yet freed. Locked only around vector operations
/// that cannot panic, never while a cycle runs.
static TOKENS: SlotTable<StopHandle> = SlotTable::new();

fn invalid(token: PlcStop) -> Failure {
    Failure::new(
        PLC_E_INVALID_HANDLE,
        format!(
            "stop token {:#x} is not valid (never made, or freed)",
            token.id
        ),
    )
}

/// Makes a stop token for `plc` into `*out` ({0} on failure). The token
/// stays valid until `plc_stop_token_free`, even after its PLC is freed
/// (an abort then does nothing). Take it before starting the cycle to be
/// aborted: this call waits for the PLC's lock like any other.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_stop_token(plc: PlcHandle, out: *mut PlcStop) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        unsafe { store(out, "out", PlcStop { id: 0 }) }?;
        let handle = handles::with_entry(plc, |e| Ok(e.plc.stop_handle()))?;
        let token = PlcStop {
            id: TOKENS.insert(handle),
        };
        unsafe { store(out, "out", token) }
    })
}

/// Aborts the PLC's running cycle, from any thread, without waiting for
/// it: the cycle is interrupted at its next backward jump or call (even
/// inside a loop that never ends) and `plc_run_cycle` returns
/// `PLC_E_RUNTIME_FAULT` with an R009 "aborted" message; the PLC is then
/// faulted until `plc_reset_cold` or `plc_reset_warm`. If no cycle is
/// running, the next one is aborted as it starts.
#[unsafe(no_mangle)]
pub extern "C" fn plc_abort(token: PlcStop) -> c_int {
    guard(|| {
        // Cloned out so that the table is not locked while aborting.
        let handle = TOKENS.get(token.id).ok_or_else(|| invalid(token))?;
        handle.abort();
        Ok(())
    })
}

/// Frees a stop token; it becomes invalid.
#[unsafe(no_mangle)]
pub extern "C" fn plc_stop_token_free(token: PlcStop) -> c_int {
    guard(|| {
        if TOKENS.remove(token.id) {
            Ok(())
        } else {
            Err(invalid(token))
        }
    })
}
