//! The objects references were taken from, and the checked dereference.
//!
//! `REF(x)` / `ADR(x)` number the object `x` (its absolute address and its
//! extent in slots) in a [`RefTable`]; the reference value holds that
//! number and an offset (see [`crate::ir::refs`]). A dereference looks the
//! number up and checks that the slots it reads or writes lie inside the
//! object, so a reference can never reach memory outside the variable it
//! was taken from, whatever arithmetic was done on it.

use super::{FaultKind, Machine};
use crate::elementary::ElemType;
use crate::ir::byte_layout::ByteLayout;
use crate::ir::image::{ArrayDesc, Image};
use crate::ir::op::Op;
use crate::ir::refs;
use crate::ir::type_table::TypeKind;
use std::collections::HashMap;

/// Runs one reference instruction on the frame at `fp` of `m`'s memory.
///
/// # Safety
/// `op`'s frame operands lie inside the frame at `fp` and its descriptor
/// index inside `img.arrays` (the verifier checked both at link time).
#[inline(never)]
pub(super) unsafe fn run(
    m: &mut Machine,
    img: &Image,
    fp: *mut u64,
    op: &Op,
) -> Result<(), FaultKind> {
    // SAFETY: frame operands are inside the frame (caller's contract).
    let r = |s: crate::ir::op::Slot| unsafe { *fp.add(s.index()) };
    // `Vec::as_mut_ptr` makes no reference to the buffer, so `fp` (taken
    // the same way by the dispatch loop) stays valid beside it.
    let len = m.mem.len();
    // SAFETY: the pointer is to `len` slots, valid while this runs.
    let memory = unsafe { Memory::new(m.mem.as_mut_ptr(), len) };
    let (table, strings) = (&mut m.refs, &mut m.strings);
    let layouts = &img.byte_layouts[..];
    let (d, v) = match *op {
        Op::RefMake { d, p, len, layout } => (d, table.make(r(p), len, layout, memory.len)?),
        Op::RefAddr { d, r: s, width } => (d, table.address(r(s), width)? as u64),
        Op::RefIndex { d, idx, desc, unit } => {
            let ad = img.arrays.get(desc.index()).ok_or(FaultKind::BadAddress)?;
            (d, index(r(d), r(idx), ad, unit)?)
        }
        Op::PtrAdd { d, b, unit, slots } => {
            let moved = add_bytes(r(d), r(b), unit, slots);
            (d, table.byte_view_of(r(d), moved, r(b), unit, layouts))
        }
        Op::RefValid { d, r: s, width } => {
            let ok = if refs::is_view(r(s)) {
                table.view_range(r(s), 1, memory, strings, layouts).is_ok()
            } else {
                table.address(r(s), width).is_ok()
            };
            (d, ok as u64)
        }
        // oop's call through an interface that holds no instance (R080)
        // shares this out-of-line arm: one arm less in the dispatch loop.
        Op::FaultNullItf => return Err(FaultKind::NullInterface),
        Op::FaultReentry => return Err(FaultKind::MethodReentered),
        Op::FaultRaise { c } => return Err(FaultKind::Raised(r(c) as u32)),
        Op::RefLoad { d, r: s, elem } => match table.address(r(s), 1) {
            Ok(a) => (d, memory.load(a)?),
            Err(_) if refs::is_view(r(s)) => {
                (d, table.view_load(r(s), elem, memory, strings, layouts)?)
            }
            Err(e) => return Err(e),
        },
        Op::RefStore { r: s, s: v, elem } => {
            match table.address(r(s), 1) {
                Ok(a) => memory.store(a, r(v))?,
                Err(_) if refs::is_view(r(s)) => {
                    table.view_store(r(s), elem, r(v), memory, strings, layouts)?
                }
                Err(e) => return Err(e),
            }
            return Ok(());
        }
        Op::RefView { d, unit } => (d, table.view_of(r(d), unit, layouts)),
        Op::PtrToInt { d, unit } => (d, table.image(r(d), unit, memory, strings, layouts)?),
        Op::IntToPtr { d, ty } => (d, typed_from_image(from_image(r(d)), ty, img, table)),
        _ => return Ok(()),
    };
    // SAFETY: as for `r`.
    unsafe { *fp.add(d.index()) = v };
    Ok(())
}

