//! The scan's side of the web monitor: between two cycles it publishes
//! the values the cycle left (at most [`PUBLISH_EVERY`]) and carries out
//! the commands the monitor queued (at most [`COMMANDS_PER_TICK`]), as the
//! Modbus and OPC UA exchanges do. It never waits: the snapshot's lock is
//! only tried, the queue only polled.
//!
//! After a fault the run has ended; [`ScanSide::wait_in_fault`] keeps the
//! monitor answering (the faulted state published, commands carried out)
//! until a reset or a stop.

use super::state::{Command, CommandQueue, FaultView, Outcome, Shared, Snapshot, bump};
use plcrun::{Plc, StopHandle, VarError, VarRef};
use std::sync::mpsc::RecvTimeoutError;
use std::sync::{Arc, TryLockError};
use std::time::{Duration, Instant, SystemTime};

/// The shortest time between two publications.
pub(super) const PUBLISH_EVERY: Duration = Duration::from_millis(200);

/// The most commands carried out between two cycles.
const COMMANDS_PER_TICK: usize = 8;

/// How the run goes on after [`ScanSide::wait_in_fault`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AfterFault {
    /// The PLC was reset from the monitor: run again.
    Reset,
    /// A stop was asked (Ctrl-C, SIGTERM): end the run.
    Stop,
}

/// The scan's end of the monitor (see the module docs).
pub struct ScanSide {
    shared: Arc<Shared>,
    /// The catalogue's variables, resolved once.
    refs: Vec<VarRef>,
    queue: CommandQueue,
    /// When the last publication was made.
    last: Option<Instant>,
    /// Publication number of the last one.
    seq: u64,
    /// A command changed something: publish after the next cycle.
    publish_next: bool,
}

impl std::fmt::Debug for ScanSide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ScanSide")
            .field("variables", &self.refs.len())
            .field("seq", &self.seq)
            .finish_non_exhaustive()
    }
}

impl ScanSide {
    /// The scan side for `plc`, whose variables `shared` lists.
    pub(super) fn new(shared: Arc<Shared>, plc: &Plc, queue: CommandQueue) -> ScanSide {
        let refs = shared
            .variables
            .iter()
            .filter_map(|v| plc.resolve(&v.path).ok())
            .collect();
        ScanSide {
            shared,
            refs,
            queue,
            last: None,
            seq: 0,
            publish_next: false,
        }
    }

    /// Between two cycles: publishes the cycle's values when it is time,
    /// then carries out the queued commands (their effect is published
    /// after the next cycle).
    pub fn between_ticks(&mut self, plc: &mut Plc) {
        let now = Instant::now();
        if self.publish_next || self.last.is_none_or(|t| now - t >= PUBLISH_EVERY) {
            self.publish(plc, now);
        }
        for _ in 0..COMMANDS_PER_TICK {
            let Ok((command, reply)) = self.queue.try_recv() else {
                break;
            };
            let outcome = carry_out(plc, command);
            self.publish_next = true;
            bump(&self.shared.counters.commands);
            // The asker may have given up waiting: nothing to do then.
            let _ = reply.try_send(outcome);
        }
    }

    /// Publishes the values of `plc` now (before the first cycle: its
    /// initial values).
    pub fn publish_now(&mut self, plc: &Plc) {
        self.publish(plc, Instant::now());
    }

