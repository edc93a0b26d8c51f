//! Loop superinstructions. After a block is emitted, two-instruction loops
//! whose instructions always run as a pair are marked so that the executor
//! runs the whole loop in one dispatch:
//!
//! - `StoreElem` + `AddBr` jumping back to it becomes [`Op::StoreStep`]
//!   (`WHILE j <= n DO a[j] := v; j := j + k; END_WHILE`);
//! - `ForNext` whose body starts with a `JzElem`/`JnzElem` on the loop
//!   variable that jumps back to it becomes [`Op::ForScan`]
//!   (`FOR i := a TO b DO IF f[i] THEN ... END_IF; END_FOR`).
//!
//! Only the first instruction of a pair changes; the second stays where it
//! was, so jumps into the pair and fault locations are unchanged. The fused
//! forms re-read every operand on every iteration, exactly as the pair
//! does, so they need no knowledge of aliasing.

use super::op::{ArrayIdx, Op, ShortArrayIdx, ShortTarget, Slot, Target};

/// Rewrites the fusable loop pairs of one code block in place.
pub fn fuse_loops(ops: &mut [Op]) {
    for at in 0..ops.len() {
        if let Some(fused) = fused(ops, at) {
            ops[at] = fused;
        }
    }
}

/// The superinstruction that may replace `ops[at]`, if any.
fn fused(ops: &[Op], at: usize) -> Option<Op> {
    match ops[at] {
        Op::StoreElem { idx, s, desc } => match ops.get(at + 1)? {
            Op::AddBr { d, t, .. } if *d == idx && t.index() == at => {
                Some(Op::StoreStep { idx, s, desc })
            }
            _ => None,
        },
        Op::ForNext {
            i,
            lim,
            t,
            step,
            shift,
        } => {
            let (idx, desc, back, when) = element_test(ops.get(t.index())?)?;
            if idx != i || back.index() != at {
                return None;
            }
            Some(Op::ForScan {
                i,
                lim,
                t: ShortTarget::new(u16::try_from(t.get()).ok()?),
                desc: ShortArrayIdx::new(u16::try_from(desc.get()).ok()?),
                step: i8::try_from(step).ok()?,
                shift,
                when,
            })
        }
        _ => None,
    }
}

/// A branch on a BOOL array element as (index slot, descriptor, target,
/// value of the element for which it falls through).
fn element_test(op: &Op) -> Option<(Slot, ArrayIdx, Target, bool)> {
    match *op {
        Op::JzElem { idx, desc, t } => Some((idx, desc, t, true)),
        Op::JnzElem { idx, desc, t } => Some((idx, desc, t, false)),
        _ => None,
    }
}

/// Whether the `StoreStep` at `ops[at]` is still followed by the `AddBr`
/// stepping its index back to it (named by the instruction list as its
/// partner check; the verifier runs it, the executor relies on it).
pub fn store_step_partner(ops: &[Op], at: usize) -> bool {
    let Some(Op::StoreStep { idx, .. }) = ops.get(at) else {
        return false;
    };
    matches!(
        ops.get(at + 1),
        Some(Op::AddBr { d, t, .. }) if d == idx && t.index() == at
    )
}

/// Whether the `ForScan` at `ops[at]` still targets the element test on its
/// variable that jumps back to it, with the loop body after that test.
pub fn for_scan_partner(ops: &[Op], at: usize) -> bool {
    let Some(&Op::ForScan {
        i, t, desc, when, ..
    }) = ops.get(at)
    else {
        return false;
    };
    let test = ops.get(t.index()).and_then(element_test);
    test.is_some_and(|(idx, d, back, w)| {
        idx == i && d == ArrayIdx::from(desc) && back.index() == at && w == when
    }) && t.index() + 1 < ops.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::op::Cmp;

    fn slot(n: u32) -> Slot {
        Slot::new(n)
    }

    fn add_br(d: u32, t: u16) -> Op {
        Op::AddBr {
            d: slot(d),
            b: slot(7),
            imm: 100,
            t: ShortTarget::new(t),
            cmp: Cmp::Le,
            shift: 32,
        }
    }

    fn for_next(i: u32, t: u32, step: i16) -> Op {
        Op::ForNext {
            i: slot(i),
            lim: 50,
            t: Target::new(t),
            step,
            shift: 32,
        }
    }

    fn store_elem(idx: u32) -> Op {
        Op::StoreElem {
            idx: slot(idx),
            s: slot(4),
            desc: ArrayIdx::new(0),
        }
    }

    fn elem_test(jump_if_true: bool, idx: u32, t: u32) -> Op {
        let (idx, desc, t) = (slot(idx), ArrayIdx::new(1), Target::new(t));
        if jump_if_true {
            Op::JnzElem { idx, desc, t }
        } else {
            Op::JzElem { idx, desc, t }
        }
    }

    #[test]
    fn store_then_step_back_is_fused() {
        let mut ops = vec![Op::Nop, store_elem(3), add_br(3, 1), Op::Ret];
        fuse_loops(&mut ops);
        assert_eq!(
            ops[1],
            Op::StoreStep {
                idx: slot(3),
                s: slot(4),
                desc: ArrayIdx::new(0)
            }
        );
        assert!(matches!(ops[2], Op::AddBr { .. }));
        assert!(store_step_partner(&ops, 1));
    }

    #[test]
    fn store_step_needs_the_same_variable_and_a_jump_to_the_store() {
        let store = store_elem(3);
        for step in [add_br(5, 0), add_br(3, 2)] {
            let mut ops = vec![store, step, Op::Ret];
            fuse_loops(&mut ops);
            assert!(matches!(ops[0], Op::StoreElem { .. }), "{step:?}");
        }
    }

    #[test]
    fn for_loop_guarded_by_its_element_is_fused() {
        let mut ops = vec![
            elem_test(false, 2, 2),
            Op::Nop,
            for_next(2, 0, 1),
            elem_test(true, 2, 5),
            Op::Nop,
            for_next(2, 3, -1),
            Op::Ret,
        ];
        fuse_loops(&mut ops);
        assert!(matches!(
            ops[2],
            Op::ForScan {
                i,
                t,
                desc,
                step: 1,
                when: true,
                ..
            } if i == slot(2) && t == ShortTarget::new(0) && desc == ShortArrayIdx::new(1)
        ));
        assert!(matches!(
            ops[5],
            Op::ForScan {
                t,
                step: -1,
                when: false,
                ..
            } if t == ShortTarget::new(3)
        ));
        assert!(for_scan_partner(&ops, 2) && for_scan_partner(&ops, 5));
    }

    #[test]
    fn for_scan_needs_the_loop_variable_a_jump_back_and_a_small_step() {
        let test = |idx, t| elem_test(false, idx, t);
        for (first, step) in [(test(9, 2), 1), (test(2, 1), 1), (test(2, 2), 300)] {
            let mut ops = vec![first, Op::Nop, for_next(2, 0, step), Op::Ret];
            fuse_loops(&mut ops);
            assert!(matches!(ops[2], Op::ForNext { .. }), "{first:?} {step}");
        }
    }

    #[test]
    fn a_broken_pair_fails_the_partner_check() {
        let ops = vec![
            Op::StoreStep {
                idx: slot(3),
                s: slot(4),
                desc: ArrayIdx::new(0),
            },
            Op::Ret,
        ];
        assert!(!store_step_partner(&ops, 0));
        assert!(!for_scan_partner(&ops, 0));
    }
}