/// The memory as the byte path sees it: a raw buffer and its length (no
/// reference to it is made, so the caller's frame pointer stays valid).
#[derive(Clone, Copy)]
pub(super) struct Memory {
    base: *mut u64,
    pub(super) len: usize,
}

impl Memory {
    /// # Safety
    /// `base` points to `len` slots that stay valid while it is used.
    unsafe fn new(base: *mut u64, len: usize) -> Memory {
        Memory { base, len }
    }

    pub(super) fn load(self, a: usize) -> Result<u64, FaultKind> {
        if a >= self.len {
            return Err(FaultKind::BadAddress);
        }
        // SAFETY: a < len (see `new`).
        Ok(unsafe { *self.base.add(a) })
    }

    pub(super) fn store(self, a: usize, v: u64) -> Result<(), FaultKind> {
        if a >= self.len {
            return Err(FaultKind::BadAddress);
        }
        // SAFETY: a < len (see `new`).
        unsafe { *self.base.add(a) = v };
        Ok(())
    }
}

/// One object a reference designates: where it starts and how many slots
/// it has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RefObject {
    /// Absolute address of the object's first slot.
    pub start: u32,
    /// Its size in slots.
    pub len: u32,
    /// The code of its elementary type (`ir::refs::elem_code`) or of its
    /// aggregate's byte layout (0: none), which gives its bytes to byte
    /// views.
    pub layout: u16,
}

/// The objects of one memory layout, numbered from 1 in the order they
/// were first referenced (the same object always gets the same number).
#[derive(Debug, Clone, Default)]
pub struct RefTable {
    objects: Vec<RefObject>,
    numbers: HashMap<RefObject, u32>,
    /// Per string id, the characters byte views wrote past its NUL, with
    /// the text they were written beside: a string operation that changes
    /// the text makes them read 0 again (`vm::byte_view`).
    pub(super) tails: HashMap<usize, (String, Vec<u16>)>,
}

impl RefTable {
    /// A reference to the object of `len` slots at `start`, which must lie
    /// in a memory of `mem_len` slots.
    pub fn make(
        &mut self,
        start: u64,
        len: u32,
        layout: u16,
        mem_len: usize,
    ) -> Result<u64, FaultKind> {
        if start > mem_len as u64 || len as u64 > mem_len as u64 - start {
            return Err(FaultKind::BadAddress);
        }
        let obj = RefObject {
            start: start as u32,
            len,
            layout,
        };
        if let Some(&n) = self.numbers.get(&obj) {
            return Ok(refs::pack(n, 0));
        }
        let n = u32::try_from(self.objects.len() + 1)
            .ok()
            .filter(|n| *n < refs::VIEW)
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
        let Some(obj) = self.objects.get(n as usize - 1) else {
            return Err(if refs::is_view(r) {
                FaultKind::ByteViewAggregate
            } else {
                FaultKind::StaleReference
            });
        };
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

    /// `moved`, the typed pointer `p` moved by `bytes`, as a byte view when
    /// it moved into a STRING's characters (`ADR(str) + 8`, as OSCAT
    /// writes a string from its end) or into a structure's fields
    /// (`ADR(st) + 4`): their bytes are those of their values.
    fn byte_view_of(
        &self,
        p: u64,
        moved: u64,
        bytes: u64,
        unit: u16,
        layouts: &[ByteLayout],
    ) -> u64 {
        if refs::offset(moved) != refs::MISALIGNED || refs::is_view(p) {
            return moved;
        }
        let n = refs::object_number(p);
        let start = if let Some(l) = self.aggregate(n, layouts) {
            match l.byte_of_slot(refs::offset(p)) {
                Some(b) => b,
                None => return moved,
            }
        } else {
            let string = self
                .object(n)
                .and_then(|o| refs::code_elem(o.layout))
                .is_some_and(|e| matches!(e, ElemType::String | ElemType::WString));
            if !string {
                return moved;
            }
            refs::offset(p).wrapping_mul(unit as u32)
        };
        refs::view(refs::object(p), start.wrapping_add(bytes as u32))
    }

    /// The object numbered `n` (view flag removed).
    pub(super) fn object(&self, n: u32) -> Option<&RefObject> {
        self.objects.get((n as usize).checked_sub(1)?)
    }

    /// The byte layout of object `n`, when it is an aggregate that has one.
    pub(super) fn aggregate<'l>(
        &self,
        n: u32,
        layouts: &'l [ByteLayout],
    ) -> Option<&'l ByteLayout> {
        let code = self.object(n)?.layout;
        layouts.get(refs::aggregate_layout(code)?)
    }

    /// Typed pointer `p` as a byte view (`to_view`); into an aggregate, the
    /// byte at which its slot starts (a slot inside a value poisons the
    /// offset: the dereference faults).
    pub(super) fn view_of(&self, p: u64, unit: u16, layouts: &[ByteLayout]) -> u64 {
        if p == refs::NULL || refs::is_view(p) {
            return p;
        }
        match self.aggregate(refs::object(p), layouts) {
            Some(l) => refs::view(
                refs::object(p),
                l.byte_of_slot(refs::offset(p)).unwrap_or(refs::MISALIGNED),
            ),
            None => to_view(p, unit),
        }
    }
}

