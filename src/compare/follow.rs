//! The rule that says whether B's outputs match A's at each cycle.
//!
//! Without lag, a compared output must hold equal values in A and B after
//! every cycle. With `--lag K` (K >= 1), each output is judged on its own,
//! by its changes: B must go through the same sequence of values as A, and
//! each change of A at cycle `t` must appear in B at a cycle in
//! `t ..= t + K`. Exactly:
//!
//! * before cycle 0, if B's initial value differs from A's, it counts as a
//!   change of A at cycle 0 to A's value;
//! * after each cycle `t`, if A's value changed, `(t, new value)` joins A's
//!   queue of pending changes; then, if B's value changed, it must equal the
//!   value at the head of the queue, which it then leaves (B changing with
//!   nothing pending, or to another value, is a difference at `t`);
//! * a change of A still pending after cycle `t + K` is a difference at
//!   cycle `t + K` (B did not follow in time).
//!
//! So B may never lead A, never skip or add a value, and lag by any delay
//! from 0 to K cycles, chosen per change. Changes of A in the last K cycles
//! of a run may still be pending when it ends: that is not a difference.

use super::run_pair::{Mismatch, OutputDifference};
use crate::runtime::plc_value::Value;
use std::collections::VecDeque;

/// Equal values (types may differ slightly: INT against DINT compares the
/// literal).
pub(crate) fn same(a: &Value, b: &Value) -> bool {
    a == b || a.to_literal() == b.to_literal()
}

/// One compared output under a lag.
#[derive(Debug)]
struct Track {
    a_prev: Value,
    b_prev: Value,
    pending: VecDeque<(u64, Value)>,
}

/// The judge of one run.
#[derive(Debug)]
pub(crate) struct Follower {
    lag: u64,
    tracks: Vec<Track>,
}

impl Follower {
    /// Starts with the outputs' values before cycle 0.
    pub(crate) fn new(lag: u64, a: &[Value], b: &[Value]) -> Follower {
        let tracks = a
            .iter()
            .zip(b)
            .map(|(x, y)| {
                let mut pending = VecDeque::new();
                if lag > 0 && !same(x, y) {
                    pending.push_back((0, x.clone()));
                }
                Track {
                    a_prev: x.clone(),
                    b_prev: y.clone(),
                    pending,
                }
            })
            .collect();
        Follower { lag, tracks }
    }

    /// Judges the values after cycle `cycle`; pushes one entry per output
    /// that differs (index into the compared outputs) into `out`.
    pub(crate) fn observe(
        &mut self,
        cycle: u64,
        a: &[Value],
        b: &[Value],
        out: &mut Vec<(usize, OutputDifference)>,
    ) {
        if self.lag == 0 {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                if !same(x, y) {
                    out.push((i, OutputDifference::new(i, x, y, Mismatch::Values)));
                }
            }
            return;
        }
        for (i, ((x, y), t)) in a.iter().zip(b).zip(&mut self.tracks).enumerate() {
            if let Some(m) = t.step(cycle, self.lag, x, y) {
                out.push((i, OutputDifference::new(i, x, y, m)));
            }
        }
    }
}

impl Track {
    fn step(&mut self, cycle: u64, lag: u64, a: &Value, b: &Value) -> Option<Mismatch> {
        if !same(a, &self.a_prev) {
            self.pending.push_back((cycle, a.clone()));
            self.a_prev = a.clone();
        }
        if !same(b, &self.b_prev) {
            self.b_prev = b.clone();
            match self.pending.front() {
                None => return Some(Mismatch::BChangedAlone),
                Some((_, want)) if !same(want, b) => {
                    return Some(Mismatch::WrongValue {
                        expected: want.to_literal(),
                    });
                }
                Some(_) => {
                    self.pending.pop_front();
                }
            }
        }
        match self.pending.front() {
            Some((at, want)) if cycle >= at + lag => Some(Mismatch::NotFollowed {
                a_changed_at: *at,
                value: want.to_literal(),
            }),
            _ => None,
        }
    }
}
