//! The interrupt word: how another thread stops a running cycle.
//!
//! The executor looks at one word at every backward jump, at every call
//! (block entry) and after every memory copy, with a relaxed load: nothing
//! set, nothing to do. A stop handle sets the abort bit; the watchdog
//! thread sets the watchdog bit for the task run it saw overrunning. Only
//! when the word is not zero does the executor take the cold path
//! ([`Interrupt::pending`]), which decides whether the request still holds.

use super::FaultKind;
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};

/// Bit of the word: a stop handle asked to end the cycle now.
const ABORT: u32 = 1;
/// Bit of the word: the watchdog saw the running task overrun its limit.
const WATCHDOG: u32 = 2;

/// The word the executor polls, and what the watchdog needs to tell a
/// current request from a stale one. Shared (behind an `Arc`) by a
/// machine, its PLC's stop handles and its watchdog thread.
#[derive(Debug, Default)]
pub(crate) struct Interrupt {
    word: AtomicU32,
    /// Odd while a task's code runs: the runner adds one when a task run
    /// starts and when it ends, so each run has its own number.
    activity: AtomicU64,
    /// The task run the watchdog bit was set for.
    fired_for: AtomicU64,
}

impl Interrupt {
    /// The word itself, for the executor's hot-path load.
    #[inline(always)]
    pub(crate) fn word(&self) -> &AtomicU32 {
        &self.word
    }

    /// Asks the running (or next) cycle to stop at once.
    pub(crate) fn abort(&self) {
        self.word.fetch_or(ABORT, Ordering::Release);
    }

    /// Withdraws an abort request.
    pub(crate) fn clear_abort(&self) {
        self.word.fetch_and(!ABORT, Ordering::Release);
    }

    /// The number of the current task run (odd while one runs).
    pub(crate) fn activity(&self) -> u64 {
        self.activity.load(Ordering::Acquire)
    }

    /// Publishes the next activity number. Only the thread running the
    /// PLC calls it, so a load and a store suffice (no read-modify-write).
    #[inline]
    pub(crate) fn advance_activity(&self) -> u64 {
        let next = self.activity.load(Ordering::Relaxed).wrapping_add(1);
        self.activity.store(next, Ordering::Release);
        next
    }

    /// The watchdog's verdict on task run `activity`: stop it.
    pub(crate) fn fire_watchdog(&self, activity: u64) {
        self.fired_for.store(activity, Ordering::Relaxed);
        self.word.fetch_or(WATCHDOG, Ordering::Release);
    }

    /// The look a backward jump or a call takes: the fault to stop with,
    /// if the word is set and what it says applies ([`Self::pending`]).
    /// One relaxed load on the way that goes on.
    #[inline(always)]
    pub(crate) fn stop_request(&self) -> Option<FaultKind> {
        if self.word.load(Ordering::Relaxed) != 0 {
            self.pending()
        } else {
            None
        }
    }

    /// What a non-zero word means for the code running now: an abort, a
    /// watchdog expiry of this task run, or nothing (a watchdog bit left
    /// over from a run that has ended, which is cleared here).
    #[cold]
    #[inline(never)]
    pub(crate) fn pending(&self) -> Option<FaultKind> {
        let word = self.word.load(Ordering::Acquire);
        if word & ABORT != 0 {
            return Some(FaultKind::Aborted);
        }
        if word & WATCHDOG != 0 {
            if self.fired_for.load(Ordering::Relaxed) == self.activity.load(Ordering::Relaxed) {
                return Some(FaultKind::Watchdog);
            }
            // Stale. Should the watchdog fire for this run meanwhile and
            // lose its bit here, it fires again at its next look.
            self.word.fetch_and(!WATCHDOG, Ordering::Release);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_watchdog_bit_counts_only_for_the_run_it_was_set_for() {
        let irq = Interrupt::default();
        assert_eq!(irq.pending(), None);
        let run = irq.advance_activity();
        irq.fire_watchdog(run);
        assert_eq!(irq.pending(), Some(FaultKind::Watchdog));
        irq.advance_activity(); // the run ends
        irq.advance_activity(); // the next one starts
        assert_eq!(irq.pending(), None);
        assert_eq!(irq.word().load(Ordering::Relaxed), 0, "stale bit cleared");
    }

    #[test]
    fn an_abort_holds_until_withdrawn() {
        let irq = Interrupt::default();
        irq.abort();
        irq.advance_activity();
        assert_eq!(irq.pending(), Some(FaultKind::Aborted));
        assert_eq!(irq.pending(), Some(FaultKind::Aborted));
        irq.clear_abort();
        assert_eq!(irq.pending(), None);
    }
}
