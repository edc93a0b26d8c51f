//! The objects references were taken from, and the checked dereference.
//!
//! `REF(x)` / `ADR(x)` number the object `x` (its absolute address and its
//! extent in slots) in a [`RefTable`]; the reference value holds that
//! number and an offset (see [`crate::ir::refs`]). A dereference looks the
//! number up and checks that the slots it reads or writes lie inside the
//! object, so a reference can never reach memory outside the variable it
//! was taken from, whatever arithmetic was done on it.

use super::FaultKind;
use crate::ir::image::{ArrayDesc, Image};
use crate::ir::op::Op;
use crate::ir::refs;
use std::collections::HashMap;

/// Runs one reference instruction on the frame at `fp` in a memory of
/// `mem_len` slots.
///
/// # Safety
/// `op`'s frame operands lie inside the frame at `fp` and its descriptor
/// index inside `img.arrays` (the verifier checked both at link time).
#[inline(never)]
pub(super) unsafe fn run(
    table: &mut RefTable,
    img: &Image,
    fp: *mut u64,
    mem_len: usize,
    op: &Op,
) -> Result<(), FaultKind> {
    // SAFETY: frame operands are inside the frame (caller's contract).
    let r = |s: crate::ir::op::Slot| unsafe { *fp.add(s.index()) };
    let (d, v) = match *op {
        Op::RefMake { d, p, len } => (d, table.make(r(p), len, mem_len)?),
        Op::RefAddr { d, r: s, width } => (d, table.address(r(s), width)? as u64),
        Op::RefIndex { d, idx, desc } => {
            let ad = img.arrays.get(desc.index()).ok_or(FaultKind::BadAddress)?;
            (d, index(r(d), r(idx), ad)?)
        }
        Op::PtrAdd { d, b, unit, slots } => (d, add_bytes(r(d), r(b), unit, slots)),
        Op::RefValid { d, r: s, width } => (d, table.address(r(s), width).is_ok() as u64),
        // oop's call through an interface that holds no instance (R080)
        // shares this out-of-line arm: one arm less in the dispatch loop.
        Op::FaultNullItf => return Err(FaultKind::NullInterface),
        _ => return Ok(()),
    };
    // SAFETY: as for `r`.
    unsafe { *fp.add(d.index()) = v };
    Ok(())
}

/// One object a reference designates: where it starts and how many slots
/// it has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RefObject {
    /// Absolute address of the object's first slot.
    pub start: u32,
    /// Its size in slots.
    pub len: u32,
}

/// The objects of one memory layout, numbered from 1 in the order they
/// were first referenced (the same object always gets the same number).
#[derive(Debug, Clone, Default)]
pub struct RefTable {
    objects: Vec<RefObject>,
    numbers: HashMap<RefObject, u32>,
}

impl RefTable {
    /// A reference to the object of `len` slots at `start`, which must lie
    /// in a memory of `mem_len` slots.
    pub fn make(&mut self, start: u64, len: u32, mem_len: usize) -> Result<u64, FaultKind> {
        if start > mem_len as u64 || len as u64 > mem_len as u64 - start {
            return Err(FaultKind::BadAddress);
        }
        let obj = RefObject {
            start: start as u32,
            len,
        };
        if let Some(&n) = self.numbers.get(&obj) {
            return Ok(refs::pack(n, 0));
        }
        let n = u32::try_from(self.objects.len() + 1)
            .ok()
            .filter(|n| *n != u32::MAX)
            .ok_or(FaultKind::TooManyReferencedObjects)?;
        self.objects.push(obj);
        self.numbers.insert(obj, n);
        Ok(refs::pack(n, 0))
    }

    /// The absolute address of the `width` slots `r` designates.
    #[inline]
    pub fn address(&self, r: u64, width: u32) -> Result<usize, FaultKind> {
        let n = refs::object(r);
        if n == 0 {
            return Err(FaultKind::NullReference);
        }
        let obj = self
            .objects
            .get(n as usize - 1)
            .ok_or(FaultKind::StaleReference)?;
        let off = refs::offset(r);
        if off as u64 + width as u64 > obj.len as u64 {
            return Err(FaultKind::OutsideObject {
                offset: off as i32 as i64,
                width,
                len: obj.len,
            });
        }
        Ok(obj.start as usize + off as usize)
    }
}

/// `r` moved to element `idx` of the array `ad` describes (the index is
/// checked against the declared bounds).
#[inline]
pub fn index(r: u64, idx: u64, ad: &ArrayDesc) -> Result<u64, FaultKind> {
    let i = (idx as i64).wrapping_sub(ad.lo) as u64;
    if i >= ad.len {
        return Err(FaultKind::IndexOutOfRange {
            index: idx as i64,
            lo: ad.lo,
            hi: ad.lo + ad.len as i64 - 1,
        });
    }
    Ok(refs::moved(r, (i as i64).wrapping_mul(ad.stride as i64)))
}

/// Pointer `p` moved by `bytes` bytes: whole elements of `unit` bytes and
/// `slots` slots; any other distance poisons the offset.
#[inline]
pub fn add_bytes(p: u64, bytes: u64, unit: u16, slots: u16) -> u64 {
    let b = bytes as i64;
    let unit = unit.max(1) as i64;
    if b % unit != 0 {
        return refs::pack(refs::object(p), refs::MISALIGNED);
    }
    refs::moved(p, (b / unit).wrapping_mul(slots as i64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_object_same_number_and_checked_extent() {
        let mut t = RefTable::default();
        let a = t.make(10, 4, 100).unwrap();
        assert_eq!(t.make(10, 4, 100).unwrap(), a);
        let b = t.make(10, 1, 100).unwrap();
        assert_ne!(a, b);
        assert_eq!(t.address(a, 4), Ok(10));
        assert_eq!(t.address(refs::moved(a, 3), 1), Ok(13));
        assert!(matches!(
            t.address(refs::moved(a, 4), 1),
            Err(FaultKind::OutsideObject { .. })
        ));
        assert!(matches!(
            t.address(refs::moved(a, -1), 1),
            Err(FaultKind::OutsideObject { .. })
        ));
        assert_eq!(t.address(refs::NULL, 1), Err(FaultKind::NullReference));
        assert_eq!(
            t.address(refs::pack(9, 0), 1),
            Err(FaultKind::StaleReference)
        );
        assert_eq!(t.make(99, 2, 100), Err(FaultKind::BadAddress));
    }

    #[test]
    fn byte_arithmetic_moves_whole_elements_only() {
        let p = refs::pack(1, 0);
        assert_eq!(add_bytes(p, 8, 4, 1), refs::pack(1, 2));
        assert_eq!(add_bytes(p, (-4i64) as u64, 4, 1), refs::moved(p, -1));
        assert_eq!(refs::offset(add_bytes(p, 3, 4, 1)), refs::MISALIGNED);
    }
}
