//! The process image from C: `%I`, `%Q`, `%M` bits, bytes and words by
//! address text (`%IX0.3`, `%QW4`, `%I0.0.0.0.1`), and whole areas copied
//! to and from a byte buffer. The host writes `%I` and `%M` (the program
//! sees them from the start of the next cycle) and reads all three; `%Q`
//! is the program's (`PLC_E_READ_ONLY`).

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::status::{PLC_E_ADDRESS_OUT_OF_RANGE, PLC_E_INVALID_ARGUMENT, PLC_E_READ_ONLY};
use crate::text::{input, store};
use plcrun::{AddressError, Area, ProcessImage};
use std::ffi::{c_char, c_int};

/// `PLC_AREA_INPUT` in the header: `%I`.
pub const PLC_AREA_INPUT: c_int = 0;
/// `PLC_AREA_OUTPUT`: `%Q`.
pub const PLC_AREA_OUTPUT: c_int = 1;
/// `PLC_AREA_MEMORY`: `%M`.
pub const PLC_AREA_MEMORY: c_int = 2;

pub(crate) fn area(code: c_int) -> Result<Area, Failure> {
    match code {
        PLC_AREA_INPUT => Ok(Area::Input),
        PLC_AREA_OUTPUT => Ok(Area::Output),
        PLC_AREA_MEMORY => Ok(Area::Memory),
        other => Err(Failure::new(
            PLC_E_INVALID_ARGUMENT,
            format!(
                "{other} is not an image area (PLC_AREA_INPUT 0, PLC_AREA_OUTPUT 1, \
                 PLC_AREA_MEMORY 2)"
            ),
        )),
    }
}

/// Reads the value at `address` with `get` into `*out`.
///
/// # Safety
/// `address` is NULL or NUL-terminated; `out` is NULL or writable.
unsafe fn read<T>(
    plc: PlcHandle,
    address: *const c_char,
    out: *mut T,
    get: impl FnOnce(&ProcessImage, &str) -> Result<T, AddressError>,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let address = unsafe { input(address, "address") }?;
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let value = handles::with_entry(plc, |e| Ok(get(e.plc.process_image(), address)?))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", value) }
    })
}

/// Writes at `address` with `put`.
///
/// # Safety
/// `address` is NULL or NUL-terminated.
unsafe fn write(
    plc: PlcHandle,
    address: *const c_char,
    put: impl FnOnce(&mut ProcessImage, &str) -> Result<(), AddressError>,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let address = unsafe { input(address, "address") }?;
        handles::with_entry(plc, |e| Ok(put(e.plc.process_image_mut(), address)?))
    })
}

/// Reads a bit (`%IX0.3`, `%QX1.0`, `%Q0.0.0.1.7`).
///
/// # Safety
/// `address` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_bit(
    plc: PlcHandle,
    address: *const c_char,
    out: *mut bool,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { read(plc, address, out, ProcessImage::read_bit) }
}

/// Reads a byte (`%QB2`).
///
/// # Safety
/// `address` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_byte(
    plc: PlcHandle,
    address: *const c_char,
    out: *mut u8,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { read(plc, address, out, ProcessImage::read_byte) }
}

/// Reads a word (`%QW4`: bytes 4 and 5, little-endian).
///
/// # Safety
/// `address` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_word(
    plc: PlcHandle,
    address: *const c_char,
    out: *mut u16,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { read(plc, address, out, ProcessImage::read_word) }
}

/// Reads a double word (`%QD8`).
///
/// # Safety
/// `address` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_dword(
    plc: PlcHandle,
    address: *const c_char,
    out: *mut u32,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { read(plc, address, out, ProcessImage::read_dword) }
}

/// Reads a long word (`%QL8`).
///
/// # Safety
/// `address` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_lword(
    plc: PlcHandle,
    address: *const c_char,
    out: *mut u64,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { read(plc, address, out, ProcessImage::read_lword) }
}

/// Writes a bit of `%I` or `%M`.
///
/// # Safety
/// `address` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_bit(
    plc: PlcHandle,
    address: *const c_char,
    value: bool,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { write(plc, address, |i, a| i.write_bit(a, value)) }
}

/// Writes a byte of `%I` or `%M`.
///
/// # Safety
/// `address` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_byte(
    plc: PlcHandle,
    address: *const c_char,
    value: u8,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { write(plc, address, |i, a| i.write_byte(a, value)) }
}

/// Writes a word of `%I` or `%M` (little-endian).
///
/// # Safety
/// `address` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_word(
    plc: PlcHandle,
    address: *const c_char,
    value: u16,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { write(plc, address, |i, a| i.write_word(a, value)) }
}

/// Writes a double word of `%I` or `%M`.
///
/// # Safety
/// `address` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_dword(
    plc: PlcHandle,
    address: *const c_char,
    value: u32,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { write(plc, address, |i, a| i.write_dword(a, value)) }
}