    /// After the run ended on a fault: publishes the faulted state, then
    /// carries out commands (a reset ends the wait) until a stop is asked
    /// through `stop`.
    pub fn wait_in_fault(&mut self, plc: &mut Plc, stop: &StopHandle) -> AfterFault {
        self.publish(plc, Instant::now());
        loop {
            if stop.is_stop_requested() {
                return AfterFault::Stop;
            }
            match self.queue.recv_timeout(Duration::from_millis(50)) {
                Ok((command, reply)) => {
                    let reset = matches!(command, Command::Reset { .. });
                    let outcome = carry_out(plc, command);
                    let done = reset && outcome.is_ok();
                    bump(&self.shared.counters.commands);
                    let _ = reply.try_send(outcome);
                    self.publish(plc, Instant::now());
                    if done {
                        return AfterFault::Reset;
                    }
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => return AfterFault::Stop,
            }
        }
    }

    /// Publishes the values of `plc` now, unless a reader holds the slot
    /// (then the next tick tries again). Reuses the last snapshot's
    /// buffers when no reader still holds it.
    fn publish(&mut self, plc: &Plc, now: Instant) {
        let mut slot = match self.shared.snapshot.try_lock() {
            Ok(slot) => slot,
            // A reader panicked while holding it: the pointer is intact.
            Err(TryLockError::Poisoned(p)) => p.into_inner(),
            Err(TryLockError::WouldBlock) => {
                bump(&self.shared.counters.publishes_deferred);
                self.publish_next = true;
                return;
            }
        };
        self.seq += 1;
        let old = match Arc::get_mut(&mut slot) {
            Some(snapshot) => {
                self.fill(plc, snapshot);
                None
            }
            None => {
                let mut fresh = Snapshot::empty();
                self.fill(plc, &mut fresh);
                Some(std::mem::replace(&mut *slot, Arc::new(fresh)))
            }
        };
        drop(slot);
        // A reader's old snapshot is only released here, outside the lock.
        drop(old);
        self.last = Some(now);
        self.publish_next = false;
        bump(&self.shared.counters.publishes);
    }

    /// Fills `s` with the values of `plc`.
    fn fill(&self, plc: &Plc, s: &mut Snapshot) {
        s.seq = self.seq;
        s.cycle = plc.cycle();
        s.time_ns = plc.time();
        s.at = SystemTime::now();
        s.values.clear();
        s.forced.clear();
        for r in &self.refs {
            // Resolved by this PLC: a read cannot fail.
            if let Ok(v) = plc.get(r) {
                s.values.push(v);
            }
            s.forced.push(plc.is_forced(r));
        }
        s.active.clear();
        let states = plc.chart_states();
        for chart in &self.shared.charts {
            let active = states
                .iter()
                .find(|c| c.path == chart.path)
                .map(|c| c.active.clone())
                .unwrap_or_default();
            s.active.push(active);
        }
        s.fault = plc.fault().map(|f| FaultView {
            code: f.code().to_string(),
            message: f.to_string(),
            cycle: f.cycle,
        });
    }
}

/// Carries out one command on `plc`.
fn carry_out(plc: &mut Plc, command: Command) -> Outcome {
    match command {
        Command::Write { path, literal } => plc
            .write(&path, &literal)
            .map(|()| format!("{path} := {}", literal.trim()))
            .map_err(refusal),
        Command::Force { path, literal } => plc
            .force(&path, &literal)
            .map(|()| format!("{path} forced to {}", literal.trim()))
            .map_err(refusal),
        Command::Unforce { path } => match plc.unforce(&path) {
            Ok(true) => Ok(format!("{path} unforced")),
            Ok(false) => Ok(format!("{path} was not forced")),
            Err(e) => Err(refusal(e)),
        },
        Command::Reset { warm } => {
            if plc.fault().is_none() {
                return Err((
                    409,
                    "the PLC is running: only a faulted PLC is reset".into(),
                ));
            }
            if warm {
                plc.reset_warm();
                Ok("warm reset: the PLC runs again, RETAIN values kept".into())
            } else {
                plc.reset_cold();
                Ok("cold reset: the PLC runs again from its initial values".into())
            }
        }
    }
}

/// The HTTP status and message of a refused write.
fn refusal(e: VarError) -> (u16, String) {
    let status = match &e {
        VarError::BadPath { .. }
        | VarError::Unknown { .. }
        | VarError::NotLocated { .. }
        | VarError::NoMember { .. }
        | VarError::NotAnArray { .. }
        | VarError::IndexCount { .. }
        | VarError::IndexOutOfBounds { .. } => 404,
        VarError::ReadOnly { .. } => 409,
        _ => 400,
    };
    (status, e.to_string())
}
