//! Conversions between slot encodings (the `*_TO_*` functions), shared
//! by the executor and by constant folding in the checker. A conversion
//! that cannot be done returns a [`ConvError`]; the executor turns it into
//! a runtime fault, the checker into a diagnostic.

use super::encode::{wrap_s, wrap_u};
use std::fmt;

/// Conversions between slot encodings. `S`/`U` = signed/unsigned integer,
/// `F32`/`F64` = REAL/LREAL. Integer targets carry a shift (`64 - bits`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Conv {
    /// Integer to signed integer, wrapping (e.g. DINT_TO_INT).
    WrapS(u8),
    /// Integer to unsigned integer or bit string, wrapping.
    WrapU(u8),
    /// Signed integer to REAL.
    SToF32,
    /// Unsigned integer to REAL.
    UToF32,
    /// Signed integer to LREAL.
    SToF64,
    /// Unsigned integer to LREAL.
    UToF64,
    /// REAL to LREAL.
    F32ToF64,
    /// LREAL to REAL.
    F64ToF32,
    /// REAL to signed integer, rounding half away from zero; out of range faults.
    F32ToS(u8),
    /// REAL to unsigned integer, rounding; out of range faults.
    F32ToU(u8),
    /// LREAL to signed integer, rounding; out of range faults.
    F64ToS(u8),
    /// LREAL to unsigned integer, rounding; out of range faults.
    F64ToU(u8),
    /// TRUNC of REAL to signed integer; out of range faults.
    TruncF32ToS(u8),
    /// TRUNC of LREAL to signed integer; out of range faults.
    TruncF64ToS(u8),
    /// TRUNC of REAL to unsigned integer.
    TruncF32ToU(u8),
    /// TRUNC of LREAL to unsigned integer.
    TruncF64ToU(u8),
    /// Integer to BOOL (non-zero is TRUE).
    ToBool,
    /// Signed integer checked into a signed range (faults when it does not fit).
    CheckS(u8),
    /// Integer checked into an unsigned range.
    CheckU(u8),
    /// Signed integer checked into an unsigned range (negative values fault).
    CheckSToU(u8),
    /// Binary to BCD (value of `bits` width); faults if it does not fit.
    ToBcd(u8),
    /// BCD to binary; faults on an invalid nibble.
    FromBcd,
    /// Nanoseconds to whole milliseconds (`TIME_TO_<int>`, truncated
    /// toward zero), checked into a signed range (faults when it does not fit).
    NsToMsS(u8),
    /// Nanoseconds to whole milliseconds, checked into an unsigned range.
    NsToMsU(u8),
    /// Milliseconds (signed) to nanoseconds (`<int>_TO_TIME`); faults
    /// beyond the range of TIME.
    MsToNsS,
    /// Milliseconds (unsigned) to nanoseconds; faults beyond the range of TIME.
    MsToNsU,
    /// TIME to REAL milliseconds.
    NsToMsF32,
    /// TIME to LREAL milliseconds.
    NsToMsF64,
    /// REAL milliseconds to TIME.
    MsF32ToNs,
    /// LREAL milliseconds to TIME.
    MsF64ToNs,
    /// DT to DATE (drop the time of day).
    DtToDate,
    /// DT to TOD (keep the time of day).
    DtToTod,
    /// REAL to BOOL: TRUE unless the value is 0.0 or -0.0 (a NaN is TRUE).
    F32ToBool,
    /// LREAL to BOOL, as [`Conv::F32ToBool`].
    F64ToBool,
    /// Nanoseconds since 1970 to whole seconds, rounded down (a DT or
    /// DATE as the count CODESYS gives: `DT_TO_UDINT`).
    NsToSecs,
    /// Seconds since 1970 to nanoseconds (`UDINT_TO_DT`); faults beyond
    /// the range of the 64-bit nanosecond count.
    SecsToNs,
}

/// Why a conversion cannot be done.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConvError {
    /// The result does not fit the target type (or the source is NaN).
    Overflow,
    /// A nibble of a BCD value is above 9.
    InvalidBcd,
}

impl fmt::Display for ConvError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ConvError::Overflow => "conversion result out of the target type's range",
            ConvError::InvalidBcd => "invalid BCD value",
        })
    }
}

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

fn real_to_s(f: f64, shift: u8) -> Result<u64, ConvError> {
    f64_to_i64(f)
        .and_then(|v| fits_s(v, shift))
        .ok_or(ConvError::Overflow)
}

