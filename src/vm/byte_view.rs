//! Byte views: a pointer whose element type differs from its object's.
//!
//! OSCAT walks strings byte by byte (`ps : POINTER TO BYTE; ps :=
//! ADR(str)`), reads the bit pattern of a REAL through a `POINTER TO
//! DWORD`, and keeps pointers in DWORDs. Memory here is typed slots and
//! strings live in their own store, so such a pointer is a *byte view*
//! (`ir::refs::VIEW`): its offset counts bytes of the object as CODESYS
//! lays it out, and each access assembles or scatters those bytes,
//! little-endian:
//!
//! - an object of an elementary type (or an array of one) has
//!   `elem_bytes` bytes per slot: the low bytes of the slot's encoding
//!   (`elementary`), so a REAL gives its IEEE bit pattern;
//! - a STRING[n] has n+1 bytes, a WSTRING[n] 2(n+1) (`PlcString::byte_at`);
//! - a structure, or an array of structures or strings, has the bytes
//!   of its values one after another, as its `ir::byte_layout` places them.
//!
//! Every access is checked against the object's bytes (R031), and writes
//! leave each slot in its type's canonical encoding (a signed value
//! sign-extended, a BOOL 0 or 1), so a view can never make a value the
//! typed code could not. The typed path (`vm::refs`) never comes here.

use super::refs::{Memory, RefTable};
use super::{FaultKind, PlcString};
use crate::elementary::ElemType;
use crate::ir::byte_layout::ByteLayout;
use crate::ir::refs;

/// Where a view's bytes are.
pub(super) enum Bytes<'l> {
    /// Slots of an elementary type, `width` bytes each, from `start`.
    Slots {
        start: usize,
        elem: ElemType,
        width: u32,
    },
    /// The string with this id.
    Str(usize),
    /// The slots of an aggregate from `start`, as `layout` places them.
    Aggregate {
        start: usize,
        layout: &'l ByteLayout,
    },
}

