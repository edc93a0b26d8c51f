//! Variables by path or by resolved handle: as IEC literals, and as typed
//! scalars (the rules are in `scalar.rs`).

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle, PlcVar, var_ref};
use crate::scalar;
use crate::status::PLC_E_BAD_VALUE;
use crate::text::{input, output, store};
use plcrun::{Plc, Value, VarRef};
use std::ffi::{c_char, c_int};

/// A variable as an entry point names it.
#[derive(Clone, Copy)]
enum Target<'a> {
    Path(&'a str),
    Var(PlcVar),
}

/// The path argument of a by-path entry point.
///
/// # Safety
/// `path` is NULL or NUL-terminated.
unsafe fn path<'a>(path: *const c_char) -> Result<Target<'a>, Failure> {
    // SAFETY: the caller's contract.
    Ok(Target::Path(unsafe { input(path, "path") }?))
}

/// Runs `f` on the variable `target` of `plc`.
fn with_var<T>(
    plc: PlcHandle,
    target: Target,
    f: impl FnOnce(&mut Plc, &VarRef) -> Result<T, Failure>,
) -> Result<T, Failure> {
    handles::with_entry(plc, |e| match target {
        Target::Path(p) => {
            let r = e.plc.resolve(p)?;
            f(&mut e.plc, &r)
        }
        Target::Var(v) => {
            let r = var_ref(&e.vars, e.tag, v)?;
            f(&mut e.plc, r)
        }
    })
}

/// Writes `number`, made a value by `make` from the variable's current
/// value (which gives its type); a number the type cannot hold is out of
/// range.
fn set_typed<N: Copy + std::fmt::Display>(
    plc: PlcHandle,
    target: Target,
    number: N,
    make: impl FnOnce(&str, &Value, N) -> Result<Value, Failure>,
) -> Result<(), Failure> {
    with_var(plc, target, |plc, r| {
        let current = plc.get(r)?;
        let v = make(r.name(), &current, number)?;
        plc.set(r, &v).map_err(|e| match Failure::from(e) {
            f if f.code == PLC_E_BAD_VALUE => scalar::out_of_range(r.name(), &current, number),
            f => f,
        })
    })
}

/// The variable as a literal, into the caller's buffer.
///
/// # Safety
/// `buf` is NULL or holds `cap` bytes; `needed` is NULL or writable.
unsafe fn get_literal(
    plc: PlcHandle,
    t: Target,
    buf: *mut c_char,
    cap: usize,
    needed: *mut usize,
) -> Result<(), Failure> {
    let text = with_var(plc, t, |plc, r| Ok(plc.get(r)?.to_literal()))?;
    // SAFETY: the caller's contract.
    unsafe { output(&text, buf, cap, needed) }
}

/// Writes the variable from a literal of its type.
///
/// # Safety
/// `literal` is NULL or NUL-terminated.
unsafe fn set_literal(plc: PlcHandle, t: Target, literal: *const c_char) -> Result<(), Failure> {
    // SAFETY: the caller's contract.
    let literal = unsafe { input(literal, "literal") }?;
    with_var(plc, t, |plc, r| {
        let v = plc.parse_value(r, literal)?;
        Ok(plc.set(r, &v)?)
    })
}

/// Reads a BOOL into `*out`.
///
/// # Safety
/// `out` is NULL or writable.
unsafe fn get_bool(plc: PlcHandle, t: Target, out: *mut bool) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null("out"));
    }
    let b = with_var(plc, t, |plc, r| scalar::to_bool(r.name(), &plc.get(r)?))?;
    // SAFETY: the caller's contract.
    unsafe { store(out, "out", b) }
}

/// Reads an integer-like variable into `*out`.
///
/// # Safety
/// `out` is NULL or writable.
unsafe fn get_i64(plc: PlcHandle, t: Target, out: *mut i64) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null("out"));
    }
    let n = with_var(plc, t, |plc, r| scalar::to_i64(r.name(), &plc.get(r)?))?;
    // SAFETY: the caller's contract.
    unsafe { store(out, "out", n) }
}

/// Reads a REAL or LREAL into `*out`.
///
/// # Safety
/// `out` is NULL or writable.
unsafe fn get_f64(plc: PlcHandle, t: Target, out: *mut f64) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null("out"));
    }
    let x = with_var(plc, t, |plc, r| scalar::to_f64(r.name(), &plc.get(r)?))?;
    // SAFETY: the caller's contract.
    unsafe { store(out, "out", x) }
}

/// Resolves `path` once for repeated access: `*out` gets a handle valid
/// until the PLC is freed (resolving the same path again gives the same
/// handle; handles need no freeing).
///
/// # Safety
/// `path` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_resolve(
    plc: PlcHandle,
    path: *const c_char,
    out: *mut PlcVar,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        unsafe { store(out, "out", PlcVar { id: 0 }) }?;
        let path = unsafe { input(path, "path") }?;
        let var = handles::with_entry(plc, |e| e.resolve(path))?;
        unsafe { store(out, "out", var) }
    })
}