fn real_to_u(f: f64, shift: u8) -> Result<u64, ConvError> {
    f64_to_u64(f)
        .and_then(|v| fits_u(v, shift))
        .ok_or(ConvError::Overflow)
}

fn to_bcd(mut v: u64, bits: u8) -> Result<u64, ConvError> {
    let mut out = 0u64;
    let mut pos = 0;
    while v > 0 {
        if pos >= bits as u32 {
            return Err(ConvError::Overflow);
        }
        out |= (v % 10) << pos;
        v /= 10;
        pos += 4;
    }
    Ok(out)
}

fn from_bcd(mut v: u64) -> Result<u64, ConvError> {
    let mut out = 0u64;
    let mut scale = 1u64;
    while v > 0 {
        let digit = v & 0xF;
        if digit > 9 {
            return Err(ConvError::InvalidBcd);
        }
        out += digit * scale;
        scale = scale.saturating_mul(10);
        v >>= 4;
    }
    Ok(out)
}

const NS_PER_MS: i64 = 1_000_000;
const NS_PER_S: i64 = 1_000_000_000;
const DAY_NS: i64 = 86_400_000_000_000;

/// Applies conversion `c` to slot value `x`.
pub fn convert(c: Conv, x: u64) -> Result<u64, ConvError> {
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
        Conv::CheckS(s) => fits_s(x as i64, s).ok_or(ConvError::Overflow)?,
        Conv::CheckU(s) => fits_u(x, s).ok_or(ConvError::Overflow)?,
        Conv::CheckSToU(s) => {
            if (x as i64) < 0 {
                return Err(ConvError::Overflow);
            }
            fits_u(x, s).ok_or(ConvError::Overflow)?
        }
        Conv::ToBcd(bits) => to_bcd(x, bits)?,
        Conv::FromBcd => from_bcd(x)?,
        // Like the integer conversions, a count that does not fit faults
        // (semantics §3) instead of wrapping.
        Conv::NsToMsS(s) => fits_s((x as i64) / NS_PER_MS, s).ok_or(ConvError::Overflow)?,
        Conv::NsToMsU(s) => {
            let ms = u64::try_from((x as i64) / NS_PER_MS).map_err(|_| ConvError::Overflow)?;
            fits_u(ms, s).ok_or(ConvError::Overflow)?
        }
        Conv::MsToNsS => (x as i64)
            .checked_mul(NS_PER_MS)
            .ok_or(ConvError::Overflow)? as u64,
        Conv::MsToNsU => i64::try_from(x)
            .ok()
            .and_then(|ms| ms.checked_mul(NS_PER_MS))
            .ok_or(ConvError::Overflow)? as u64,
        Conv::NsToMsF32 => (((x as i64) as f64 / NS_PER_MS as f64) as f32).to_bits() as u64,
        Conv::NsToMsF64 => ((x as i64) as f64 / NS_PER_MS as f64).to_bits(),
        Conv::MsF32ToNs => {
            f64_to_i64((f32v() * NS_PER_MS as f64).round()).ok_or(ConvError::Overflow)? as u64
        }
        Conv::MsF64ToNs => {
            f64_to_i64((f64v() * NS_PER_MS as f64).round()).ok_or(ConvError::Overflow)? as u64
        }
        // The first day of the range has no midnight in range: it faults.
        Conv::DtToDate => (x as i64)
            .div_euclid(DAY_NS)
            .checked_mul(DAY_NS)
            .ok_or(ConvError::Overflow)? as u64,
        Conv::DtToTod => (x as i64).rem_euclid(DAY_NS) as u64,
        Conv::F32ToBool => (f32v() != 0.0) as u64,
        Conv::F64ToBool => (f64v() != 0.0) as u64,
        Conv::NsToSecs => (x as i64).div_euclid(NS_PER_S) as u64,
        Conv::SecsToNs => (x as i64)
            .checked_mul(NS_PER_S)
            .ok_or(ConvError::Overflow)? as u64,
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
            Err(ConvError::Overflow)
        );
        assert_eq!(
            convert(Conv::F32ToS(32), f(f32::NAN)),
            Err(ConvError::Overflow)
        );
    }

    #[test]
    fn bcd() {
        assert_eq!(convert(Conv::ToBcd(16), 1234), Ok(0x1234));
        assert_eq!(convert(Conv::FromBcd, 0x1234), Ok(1234));
        assert_eq!(convert(Conv::FromBcd, 0x1A), Err(ConvError::InvalidBcd));
        assert_eq!(convert(Conv::ToBcd(8), 100), Err(ConvError::Overflow));
    }
}
