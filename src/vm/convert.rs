//! Value conversions between slot encodings (the `*_TO_*` functions).

use super::FaultKind;
use crate::ir::op::{Conv, wrap_s, wrap_u};

/// `f` as i64 if it is finite and in range.
pub fn f64_to_i64(f: f64) -> Option<i64> {
    if f.is_finite() && (-9_223_372_036_854_775_808.0..9_223_372_036_854_775_808.0).contains(&f) {
        Some(f as i64)
    } else {
        None
    }
}

fn f64_to_u64(f: f64) -> Option<u64> {
    if f.is_finite() && f > -1.0 && f < 18_446_744_073_709_551_616.0 {
        Some(f as u64)
    } else {
        None
    }
}

/// Checks that signed `v` fits in `64 - shift` bits.
fn fits_s(v: i64, shift: u8) -> Option<u64> {
    let w = wrap_s(v as u64, shift);
    (w as i64 == v).then_some(w)
}

/// Checks that unsigned `v` fits in `64 - shift` bits.
fn fits_u(v: u64, shift: u8) -> Option<u64> {
    let w = wrap_u(v, shift);
    (w == v).then_some(w)
}

fn real_to_s(f: f64, shift: u8) -> Result<u64, FaultKind> {
    f64_to_i64(f)
        .and_then(|v| fits_s(v, shift))
        .ok_or(FaultKind::ConversionOverflow)
}

fn real_to_u(f: f64, shift: u8) -> Result<u64, FaultKind> {
    f64_to_u64(f)
        .and_then(|v| fits_u(v, shift))
        .ok_or(FaultKind::ConversionOverflow)
}

fn to_bcd(mut v: u64, bits: u8) -> Result<u64, FaultKind> {
    let mut out = 0u64;
    let mut pos = 0;
    while v > 0 {
        if pos >= bits as u32 {
            return Err(FaultKind::ConversionOverflow);
        }
        out |= (v % 10) << pos;
        v /= 10;
        pos += 4;
    }
    Ok(out)
}

fn from_bcd(mut v: u64) -> Result<u64, FaultKind> {
    let mut out = 0u64;
    let mut scale = 1u64;
    while v > 0 {
        let digit = v & 0xF;
        if digit > 9 {
            return Err(FaultKind::InvalidBcd);
        }
        out += digit * scale;
        scale = scale.saturating_mul(10);
        v >>= 4;
    }
    Ok(out)
}

const NS_PER_MS: i64 = 1_000_000;
const DAY_NS: i64 = 86_400_000_000_000;

/// Applies conversion `c` to slot value `x`.
pub fn convert(c: Conv, x: u64) -> Result<u64, FaultKind> {
    let f32v = || f32::from_bits(x as u32) as f64;
    let f64v = || f64::from_bits(x);
    Ok(match c {
        Conv::WrapS(s) => wrap_s(x, s),
        Conv::WrapU(s) => wrap_u(x, s),
        Conv::SToF32 => ((x as i64) as f32).to_bits() as u64,
        Conv::UToF32 => (x as f32).to_bits() as u64,
        Conv::SToF64 => ((x as i64) as f64).to_bits(),
        Conv::UToF64 => (x as f64).to_bits(),
        Conv::F32ToF64 => f32v().to_bits(),
        Conv::F64ToF32 => (f64v() as f32).to_bits() as u64,
        Conv::F32ToS(s) => real_to_s(f32v().round(), s)?,
        Conv::F32ToU(s) => real_to_u(f32v().round(), s)?,
        Conv::F64ToS(s) => real_to_s(f64v().round(), s)?,
        Conv::F64ToU(s) => real_to_u(f64v().round(), s)?,
        Conv::TruncF32ToS(s) => real_to_s(f32v().trunc(), s)?,
        Conv::TruncF64ToS(s) => real_to_s(f64v().trunc(), s)?,
        Conv::TruncF32ToU(s) => real_to_u(f32v().trunc(), s)?,
        Conv::TruncF64ToU(s) => real_to_u(f64v().trunc(), s)?,
        Conv::ToBool => (x != 0) as u64,
        Conv::CheckS(s) => fits_s(x as i64, s).ok_or(FaultKind::ConversionOverflow)?,
        Conv::CheckU(s) => fits_u(x, s).ok_or(FaultKind::ConversionOverflow)?,
        Conv::CheckSToU(s) => {
            if (x as i64) < 0 {
                return Err(FaultKind::ConversionOverflow);
            }
            fits_u(x, s).ok_or(FaultKind::ConversionOverflow)?
        }
        Conv::ToBcd(bits) => to_bcd(x, bits)?,
        Conv::FromBcd => from_bcd(x)?,
        Conv::NsToMsS(s) => wrap_s(((x as i64) / NS_PER_MS) as u64, s),
        Conv::NsToMsU(s) => wrap_u(((x as i64) / NS_PER_MS) as u64, s),
        Conv::MsToNsS => ((x as i64).wrapping_mul(NS_PER_MS)) as u64,
        Conv::MsToNsU => x.wrapping_mul(NS_PER_MS as u64),
        Conv::NsToMsF32 => (((x as i64) as f64 / NS_PER_MS as f64) as f32).to_bits() as u64,
        Conv::NsToMsF64 => ((x as i64) as f64 / NS_PER_MS as f64).to_bits(),
        Conv::MsF32ToNs => f64_to_i64((f32v() * NS_PER_MS as f64).round())
            .ok_or(FaultKind::ConversionOverflow)? as u64,
        Conv::MsF64ToNs => f64_to_i64((f64v() * NS_PER_MS as f64).round())
            .ok_or(FaultKind::ConversionOverflow)? as u64,
        Conv::DtToDate => ((x as i64).div_euclid(DAY_NS) * DAY_NS) as u64,
        Conv::DtToTod => (x as i64).rem_euclid(DAY_NS) as u64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_half_away_from_zero() {
        let f = |v: f32| (v.to_bits()) as u64;
        assert_eq!(convert(Conv::F32ToS(48), f(2.5)), Ok(3));
        assert_eq!(convert(Conv::F32ToS(48), f(-2.5)), Ok((-3i64) as u64));
        assert_eq!(convert(Conv::TruncF32ToS(48), f(-2.7)), Ok((-2i64) as u64));
        assert_eq!(
            convert(Conv::F32ToS(48), f(40000.0)),
            Err(FaultKind::ConversionOverflow)
        );
        assert_eq!(
            convert(Conv::F32ToS(32), f(f32::NAN)),
            Err(FaultKind::ConversionOverflow)
        );
    }

    #[test]
    fn bcd() {
        assert_eq!(convert(Conv::ToBcd(16), 1234), Ok(0x1234));
        assert_eq!(convert(Conv::FromBcd, 0x1234), Ok(1234));
        assert_eq!(convert(Conv::FromBcd, 0x1A), Err(FaultKind::InvalidBcd));
        assert_eq!(
            convert(Conv::ToBcd(8), 100),
            Err(FaultKind::ConversionOverflow)
        );
    }
}
