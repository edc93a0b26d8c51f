//! Loads, stores, addresses and array elements. Frame operands need no
//! check (verified); an element index is checked against its descriptor
//! and an address computed at run time against memory, as the
//! interpreter checks them, with the same faults.

use super::proved::Access;
use super::{I64, Lower};
use crate::ir::op::{ArrayIdx, Op, Slot, wrap_s};
use crate::vm::native::helpers::{WHY_BAD_ADDRESS, WHY_OPERANDS};
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{InstBuilder, MemFlagsData, Value, types};
use std::mem::offset_of;

impl Lower<'_, '_> {
    /// Translates a memory instruction; false when `op` is not one.
    pub(super) fn memory(&mut self, op: &Op) -> bool {
        match *op {
            Op::LoadK { d, k } => {
                let v = self.b.ins().iconst(I64, self.img.consts[k.index()] as i64);
                self.set(d, v);
            }
            Op::LoadI { d, imm } => {
                let v = self.b.ins().iconst(I64, imm as i64);
                self.set(d, v);
            }
            Op::Mov { d, s } => {
                let v = self.get(s);
                self.set(d, v);
            }
            Op::LoadAbs { d, abs } => {
                let a = self.b.ins().iconst(I64, abs as i64);
                let v = self.load_at(a, None);
                self.set(d, v);
            }
            Op::StoreAbs { abs, s } => {
                let v = self.get(s);
                let a = self.b.ins().iconst(I64, abs as i64);
                self.store_at(a, v, None);
            }
            Op::LoadInd { d, p, off } => {
                let known = self.pointed(p, i64::from(off), 1);
                let base = self.get(p);
                let a = self.b.ins().iadd_imm_s(base, off as i64);
                let v = self.load_at(a, known);
                self.set(d, v);
            }
            Op::StoreInd { p, off, s } => {
                let known = self.pointed(p, i64::from(off), 1);
                let base = self.get(p);
                let a = self.b.ins().iadd_imm_s(base, off as i64);
                let v = self.get(s);
                self.store_at(a, v, known);
            }
            Op::AddrOf { d, off } => {
                let base = self.base();
                let v = self.b.ins().iadd_imm_s(base, off.index() as i64);
                self.set(d, v);
            }
            Op::AddrAdd { d, p, off } => {
                let x = self.get(p);
                let v = self.b.ins().iadd_imm_s(x, off as i64);
                self.set(d, v);
            }
            Op::Clock { d } => {
                let flags = MemFlagsData::trusted();
                let ctx = self.ctx();
                let v = self
                    .b
                    .ins()
                    .load(I64, flags, ctx, offset_of!(super::Ctx, now) as i32);
                self.set(d, v);
            }
            _ => return self.elements(op),
        }
        true
    }

    fn elements(&mut self, op: &Op) -> bool {
        let flags = MemFlagsData::trusted();
        match *op {
            Op::LoadElem { d, idx, desc } => {
                let at = self.element(idx, desc);
                self.element_access(desc, false);
                let v = self.b.ins().load(I64, flags, at, 0);
                self.set(d, v);
            }
            // The fused store loop runs as its plain element store; its
            // partner `AddBr`, the next instruction, is compiled in place.
            Op::StoreElem { idx, s, desc } | Op::StoreStep { idx, s, desc } => {
                let at = self.element(idx, desc);
                let v = self.get(s);
                self.element_access(desc, true);
                self.b.ins().store(flags, v, at, 0);
            }
            Op::ElemAddr { d, idx, desc } => {
                let i = self.index(idx, desc);
                let rel = self.relative(i, desc);
                let x = self.get(d);
                let v = self.b.ins().iadd(x, rel);
                self.set(d, v);
            }
            Op::ElemRef { d, idx, desc } => {
                let i = self.index(idx, desc);
                let rel = self.relative(i, desc);
                let base = self.base();
                let v = self.b.ins().iadd(base, rel);
                let ad = self.img.arrays[desc.index()];
                let lo = u64::from(ad.offset);
                let hi = lo.saturating_add(ad.len.saturating_mul(u64::from(ad.stride)));
                self.set_pointer(d, v, (lo, hi));
            }
            Op::IndexStep { acc, idx, desc } => {
                let i = self.index(idx, desc);
                let x = self.get(acc);
                let len = self.img.arrays[desc.index()].len;
                let v = self.b.ins().imul_imm_s(x, len as i64);
                let v = self.b.ins().iadd(v, i);
                self.set(acc, v);
            }
            Op::LoadElemU { d, idx, bias } => self.proved_element(idx, bias, Access::Load(d)),
            Op::StoreElemU { idx, s, bias } => self.proved_element(idx, bias, Access::Store(s)),
            Op::FillElems {
                i,
                v,
                lim,
                desc,
                shift,
            } => self.fill(i, v, lim, desc.index(), shift),
            _ => return false,
        }
        true
    }

