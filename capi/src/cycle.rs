//! Running cycles on the virtual clock, the clock itself, the fault that
//! stops a PLC (the library's faulted state) and the resets that clear it.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::status::PLC_E_FAULTED;
use crate::text::{output, store};
use std::ffi::{c_char, c_int};

/// Runs one cycle: every task due at this tick runs its programs, then
/// the clock advances by one cycle time. A runtime fault returns
/// `PLC_E_RUNTIME_FAULT` (`plc_last_error()` says what, in which POU,
/// at which `file:line:column`, in which cycle) and stops the PLC: later
/// cycles return `PLC_E_FAULTED` until `plc_reset_cold` or
/// `plc_reset_warm`; its variables can still be read and written.
#[unsafe(no_mangle)]
pub extern "C" fn plc_run_cycle(plc: PlcHandle) -> c_int {
    guard(|| {
        handles::with_entry(plc, |e| {
            // The library keeps the fault (faulted STOP); only the status
            // tells a new fault from the one that stopped the PLC earlier.
            if let Some(f) = e.plc.fault() {
                return Err(Failure::new(
                    PLC_E_FAULTED,
                    format!("the PLC is stopped on an earlier fault: {f}"),
                ));
            }
            let result = e.plc.run_cycle().map_err(|f| Failure::from(&f));
            // The server sees the cycle (even a faulted one) and the
            // clients' writes land before the next.
            if let Some((_, exchange)) = &mut e.opcua {
                exchange.exchange(&mut e.plc);
            }
            result
        })
    })
}

/// Whether the PLC is stopped on a fault (`*out` true) or can run.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_is_faulted(plc: PlcHandle, out: *mut bool) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let faulted = handles::with_entry(plc, |e| Ok(e.plc.fault().is_some()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", faulted) }
    })
}

/// The fault that stopped the PLC, as `plc_run_cycle` reported it ("" when
/// it is not faulted), into the caller's buffer.
///
/// # Safety
/// `buf` is NULL or holds `capacity` bytes; `needed` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_fault_message(
    plc: PlcHandle,
    buf: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> c_int {
    guard(|| {
        let text = handles::with_entry(plc, |e| {
            Ok(e.plc.fault().map(|f| f.to_string()).unwrap_or_default())
        })?;
        // SAFETY: the caller's contract.
        unsafe { output(&text, buf, capacity, needed) }
    })
}

/// Cold reset: every variable back to its initial value (retained ones
/// too), cycle count and clock back to 0, the fault and any abort request
/// cleared; cycles run again. The program, the watchdog limits, the
/// forces and resolved handles stay.
#[unsafe(no_mangle)]
pub extern "C" fn plc_reset_cold(plc: PlcHandle) -> c_int {
    guard(|| {
        handles::with_entry(plc, |e| {
            e.plc.reset_cold();
            Ok(())
        })
    })
}

/// Warm reset: as `plc_reset_cold`, but the retained (RETAIN, PERSISTENT)
/// variables keep their values.
#[unsafe(no_mangle)]
pub extern "C" fn plc_reset_warm(plc: PlcHandle) -> c_int {
    guard(|| {
        handles::with_entry(plc, |e| {
            e.plc.reset_warm();
            Ok(())
        })
    })
}

/// The number of the next cycle to run (0 before the first).
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_cycle(plc: PlcHandle, out: *mut u64) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let cycle = handles::with_entry(plc, |e| Ok(e.plc.cycle()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", cycle) }
    })
}

/// The virtual clock at the start of the next cycle, in nanoseconds.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_time_ns(plc: PlcHandle, out: *mut i64) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let time = handles::with_entry(plc, |e| Ok(e.plc.time()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", time) }
    })
}

/// The duration of one cycle (the base tick), in nanoseconds.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_cycle_time_ns(plc: PlcHandle, out: *mut i64) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let tick = handles::with_entry(plc, |e| Ok(e.plc.cycle_time()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", tick) }
    })
}
