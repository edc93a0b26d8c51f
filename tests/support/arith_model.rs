//! The independent reference model of tests/arith_conformance.rs: values
//! of every elementary type in plain Rust (i128 and f32/f64), written
//! from docs/semantics.md §3 and IEC 61131-3, never calling plcrun's own
//! value or conversion code.
#![allow(dead_code)]

use plcrun::ElemType as E;
use proptest::prelude::*;

/// Nanoseconds per millisecond and per day.
pub const MS: i64 = 1_000_000;
pub const DAY: i64 = 86_400 * 1_000_000_000;

/// What an operation gives: a value in its slot encoding, a text, or a
/// runtime fault code.
#[derive(Debug, Clone, PartialEq)]
pub enum Out {
    /// A scalar: its type and raw slot bits (NaNs compare equal).
    V(E, u64),
    /// A STRING or WSTRING value.
    S(String),
    /// A runtime fault (`R001`...).
    Fault(&'static str),
}

impl Out {
    /// The value with every NaN made one NaN, so that results compare.
    pub fn normalized(self) -> Out {
        match self {
            Out::V(E::Real, r) if f32::from_bits(r as u32).is_nan() => Out::V(E::Real, u64::MAX),
            Out::V(E::Lreal, r) if f64::from_bits(r).is_nan() => Out::V(E::Lreal, u64::MAX),
            o => o,
        }
    }
}

/// The integer-like families: they convert among themselves.
pub fn int_like(t: E) -> bool {
    matches!(
        kind(t),
        K::Bool | K::Signed | K::Unsigned | K::Bits | K::Char
    )
}

/// Width in bits of an integer-like type.
pub fn width(t: E) -> u32 {
    match t {
        E::Bool => 1,
        E::Sint | E::Usint | E::Byte | E::Char => 8,
        E::Int | E::Uint | E::Word | E::Wchar => 16,
        E::Dint | E::Udint | E::Dword | E::Real => 32,
        _ => 64,
    }
}

pub fn signed(t: E) -> bool {
    matches!(t, E::Sint | E::Int | E::Dint | E::Lint)
}

/// The range of an integer-like type.
pub fn range(t: E) -> (i128, i128) {
    let w = width(t);
    if signed(t) {
        (-(1i128 << (w - 1)), (1i128 << (w - 1)) - 1)
    } else {
        (0, (1i128 << w) - 1)
    }
}

/// The slot bits of mathematical integer `v` wrapped to `t` (two's
/// complement, sign-extended for signed types, zero-extended otherwise).
pub fn wrap(t: E, v: i128) -> u64 {
    let w = width(t);
    let low = (v as u128 & ((1u128 << w) - 1)) as u64;
    if signed(t) && w < 64 && low >> (w - 1) & 1 == 1 {
        low | !((1u64 << w) - 1)
    } else {
        low
    }
}

/// The mathematical value of an integer-like (or TIME/date) slot.
pub fn num(t: E, raw: u64) -> i128 {
    if signed(t) || matches!(kind(t), K::Dur | K::Date) {
        i128::from(raw as i64)
    } else {
        i128::from(raw)
    }
}

/// `v` as the value of `t` if it fits, else the conversion fault.
pub fn checked(t: E, v: i128) -> Out {
    let (lo, hi) = range(t);
    if (lo..=hi).contains(&v) {
        Out::V(t, wrap(t, v))
    } else {
        Out::Fault("R004")
    }
}

/// The model's own grouping of the elementary types.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum K {
    Bool,
    Signed,
    Unsigned,
    Bits,
    Real,
    Dur,
    Date,
    Char,
    Str,
}

/// The group of `t`.
pub fn kind(t: E) -> K {
    match t {
        E::Bool => K::Bool,
        E::Sint | E::Int | E::Dint | E::Lint => K::Signed,
        E::Usint | E::Uint | E::Udint | E::Ulint => K::Unsigned,
        E::Byte | E::Word | E::Dword | E::Lword => K::Bits,
        E::Real | E::Lreal => K::Real,
        E::Time | E::Ltime => K::Dur,
        E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt => K::Date,
        E::Char | E::Wchar => K::Char,
        E::String | E::WString => K::Str,
    }
}

/// A real slot as f64 (REAL widened exactly).
pub fn real(t: E, raw: u64) -> f64 {
    if t == E::Real {
        f64::from(f32::from_bits(raw as u32))
    } else {
        f64::from_bits(raw)
    }
}

/// The slot of real `v` in `t` (rounded to f32 for REAL).
pub fn real_slot(t: E, v: f64) -> u64 {
    if t == E::Real {
        u64::from((v as f32).to_bits())
    } else {
        v.to_bits()
    }
}

/// Round to the nearest integer, halves away from zero (§3), computed
/// from the fraction so that it does not rely on `f64::round`.
pub fn round_half_away(v: f64) -> f64 {
    let fl = v.floor();
    let frac = v - fl;
    if frac > 0.5 || (frac == 0.5 && v > 0.0) {
        fl + 1.0
    } else {
        fl
    }
}

