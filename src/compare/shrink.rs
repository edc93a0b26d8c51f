//! Shrinking a failing plan to a short counterexample: delta debugging
//! (ddmin) over its input changes, and truncation of the run.
//!
//! The run is first cut after the cycle of the difference (later cycles
//! cannot matter). Then ddmin splits the changes into `n` chunks (starting
//! with 2) and tries each chunk alone, then each complement; the first
//! subset that still makes the programs differ (any difference) is kept,
//! the run is cut again after its new first difference, and the search
//! goes on with `n` reduced by one (at least 2); when no subset fails, `n`
//! doubles, until it exceeds the number of changes. The result is
//! 1-minimal: removing any single change makes the difference disappear
//! (or move past the end of the cut run). The empty plan is tried first.
//! The search stops after [`MAX_RUNS`] runs, keeping the smallest failing
//! plan found so far.

use super::error::CompareError;
use super::input_plan::{InputChange, InputPlan};
use super::run_pair::{Difference, Pair};

/// The most runs one shrink may take.
pub const MAX_RUNS: u64 = 20_000;

/// A shrunk counterexample.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shrunk {
    /// The smallest failing plan found.
    pub plan: InputPlan,
    /// Its first difference.
    pub difference: Difference,
    /// How many runs the search took.
    pub runs: u64,
}

/// The search's state: the smallest failing plan so far.
struct Search<'p> {
    pair: &'p mut Pair,
    best: InputPlan,
    difference: Difference,
    runs: u64,
}

impl Search<'_> {
    /// Whether `changes` (within the current run length) still fail; if
    /// so they become the best plan, cut after the new difference.
    fn fails(&mut self, changes: &[InputChange]) -> Result<bool, CompareError> {
        if self.runs >= MAX_RUNS {
            return Ok(false);
        }
        self.runs += 1;
        let plan = InputPlan {
            cycles: self.best.cycles,
            changes: changes.to_vec(),
        };
        match self.pair.run(&plan)? {
            Some(d) => {
                self.best = plan.truncated(d.cycle + 1);
                self.difference = d;
                Ok(true)
            }
            None => Ok(false),
        }
    }
}

impl Pair {
    /// Shrinks `plan`, which fails with `difference`, as the module docs
    /// describe.
    pub fn shrink(
        &mut self,
        plan: &InputPlan,
        difference: &Difference,
    ) -> Result<Shrunk, CompareError> {
        let mut s = Search {
            pair: self,
            best: plan.truncated(difference.cycle + 1),
            difference: difference.clone(),
            runs: 0,
        };
        if s.fails(&[])? {
            return Ok(finish(s));
        }
        let mut n = 2usize;
        while s.best.changes.len() >= 2 && s.runs < MAX_RUNS {
            let changes = s.best.changes.clone();
            let chunks = split(changes.len(), n);
            let mut reduced = false;
            for &(lo, hi) in &chunks {
                if s.fails(&changes[lo..hi])? {
                    n = 2;
                    reduced = true;
                    break;
                }
            }
            if !reduced && n > 2 {
                for &(lo, hi) in &chunks {
                    let rest: Vec<InputChange> = changes[..lo]
                        .iter()
                        .chain(&changes[hi..])
                        .cloned()
                        .collect();
                    if s.fails(&rest)? {
                        n = (n - 1).max(2);
                        reduced = true;
                        break;
                    }
                }
            }
            if !reduced {
                if n >= changes.len() {
                    break;
                }
                n = (2 * n).min(changes.len());
            }
        }
        Ok(finish(s))
    }
}

fn finish(s: Search<'_>) -> Shrunk {
    Shrunk {
        plan: s.best,
        difference: s.difference,
        runs: s.runs,
    }
}

/// `n` nearly equal consecutive ranges covering `0..len`.
fn split(len: usize, n: usize) -> Vec<(usize, usize)> {
    let n = n.clamp(1, len.max(1));
    (0..n).map(|k| (k * len / n, (k + 1) * len / n)).collect()
}
