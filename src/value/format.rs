//! Values as IEC 61131-3 literal text, the way traces and messages print them.
//!
//! The input is an elementary type and the raw 64-bit slot (see
//! [`crate::elementary`] for the encoding). Printing rules:
//!
//! | type | example |
//! |---|---|
//! | BOOL | `TRUE`, `FALSE` (any non-zero slot is `TRUE`) |
//! | SINT .. LINT, USINT .. ULINT | `-32768`, `42` |
//! | BYTE .. LWORD | `16#FF` (upper-case hex, no padding) |
//! | REAL, LREAL | `1.0`, `0.1`, `-2.5`, `1.0E+20`, `1.5E-07`, `NaN`, `INF`, `-INF` |
//! | TIME, LTIME | `T#1s500ms`, `T#0s`, `T#-2ms`, `LT#5us` |
//! | DATE, LDATE | `D#2024-01-31`, `LDATE#1969-12-31` |
//! | TOD, LTOD | `TOD#12:30:15`, `TOD#12:30:15.5`, `LTOD#00:00:00.000000001` |
//! | DT, LDT | `DT#2024-01-31-12:30:15`, `LDT#2024-01-31-12:30:15.25` |
//! | CHAR, WCHAR | `'A'`, `'$''`, `"A"`, `"$""` |
//!
//! Reals print the shortest decimal that reads back to the same value of their
//! own width (`REAL#0.1` prints `0.1`, not `0.10000000149011612`). The
//! exponent form `d.dddE±XX` (at least two exponent digits) is used when the
//! decimal exponent of the value is ≥ 16 or ≤ -5; otherwise plain decimal
//! notation is used. Either way the text always has a `.` or an exponent.
//!
//! Only the slot's width is looked at: bits above the type's width are ignored.
//! Date and time-of-day values are split with Euclidean division, so slots
//! before 1970 print as earlier dates and a TOD slot outside one day wraps
//! modulo 24 hours. Nothing here panics, whatever the slot holds.

use crate::elementary::ElemType;
use crate::value::literal::format_duration;
use std::fmt::Write;

const NANOS_PER_DAY: i64 = 86_400_000_000_000;
const NANOS_PER_SEC: i64 = 1_000_000_000;

/// A value as printed in traces: the IEC literal text.
///
/// Covers every elementary type except STRING and WSTRING, whose slots hold
/// an index into the string store (use [`format_string`] on the text); for
/// those this returns `<STRING #index>` / `<WSTRING #index>`.
pub fn format_value(ty: ElemType, raw: u64) -> String {
    let mut out = String::new();
    write_value(&mut out, ty, raw);
    out
}

/// Appends the text [`format_value`] would return to `out`, so that callers
/// printing many values can reuse one buffer.
pub fn write_value(out: &mut String, ty: ElemType, raw: u64) {
    use ElemType::*;
    // `write!` into a `String` cannot fail.
    let _ = match ty {
        Bool => {
            out.push_str(if raw != 0 { "TRUE" } else { "FALSE" });
            Ok(())
        }
        Sint => write!(out, "{}", raw as i8),
        Int => write!(out, "{}", raw as i16),
        Dint => write!(out, "{}", raw as i32),
        Lint => write!(out, "{}", raw as i64),
        Usint => write!(out, "{}", raw as u8),
        Uint => write!(out, "{}", raw as u16),
        Udint => write!(out, "{}", raw as u32),
        Ulint => write!(out, "{raw}"),
        Byte => write!(out, "16#{:X}", raw as u8),
        Word => write!(out, "16#{:X}", raw as u16),
        Dword => write!(out, "16#{:X}", raw as u32),
        Lword => write!(out, "16#{raw:X}"),
        Real => {
            write_real(out, f32::from_bits(raw as u32));
            Ok(())
        }
        Lreal => {
            write_real(out, f64::from_bits(raw));
            Ok(())
        }
        Time => {
            out.push_str(&format_duration(raw as i64, "T#"));
            Ok(())
        }
        Ltime => {
            out.push_str(&format_duration(raw as i64, "LT#"));
            Ok(())
        }
        Date | Ldate => {
            out.push_str(if ty == Date { "D#" } else { "LDATE#" });
            write_date(out, (raw as i64).div_euclid(NANOS_PER_DAY));
            Ok(())
        }
        Tod | Ltod => {
            out.push_str(if ty == Tod { "TOD#" } else { "LTOD#" });
            write_time_of_day(out, (raw as i64).rem_euclid(NANOS_PER_DAY));
            Ok(())
        }
        Dt | Ldt => {
            out.push_str(if ty == Dt { "DT#" } else { "LDT#" });
            let nanos = raw as i64;
            write_date(out, nanos.div_euclid(NANOS_PER_DAY));
            out.push('-');
            write_time_of_day(out, nanos.rem_euclid(NANOS_PER_DAY));
            Ok(())
        }
        Char => {
            out.push('\'');
            let byte = raw as u8;
            if byte.is_ascii() {
                push_escaped(out, char::from(byte), false);
            } else {
                // A non-ASCII byte has no single meaning as text: keep it exact.
                let _ = write!(out, "${byte:02X}");
            }
            out.push('\'');
            Ok(())
        }
        Wchar => {
            out.push('"');
            let unit = raw as u16;
            match char::from_u32(u32::from(unit)) {
                Some(c) => push_escaped(out, c, true),
                // A lone surrogate: print the code unit.
                None => {
                    let _ = write!(out, "${unit:04X}");
                }
            }
            out.push('"');
            Ok(())
        }
        String => write!(out, "<STRING #{raw}>"),
        WString => write!(out, "<WSTRING #{raw}>"),
    };
}

