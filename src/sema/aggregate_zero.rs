//! Clearing arrays and structures to zero, as CODESYS code does with
//! `MEMSET(ADR(x), 0, SIZEOF(x))` (memory_idioms.rs): every number 0,
//! every BOOL FALSE, every pointer, reference and interface NULL, every
//! STRING empty. A STRING slot holds the id of its own buffer, so a
//! string is emptied by text and its slot keeps its id.

use super::aggregate_copy::FieldPart;
use super::body::BodyBuilder;
use crate::ir::op::{Op, Slot, Target};
use crate::ir::type_table::{TypeId, TypeKind};

/// Zero slots stored one by one without a loop.
const UNROLL_SLOTS: u32 = 8;
/// Elements of a string-holding array cleared one by one without a loop.
const UNROLL_ELEMS: u64 = 4;

impl BodyBuilder<'_> {
    /// Whether a value of type `ty` can be cleared to zero: it holds no
    /// function block instance (whose hidden state zero bytes would
    /// break) and no SFC step.
    pub(super) fn can_zero(&self, ty: TypeId) -> bool {
        match &self.types.get(ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. }
            | TypeKind::Ref { .. } => true,
            TypeKind::Array { elem, .. } => self.can_zero(*elem),
            TypeKind::Struct { fields } => fields.iter().all(|f| self.can_zero(f.ty)),
            _ => false,
        }
    }

    /// Clears `count` consecutive values of `elem` at offset `off` from
    /// the address in slot `d` (`can_zero(elem)` holds).
    pub(super) fn zero_elems(&mut self, d: Slot, elem: TypeId, off: u32, count: u64) {
        let stride = self.types.size(elem);
        if !self.contains_strings(elem) {
            // Arrays are at most MAX_FRAME_SLOTS long: the product fits.
            let n = u32::try_from(count.saturating_mul(stride as u64)).unwrap_or(u32::MAX);
            self.zero_plain(d, off, n);
        } else if count <= UNROLL_ELEMS {
            for i in 0..count as u32 {
                self.zero_at(d, elem, off + i * stride);
            }
        } else {
            self.zero_loop(d, elem, off, count, stride);
        }
    }

    /// Clears the `ty` at offset `off` from the address in `d`.
    fn zero_at(&mut self, d: Slot, ty: TypeId, off: u32) {
        match self.types.get(ty).kind.clone() {
            _ if !self.contains_strings(ty) => {
                let n = self.types.size(ty);
                self.zero_plain(d, off, n);
            }
            TypeKind::Str { .. } => {
                let id = self.block.temp();
                self.block.emit(Op::LoadInd { d: id, p: d, off });
                let k = self.out.str_const("");
                self.block.emit(Op::StrConst { d: id, k });
            }
            TypeKind::Struct { fields } => {
                // Runs of string-free fields are cleared together.
                for part in self.field_parts(&fields) {
                    match part {
                        FieldPart::Plain { at, n } => self.zero_plain(d, off + at, n),
                        FieldPart::Strings { at, ty } => self.zero_at(d, ty, off + at),
                    }
                }
            }
            TypeKind::Array { dims, elem } => {
                let count: u64 = dims.iter().map(|d| d.len()).product();
                self.zero_elems(d, elem, off, count);
            }
            _ => {
                let n = self.types.size(ty);
                self.zero_plain(d, off, n);
            }
        }
    }

    /// Stores 0 in the `n` string-free slots at offset `off`.
    fn zero_plain(&mut self, d: Slot, off: u32, n: u32) {
        if n == 0 {
            return;
        }
        let zero = self.block.const_slot(0);
        if n <= UNROLL_SLOTS {
            for i in 0..n {
                self.block.emit(Op::StoreInd {
                    p: d,
                    off: off + i,
                    s: zero,
                });
            }
            return;
        }
        let (p, left) = (self.block.temp(), self.block.temp());
        self.block.emit(Op::AddrAdd { d: p, p: d, off });
        self.block.emit(Op::LoadI {
            d: left,
            imm: i32::try_from(n).unwrap_or(i32::MAX),
        });
        self.block.last_def = None;
        let top = self.block.here();
        self.block.emit(Op::StoreInd { p, off: 0, s: zero });
        self.block.emit(Op::AddrAdd { d: p, p, off: 1 });
        self.count_down(left, top);
    }

    /// Clears `count` elements of `elem` (`stride` slots apart) from
    /// offset `off` in a loop over a moving address.
    fn zero_loop(&mut self, d: Slot, elem: TypeId, off: u32, count: u64, stride: u32) {
        let (p, left) = (self.block.temp(), self.block.temp());
        self.block.emit(Op::AddrAdd { d: p, p: d, off });
        // Arrays are at most MAX_FRAME_SLOTS long, well inside an i32.
        let n = i32::try_from(count).unwrap_or(i32::MAX);
        self.block.emit(Op::LoadI { d: left, imm: n });
        self.block.last_def = None;
        let top = self.block.here();
        self.zero_at(p, elem, 0);
        self.block.emit(Op::AddrAdd {
            d: p,
            p,
            off: stride,
        });
        self.count_down(left, top);
    }

    /// Decrements `left` and jumps back to `top` while it is not zero.
    pub(super) fn count_down(&mut self, left: Slot, top: Target) {
        self.block.emit(Op::AddSI {
            d: left,
            a: left,
            imm: -1,
            shift: 0,
        });
        self.block.last_def = None;
        self.block.emit(Op::Jnz { c: left, t: top });
        self.block.here();
    }
}
