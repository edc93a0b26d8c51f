//! TcUnit's count of a suite's assertions, `AssertResults.TotalAsserts`
//! and `AssertArrayResults.TotalArrayAsserts`, which suites read to check
//! that their assertions ran. TcUnit counts *distinct* assertions: one
//! that repeats an earlier one (same values, message and test) in a later
//! cycle is the same assertion; the k-th identical call within one cycle
//! is a new one only when no earlier cycle had k of them. The count stops
//! at `GVL_Param_TcUnit.MaxNumberOfAssertsForEachTestSuite`. This follows
//! TcUnit's bookkeeping step for step (its slots are reused once an
//! assertion stops repeating), so the totals are the ones TcUnit gives.

/// `GVL_Param_TcUnit.MaxNumberOfAssertsForEachTestSuite`'s default.
pub(crate) const MAX_ASSERTS: usize = 1000;

/// What makes two assertion calls the same assertion: for a value
/// assertion its values (typed), message and test; for an array assertion
/// the arrays' sizes and types, message and test.
pub(crate) type Key = (String, String, String, String);

/// One remembered assertion.
#[derive(Debug, Clone, Default)]
struct Instance {
    key: Option<Key>,
    /// Calls of it in the last cycle the suite asserted in.
    detection: u32,
    /// Calls of it in the current cycle.
    this_cycle: u32,
}

impl Instance {
    fn free(&self) -> bool {
        self.detection == 0 && self.this_cycle == 0
    }
}

/// One suite's count of value or of array assertions.
#[derive(Debug, Clone, Default)]
pub(crate) struct AssertCounts {
    instances: Vec<Instance>,
    /// `TotalAsserts` (or `TotalArrayAsserts`).
    total: usize,
    /// The cycle of the last call.
    cycle: Option<u64>,
    /// The count reached its limit (reported once).
    overflowed: bool,
}

impl AssertCounts {
    /// The count so far.
    pub(crate) fn total(&self) -> usize {
        self.total
    }

    /// An assertion call with `key` in `cycle`; returns true the first
    /// time the count would pass its limit.
    pub(crate) fn report(&mut self, key: Key, cycle: u64) -> bool {
        if self.cycle != Some(cycle) {
            for i in &mut self.instances {
                i.detection = i.this_cycle;
                i.this_cycle = 0;
            }
            self.cycle = Some(cycle);
        }
        // TcUnit looks among its first `total` slots, which hold every
        // instance: each is made after `total` grew, or once it is full.
        let found = self
            .instances
            .iter_mut()
            .find(|i| i.key.as_ref() == Some(&key));
        match found {
            Some(i) => {
                i.this_cycle += 1;
                if i.this_cycle > i.detection {
                    return self.add();
                }
                false
            }
            None => {
                let overflow = self.add();
                self.create(key);
                overflow
            }
        }
    }

    /// One more distinct assertion, up to the limit.
    fn add(&mut self) -> bool {
        if self.total < MAX_ASSERTS {
            self.total += 1;
            false
        } else {
            let first = !self.overflowed;
            self.overflowed = true;
            first
        }
    }

    /// Remembers `key` in the first free slot.
    fn create(&mut self, key: Key) {
        let new = Instance {
            key: Some(key),
            detection: 0,
            this_cycle: 1,
        };
        if let Some(slot) = self.instances.iter_mut().find(|i| i.free()) {
            *slot = new;
        } else if self.instances.len() < MAX_ASSERTS {
            self.instances.push(new);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(v: &str) -> Key {
        (v.into(), v.into(), "m".into(), "t".into())
    }

    #[test]
    fn a_repeated_assertion_counts_once_and_a_second_identical_call_in_a_cycle_counts_again() {
        let mut c = AssertCounts::default();
        c.report(key("1"), 0);
        c.report(key("1"), 1);
        c.report(key("2"), 1);
        assert_eq!(c.total(), 2);
        // Two identical calls in one cycle: two assertions.
        c.report(key("1"), 2);
        c.report(key("1"), 2);
        assert_eq!(c.total(), 3);
    }

    #[test]
    fn the_count_stops_at_the_limit_and_says_so_once() {
        let mut c = AssertCounts::default();
        let overflows = (0..MAX_ASSERTS + 100)
            .filter(|_| c.report(key("x"), 0))
            .count();
        assert_eq!(c.total(), MAX_ASSERTS);
        assert_eq!(overflows, 1);
    }
}
