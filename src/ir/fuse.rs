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

use super::op::Op;

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
            Op::AddBr { d, t, .. } if *d == idx && *t as usize == at => {
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
            let (idx, desc, back, when) = element_test(ops.get(t as usize)?)?;
            if idx != i || back as usize != at {
                return None;
            }
            Some(Op::ForScan {
                i,
                lim,
                t: u16::try_from(t).ok()?,
                desc: u16::try_from(desc).ok()?,
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
fn element_test(op: &Op) -> Option<(u32, u32, u32, bool)> {
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
        Some(Op::AddBr { d, t, .. }) if d == idx && *t as usize == at
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
    ops.get(t as usize).and_then(element_test) == Some((i, desc as u32, at as u32, when))
        && (t as usize) + 1 < ops.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::op::Cmp;

    fn add_br(d: u32, t: u16) -> Op {
        Op::AddBr {
            d,
            b: 7,
            imm: 100,
            t,
            cmp: Cmp::Le,
            shift: 32,
        }
    }

    fn for_next(i: u32, t: u32, step: i16) -> Op {
        Op::ForNext {
            i,
            lim: 50,
            t,
            step,
            shift: 32,
        }
    }

    #[test]
    fn store_then_step_back_is_fused() {
        let mut ops = vec![
            Op::Nop,
            Op::StoreElem {
                idx: 3,
                s: 4,
                desc: 0,
            },
            add_br(3, 1),
            Op::Ret,
        ];
        fuse_loops(&mut ops);
        assert!(matches!(
            ops[1],
            Op::StoreStep {
                idx: 3,
                s: 4,
                desc: 0
            }
        ));
        assert!(matches!(ops[2], Op::AddBr { .. }));
        assert!(store_step_partner(&ops, 1));
    }

    #[test]
    fn store_step_needs_the_same_variable_and_a_jump_to_the_store() {
        let store = Op::StoreElem {
            idx: 3,
            s: 4,
            desc: 0,
        };
        for step in [add_br(5, 0), add_br(3, 2)] {
            let mut ops = vec![store, step, Op::Ret];
            fuse_loops(&mut ops);
            assert!(matches!(ops[0], Op::StoreElem { .. }), "{step:?}");
        }
    }

    #[test]
    fn for_loop_guarded_by_its_element_is_fused() {
        let mut ops = vec![
            Op::JzElem {
                idx: 2,
                desc: 1,
                t: 2,
            },
            Op::Nop,
            for_next(2, 0, 1),
            Op::JnzElem {
                idx: 2,
                desc: 1,
                t: 5,
            },
            Op::Nop,
            for_next(2, 3, -1),
            Op::Ret,
        ];
        fuse_loops(&mut ops);
        assert!(matches!(
            ops[2],
            Op::ForScan {
                i: 2,
                t: 0,
                desc: 1,
                step: 1,
                when: true,
                ..
            }
        ));
        assert!(matches!(
            ops[5],
            Op::ForScan {
                t: 3,
                step: -1,
                when: false,
                ..
            }
        ));
        assert!(for_scan_partner(&ops, 2) && for_scan_partner(&ops, 5));
    }

    #[test]
    fn for_scan_needs_the_loop_variable_a_jump_back_and_a_small_step() {
        let test = |idx, t| Op::JzElem { idx, desc: 1, t };
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
                idx: 3,
                s: 4,
                desc: 0,
            },
            Op::Ret,
        ];
        assert!(!store_step_partner(&ops, 0));
        assert!(!for_scan_partner(&ops, 0));
    }
}