    /// The element index `idx - lo`, checked against the descriptor's
    /// length (the interpreter's index fault otherwise).
    fn index(&mut self, idx: Slot, desc: ArrayIdx) -> Value {
        let ad = self.img.arrays[desc.index()];
        let x = self.get(idx);
        let i = self.b.ins().iadd_imm_s(x, ad.lo.wrapping_neg());
        let out = self
            .b
            .ins()
            .icmp_imm_s(IntCC::UnsignedGreaterThanOrEqual, i, ad.len as i64);
        self.fault_if(out, WHY_OPERANDS);
        i
    }

    /// `offset + i * stride` in slots.
    fn relative(&mut self, i: Value, desc: ArrayIdx) -> Value {
        let ad = self.img.arrays[desc.index()];
        let scaled = self.b.ins().imul_imm_s(i, ad.stride as i64);
        self.b.ins().iadd_imm_s(scaled, ad.offset as i64)
    }

    /// The checked address of element `idx` of the frame array `desc`.
    pub(super) fn element(&mut self, idx: Slot, desc: ArrayIdx) -> Value {
        let i = self.index(idx, desc);
        let rel = self.relative(i, desc);
        let bytes = self.b.ins().ishl_imm_s(rel, 3);
        let fp = self.fp();
        self.b.ins().iadd(fp, bytes)
    }

    /// The frame slots (relative, `lo..hi`) that `n` slots from `off`
    /// after the address held in `p` may touch, when `p` holds an
    /// element address made in this region (`ElemRef`).
    pub(super) fn pointed(&self, p: Slot, off: i64, n: u64) -> Option<(u64, u64)> {
        let (lo, hi) = self.points_into(p)?;
        let lo = u64::try_from((lo as i64).checked_add(off)?).ok()?;
        let hi = u64::try_from((hi as i64).checked_add(off)?).ok()?;
        Some((lo, hi.checked_add(n)?))
    }

    /// Loads absolute slot `a` (checked against memory; held slots kept
    /// right if it is one of them: written back first when it may be,
    /// in the frame range `known` when that is known).
    fn load_at(&mut self, a: Value, known: Option<(u64, u64)>) -> Value {
        let at = self.checked_address(a);
        if let Some((lo, hi)) = known {
            self.write_back_range(lo, hi);
            return self.b.ins().load(I64, MemFlagsData::trusted(), at, 0);
        }
        let rel = self.frame_relative(a);
        let v = self.guarded(rel, 1, false, |l| {
            Some(l.b.ins().load(I64, MemFlagsData::trusted(), at, 0))
        });
        v.expect("a loaded value")
    }

    /// Stores `v` into absolute slot `a`, as `load_at` loads.
    fn store_at(&mut self, a: Value, v: Value, known: Option<(u64, u64)>) {
        let at = self.checked_address(a);
        if let Some((lo, hi)) = known {
            self.drop_range(lo, hi);
            self.b.ins().store(MemFlagsData::trusted(), v, at, 0);
            return;
        }
        let rel = self.frame_relative(a);
        self.guarded(rel, 1, true, |l| {
            l.b.ins().store(MemFlagsData::trusted(), v, at, 0);
            None
        });
    }

    /// The machine address of absolute slot `a`, which must lie in memory
    /// (a `BadAddress` fault otherwise).
    fn checked_address(&mut self, a: Value) -> Value {
        let len = self.len();
        let out = self.b.ins().icmp(IntCC::UnsignedGreaterThanOrEqual, a, len);
        self.fault_if(out, WHY_BAD_ADDRESS);
        let bytes = self.b.ins().ishl_imm_s(a, 3);
        let mem = self.mem();
        self.b.ins().iadd(mem, bytes)
    }

