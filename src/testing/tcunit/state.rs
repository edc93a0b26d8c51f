//! What the TcUnit functions record while the suites run: the suites, the
//! tests each declared (`TEST`, `TEST_ORDERED`), which are finished, the
//! assertions each ran and the failures each met, and the log lines of
//! `TCUNIT_ADSLOGSTR`.

use super::assert_counts::{AssertCounts, Key};
use crate::testing::assertions::Recorded;
use std::collections::BTreeSet;

/// The prefix that disables a TcUnit test.
const DISABLED: &str = "DISABLED_";

/// One test of a suite.
#[derive(Debug, Default)]
pub(crate) struct Test {
    /// The name given to `TEST`.
    pub(crate) name: String,
    /// Declared with `TEST_ORDERED`.
    pub(crate) ordered: bool,
    /// The cycle `TEST_FINISHED` was called in, if it was.
    pub(crate) finished: Option<u64>,
    /// The assertion calls it ran (encoded positions): each counts once,
    /// however many cycles it ran in.
    pub(crate) assertions: BTreeSet<i64>,
    /// Its failures, each assertion call reported once, with the cycle.
    pub(crate) failures: Vec<(Recorded, u64)>,
    /// The cycle it was last declared in (a second `TEST` of the same name
    /// in one cycle is an error, as in TcUnit).
    declared_in: Option<u64>,
    /// Declared twice in one cycle.
    pub(crate) duplicate: bool,
    /// Disabled by its name (`DISABLED_`): never run, as TcUnit skips it.
    pub(crate) skipped: bool,
    /// Lines logged while it was the current test.
    pub(crate) output: Vec<String>,
}

/// One suite instance.
#[derive(Debug, Default)]
pub(crate) struct Suite {
    /// Its tests, in the order they were first declared.
    pub(crate) tests: Vec<Test>,
    /// It has been called at least once.
    pub(crate) ran: bool,
    /// TcUnit's count of its value assertions (`AssertResults`).
    asserts: AssertCounts,
    /// TcUnit's count of its array assertions (`AssertArrayResults`).
    array_asserts: AssertCounts,
}

impl Suite {
    /// Every test it declared is finished or disabled (after it ran once).
    pub(crate) fn finished(&self) -> bool {
        self.ran && self.tests.iter().all(|t| t.finished.is_some() || t.skipped)
    }
}

/// The state of a TcUnit run.
#[derive(Debug, Default)]
pub(crate) struct State {
    /// The suite instances, in the order the runner calls them.
    pub(crate) suites: Vec<Suite>,
    /// The suites run one after the other (`RUN_IN_SEQUENCE`).
    pub(crate) in_sequence: bool,
    /// The cycle being run.
    pub(crate) cycle: u64,
    /// The suite being called.
    current_suite: Option<usize>,
    /// The test whose assertions count now, in the current suite; `None`
    /// outside a test, or when an ordered test's turn has not come.
    current_test: Option<usize>,
    /// Lines logged outside any test.
    pub(crate) output: Vec<String>,
    /// The position of the array assertion whose element comparisons are
    /// running: they are parts of it, not value assertions of their own.
    array_call: Option<i64>,
}

impl State {
    /// A run of `suites` suite instances.
    pub(crate) fn new(suites: usize, in_sequence: bool) -> State {
        State {
            suites: (0..suites).map(|_| Suite::default()).collect(),
            in_sequence,
            ..State::default()
        }
    }

    /// The runner is about to call suite `k`: true when it should (in a
    /// sequence, only once every earlier suite is finished).
    pub(crate) fn enter(&mut self, k: usize) -> bool {
        self.current_test = None;
        if k >= self.suites.len() {
            self.current_suite = None;
            return false;
        }
        let turn = !self.in_sequence || self.suites[..k].iter().all(Suite::finished);
        self.current_suite = turn.then_some(k);
        if turn {
            self.suites[k].ran = true;
        }
        turn
    }

    /// The suite being run, if one is.
    pub(crate) fn current_suite(&self) -> Option<usize> {
        self.current_suite
    }

    /// The suite and test being run, if a test is.
    pub(crate) fn current(&self) -> Option<(usize, usize)> {
        Some((self.current_suite?, self.current_test?))
    }

