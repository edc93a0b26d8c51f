//! IEC types as OPC UA built-in types: which DataType a variable gets,
//! how a slot's raw value becomes a `Variant`, and how a client's
//! `Variant` becomes a value the PLC accepts (docs/opcua.md, "Types").

use crate::elementary::ElemType;
use crate::ir::type_table::TypeKind;
use crate::runtime::engine::Plc;
use crate::runtime::names::VarRef;
use crate::runtime::plc_value::Value;
use async_opcua::types::{DataTypeId, DateTime, StatusCode, UAString, Variant};
use std::sync::Arc;

/// Nanoseconds from 1601-01-01 (OPC UA's epoch) to 1970-01-01 (plcrun's),
/// in 100 ns ticks.
const UNIX_EPOCH_TICKS: i64 = 116_444_736_000_000_000;

/// Nanoseconds in one millisecond (TIME is served as a Duration in ms).
const NS_PER_MS: f64 = 1_000_000.0;

/// How one single value of the PLC is served.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Kind {
    /// An elementary value (a subrange keeps its bounds).
    Scalar {
        /// Its type.
        elem: ElemType,
        /// A subrange's bounds, checked on writes.
        range: Option<(i64, i64)>,
    },
    /// STRING or WSTRING.
    Str {
        /// WSTRING.
        wide: bool,
    },
    /// An enumeration: Int32 on the wire, its names and values.
    Enum(Arc<[(String, i64)]>),
}

impl Kind {
    /// The kind of the variable `r` of `plc` (`None`: not a single value).
    pub(crate) fn of(plc: &Plc, r: &VarRef) -> Option<Kind> {
        let types = &plc.image.types;
        if r.view.is_some() {
            return types
                .scalar(r.ty)
                .map(|elem| Kind::Scalar { elem, range: None });
        }
        Some(match &types.get(r.ty).kind {
            TypeKind::Elem(e) if matches!(e, ElemType::String | ElemType::WString) => Kind::Str {
                wide: *e == ElemType::WString,
            },
            TypeKind::Elem(e) => Kind::Scalar {
                elem: *e,
                range: None,
            },
            TypeKind::Str { wide, .. } => Kind::Str { wide: *wide },
            TypeKind::Enum { values, .. } => Kind::Enum(values.iter().cloned().collect()),
            TypeKind::Subrange { base, lo, hi } => Kind::Scalar {
                elem: *base,
                range: Some((*lo, *hi)),
            },
            _ => return None,
        })
    }

    /// The OPC UA DataType of a variable of this kind.
    pub(crate) fn data_type(&self) -> DataTypeId {
        match self {
            Kind::Str { .. } => DataTypeId::String,
            Kind::Enum(_) => DataTypeId::Int32,
            Kind::Scalar { elem, .. } => elem_data_type(*elem),
        }
    }
}

/// The DataType an elementary type is served as.
fn elem_data_type(e: ElemType) -> DataTypeId {
    use ElemType as E;
    match e {
        E::Bool => DataTypeId::Boolean,
        E::Sint => DataTypeId::SByte,
        E::Int => DataTypeId::Int16,
        E::Dint => DataTypeId::Int32,
        E::Lint => DataTypeId::Int64,
        E::Usint | E::Byte | E::Char => DataTypeId::Byte,
        E::Uint | E::Word | E::Wchar => DataTypeId::UInt16,
        E::Udint | E::Dword => DataTypeId::UInt32,
        E::Ulint | E::Lword => DataTypeId::UInt64,
        E::Real => DataTypeId::Float,
        E::Lreal => DataTypeId::Double,
        E::Time | E::Ltime | E::Tod | E::Ltod => DataTypeId::Duration,
        E::Date | E::Ldate | E::Dt | E::Ldt => DataTypeId::DateTime,
        E::String | E::WString => DataTypeId::String,
    }
}

/// The Variant of a raw slot value of elementary type `e`.
pub(crate) fn scalar_variant(e: ElemType, raw: u64) -> Variant {
    use ElemType as E;
    match e {
        E::Bool => Variant::Boolean(raw != 0),
        E::Sint => Variant::SByte(raw as i64 as i8),
        E::Int => Variant::Int16(raw as i64 as i16),
        E::Dint => Variant::Int32(raw as i64 as i32),
        E::Lint => Variant::Int64(raw as i64),
        E::Usint | E::Byte | E::Char => Variant::Byte(raw as u8),
        E::Uint | E::Word | E::Wchar => Variant::UInt16(raw as u16),
        E::Udint | E::Dword => Variant::UInt32(raw as u32),
        E::Ulint | E::Lword => Variant::UInt64(raw),
        E::Real => Variant::Float(f32::from_bits(raw as u32)),
        E::Lreal => Variant::Double(f64::from_bits(raw)),
        E::Time | E::Ltime | E::Tod | E::Ltod => Variant::Double(raw as i64 as f64 / NS_PER_MS),
        E::Date | E::Ldate | E::Dt | E::Ldt => Variant::DateTime(Box::new(date_time(raw as i64))),
        E::String | E::WString => Variant::Empty,
    }
}