impl RefTable {
    /// The bytes of object `n` and their count.
    fn object_bytes<'l>(
        &self,
        n: u32,
        mem: Memory,
        strings: &[PlcString],
        layouts: &'l [ByteLayout],
    ) -> Result<(Bytes<'l>, u32), FaultKind> {
        if n == 0 {
            return Err(FaultKind::NullReference);
        }
        let obj = self.object(n).ok_or(FaultKind::NotFromPointer)?;
        if let Some(layout) = self.aggregate(n, layouts) {
            let slots = layout.period_slots as u64 * layout.repeat as u64;
            if slots > obj.len as u64 {
                return Err(FaultKind::NoByteLayout);
            }
            let start = obj.start as usize;
            return Ok((Bytes::Aggregate { start, layout }, layout.bytes()));
        }
        let elem = refs::code_elem(obj.layout).ok_or(FaultKind::NoByteLayout)?;
        Ok(match elem {
            ElemType::String | ElemType::WString => {
                let id = mem.load(obj.start as usize)? as usize;
                let s = strings.get(id).ok_or(FaultKind::BadAddress)?;
                (Bytes::Str(id), s.byte_len())
            }
            _ => {
                let w = refs::elem_bytes(elem);
                let start = obj.start as usize;
                (
                    Bytes::Slots {
                        start,
                        elem,
                        width: w,
                    },
                    obj.len.saturating_mul(w),
                )
            }
        })
    }

    /// The bytes of the object view `r` designates and their count; checks
    /// that the `width` bytes at the view's offset lie inside them.
    pub(super) fn view_range<'l>(
        &self,
        r: u64,
        width: u32,
        mem: Memory,
        strings: &[PlcString],
        layouts: &'l [ByteLayout],
    ) -> Result<(Bytes<'l>, u32), FaultKind> {
        let (bytes, len) = self.object_bytes(refs::object_number(r), mem, strings, layouts)?;
        let off = refs::offset(r);
        if off as u64 + width as u64 > len as u64 {
            return Err(FaultKind::OutsideBytes {
                offset: off as i32 as i64,
                width,
                len,
            });
        }
        Ok((bytes, len))
    }

    /// The value of type `elem` (a code) view `r` designates.
    pub(super) fn view_load(
        &self,
        r: u64,
        elem: u8,
        mem: Memory,
        strings: &[PlcString],
        layouts: &[ByteLayout],
    ) -> Result<u64, FaultKind> {
        let e = refs::code_elem(elem.into()).ok_or(FaultKind::ByteViewAggregate)?;
        let w = refs::elem_bytes(e);
        let (bytes, _) = self.view_range(r, w, mem, strings, layouts)?;
        let off = refs::offset(r);
        let mut v = 0u64;
        for i in (0..w).rev() {
            v = (v << 8) | self.read_byte(&bytes, off + i, mem, strings)? as u64;
        }
        Ok(canonical(v, w, e))
    }

    /// Writes `value` of type `elem` (a code) where view `r` designates.
    pub(super) fn view_store(
        &mut self,
        r: u64,
        elem: u8,
        value: u64,
        mem: Memory,
        strings: &mut [PlcString],
        layouts: &[ByteLayout],
    ) -> Result<(), FaultKind> {
        let e = refs::code_elem(elem.into()).ok_or(FaultKind::ByteViewAggregate)?;
        let w = refs::elem_bytes(e);
        let (bytes, _) = self.view_range(r, w, mem, strings, layouts)?;
        let off = refs::offset(r);
        for i in 0..w {
            self.write_byte(&bytes, off + i, (value >> (8 * i)) as u8, mem, strings)?;
        }
        Ok(())
    }

    /// The integer image of pointer `r` (`dw := pt`): its object's number
    /// above `IMAGE_OFFSET_BITS` bits, its byte offset below (a typed
    /// pointer's slots count `unit` bytes each, or, into an aggregate with
    /// a byte layout, the bytes before them). Only a pointer inside its
    /// object (or just past its end) has one.
    pub(super) fn image(
        &self,
        r: u64,
        unit: u16,
        mem: Memory,
        strings: &[PlcString],
        layouts: &[ByteLayout],
    ) -> Result<u64, FaultKind> {
        if r == refs::NULL {
            return Ok(0);
        }
        let n = refs::object_number(r);
        let view = self.view_of(r, unit, layouts);
        let len = match self.object(n) {
            Some(obj)
                if refs::code_elem(obj.layout).is_some()
                    || self.aggregate(n, layouts).is_some() =>
            {
                self.object_bytes(n, mem, strings, layouts)?.1
            }
            Some(obj) => obj.len.saturating_mul(unit.max(1) as u32),
            // A pointer made from an integer that named no object: its
            // image is that integer again.
            None => u32::MAX,
        };
        let off = refs::offset(view);
        let limit = 1u64 << refs::IMAGE_OFFSET_BITS;
        if off > len || off as u64 >= limit || n as u64 >= (1 << (32 - refs::IMAGE_OFFSET_BITS)) {
            return Err(FaultKind::NoIntegerImage);
        }
        Ok(((n as u64) << refs::IMAGE_OFFSET_BITS) | off as u64)
    }

    /// The characters a byte view kept past the NUL of string `id`, if
    /// its text is still the one they were written beside.
    fn tail(&self, id: usize, text: &str) -> &[u16] {
        match self.tails.get(&id) {
            Some((t, tail)) if t == text => tail,
            _ => &[],
        }
    }

    fn read_byte(
        &self,
        b: &Bytes,
        k: u32,
        mem: Memory,
        strings: &[PlcString],
    ) -> Result<u8, FaultKind> {
        Ok(match *b {
            Bytes::Slots { start, width, .. } => {
                let slot = mem.load(start + (k / width) as usize)?;
                (slot >> (8 * (k % width))) as u8
            }
            Bytes::Str(id) => self.string_byte(id, k, strings)?,
            Bytes::Aggregate { start, layout } => {
                let at = layout.place(k).ok_or(FaultKind::BadAddress)?;
                let slot = mem.load(start + at.slot as usize)?;
                match at.elem {
                    ElemType::String | ElemType::WString => {
                        self.string_byte(slot as usize, at.at, strings)?
                    }
                    _ => (slot >> (8 * at.at)) as u8,
                }
            }
        })
    }

    /// Byte `k` of the buffer of string `id`.
    fn string_byte(&self, id: usize, k: u32, strings: &[PlcString]) -> Result<u8, FaultKind> {
        let s = strings.get(id).ok_or(FaultKind::BadAddress)?;
        Ok(s.byte_at(k, self.tail(id, &s.text)))
    }

    /// Writes byte `k` of the buffer of string `id`, keeping what lies
    /// past its NUL (`PlcString::set_byte`).
    fn set_string_byte(
        &mut self,
        id: usize,
        k: u32,
        byte: u8,
        strings: &mut [PlcString],
    ) -> Result<(), FaultKind> {
        let s = strings.get_mut(id).ok_or(FaultKind::BadAddress)?;
        let mut tail = self.tail(id, &s.text).to_vec();
        s.set_byte(k, byte, &mut tail);
        if tail.is_empty() {
            self.tails.remove(&id);
        } else {
            self.tails.insert(id, (s.text.clone(), tail));
        }
        Ok(())
    }

    fn write_byte(
        &mut self,
        b: &Bytes,
        k: u32,
        byte: u8,
        mem: Memory,
        strings: &mut [PlcString],
    ) -> Result<(), FaultKind> {
        match *b {
            Bytes::Slots { start, elem, width } => {
                let a = start + (k / width) as usize;
                let shift = 8 * (k % width);
                let old = mem.load(a)?;
                let new = (old & !(0xFF << shift)) | ((byte as u64) << shift);
                mem.store(a, canonical(new, width, elem))
            }
            Bytes::Str(id) => self.set_string_byte(id, k, byte, strings),
            Bytes::Aggregate { start, layout } => {
                let at = layout.place(k).ok_or(FaultKind::BadAddress)?;
                let a = start + at.slot as usize;
                let old = mem.load(a)?;
                match at.elem {
                    ElemType::String | ElemType::WString => {
                        self.set_string_byte(old as usize, at.at, byte, strings)
                    }
                    elem => {
                        let shift = 8 * at.at;
                        let new = (old & !(0xFF << shift)) | ((byte as u64) << shift);
                        mem.store(a, canonical(new, at.width, elem))
                    }
                }
            }
        }
    }
}

