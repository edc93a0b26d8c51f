//! The process image's tables from C, by area and size: under the
//! `openplc` addressing convention each size of each area is a table of
//! its own (`%QX`, `%QW`, `%MD`...), which the area functions of
//! `image.rs` (the byte tables) do not reach. Under `iec` and `byte` every
//! size of an area is the same table, the area itself.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::image::{area, copy_in, copy_out, outputs_are_read_only};
use crate::status::PLC_E_INVALID_ARGUMENT;
use crate::text::store;
use plcrun::{Area, Width};
use std::ffi::c_int;

/// `PLC_WIDTH_BIT` in the header: the `X` addresses (`%QX`).
pub const PLC_WIDTH_BIT: c_int = 0;
/// `PLC_WIDTH_BYTE`: `B`.
pub const PLC_WIDTH_BYTE: c_int = 1;
/// `PLC_WIDTH_WORD`: `W`.
pub const PLC_WIDTH_WORD: c_int = 2;
/// `PLC_WIDTH_DWORD`: `D`.
pub const PLC_WIDTH_DWORD: c_int = 3;
/// `PLC_WIDTH_LWORD`: `L`.
pub const PLC_WIDTH_LWORD: c_int = 4;

fn width(code: c_int) -> Result<Width, Failure> {
    match code {
        PLC_WIDTH_BIT => Ok(Width::Bit),
        PLC_WIDTH_BYTE => Ok(Width::Byte),
        PLC_WIDTH_WORD => Ok(Width::Word),
        PLC_WIDTH_DWORD => Ok(Width::Dword),
        PLC_WIDTH_LWORD => Ok(Width::Lword),
        other => Err(Failure::new(
            PLC_E_INVALID_ARGUMENT,
            format!(
                "{other} is not an address size (PLC_WIDTH_BIT 0, PLC_WIDTH_BYTE 1, \
                 PLC_WIDTH_WORD 2, PLC_WIDTH_DWORD 3, PLC_WIDTH_LWORD 4)"
            ),
        )),
    }
}

/// How the errors name a table: "the table of %QW addresses".
fn table_name(area: Area, w: Width) -> String {
    format!("the table of %{}{} addresses", area.letter(), w.letter())
}

/// The size in bytes of the table holding `width`-sized (`PLC_WIDTH_*`)
/// addresses of `area` (`PLC_AREA_*`): the whole area under `iec` and
/// `byte` addressing, that size's own table under `openplc`; as long as
/// the highest address the program uses there.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_table_size(
    plc: PlcHandle,
    area: c_int,
    width: c_int,
    out: *mut usize,
) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let (a, w) = (self::area(area)?, self::width(width)?);
        let size = handles::with_entry(plc, |e| Ok(e.plc.process_image().table(a, w).len()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", size) }
    })
}

/// Copies `length` bytes of the table of `width`-sized addresses of `area`
/// from byte `offset` on into `buf` (`buf` may be NULL when `length` is 0).
///
/// # Safety
/// `buf` is NULL or holds `length` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_table(
    plc: PlcHandle,
    area: c_int,
    width: c_int,
    offset: usize,
    buf: *mut u8,
    length: usize,
) -> c_int {
    guard(|| {
        if buf.is_null() && length > 0 {
            return Err(Failure::null("buf"));
        }
        let (a, w) = (self::area(area)?, self::width(width)?);
        handles::with_entry(plc, |e| {
            let bytes = e.plc.process_image().table(a, w);
            // SAFETY: `buf` holds `length` bytes by the caller's contract.
            unsafe { copy_out(bytes, offset, length, buf, &|| table_name(a, w)) }
        })
    })
}

/// Copies `length` bytes from `data` into the table of `width`-sized
/// addresses of `area` (`%I` or `%M`) from byte `offset` on; the program
/// sees them from the start of the next cycle (`data` may be NULL when
/// `length` is 0).
///
/// # Safety
/// `data` is NULL or holds `length` readable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_table(
    plc: PlcHandle,
    area: c_int,
    width: c_int,
    offset: usize,
    data: *const u8,
    length: usize,
) -> c_int {
    guard(|| {
        if data.is_null() && length > 0 {
            return Err(Failure::null("data"));
        }
        let (a, w) = (self::area(area)?, self::width(width)?);
        handles::with_entry(plc, |e| {
            let Some(bytes) = e.plc.process_image_mut().table_mut(a, w) else {
                return Err(outputs_are_read_only());
            };
            // SAFETY: `data` holds `length` bytes by the caller's contract.
            unsafe { copy_in(bytes, offset, length, data, &|| table_name(a, w)) }
        })
    })
}