/// `r` moved to element `idx` of the array `ad` describes (the index is
/// checked against the declared bounds); a byte view moves `unit` bytes
/// per element.
#[inline]
pub fn index(r: u64, idx: u64, ad: &ArrayDesc, unit: u16) -> Result<u64, FaultKind> {
    let i = (idx as i64).wrapping_sub(ad.lo) as u64;
    if i >= ad.len {
        return Err(FaultKind::IndexOutOfRange {
            index: idx as i64,
            lo: ad.lo,
            hi: ad.lo + ad.len as i64 - 1,
        });
    }
    let step = if refs::is_view(r) {
        unit as i64
    } else {
        ad.stride as i64
    };
    Ok(refs::moved(r, (i as i64).wrapping_mul(step)))
}

/// Pointer `p` moved by `bytes` bytes: whole elements of `unit` bytes and
/// `slots` slots (a pointer to an array of one elementary type moves by
/// that type's elements: `ADR(bytes) + 5`). A byte view moves by bytes;
/// a typed pointer moved by part of an element faults when dereferenced
/// (make it a byte view, a `POINTER TO BYTE`, first).
#[inline]
pub fn add_bytes(p: u64, bytes: u64, unit: u16, slots: u16) -> u64 {
    let b = bytes as i64;
    if refs::is_view(p) || p == refs::NULL {
        return refs::moved(p, b);
    }
    let unit = unit.max(1) as i64;
    if b % unit != 0 {
        // An array of one elementary type moves by its elements
        // (`ADR(bytes) + 5`); part of an element poisons the offset.
        let per_slot = unit / (slots.max(1) as i64);
        if per_slot > 0 && per_slot * slots as i64 == unit && b % per_slot == 0 {
            return refs::moved(p, b / per_slot);
        }
        return refs::pack(refs::object(p), refs::MISALIGNED);
    }
    refs::moved(p, (b / unit).wrapping_mul(slots as i64))
}

/// Typed pointer `p` as a byte view, its offset counting `unit` bytes per
/// slot (`NULL` and views are left as they are).
#[inline]
pub fn to_view(p: u64, unit: u16) -> u64 {
    if p == refs::NULL || refs::is_view(p) {
        return p;
    }
    refs::view(
        refs::object(p),
        refs::offset(p).wrapping_mul(unit.max(1) as u32),
    )
}

