//! Memory accesses that may land on a held slot. An element of a frame
//! array lies in a range known when translating: held slots in it are
//! written back (read) or dropped (write) there. An address computed at
//! run time (through a pointer, an absolute address, a proved element
//! index) is compared with the held slots' ranges first: when it may hit
//! one, a cold path writes every held value back before the access and
//! loads them all again after a write, so held values and memory agree
//! on both paths.

use super::Lower;
use crate::ir::op::ArrayIdx;
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{InstBuilder, Value};

/// The most ranges one check compares with (nearby held slots share one).
const MAX_RANGES: usize = 4;
/// Held slots this close share a range.
const GAP: u32 = 16;

impl Lower<'_, '_> {
    /// Before an access to an element of frame array `desc`: held slots
    /// of the array written back (`writes`: also dropped).
    pub(super) fn element_access(&mut self, desc: ArrayIdx, writes: bool) {
        let ad = self.img.arrays[desc.index()];
        let lo = ad.offset as u64;
        let hi = lo.saturating_add(ad.len.saturating_mul(ad.stride as u64));
        if writes {
            self.drop_range(lo, hi);
        } else {
            self.write_back_range(lo, hi);
        }
    }

    /// Runs `access`, which touches `n` slots from frame-relative slot
    /// `rel` (any value: an address below the frame wraps around), so
    /// that held slots stay right if it touches one of them.
    pub(super) fn guarded(
        &mut self,
        rel: Value,
        n: u64,
        writes: bool,
        access: impl FnOnce(&mut Self) -> Option<Value>,
    ) -> Option<Value> {
        let ranges = ranges_of(self.cache.held.iter().map(|h| h.slot).collect());
        if ranges.is_empty() {
            return access(self);
        }
        // `[rel, rel + n)` meets `[lo, hi]` iff `rel - (lo - n + 1)`,
        // unsigned, is at most `hi - lo + n - 1`.
        let mut hit: Option<Value> = None;
        for (lo, hi) in ranges {
            let start = i64::from(lo) - (n as i64 - 1);
            let width = u64::from(hi - lo) + n;
            let d = self.b.ins().iadd_imm_s(rel, start.wrapping_neg());
            let c = self
                .b
                .ins()
                .icmp_imm_s(IntCC::UnsignedLessThan, d, width as i64);
            hit = Some(match hit {
                Some(h) => self.b.ins().bor(h, c),
                None => c,
            });
        }
        let hit = hit.expect("one range at least");
        let flush = self.b.create_block();
        let mid = self.b.create_block();
        self.b.set_cold_block(flush);
        self.b.ins().brif(hit, flush, &[], mid, &[]);
        self.b.switch_to_block(flush);
        self.b.seal_block(flush);
        self.aside(|l| {
            l.write_back_copy();
            l.b.ins().jump(mid, &[]);
        });
        self.b.switch_to_block(mid);
        self.b.seal_block(mid);
        let result = access(self);
        if writes {
            let reload = self.b.create_block();
            let after = self.b.create_block();
            self.b.set_cold_block(reload);
            self.b.ins().brif(hit, reload, &[], after, &[]);
            self.b.switch_to_block(reload);
            self.b.seal_block(reload);
            self.aside(|l| {
                l.reload_copy();
                l.b.ins().jump(after, &[]);
            });
            self.b.switch_to_block(after);
            self.b.seal_block(after);
            self.forget_floats();
        }
        result
    }

    /// The frame-relative slot of absolute slot `a`.
    pub(super) fn frame_relative(&mut self, a: Value) -> Value {
        let base = self.base();
        self.b.ins().isub(a, base)
    }
}

/// `slots` as at most [`MAX_RANGES`] inclusive ranges covering them all
/// (slots closer than [`GAP`] share one; beyond the maximum, the closest
/// neighbours merge).
fn ranges_of(mut slots: Vec<u32>) -> Vec<(u32, u32)> {
    slots.sort_unstable();
    slots.dedup();
    let mut ranges: Vec<(u32, u32)> = Vec::new();
    for s in slots {
        match ranges.last_mut() {
            Some(r) if s - r.1 <= GAP => r.1 = s,
            _ => ranges.push((s, s)),
        }
    }
    while ranges.len() > MAX_RANGES {
        let i = (0..ranges.len() - 1)
            .min_by_key(|&i| ranges[i + 1].0 - ranges[i].1)
            .expect("two ranges at least");
        ranges[i].1 = ranges[i + 1].1;
        ranges.remove(i + 1);
    }
    ranges
}

#[cfg(test)]
mod tests {
    use super::ranges_of;

    #[test]
    fn held_slots_make_at_most_four_ranges_that_cover_them() {
        assert_eq!(ranges_of(vec![]), vec![]);
        assert_eq!(
            ranges_of(vec![5, 1, 20, 16000]),
            vec![(1, 20), (16000, 16000)]
        );
        let many = vec![0, 100, 200, 250, 400, 1000, 1001];
        let r = ranges_of(many.clone());
        assert_eq!(r, vec![(0, 100), (200, 250), (400, 400), (1000, 1001)]);
        for s in many {
            assert!(r.iter().any(|&(lo, hi)| (lo..=hi).contains(&s)), "{s}");
        }
    }
}
