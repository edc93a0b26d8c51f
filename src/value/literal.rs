//! IEC literal text (the part after `T#`, `16#`, `D#`, ...) decoded into
//! numbers and printed back: used by the lexer, the stimulus reader, the
//! command line and the trace, without the lexer itself.

use crate::value::format::days_from_civil;

/// Nanoseconds per duration unit, largest first, with their IEC suffixes.
pub const DURATION_UNITS: [(&str, i128); 7] = [
    ("d", 86_400_000_000_000),
    ("h", 3_600_000_000_000),
    ("m", 60_000_000_000),
    ("s", 1_000_000_000),
    ("ms", 1_000_000),
    ("us", 1_000),
    ("ns", 1),
];

/// Parses the body of a duration literal (what follows `T#`, `TIME#`, `LT#`),
/// such as `1h2m3s`, `1.5s`, `-250ms`, `1d_2h`, `12m30s500ms`, into signed
/// nanoseconds. Units are case-insensitive; `_` separators are allowed; only
/// the last part may have a fraction.
pub fn parse_duration_body(body: &str) -> Result<i64, String> {
    let total = parse_duration_wide(body)?;
    i64::try_from(total).map_err(|_| format!("duration `{body}` is out of range"))
}

/// [`parse_duration_body`] without the range of an `i64`: the nanoseconds
/// as written (TwinCAT's LTIME reaches 2^64 - 1).
pub fn parse_duration_wide(body: &str) -> Result<i128, String> {
    let text: String = body
        .chars()
        .filter(|c| *c != '_')
        .collect::<String>()
        .to_ascii_lowercase();
    let (negative, mut rest) = match text.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, text.strip_prefix('+').unwrap_or(&text)),
    };
    if rest.is_empty() {
        return Err(format!("empty duration `{body}`"));
    }
    let mut total: i128 = 0;
    let mut last_rank: Option<usize> = None;
    let mut saw_fraction = false;
    while !rest.is_empty() {
        let num_len = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(rest.len());
        if num_len == 0 {
            return Err(format!("expected a number in duration `{body}`"));
        }
        let number = &rest[..num_len];
        rest = &rest[num_len..];
        let unit_len = rest
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(rest.len());
        let unit = &rest[..unit_len];
        rest = &rest[unit_len..];
        let Some(rank) = DURATION_UNITS.iter().position(|(u, _)| *u == unit) else {
            return Err(if unit.is_empty() {
                format!("missing unit (d, h, m, s, ms, us, ns) in duration `{body}`")
            } else {
                format!("unknown unit `{unit}` in duration `{body}`")
            });
        };
        if last_rank.is_some_and(|r| r >= rank) {
            return Err(format!(
                "units must go from largest to smallest in duration `{body}`"
            ));
        }
        if saw_fraction {
            return Err(format!(
                "only the last part of duration `{body}` may have a fraction"
            ));
        }
        last_rank = Some(rank);
        let scale = DURATION_UNITS[rank].1;
        let part = match number.split_once('.') {
            None => number
                .parse::<i128>()
                .map_err(|_| format!("number too large in duration `{body}`"))?
                .checked_mul(scale),
            Some((int, frac)) => {
                saw_fraction = true;
                if frac.contains('.') || (int.is_empty() && frac.is_empty()) {
                    return Err(format!("malformed number in duration `{body}`"));
                }
                let int: i128 = if int.is_empty() {
                    0
                } else {
                    int.parse()
                        .map_err(|_| format!("number too large in duration `{body}`"))?
                };
                let mut frac_ns: i128 = 0;
                let mut div: i128 = 1;
                for c in frac.chars().take(18) {
                    frac_ns = frac_ns * 10 + (c as i128 - '0' as i128);
                    div *= 10;
                }
                int.checked_mul(scale)
                    .and_then(|v| v.checked_add(frac_ns * scale / div))
            }
        };
        total = part
            .and_then(|p| total.checked_add(p))
            .ok_or_else(|| format!("duration `{body}` is out of range"))?;
    }
    if negative {
        total = -total;
    }
    Ok(total)
}

