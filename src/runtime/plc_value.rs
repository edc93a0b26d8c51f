//! Values read from and written to a PLC's variables from outside.

use crate::elementary::{ElemType, Family};
use std::fmt;

/// A value read from the PLC.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An elementary value in its slot encoding.
    Scalar(ElemType, u64),
    /// A string.
    String(String, bool),
    /// An enumeration value.
    Enum(String, i64),
}

impl Value {
    /// The value as an IEC literal (`TRUE`, `42`, `T#1s`, `'x'`).
    pub fn to_literal(&self) -> String {
        match self {
            Value::Scalar(t, raw) => crate::value::format::format_value(*t, *raw),
            Value::String(s, wide) => crate::value::format::format_string(s, *wide),
            Value::Enum(name, _) => name.clone(),
        }
    }

    /// As [`Self::to_literal`], but an LTIME read as TwinCAT's, unsigned:
    /// its largest value is `LT#213503d23h34m33s709ms551us615ns`, not
    /// `LT#-1ns`.
    pub(crate) fn to_unsigned_literal(&self) -> String {
        match self {
            Value::Scalar(ElemType::Ltime, raw) => {
                let mut s = String::new();
                crate::value::literal::write_unsigned_duration(&mut s, *raw, "LT#");
                s
            }
            other => other.to_literal(),
        }
    }

    /// The value as a signed integer, if it is an integer-like scalar.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::Scalar(t, raw) if t.is_signed_int() || t.family() == Family::Duration => {
                Some(*raw as i64)
            }
            Value::Scalar(t, raw) if t.is_int() || t.is_bit() => i64::try_from(*raw).ok(),
            Value::Enum(_, v) => Some(*v),
            _ => None,
        }
    }

    /// The value of a BOOL.
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Scalar(ElemType::Bool, raw) => Some(*raw != 0),
            _ => None,
        }
    }

    /// The value of a REAL or LREAL (a REAL widened exactly), or of an
    /// integer that an f64 holds exactly.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Scalar(ElemType::Real, raw) => Some(f32::from_bits(*raw as u32) as f64),
            Value::Scalar(ElemType::Lreal, raw) => Some(f64::from_bits(*raw)),
            _ => {
                let v = self.as_i64()?;
                let exact = v.unsigned_abs() <= 1 << f64::MANTISSA_DIGITS;
                exact.then_some(v as f64)
            }
        }
    }

    /// The text of a STRING or WSTRING.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::String(s, _) => Some(s),
            _ => None,
        }
    }
}

impl fmt::Display for Value {
    /// The IEC literal, as [`Value::to_literal`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_literal())
    }
}