    /// Every suite is finished.
    pub(crate) fn all_finished(&self) -> bool {
        self.suites.iter().all(Suite::finished)
    }

    /// `TEST(name)` or `TEST_ORDERED(name)`: declares the test (once) and
    /// makes it the current one; returns whether its assertions count now.
    /// As TcUnit, the name is taken without its surrounding blanks, and a
    /// name starting with `DISABLED_` (any case) declares that test
    /// without the prefix, skipped: its assertions never count.
    pub(crate) fn declare(&mut self, name: &str, ordered: bool) -> bool {
        let cycle = self.cycle;
        let Some(suite) = self.current_suite.map(|k| &mut self.suites[k]) else {
            return false;
        };
        let name = name.trim();
        let (name, disabled) = match name.get(..DISABLED.len()) {
            Some(p) if p.eq_ignore_ascii_case(DISABLED) => (&name[DISABLED.len()..], true),
            _ => (name, false),
        };
        let at = match suite.tests.iter().position(|t| t.name == name) {
            Some(i) => i,
            None => {
                suite.tests.push(Test {
                    name: name.to_string(),
                    ordered,
                    skipped: disabled,
                    ..Test::default()
                });
                suite.tests.len() - 1
            }
        };
        if suite.tests[at].skipped {
            self.current_test = None;
            return false;
        }
        let earlier_done = suite.tests[..at]
            .iter()
            .filter(|t| t.ordered)
            .all(|t| t.finished.is_some());
        let test = &mut suite.tests[at];
        if test.declared_in == Some(cycle) {
            test.duplicate = true;
        }
        test.declared_in = Some(cycle);
        let counts = test.finished.is_none() && (!ordered || earlier_done);
        self.current_test = counts.then_some(at);
        counts
    }

    /// `TEST_FINISHED()`: the current test is finished.
    pub(crate) fn finish_current(&mut self) -> bool {
        let (Some(k), Some(t)) = (self.current_suite, self.current_test) else {
            return false;
        };
        self.suites[k].tests[t].finished = Some(self.cycle);
        self.current_test = None;
        true
    }

    /// `TEST_FINISHED_NAMED(name)`: the test of that name in the current
    /// suite is finished; false when it has none.
    pub(crate) fn finish_named(&mut self, name: &str) -> bool {
        let cycle = self.cycle;
        let Some(k) = self.current_suite else {
            return false;
        };
        let Some(t) = self.suites[k].tests.iter().position(|t| t.name == name) else {
            return false;
        };
        if self.suites[k].tests[t].finished.is_none() {
            self.suites[k].tests[t].finished = Some(cycle);
        }
        if self.current_test == Some(t) {
            self.current_test = None;
        }
        true
    }

    /// `IS_TEST_FINISHED(name)`: whether the test `name` of the running
    /// suite has finished (FALSE for a test it never declared).
    pub(crate) fn is_finished(&self, name: &str) -> bool {
        self.current_suite.is_some_and(|k| {
            self.suites[k]
                .tests
                .iter()
                .any(|t| t.name == name && t.finished.is_some())
        })
    }

    /// An assertion ran (`failure` when it did not hold): counted for the
    /// current test, its failure kept once per assertion call; ignored
    /// outside a running test (after `TEST_FINISHED`, before an ordered
    /// test's turn), as in TcUnit.
    pub(crate) fn assertion(&mut self, loc: i64, failure: Option<Recorded>) {
        let cycle = self.cycle;
        let (Some(k), Some(t)) = (self.current_suite, self.current_test) else {
            return;
        };
        let test = &mut self.suites[k].tests[t];
        test.assertions.insert(loc);
        if let Some(r) = failure
            && !test.failures.iter().any(|(f, _)| f.loc == loc)
        {
            test.failures.push((r, cycle));
        }
    }

    /// An assertion call at `loc` of the running test, of `values`
    /// (expected, named with the assertion's type, and actual) and
    /// `message`: TcUnit's count of it, then [`Self::assertion`].
    pub(crate) fn assertion_call(
        &mut self,
        loc: i64,
        values: (String, String),
        message: &str,
        failure: Option<Recorded>,
    ) {
        self.count_value(loc, values, message);
        self.assertion(loc, failure);
    }