/// The Variant of a value of kind `kind`: `raw` is the slot, `text` the
/// string of a STRING variable.
pub(crate) fn variant(kind: &Kind, raw: u64, text: &str) -> Variant {
    match kind {
        Kind::Scalar { elem, .. } => scalar_variant(*elem, raw),
        Kind::Str { .. } => Variant::String(UAString::from(text)),
        Kind::Enum(_) => Variant::Int32(raw as i64 as i32),
    }
}

/// An OPC UA DateTime for nanoseconds since 1970-01-01 UTC, clamped to the
/// range OPC UA can encode.
pub(crate) fn date_time(ns: i64) -> DateTime {
    let ticks = (ns.div_euclid(100)).saturating_add(UNIX_EPOCH_TICKS);
    DateTime::from(ticks.clamp(0, DateTime::endtimes_ticks() - 1))
}

/// Nanoseconds since 1970-01-01 UTC of an OPC UA DateTime.
fn unix_ns(t: &DateTime) -> Option<i64> {
    t.ticks()
        .checked_sub(UNIX_EPOCH_TICKS)
        .and_then(|ticks| ticks.checked_mul(100))
}

/// The integer in a Variant of any integer type.
fn integer(v: &Variant) -> Option<i128> {
    Some(match v {
        Variant::SByte(x) => i128::from(*x),
        Variant::Byte(x) => i128::from(*x),
        Variant::Int16(x) => i128::from(*x),
        Variant::UInt16(x) => i128::from(*x),
        Variant::Int32(x) => i128::from(*x),
        Variant::UInt32(x) => i128::from(*x),
        Variant::Int64(x) => i128::from(*x),
        Variant::UInt64(x) => i128::from(*x),
        _ => return None,
    })
}

/// The PLC value a client's Variant writes into a variable of kind `kind`.
/// Integers of any width are accepted when they fit (BadOutOfRange
/// otherwise); REAL and LREAL take Float or Double, TIME a Double of
/// milliseconds, DT a DateTime; anything else is BadTypeMismatch.
pub(crate) fn value_of(kind: &Kind, v: &Variant) -> Result<Value, StatusCode> {
    match kind {
        Kind::Str { wide } => match v {
            Variant::String(s) => Ok(Value::String(s.as_ref().to_string(), *wide)),
            _ => Err(StatusCode::BadTypeMismatch),
        },
        Kind::Enum(values) => {
            let x = integer(v).ok_or(StatusCode::BadTypeMismatch)?;
            values
                .iter()
                .find(|(_, value)| i128::from(*value) == x)
                .map(|(name, value)| Value::Enum(name.clone(), *value))
                .ok_or(StatusCode::BadOutOfRange)
        }
        Kind::Scalar { elem, range } => {
            let raw = scalar_raw(*elem, v)?;
            if let Some((lo, hi)) = range
                && !(*lo..=*hi).contains(&(raw as i64))
            {
                return Err(StatusCode::BadOutOfRange);
            }
            Ok(Value::Scalar(*elem, raw))
        }
    }
}