/// Writes a long word of `%I` or `%M`.
///
/// # Safety
/// `address` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_lword(
    plc: PlcHandle,
    address: *const c_char,
    value: u64,
) -> c_int {
    // SAFETY: the caller's contract.
    unsafe { write(plc, address, |i, a| i.write_lword(a, value)) }
}

/// The size in bytes of an area (`PLC_AREA_*`): as long as the highest
/// address the program uses there, 0 when it uses none.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_area_size(
    plc: PlcHandle,
    area: c_int,
    out: *mut usize,
) -> c_int {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let area = self::area(area)?;
        let size = handles::with_entry(plc, |e| Ok(e.plc.process_image().area(area).len()))?;
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", size) }
    })
}

/// The bytes `offset .. offset + length` of `area`, checked against its
/// size (`PLC_E_ADDRESS_OUT_OF_RANGE` past its end).
fn span(
    bytes: usize,
    offset: usize,
    length: usize,
    table: &dyn Fn() -> String,
) -> Result<(), Failure> {
    match offset.checked_add(length) {
        Some(end) if end <= bytes => Ok(()),
        _ => Err(Failure::new(
            PLC_E_ADDRESS_OUT_OF_RANGE,
            format!(
                "bytes {offset} .. {offset}+{length} are outside {} ({bytes} bytes)",
                table()
            ),
        )),
    }
}

/// Copies `length` bytes of `bytes` from `offset` on into `buf`, once the
/// range is checked; `table` names the bytes in the error ("the %Q area").
///
/// # Safety
/// `buf` holds `length` writable bytes (it may be NULL when `length` is 0).
pub(crate) unsafe fn copy_out(
    bytes: &[u8],
    offset: usize,
    length: usize,
    buf: *mut u8,
    table: &dyn Fn() -> String,
) -> Result<(), Failure> {
    span(bytes.len(), offset, length, table)?;
    if length > 0 {
        // SAFETY: in bounds (checked above); `buf` holds `length` bytes by
        // the caller's contract.
        unsafe { std::ptr::copy_nonoverlapping(bytes[offset..].as_ptr(), buf, length) };
    }
    Ok(())
}

/// Copies `length` bytes from `data` into `bytes` from `offset` on, once
/// the range is checked (see [`copy_out`]).
///
/// # Safety
/// `data` holds `length` readable bytes outside `bytes` (it may be NULL
/// when `length` is 0).
pub(crate) unsafe fn copy_in(
    bytes: &mut [u8],
    offset: usize,
    length: usize,
    data: *const u8,
    table: &dyn Fn() -> String,
) -> Result<(), Failure> {
    span(bytes.len(), offset, length, table)?;
    if length > 0 {
        // SAFETY: in bounds (checked above); `data` holds `length` bytes by
        // the caller's contract and is not the image.
        unsafe { std::ptr::copy_nonoverlapping(data, bytes[offset..].as_mut_ptr(), length) };
    }
    Ok(())
}

/// The refusal of a host write into `%Q`.
pub(crate) fn outputs_are_read_only() -> Failure {
    Failure::new(
        PLC_E_READ_ONLY,
        "the host may write %I and %M only; %Q is written by the program",
    )
}

/// Copies `length` bytes of `area` from byte `offset` on into `buf`.
/// `buf` may be NULL when `length` is 0.
///
/// # Safety
/// `buf` is NULL or holds `length` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_read_area(
    plc: PlcHandle,
    area: c_int,
    offset: usize,
    buf: *mut u8,
    length: usize,
) -> c_int {
    guard(|| {
        if buf.is_null() && length > 0 {
            return Err(Failure::null("buf"));
        }
        let area = self::area(area)?;
        handles::with_entry(plc, |e| {
            let bytes = e.plc.process_image().area(area);
            let table = || format!("the %{} area", area.letter());
            // SAFETY: `buf` holds `length` bytes by the caller's contract.
            unsafe { copy_out(bytes, offset, length, buf, &table) }
        })
    })
}

/// Copies `length` bytes from `data` into `area` (`%I` or `%M`) from byte
/// `offset` on; the program sees them from the start of the next cycle.
/// `data` may be NULL when `length` is 0.
///
/// # Safety
/// `data` is NULL or holds `length` readable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_image_write_area(
    plc: PlcHandle,
    area: c_int,
    offset: usize,
    data: *const u8,
    length: usize,
) -> c_int {
    guard(|| {
        if data.is_null() && length > 0 {
            return Err(Failure::null("data"));
        }
        let area = self::area(area)?;
        handles::with_entry(plc, |e| {
            let image = e.plc.process_image_mut();
            let bytes = match area {
                Area::Input => image.inputs_mut(),
                Area::Memory => image.memory_mut(),
                _ => return Err(outputs_are_read_only()),
            };
            let table = || format!("the %{} area", area.letter());
            // SAFETY: `data` holds `length` bytes by the caller's contract.
            unsafe { copy_in(bytes, offset, length, data, &table) }
        })
    })
}
