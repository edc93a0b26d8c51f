//! The boundary every entry point goes through: no panic crosses it (it
//! becomes `PLC_E_PANIC`), and the message of the last failure is kept per
//! thread for `plc_last_error`.

use crate::failure::Failure;
use crate::status::{PLC_E_PANIC, PLC_OK};
use std::any::Any;
use std::cell::RefCell;
use std::ffi::{CString, c_char, c_int};
use std::panic::{AssertUnwindSafe, catch_unwind};

thread_local! {
    /// The message of the last call on this thread ("" after a success).
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Runs the body of an entry point: `Ok` is `PLC_OK`, an error its code,
/// a panic `PLC_E_PANIC`; the thread's last error is set accordingly.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> c_int {
    // The body only touches the handle table (whose lock is never held
    // across a panic) and one PLC, which a panic marks as unusable
    // (its mutex is poisoned): nothing half-updated is seen again.
    let outcome = catch_unwind(AssertUnwindSafe(body));
    let (code, message) = match outcome {
        Ok(Ok(())) => (PLC_OK, String::new()),
        Ok(Err(f)) => (f.code, f.message),
        Err(payload) => (
            PLC_E_PANIC,
            format!("internal error in plcrun: {}", panic_text(&*payload)),
        ),
    };
    set_last_error(message);
    code
}

fn panic_text(payload: &(dyn Any + Send)) -> &str {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s
    } else {
        "panic"
    }
}

fn set_last_error(message: String) {
    // A message cannot carry a NUL into C; none of ours should.
    let bytes: Vec<u8> = message
        .into_bytes()
        .into_iter()
        .filter(|b| *b != 0)
        .collect();
    let text = CString::new(bytes).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

/// The message of the last `plc_*` call made on this thread: the
/// diagnostics after `PLC_E_COMPILE`, the fault with its location after
/// `PLC_E_RUNTIME_FAULT`, what is wrong after any other error, "" after a
/// success. NUL-terminated UTF-8, owned by the library, valid until the
/// next `plc_*` call on this thread. Never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn plc_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    /// An entry point whose body panics, as a bug would: the only way to
    /// reach the panic path, so it exists for this test only.
    extern "C" fn plc_test_panic() -> c_int {
        guard(|| panic!("deliberate panic for the test"))
    }

    #[test]
    fn a_panic_becomes_an_error_code_with_its_message() {
        assert_eq!(plc_test_panic(), PLC_E_PANIC);
        let text = unsafe { CStr::from_ptr(plc_last_error()) }
            .to_str()
            .unwrap();
        assert_eq!(
            text,
            "internal error in plcrun: deliberate panic for the test"
        );
        // The next successful call clears it.
        assert_eq!(guard(|| Ok(())), PLC_OK);
        assert_eq!(unsafe { CStr::from_ptr(plc_last_error()) }.to_bytes(), b"");
    }
}
