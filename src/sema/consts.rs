//! Compile-time constant values: literals of the AST encoded into slots
//! (through the value module, which also reads values given at run time),
//! and slots decoded back into numbers for folding.

use crate::elementary::{ElemType, Family};
use crate::syntax::ast::{Literal, LiteralValue};
pub use crate::value::encode::{int_to_slot, real_to_slot};
use crate::value::text::{Encoded, Lit, encode, natural_type};

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

/// The literal as the value module sees it.
fn lit(value: &LiteralValue) -> Lit {
    let nanos = |nanos: i64, short: ElemType, long_ty: ElemType, long: bool| Lit::Nanos {
        nanos,
        ty: if long { long_ty } else { short },
    };
    match value {
        LiteralValue::Int(v) => Lit::Int(*v),
        LiteralValue::Real(v) => Lit::Real(*v),
        LiteralValue::Bool(b) => Lit::Bool(*b),
        LiteralValue::String { value, wide } => Lit::Str {
            value: value.clone(),
            wide: *wide,
        },
        LiteralValue::Duration { nanos: n, long } => {
            nanos(*n, ElemType::Time, ElemType::Ltime, *long)
        }
        LiteralValue::Date { nanos: n, long } => nanos(*n, ElemType::Date, ElemType::Ldate, *long),
        LiteralValue::TimeOfDay { nanos: n, long } => {
            nanos(*n, ElemType::Tod, ElemType::Ltod, *long)
        }
        LiteralValue::DateTime { nanos: n, long } => nanos(*n, ElemType::Dt, ElemType::Ldt, *long),
        LiteralValue::EnumValue(id) => Lit::Name(id.name.clone()),
    }
}

/// The natural elementary type of a literal without context, if it has one
/// (untyped numbers have none).
pub fn literal_type(value: &LiteralValue) -> Option<ElemType> {
    natural_type(&lit(value))
}

/// Encodes a decoded literal as a value of elementary type `ty`, or says
/// why not (the rules are the value module's, shared with values read at
/// run time).
pub fn literal_to_slot(value: &LiteralValue, ty: ElemType) -> Result<Const, String> {
    Ok(match encode(&lit(value), ty)? {
        Encoded::Bits(b) => Const::Bits(b),
        Encoded::Str(s) => Const::Str(s),
    })
}

/// Applies an optional `TYPE#` prefix check: the literal written with a
/// prefix naming an elementary type is encoded as that type.
pub fn typed_literal(lit: &Literal) -> Option<ElemType> {
    lit.type_prefix
        .as_ref()
        .and_then(|p| ElemType::from_name(&p.name))
}