/// A STRING (`wide == false`) or WSTRING (`wide == true`) value as an IEC
/// literal: `'it$'s'`, `"say $"hi$""`.
///
/// Escapes: `$$`, `$'` (STRING) or `$"` (WSTRING), `$N` for a line feed,
/// `$R`, `$T`, `$P` (form feed); any other control character becomes `$hh`
/// in a STRING and `$hhhh` in a WSTRING (upper-case hex). Other characters,
/// including non-ASCII ones, are printed as they are.
pub fn format_string(s: &str, wide: bool) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    let quote = if wide { '"' } else { '\'' };
    out.push(quote);
    for c in s.chars() {
        push_escaped(&mut out, c, wide);
    }
    out.push(quote);
    out
}

/// A value as JSON, for JSON-lines traces.
///
/// BOOL → `true`/`false`; SINT .. ULINT → JSON integers; REAL and LREAL → JSON
/// numbers with the same shortest digits as the text form (non-finite values
/// → the strings `"NaN"`, `"INF"`, `"-INF"`); every other type → its literal
/// text ([`format_value`]) as a JSON string.
pub fn json_value(ty: ElemType, raw: u64) -> serde_json::Value {
    use ElemType::*;
    use serde_json::Value;
    match ty {
        Bool => Value::Bool(raw != 0),
        Sint => Value::from(raw as i8),
        Int => Value::from(raw as i16),
        Dint => Value::from(raw as i32),
        Lint => Value::from(raw as i64),
        Usint => Value::from(raw as u8),
        Uint => Value::from(raw as u16),
        Udint => Value::from(raw as u32),
        Ulint => Value::from(raw),
        Real => json_real(f32::from_bits(raw as u32)),
        Lreal => json_real(f64::from_bits(raw)),
        _ => Value::String(format_value(ty, raw)),
    }
}

