//! Literal decoding: `parse_literal` and literals inside source.

use super::common::*;
use plcrun::syntax::ast::LiteralValue as V;
use plcrun::syntax::parse_literal;
use rstest::rstest;

const S: i64 = 1_000_000_000;

#[rstest]
#[case("TRUE", V::Bool(true))]
#[case("false", V::Bool(false))]
#[case("1", V::Int(1))]
#[case("-5", V::Int(-5))]
#[case("+7", V::Int(7))]
#[case("1_000_000", V::Int(1_000_000))]
#[case("16#FF", V::Int(255))]
#[case("16#ff_ff", V::Int(65535))]
#[case("2#1010_1010", V::Int(170))]
#[case("8#17", V::Int(15))]
#[case("18446744073709551615", V::Int(18_446_744_073_709_551_615))]
#[case("1.5", V::Real(1.5))]
#[case("-2.5E3", V::Real(-2500.0))]
#[case("1.5E-3", V::Real(0.0015))]
#[case("1e10", V::Real(1e10))]
#[case("T#1s500ms", V::Duration { nanos: 1_500_000_000, long: false })]
#[case("t#10m", V::Duration { nanos: 600 * S, long: false })]
#[case("TIME#-2ms", V::Duration { nanos: -2_000_000, long: false })]
#[case("T#-2ms", V::Duration { nanos: -2_000_000, long: false })]
#[case("T#1d_2h", V::Duration { nanos: 26 * 3600 * S, long: false })]
#[case("T#1.5s", V::Duration { nanos: 1_500_000_000, long: false })]
#[case("LT#1ns", V::Duration { nanos: 1, long: true })]
#[case("LTIME#5us", V::Duration { nanos: 5_000, long: true })]
#[case("D#2024-01-31", V::Date { nanos: 1_706_659_200 * S, long: false })]
#[case("DATE#2000-02-29", V::Date { nanos: 951_782_400 * S, long: false })]
#[case("D#1969-12-31", V::Date { nanos: -86_400 * S, long: false })]
#[case("LDATE#1970-01-01", V::Date { nanos: 0, long: true })]
#[case("TOD#12:00:00.5", V::TimeOfDay { nanos: 43_200 * S + S / 2, long: false })]
#[case("TIME_OF_DAY#00:00:01", V::TimeOfDay { nanos: S, long: false })]
#[case("LTOD#23:59:59.999999999", V::TimeOfDay { nanos: 86_400 * S - 1, long: true })]
#[case("DT#2024-01-31-12:00:00", V::DateTime { nanos: 1_706_702_400 * S, long: false })]
#[case("DATE_AND_TIME#1970-01-01-00:00:00.25", V::DateTime { nanos: S / 4, long: false })]
#[case("LDT#1970-01-02-00:00:00", V::DateTime { nanos: 86_400 * S, long: true })]
#[case("'text'", V::String { value: "text".into(), wide: false })]
#[case("''", V::String { value: "".into(), wide: false })]
#[case("'a$'b$$c$Nd$te$41'", V::String { value: "a'b$c\nd\teA".into(), wide: false })]
#[case("\"wide\"", V::String { value: "wide".into(), wide: true })]
#[case("\"$\"q$00e9\"", V::String { value: "\"qé".into(), wide: true })]
#[case("'héllo ☃'", V::String { value: "héllo ☃".into(), wide: false })]
fn literal_values(#[case] text: &str, #[case] expected: V) {
    let lit = parse_literal(text).unwrap_or_else(|e| panic!("{text}: {e}"));
    assert_eq!(lit.value, expected, "{text}");
    assert!(lit.type_prefix.is_none(), "{text}");
}

#[rstest]
#[case("INT#-3", "INT", V::Int(-3))]
#[case("int#5", "int", V::Int(5))]
#[case("BOOL#1", "BOOL", V::Bool(true))]
#[case("BOOL#0", "BOOL", V::Bool(false))]
#[case("BOOL#TRUE", "BOOL", V::Bool(true))]
#[case("WORD#16#FF", "WORD", V::Int(255))]
#[case("DINT#-2#101", "DINT", V::Int(-5))]
#[case("REAL#1.5", "REAL", V::Real(1.5))]
#[case("LREAL#2.5", "LREAL", V::Real(2.5))]
#[case("LREAL#-1.0E2", "LREAL", V::Real(-100.0))]
#[case("REAL#3", "REAL", V::Real(3.0))]
#[case("STRING#'abc'", "STRING", V::String { value: "abc".into(), wide: false })]
fn typed_literals(#[case] text: &str, #[case] prefix: &str, #[case] expected: V) {
    let lit = parse_literal(text).unwrap_or_else(|e| panic!("{text}: {e}"));
    assert_eq!(lit.value, expected);
    assert_eq!(lit.type_prefix.map(|p| p.name).as_deref(), Some(prefix));
}

#[test]
fn enum_qualified_literal() {
    let lit = parse_literal("Color#Red").unwrap();
    assert_eq!(lit.type_prefix.unwrap().name, "Color");
    match lit.value {
        V::EnumValue(v) => assert_eq!(v.name, "Red"),
        other => panic!("{other:?}"),
    }
}

#[rstest]
#[case("")]
#[case("T#5")]
#[case("T#5x")]
#[case("16#G1")]
#[case("2#102")]
#[case("3#12")]
#[case("INT#")]
#[case("INT#abc")]
#[case("BOOL#2")]
#[case("INT#1.5")]
#[case("D#2023-02-29")]
#[case("D#2024-13-01")]
#[case("TOD#24:00:00")]
#[case("TOD#12")]
#[case("DT#2024-01-31")]
#[case("'open")]
#[case("'bad $Q escape'")]
#[case("1 2")]
#[case("x")]
#[case("-TRUE")]
#[case("99999999999999999999999")]
fn bad_literals(#[case] text: &str) {
    assert!(parse_literal(text).is_err(), "{text} should be rejected");
}

#[rstest]
#[case("%IX0.3", "Input", "Bit", true, &[0, 3])]
#[case("%QW4", "Output", "Word", true, &[4])]
#[case("%I0.0.0.0.1", "Input", "Bit", false, &[0, 0, 0, 0, 1])]
#[case("%MD12", "Memory", "Dword", true, &[12])]
#[case("%mb7", "Memory", "Byte", true, &[7])]
#[case("%QL1.2", "Output", "Lword", true, &[1, 2])]
#[case("%I*", "Input", "Bit", false, &[])]
fn direct_addresses(
    #[case] text: &str,
    #[case] area: &str,
    #[case] size: &str,
    #[case] explicit: bool,
    #[case] fields: &[u64],
) {
    let unit = parse_ok(&format!(
        "PROGRAM p VAR v AT {text} : BOOL; END_VAR END_PROGRAM"
    ));
    let d = pou(&unit).var_blocks[0].decls[0].location.clone().unwrap();
    assert_eq!(format!("{:?}", d.area), area);
    assert_eq!(format!("{:?}", d.size), size);
    assert_eq!(d.explicit_size, explicit);
    assert_eq!(d.fields, fields);
    assert_eq!(d.text, text);
    assert_eq!((d.span.end - d.span.start) as usize, text.len());
}

#[test]
fn range_dots_are_not_reals() {
    let unit = parse_ok("TYPE r : INT (1..5); a : ARRAY[0..10, -1..1] OF INT; END_TYPE");
    let text = format!("{unit:?}");
    assert!(!text.contains("Real("), "{text}");
}
