//! Link-time verification of an image. The executor reads and writes frame
//! slots without bounds checks; this pass is what makes that sound: every
//! frame operand of every block must lie inside the block's frame, every
//! jump inside the block, every block must end with `Ret`, and every frame
//! a block can run on must lie inside memory.

use super::image::{CodeKind, Image};
use super::op::Op;
use super::operands::{for_each_slot, slot_span, target_mut};

/// Checks the invariants the executor relies on; the error names the first
/// violation (it indicates a compiler bug, never a user error).
pub fn verify(image: &Image) -> Result<(), String> {
    let mem = image.memory.len() as u64;
    for (ci, c) in image.codes.iter().enumerate() {
        let size = c.frame_size as u64;
        let fail = |pc: usize, what: &str| Err(format!("code {ci} `{}` op {pc}: {what}", c.name));
        if !matches!(c.ops.last(), Some(Op::Ret)) {
            return fail(c.ops.len(), "block does not end with Ret");
        }
        if c.spans.len() != c.ops.len() {
            return fail(0, "span table length differs from the instruction count");
        }
        if c.kind == CodeKind::Function && c.frame as u64 + size > mem {
            return fail(0, "function frame outside memory");
        }
        for &(slot, _) in &c.entry_init {
            if slot as u64 >= size {
                return fail(0, "entry reset outside the frame");
            }
        }
        for &(slot, k) in &c.entry_strings {
            if slot as u64 >= size || k as usize >= image.str_consts.len() {
                return fail(0, "entry string reset out of range");
            }
        }
        // An array the executor indexes with a checked index but unchecked
        // element access: every element lies inside the frame.
        let elements_in_frame = |desc: u32| {
            image.arrays.get(desc as usize).is_some_and(|d| {
                d.stride >= 1 && d.offset as u64 + d.len.saturating_mul(d.stride as u64) <= size
            })
        };
        for (pc, op) in c.ops.iter().enumerate() {
            let mut op = *op;
            let mut bad = false;
            for_each_slot(&mut op, &mut |s| {
                if *s as u64 >= size {
                    bad = true;
                }
            });
            // Operands that start a run of consecutive slots.
            let run = match op {
                Op::Mux { first, .. } => Some(first),
                Op::StrCall { a, .. } => Some(a),
                _ => None,
            };
            if let Some(start) = run
                && start as u64 + slot_span(&op) as u64 > size
            {
                bad = true;
            }
            if bad {
                return fail(pc, "frame operand outside the frame");
            }
            if let Some(t) = target_mut(&mut op)
                && (*t as usize >= c.ops.len() || matches!(c.ops[*t as usize], Op::Operand { .. }))
            {
                return fail(pc, "jump target outside the block or onto an operand word");
            }
            if matches!(op, Op::MulAddF32 { .. } | Op::MulAddF64 { .. })
                && !matches!(c.ops.get(pc + 1), Some(Op::Operand { .. }))
            {
                return fail(pc, "two-word instruction without its operand word");
            }
            if !super::fuse::partner_ok(&c.ops, pc) {
                return fail(pc, "loop superinstruction without its partner instruction");
            }
            let ok = match op {
                Op::AddBr { t, .. } => c
                    .ops
                    .get(t as usize)
                    .is_some_and(|o| !matches!(o, Op::Operand { .. })),
                Op::FillElems { desc, .. } => image
                    .arrays
                    .get(desc as usize)
                    .is_some_and(|d| d.stride == 1 && d.offset as u64 + d.len <= size),
                Op::ForScan { desc, .. } => elements_in_frame(desc as u32),
                Op::LoadElem { desc, .. }
                | Op::StoreElem { desc, .. }
                | Op::StoreStep { desc, .. }
                | Op::JzElem { desc, .. }
                | Op::JnzElem { desc, .. } => elements_in_frame(desc),
                Op::ElemRef { desc, .. } => image.arrays.get(desc as usize).is_some_and(|d| {
                    d.offset as u64 + d.len.saturating_mul(d.stride as u64) <= size
                }),
                Op::ElemAddr { desc, .. } | Op::IndexStep { desc, .. } => {
                    (desc as usize) < image.arrays.len()
                }
                Op::LoadAbs { abs, .. } | Op::StoreAbs { abs, .. } => (abs as u64) < mem,
                Op::LoadK { k, .. } => (k as usize) < image.consts.len(),
                Op::StrConst { k, .. } => (k as usize) < image.str_consts.len(),
                Op::ToStr { ty, .. } | Op::FromStr { ty, .. } => {
                    (ty as usize) < image.scalar_types.len()
                }
                Op::CallFb { code, inst } => image.codes.get(code as usize).is_some_and(|callee| {
                    callee.kind == CodeKind::FunctionBlock
                        && inst as u64 + callee.frame_size as u64 <= size
                }),
                Op::CallFbInd { code, .. } => image
                    .codes
                    .get(code as usize)
                    .is_some_and(|callee| callee.kind == CodeKind::FunctionBlock),
                Op::CallNative { fb, inst } => {
                    inst as u64 + crate::stdlib::interface(fb).len() as u64 <= size
                }
                Op::CallFn { code } => image
                    .codes
                    .get(code as usize)
                    .is_some_and(|callee| callee.kind == CodeKind::Function),
                _ => true,
            };
            if !ok {
                return fail(pc, "table index, address or callee frame out of range");
            }
        }
    }
    for p in &image.programs {
        let Some(c) = image.codes.get(p.code as usize) else {
            return Err(format!("program `{}` has no code", p.name));
        };
        if p.base as u64 + c.frame_size as u64 > mem {
            return Err(format!("program instance `{}` outside memory", p.name));
        }
        let connections = p.inputs.iter().chain(&p.outputs);
        if connections
            .into_iter()
            .any(|&(a, b)| a as u64 >= mem || b as u64 >= mem)
        {
            return Err(format!("a connection of `{}` is outside memory", p.name));
        }
    }
    Ok(())
}
