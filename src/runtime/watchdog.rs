//! The cycle-time watchdog: a limit per task, enforced by one timer
//! thread per PLC that interrupts a task run overrunning it.
//!
//! The thread that runs the PLC never reads the clock for the watchdog. It
//! only publishes, with two plain atomic stores, that a task run started
//! (an odd activity number, with the task's limit) or ended (the next,
//! even, number). The watchdog thread looks at that number every eighth
//! of the smallest limit; the first time it sees a run, it notes the time,
//! and once that run has been seen for its whole limit it sets the
//! interrupt word, which the executor polls at every backward jump and
//! call. So a run is stopped at most an eighth of the limit (plus the
//! operating system's wake-up latency) after its limit, and the time it
//! reports is measured from that first look: at most an eighth of the
//! limit (plus that latency) below the real time spent. The thread is started by the first
//! task run that has a limit and ends with its PLC.

use super::engine::Plc;
use crate::vm::Interrupt;
use std::fmt;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Barrier};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The polling period never goes below this, so that a tiny limit does
/// not turn the watchdog thread into a busy loop.
const MIN_PERIOD: Duration = Duration::from_micros(250);

/// A task ran past its watchdog limit: which task, the limit and the time
/// it had run when it was stopped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WatchdogTrip {
    /// The task's name (`default` for the implicit task of a program
    /// without configuration).
    pub task: String,
    /// The task's limit.
    pub limit: Duration,
    /// The time the task had run when it was stopped (measured from the
    /// watchdog's first look at the run: at most an eighth of the limit,
    /// plus the operating system's wake-up latency, below the real time).
    pub elapsed: Duration,
}

impl fmt::Display for WatchdogTrip {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "watchdog: task `{}` ran {}, limit {}",
            self.task,
            Millis(self.elapsed),
            Millis(self.limit)
        )
    }
}

/// A duration in milliseconds, with one decimal unless whole.
struct Millis(Duration);

impl fmt::Display for Millis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let tenths = (self.0.as_micros() + 50) / 100;
        if tenths.is_multiple_of(10) {
            write!(f, "{} ms", tenths / 10)
        } else {
            write!(f, "{}.{} ms", tenths / 10, tenths % 10)
        }
    }
}

/// A task name that the PLC's configuration does not have.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownTask {
    /// The name asked for.
    pub name: String,
    /// The tasks there are.
    pub known: Vec<String>,
}

impl fmt::Display for UnknownTask {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "no task `{}` (the tasks are: {})",
            self.name,
            self.known.join(", ")
        )
    }
}

impl std::error::Error for UnknownTask {}

/// What the running PLC and its watchdog thread share.
#[derive(Debug)]
struct Shared {
    interrupt: Arc<Interrupt>,
    /// The limit of the task run under way, in ns (0: none).
    limit_ns: AtomicU64,
    /// How often the thread looks, in ns.
    period_ns: AtomicU64,
    /// The run the thread last saw for the first time, and when (ns since
    /// `epoch`).
    seen_for: AtomicU64,
    seen_at: AtomicU64,
    shutdown: AtomicBool,
    epoch: Instant,
}

impl Shared {
    fn since_epoch(&self) -> u64 {
        self.epoch.elapsed().as_nanos() as u64
    }
}

/// The limits of a PLC's tasks and the timer thread enforcing them.
#[derive(Debug)]
pub(crate) struct Watchdog {
    /// Per task (indexed like the image's tasks).
    limits: Vec<Option<Duration>>,
    /// The same in ns (0: none), as the cycle publishes them.
    limits_ns: Vec<u64>,
    /// The task whose run is under way (between `enter` and `leave`),
    /// `NO_TASK` between runs.
    running: usize,
    shared: Arc<Shared>,
    thread: Option<JoinHandle<()>>,
}

/// `Watchdog::running` between task runs.
const NO_TASK: usize = usize::MAX;

fn nanos(d: Duration) -> u64 {
    d.as_nanos().min(u64::MAX as u128) as u64
}

impl Watchdog {
    /// The watchdog of a machine polling `interrupt`, with `tasks` tasks
    /// limited to `limit` each.
    pub(crate) fn new(interrupt: Arc<Interrupt>, tasks: usize, limit: Option<Duration>) -> Self {
        let mut w = Watchdog {
            limits: vec![limit; tasks],
            limits_ns: vec![limit.map_or(0, nanos); tasks],
            running: NO_TASK,
            shared: Arc::new(Shared {
                interrupt,
                limit_ns: AtomicU64::new(0),
                period_ns: AtomicU64::new(0),
                seen_for: AtomicU64::new(0),
                seen_at: AtomicU64::new(0),
                shutdown: AtomicBool::new(false),
                epoch: Instant::now(),
            }),
            thread: None,
        };
        w.update_period();
        w
    }

    fn update_period(&mut self) {
        let smallest = self.limits.iter().flatten().min().copied();
        let period = smallest.map_or(Duration::from_secs(1), |l| (l / 8).max(MIN_PERIOD));
        self.shared
            .period_ns
            .store(nanos(period), Ordering::Relaxed);
    }

    /// Task `task` (an index into the image's tasks) runs its code from
    /// now on; nothing to do while the same task goes on.
    #[inline]
    pub(crate) fn enter(&mut self, task: usize) {
        if self.running == task {
            return;
        }
        self.leave();
        let limit = self.limits_ns.get(task).copied().unwrap_or(0);
        self.shared.limit_ns.store(limit, Ordering::Relaxed);
        self.shared.interrupt.advance_activity();
        self.running = task;
        if limit != 0 && self.thread.is_none() {
            self.start_thread();
        }
    }