/// Converts days since 1970-01-01 into a proleptic Gregorian
/// `(year, month, day)`; negative days are dates before 1970.
pub fn civil_from_days(days: i64) -> (i64, u32, u32) {
    // Howard Hinnant's algorithm, with eras of 400 years (146 097 days)
    // starting on 0000-03-01. `days` comes from nanoseconds in an i64, so it
    // is far from overflowing here.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let day_of_era = z.rem_euclid(146_097);
    let year_of_era =
        (day_of_era - day_of_era / 1_460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_from_march = (5 * day_of_year + 2) / 153;
    let day = day_of_year - (153 * month_from_march + 2) / 5 + 1;
    let month = if month_from_march < 10 {
        month_from_march + 3
    } else {
        month_from_march - 9
    };
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    (year, month as u32, day as u32)
}

/// Converts a proleptic Gregorian date into days since 1970-01-01 (the
/// inverse of [`civil_from_days`]). The date is not validated: month 13 or
/// day 32 roll over.
pub fn days_from_civil(year: i64, month: u32, day: u32) -> i64 {
    let year = year - i64::from(month <= 2);
    let era = year.div_euclid(400);
    let year_of_era = year.rem_euclid(400);
    let month = i64::from(month);
    let month_from_march = if month > 2 { month - 3 } else { month + 9 };
    let day_of_year = (153 * month_from_march + 2) / 5 + i64::from(day) - 1;
    let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    era * 146_097 + day_of_era - 719_468
}

/// `yyyy-mm-dd` for days since 1970-01-01.
fn write_date(out: &mut String, days: i64) {
    let (year, month, day) = civil_from_days(days);
    let _ = write!(out, "{year:04}-{month:02}-{day:02}");
}

/// `hh:mm:ss` plus `.f..` (trailing zeros trimmed) when the nanoseconds are
/// not zero; `nanos` is in `0..NANOS_PER_DAY`.
fn write_time_of_day(out: &mut String, nanos: i64) {
    let secs = nanos / NANOS_PER_SEC;
    let frac = nanos % NANOS_PER_SEC;
    let _ = write!(
        out,
        "{:02}:{:02}:{:02}",
        secs / 3600,
        secs / 60 % 60,
        secs % 60
    );
    if frac != 0 {
        let start = out.len();
        let _ = write!(out, ".{frac:09}");
        let trimmed = out[start..].trim_end_matches('0').len();
        out.truncate(start + trimmed);
    }
}

/// The float widths we print; both have a shortest round-trip `Display`
/// and `LowerExp` in std.
trait IecFloat: Copy + std::fmt::Display + std::fmt::LowerExp {
    fn is_nan(self) -> bool;
    fn is_infinite(self) -> bool;
    fn is_sign_negative(self) -> bool;
}

impl IecFloat for f32 {
    fn is_nan(self) -> bool {
        f32::is_nan(self)
    }
    fn is_infinite(self) -> bool {
        f32::is_infinite(self)
    }
    fn is_sign_negative(self) -> bool {
        f32::is_sign_negative(self)
    }
}

impl IecFloat for f64 {
    fn is_nan(self) -> bool {
        f64::is_nan(self)
    }
    fn is_infinite(self) -> bool {
        f64::is_infinite(self)
    }
    fn is_sign_negative(self) -> bool {
        f64::is_sign_negative(self)
    }
}

/// Decimal exponents at or beyond these use the exponent form.
const EXP_FORM_MIN: i32 = 16;
const EXP_FORM_MAX_NEG: i32 = -5;

/// Appends a real in the shortest round-trip form (see the module docs).
fn write_real<F: IecFloat>(out: &mut String, value: F) {
    if value.is_nan() {
        out.push_str("NaN");
        return;
    }
    if value.is_infinite() {
        out.push_str(if value.is_sign_negative() {
            "-INF"
        } else {
            "INF"
        });
        return;
    }
    // std's `{:e}` prints the shortest digits that round-trip at this width,
    // as `-d.ddde-7`; we only re-dress the exponent.
    let start = out.len();
    let _ = write!(out, "{value:e}");
    let Some(e_at) = out[start..].find('e').map(|i| start + i) else {
        return;
    };
    let exponent: i32 = out[e_at + 1..].parse().unwrap_or(0);
    if exponent >= EXP_FORM_MIN || exponent <= EXP_FORM_MAX_NEG {
        out.truncate(e_at);
        if !out[start..].contains('.') {
            out.push_str(".0");
        }
        let sign = if exponent < 0 { '-' } else { '+' };
        let _ = write!(out, "E{sign}{:02}", exponent.unsigned_abs());
    } else {
        // `Display` is also shortest round-trip and never uses an exponent.
        out.truncate(start);
        let _ = write!(out, "{value}");
        if !out[start..].contains('.') {
            out.push_str(".0");
        }
    }
}

fn json_real<F: IecFloat>(value: F) -> serde_json::Value {
    let mut text = String::new();
    write_real(&mut text, value);
    if value.is_nan() || value.is_infinite() {
        return serde_json::Value::String(text);
    }
    // The shortest text has at most 17 significant digits, so the f64 read
    // back from it prints with the same digits again (for REAL this avoids
    // the widening noise of `0.1f32 as f64`).
    text.parse::<f64>()
        .ok()
        .and_then(serde_json::Number::from_f64)
        .map_or(serde_json::Value::String(text), serde_json::Value::Number)
}

/// Appends one character of a STRING (`'`-quoted) or WSTRING (`"`-quoted)
/// literal body, escaped.
fn push_escaped(out: &mut String, c: char, wide: bool) {
    match c {
        '$' => out.push_str("$$"),
        '\'' if !wide => out.push_str("$'"),
        '"' if wide => out.push_str("$\""),
        '\n' => out.push_str("$N"),
        '\r' => out.push_str("$R"),
        '\t' => out.push_str("$T"),
        '\u{0C}' => out.push_str("$P"),
        c if c.is_control() => {
            // Control characters are all below U+0100.
            let _ = if wide {
                write!(out, "${:04X}", u32::from(c))
            } else {
                write!(out, "${:02X}", u32::from(c))
            };
        }
        c => out.push(c),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ElemType::*;
    use rstest::rstest;
    use serde_json::json;

    fn f32_slot(v: f32) -> u64 {
        u64::from(v.to_bits())
    }

    fn f64_slot(v: f64) -> u64 {
        v.to_bits()
    }

    const SEC: i64 = NANOS_PER_SEC;
    const DAY: i64 = NANOS_PER_DAY;

    #[rstest]
    #[case(Bool, 0, "FALSE")]
    #[case(Bool, 1, "TRUE")]
    #[case(Sint, (-128i64) as u64, "-128")]
    #[case(Int, (-32768i64) as u64, "-32768")]
    #[case(Int, 42, "42")]
    #[case(Dint, (-1i64) as u64, "-1")]
    #[case(Lint, i64::MIN as u64, "-9223372036854775808")]
    #[case(Usint, 255, "255")]
    #[case(Uint, 65535, "65535")]
    #[case(Udint, 4_294_967_295, "4294967295")]
    #[case(Ulint, u64::MAX, "18446744073709551615")]
    #[case(Byte, 0xFF, "16#FF")]
    #[case(Byte, 0, "16#0")]
    #[case(Word, 0x0A0B, "16#A0B")]
    #[case(Dword, 0xDEAD_BEEF, "16#DEADBEEF")]
    #[case(Lword, u64::MAX, "16#FFFFFFFFFFFFFFFF")]
    // Bits above the type's width are ignored.
    #[case(Int, 0xFFFF_0000_0000_0005, "5")]
    #[case(Byte, 0x1FF, "16#FF")]
    fn integers_and_bits(#[case] ty: ElemType, #[case] raw: u64, #[case] text: &str) {
        assert_eq!(format_value(ty, raw), text);
    }

    #[rstest]
    #[case(1.0, "1.0")]
    #[case(0.1, "0.1")]
    #[case(-2.5, "-2.5")]
    #[case(0.0, "0.0")]
    #[case(-0.0, "-0.0")]
    #[case(16_777_216.0, "16777216.0")]
    #[case(1e20, "1.0E+20")]
    #[case(1.5e-7, "1.5E-07")]
    #[case(1e16, "1.0E+16")]
    #[case(1e15, "1000000000000000.0")]
    #[case(1e-4, "0.0001")]
    #[case(1e-5, "1.0E-05")]
    #[case(3.402_823_5e38, "3.4028235E+38")]
    #[case(1e-45, "1.0E-45")]
    #[case(0.3, "0.3")]
    #[case(123.456, "123.456")]
    #[case(f32::NAN, "NaN")]
    #[case(f32::INFINITY, "INF")]
    #[case(f32::NEG_INFINITY, "-INF")]
    fn reals(#[case] value: f32, #[case] text: &str) {
        assert_eq!(format_value(Real, f32_slot(value)), text);
    }

    #[rstest]
    #[case(1.0, "1.0")]
    #[case(0.1, "0.1")]
    #[case(0.1 + 0.2, "0.30000000000000004")]
    #[case(-2.5, "-2.5")]
    #[case(-0.0, "-0.0")]
    #[case(1e20, "1.0E+20")]
    #[case(1.5e-7, "1.5E-07")]
    #[case(1e300, "1.0E+300")]
    #[case(-1.2345e-300, "-1.2345E-300")]
    #[case(f64::MAX, "1.7976931348623157E+308")]
    #[case(5e-324, "5.0E-324")]
    #[case(9_007_199_254_740_993.0, "9007199254740992.0")]
    #[case(1.0e16 + 2.0, "1.0000000000000002E+16")]
    #[case(f64::NAN, "NaN")]
    #[case(f64::NEG_INFINITY, "-INF")]
    fn lreals(#[case] value: f64, #[case] text: &str) {
        assert_eq!(format_value(Lreal, f64_slot(value)), text);
    }

    #[test]
    fn reals_read_back_to_the_same_value() {
        let samples32 = [
            0.1f32,
            1.0 / 3.0,
            2.0f32.sqrt(),
            1e-38,
            7e-45,
            123_456_790.0,
        ];
        for v in samples32 {
            let text = format_value(Real, f32_slot(v));
            let back: f32 = text.replace('E', "e").parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{text}");
        }
        let samples64 = [0.1f64, 1.0 / 3.0, std::f64::consts::PI, 2.2e-308, 6.02e23];
        for v in samples64 {
            let text = format_value(Lreal, f64_slot(v));
            let back: f64 = text.replace('E', "e").parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{text}");
        }
    }

    #[rstest]
    #[case(Time, 0, "T#0s")]
    #[case(Time, 1_500_000_000, "T#1s500ms")]
    #[case(Time, (-2_000_000i64) as u64, "T#-2ms")]
    #[case(Time, 600 * SEC as u64, "T#10m")]
    #[case(Ltime, 5_000, "LT#5us")]
    #[case(Ltime, 0, "LT#0s")]
    fn durations(#[case] ty: ElemType, #[case] raw: u64, #[case] text: &str) {
        assert_eq!(format_value(ty, raw), text);
    }

    #[rstest]
    #[case(0, (1970, 1, 1))]
    #[case(-1, (1969, 12, 31))]
    #[case(11_016, (2000, 2, 29))]
    #[case(19_753, (2024, 1, 31))]
    #[case(19_782, (2024, 2, 29))]
    #[case(19_417, (2023, 3, 1))]
    #[case(-24_048, (1904, 2, 29))]
    #[case(-25_567, (1900, 1, 1))]
    #[case(-135_081, (1600, 2, 29))]
    fn civil_dates(#[case] days: i64, #[case] ymd: (i64, u32, u32)) {
        assert_eq!(civil_from_days(days), ymd);
        assert_eq!(days_from_civil(ymd.0, ymd.1, ymd.2), days);
    }

    #[test]
    fn civil_dates_round_trip_and_advance_one_day_at_a_time() {
        let mut prev = civil_from_days(-150_000);
        for days in -149_999..150_000 {
            let ymd = civil_from_days(days);
            assert_eq!(days_from_civil(ymd.0, ymd.1, ymd.2), days);
            let next_day = (prev.0, prev.1, prev.2 + 1);
            let next_month = (prev.0, prev.1 + 1, 1);
            let next_year = (prev.0 + 1, 1, 1);
            assert!(
                ymd == next_day || ymd == next_month || ymd == next_year,
                "{prev:?} -> {ymd:?}"
            );
            prev = ymd;
        }
    }

    #[rstest]
    #[case(Date, 0, "D#1970-01-01")]
    #[case(Date, 19_753 * DAY, "D#2024-01-31")]
    #[case(Date, 11_016 * DAY, "D#2000-02-29")]
    #[case(Date, -DAY, "D#1969-12-31")]
    // Part of a day before 1970 still belongs to the day before.
    #[case(Date, -1, "D#1969-12-31")]
    #[case(Ldate, 19_782 * DAY, "LDATE#2024-02-29")]
    #[case(Tod, 0, "TOD#00:00:00")]
    #[case(Tod, (12 * 3600 + 30 * 60 + 15) * SEC, "TOD#12:30:15")]
    #[case(Tod, (12 * 3600 + 30 * 60 + 15) * SEC + 500_000_000, "TOD#12:30:15.5")]
    #[case(Tod, DAY - 1, "TOD#23:59:59.999999999")]
    #[case(Tod, DAY + SEC, "TOD#00:00:01")]
    #[case(Ltod, 1, "LTOD#00:00:00.000000001")]
    #[case(Ltod, 10_000_000, "LTOD#00:00:00.01")]
    #[case(Dt, 0, "DT#1970-01-01-00:00:00")]
    #[case(Dt, 19_753 * DAY + (12 * 3600 + 30 * 60 + 15) * SEC, "DT#2024-01-31-12:30:15")]
    #[case(Dt, 19_753 * DAY + (12 * 3600 + 30 * 60 + 15) * SEC + 125_000_000, "DT#2024-01-31-12:30:15.125")]
    #[case(Dt, -SEC / 2, "DT#1969-12-31-23:59:59.5")]
    #[case(Ldt, 11_016 * DAY + 86_399 * SEC, "LDT#2000-02-29-23:59:59")]
    #[case(Ldt, i64::MIN, "LDT#1677-09-21-00:12:43.145224192")]
    #[case(Ldt, i64::MAX, "LDT#2262-04-11-23:47:16.854775807")]
    fn dates_and_times(#[case] ty: ElemType, #[case] nanos: i64, #[case] text: &str) {
        assert_eq!(format_value(ty, nanos as u64), text);
    }

    #[rstest]
    #[case(Char, b'A' as u64, "'A'")]
    #[case(Char, b'\'' as u64, "'$''")]
    #[case(Char, b'"' as u64, "'\"'")]
    #[case(Char, b'$' as u64, "'$$'")]
    #[case(Char, b'\n' as u64, "'$N'")]
    #[case(Char, 0, "'$00'")]
    #[case(Char, 0xE9, "'$E9'")]
    #[case(Wchar, 'A' as u64, "\"A\"")]
    #[case(Wchar, '"' as u64, "\"$\"\"")]
    #[case(Wchar, '\'' as u64, "\"'\"")]
    #[case(Wchar, 'é' as u64, "\"é\"")]
    #[case(Wchar, 0x7F, "\"$007F\"")]
    #[case(Wchar, 0xD800, "\"$D800\"")]
    fn chars(#[case] ty: ElemType, #[case] raw: u64, #[case] text: &str) {
        assert_eq!(format_value(ty, raw), text);
    }

    #[rstest]
    #[case("", false, "''")]
    #[case("it's", false, "'it$'s'")]
    #[case("say \"hi\"", false, "'say \"hi\"'")]
    #[case("say \"hi\"", true, "\"say $\"hi$\"\"")]
    #[case("it's", true, "\"it's\"")]
    #[case("5$ a\nb\r\tc\u{0C}", false, "'5$$ a$Nb$R$Tc$P'")]
    #[case("bell\u{07}", false, "'bell$07'")]
    #[case("bell\u{07}", true, "\"bell$0007\"")]
    #[case("a,b", false, "'a,b'")]
    #[case("Grüße", false, "'Grüße'")]
    fn strings(#[case] s: &str, #[case] wide: bool, #[case] text: &str) {
        assert_eq!(format_string(s, wide), text);
    }

    #[test]
    fn string_slots_do_not_panic() {
        assert_eq!(format_value(String, 3), "<STRING #3>");
        assert_eq!(format_value(WString, 0), "<WSTRING #0>");
    }

    #[test]
    fn every_type_formats_any_slot_without_panicking() {
        for ty in ElemType::ALL {
            for raw in [0, 1, u64::MAX, i64::MIN as u64, 0x7FF8_0000_0000_0001] {
                assert!(!format_value(ty, raw).is_empty());
                let _ = json_value(ty, raw);
            }
        }
    }

    #[test]
    fn write_value_appends() {
        let mut buf = "x=".to_string();
        write_value(&mut buf, Int, 7);
        assert_eq!(buf, "x=7");
    }

    #[rstest]
    #[case(Bool, 1, json!(true))]
    #[case(Bool, 0, json!(false))]
    #[case(Int, (-5i64) as u64, json!(-5))]
    #[case(Ulint, u64::MAX, json!(u64::MAX))]
    #[case(Lint, i64::MIN as u64, json!(i64::MIN))]
    #[case(Byte, 0xFF, json!("16#FF"))]
    #[case(Time, 1_500_000_000, json!("T#1s500ms"))]
    #[case(Date, 0, json!("D#1970-01-01"))]
    #[case(Char, b'A' as u64, json!("'A'"))]
    #[case(Real, f32_slot(f32::NAN), json!("NaN"))]
    #[case(Real, f32_slot(f32::INFINITY), json!("INF"))]
    #[case(Lreal, f64_slot(f64::NEG_INFINITY), json!("-INF"))]
    fn json_values(#[case] ty: ElemType, #[case] raw: u64, #[case] value: serde_json::Value) {
        assert_eq!(json_value(ty, raw), value);
    }

    #[rstest]
    #[case(Real, f32_slot(0.1), "0.1")]
    #[case(Real, f32_slot(1e20), "1e+20")]
    #[case(Real, f32_slot(-2.5), "-2.5")]
    #[case(Real, f32_slot(1.0), "1.0")]
    #[case(Lreal, f64_slot(0.1), "0.1")]
    #[case(Lreal, f64_slot(1.5e-7), "1.5e-7")]
    fn json_reals_keep_the_shortest_digits(
        #[case] ty: ElemType,
        #[case] raw: u64,
        #[case] text: &str,
    ) {
        assert_eq!(json_value(ty, raw).to_string(), text);
    }
}
