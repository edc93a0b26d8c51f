//! Creating a PLC from source texts, freeing it, and what it was built
//! with: its warnings, the library's version.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, Entry, PlcHandle};
use crate::status::PLC_E_INVALID_ARGUMENT;
use crate::text::{input, output, store};
use plcrun::{Options, Plc};
use std::ffi::{c_char, c_int};
use std::time::Duration;

/// The version of this interface (`PLC_ABI_VERSION` in the header); it
/// changes when an existing declaration changes, not when one is added.
pub const PLC_ABI_VERSION: c_int = 1;

/// One source file: its name (used in diagnostics and fault locations;
/// its extension chooses the language: `.st`, `.il`, `.sfc`) and its text.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct PlcSource {
    /// The file name, NUL-terminated UTF-8.
    pub name: *const c_char,
    /// The source text, NUL-terminated UTF-8.
    pub text: *const c_char,
}

/// How to build and run the program (`plc_options`).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct PlcOptions {
    /// Cycle time of the implicit task in nanoseconds; must be > 0.
    pub cycle_time_ns: i64,
    /// The PROGRAM to run when the sources hold several; NULL for none.
    pub program: *const c_char,
    /// Wall-clock limit of one cycle in nanoseconds; <= 0 disables it.
    pub watchdog_ns: i64,
}

/// Fills `options` with the defaults: 10 ms cycles, no program chosen,
/// a 1 s watchdog. Returns `PLC_E_NULL_ARGUMENT` for NULL.
///
/// # Safety
/// `options` is NULL or points to a writable `plc_options`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_options_init(options: *mut PlcOptions) -> c_int {
    guard(|| {
        let d = Options::default();
        let defaults = PlcOptions {
            cycle_time_ns: d.cycle_time,
            program: std::ptr::null(),
            watchdog_ns: d.watchdog.map_or(0, |w| w.as_nanos() as i64),
        };
        // SAFETY: the caller's contract.
        unsafe { store(options, "options", defaults) }
    })
}

/// The library's options from the C ones.
///
/// # Safety
/// `options` is NULL or points to a valid `plc_options`.
unsafe fn options_from(options: *const PlcOptions) -> Result<Options, Failure> {
    let mut o = Options::default();
    if options.is_null() {
        return Ok(o);
    }
    // SAFETY: not NULL, valid by the caller's contract.
    let c = unsafe { *options };
    if c.cycle_time_ns <= 0 {
        return Err(Failure::new(
            PLC_E_INVALID_ARGUMENT,
            format!("cycle_time_ns must be positive, not {}", c.cycle_time_ns),
        ));
    }
    o.cycle_time = c.cycle_time_ns;
    o.watchdog = (c.watchdog_ns > 0).then(|| Duration::from_nanos(c.watchdog_ns as u64));
    if !c.program.is_null() {
        // SAFETY: not NULL, NUL-terminated by the caller's contract.
        o.program = Some(unsafe { input(c.program, "options->program") }?.to_string());
    }
    Ok(o)
}

/// Compiles `count` source files into a new PLC and stores its handle in
/// `*out` (`{0}` on failure). `options` may be NULL for the defaults.
/// When the sources do not compile, returns `PLC_E_COMPILE` and
/// `plc_last_error()` holds every diagnostic with its file, line and
/// column. The texts are copied: the caller may free them afterwards.
///
/// # Safety
/// `sources` points to `count` valid `plc_source` values; `options` is
/// NULL or valid; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_create(
    sources: *const PlcSource,
    count: usize,
    options: *const PlcOptions,
    out: *mut PlcHandle,
) -> c_int {
    guard(|| {
        // SAFETY (whole body): the caller's contract above.
        unsafe { store(out, "out", PlcHandle { id: 0 }) }?;
        if sources.is_null() {
            return Err(Failure::null("sources"));
        }
        if count == 0 {
            return Err(Failure::new(PLC_E_INVALID_ARGUMENT, "no source file given"));
        }
        let list = unsafe { std::slice::from_raw_parts(sources, count) };
        let mut files = Vec::with_capacity(count);
        for (i, s) in list.iter().enumerate() {
            let name = unsafe { input(s.name, &format!("sources[{i}].name")) }?;
            let text = unsafe { input(s.text, &format!("sources[{i}].text")) }?;
            files.push((name, text));
        }
        let options = unsafe { options_from(options) }?;
        let plc = Plc::compile_files(&files, &options)?;
        let handle = handles::insert(Entry::new(plc));
        unsafe { store(out, "out", handle) }
    })
}

/// Frees a PLC. Its handle and its variable handles become invalid (a
/// later use, or a second free, gives `PLC_E_INVALID_HANDLE`). A call
/// still running on it in another thread finishes first.
#[unsafe(no_mangle)]
pub extern "C" fn plc_free(plc: PlcHandle) -> c_int {
    guard(|| handles::remove(plc))
}

/// The warnings of the compilation, rendered like diagnostics ("" when
/// there are none), into the caller's buffer (see the header's "Text
/// out" rules).
///
/// # Safety
/// `buf` is NULL or holds `capacity` bytes; `needed` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_warnings(
    plc: PlcHandle,
    buf: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> c_int {
    guard(|| {
        let text = handles::with_entry(plc, |e| Ok(e.plc.warnings().render(e.plc.sources())))?;
        // SAFETY: the caller's contract.
        unsafe { output(&text, buf, capacity, needed) }
    })
}

/// The library's version, e.g. "0.1.0": static, NUL-terminated.
#[unsafe(no_mangle)]
pub extern "C" fn plc_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The interface version the library implements; compare it with the
/// header's `PLC_ABI_VERSION` to detect a header from another version.
#[unsafe(no_mangle)]
pub extern "C" fn plc_abi_version() -> c_int {
    PLC_ABI_VERSION
}