    /// The task run under way (if any) has ended.
    #[inline]
    pub(crate) fn leave(&mut self) {
        if self.running != NO_TASK {
            self.running = NO_TASK;
            self.shared.interrupt.advance_activity();
        }
    }

    /// Why the run under way was stopped by the watchdog: the task, its
    /// limit and the time spent (`tasks` names the image's tasks).
    pub(crate) fn trip(&self, task_name: impl Fn(usize) -> String) -> Option<WatchdogTrip> {
        let task = self.running;
        let limit = self.limits.get(task).copied().flatten()?;
        let now = self.shared.since_epoch();
        let run = self.shared.interrupt.activity();
        let elapsed = if self.shared.seen_for.load(Ordering::Acquire) == run {
            Duration::from_nanos(now.saturating_sub(self.shared.seen_at.load(Ordering::Relaxed)))
        } else {
            limit
        };
        Some(WatchdogTrip {
            task: task_name(task),
            limit,
            elapsed,
        })
    }

    /// Sets the limit of task `task` (an index into the image's tasks).
    fn set_limit(&mut self, task: usize, limit: Option<Duration>) {
        if let (Some(slot), Some(ns)) = (self.limits.get_mut(task), self.limits_ns.get_mut(task)) {
            *slot = limit;
            *ns = limit.map_or(0, nanos);
        }
        self.update_period();
    }

    /// Starts the timer thread and waits until it is under way, so that
    /// whatever the thread's start-up allocates is allocated before the
    /// cycle goes on (cycles do not allocate, even on another thread).
    /// Should the system refuse a thread, the next task run with a limit
    /// tries again.
    #[cold]
    fn start_thread(&mut self) {
        let shared = Arc::clone(&self.shared);
        let ready = Arc::new(Barrier::new(2));
        let started = Arc::clone(&ready);
        self.thread = std::thread::Builder::new()
            .name("plcrun-watchdog".into())
            .spawn(move || {
                started.wait();
                watch(&shared)
            })
            .ok();
        if self.thread.is_some() {
            ready.wait();
        }
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        self.shared.shutdown.store(true, Ordering::Release);
        if let Some(thread) = self.thread.take() {
            thread.thread().unpark();
            let _ = thread.join();
        }
    }
}

/// The timer thread: looks at the activity every period, and sets the
/// interrupt word for a run it has seen for its whole limit.
fn watch(shared: &Shared) {
    let mut seen: Option<(u64, u64)> = None; // (run, first seen at)
    while !shared.shutdown.load(Ordering::Acquire) {
        let period = shared.period_ns.load(Ordering::Relaxed);
        let run = shared.interrupt.activity();
        let limit = shared.limit_ns.load(Ordering::Relaxed);
        let now = shared.since_epoch();
        let mut sleep = period;
        if run % 2 == 1 && limit > 0 {
            let first = match seen {
                Some((r, at)) if r == run => at,
                _ => {
                    seen = Some((run, now));
                    shared.seen_at.store(now, Ordering::Relaxed);
                    shared.seen_for.store(run, Ordering::Release);
                    now
                }
            };
            let deadline = first.saturating_add(limit);
            if now >= deadline {
                // Fires again at the next look if the run goes on (the
                // executor may have dropped a bit set as it moved on).
                if shared.interrupt.activity() == run {
                    shared.interrupt.fire_watchdog(run);
                }
            } else {
                sleep = sleep.min(deadline - now);
            }
        }
        std::thread::park_timeout(Duration::from_nanos(sleep.max(1)));
    }
}

impl Plc {
    /// Sets the watchdog limit of the task named `task` (case-insensitive;
    /// `default` is the implicit task of a program without configuration);
    /// `None` (or a zero limit) turns its watchdog off. A run of the task's programs that
    /// takes longer is stopped with a [`crate::FaultKind::Watchdog`] fault
    /// (R008) whose [`crate::RuntimeFault::watchdog`] names the task, the
    /// limit and the time spent. [`crate::Options::watchdog`] is every
    /// task's limit to begin with.
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// use std::time::Duration;
    /// let src = "PROGRAM P VAR x : INT; END_VAR x := x + 1; END_PROGRAM
    ///            CONFIGURATION C RESOURCE R ON PLC
    ///              TASK fast (INTERVAL := T#10ms, PRIORITY := 0);
    ///              PROGRAM p1 WITH fast : P;
    ///            END_RESOURCE END_CONFIGURATION";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// plc.set_task_watchdog("fast", Some(Duration::from_millis(5)))?;
    /// assert_eq!(plc.task_watchdog("fast")?, Some(Duration::from_millis(5)));
    /// assert!(plc.set_task_watchdog("slow", None).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_task_watchdog(
        &mut self,
        task: &str,
        limit: Option<Duration>,
    ) -> Result<(), UnknownTask> {
        let k = self.task_index(task)?;
        self.watchdog.set_limit(k, limit);
        Ok(())
    }

    /// The watchdog limit of the task named `task` (`None`: off).
    pub fn task_watchdog(&self, task: &str) -> Result<Option<Duration>, UnknownTask> {
        let k = self.task_index(task)?;
        Ok(self.watchdog.limits[k])
    }

    /// Sets the same watchdog limit for every task (`None`: off).
    pub fn set_watchdog(&mut self, limit: Option<Duration>) {
        for k in 0..self.watchdog.limits.len() {
            self.watchdog.set_limit(k, limit);
        }
    }

    fn task_index(&self, task: &str) -> Result<usize, UnknownTask> {
        let tasks = &self.image.tasks;
        tasks
            .iter()
            .position(|t| t.name.eq_ignore_ascii_case(task.trim()))
            .ok_or_else(|| UnknownTask {
                name: task.to_string(),
                known: tasks.iter().map(|t| t.name.clone()).collect(),
            })
    }
}
