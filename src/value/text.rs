//! A whole IEC literal written as text — `TRUE`, `-42`, `16#FF`, `2.5E3`,
//! `INT#-3`, `T#1s500ms`, `D#2024-01-31`, `'text'` — decoded without the
//! lexer, and encoded into the slot of an elementary type. This is how
//! values given from outside (stimulus cells, `--set`, the API's `write`)
//! and `STRING_TO_*` at run time are read; the lexer decodes the same
//! literal bodies through the same functions.

use super::encode::{int_to_slot, real_to_slot};
use super::literal::{
    decode_string, parse_date_body, parse_dt_body, parse_duration_body, parse_int_text,
    parse_real_text, parse_tod_body,
};
use crate::elementary::{ElemType, Family};

/// A decoded literal, before it is given a type.
#[derive(Debug, Clone, PartialEq)]
pub enum Lit {
    /// A whole number whose type is not fixed yet (ANY_INT).
    Int(i128),
    /// A real number whose type is not fixed yet (ANY_REAL).
    Real(f64),
    /// `TRUE` / `FALSE` (also `BOOL#1`).
    Bool(bool),
    /// A quoted string; `wide` for `"..."`.
    Str {
        /// The decoded characters.
        value: String,
        /// WSTRING.
        wide: bool,
    },
    /// A duration, date, time of day or date and time, in nanoseconds,
    /// with the type its prefix gives (`T#` TIME, `LDT#` LDT, ...).
    Nanos {
        /// The value.
        nanos: i64,
        /// TIME, LTIME, DATE, LDATE, TOD, LTOD, DT or LDT.
        ty: ElemType,
    },
    /// A name: an enumeration value (`Red`, or `Color#Red` with a prefix).
    Name(String),
}

/// The prefixes whose literal bodies are durations or dates.
fn time_prefix(prefix: &str) -> Option<ElemType> {
    use ElemType::*;
    Some(match prefix.to_ascii_uppercase().as_str() {
        "T" | "TIME" => Time,
        "LT" | "LTIME" => Ltime,
        "D" | "DATE" => Date,
        "LD" | "LDATE" => Ldate,
        "TOD" | "TIME_OF_DAY" => Tod,
        "LTOD" | "LTIME_OF_DAY" => Ltod,
        "DT" | "DATE_AND_TIME" => Dt,
        "LDT" | "LDATE_AND_TIME" => Ldt,
        _ => return None,
    })
}

/// Decodes the body of a `T#`, `D#`, `TOD#`, `DT#` (and long) literal.
/// `None` when `prefix` is not one of those.
pub fn decode_time_body(prefix: &str, body: &str) -> Option<Result<Lit, String>> {
    let ty = time_prefix(prefix)?;
    let nanos = match ty.family() {
        Family::Duration => parse_duration_body(body),
        _ => match ty {
            ElemType::Date | ElemType::Ldate => parse_date_body(body),
            ElemType::Tod | ElemType::Ltod => parse_tod_body(body),
            _ => parse_dt_body(body),
        },
    };
    Some(nanos.map(|nanos| Lit::Nanos { nanos, ty }))
}

/// What a type prefix allows in its body.
#[derive(Clone, Copy, PartialEq)]
enum BodyKind {
    Int,
    Real,
    Bool,
    Str,
}

fn body_kind(upper: &str) -> Option<BodyKind> {
    Some(match upper {
        "SINT" | "INT" | "DINT" | "LINT" | "USINT" | "UINT" | "UDINT" | "ULINT" => BodyKind::Int,
        "BYTE" | "WORD" | "DWORD" | "LWORD" => BodyKind::Int,
        "REAL" | "LREAL" => BodyKind::Real,
        "BOOL" => BodyKind::Bool,
        "STRING" | "WSTRING" => BodyKind::Str,
        _ => return None,
    })
}

