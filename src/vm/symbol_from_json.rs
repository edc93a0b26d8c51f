//! A value written from JSON text, given its type's name and its address:
//! what Tc3_JsonXml's `FB_JsonReadWriteDataType.SetSymbolFromJson` does
//! (a structure filled from a message received as JSON). The reverse of
//! [`super::json_of_symbol`], with the same mapping:
//!
//! - a structure takes an object: each field the key of its name (the
//!   exact name first, else in any case), a field without a key keeps its
//!   value, a key without a field is ignored;
//! - an array takes an array: its first elements, as many as both have
//!   (one array of arrays per further dimension);
//! - a BOOL takes `true`/`false`; an integer or bit string a number with
//!   no fraction that its type holds; a REAL or LREAL any number; an
//!   enumeration its number or a value's name; a STRING a string (cut to
//!   its length); a duration, date or time of day its IEC literal as a
//!   string; a reference, pointer or block instance is left as it is.
//!
//! The text is checked against the whole type first: anything else (text
//! that is not JSON, a value of the wrong kind, a number out of range)
//! writes nothing and fails.

use super::PlcString;
use super::refs::RefTable;
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::type_table::{Dim, MemberKind, TypeId, TypeKind, TypeTable};
use serde_json::Value;

/// Writes the value `json` gives into the `datatype` at the pointer
/// whose integer image is `image`; false (nothing written) when the type
/// is not declared, the pointer designates no object large enough, or the
/// text does not fit the type.
pub(super) fn symbol_from_json(
    img: &Image,
    table: &RefTable,
    mem: &mut [u64],
    strings: &mut [PlcString],
    json: &str,
    datatype: &str,
    image: u64,
) -> bool {
    let Some(ty) = super::json_of_symbol::type_named(&img.types, datatype) else {
        return false;
    };
    let Some(at) = super::json_of_symbol::address(img, table, ty, image) else {
        return false;
    };
    let Ok(value) = serde_json::from_str::<Value>(json) else {
        return false;
    };
    let mut reader = JsonReader {
        types: &img.types,
        mem,
        strings,
        write: false,
    };
    if reader.value(ty, at, &value).is_none() {
        return false;
    }
    reader.write = true;
    reader.value(ty, at, &value).is_some()
}

struct JsonReader<'a> {
    types: &'a TypeTable,
    mem: &'a mut [u64],
    strings: &'a mut [PlcString],
    /// False: only check that the text fits (nothing is written).
    write: bool,
}

impl JsonReader<'_> {
    /// Takes `v` into the value of type `ty` at absolute slot `at`.
    fn value(&mut self, ty: TypeId, at: usize, v: &Value) -> Option<()> {
        match &self.types.get(ty).kind {
            TypeKind::Elem(e) => {
                let raw = scalar(*e, v)?;
                self.store(at, raw)
            }
            TypeKind::Subrange { base, lo, hi } => {
                let raw = scalar(*base, v)?;
                let n = if base.is_signed_int() {
                    raw as i64 as i128
                } else {
                    raw as i128
                };
                (*lo as i128 <= n && n <= *hi as i128).then_some(())?;
                self.store(at, raw)
            }
            TypeKind::Enum { base, values } => {
                let raw = match v {
                    Value::String(name) => {
                        let (_, n) = values.iter().find(|(k, _)| k.eq_ignore_ascii_case(name))?;
                        crate::value::encode::int_to_slot(*n as i128, *base)?
                    }
                    _ => scalar(*base, v)?,
                };
                self.store(at, raw)
            }
            TypeKind::Str { .. } => {
                let Value::String(text) = v else {
                    return None;
                };
                let id = *self.mem.get(at)? as usize;
                let s = self.strings.get_mut(id)?;
                if self.write {
                    s.set(text);
                }
                Some(())
            }
            TypeKind::Array { dims, elem } => {
                let stride = self.types.size(*elem) as usize;
                self.array(dims, *elem, stride, at, v)
            }
            TypeKind::Struct { fields } => {
                let Value::Object(map) = v else {
                    return None;
                };
                for f in fields {
                    if matches!(f.kind, MemberKind::InOut | MemberKind::External) {
                        continue;
                    }
                    let found = map.get(&f.name).or_else(|| {
                        map.iter()
                            .find(|(k, _)| k.eq_ignore_ascii_case(&f.name))
                            .map(|(_, x)| x)
                    });
                    if let Some(x) = found {
                        self.value(f.ty, at + f.offset as usize, x)?;
                    }
                }
                Some(())
            }
            // References and block instances are no data of the message.
            _ => Some(()),
        }
    }

    /// Takes the elements of JSON array `v` into an array of `dims` at `at`.
    fn array(
        &mut self,
        dims: &[Dim],
        elem: TypeId,
        stride: usize,
        at: usize,
        v: &Value,
    ) -> Option<()> {
        let Value::Array(items) = v else {
            return None;
        };
        let (first, rest) = dims.split_first()?;
        let inner: usize = rest.iter().map(|d| d.len() as usize).product();
        for (i, x) in items.iter().take(first.len() as usize).enumerate() {
            let base = at + i * inner * stride;
            if rest.is_empty() {
                self.value(elem, base, x)?;
            } else {
                self.array(rest, elem, stride, base, x)?;
            }
        }
        Some(())
    }

    fn store(&mut self, at: usize, raw: u64) -> Option<()> {
        let slot = self.mem.get_mut(at)?;
        if self.write {
            *slot = raw;
        }
        Some(())
    }
}

/// The slot encoding of JSON value `v` as an `e` (`None` when it is not
/// one: a wrong kind, a fraction for an integer, out of range).
fn scalar(e: ElemType, v: &Value) -> Option<u64> {
    match (e, v) {
        (ElemType::Bool, Value::Bool(b)) => Some(*b as u64),
        (ElemType::Real, Value::Number(n)) => Some((n.as_f64()? as f32).to_bits() as u64),
        (ElemType::Lreal, Value::Number(n)) => Some(n.as_f64()?.to_bits()),
        (e, Value::Number(n)) if e.is_int() || e.is_bit() => {
            let whole = match (n.as_i64(), n.as_u64()) {
                (Some(i), _) => i as i128,
                (None, Some(u)) => u as i128,
                _ => {
                    let f = n.as_f64()?;
                    (f.fract() == 0.0 && f.abs() < 1e19).then_some(f as i128)?
                }
            };
            crate::value::encode::int_to_slot(whole, e)
        }
        (e, Value::String(text)) if !e.is_string() && e != ElemType::Bool => {
            crate::value::text::parse_scalar(text, e)
        }
        _ => None,
    }
}
