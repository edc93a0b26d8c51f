//! S7-200 operand names for programs built by the S7-200 STL front-end
//! (docs/s7-200.md): `I0.0`, `Q0.1`, `V6.1`, `VB6`, `VW10`, `VD20`,
//! `SM0.1`, `MB3`, `T37` (timer bit), `T37.CV` (its current value), `C0`,
//! `C0.CV`, and the German areas `E` (= `I`) and `A` (= `Q`). They name
//! views of the program's byte images (`S7_V` …), so the trace, the
//! stimulus, forcing and the embedding API see the same overlapping memory
//! as the program.

use super::byte_view::ByteView;
use super::names::VarRef;
use super::var_error::VarError;
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::type_table::{TypeKind, TypeTable};

/// The member that marks a program as built by the S7-200 front-end (the
/// V memory image; the front-end declares it in every S7-200 program).
const MARKER: &str = "S7_V";

/// How an S7-200 name reads its memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Width {
    Bit(u8),
    Byte,
    Word,
    Dword,
}

/// A parsed S7-200 name: the image member it lives in, the element index,
/// and the width.
struct Place {
    member: &'static str,
    index: u32,
    width: Width,
}

/// The byte-image member of an area letter group (German `E`/`A` included).
fn area_member(area: &str) -> Option<&'static str> {
    Some(match area {
        "I" | "E" => "S7_I",
        "Q" | "A" => "S7_Q",
        "M" => "S7_M",
        "V" => "S7_V",
        "SM" => "S7_SM",
        _ => return None,
    })
}

/// Splits `text` (upper case) into an S7-200 place, or `None` when it is
/// not written as one.
fn parse(text: &str) -> Option<Place> {
    let number = |s: &str| -> Option<u32> {
        if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        s.parse().ok()
    };
    for (prefix, bit_member, word_member) in [("T", "S7_TB", "S7_T"), ("C", "S7_CB", "S7_C")] {
        if let Some(rest) = text.strip_prefix(prefix) {
            let (n, cv) = match rest.strip_suffix(".CV") {
                Some(n) => (n, true),
                None => (rest, false),
            };
            if let Some(index) = number(n) {
                let (member, width) = if cv {
                    (word_member, Width::Word)
                } else {
                    (bit_member, Width::Bit(0))
                };
                return Some(Place {
                    member,
                    index,
                    width,
                });
            }
        }
    }
    let split = text.find(|c: char| c.is_ascii_digit())?;
    let (letters, digits) = text.split_at(split);
    if let Some((byte, bit)) = digits.split_once('.') {
        let bit = number(bit)?;
        if bit > 7 {
            return None;
        }
        return Some(Place {
            member: area_member(letters)?,
            index: number(byte)?,
            width: Width::Bit(bit as u8),
        });
    }
    let index = number(digits)?;
    let (area, width) = match letters.as_bytes().last()? {
        b'B' => (&letters[..letters.len() - 1], Width::Byte),
        b'W' => (&letters[..letters.len() - 1], Width::Word),
        b'D' => (&letters[..letters.len() - 1], Width::Dword),
        _ => return None,
    };
    Some(Place {
        member: area_member(area)?,
        index,
        width,
    })
}

/// Resolves `text` as an S7-200 operand name when `image` was built by the
/// S7-200 front-end and `text` is written as one; `None` otherwise (the
/// name is then resolved the ordinary way).
pub(crate) fn resolve(image: &Image, text: &str, owner: u64) -> Option<Result<VarRef, VarError>> {
    let [inst] = image.programs.as_slice() else {
        return None;
    };
    image.member_named(inst.ty, MARKER)?;
    let trimmed = text.trim();
    let place = parse(&trimmed.to_ascii_uppercase())?;
    let m = image.member_named(inst.ty, place.member)?;
    let TypeKind::Array { dims, elem } = &image.types.get(m.ty).kind else {
        return None;
    };
    let dim = dims.first()?;
    let bytes = match place.width {
        Width::Word if place.member.starts_with("S7_T") || place.member.starts_with("S7_C") => 1,
        Width::Word => 2,
        Width::Dword => 4,
        Width::Bit(_) | Width::Byte => 1,
    };
    let first = i64::from(place.index);
    let last = first + bytes - 1;
    if first < dim.lo || last > dim.hi {
        return Some(Err(VarError::IndexOutOfBounds {
            path: trimmed.to_string(),
            index: last,
            lo: dim.lo,
            hi: dim.hi,
        }));
    }
    let slot = inst.base + m.offset + ((first - dim.lo) as u32) * image.types.size(*elem);
    let is_byte_image = matches!(&image.types.get(*elem).kind, TypeKind::Elem(ElemType::Byte));
    let (ty, view) = match (place.width, is_byte_image) {
        (Width::Bit(n), true) => (ElemType::Bool, Some(ByteView::Bit(n))),
        (Width::Byte, true) => (ElemType::Byte, None),
        (Width::Word, true) => (ElemType::Word, Some(ByteView::BigEndian(2))),
        (Width::Dword, true) => (ElemType::Dword, Some(ByteView::BigEndian(4))),
        // Timer and counter bits and current values are whole slots.
        (_, false) => {
            let TypeKind::Elem(e) = image.types.get(*elem).kind else {
                return None;
            };
            (e, None)
        }
    };
    Some(Ok(VarRef {
        name: trimmed.to_string(),
        addr: slot,
        ty: TypeTable::elem(ty),
        owner,
        read_only: None,
        view,
    }))
}

/// The default trace of an S7-200 program: every bit of the Q bytes up to
/// the highest one the program uses (the front-end records that byte as
/// the bounds of `S7_QUSED`), or `None` when `image` is not an S7-200
/// program.
pub(crate) fn default_trace(image: &Image) -> Option<Vec<String>> {
    let [inst] = image.programs.as_slice() else {
        return None;
    };
    let members = image.types.members(inst.ty);
    if !members.iter().any(|m| m.name.eq_ignore_ascii_case(MARKER)) {
        return None;
    }
    let last = members
        .iter()
        .find(|m| m.name.eq_ignore_ascii_case("S7_QUSED"))
        .and_then(|m| match &image.types.get(m.ty).kind {
            TypeKind::Array { dims, .. } => dims.first().map(|d| d.hi),
            _ => None,
        })
        .unwrap_or(0);
    Some(
        (0..=last)
            .flat_map(|byte| (0..8).map(move |bit| format!("Q{byte}.{bit}")))
            .collect(),
    )
}