/// Formats nanoseconds as an IEC duration literal: largest unit first, zero
/// parts omitted, `T#0s` for zero, `T#-2ms` for negatives. `prefix` is `T#`
/// or `LT#`.
pub fn format_duration(nanos: i64, prefix: &str) -> String {
    let mut out = String::new();
    write_duration(&mut out, nanos, prefix);
    out
}

/// Appends [`format_duration`]'s text to `out`, without allocating beyond
/// `out`'s growth: the trace writes one per row.
pub fn write_duration(out: &mut String, nanos: i64, prefix: &str) {
    out.push_str(prefix);
    if nanos == 0 {
        out.push_str("0s");
        return;
    }
    if nanos < 0 {
        out.push('-');
    }
    // |i64::MIN| fits in u64, and every unit's scale does too.
    write_magnitude(out, nanos.unsigned_abs());
}

/// A duration of `nanos` nanoseconds read as unsigned, as TwinCAT's LTIME
/// is (up to `LT#213503d23h34m33s709ms551us615ns`), after `prefix`.
pub fn write_unsigned_duration(out: &mut String, nanos: u64, prefix: &str) {
    out.push_str(prefix);
    if nanos == 0 {
        out.push_str("0s");
        return;
    }
    write_magnitude(out, nanos);
}

/// `rest` nanoseconds in days, hours ... nanoseconds, the zero units left out.
fn write_magnitude(out: &mut String, mut rest: u64) {
    use std::fmt::Write as _;
    for (unit, scale) in DURATION_UNITS {
        let scale = scale as u64;
        let n = rest / scale;
        if n > 0 {
            let _ = write!(out, "{n}");
            out.push_str(unit);
            rest -= n * scale;
        }
    }
}

/// Parses an integer literal: decimal (`1_000`) or based (`2#1010`,
/// `8#17`, `16#FF`, and CODESYS's explicit decimal `10#123`), without sign.
pub fn parse_int_text(text: &str) -> Result<i128, String> {
    let (base, digits) = match text.split_once('#') {
        None => (10, text),
        Some((b, d)) => {
            let base = match b.replace('_', "").as_str() {
                "2" => 2,
                "8" => 8,
                "10" => 10,
                "16" => 16,
                _ => return Err(format!("base `{b}` is not 2, 8, 10 or 16 in `{text}`")),
            };
            (base, d)
        }
    };
    if digits.is_empty() {
        return Err(format!("missing digits in `{text}`"));
    }
    // Runs of underscores between digits are CODESYS's (the lexer warns,
    // W349); one at either end is no literal.
    if digits.starts_with('_') || digits.ends_with('_') {
        return Err(format!("misplaced `_` in `{text}`"));
    }
    let mut value: i128 = 0;
    for c in digits.chars().filter(|c| *c != '_') {
        let d = c
            .to_digit(base)
            .ok_or_else(|| format!("`{c}` is not a base-{base} digit in `{text}`"))?;
        value = value
            .checked_mul(i128::from(base))
            .and_then(|v| v.checked_add(i128::from(d)))
            .filter(|v| *v <= i128::from(u64::MAX))
            .ok_or_else(|| format!("integer `{text}` is too large"))?;
    }
    Ok(value)
}

/// Parses a real literal such as `1.5`, `1_000.25`, `1.5E-3`, `1e10`.
pub fn parse_real_text(text: &str) -> Result<f64, String> {
    let clean: String = text.chars().filter(|c| *c != '_').collect();
    let ok_shape = clean.starts_with(|c: char| c.is_ascii_digit())
        && clean
            .chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '+' | '-'));
    match clean.parse::<f64>() {
        Ok(v) if ok_shape && v.is_finite() => Ok(v),
        Ok(_) => Err(format!("real `{text}` is out of range")),
        Err(_) => Err(format!("malformed real `{text}`")),
    }
}

