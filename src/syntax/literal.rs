//! Typed literal bodies (`INT#-3`, `WORD#16#FF`, `Color#Red`) decoded into
//! AST literal values; the decoding itself is `crate::value::text`'s,
//! shared with values read at run time.

use crate::source::Span;
use crate::syntax::ast::{Ident, LiteralValue};
use crate::value::text::{self, Lit};

/// Decodes the body of a literal with a type prefix (`INT#-3`,
/// `WORD#16#FF`, `REAL#1.5`, `BOOL#1`, `STRING#'x'`, `Color#Red`) into an
/// AST literal value (an enumeration value gets an empty span; the lexer
/// sets it). `prefix` has no `#`. Time and date prefixes are not handled
/// here.
pub fn decode_typed_body(prefix: &str, body: &str) -> Result<LiteralValue, String> {
    Ok(match text::decode_typed_body(prefix, body)? {
        Lit::Int(v) => LiteralValue::Int(v),
        Lit::Real(v) => LiteralValue::Real(v),
        Lit::Bool(b) => LiteralValue::Bool(b),
        Lit::Str { value, wide } => LiteralValue::String { value, wide },
        Lit::Name(name) => LiteralValue::EnumValue(Ident {
            name,
            span: Span::default(),
        }),
        // Not produced for a type prefix; kept total for the compiler.
        Lit::Nanos { nanos, .. } => LiteralValue::Duration { nanos, long: false },
    })
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
