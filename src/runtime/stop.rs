//! Ending a run from another thread.
//!
//! A [`StopHandle`] is a cheap, clonable, `Send + Sync` reference to one
//! PLC's stop requests. Two strengths exist because a PLC has two ways to
//! stop: at the next cycle boundary (Ctrl-C, SIGTERM, a host shutting down
//! cleanly: the trace is flushed and retained data saved), or at once, even
//! inside a runaway loop of the running cycle.

use crate::vm::Interrupt;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The flags a [`StopHandle`] shares with its PLC.
#[derive(Debug, Default)]
pub(crate) struct StopFlags {
    /// End the run at the next cycle boundary.
    pub(crate) stop: AtomicBool,
    /// Interrupt the running cycle now.
    pub(crate) abort: AtomicBool,
    /// The word the PLC's executor polls; `abort` sets its abort bit.
    pub(crate) interrupt: Arc<Interrupt>,
}

/// Asks a PLC (or a run loop driving it) to stop, from any thread.
///
/// ```
/// use plcrun::{Options, Plc};
/// let plc = Plc::compile_files(&[("p.st", "PROGRAM P END_PROGRAM")], &Options::default())?;
/// let handle = plc.stop_handle();
/// std::thread::spawn(move || handle.stop()).join().unwrap();
/// assert!(plc.stop_handle().is_stop_requested());
/// # Ok::<(), plcrun::CompileError>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct StopHandle {
    pub(crate) flags: Arc<StopFlags>,
}

impl StopHandle {
    /// A handle whose [`Self::abort`] interrupts the machine polling
    /// `interrupt`.
    pub(crate) fn interrupting(interrupt: Arc<Interrupt>) -> StopHandle {
        StopHandle {
            flags: Arc::new(StopFlags {
                interrupt,
                ..StopFlags::default()
            }),
        }
    }

    /// Asks the run to end at the next cycle boundary: the cycle under way
    /// completes.
    pub fn stop(&self) {
        self.flags.stop.store(true, Ordering::Release);
    }

    /// Asks the run to end now: the cycle under way is interrupted at its
    /// next backward jump or call, even inside a loop that never ends, and
    /// fails with an `Aborted` fault (R009) that leaves the PLC faulted
    /// until a reset ([`crate::Plc::reset_cold`]). If no cycle is running,
    /// the next one is interrupted as it starts. Implies [`Self::stop`].
    pub fn abort(&self) {
        self.flags.stop.store(true, Ordering::Release);
        self.flags.abort.store(true, Ordering::Release);
        self.flags.interrupt.abort();
    }

    /// True once [`Self::stop`] or [`Self::abort`] was called (and not
    /// cleared since).
    pub fn is_stop_requested(&self) -> bool {
        self.flags.stop.load(Ordering::Acquire)
    }

    /// True once [`Self::abort`] was called (and not cleared since).
    pub fn is_abort_requested(&self) -> bool {
        self.flags.abort.load(Ordering::Acquire)
    }

    /// Withdraws both requests, so that the PLC can be run again.
    pub fn clear(&self) {
        self.flags.stop.store(false, Ordering::Release);
        self.flags.abort.store(false, Ordering::Release);
        self.flags.interrupt.clear_abort();
    }
}
