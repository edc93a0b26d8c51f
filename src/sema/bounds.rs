//! Index range proofs. Inside `FOR i := a TO b BY k` with constant `a`,
//! `b` and `k`, the body only ever sees `a <= i <= b` (the loop's back
//! edge tests the exact sum, so `i` never wraps into the body). When that
//! range lies inside an array's bounds and nothing in the body can write
//! `i`, the element accesses `arr[i]` cannot fail their bounds check: they
//! become `LoadElemU` / `StoreElemU`, which skip it.

use crate::ir::image::ArrayDesc;
use crate::ir::op::{ArrayIdx, Op, Slot};
use crate::ir::operands::writes;

/// Rewrites the element accesses of `body` indexed by `i` whose array
/// covers `lo..=hi`, if the body provably leaves `i` alone.
pub(super) fn drop_proven_checks(body: &mut [Op], arrays: &[ArrayDesc], i: Slot, lo: i64, hi: i64) {
    if !body.iter().all(|op| leaves_alone(op, i)) {
        return;
    }
    let bias_of = |desc: ArrayIdx| {
        let a = arrays.get(desc.index())?;
        let inside =
            a.stride == 1 && a.lo <= lo && hi < a.lo.checked_add(i64::try_from(a.len).ok()?)?;
        inside.then(|| i32::try_from(a.offset as i64 - a.lo).ok())?
    };
    for op in body.iter_mut() {
        *op = match *op {
            Op::LoadElem { d, idx, desc } if idx == i => match bias_of(desc) {
                Some(bias) => Op::LoadElemU { d, idx, bias },
                None => continue,
            },
            Op::StoreElem { idx, s, desc } if idx == i => match bias_of(desc) {
                Some(bias) => Op::StoreElemU { idx, s, bias },
                None => continue,
            },
            _ => continue,
        };
    }
}

/// Whether `op` certainly does not change slot `i`, a plain variable of the
/// frame (never an array element or a member of an instance): it does not
/// write it by name, does not take its address (a function could write
/// through a VAR_IN_OUT), and is not a call of a user FB (whose instance
/// may keep a VAR_IN_OUT address from an earlier call).
fn leaves_alone(op: &Op, i: Slot) -> bool {
    let mut copy = *op;
    let writes_i = writes(&mut copy).slot.is_some_and(|s| *s == i);
    let escapes = matches!(*op, Op::AddrOf { off, .. } if off == i);
    // A dereference may write `i` through a reference taken earlier.
    let user_call = matches!(
        op,
        Op::CallFb { .. }
            | Op::CallFbInd { .. }
            | Op::Sfc { .. }
            | Op::RefAddr { .. }
            | Op::RefStore { .. }
    );
    !writes_i && !escapes && !user_call
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::op::{CodeIdx, Target};
    use crate::source::Span;

    /// The loop variable and the value slot of the tests.
    const I: Slot = Slot::new(2);
    const V: Slot = Slot::new(9);

    fn array(offset: u32, lo: i64, len: u64) -> ArrayDesc {
        ArrayDesc {
            offset,
            lo,
            len,
            stride: 1,
            span: Span::default(),
        }
    }

    fn load(desc: u32) -> Op {
        Op::LoadElem {
            d: V,
            idx: I,
            desc: ArrayIdx::new(desc),
        }
    }

    #[test]
    fn accesses_inside_the_bounds_lose_their_check() {
        // a: [0..9] at slot 20, b: [1..5] at slot 40.
        let arrays = [array(20, 0, 10), array(40, 1, 5)];
        let mut body = [
            load(0),
            Op::StoreElem {
                idx: I,
                s: V,
                desc: ArrayIdx::new(0),
            },
            load(1),
        ];
        drop_proven_checks(&mut body, &arrays, I, 0, 9);
        assert!(matches!(
            body[0],
            Op::LoadElemU {
                d: V,
                idx: I,
                bias: 20
            }
        ));
        assert!(matches!(
            body[1],
            Op::StoreElemU {
                idx: I,
                s: V,
                bias: 20
            }
        ));
        // 0..=9 is not inside b's 1..=5: still checked.
        assert!(matches!(body[2], Op::LoadElem { .. }));
        let mut body = [load(1)];
        drop_proven_checks(&mut body, &arrays, I, 1, 5);
        assert!(matches!(body[0], Op::LoadElemU { bias: 39, .. }));
    }

    #[test]
    fn a_body_that_may_change_the_index_keeps_every_check() {
        let arrays = [array(20, 0, 10)];
        let changes = [
            Op::AddSI {
                d: I,
                a: I,
                imm: 1,
                shift: 32,
            },
            Op::AddrOf {
                d: Slot::new(7),
                off: I,
            },
            Op::CallFb {
                code: CodeIdx::new(1),
                inst: Slot::new(30),
            },
            Op::ForNext {
                i: I,
                lim: 3,
                t: Target::new(0),
                step: 1,
                shift: 32,
            },
        ];
        for change in changes {
            let mut body = [load(0), change];
            drop_proven_checks(&mut body, &arrays, I, 0, 9);
            assert!(matches!(body[0], Op::LoadElem { .. }), "{change:?}");
        }
    }

    #[test]
    fn other_indexes_keep_their_check() {
        let arrays = [array(20, 0, 10)];
        let mut body = [Op::LoadElem {
            d: V,
            idx: Slot::new(3),
            desc: ArrayIdx::new(0),
        }];
        drop_proven_checks(&mut body, &arrays, I, 0, 9);
        assert!(matches!(body[0], Op::LoadElem { .. }));
    }
}
