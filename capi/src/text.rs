//! Text across the boundary: NUL-terminated UTF-8 in, and out into a
//! buffer the caller owns (`buf`, `capacity`, `*needed`), like `snprintf`.

use crate::failure::Failure;
use crate::status::{PLC_E_BUFFER_TOO_SMALL, PLC_E_INVALID_ARGUMENT};
use std::ffi::{CStr, c_char};

/// The text behind a C string argument named `what`.
///
/// # Safety
/// `ptr` is NULL or points to a NUL-terminated string that stays valid
/// for the call.
pub(crate) unsafe fn input<'a>(ptr: *const c_char, what: &str) -> Result<&'a str, Failure> {
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: not NULL, and NUL-terminated by the caller's contract.
    let c = unsafe { CStr::from_ptr(ptr) };
    c.to_str().map_err(|e| {
        Failure::new(
            PLC_E_INVALID_ARGUMENT,
            format!("`{what}` is not UTF-8 (byte {})", e.valid_up_to()),
        )
    })
}

/// Copies `text` and its NUL into `buf` when `capacity` allows; otherwise
/// leaves an empty string in `buf` (if `capacity` > 0: never a cut UTF-8
/// sequence) and fails with `PLC_E_BUFFER_TOO_SMALL`. `*needed` (when not
/// NULL) gets the size that holds it all, NUL included, in both cases.
/// `buf` may be NULL when `capacity` is 0, to ask for the size.
///
/// # Safety
/// `buf` is NULL or points to `capacity` writable bytes; `needed` is NULL
/// or points to a writable `size_t`.
pub(crate) unsafe fn output(
    text: &str,
    buf: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> Result<(), Failure> {
    if capacity > 0 && buf.is_null() {
        return Err(Failure::null("buf"));
    }
    let size = text.len() + 1;
    if !needed.is_null() {
        // SAFETY: writable by the caller's contract.
        unsafe { needed.write(size) };
    }
    if size > capacity {
        if capacity > 0 {
            // SAFETY: `buf` holds at least one byte.
            unsafe { buf.write(0) };
        }
        return Err(Failure::new(
            PLC_E_BUFFER_TOO_SMALL,
            format!("the text needs {size} bytes, the buffer has {capacity}"),
        ));
    }
    // SAFETY: `buf` holds `capacity >= size` bytes.
    unsafe {
        std::ptr::copy_nonoverlapping(text.as_ptr(), buf.cast::<u8>(), text.len());
        buf.add(text.len()).write(0);
    }
    Ok(())
}

/// Stores `value` through an out-parameter named `what`.
///
/// # Safety
/// `out` is NULL or points to a writable `T`.
pub(crate) unsafe fn store<T>(out: *mut T, what: &str, value: T) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: not NULL, writable by the caller's contract.
    unsafe { out.write(value) };
    Ok(())
}
