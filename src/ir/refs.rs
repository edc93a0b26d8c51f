//! The value of a reference or pointer in its slot.
//!
//! A reference is one 64-bit slot: the number of the *object* it was taken
//! from in the upper 32 bits and its offset inside that object, in slots,
//! in the lower 32 bits. Object 0 is `NULL`. The machine keeps, per object
//! number, the object's absolute address and extent (see
//! `vm::refs::RefTable`), so every dereference is checked against the
//! object the reference came from: an offset is only ever an offset, never
//! an address.
//!
//! For example `pack(3, 2)` is slot 2 of object 3, and `NULL` is object 0
//! (the unit tests below check both).

use crate::elementary::ElemType;

/// The slot value of `NULL` (and of every reference variable at start).
pub const NULL: u64 = 0;

/// The offset given to a pointer moved by a number of bytes that is not a
/// whole number of its elements: no object is that large, so the next
/// dereference faults (R031).
pub const MISALIGNED: u32 = 0x8000_0000;

/// A reference to slot `offset` of object `object`.
#[inline(always)]
pub fn pack(object: u32, offset: u32) -> u64 {
    ((object as u64) << 32) | offset as u64
}

/// The object a reference designates (0 for `NULL`).
#[inline(always)]
pub fn object(r: u64) -> u32 {
    (r >> 32) as u32
}

/// The offset of a reference inside its object, in slots.
#[inline(always)]
pub fn offset(r: u64) -> u32 {
    r as u32
}

/// The reference `r` moved by `delta` slots (wrapping: a result outside
/// the object faults when it is dereferenced).
#[inline(always)]
pub fn moved(r: u64, delta: i64) -> u64 {
    pack(object(r), offset(r).wrapping_add(delta as u32))
}

/// The flag, in a reference's object number, of a *byte view*: a pointer
/// whose element type differs from the object's (`ps : POINTER TO BYTE`
/// over a STRING, `POINTER TO DWORD` over a REAL), or that was made from
/// an integer. Its offset counts bytes, not slots, and every dereference
/// takes the out-of-line byte path (`vm::refs`): the bytes are those the
/// object has in CODESYS, little-endian.
pub const VIEW: u32 = 0x8000_0000;

/// True for a byte view (see [`VIEW`]).
#[inline(always)]
pub fn is_view(r: u64) -> bool {
    object(r) & VIEW != 0
}

/// The byte view of object `object` at byte `offset`.
#[inline(always)]
pub fn view(object: u32, offset: u32) -> u64 {
    pack(object | VIEW, offset)
}

/// The number of the object a reference designates, view flag removed.
#[inline(always)]
pub fn object_number(r: u64) -> u32 {
    object(r) & !VIEW
}

/// `Op::IntToPtr`'s type when the pointer stays a byte view.
pub const NO_TYPE: u32 = u32::MAX;

/// The integer image of a pointer (`dw := pt`) holds its object's number
/// above this many bits and its byte offset below: objects of up to 1 MiB,
/// 4095 objects, in a DWORD (an object starts at a multiple of 2^20, so
/// CODESYS's alignment tests on the image hold).
pub const IMAGE_OFFSET_BITS: u32 = 20;

/// The code of an elementary type in an instruction (`RefLoad`,
/// `RefStore`, `RefMake`'s layout): its place in [`ElemType::ALL`] plus
/// one; 0 means "no elementary layout" (a structure, an FB, an array of
/// strings).
pub fn elem_code(e: ElemType) -> u8 {
    ElemType::ALL
        .iter()
        .position(|x| *x == e)
        .map_or(0, |i| i as u8 + 1)
}

/// The elementary type of a code from [`elem_code`] (`None` for 0 and
/// for an aggregate's code).
pub fn code_elem(code: u16) -> Option<ElemType> {
    ElemType::ALL.get((code as usize).checked_sub(1)?).copied()
}

/// `RefMake`'s layout codes from this one up name an aggregate's byte
/// layout: entry `code - FIRST_AGGREGATE_LAYOUT` of `Image::byte_layouts`
/// (`ir::byte_layout`). The codes below are [`elem_code`]'s.
pub const FIRST_AGGREGATE_LAYOUT: u16 = 256;

/// The index in `Image::byte_layouts` an aggregate's layout code names.
pub fn aggregate_layout(code: u16) -> Option<usize> {
    code.checked_sub(FIRST_AGGREGATE_LAYOUT).map(usize::from)
}

/// Bytes of one value of `e` in CODESYS's memory as plcrun models it
/// (what `SIZEOF` says): BOOL 1, the integers and reals their width, the
/// time and date types 8; a STRING/WSTRING character 1/2.
pub fn elem_bytes(e: ElemType) -> u32 {
    match e {
        ElemType::Bool => 1,
        ElemType::String => 1,
        ElemType::WString => 2,
        _ => e.bits().div_ceil(8),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_and_codes() {
        let v = view(3, 7);
        assert!(is_view(v) && !is_view(pack(3, 7)));
        assert_eq!((object_number(v), offset(v)), (3, 7));
        for e in ElemType::ALL {
            assert_eq!(code_elem(elem_code(e).into()), Some(e));
        }
        assert_eq!(code_elem(0), None);
        assert_eq!(code_elem(FIRST_AGGREGATE_LAYOUT), None);
        assert_eq!(aggregate_layout(FIRST_AGGREGATE_LAYOUT + 2), Some(2));
        assert_eq!(aggregate_layout(elem_code(ElemType::Int).into()), None);
        assert_eq!(elem_bytes(ElemType::Real), 4);
        assert_eq!(elem_bytes(ElemType::Time), 8);
    }

    #[test]
    fn packing() {
        let r = pack(3, 2);
        assert_eq!((object(r), offset(r)), (3, 2));
        assert_eq!(object(NULL), 0);
        assert_eq!(offset(moved(r, -3)), u32::MAX);
    }
}
