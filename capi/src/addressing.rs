//! The addressing convention of a PLC's process image from C
//! (docs/runtime.md, "Addressing"): which bytes `%QW1` names.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::status::PLC_E_INVALID_ARGUMENT;
use crate::text::store;
use plcrun::Addressing;
use std::ffi::c_int;

/// `PLC_ADDRESSING_IEC`: CODESYS' layout, `%QWn` is bytes `2n`, `2n+1`.
pub const PLC_ADDRESSING_IEC: c_int = 0;
/// `PLC_ADDRESSING_OPENPLC`: matiec/OpenPLC, one table per area and size.
pub const PLC_ADDRESSING_OPENPLC: c_int = 1;
/// `PLC_ADDRESSING_BYTE`: every address a byte offset (S7).
pub const PLC_ADDRESSING_BYTE: c_int = 2;

fn from_code(code: c_int) -> Result<Addressing, Failure> {
    match code {
        PLC_ADDRESSING_IEC => Ok(Addressing::Iec),
        PLC_ADDRESSING_OPENPLC => Ok(Addressing::OpenPlc),
        PLC_ADDRESSING_BYTE => Ok(Addressing::Byte),
        other => Err(Failure::new(
            PLC_E_INVALID_ARGUMENT,
            format!(
                "{other} is not an addressing convention (PLC_ADDRESSING_IEC 0, \
                 PLC_ADDRESSING_OPENPLC 1, PLC_ADDRESSING_BYTE 2)"
            ),
        )),
    }
}

fn to_code(addressing: Addressing) -> c_int {
    match addressing {
        Addressing::Iec => PLC_ADDRESSING_IEC,
        Addressing::OpenPlc => PLC_ADDRESSING_OPENPLC,
        Addressing::Byte => PLC_ADDRESSING_BYTE,
    }
}

/// Lays the process image out again under `addressing`
/// (`PLC_ADDRESSING_*`): located variables keep their values, the image
/// takes them at their new places, and the overlap warnings (W204) of
/// `plc_warnings` are judged again. Call it after `plc_create`, before the
/// first cycle. An unknown code is `PLC_E_INVALID_ARGUMENT`.
#[unsafe(no_mangle)]
pub extern "C" fn plc_set_addressing(plc: PlcHandle, addressing: c_int) -> c_int {
    guard(|| {
        let addressing = from_code(addressing)?;
        handles::with_entry(plc, |e| {
            e.plc.set_addressing(addressing);
            Ok(())
        })
    })
}

/// The addressing convention of the PLC's image (`PLC_ADDRESSING_*`)
/// into `*out`: the one set, or the one chosen from the sources.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_addressing(plc: PlcHandle, out: *mut c_int) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let code = handles::with_entry(plc, |e| Ok(to_code(e.plc.addressing())))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", code) }
    })
}
