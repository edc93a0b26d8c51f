//! Copying arrays and structures by value. A STRING slot holds the id of
//! its own string buffer, so a byte copy would make two variables share
//! one buffer: strings are copied by text (`StrMov` between the two
//! buffers), the slots around them by `MemCopy`. Arrays of more than a few
//! string-holding elements copy in a loop, so the code stays small.

use super::body::BodyBuilder;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{Member, TypeId, TypeKind};

/// Elements of a string-holding array copied one by one without a loop.
const UNROLL_ELEMS: u64 = 4;

/// Part of a structure's slots ([`BodyBuilder::field_parts`]).
pub(super) enum FieldPart {
    /// `n` string-free slots at offset `at`.
    Plain { at: u32, n: u32 },
    /// A field holding strings, of type `ty`, at offset `at`.
    Strings { at: u32, ty: TypeId },
}

impl BodyBuilder<'_> {
    /// Copies a value of type `ty` from the address in slot `s` to the
    /// address in slot `d` (both aggregates of that type).
    pub(super) fn copy_value(&mut self, d: Slot, s: Slot, ty: TypeId) {
        if !self.contains_strings(ty) {
            let n = self.types.size(ty);
            self.block.emit(Op::MemCopy { d, s, n });
            return;
        }
        self.copy_at(d, s, ty, 0);
    }

    /// Copies the `ty` at offset `off` from the addresses in `d` and `s`.
    pub(super) fn copy_at(&mut self, d: Slot, s: Slot, ty: TypeId, off: u32) {
        match self.types.get(ty).kind.clone() {
            _ if !self.contains_strings(ty) => {
                let n = self.types.size(ty);
                self.copy_plain(d, s, off, n);
            }
            TypeKind::Str { .. } => {
                let (di, si) = (self.block.temp(), self.block.temp());
                self.block.emit(Op::LoadInd { d: di, p: d, off });
                self.block.emit(Op::LoadInd { d: si, p: s, off });
                self.block.emit(Op::StrMov { d: di, s: si });
            }
            TypeKind::Struct { fields } => {
                // Runs of string-free fields are copied in one MemCopy.
                for part in self.field_parts(&fields) {
                    match part {
                        FieldPart::Plain { at, n } => self.copy_plain(d, s, off + at, n),
                        FieldPart::Strings { at, ty } => self.copy_at(d, s, ty, off + at),
                    }
                }
            }
            TypeKind::Array { dims, elem } => {
                let count: u64 = dims.iter().map(|d| d.len()).product();
                self.copy_elems(d, s, elem, off, count);
            }
            TypeKind::Pou { .. } => self.copy_fb_at(d, s, ty, off),
            _ => {
                let n = self.types.size(ty);
                self.copy_plain(d, s, off, n);
            }
        }
    }

    /// Copies `count` consecutive values of `elem` at offset `off` from
    /// the addresses in `d` and `s`.
    pub(super) fn copy_elems(&mut self, d: Slot, s: Slot, elem: TypeId, off: u32, count: u64) {
        let stride = self.types.size(elem);
        if !self.contains_strings(elem) {
            // Arrays are at most MAX_FRAME_SLOTS long: the product fits.
            let n = u32::try_from(count.saturating_mul(stride as u64)).unwrap_or(u32::MAX);
            self.copy_plain(d, s, off, n);
        } else if count <= UNROLL_ELEMS {
            for i in 0..count as u32 {
                self.copy_at(d, s, elem, off + i * stride);
            }
        } else {
            self.copy_loop(d, s, elem, off, count, stride);
        }
    }

    /// A structure's fields as runs of adjacent string-free slots and
    /// the string-holding fields between them, in order.
    pub(super) fn field_parts(&self, fields: &[Member]) -> Vec<FieldPart> {
        let mut parts = Vec::new();
        let mut run: Option<(u32, u32)> = None;
        for f in fields {
            let size = self.types.size(f.ty);
            if self.contains_strings(f.ty) {
                if let Some((at, n)) = run.take() {
                    parts.push(FieldPart::Plain { at, n });
                }
                parts.push(FieldPart::Strings {
                    at: f.offset,
                    ty: f.ty,
                });
                continue;
            }
            run = match run {
                Some((at, n)) if at + n == f.offset => Some((at, n + size)),
                Some((at, n)) => {
                    parts.push(FieldPart::Plain { at, n });
                    Some((f.offset, size))
                }
                None => Some((f.offset, size)),
            };
        }
        if let Some((at, n)) = run {
            parts.push(FieldPart::Plain { at, n });
        }
        parts
    }

    /// `MemCopy` of `n` string-free slots at offset `off`.
    pub(super) fn copy_plain(&mut self, d: Slot, s: Slot, off: u32, n: u32) {
        if n == 0 {
            return;
        }
        let (da, sa) = (self.block.temp(), self.block.temp());
        self.block.emit(Op::AddrAdd { d: da, p: d, off });
        self.block.emit(Op::AddrAdd { d: sa, p: s, off });
        self.block.emit(Op::MemCopy { d: da, s: sa, n });
    }

    /// Copies `count` elements of `elem` (`stride` slots apart) from
    /// offset `off` in a loop over two moving addresses.
    fn copy_loop(&mut self, d: Slot, s: Slot, elem: TypeId, off: u32, count: u64, stride: u32) {
        let (dp, sp, left) = (self.block.temp(), self.block.temp(), self.block.temp());
        self.block.emit(Op::AddrAdd { d: dp, p: d, off });
        self.block.emit(Op::AddrAdd { d: sp, p: s, off });
        // Arrays are at most MAX_FRAME_SLOTS long, well inside an i32.
        let n = i32::try_from(count).unwrap_or(i32::MAX);
        self.block.emit(Op::LoadI { d: left, imm: n });
        self.block.last_def = None;
        let top = self.block.here();
        self.copy_at(dp, sp, elem, 0);
        self.block.emit(Op::AddrAdd {
            d: dp,
            p: dp,
            off: stride,
        });
        self.block.emit(Op::AddrAdd {
            d: sp,
            p: sp,
            off: stride,
        });
        self.count_down(left, top);
    }
}