/// A variable's value as an IEC literal (`TRUE`, `42`, `T#1s500ms`,
/// `'text'`) into the caller's buffer.
///
/// # Safety
/// `path` is NULL or NUL-terminated; `buf` is NULL or holds `capacity`
/// bytes; `needed` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_get_literal(
    plc: PlcHandle,
    path: *const c_char,
    buf: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let t = unsafe { self::path(path) }?;
        unsafe { get_literal(plc, t, buf, capacity, needed) }
    })
}

/// Writes a variable from an IEC literal of its type.
///
/// # Safety
/// `path` and `literal` are NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_set_literal(
    plc: PlcHandle,
    path: *const c_char,
    literal: *const c_char,
) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let t = unsafe { self::path(path) }?;
        unsafe { set_literal(plc, t, literal) }
    })
}

/// Reads a BOOL.
///
/// # Safety
/// `path` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_get_bool(
    plc: PlcHandle,
    path: *const c_char,
    out: *mut bool,
) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let t = unsafe { self::path(path) }?;
        unsafe { get_bool(plc, t, out) }
    })
}

/// Writes a BOOL.
///
/// # Safety
/// `path` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_set_bool(plc: PlcHandle, path: *const c_char, value: bool) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let t = unsafe { self::path(path) }?;
        set_typed(plc, t, value, scalar::from_bool)
    })
}

/// Reads an integer-like variable (see the header for which).
///
/// # Safety
/// `path` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_get_i64(plc: PlcHandle, path: *const c_char, out: *mut i64) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let t = unsafe { self::path(path) }?;
        unsafe { get_i64(plc, t, out) }
    })
}

/// Writes an integer-like variable; a number outside its type's range is
/// `PLC_E_OUT_OF_RANGE`.
///
/// # Safety
/// `path` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_set_i64(plc: PlcHandle, path: *const c_char, value: i64) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let t = unsafe { self::path(path) }?;
        set_typed(plc, t, value, scalar::from_i64)
    })
}

/// Reads a REAL or LREAL.
///
/// # Safety
/// `path` is NULL or NUL-terminated; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_get_f64(plc: PlcHandle, path: *const c_char, out: *mut f64) -> c_int {
    guard(|| {
        // SAFETY (both calls): the caller's contract.
        let t = unsafe { self::path(path) }?;
        unsafe { get_f64(plc, t, out) }
    })
}

/// Writes a REAL or LREAL.
///
/// # Safety
/// `path` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_set_f64(plc: PlcHandle, path: *const c_char, value: f64) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let t = unsafe { self::path(path) }?;
        set_typed(plc, t, value, scalar::from_f64)
    })
}

/// `plc_get_literal` through a resolved handle.
///
/// # Safety
/// `buf` is NULL or holds `capacity` bytes; `needed` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_var_get_literal(
    plc: PlcHandle,
    var: PlcVar,
    buf: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> c_int {
    // SAFETY: the caller's contract.
    guard(|| unsafe { get_literal(plc, Target::Var(var), buf, capacity, needed) })
}

/// `plc_set_literal` through a resolved handle.
///
/// # Safety
/// `literal` is NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_var_set_literal(
    plc: PlcHandle,
    var: PlcVar,
    literal: *const c_char,
) -> c_int {
    // SAFETY: the caller's contract.
    guard(|| unsafe { set_literal(plc, Target::Var(var), literal) })
}

/// `plc_get_bool` through a resolved handle.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_var_get_bool(plc: PlcHandle, var: PlcVar, out: *mut bool) -> c_int {
    // SAFETY: the caller's contract.
    guard(|| unsafe { get_bool(plc, Target::Var(var), out) })
}

/// `plc_set_bool` through a resolved handle.
#[unsafe(no_mangle)]
pub extern "C" fn plc_var_set_bool(plc: PlcHandle, var: PlcVar, value: bool) -> c_int {
    guard(|| set_typed(plc, Target::Var(var), value, scalar::from_bool))
}

/// `plc_get_i64` through a resolved handle.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_var_get_i64(plc: PlcHandle, var: PlcVar, out: *mut i64) -> c_int {
    // SAFETY: the caller's contract.
    guard(|| unsafe { get_i64(plc, Target::Var(var), out) })
}

/// `plc_set_i64` through a resolved handle.
#[unsafe(no_mangle)]
pub extern "C" fn plc_var_set_i64(plc: PlcHandle, var: PlcVar, value: i64) -> c_int {
    guard(|| set_typed(plc, Target::Var(var), value, scalar::from_i64))
}

/// `plc_get_f64` through a resolved handle.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_var_get_f64(plc: PlcHandle, var: PlcVar, out: *mut f64) -> c_int {
    // SAFETY: the caller's contract.
    guard(|| unsafe { get_f64(plc, Target::Var(var), out) })
}

/// `plc_set_f64` through a resolved handle.
#[unsafe(no_mangle)]
pub extern "C" fn plc_var_set_f64(plc: PlcHandle, var: PlcVar, value: f64) -> c_int {
    guard(|| set_typed(plc, Target::Var(var), value, scalar::from_f64))
}