/// A real that is already integral, as an integer if finite and within
/// ±2^100 (far outside every target range), else `None`.
pub fn integral(v: f64) -> Option<i128> {
    (v.is_finite() && v.abs() < 1e30).then_some(v as i128)
}

/// Arbitrary slot bits of type `t`: random, small, and edge values.
pub fn arb(t: E) -> BoxedStrategy<u64> {
    let edges = edges(t);
    prop_oneof![
        3 => any::<u64>().prop_map(move |x| random(t, x)),
        3 => (-400i64..400).prop_map(move |x| small(t, x)),
        2 => proptest::sample::select(edges),
    ]
    .boxed()
}

fn random(t: E, x: u64) -> u64 {
    match kind(t) {
        // Dates within ±550 years of 1970, times of day within the day.
        K::Date => {
            let span = 400_000 * DAY as i128;
            let v = (x as i128 % (2 * span) - span) as i64;
            match t {
                E::Date | E::Ldate => (v.div_euclid(DAY) * DAY) as u64,
                E::Tod | E::Ltod => v.rem_euclid(DAY) as u64,
                _ => v as u64,
            }
        }
        _ if t == E::Real => x & 0xFFFF_FFFF,
        _ if int_like(t) => wrap(t, i128::from(x)),
        _ => x,
    }
}

/// Small values: for reals quarters (halves exercise the rounding rule),
/// for durations quarter milliseconds, for dates whole days.
fn small(t: E, x: i64) -> u64 {
    match t {
        E::Real | E::Lreal => real_slot(t, x as f64 / 4.0),
        E::Time | E::Ltime => (x * MS / 4) as u64,
        E::Date | E::Ldate => (x * 97 * DAY) as u64,
        E::Tod | E::Ltod => (x.rem_euclid(400) * (DAY / 400) + x.abs()) as u64,
        E::Dt | E::Ldt => (x * 97 * DAY / 7 + x) as u64,
        _ => wrap(t, i128::from(x)),
    }
}

fn edges(t: E) -> Vec<u64> {
    match t {
        E::Real => [
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            -2.5,
            127.5,
            -128.5,
            255.5,
            32767.5,
            -32768.5,
            65535.5,
            2147483520.0,
            4294967040.0,
            f32::MAX,
            f32::MIN,
            f32::EPSILON,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ]
        .iter()
        .map(|f| u64::from(f.to_bits()))
        .collect(),
        E::Lreal => [
            0.0f64,
            -0.0,
            0.5,
            -0.5,
            2.5,
            -2.5,
            127.5,
            -128.5,
            32767.5,
            -32768.5,
            2147483647.5,
            -2147483648.5,
            4294967295.5,
            9.2e18,
            -9.2e18,
            1.8e19,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ]
        .iter()
        .map(|f| f.to_bits())
        .collect(),
        E::Time | E::Ltime | E::Dt | E::Ldt => [
            0,
            1,
            -1,
            MS,
            -MS,
            i64::MAX,
            i64::MIN,
            i64::MAX - MS,
            32_767 * MS,
            32_768 * MS,
            -32_768 * MS,
            -32_769 * MS,
        ]
        .iter()
        .map(|x| *x as u64)
        .collect(),
        E::Date | E::Ldate => vec![0, DAY as u64, (-DAY) as u64],
        E::Tod | E::Ltod => vec![0, (DAY - 1) as u64, (DAY / 2) as u64],
        _ => {
            let (lo, hi) = range(t);
            [lo, hi, 0, 1, -1, lo + 1, hi - 1, 2, -2]
                .iter()
                .map(|v| wrap(t, *v))
                .collect()
        }
    }
}