/// The pointer whose integer image is `v` (`pt := dw`): 0 is `NULL`, any
/// other value a byte view of the object it names (which the dereference
/// checks: R035 if no pointer gave that number).
#[inline]
pub fn from_image(v: u64) -> u64 {
    if v == 0 {
        return refs::NULL;
    }
    let n = (v >> refs::IMAGE_OFFSET_BITS).min((refs::VIEW - 1) as u64) as u32;
    refs::view(n, (v & ((1 << refs::IMAGE_OFFSET_BITS) - 1)) as u32)
}

/// View `v` (from an integer) as a typed pointer to a `ty` when `ty` is a
/// type and the memory it designates holds one there (`vm::type_at`); an
/// aggregate's image counts slots (`PtrToInt`'s unit is 1 for them).
fn typed_from_image(v: u64, ty: u32, img: &Image, table: &RefTable) -> u64 {
    if ty == refs::NO_TYPE || !refs::is_view(v) {
        return v;
    }
    let n = refs::object_number(v);
    let Some(obj) = table.object(n) else {
        return v;
    };
    let off = refs::offset(v);
    let ty = crate::ir::type_table::TypeId(ty);
    // An aggregate's image counts bytes; its values start at slots.
    let layout = table.aggregate(n, &img.byte_layouts);
    let off = match layout {
        Some(l) => match l.slot_of_byte(off) {
            Some(s) => s,
            None => return v,
        },
        None => off,
    };
    // The object itself, or one of its elements, is of its layout's types.
    if let Some(l) = layout
        && ((off == 0 && l.whole == ty)
            || (off % l.period_slots.max(1) == 0 && off < obj.len && l.period == ty))
    {
        return refs::pack(n, off);
    }
    let typed = match refs::code_elem(obj.layout) {
        // A string object: the image of its first byte is the string.
        Some(e @ (ElemType::String | ElemType::WString)) => {
            let wide = e == ElemType::WString;
            off == 0 && matches!(img.types.get(ty).kind, TypeKind::Str { wide: w, .. } if w == wide)
        }
        Some(_) => false,
        None => {
            off as u64 + img.types.size(ty) as u64 <= obj.len as u64
                && super::type_at::holds(img, obj.start + off, ty)
        }
    };
    if typed { refs::pack(n, off) } else { v }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_object_same_number_and_checked_extent() {
        let mut t = RefTable::default();
        let a = t.make(10, 4, 0, 100).unwrap();
        assert_eq!(t.make(10, 4, 0, 100).unwrap(), a);
        let b = t.make(10, 1, 0, 100).unwrap();
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
        assert_eq!(t.make(99, 2, 0, 100), Err(FaultKind::BadAddress));
    }

    #[test]
    fn byte_arithmetic_moves_whole_elements_only() {
        let p = refs::pack(1, 0);
        assert_eq!(add_bytes(p, 8, 4, 1), refs::pack(1, 2));
        assert_eq!(add_bytes(p, (-4i64) as u64, 4, 1), refs::moved(p, -1));
        assert_eq!(refs::offset(add_bytes(p, 3, 4, 1)), refs::MISALIGNED);
        assert_eq!(refs::offset(add_bytes(p, 3, 4, 2)), refs::MISALIGNED);
        // an array of four 1-byte slots moved by 5 bytes: 5 slots
        assert_eq!(add_bytes(p, 5, 4, 4), refs::pack(1, 5));
        // a byte view moves by bytes
        assert_eq!(add_bytes(refs::view(1, 11), 1, 4, 1), refs::view(1, 12));
    }

    #[test]
    fn integer_images_name_objects() {
        assert_eq!(from_image(0), refs::NULL);
        assert_eq!(from_image((3 << 20) + 5), refs::view(3, 5));
        assert_eq!(to_view(refs::pack(2, 3), 4), refs::view(2, 12));
        assert_eq!(to_view(refs::NULL, 4), refs::NULL);
    }
}