/// Decodes the inside of a string literal (without its quotes). `wide`
/// selects the WSTRING rules (`$"` and four-digit `$hhhh` codes) instead of
/// the STRING ones (`$'` and two-digit `$hh`). On error returns the byte
/// range (inside `inner`) of the bad escape and a message.
pub fn decode_string(inner: &str, wide: bool) -> Result<String, (usize, usize, String)> {
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c != '$' {
            out.push(c);
            continue;
        }
        let Some((_, e)) = chars.next() else {
            return Err((i, i + 1, "`$` at the end of a string".into()));
        };
        match e.to_ascii_uppercase() {
            '$' => out.push('$'),
            '\'' => out.push('\''),
            '"' => out.push('"'),
            'L' | 'N' => out.push('\n'),
            'P' => out.push('\u{0c}'),
            'R' => out.push('\r'),
            'T' => out.push('\t'),
            h if h.is_ascii_hexdigit() => {
                let want = if wide { 4 } else { 2 };
                let mut code = h.to_digit(16).unwrap_or(0);
                let mut end = i + 2;
                for _ in 1..want {
                    match chars.peek() {
                        Some(&(j, d)) if d.is_ascii_hexdigit() => {
                            code = code * 16 + d.to_digit(16).unwrap_or(0);
                            end = j + 1;
                            chars.next();
                        }
                        _ => {
                            return Err((
                                i,
                                end,
                                format!("`$` code needs {want} hexadecimal digits"),
                            ));
                        }
                    }
                }
                match char::from_u32(code) {
                    Some(ch) => out.push(ch),
                    None => return Err((i, end, format!("`$` code {code:#x} is not a character"))),
                }
            }
            _ => {
                let end = i + 1 + e.len_utf8();
                return Err((
                    i,
                    end,
                    format!("unknown escape `${e}` (use $$ $' $\" $L $N $P $R $T or $hh)"),
                ));
            }
        }
    }
    Ok(out)
}

/// Nanoseconds per day.
const NANOS_PER_DAY: i128 = 86_400_000_000_000;

fn is_leap(year: i64) -> bool {
    (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
}

fn days_in_month(year: i64, month: u32) -> u32 {
    match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        _ if is_leap(year) => 29,
        _ => 28,
    }
}

/// Splits `s` on `sep` into exactly `n` unsigned numeric fields (`_` allowed).
fn fields(s: &str, sep: char, n: usize, what: &str) -> Result<Vec<u64>, String> {
    let parts: Vec<&str> = s.split(sep).collect();
    if parts.len() != n {
        return Err(format!("malformed {what} `{s}`"));
    }
    parts
        .iter()
        .map(|p| {
            let p: String = p.chars().filter(|c| *c != '_').collect();
            if p.is_empty() || !p.chars().all(|c| c.is_ascii_digit()) || p.len() > 9 {
                Err(format!("malformed {what} `{s}`"))
            } else {
                p.parse::<u64>()
                    .map_err(|_| format!("malformed {what} `{s}`"))
            }
        })
        .collect()
}

/// Parses the body of a date literal (`2024-01-31`) into nanoseconds since
/// 1970-01-01.
pub fn parse_date_body(body: &str) -> Result<i64, String> {
    let f = fields(body, '-', 3, "date")?;
    let (y, m, d) = (f[0] as i64, f[1] as u32, f[2] as u32);
    if !(1..=12).contains(&m) {
        return Err(format!("month {m} is not 1..12 in date `{body}`"));
    }
    if d == 0 || d > days_in_month(y, m) {
        return Err(format!(
            "day {d} does not exist in month {m} of date `{body}`"
        ));
    }
    let nanos = i128::from(days_from_civil(y, m, d)) * NANOS_PER_DAY;
    i64::try_from(nanos).map_err(|_| format!("date `{body}` is out of range (1678..2262)"))
}

