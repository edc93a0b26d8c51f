//! Compile-time constant values: decoding literals into slot encodings,
//! range checks, and parsing scalar text at run time (STRING_TO_*, stimulus).

use crate::syntax::ast::{Literal, LiteralValue};
use crate::types::{ElemType, Family};

/// A value known at compile time.
#[derive(Debug, Clone, PartialEq)]
pub enum Const {
    /// An integer literal whose type is not fixed yet (ANY_INT).
    Int(i128),
    /// A real literal whose type is not fixed yet (ANY_REAL).
    Real(f64),
    /// A typed scalar in its slot encoding.
    Bits(u64),
    /// A string.
    Str(String),
}

/// Encodes an integer into the slot of `ty`, if it fits.
pub fn int_to_slot(v: i128, ty: ElemType) -> Option<u64> {
    match ty.family() {
        Family::Real => Some(if ty == ElemType::Real {
            (v as f32).to_bits() as u64
        } else {
            (v as f64).to_bits()
        }),
        Family::Duration | Family::DateTime => i64::try_from(v).ok().map(|x| x as u64),
        _ => {
            let (lo, hi) = ty.int_range()?;
            (lo..=hi).contains(&v).then_some(v as u64)
        }
    }
}

/// Encodes a real into the slot of `ty` (REAL or LREAL).
pub fn real_to_slot(v: f64, ty: ElemType) -> Option<u64> {
    match ty {
        ElemType::Real => {
            let f = v as f32;
            (f.is_finite() || !v.is_finite()).then_some(f.to_bits() as u64)
        }
        ElemType::Lreal => Some(v.to_bits()),
        _ => None,
    }
}

/// Decodes a slot of integer type `ty` into an i128.
pub fn slot_to_int(bits: u64, ty: ElemType) -> i128 {
    if ty.is_signed_int() || matches!(ty.family(), Family::Duration | Family::DateTime) {
        bits as i64 as i128
    } else {
        bits as i128
    }
}

/// Decodes a slot of REAL/LREAL into f64.
pub fn slot_to_real(bits: u64, ty: ElemType) -> f64 {
    if ty == ElemType::Real {
        f32::from_bits(bits as u32) as f64
    } else {
        f64::from_bits(bits)
    }
}

/// The natural elementary type of a literal without context, if it has one
/// (untyped numbers have none).
pub fn literal_type(lit: &LiteralValue) -> Option<ElemType> {
    Some(match lit {
        LiteralValue::Int(_) | LiteralValue::Real(_) | LiteralValue::EnumValue(_) => return None,
        LiteralValue::Bool(_) => ElemType::Bool,
        LiteralValue::Duration { long, .. } => {
            if *long {
                ElemType::Ltime
            } else {
                ElemType::Time
            }
        }
        LiteralValue::Date { long, .. } => {
            if *long {
                ElemType::Ldate
            } else {
                ElemType::Date
            }
        }
        LiteralValue::TimeOfDay { long, .. } => {
            if *long {
                ElemType::Ltod
            } else {
                ElemType::Tod
            }
        }
        LiteralValue::DateTime { long, .. } => {
            if *long {
                ElemType::Ldt
            } else {
                ElemType::Dt
            }
        }
        LiteralValue::String { wide, .. } => {
            if *wide {
                ElemType::WString
            } else {
                ElemType::String
            }
        }
    })
}

/// Encodes a decoded literal as a value of elementary type `ty`, or says why not.
pub fn literal_to_slot(lit: &LiteralValue, ty: ElemType) -> Result<Const, String> {
    let out_of_range = |v: &dyn std::fmt::Display| format!("{v} does not fit in {ty}");
    match lit {
        LiteralValue::Int(v) => {
            if ty == ElemType::Bool {
                return match v {
                    0 | 1 => Ok(Const::Bits(*v as u64)),
                    _ => Err(out_of_range(v)),
                };
            }
            if !(ty.is_num() || ty.is_bit() || ty.family() == Family::Char) {
                return Err(format!("an integer literal is not a {ty}"));
            }
            int_to_slot(*v, ty)
                .map(Const::Bits)
                .ok_or_else(|| out_of_range(v))
        }
        LiteralValue::Real(v) => {
            if !ty.is_real() {
                return Err(format!("a real literal is not a {ty}"));
            }
            real_to_slot(*v, ty)
                .map(Const::Bits)
                .ok_or_else(|| out_of_range(v))
        }
        LiteralValue::Bool(b) => {
            if ty.is_bit() {
                Ok(Const::Bits(*b as u64))
            } else {
                Err(format!("a BOOL literal is not a {ty}"))
            }
        }
        LiteralValue::String { value, wide } => {
            if ty.is_string() && (*wide == (ty == ElemType::WString) || !*wide) {
                Ok(Const::Str(value.clone()))
            } else if ty.family() == Family::Char && value.chars().count() == 1 {
                Ok(Const::Bits(
                    value.chars().next().map(|c| c as u64).unwrap_or(0),
                ))
            } else {
                Err(format!("a string literal is not a {ty}"))
            }
        }
        LiteralValue::EnumValue(_) => Err(format!("an enumeration value is not a {ty}")),
        LiteralValue::Duration { nanos, .. }
        | LiteralValue::Date { nanos, .. }
        | LiteralValue::TimeOfDay { nanos, .. }
        | LiteralValue::DateTime { nanos, .. } => {
            let natural = literal_type(lit).unwrap_or(ty);
            if natural == ty || natural.widens_to(ty) || same_kind_long(natural, ty) {
                Ok(Const::Bits(*nanos as u64))
            } else {
                Err(format!("a {natural} literal is not a {ty}"))
            }
        }
    }
}

/// TIME/LTIME, DATE/LDATE... share an encoding (nanoseconds).
fn same_kind_long(a: ElemType, b: ElemType) -> bool {
    use ElemType::*;
    matches!(
        (a, b),
        (Time, Ltime)
            | (Ltime, Time)
            | (Date, Ldate)
            | (Ldate, Date)
            | (Tod, Ltod)
            | (Ltod, Tod)
            | (Dt, Ldt)
            | (Ldt, Dt)
    )
}

/// Applies an optional `TYPE#` prefix check: the literal written with a
/// prefix naming an elementary type is encoded as that type.
pub fn typed_literal(lit: &Literal) -> Option<ElemType> {
    lit.type_prefix
        .as_ref()
        .and_then(|p| ElemType::from_name(&p.name))
}

/// Parses `text` as a value of `ty` (used by `STRING_TO_*` and for values
/// given from outside). Accepts IEC literals; bare numbers for numeric types.
pub fn parse_scalar(text: &str, ty: ElemType) -> Option<u64> {
    let lit = crate::syntax::parse_literal(text.trim()).ok()?;
    if let Some(prefix) = typed_literal(&lit)
        && prefix != ty
        && !prefix.widens_to(ty)
    {
        return None;
    }
    match literal_to_slot(&lit.value, ty).ok()? {
        Const::Bits(b) => Some(b),
        Const::Int(v) => int_to_slot(v, ty),
        Const::Real(v) => real_to_slot(v, ty),
        Const::Str(_) => None,
    }
}
