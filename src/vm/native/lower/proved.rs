//! Element accesses whose index the compiler proved in range
//! (`LoadElemU`, `StoreElemU`). The interpreter still checks that the
//! slot lies in the frame, and a held slot must stay right if it is the
//! one touched. Both questions have the same answer for every slot of the
//! run of frame slots around the element's bias that holds no held slot,
//! where a proved access lands: one comparison sends such an access
//! straight to memory, and anything else takes the full checks on a cold
//! path. Same faults, same memory, fewer instructions in a loop over an
//! array (three where there were seven to ten).

use super::{I64, Lower};
use crate::ir::op::Slot;
use crate::vm::native::helpers::WHY_BAD_ADDRESS;
use cranelift_codegen::entity::EntityRef;
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{Block, BlockArg, InstBuilder, MemFlagsData, Value};

/// What a proved access does.
#[derive(Clone, Copy)]
pub(super) enum Access {
    /// Loads the element into this slot.
    Load(Slot),
    /// Stores this slot's value into the element.
    Store(Slot),
}

impl Lower<'_, '_> {
    /// Translates `LoadElemU`/`StoreElemU`: frame slot `idx + bias`.
    pub(super) fn proved_element(&mut self, idx: Slot, bias: i32, access: Access) {
        let x = self.get(idx);
        let stored = match access {
            Access::Store(s) => Some(self.get(s)),
            Access::Load(_) => None,
        };
        let loaded = match self.free_run(bias) {
            Some((lo, hi)) => self.fast_or_checked(x, bias, stored, (lo, hi)),
            None => self.checked_element(x, bias, stored),
        };
        match access {
            Access::Load(d) => self.set(d, loaded.expect("a loaded value")),
            // The cold path may have loaded held values again.
            Access::Store(_) => self.forget_floats(),
        }
    }

    /// The run `lo..hi` of frame slots that holds no held slot and
    /// contains `bias` (or, when `bias` is held, begins right after the
    /// held slots there); `None` when there is none or the displacement
    /// does not fit an instruction.
    fn free_run(&self, bias: i32) -> Option<(u64, u64)> {
        let frame = u64::from(self.img.codes[self.code.index()].frame_size);
        let mut held: Vec<u64> = self.cache.held.iter().map(|h| u64::from(h.slot)).collect();
        held.sort_unstable();
        let mut p = u64::try_from(bias).ok()?;
        for &h in &held {
            if h == p {
                p += 1;
            }
        }
        let lo = held.iter().rev().find(|&&h| h < p).map_or(0, |&h| h + 1);
        let hi = held
            .iter()
            .find(|&&h| h > p)
            .copied()
            .unwrap_or(frame)
            .min(frame);
        let displacement_fits = i32::try_from(i64::from(bias) * 8).is_ok();
        (p < hi && displacement_fits).then_some((lo, hi))
    }

    /// One comparison, then the access straight to memory; the checked
    /// access on a cold path when the slot falls outside `lo..hi`.
    fn fast_or_checked(
        &mut self,
        x: Value,
        bias: i32,
        stored: Option<Value>,
        (lo, hi): (u64, u64),
    ) -> Option<Value> {
        let rel = self.b.ins().iadd_imm_s(x, i64::from(bias) - lo as i64);
        let inside = self
            .b
            .ins()
            .icmp_imm_s(IntCC::UnsignedLessThan, rel, (hi - lo) as i64);
        let (fast, slow, join) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        let result = stored
            .is_none()
            .then(|| self.b.append_block_param(join, I64));
        let fp = self.fp();
        self.b.set_cold_block(slow);
        self.b.ins().brif(inside, fast, &[], slow, &[]);

        self.b.switch_to_block(fast);
        self.b.seal_block(fast);
        let bytes = self.b.ins().ishl_imm_s(x, 3);
        let addr = self.b.ins().iadd(fp, bytes);
        let flags = MemFlagsData::trusted();
        let displacement = bias * 8;
        let args: Vec<BlockArg> = match stored {
            Some(v) => {
                self.b.ins().store(flags, v, addr, displacement);
                Vec::new()
            }
            None => vec![BlockArg::Value(self.b.ins().load(
                I64,
                flags,
                addr,
                displacement,
            ))],
        };
        self.b.ins().jump(join, &args);

        self.b.switch_to_block(slow);
        self.b.seal_block(slow);
        // Every block the checks make is cold too, so that the layout
        // keeps the fast path straight.
        let first_new = self.b.func.dfg.num_blocks();
        let loaded = self.aside(|l| {
            let v = l.checked_element(x, bias, stored);
            let args: Vec<BlockArg> = v.into_iter().map(BlockArg::Value).collect();
            l.b.ins().jump(join, &args);
            v
        });
        for k in first_new..self.b.func.dfg.num_blocks() {
            self.b.set_cold_block(Block::new(k));
        }
        debug_assert_eq!(loaded.is_some(), result.is_some());

        self.b.switch_to_block(join);
        self.b.seal_block(join);
        result
    }

    /// The interpreter's checks in full: the slot inside the frame (a
    /// `BadAddress` fault otherwise), held slots written back before it
    /// is read and loaded again after it is written when it may be one.
    fn checked_element(&mut self, x: Value, bias: i32, stored: Option<Value>) -> Option<Value> {
        let at = self.b.ins().iadd_imm_s(x, i64::from(bias));
        let frame = i64::from(self.img.codes[self.code.index()].frame_size);
        let out = self
            .b
            .ins()
            .icmp_imm_s(IntCC::UnsignedGreaterThanOrEqual, at, frame);
        self.fault_if(out, WHY_BAD_ADDRESS);
        let bytes = self.b.ins().ishl_imm_s(at, 3);
        let fp = self.fp();
        let addr = self.b.ins().iadd(fp, bytes);
        let flags = MemFlagsData::trusted();
        match stored {
            None => self.guarded(at, 1, false, |l| Some(l.b.ins().load(I64, flags, addr, 0))),
            Some(v) => self.guarded(at, 1, true, |l| {
                l.b.ins().store(flags, v, addr, 0);
                None
            }),
        }
    }
}