/// Parses the body of a time-of-day literal (`12:00:00.5`, seconds
/// optional) into nanoseconds since midnight.
pub fn parse_tod_body(body: &str) -> Result<i64, String> {
    let (hms, frac) = match body.split_once('.') {
        Some((a, b)) => (a, Some(b)),
        None => (body, None),
    };
    let parts = hms.split(':').count();
    if !(2..=3).contains(&parts) {
        return Err(format!(
            "malformed time of day `{body}` (expected hh:mm:ss)"
        ));
    }
    let f = fields(hms, ':', parts, "time of day")?;
    let (h, m, s) = (f[0], f[1], f.get(2).copied().unwrap_or(0));
    if h > 23 || m > 59 || s > 59 {
        return Err(format!("time of day `{body}` is out of range"));
    }
    let mut nanos = ((h * 60 + m) * 60 + s) as i64 * 1_000_000_000;
    if let Some(frac) = frac {
        if parts != 3 {
            return Err(format!("malformed time of day `{body}`"));
        }
        let digits: String = frac.chars().filter(|c| *c != '_').collect();
        if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) {
            return Err(format!("malformed fraction in time of day `{body}`"));
        }
        let mut scale = 100_000_000;
        for c in digits.chars().take(9) {
            nanos += i64::from(c as u8 - b'0') * scale;
            scale /= 10;
        }
    }
    Ok(nanos)
}

/// Parses the body of a date-and-time literal (`2024-01-31-12:00:00.5`)
/// into nanoseconds since 1970-01-01T00:00:00.
pub fn parse_dt_body(body: &str) -> Result<i64, String> {
    let mut dashes = body.match_indices('-').map(|(i, _)| i);
    let split = dashes.nth(2).ok_or_else(|| {
        format!("malformed date and time `{body}` (expected yyyy-mm-dd-hh:mm:ss)")
    })?;
    let date = parse_date_body(&body[..split])?;
    let tod = parse_tod_body(&body[split + 1..])?;
    date.checked_add(tod)
        .ok_or_else(|| format!("date and time `{body}` is out of range"))
}

/// A literal that does not decode.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LiteralError {
    /// The text as given.
    pub literal: String,
    /// Why it does not decode.
    pub reason: String,
}

impl std::fmt::Display for LiteralError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.reason)
    }
}

impl std::error::Error for LiteralError {}

