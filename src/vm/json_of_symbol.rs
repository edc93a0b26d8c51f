//! The JSON text of a value given by its type's name and its address:
//! what Tc3_JsonXml's `FB_JsonReadWriteDataType.AddJsonValueFromSymbol`
//! writes (SLAC's logger sends each event so, `'ST_LoggingEventInfo'` and
//! `ADR(stEventInfo)`). TwinCAT reads the type from the application's
//! symbol information; plcrun from the program's type table, by name (any
//! case), and the value from the object the address was taken of.
//!
//! A structure is an object of its fields by name, in declaration order;
//! an array a JSON array (one of arrays for each further dimension); a
//! BOOL `true`/`false`; an integer, bit string or enumeration its number;
//! a REAL or LREAL its number (`null` when it is not finite); a STRING
//! a JSON string; a duration, date or time of day its IEC literal as a
//! string (`"T#1s500ms"`); a reference, pointer or function block
//! instance `null`. The text is compact (no spaces).

use super::PlcString;
use super::refs::RefTable;
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::refs;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, TypeTable};
use std::fmt::Write;

use crate::ir::op::JSON_OF_SYMBOL_MAX as MAX_JSON;

/// The JSON text of the `datatype` at the pointer whose integer image is
/// `image`; `None` when no such type is declared, the pointer designates
/// no object large enough to hold one there, or the text is longer than
/// [`MAX_JSON`]. (The caller's byte count is not needed: the object the
/// pointer was taken of bounds what is read.)
pub(super) fn json_of_symbol(
    img: &Image,
    table: &RefTable,
    mem: &[u64],
    strings: &[PlcString],
    datatype: &str,
    image: u64,
) -> Option<String> {
    let ty = type_named(&img.types, datatype)?;
    let at = address(img, table, ty, image)?;
    let mut w = JsonWriter {
        types: &img.types,
        mem,
        strings,
        out: String::new(),
    };
    w.value(ty, at)?;
    (w.out.chars().count() <= MAX_JSON as usize).then_some(w.out)
}

/// The absolute slot of the `ty` the pointer whose integer image is
/// `image` designates, when its object holds one there (in size).
pub(super) fn address(img: &Image, table: &RefTable, ty: TypeId, image: u64) -> Option<usize> {
    let r = super::refs::from_image(image);
    let n = refs::object_number(r);
    let obj = *table.object(n)?;
    let off = refs::offset(r);
    let slot = match table.aggregate(n, &img.byte_layouts) {
        Some(l) => l.slot_of_byte(off)?,
        None if off == 0 => 0,
        None => return None,
    };
    if slot as u64 + img.types.size(ty) as u64 > obj.len as u64 {
        return None;
    }
    Some(obj.start as usize + slot as usize)
}

/// The declared type named `name` (any case): a structure first, then any
/// other (an alias, an enumeration).
pub(super) fn type_named(types: &TypeTable, name: &str) -> Option<TypeId> {
    let named = |t: &TypeId| types.name(*t).eq_ignore_ascii_case(name.trim());
    let all = (0..types.len() as u32).map(TypeId);
    let mut found = all.filter(named);
    let first = found.next()?;
    let structure = |t: &TypeId| matches!(types.get(*t).kind, TypeKind::Struct { .. });
    Some(if structure(&first) {
        first
    } else {
        found.find(structure).unwrap_or(first)
    })
}

struct JsonWriter<'a> {
    types: &'a TypeTable,
    mem: &'a [u64],
    strings: &'a [PlcString],
    out: String,
}

impl JsonWriter<'_> {
    /// Appends the value of type `ty` at absolute slot `at`.
    fn value(&mut self, ty: TypeId, at: usize) -> Option<()> {
        if self.out.len() > 4 * MAX_JSON as usize {
            return None;
        }
        match &self.types.get(ty).kind {
            TypeKind::Elem(e) => {
                let raw = *self.mem.get(at)?;
                self.scalar(*e, raw)
            }
            TypeKind::Enum { base, .. } | TypeKind::Subrange { base, .. } => {
                let raw = *self.mem.get(at)?;
                self.scalar(*base, raw)
            }
            TypeKind::Str { .. } => {
                let id = *self.mem.get(at)? as usize;
                let text = self.strings.get(id)?.as_str();
                write_string(&mut self.out, text);
                Some(())
            }
            TypeKind::Array { dims, elem } => {
                let stride = self.types.size(*elem) as usize;
                self.array(dims, *elem, stride, at)
            }
            TypeKind::Struct { fields } => {
                self.out.push('{');
                let mut first = true;
                for f in fields {
                    if matches!(f.kind, MemberKind::InOut | MemberKind::External) {
                        continue;
                    }
                    if !first {
                        self.out.push(',');
                    }
                    first = false;
                    write_string(&mut self.out, &f.name);
                    self.out.push(':');
                    self.value(f.ty, at + f.offset as usize)?;
                }
                self.out.push('}');
                Some(())
            }
            _ => {
                self.out.push_str("null");
                Some(())
            }
        }
    }

    /// Appends the elements of an array of `dims` from `at`, one JSON
    /// array per dimension.
    fn array(
        &mut self,
        dims: &[crate::ir::type_table::Dim],
        elem: TypeId,
        stride: usize,
        at: usize,
    ) -> Option<()> {
        let (first, rest) = dims.split_first()?;
        let inner: usize = rest.iter().map(|d| d.len() as usize).product();
        self.out.push('[');
        for i in 0..first.len() as usize {
            if i > 0 {
                self.out.push(',');
            }
            let base = at + i * inner * stride;
            if rest.is_empty() {
                self.value(elem, base)?;
            } else {
                self.array(rest, elem, stride, base)?;
            }
        }
        self.out.push(']');
        Some(())
    }

    /// Appends an elementary value from its slot.
    fn scalar(&mut self, e: ElemType, raw: u64) -> Option<()> {
        match e {
            ElemType::Bool => self.out.push_str(if raw != 0 { "true" } else { "false" }),
            ElemType::Real | ElemType::Lreal => {
                let v = match e {
                    ElemType::Real => f32::from_bits(raw as u32) as f64,
                    _ => f64::from_bits(raw),
                };
                if v.is_finite() {
                    let text = crate::value::format::format_value(e, raw);
                    self.out.push_str(&text);
                } else {
                    self.out.push_str("null");
                }
            }
            e if e.is_signed_int() => write!(self.out, "{}", raw as i64).ok()?,
            e if e.is_int() || e.is_bit() => write!(self.out, "{raw}").ok()?,
            e => {
                let text = crate::value::format::format_value(e, raw);
                write_string(&mut self.out, &text);
            }
        }
        Some(())
    }
}

/// `text` as a JSON string.
fn write_string(out: &mut String, text: &str) {
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

#[cfg(test)]
mod tests {
    use super::write_string;

    #[test]
    fn strings_are_escaped() {
        let mut out = String::new();
        write_string(&mut out, "a\"b\\c\nd\u{1}");
        assert_eq!(out, "\"a\\\"b\\\\c\\nd\\u0001\"");
    }
}