/// The raw slot value of a Variant written to an elementary type.
fn scalar_raw(e: ElemType, v: &Variant) -> Result<u64, StatusCode> {
    use ElemType as E;
    match e {
        E::Bool => match v {
            Variant::Boolean(b) => Ok(u64::from(*b)),
            _ => Err(StatusCode::BadTypeMismatch),
        },
        E::Real | E::Lreal => {
            let x = match v {
                Variant::Float(f) => f64::from(*f),
                Variant::Double(d) => *d,
                _ => return Err(StatusCode::BadTypeMismatch),
            };
            crate::value::encode::real_to_slot(x, e).ok_or(StatusCode::BadOutOfRange)
        }
        E::Time | E::Ltime | E::Tod | E::Ltod => {
            let ms = match v {
                Variant::Double(d) => *d,
                Variant::Float(f) => f64::from(*f),
                _ => integer(v).ok_or(StatusCode::BadTypeMismatch)? as f64,
            };
            let ns = (ms * NS_PER_MS).round();
            if !ns.is_finite() || ns < i64::MIN as f64 || ns >= i64::MAX as f64 {
                return Err(StatusCode::BadOutOfRange);
            }
            let ns = ns as i64;
            let day = 86_400_000_000_000;
            if matches!(e, E::Tod | E::Ltod) && !(0..day).contains(&ns) {
                return Err(StatusCode::BadOutOfRange);
            }
            Ok(ns as u64)
        }
        E::Date | E::Ldate | E::Dt | E::Ldt => match v {
            Variant::DateTime(t) => unix_ns(t)
                .map(|ns| ns as u64)
                .ok_or(StatusCode::BadOutOfRange),
            _ => Err(StatusCode::BadTypeMismatch),
        },
        E::String | E::WString => Err(StatusCode::BadTypeMismatch),
        _ => {
            let x = integer(v).ok_or(StatusCode::BadTypeMismatch)?;
            let (lo, hi) = e.int_range().ok_or(StatusCode::BadTypeMismatch)?;
            if !(lo..=hi).contains(&x) {
                return Err(StatusCode::BadOutOfRange);
            }
            Ok(x as i64 as u64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scalar(elem: ElemType) -> Kind {
        Kind::Scalar { elem, range: None }
    }

    #[test]
    fn integers_round_trip_and_refuse_what_does_not_fit() {
        let int = scalar(ElemType::Int);
        assert_eq!(
            scalar_variant(ElemType::Int, (-5i64) as u64),
            Variant::Int16(-5)
        );
        assert_eq!(
            value_of(&int, &Variant::Int64(-5)),
            Ok(Value::Scalar(ElemType::Int, (-5i64) as u64))
        );
        assert_eq!(
            value_of(&int, &Variant::Int32(40_000)),
            Err(StatusCode::BadOutOfRange)
        );
        assert_eq!(
            value_of(&int, &Variant::Boolean(true)),
            Err(StatusCode::BadTypeMismatch)
        );
        let byte = scalar(ElemType::Usint);
        assert_eq!(
            value_of(&byte, &Variant::Int16(-1)),
            Err(StatusCode::BadOutOfRange)
        );
    }

    #[test]
    fn time_is_milliseconds_and_dt_is_a_date_time() {
        assert_eq!(
            scalar_variant(ElemType::Time, 1_500_000_000),
            Variant::Double(1500.0)
        );
        assert_eq!(
            value_of(&scalar(ElemType::Time), &Variant::Double(2.5)),
            Ok(Value::Scalar(ElemType::Time, 2_500_000))
        );
        // DT#2024-01-02-03:04:05 is 1704164645 s after 1970.
        let ns = 1_704_164_645_000_000_000i64;
        let Variant::DateTime(t) = scalar_variant(ElemType::Dt, ns as u64) else {
            panic!("not a DateTime")
        };
        assert_eq!(t.to_rfc3339(), "2024-01-02T03:04:05.000Z");
        assert_eq!(
            value_of(&scalar(ElemType::Dt), &Variant::DateTime(t)),
            Ok(Value::Scalar(ElemType::Dt, ns as u64))
        );
    }

    #[test]
    fn subranges_and_enums_check_their_values() {
        let sub = Kind::Scalar {
            elem: ElemType::Int,
            range: Some((1, 10)),
        };
        assert_eq!(
            value_of(&sub, &Variant::Int16(11)),
            Err(StatusCode::BadOutOfRange)
        );
        let e = Kind::Enum(Arc::from(vec![
            ("Red".to_string(), 0),
            ("Blue".to_string(), 5),
        ]));
        assert_eq!(
            value_of(&e, &Variant::Int32(5)),
            Ok(Value::Enum("Blue".into(), 5))
        );
        assert_eq!(
            value_of(&e, &Variant::Int32(1)),
            Err(StatusCode::BadOutOfRange)
        );
        assert_eq!(variant(&e, 5, ""), Variant::Int32(5));
    }

    #[test]
    fn reals_come_back_as_written() {
        let real = scalar(ElemType::Real);
        let Ok(Value::Scalar(_, raw)) = value_of(&real, &Variant::Float(1.25)) else {
            panic!("refused")
        };
        assert_eq!(scalar_variant(ElemType::Real, raw), Variant::Float(1.25));
    }
}
