//! PLC values as Python values and back.
//!
//! Reading: BOOL → `bool`; integers and bit strings → `int`; REAL, LREAL →
//! `float`; TIME, LTIME → `datetime.timedelta`; DATE → `datetime.date`;
//! TIME_OF_DAY → `datetime.time`; DATE_AND_TIME → `datetime.datetime`;
//! STRING, WSTRING, CHAR, enumerations → `str`.
//!
//! Writing goes through the library's own literal decoding
//! ([`plcrun::Plc::parse_value`]): the Python value is written as the IEC
//! literal it stands for, so range checks, subranges and enumeration names
//! are the library's. A `str` given to a variable that is not a string is
//! taken as an IEC literal (`"T#1s"`, `"16#FF"`, `"Color#Red"`).

use crate::errors::variable_message;
use plcrun::{ElemType, ElemType as E, Value};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyFloat, PyInt, PyString};

const NANOS_PER_MICRO: i64 = 1_000;

/// The `datetime` module, imported once.
fn datetime(py: Python<'_>) -> PyResult<&Bound<'_, PyModule>> {
    static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
    MODULE
        .get_or_try_init(py, || Ok(py.import("datetime")?.unbind()))
        .map(|m| m.bind(py))
}

/// A duration in nanoseconds as a `datetime.timedelta` (whose resolution is
/// a microsecond: finer parts are truncated towards negative infinity).
pub fn timedelta(py: Python<'_>, nanos: i64) -> PyResult<Py<PyAny>> {
    let micros = nanos.div_euclid(NANOS_PER_MICRO);
    let td = datetime(py)?.getattr("timedelta")?;
    Ok(td.call1((0, 0, micros))?.unbind())
}

/// A `datetime.timedelta` as nanoseconds.
pub fn timedelta_nanos(obj: &Bound<'_, PyAny>) -> PyResult<i64> {
    let days: i64 = obj.getattr("days")?.extract()?;
    let seconds: i64 = obj.getattr("seconds")?.extract()?;
    let micros: i64 = obj.getattr("microseconds")?.extract()?;
    days.checked_mul(86_400_000_000_000)
        .and_then(|d| d.checked_add(seconds * 1_000_000_000 + micros * NANOS_PER_MICRO))
        .ok_or_else(|| pyo3::exceptions::PyOverflowError::new_err("duration out of range"))
}

/// `value` as a Python object.
pub fn to_py(py: Python<'_>, value: &Value) -> PyResult<Py<PyAny>> {
    let t = match value {
        Value::String(s, _) => return Ok(PyString::new(py, s).into_any().unbind()),
        Value::Enum(name, _) => return Ok(PyString::new(py, name).into_any().unbind()),
        Value::Scalar(t, _) => *t,
    };
    match t {
        E::Bool => Ok(PyBool::new(py, value.as_bool().unwrap_or(false))
            .to_owned()
            .into_any()
            .unbind()),
        E::Real => {
            // The float whose shortest decimal is the REAL's (0.1, not
            // 0.10000000149011612), as the trace prints it.
            let single = value.as_f64().unwrap_or(f64::NAN) as f32;
            let v = format!("{single}")
                .parse::<f64>()
                .unwrap_or(f64::from(single));
            Ok(PyFloat::new(py, v).into_any().unbind())
        }
        E::Lreal => Ok(PyFloat::new(py, value.as_f64().unwrap_or(f64::NAN))
            .into_any()
            .unbind()),
        E::Time | E::Ltime => timedelta(py, value.as_i64().unwrap_or(0)),
        E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt => {
            date_value(py, t, &value.to_literal())
        }
        E::Char | E::Wchar => {
            let lit = value.to_literal();
            let inner = lit.get(1..lit.len().saturating_sub(1)).unwrap_or("");
            Ok(PyString::new(py, inner).into_any().unbind())
        }
        _ => match (value.as_i64(), value) {
            (Some(v), _) => Ok(PyInt::new(py, v).into_any().unbind()),
            // ULINT and LWORD above i64::MAX.
            (None, Value::Scalar(_, raw)) => Ok(PyInt::new(py, *raw).into_any().unbind()),
            (None, _) => Ok(py.None()),
        },
    }
}

/// A date, time of day or date-and-time from its IEC literal text
/// (`D#2024-01-31`, `TOD#12:00:00.5`, `DT#2024-01-31-12:00:00`).
fn date_value(py: Python<'_>, t: ElemType, literal: &str) -> PyResult<Py<PyAny>> {
    let body = literal.split_once('#').map_or(literal, |(_, b)| b);
    let m = datetime(py)?;
    let bad = || PyTypeError::new_err(format!("unexpected date literal `{literal}`"));
    let date = |text: &str| -> PyResult<(i64, i64, i64)> {
        let mut f = text.splitn(3, '-').map(|p| p.parse::<i64>());
        match (f.next(), f.next(), f.next()) {
            (Some(Ok(y)), Some(Ok(mo)), Some(Ok(d))) => Ok((y, mo, d)),
            _ => Err(bad()),
        }
    };
    let tod = |text: &str| -> PyResult<(i64, i64, i64, i64)> {
        let (hms, frac) = text.split_once('.').unwrap_or((text, ""));
        let mut f = hms.split(':').map(|p| p.parse::<i64>());
        let (h, mi, s) = match (f.next(), f.next(), f.next()) {
            (Some(Ok(h)), Some(Ok(mi)), s) => (h, mi, s.and_then(Result::ok).unwrap_or(0)),
            _ => return Err(bad()),
        };
        let digits: String = frac.chars().chain("000000".chars()).take(6).collect();
        Ok((h, mi, s, digits.parse().map_err(|_| bad())?))
    };
    let obj = match t {
        E::Date | E::Ldate => {
            let (y, mo, d) = date(body)?;
            m.getattr("date")?.call1((y, mo, d))?
        }
        E::Tod | E::Ltod => {
            let (h, mi, s, us) = tod(body)?;
            m.getattr("time")?.call1((h, mi, s, us))?
        }
        _ => {
            let split = body
                .match_indices('-')
                .nth(2)
                .map(|(i, _)| i)
                .ok_or_else(bad)?;
            let (y, mo, d) = date(&body[..split])?;
            let (h, mi, s, us) = tod(&body[split + 1..])?;
            m.getattr("datetime")?.call1((y, mo, d, h, mi, s, us))?
        }
    };
    Ok(obj.unbind())
}

/// The IEC literal that writes `obj` into a variable whose current value is
/// `current` (which gives its type); `path` names it in errors.
pub fn literal_for(
    py: Python<'_>,
    path: &str,
    current: &Value,
    obj: &Bound<'_, PyAny>,
) -> PyResult<String> {
    let wrong = |what: &str| {
        PyTypeError::new_err(format!(
            "`{path}` takes {what}, not {}",
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    };
    let t = match current {
        Value::String(_, wide) => {
            let s: String = obj.extract().map_err(|_| wrong("a str"))?;
            return Ok(quoted(&s, *wide));
        }
        Value::Enum(..) => {
            return obj
                .extract::<String>()
                .map_err(|_| wrong("a str (a value name)"));
        }
        Value::Scalar(t, _) => *t,
    };
    if matches!(t, ElemType::Char | ElemType::Wchar) {
        let s: String = obj.extract().map_err(|_| wrong("a str of one character"))?;
        if s.chars().count() != 1 {
            return Err(wrong("a str of one character"));
        }
        return Ok(quoted(&s, t == ElemType::Wchar));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        // Any IEC literal for any type (`T#1s`, `16#FF`, `TRUE`).
        return Ok(s.to_cow()?.into_owned());
    }
    match t {
        E::Bool => obj
            .extract::<bool>()
            .map(|b| if b { "TRUE" } else { "FALSE" }.to_string())
            .map_err(|_| wrong("a bool")),
        E::Real | E::Lreal => {
            if obj.is_instance_of::<PyBool>() {
                return Err(wrong("a float"));
            }
            let v: f64 = obj.extract().map_err(|_| wrong("a float"))?;
            if !v.is_finite() {
                return Err(variable_message(
                    py,
                    path,
                    format!("`{path}` cannot take the non-finite value {v}"),
                ));
            }
            Ok(format!("{v:?}"))
        }
        E::Time | E::Ltime => {
            let ns = timedelta_nanos(obj).map_err(|_| wrong("a datetime.timedelta"))?;
            Ok(format!("{}#{ns}ns", if t == E::Time { "T" } else { "LT" }))
        }
        E::Date => date_literal(obj, "D#").map_err(|_| wrong("a datetime.date")),
        E::Ldate => date_literal(obj, "LDATE#").map_err(|_| wrong("a datetime.date")),
        E::Tod => tod_literal(obj, "TOD#").map_err(|_| wrong("a datetime.time")),
        E::Ltod => tod_literal(obj, "LTOD#").map_err(|_| wrong("a datetime.time")),
        E::Dt | E::Ldt => {
            let prefix = if t == E::Dt { "DT#" } else { "LDT#" };
            let d = date_literal(obj, prefix).map_err(|_| wrong("a datetime.datetime"))?;
            let tod = tod_literal(obj, "").map_err(|_| wrong("a datetime.datetime"))?;
            Ok(format!("{d}-{tod}"))
        }
        _ => {
            // Integers and bit strings; not bool, not float (no silent
            // truncation). Range checks are the library's.
            if obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyFloat>() {
                return Err(wrong("an int"));
            }
            let v: i128 = obj.extract().map_err(|_| wrong("an int"))?;
            Ok(v.to_string())
        }
    }
}

/// `s` as a STRING (`'...'`) or WSTRING (`"..."`) literal.
fn quoted(s: &str, wide: bool) -> String {
    let q = if wide { '"' } else { '\'' };
    let mut out = String::with_capacity(s.len() + 2);
    out.push(q);
    for c in s.chars() {
        match c {
            '$' => out.push_str("$$"),
            '\n' => out.push_str("$N"),
            '\r' => out.push_str("$R"),
            '\t' => out.push_str("$T"),
            '\x0c' => out.push_str("$P"),
            c if c == q => {
                out.push('$');
                out.push(c);
            }
            c if (c as u32) < 0x20 && !wide => out.push_str(&format!("${:02X}", c as u32)),
            c if (c as u32) < 0x20 => out.push_str(&format!("${:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push(q);
    out
}

/// `prefix` and the date of a `datetime.date` or `datetime.datetime`.
fn date_literal(obj: &Bound<'_, PyAny>, prefix: &str) -> PyResult<String> {
    let y: i64 = obj.getattr("year")?.extract()?;
    let m: i64 = obj.getattr("month")?.extract()?;
    let d: i64 = obj.getattr("day")?.extract()?;
    Ok(format!("{prefix}{y:04}-{m:02}-{d:02}"))
}

/// `prefix` and the time of day of a `datetime.time` or `datetime.datetime`.
fn tod_literal(obj: &Bound<'_, PyAny>, prefix: &str) -> PyResult<String> {
    let h: i64 = obj.getattr("hour")?.extract()?;
    let m: i64 = obj.getattr("minute")?.extract()?;
    let s: i64 = obj.getattr("second")?.extract()?;
    let us: i64 = obj.getattr("microsecond")?.extract()?;
    Ok(format!("{prefix}{h:02}:{m:02}:{s:02}.{us:06}"))
}
