//! Decoding of IEC literal text (the part after `T#`, `16#`, ...) into values,
//! shared by the lexer, the stimulus reader and `--set`.

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
    i64::try_from(total).map_err(|_| format!("duration `{body}` is out of range"))
}

/// Formats nanoseconds as an IEC duration literal: largest unit first, zero
/// parts omitted, `T#0s` for zero, `T#-2ms` for negatives. `prefix` is `T#`
/// or `LT#`.
pub fn format_duration(nanos: i64, prefix: &str) -> String {
    if nanos == 0 {
        return format!("{prefix}0s");
    }
    let mut out = String::from(prefix);
    if nanos < 0 {
        out.push('-');
    }
    let mut rest = (nanos as i128).abs();
    for (unit, scale) in DURATION_UNITS {
        let n = rest / scale;
        if n > 0 {
            out.push_str(&n.to_string());
            out.push_str(unit);
            rest -= n * scale;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }
}
