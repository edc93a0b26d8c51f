//! Typed literal bodies (`INT#-3`, `WORD#16#FF`, `Color#Red`) decoded into
//! AST literal values; the number and date text itself is decoded by
//! [`crate::value::literal`].

use crate::source::Span;
use crate::syntax::ast::{Ident, LiteralValue};
use crate::value::literal::{decode_string, parse_int_text, parse_real_text};

/// The elementary type names whose typed literals hold numbers.
fn numeric_type(upper: &str) -> Option<NumKind> {
    Some(match upper {
        "SINT" | "INT" | "DINT" | "LINT" | "USINT" | "UINT" | "UDINT" | "ULINT" => NumKind::Int,
        "BYTE" | "WORD" | "DWORD" | "LWORD" => NumKind::Int,
        "REAL" | "LREAL" => NumKind::Real,
        "BOOL" => NumKind::Bool,
        "STRING" | "WSTRING" => NumKind::Str,
        _ => return None,
    })
}

#[derive(Clone, Copy, PartialEq)]
enum NumKind {
    Int,
    Real,
    Bool,
    Str,
}

/// Decodes the body of a literal with a type prefix (`INT#-3`,
/// `WORD#16#FF`, `REAL#1.5`, `BOOL#1`, `STRING#'x'`, `Color#Red`).
/// `prefix` has no `#`. Time and date prefixes are not handled here.
pub fn decode_typed_body(prefix: &str, body: &str) -> Result<LiteralValue, String> {
    let upper = prefix.to_ascii_uppercase();
    let kind = numeric_type(&upper);
    if body.is_empty() {
        return Err(format!("missing value after `{prefix}#`"));
    }
    let quoted = body.starts_with('\'') || body.starts_with('"');
    if quoted {
        let wide = body.starts_with('"');
        let q = if wide { '"' } else { '\'' };
        if body.len() < 2 || !body.ends_with(q) {
            return Err(format!("unterminated string in `{prefix}#{body}`"));
        }
        if !matches!(kind, Some(NumKind::Str) | None) {
            return Err(format!("`{prefix}#` cannot take a string"));
        }
        let value = decode_string(&body[1..body.len() - 1], wide).map_err(|e| e.2)?;
        return Ok(LiteralValue::String { value, wide });
    }
    let first = body.trim_start_matches(['+', '-']);
    let is_word = first.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
    if is_word {
        if first.len() != body.len() {
            return Err(format!("malformed literal `{prefix}#{body}`"));
        }
        return match (kind, first.to_ascii_uppercase().as_str()) {
            (Some(NumKind::Bool), "TRUE") => Ok(LiteralValue::Bool(true)),
            (Some(NumKind::Bool), "FALSE") => Ok(LiteralValue::Bool(false)),
            (Some(_), _) => Err(format!("`{body}` is not a value of type {upper}")),
            (None, _) => Ok(LiteralValue::EnumValue(Ident {
                name: body.to_string(),
                span: Span::default(),
            })),
        };
    }
    let negative = body.starts_with('-');
    let is_real = !first.contains('#') && first.contains(['.', 'e', 'E']);
    if is_real {
        if matches!(kind, Some(NumKind::Int | NumKind::Bool | NumKind::Str)) {
            return Err(format!("`{body}` is not a value of type {upper}"));
        }
        let v = parse_real_text(first)?;
        return Ok(LiteralValue::Real(if negative { -v } else { v }));
    }
    let v = parse_int_text(first)?;
    let v = if negative { -v } else { v };
    match kind {
        Some(NumKind::Bool) => match v {
            0 => Ok(LiteralValue::Bool(false)),
            1 => Ok(LiteralValue::Bool(true)),
            _ => Err(format!("`{body}` is not a BOOL (use 0, 1, TRUE or FALSE)")),
        },
        Some(NumKind::Real) => Ok(LiteralValue::Real(v as f64)),
        Some(NumKind::Str) => Err(format!("`{prefix}#` needs a quoted string")),
        _ => Ok(LiteralValue::Int(v)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_bodies() {
        assert_eq!(decode_typed_body("INT", "-3"), Ok(LiteralValue::Int(-3)));
        assert_eq!(
            decode_typed_body("word", "16#FF"),
            Ok(LiteralValue::Int(255))
        );
        assert_eq!(
            decode_typed_body("LREAL", "2.5"),
            Ok(LiteralValue::Real(2.5))
        );
        assert_eq!(
            decode_typed_body("BOOL", "FALSE"),
            Ok(LiteralValue::Bool(false))
        );
        assert_eq!(decode_typed_body("MyAlias", "7"), Ok(LiteralValue::Int(7)));
        assert!(matches!(
            decode_typed_body("Color", "Red"),
            Ok(LiteralValue::EnumValue(i)) if i.name == "Red"
        ));
        assert!(decode_typed_body("INT", "").is_err());
        assert!(decode_typed_body("INT", "Red").is_err());
        assert!(decode_typed_body("DINT", "1.5").is_err());
    }
}