    /// TcUnit's count of the running test's assertions: a value
    /// assertion at `loc` of values `expected`, `actual` (named with the
    /// assertion's type) and `message`; the element comparisons of the
    /// array assertion at `loc` are not counted here.
    fn count_value(&mut self, loc: i64, values: (String, String), message: &str) {
        if self.array_call == Some(loc) {
            return;
        }
        self.array_call = None;
        self.count(false, (values.0, values.1, message.to_string()));
    }

    /// TcUnit's count of the running test's array assertions: the one at
    /// `loc` over arrays described by `shape` (their sizes and types).
    pub(crate) fn count_array(&mut self, loc: i64, shape: (String, String), message: &str) {
        self.array_call = Some(loc);
        self.count(true, (shape.0, shape.1, message.to_string()));
    }

    fn count(&mut self, arrays: bool, (e, a, m): (String, String, String)) {
        let cycle = self.cycle;
        let (Some(k), Some(t)) = (self.current_suite, self.current_test) else {
            return;
        };
        let key: Key = (e, a, m, self.suites[k].tests[t].name.clone());
        let suite = &mut self.suites[k];
        let counts = if arrays {
            &mut suite.array_asserts
        } else {
            &mut suite.asserts
        };
        if counts.report(key, cycle) {
            suite.tests[t].output.push(
                "Max number of assertions exceeded. Check parameter MaxNumberOfAssertsForEachTestSuite."
                    .to_string(),
            );
        }
    }

    /// `AssertResults.TotalAsserts` (or, with `arrays`,
    /// `AssertArrayResults.TotalArrayAsserts`) of the running suite.
    pub(crate) fn total_asserts(&self, arrays: bool) -> usize {
        self.current_suite.map_or(0, |k| {
            let s = &self.suites[k];
            if arrays {
                s.array_asserts.total()
            } else {
                s.asserts.total()
            }
        })
    }

    /// `TCUNIT_ADSLOGSTR`: a line for the current test, or for the run.
    pub(crate) fn log(&mut self, line: String) {
        match (self.current_suite, self.current_test) {
            (Some(k), Some(t)) => self.suites[k].tests[t].output.push(line),
            _ => self.output.push(line),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fail(loc: i64) -> Option<Recorded> {
        Some(Recorded {
            loc,
            expected: "1".into(),
            actual: "2".into(),
            index: None,
            element: None,
            message: String::new(),
        })
    }

    #[test]
    fn ordered_tests_wait_for_the_earlier_ones_and_finished_tests_ignore_assertions() {
        let mut s = State::new(1, false);
        assert!(s.enter(0));
        assert!(s.declare("first", true));
        s.assertion(10, None);
        assert!(!s.declare("second", true));
        s.assertion(20, fail(20));
        assert!(s.suites[0].tests[1].assertions.is_empty());
        s.cycle = 1;
        s.enter(0);
        assert!(s.declare("first", true));
        assert!(s.finish_current());
        s.assertion(11, fail(11));
        assert!(s.declare("second", true));
        s.assertion(20, fail(20));
        s.cycle = 2;
        s.enter(0);
        s.declare("first", true);
        s.declare("second", true);
        s.assertion(20, fail(20));
        s.finish_current();
        let t = &s.suites[0].tests;
        assert_eq!(t[0].failures.len(), 0, "after TEST_FINISHED nothing counts");
        assert_eq!(t[1].failures.len(), 1, "one failure per assertion call");
        assert_eq!(t[1].failures[0].1, 1);
        assert!(s.all_finished());
    }

    #[test]
    fn in_sequence_a_suite_waits_until_the_earlier_ones_are_finished() {
        let mut s = State::new(2, true);
        assert!(s.enter(0));
        s.declare("a", false);
        assert!(!s.enter(1));
        s.cycle = 1;
        s.enter(0);
        s.declare("a", false);
        s.finish_current();
        assert!(s.enter(1));
        s.declare("b", false);
        assert!(!s.all_finished());
        s.declare("b", false);
        assert!(s.suites[1].tests[0].duplicate);
        assert!(!s.suites[0].tests[0].duplicate);
    }
}
