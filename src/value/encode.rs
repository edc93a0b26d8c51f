//! Numbers encoded into the 64-bit slot of an elementary type (see
//! [`crate::elementary`] for the encoding of each type).

use crate::elementary::{ElemType, Family};

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

/// Whether `raw` is a slot value of `ty` as the executor keeps it: BOOL 0
/// or 1, integers and bit strings sign- or zero-extended from their width,
/// REAL in the low 32 bits. (Every 64-bit pattern is an LREAL, a duration
/// or a date.)
pub fn is_canonical(ty: ElemType, raw: u64) -> bool {
    match ty.int_range() {
        Some((lo, hi)) => {
            let v = if ty.is_signed_int() {
                i128::from(raw as i64)
            } else {
                i128::from(raw)
            };
            (lo..=hi).contains(&v)
        }
        None if ty == ElemType::Real => raw <= u64::from(u32::MAX),
        None => true,
    }
}

/// Encodes a real into the slot of `ty` (REAL or LREAL); a finite value too
/// large for REAL does not fit.
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

/// Sign-extends or zero-extends `x` from `64 - shift` bits.
#[inline(always)]
pub fn wrap_s(x: u64, shift: u8) -> u64 {
    (((x << shift) as i64) >> shift) as u64
}

/// Zero-extends `x` from `64 - shift` bits.
#[inline(always)]
pub fn wrap_u(x: u64, shift: u8) -> u64 {
    (x << shift) >> shift
}