    /// `FillElems`: when the whole range `i ..= lim` lies in the array and
    /// `lim + 1` fits the type, every element gets `v`, `i` becomes
    /// `lim + 1` and the interrupt word is looked at once; otherwise
    /// nothing happens (the loop after it does the work).
    fn fill(&mut self, i: Slot, v: Slot, lim: i32, desc: usize, shift: u8) {
        let ad = self.img.arrays[desc];
        let last = lim as i64;
        let after = wrap_s((last + 1) as u64, shift);
        let b = last.wrapping_sub(ad.lo);
        if after as i64 != last + 1 || b < 0 || b as u64 >= ad.len {
            return;
        }
        self.drop_range(ad.offset as u64, (ad.offset as u64).saturating_add(ad.len));
        let start = self.get(i);
        let first = self.b.ins().iadd_imm_s(start, ad.lo.wrapping_neg());
        let in_order = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedLessThanOrEqual, start, last);
        let inside = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedGreaterThanOrEqual, first, 0);
        let go = self.b.ins().band(in_order, inside);
        let done = self.b.create_block();
        let value = self.get(v);
        // The elements `first ..= b`: four at a time (two 16-byte
        // stores of the value twice) while four remain, then one at a
        // time. Every store lies in the array, as the interpreter's loop's.
        let fp = self.fp();
        let pair = self.b.ins().splat(types::I64X2, value);
        let arg = cranelift_codegen::ir::BlockArg::Value;
        let (fours, four, ones, one, after_fill) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        let k4 = self.b.append_block_param(fours, I64);
        let k4_in = self.b.append_block_param(four, I64);
        let k1 = self.b.append_block_param(ones, I64);
        let k1_in = self.b.append_block_param(one, I64);
        self.b.ins().brif(go, fours, &[arg(first)], done, &[]);
        // Whether four more elements from `k` lie in the range: k + 3 <= b.
        let room4 =
            |l: &mut Self, k: Value| l.b.ins().icmp_imm_s(IntCC::SignedLessThanOrEqual, k, b - 3);
        let at = |l: &mut Self, k: Value| {
            let slot = l.b.ins().iadd_imm_s(k, ad.offset as i64);
            let bytes = l.b.ins().ishl_imm_s(slot, 3);
            l.b.ins().iadd(fp, bytes)
        };
        // Vector stores need not be aligned: slots are 8-byte aligned.
        let unaligned = MemFlagsData::new().with_notrap();
        self.b.switch_to_block(fours);
        let more = room4(self, k4);
        self.b.ins().brif(more, four, &[arg(k4)], ones, &[arg(k4)]);
        self.b.switch_to_block(four);
        let a = at(self, k4_in);
        self.b.ins().store(unaligned, pair, a, 0);
        self.b.ins().store(unaligned, pair, a, 16);
        let next = self.b.ins().iadd_imm_s(k4_in, 4);
        let more = room4(self, next);
        self.b
            .ins()
            .brif(more, four, &[arg(next)], ones, &[arg(next)]);
        self.b.seal_block(fours);
        self.b.seal_block(four);
        self.b.switch_to_block(ones);
        let more = self.b.ins().icmp_imm_s(IntCC::SignedLessThanOrEqual, k1, b);
        self.b.ins().brif(more, one, &[arg(k1)], after_fill, &[]);
        self.b.switch_to_block(one);
        let a = at(self, k1_in);
        self.b.ins().store(MemFlagsData::trusted(), value, a, 0);
        let next = self.b.ins().iadd_imm_s(k1_in, 1);
        let more = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedLessThanOrEqual, next, b);
        self.b.ins().brif(more, one, &[arg(next)], after_fill, &[]);
        self.b.seal_block(ones);
        self.b.seal_block(one);
        self.b.switch_to_block(after_fill);
        self.b.seal_block(after_fill);
        let end = self.b.ins().iconst(I64, after as i64);
        self.set(i, end);
        self.tick();
        self.b.ins().jump(done, &[]);
        self.b.switch_to_block(done);
        self.b.seal_block(done);
    }
}