/// Parses a duration written as on the command line or in a stimulus
/// file: `10ms`, `1.5s`, `T#10ms` or `TIME#1m` (prefixes case-insensitive),
/// into signed nanoseconds.
pub fn parse_time_literal(text: &str) -> Result<i64, LiteralError> {
    let t = text.trim();
    let body = ["TIME#", "T#"]
        .iter()
        .find_map(|p| {
            t.get(..p.len())
                .filter(|head| head.eq_ignore_ascii_case(p))
                .map(|_| &t[p.len()..])
        })
        .unwrap_or(t);
    parse_duration_body(body).map_err(|reason| LiteralError {
        literal: t.to_string(),
        reason,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_literals_with_and_without_prefix() {
        assert_eq!(parse_time_literal("10ms"), Ok(10_000_000));
        assert_eq!(parse_time_literal(" T#1s "), Ok(1_000_000_000));
        assert_eq!(parse_time_literal("time#2m"), Ok(120_000_000_000));
        assert_eq!(parse_time_literal("t#-5ms"), Ok(-5_000_000));
        let e = parse_time_literal("T#ten").unwrap_err();
        assert_eq!(e.literal, "T#ten");
        assert!(parse_time_literal("").is_err());
    }

    #[test]
    fn durations_parse() {
        assert_eq!(parse_duration_body("5s"), Ok(5_000_000_000));
        assert_eq!(parse_duration_body("1.5s"), Ok(1_500_000_000));
        assert_eq!(parse_duration_body("-250ms"), Ok(-250_000_000));
        assert_eq!(parse_duration_body("1d_2h"), Ok(93_600_000_000_000));
        assert_eq!(parse_duration_body("1H2M3S"), Ok(3_723_000_000_000));
        assert_eq!(parse_duration_body("12m30s500ms"), Ok(750_500_000_000));
        assert!(parse_duration_body("5").is_err());
        assert!(parse_duration_body("5s1m").is_err());
        assert!(parse_duration_body("1.5s2ms").is_err());
        assert!(parse_duration_body("").is_err());
        assert!(parse_duration_body("99999999999d").is_err());
    }

    #[test]
    fn durations_format() {
        assert_eq!(format_duration(0, "T#"), "T#0s");
        assert_eq!(format_duration(1_500_000_000, "T#"), "T#1s500ms");
        assert_eq!(format_duration(600_000_000_000, "T#"), "T#10m");
        assert_eq!(format_duration(-2_000_000, "T#"), "T#-2ms");
        assert_eq!(
            format_duration(90_061_001_001_001, "LT#"),
            "LT#1d1h1m1s1ms1us1ns"
        );
        // The extremes of LTIME: |i64::MIN| needs the unsigned magnitude.
        assert_eq!(
            format_duration(i64::MIN, "LT#"),
            "LT#-106751d23h47m16s854ms775us808ns"
        );
        assert_eq!(
            format_duration(i64::MAX, "LT#"),
            "LT#106751d23h47m16s854ms775us807ns"
        );
    }

    #[test]
    fn durations_append_to_what_is_there() {
        let mut out = String::from("x=");
        write_duration(&mut out, 10_000_000, "T#");
        write_duration(&mut out, 0, ",T#");
        assert_eq!(out, "x=T#10ms,T#0s");
    }

    #[test]
    fn an_unsigned_duration_reaches_twincat_s_largest_ltime() {
        let mut out = String::new();
        write_unsigned_duration(&mut out, u64::MAX, "LT#");
        write_unsigned_duration(&mut out, 0, ",LT#");
        write_unsigned_duration(&mut out, 1_500_000_000, ",LT#");
        assert_eq!(out, "LT#213503d23h34m33s709ms551us615ns,LT#0s,LT#1s500ms");
    }

    #[test]
    fn integers() {
        assert_eq!(parse_int_text("1_000"), Ok(1000));
        assert_eq!(parse_int_text("16#FF"), Ok(255));
        assert_eq!(parse_int_text("2#1_0"), Ok(2));
        assert_eq!(parse_int_text("8#777"), Ok(511));
        assert!(parse_int_text("16#").is_err());
        assert_eq!(parse_int_text("10#1_5"), Ok(15));
        assert!(parse_int_text("10#A").is_err());
        assert!(parse_int_text("3#1").is_err());
        assert_eq!(parse_int_text("1__0"), Ok(10));
        assert!(parse_int_text("16#FF__").is_err());
        assert!(parse_int_text("18446744073709551616").is_err());
    }

    #[test]
    fn civil_dates() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(1970, 3, 1), 59);
        assert_eq!(days_from_civil(1972, 3, 1), 790);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
        assert_eq!(days_from_civil(2024, 1, 31), 19_753);
        assert_eq!(days_from_civil(1969, 12, 31), -1);
        assert_eq!(days_from_civil(1900, 3, 1), -25_508);
        assert!(parse_date_body("2100-02-29").is_err());
        assert!(parse_date_body("2000-02-29").is_ok());
        assert!(parse_date_body("2024-1-31").is_ok());
        assert!(parse_date_body("3000-01-01").is_err());
    }

    #[test]
    fn times_of_day() {
        assert_eq!(parse_tod_body("00:00:00"), Ok(0));
        assert_eq!(parse_tod_body("12:30"), Ok(45_000_000_000_000));
        assert_eq!(parse_tod_body("00:00:00.000000001"), Ok(1));
        assert!(parse_tod_body("12:60:00").is_err());
        assert!(parse_tod_body("12:00:00.").is_err());
        assert_eq!(parse_dt_body("1970-01-01-00:00:01"), Ok(1_000_000_000));
        assert!(parse_dt_body("1970-01-01").is_err());
    }

    #[test]
    fn strings() {
        assert_eq!(decode_string("a$$b$'c", false).as_deref(), Ok("a$b'c"));
        assert_eq!(
            decode_string("$l$N$p$r$t", false).as_deref(),
            Ok("\n\n\u{c}\r\t")
        );
        assert_eq!(decode_string("$41$7E", false).as_deref(), Ok("A~"));
        assert_eq!(decode_string("$0041$\"", true).as_deref(), Ok("A\""));
        assert_eq!(decode_string("ab$Q", false).unwrap_err().0, 2);
        assert!(decode_string("$4", false).is_err());
        assert!(decode_string("$", false).is_err());
    }
}