/// The slot encoding of type `e` whose low `w` bytes are those of `v`:
/// signed integers sign-extended, BOOL 1 for any non-zero byte, the rest
/// zero-extended (a REAL keeps its bit pattern in the low 32 bits).
fn canonical(v: u64, w: u32, e: ElemType) -> u64 {
    let bits = 8 * w;
    let low = if bits >= 64 {
        v
    } else {
        v & ((1u64 << bits) - 1)
    };
    if e == ElemType::Bool {
        return (low != 0) as u64;
    }
    if e.is_signed_int() && bits < 64 {
        let sh = 64 - bits;
        return (((low << sh) as i64) >> sh) as u64;
    }
    low
}

#[cfg(test)]
mod tests {
    use super::canonical;
    use crate::elementary::ElemType;

    #[test]
    fn canonical_encodings() {
        assert_eq!(canonical(0xFF, 1, ElemType::Sint), u64::MAX);
        assert_eq!(canonical(0x1FF, 1, ElemType::Byte), 0xFF);
        assert_eq!(canonical(0x40, 1, ElemType::Bool), 1);
        assert_eq!(canonical(0x8000, 2, ElemType::Int) as i64, -32768);
        assert_eq!(canonical(0x3F80_0000, 4, ElemType::Real), 0x3F80_0000);
    }
}