/// Decodes the body of a literal with a type prefix (`INT#-3`,
/// `WORD#16#FF`, `REAL#1.5`, `BOOL#1`, `STRING#'x'`, `Color#Red`).
/// `prefix` has no `#`. Time and date prefixes are not handled here.
pub fn decode_typed_body(prefix: &str, body: &str) -> Result<Lit, String> {
    let upper = prefix.to_ascii_uppercase();
    let kind = body_kind(&upper);
    if body.is_empty() {
        return Err(format!("missing value after `{prefix}#`"));
    }
    if body.starts_with('\'') || body.starts_with('"') {
        let wide = body.starts_with('"');
        let q = if wide { '"' } else { '\'' };
        if body.len() < 2 || !body.ends_with(q) {
            return Err(format!("unterminated string in `{prefix}#{body}`"));
        }
        if !matches!(kind, Some(BodyKind::Str) | None) {
            return Err(format!("`{prefix}#` cannot take a string"));
        }
        let value = decode_string(&body[1..body.len() - 1], wide).map_err(|e| e.2)?;
        return Ok(Lit::Str { value, wide });
    }
    let first = body.trim_start_matches(['+', '-']);
    if first.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
        if first.len() != body.len() {
            return Err(format!("malformed literal `{prefix}#{body}`"));
        }
        return match (kind, first.to_ascii_uppercase().as_str()) {
            (Some(BodyKind::Bool), "TRUE") => Ok(Lit::Bool(true)),
            (Some(BodyKind::Bool), "FALSE") => Ok(Lit::Bool(false)),
            (Some(_), _) => Err(format!("`{body}` is not a value of type {upper}")),
            (None, _) => Ok(Lit::Name(body.to_string())),
        };
    }
    let negative = body.starts_with('-');
    if !first.contains('#') && first.contains(['.', 'e', 'E']) {
        if matches!(kind, Some(BodyKind::Int | BodyKind::Bool | BodyKind::Str)) {
            return Err(format!("`{body}` is not a value of type {upper}"));
        }
        let v = parse_real_text(first)?;
        return Ok(Lit::Real(if negative { -v } else { v }));
    }
    let v = parse_int_text(first)?;
    let v = if negative { -v } else { v };
    match kind {
        Some(BodyKind::Bool) => match v {
            0 => Ok(Lit::Bool(false)),
            1 => Ok(Lit::Bool(true)),
            _ => Err(format!("`{body}` is not a BOOL (use 0, 1, TRUE or FALSE)")),
        },
        Some(BodyKind::Real) => Ok(Lit::Real(v as f64)),
        Some(BodyKind::Str) => Err(format!("`{prefix}#` needs a quoted string")),
        _ => Ok(Lit::Int(v)),
    }
}

/// The length of the number at the start of `s`: an optional sign,
/// decimal digits (with `_`), then either `#` and the digits of a based
/// integer, or an optional fraction (`.` and a digit) and exponent (`e`,
/// an optional sign, a digit). A letter or `_` after the sign starts a name,
/// which is taken whole. The lexer uses the same rule for literal bodies.
pub fn numeric_len(s: &[u8]) -> usize {
    let run = |s: &[u8], f: fn(u8) -> bool| s.iter().position(|&c| !f(c)).unwrap_or(s.len());
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let digit = |c: u8| c.is_ascii_digit() || c == b'_';
    let mut i = usize::from(matches!(s.first(), Some(b'+' | b'-')));
    if s.get(i)
        .is_some_and(|c| c.is_ascii_alphabetic() || *c == b'_')
    {
        return i + run(&s[i..], word);
    }
    i += run(&s[i..], digit);
    if s.get(i) == Some(&b'#') {
        i += 1;
        return i + run(&s[i..], word);
    }
    if s.get(i) == Some(&b'.') && s.get(i + 1).is_some_and(u8::is_ascii_digit) {
        i += 1 + run(&s[i + 1..], digit);
    }
    if matches!(s.get(i), Some(b'e' | b'E')) {
        let mut j = i + 1;
        if matches!(s.get(j), Some(b'+' | b'-')) {
            j += 1;
        }
        if s.get(j).is_some_and(u8::is_ascii_digit) {
            i = j + run(&s[j..], digit);
        }
    }
    i
}

