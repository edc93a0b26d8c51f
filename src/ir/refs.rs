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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing() {
        let r = pack(3, 2);
        assert_eq!((object(r), offset(r)), (3, 2));
        assert_eq!(object(NULL), 0);
        assert_eq!(offset(moved(r, -3)), u32::MAX);
    }
}
