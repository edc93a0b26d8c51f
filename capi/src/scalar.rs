//! The typed accessors' rules: which variables read and write as a C
//! `bool`, `int64_t` or `double`, and how a number becomes a value of the
//! variable's type (or is refused).
//!
//! - bool: BOOL.
//! - int64_t: the integers (SINT .. ULINT), the bit strings (BYTE ..
//!   LWORD), subranges, TIME and LTIME (nanoseconds), enumerations (the
//!   value's number). Not BOOL, REAL, dates, CHAR, strings.
//! - double: REAL and LREAL; a REAL is widened exactly on reading and
//!   rounded to the nearest REAL on writing.
//!
//! Any other pairing is `PLC_E_WRONG_TYPE`; a number the type cannot hold
//! is `PLC_E_OUT_OF_RANGE`. Every variable reads and writes as a literal.

use crate::failure::Failure;
use crate::status::{PLC_E_OUT_OF_RANGE, PLC_E_WRONG_TYPE};
use plcrun::{ElemType, Value};
use std::borrow::Cow;

/// The name of a value's type, for messages.
fn type_name(v: &Value) -> Cow<'static, str> {
    match v {
        Value::Scalar(t, _) => Cow::Borrowed(t.name()),
        Value::String(_, false) => Cow::Borrowed("STRING"),
        Value::String(_, true) => Cow::Borrowed("WSTRING"),
        Value::Enum(name, _) => Cow::Owned(format!("enumeration (value {name})")),
    }
}

fn wrong(path: &str, v: &Value, wanted: &str) -> Failure {
    Failure::new(
        PLC_E_WRONG_TYPE,
        format!("`{path}` is a {}, not {wanted}", type_name(v)),
    )
}

pub(crate) fn out_of_range(path: &str, v: &Value, number: impl std::fmt::Display) -> Failure {
    Failure::new(
        PLC_E_OUT_OF_RANGE,
        format!("{number} does not fit `{path}` ({})", type_name(v)),
    )
}

/// Whether a value's type reads and writes as `int64_t`.
fn is_integer(v: &Value) -> bool {
    match v {
        Value::Scalar(t, _) => {
            t.is_int()
                || matches!(
                    t,
                    ElemType::Byte
                        | ElemType::Word
                        | ElemType::Dword
                        | ElemType::Lword
                        | ElemType::Time
                        | ElemType::Ltime
                )
        }
        Value::Enum(..) => true,
        Value::String(..) => false,
    }
}

/// A BOOL's value.
pub(crate) fn to_bool(path: &str, v: &Value) -> Result<bool, Failure> {
    match v {
        Value::Scalar(ElemType::Bool, raw) => Ok(*raw != 0),
        _ => Err(wrong(path, v, "a BOOL")),
    }
}

/// The value of the type of `current` (the variable's value now) for a
/// BOOL.
pub(crate) fn from_bool(path: &str, current: &Value, b: bool) -> Result<Value, Failure> {
    to_bool(path, current)?;
    Ok(Value::Scalar(ElemType::Bool, u64::from(b)))
}

/// An integer-like value as a number.
pub(crate) fn to_i64(path: &str, v: &Value) -> Result<i64, Failure> {
    if !is_integer(v) {
        return Err(wrong(path, v, "an integer"));
    }
    match v {
        // ULINT and LWORD above i64::MAX.
        Value::Scalar(_, raw) if v.as_i64().is_none() => Err(Failure::new(
            PLC_E_OUT_OF_RANGE,
            format!("`{path}` holds {raw}, more than int64_t holds: read it as a literal"),
        )),
        _ => v.as_i64().ok_or_else(|| wrong(path, v, "an integer")),
    }
}

/// The value of the type of `current` for the number `n`; whether it is
/// in the type's range is checked by the library's `Plc::set`.
pub(crate) fn from_i64(path: &str, current: &Value, n: i64) -> Result<Value, Failure> {
    if !is_integer(current) {
        return Err(wrong(path, current, "an integer"));
    }
    match current {
        Value::Scalar(t, _)
            if t.is_signed_int() || matches!(t, ElemType::Time | ElemType::Ltime) =>
        {
            Ok(Value::Scalar(*t, n as u64))
        }
        Value::Scalar(t, _) => match u64::try_from(n) {
            Ok(raw) => Ok(Value::Scalar(*t, raw)),
            Err(_) => Err(out_of_range(path, current, n)),
        },
        // The library checks the number is one of the enumeration's.
        _ => Ok(Value::Enum(String::new(), n)),
    }
}

/// A REAL or LREAL as a double.
pub(crate) fn to_f64(path: &str, v: &Value) -> Result<f64, Failure> {
    match v {
        Value::Scalar(ElemType::Real | ElemType::Lreal, _) => {
            v.as_f64().ok_or_else(|| wrong(path, v, "a REAL or LREAL"))
        }
        _ => Err(wrong(path, v, "a REAL or LREAL")),
    }
}

/// The value of the type of `current` (REAL or LREAL) for `x`.
pub(crate) fn from_f64(path: &str, current: &Value, x: f64) -> Result<Value, Failure> {
    match current {
        Value::Scalar(ElemType::Lreal, _) => Ok(Value::Scalar(ElemType::Lreal, x.to_bits())),
        Value::Scalar(ElemType::Real, _) => {
            let f = x as f32;
            if x.is_finite() && !f.is_finite() {
                return Err(out_of_range(path, current, x));
            }
            Ok(Value::Scalar(ElemType::Real, u64::from(f.to_bits())))
        }
        _ => Err(wrong(path, current, "a REAL or LREAL")),
    }
}