/// `FROM_TO_TO` of raw `x`, or `None` when the model has no such
/// conversion (docs/semantics.md §3; strings aside).
pub fn convert(f: E, t: E, x: u64) -> Option<Out> {
    let (kf, kt) = (kind(f), kind(t));
    if kf == K::Str || kt == K::Str {
        return None;
    }
    if f == t {
        return Some(Out::V(t, x));
    }
    Some(match (kf, kt) {
        (_, K::Bool) if int_like(f) => Out::V(t, u64::from(x != 0)),
        // To or from a bit string: the bit pattern, cut or extended.
        (K::Bits, _) | (_, K::Bits) if int_like(f) && int_like(t) => Out::V(t, wrap(t, num(f, x))),
        // Between numbers: the value, which must fit.
        _ if int_like(f) && int_like(t) => checked(t, num(f, x)),
        (_, K::Real) if int_like(f) => Out::V(t, to_real(t, num(f, x))),
        (K::Real, _) if int_like(t) && kt != K::Bool => real_to_int(t, real(f, x)),
        (K::Real, K::Real) => Out::V(t, real_slot(t, real(f, x))),
        (K::Dur, K::Dur) => Out::V(t, x),
        // Durations count milliseconds (truncated toward zero).
        (K::Dur, _) if int_like(t) && kt != K::Bool => checked(t, num(f, x) / i128::from(MS)),
        (_, K::Dur) if int_like(f) => ms_to_time(t, num(f, x) * i128::from(MS)),
        (K::Dur, K::Real) => Out::V(t, real_slot(t, num(f, x) as f64 / MS as f64)),
        (K::Real, K::Dur) => real_ms_to_time(t, real(f, x)),
        (K::Date, K::Date) => return date_convert(f, t, x),
        // Beyond edition 3 (CODESYS): REAL to BOOL is "not zero" (NaN is
        // not zero), so are durations and dates.
        (K::Real, K::Bool) => bool_of(real(f, x) != 0.0),
        (K::Dur | K::Date, K::Bool) => bool_of(x != 0),
        // A date converts as its count (seconds, milliseconds or
        // nanoseconds), which converts like a LINT.
        (K::Date, _) if int_like(t) || kt == K::Real => {
            return convert(E::Lint, t, date_count(f, x as i64) as u64);
        }
        (_, K::Date) if int_like(f) || kf == K::Real => match convert(f, E::Lint, x)? {
            Out::V(_, n) => date_of_count(t, i128::from(n as i64)),
            fault => fault,
        },
        (K::Date, K::Dur) if matches!(f, E::Tod | E::Ltod) => Out::V(t, x),
        (K::Dur, K::Date) if matches!(t, E::Tod | E::Ltod) => {
            Out::V(t, (x as i64).rem_euclid(DAY) as u64)
        }
        _ => return None,
    })
}

fn bool_of(b: bool) -> Out {
    Out::V(E::Bool, u64::from(b))
}

/// Nanoseconds in one count of date type `t`: a second for DATE and DT,
/// a millisecond for TOD, one for the long forms.
fn count_unit(t: E) -> i128 {
    match t {
        E::Date | E::Dt => 1_000_000_000,
        E::Tod => i128::from(MS),
        _ => 1,
    }
}

/// The count date `t` (nanoseconds `ns`) converts as, rounded down.
fn date_count(t: E, ns: i64) -> i128 {
    i128::from(ns).div_euclid(count_unit(t))
}

/// Date `t` at `n` counts: a date rounded down to its midnight, a time of
/// day wrapped around midnight; beyond 64-bit nanoseconds is R004.
fn date_of_count(t: E, n: i128) -> Out {
    let ns = n * count_unit(t);
    let fit = |v: i128| match i64::try_from(v) {
        Ok(v) => Out::V(t, v as u64),
        Err(_) => Out::Fault("R004"),
    };
    if i64::try_from(ns).is_err() {
        return Out::Fault("R004");
    }
    match t {
        E::Date | E::Ldate => fit(ns.div_euclid(i128::from(DAY)) * i128::from(DAY)),
        E::Tod | E::Ltod => fit(ns.rem_euclid(i128::from(DAY))),
        _ => fit(ns),
    }
}

fn to_real(t: E, v: i128) -> u64 {
    if t == E::Real {
        u64::from((v as f32).to_bits())
    } else {
        (v as f64).to_bits()
    }
}

/// REAL/LREAL to an integer-like type: rounded, halves away from zero;
/// NaN, infinities and values outside the range fault.
pub fn real_to_int(t: E, v: f64) -> Out {
    match integral(round_half_away(v)) {
        Some(i) => checked(t, i),
        None => Out::Fault("R004"),
    }
}

/// TRUNC: toward zero; NaN, infinities and values outside the range fault.
pub fn real_trunc(t: E, v: f64) -> Out {
    match integral(v.trunc()) {
        Some(i) => checked(t, i),
        None => Out::Fault("R004"),
    }
}

fn ms_to_time(t: E, ns: i128) -> Out {
    match i64::try_from(ns) {
        Ok(v) => Out::V(t, v as u64),
        Err(_) => Out::Fault("R004"),
    }
}

fn real_ms_to_time(t: E, ms: f64) -> Out {
    match integral(round_half_away(ms * MS as f64)) {
        Some(ns) => ms_to_time(t, ns),
        None => Out::Fault("R004"),
    }
}

fn date_convert(f: E, t: E, x: u64) -> Option<Out> {
    let v = x as i64;
    let same = |a: E, b: E| [f, t] == [a, b] || [f, t] == [b, a];
    Some(match (f, t) {
        // The first day of the range has no midnight in range.
        (E::Dt | E::Ldt, E::Date | E::Ldate) => match v.div_euclid(DAY).checked_mul(DAY) {
            Some(d) => Out::V(t, d as u64),
            None => Out::Fault("R004"),
        },
        (E::Dt | E::Ldt, E::Tod | E::Ltod) => Out::V(t, v.rem_euclid(DAY) as u64),
        (E::Date | E::Ldate, E::Dt | E::Ldt) => Out::V(t, x),
        _ if same(E::Date, E::Ldate) || same(E::Tod, E::Ltod) || same(E::Dt, E::Ldt) => {
            Out::V(t, x)
        }
        _ => return None,
    })
}