/// True when `s` is a name: a letter or `_`, then letters, digits, `_`.
fn is_name(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Decodes `text` (surrounding blanks ignored) as one literal: the
/// literal and the elementary type its `TYPE#` prefix names, if any. A
/// sign is allowed only before a plain number (`-5`, `+2.5`).
pub fn parse_literal_text(text: &str) -> Result<(Lit, Option<ElemType>), String> {
    let t = text.trim();
    if t.is_empty() {
        return Err(format!("`{t}` is not a literal: it is empty"));
    }
    let (negative, body) = match t.strip_prefix('-') {
        Some(rest) => (Some(true), rest.trim_start()),
        None => match t.strip_prefix('+') {
            Some(rest) => (Some(false), rest.trim_start()),
            None => (None, t),
        },
    };
    let (lit, prefix) = parse_unsigned(body, t)?;
    match (negative, prefix, lit) {
        (None, prefix, lit) => Ok((lit, prefix)),
        (Some(neg), None, Lit::Int(v)) => Ok((Lit::Int(if neg { -v } else { v }), None)),
        (Some(neg), None, Lit::Real(v)) => Ok((Lit::Real(if neg { -v } else { v }), None)),
        _ => Err(format!(
            "`{t}`: a sign is only allowed before a plain number"
        )),
    }
}

/// One literal without a leading sign; `whole` is the text for messages.
fn parse_unsigned(body: &str, whole: &str) -> Result<(Lit, Option<ElemType>), String> {
    let not_single = || format!("`{whole}` is not a single IEC literal");
    if body.starts_with('\'') || body.starts_with('"') {
        let wide = body.starts_with('"');
        let q = if wide { '"' } else { '\'' };
        let inner = body
            .get(1..body.len().saturating_sub(1))
            .filter(|_| body.len() >= 2 && body.ends_with(q) && closes(body))
            .ok_or_else(not_single)?;
        let value = decode_string(inner, wide).map_err(|e| e.2)?;
        return Ok((Lit::Str { value, wide }, None));
    }
    if body.starts_with(|c: char| c.is_ascii_digit()) {
        if numeric_len(body.as_bytes()) != body.len() {
            return Err(not_single());
        }
        let is_real = !body.contains('#') && body.contains(['.', 'e', 'E']);
        return if is_real {
            parse_real_text(body).map(|v| (Lit::Real(v), None))
        } else {
            parse_int_text(body).map(|v| (Lit::Int(v), None))
        };
    }
    if let Some((prefix, rest)) = body.split_once('#')
        && is_name(prefix)
    {
        if let Some(lit) = decode_time_body(prefix, rest) {
            return Ok((lit?, None));
        }
        let lit = decode_typed_body(prefix, rest)?;
        return Ok((lit, ElemType::from_name(prefix)));
    }
    if is_name(body) {
        return Ok((
            match body.to_ascii_uppercase().as_str() {
                "TRUE" => Lit::Bool(true),
                "FALSE" => Lit::Bool(false),
                _ => Lit::Name(body.to_string()),
            },
            None,
        ));
    }
    Err(not_single())
}

/// True when the final quote of a quoted `s` is not escaped by `$`.
fn closes(s: &str) -> bool {
    let body = &s.as_bytes()[1..s.len() - 1];
    let dollars = body.iter().rev().take_while(|c| **c == b'$').count();
    dollars % 2 == 0 && !body.contains(&b'\n')
}

/// The natural type of a literal without context (untyped numbers and
/// names have none).
pub fn natural_type(lit: &Lit) -> Option<ElemType> {
    match lit {
        Lit::Int(_) | Lit::Real(_) | Lit::Name(_) => None,
        Lit::Bool(_) => Some(ElemType::Bool),
        Lit::Nanos { ty, .. } => Some(*ty),
        Lit::Str { wide: true, .. } => Some(ElemType::WString),
        Lit::Str { wide: false, .. } => Some(ElemType::String),
    }
}

/// TIME/LTIME, DATE/LDATE... share an encoding (nanoseconds).
pub fn same_kind_long(a: ElemType, b: ElemType) -> bool {
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

/// A literal encoded for a type: a slot value, or a string (whose slot
/// holds a string index, not the text).
#[derive(Debug, Clone, PartialEq)]
pub enum Encoded {
    /// The slot value.
    Bits(u64),
    /// A STRING or WSTRING value.
    Str(String),
}

/// Encodes a literal as a value of elementary type `ty`, or says why not.
pub fn encode(lit: &Lit, ty: ElemType) -> Result<Encoded, String> {
    let out_of_range = |v: &dyn std::fmt::Display| format!("{v} does not fit in {ty}");
    match lit {
        Lit::Int(v) => {
            if ty == ElemType::Bool {
                return match v {
                    0 | 1 => Ok(Encoded::Bits(*v as u64)),
                    _ => Err(out_of_range(v)),
                };
            }
            if !(ty.is_num() || ty.is_bit() || ty.family() == Family::Char) {
                return Err(format!("an integer literal is not a {ty}"));
            }
            int_to_slot(*v, ty)
                .map(Encoded::Bits)
                .ok_or_else(|| out_of_range(v))
        }
        Lit::Real(v) => {
            if !ty.is_real() {
                return Err(format!("a real literal is not a {ty}"));
            }
            real_to_slot(*v, ty)
                .map(Encoded::Bits)
                .ok_or_else(|| out_of_range(v))
        }
        Lit::Bool(b) if ty.is_bit() => Ok(Encoded::Bits(*b as u64)),
        Lit::Bool(_) => Err(format!("a BOOL literal is not a {ty}")),
        Lit::Str { value, wide } => {
            if ty.is_string() && (*wide == (ty == ElemType::WString) || !*wide) {
                Ok(Encoded::Str(value.clone()))
            } else if ty.family() == Family::Char && value.chars().count() == 1 {
                Ok(Encoded::Bits(
                    value.chars().next().map(|c| c as u64).unwrap_or(0),
                ))
            } else {
                Err(format!("a string literal is not a {ty}"))
            }
        }
        Lit::Name(_) => Err(format!("an enumeration value is not a {ty}")),
        Lit::Nanos { nanos, ty: natural } => {
            let natural = *natural;
            if natural == ty || natural.widens_to(ty) || same_kind_long(natural, ty) {
                Ok(Encoded::Bits(*nanos as u64))
            } else {
                Err(format!("a {natural} literal is not a {ty}"))
            }
        }
    }
}

/// Parses `text` as a value of the (non-string) elementary type `ty`: an
/// IEC literal of that type (a `TYPE#` prefix must name `ty` or a type
/// that widens to it), or a bare number for numeric types. `None` when it
/// is not one.
pub fn parse_scalar(text: &str, ty: ElemType) -> Option<u64> {
    let (lit, prefix) = parse_literal_text(text).ok()?;
    if let Some(prefix) = prefix
        && prefix != ty
        && !prefix.widens_to(ty)
    {
        return None;
    }
    match encode(&lit, ty).ok()? {
        Encoded::Bits(b) => Some(b),
        Encoded::Str(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scalars_of_every_shape() {
        assert_eq!(parse_scalar(" TRUE ", ElemType::Bool), Some(1));
        assert_eq!(parse_scalar("-5", ElemType::Int), Some(-5i64 as u64));
        assert_eq!(parse_scalar("16#FF", ElemType::Byte), Some(255));
        assert_eq!(parse_scalar("INT#7", ElemType::Dint), Some(7));
        assert_eq!(parse_scalar("DINT#7", ElemType::Int), None);
        assert_eq!(parse_scalar("T#1s", ElemType::Time), Some(1_000_000_000));
        assert_eq!(parse_scalar("'A'", ElemType::Char), Some(65));
        assert_eq!(parse_scalar("2.5", ElemType::Lreal), Some(2.5f64.to_bits()));
        assert_eq!(parse_scalar("32768", ElemType::Int), None);
        assert_eq!(parse_scalar("-T#1s", ElemType::Time), None);
    }

    #[test]
    fn a_value_text_is_one_literal_without_comments() {
        assert_eq!(parse_scalar("1 (* one *)", ElemType::Int), None);
        assert_eq!(parse_scalar("1 // one", ElemType::Int), None);
        assert_eq!(parse_scalar("1 2", ElemType::Int), None);
        assert_eq!(parse_scalar("1.", ElemType::Real), None);
        assert!(parse_literal_text("").is_err());
    }

    #[test]
    fn strings_decode_their_escapes() {
        let (lit, _) = parse_literal_text("'a$'b$N'").unwrap();
        assert_eq!(
            lit,
            Lit::Str {
                value: "a'b\n".into(),
                wide: false
            }
        );
        assert!(parse_literal_text("'a$'").is_err());
    }
}
