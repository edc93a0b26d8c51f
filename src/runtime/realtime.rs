//! Running a session's tasks on the wall clock, with per-task statistics.
//!
//! A [`TaskRunner`] drives a [`Session`] base tick by base tick. In real
//! time, base tick `k` of the run has the absolute deadline `start + k ×
//! base tick` on the monotonic clock (deadlines are computed from the
//! start, never from the previous wake-up, so nothing drifts over hours);
//! the runner sleeps until the deadline (on Linux with one
//! `clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)`, so no time passes
//! between computing how long to sleep and sleeping), then runs the tasks
//! due at that tick in priority order, and the program's clock is the monotonic time
//! since the start (what TON and the SFC step times see). When the tick
//! ends after the deadline of the tick after next, the runtime has fallen
//! behind: the ticks in between are skipped, never queued, and each
//! activation of a task that they held is counted as an overrun of that
//! task; the run resumes with the latest tick whose deadline has passed.
//!
//! Before the first tick of a real-time run, the runner prepares its own
//! thread as [`TaskRunner::set_real_time_setup`] says (priority, CPU,
//! locked memory; see [`crate::runtime::rt_thread`]).
//!
//! Per task the runner records cycles, execution time and start jitter
//! (how late the task's first program started after the tick's deadline),
//! readable at any time through [`TaskStatsHandle`]. The same runner in
//! virtual time ([`TaskRunner::virtual_time`]) runs as fast as possible on
//! the virtual clock, with the trace of [`Session::run`] bit for bit, and
//! records execution times (there are no deadlines, hence no jitter).
//!
//! ```
//! use plcrun::{Options, Plc, Session, TaskRunner, TraceFormat, TraceWriter};
//! use std::time::Duration;
//!
//! let src = "PROGRAM P VAR_OUTPUT n : DINT; END_VAR n := n + 1; END_PROGRAM";
//! let options = Options { cycle_time: 2_000_000, ..Options::default() }; // 2 ms
//! let plc = Plc::compile_files(&[("p.st", src)], &options)?;
//! let stop = plc.stop_handle();
//! let runner = TaskRunner::real_time(&plc);
//! let stats = runner.stats();
//! let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
//! // On its own thread, until stopped.
//! let thread = runner.spawn(Session::new(plc), None, trace);
//! while stats.snapshot()[0].cycles < 6 {
//!     std::thread::sleep(Duration::from_millis(5));
//! }
//! stop.stop();
//! let outcome = thread.join();
//! outcome.result?;
//! let s = &stats.snapshot()[0];
//! assert!(s.cycles > 5, "{s:?}");
//! let jitter = s.start_jitter.unwrap();
//! assert!(jitter.min_ns <= jitter.mean_ns && jitter.mean_ns <= jitter.max_ns);
//! assert!(outcome.session.plc().read("n")?.to_literal().parse::<u64>()? == s.cycles);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::clock::Clock;
use super::engine::Plc;
use super::rt_thread::{RealTimeReport, RealTimeSetup};
use super::session::{RunError, Session};
use super::task_stats::{TaskRecord, TaskStatsHandle};
use super::tasks::TickTiming;
use super::trace::TraceWriter;
use std::io::Write;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The longest single sleep while waiting for a deadline, so that a stop
/// asked during a long interval is seen soon.
const MAX_SLEEP: Duration = Duration::from_millis(20);

/// Runs a session's tasks tick by tick, in real or virtual time, recording
/// per-task statistics (see the module docs).
#[derive(Debug)]
pub struct TaskRunner {
    real_time: bool,
    stats: TaskStatsHandle,
    timing: TickTiming,
    between_ticks: Option<BetweenTicks>,
    setup: RealTimeSetup,
    setup_report: Option<RealTimeReport>,
}

/// A hook the runner calls with the whole session after each tick (see
/// [`TaskRunner::set_between_ticks`]).
pub type BetweenTicksHook = Box<dyn FnMut(&mut Session) + Send>;

/// [`BetweenTicksHook`], printable with the runner.
struct BetweenTicks(BetweenTicksHook);

impl std::fmt::Debug for BetweenTicks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("BetweenTicks(..)")
    }
}

/// What a run on its own thread hands back (see [`TaskRunner::spawn`]).
pub struct RunOutcome<W: Write> {
    /// The session, with its PLC as the run left it.
    pub session: Session,
    /// The trace writer (call [`TraceWriter::finish`] to get the output).
    pub trace: TraceWriter<W>,
    /// How the run ended.
    pub result: Result<(), RunError>,
    /// What preparing the thread did (real-time runs that got that far).
    pub real_time: Option<RealTimeReport>,
}

/// A run on its own thread (see [`TaskRunner::spawn`]).
pub struct RunThread<W: Write> {
    thread: JoinHandle<RunOutcome<W>>,
}

impl<W: Write> RunThread<W> {
    /// Waits for the run to end (stop it first with the PLC's
    /// [`crate::StopHandle`], or give it a number of cycles).
    ///
    /// # Panics
    /// If the run's thread panicked (the runtime does not panic on any
    /// program or input; a cycle or stop hook might).
    pub fn join(self) -> RunOutcome<W> {
        match self.thread.join() {
            Ok(outcome) => outcome,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    }

    /// True once the run has ended.
    pub fn is_finished(&self) -> bool {
        self.thread.is_finished()
    }
}

impl TaskRunner {
    /// A runner on the wall clock for `plc`'s tasks.
    pub fn real_time(plc: &Plc) -> TaskRunner {
        TaskRunner::new(plc, true)
    }

    /// A runner on the virtual clock (as fast as possible, the trace of
    /// [`Session::run`]) that also records execution times.
    pub fn virtual_time(plc: &Plc) -> TaskRunner {
        TaskRunner::new(plc, false)
    }

    fn new(plc: &Plc, real_time: bool) -> TaskRunner {
        let records = plc
            .tasks()
            .iter()
            .map(|t| TaskRecord::new(&t.name, t.interval_ns, t.priority))
            .collect();
        TaskRunner {
            real_time,
            stats: TaskStatsHandle::new(records),
            timing: TickTiming::default(),
            between_ticks: None,
            setup: RealTimeSetup::default(),
            setup_report: None,
        }
    }

    /// Sets a hook called with the whole session after each tick, once its
    /// trace row is written and before the wait for the next deadline: the
    /// place for what needs more than the PLC, such as
    /// [`Session::online_change`] (loading a new version compiled on
    /// another thread). Its time counts against the next deadline, as a
    /// cycle's does. Replaces any hook set before; without one the loop
    /// pays a single branch.
    ///
    /// ```
    /// use plcrun::{Options, Plc, Session, TaskRunner, TraceFormat, TraceWriter};
    ///
    /// let v1 = "PROGRAM P VAR_OUTPUT n : DINT; END_VAR n := n + 1; END_PROGRAM";
    /// let v2 = "PROGRAM P VAR_OUTPUT n : DINT; END_VAR n := n + 100; END_PROGRAM";
    /// let plc = Plc::compile_files(&[("p.st", v1)], &Options::default())?;
    /// let mut next = Some(Plc::compile_files(&[("p.st", v2)], &Options::default())?);
    /// let mut runner = TaskRunner::virtual_time(&plc);
    /// runner.set_between_ticks(move |session| {
    ///     if session.plc().cycle() == 3 && let Some(new) = next.take() {
    ///         session.online_change(new).expect("same tasks, same variables");
    ///     }
    /// });
    /// let mut session = Session::new(plc);
    /// let mut trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    /// runner.run(&mut session, Some(5), &mut trace)?;
    /// assert_eq!(session.plc().read("n")?.to_literal(), "203"); // 1, 2, 3, then +100 twice
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_between_ticks(&mut self, hook: impl FnMut(&mut Session) + Send + 'static) {
        self.between_ticks = Some(BetweenTicks(Box::new(hook)));
    }

    /// How a real-time run prepares the thread it runs on (applied when
    /// [`Self::run`] starts, on that thread; ignored in virtual time). A
    /// setting the operating system refuses ends the run before its first
    /// tick with [`RunError::RealTime`]; a refused memory lock does not,
    /// and [`Self::real_time_report`] says why.
    pub fn set_real_time_setup(&mut self, setup: RealTimeSetup) {
        self.setup = setup;
    }

    /// What preparing the thread did, once a real-time run has started.
    pub fn real_time_report(&self) -> Option<&RealTimeReport> {
        self.setup_report.as_ref()
    }

    /// True for a wall-clock runner.
    pub fn is_real_time(&self) -> bool {
        self.real_time
    }

    /// The statistics, readable from any thread at any time.
    pub fn stats(&self) -> TaskStatsHandle {
        self.stats.clone()
    }

    /// Runs `cycles` base ticks (`None`: until stopped), writing one trace
    /// row per tick to `out` — flushed row by row in real time. Ends
    /// cleanly at the cycle boundary after a stop asked through the PLC's
    /// [`crate::StopHandle`], then runs the session's stop hook; ends at
    /// the first fault, trace or live-stimulus error otherwise. The PLC's
    /// clock is restored when the run ends.
    pub fn run<W: Write>(
        &mut self,
        session: &mut Session,
        cycles: Option<u64>,
        out: &mut TraceWriter<W>,
    ) -> Result<(), RunError> {
        let previous_clock = session.plc().clock().clone();
        let result = self.run_ticks(session, cycles, out);
        session.plc_mut().set_clock(previous_clock);
        result?;
        out.flush().map_err(RunError::Trace)?;
        session.run_on_stop()
    }

    fn run_ticks<W: Write>(
        &mut self,
        session: &mut Session,
        cycles: Option<u64>,
        out: &mut TraceWriter<W>,
    ) -> Result<(), RunError> {
        let first_tick = session.plc().next_tick();
        if self.real_time {
            let report = self.setup.apply().map_err(RunError::RealTime)?;
            self.setup_report = Some(report);
        }
        let result = self.ticks(session, cycles, out, first_tick);
        // The CPUs may sleep again once the run is over.
        if let Some(report) = &mut self.setup_report {
            report.release();
        }
        result
    }

    fn ticks<W: Write>(
        &mut self,
        session: &mut Session,
        cycles: Option<u64>,
        out: &mut TraceWriter<W>,
        first_tick: u64,
    ) -> Result<(), RunError> {
        let stop = session.plc().stop_handle();
        let base = u64::try_from(session.plc().cycle_time())
            .unwrap_or(1)
            .max(1);
        let start = Instant::now();
        let sleeper = Sleeper::new(start);
        if self.real_time {
            out.set_streaming(true);
            // The program's clock continues the schedule's: tick k at k × base.
            let since = Duration::from_nanos(base.saturating_mul(first_tick));
            let origin = start.checked_sub(since).unwrap_or(start);
            session.plc_mut().set_clock(Clock::monotonic_since(origin));
        }
        let deadline_of = |tick: u64| {
            let ns = base.saturating_mul(tick.saturating_sub(first_tick));
            start + Duration::from_nanos(ns)
        };
        let mut ran = 0u64;
        while cycles.is_none_or(|n| ran < n) && !stop.is_stop_requested() {
            let deadline = self
                .real_time
                .then(|| deadline_of(session.plc().next_tick()));
            if deadline.is_some_and(|d| !sleeper.sleep_until(d, &stop)) {
                break;
            }
            session.apply_live_stimulus().map_err(RunError::Stimulus)?;
            let cycle = session.plc().cycle();
            let (timing, stats) = (&mut self.timing, &self.stats);
            session.step_by(|plc| plc.run_tick_timed(deadline, timing, stats))?;
            let time = session.plc().last_cycle_time();
            out.row_marked(cycle, time, session.cells(), session.forced_cells())
                .map_err(RunError::Trace)?;
            ran += 1;
            if let Some(BetweenTicks(hook)) = &mut self.between_ticks {
                hook(session);
            }
            if self.real_time {
                // The latest tick whose deadline has passed; the ones
                // before it (after the tick just run) are missed.
                let behind = start.elapsed().as_nanos() / u128::from(base);
                let latest = first_tick.saturating_add(u64::try_from(behind).unwrap_or(u64::MAX));
                session.plc_mut().skip_ticks_to(latest, &self.stats);
            }
        }
        Ok(())
    }

    /// Runs on a new thread (see [`Self::run`]); stop it with the PLC's
    /// [`crate::StopHandle`], taken before, and read the statistics with
    /// [`Self::stats`], taken before, while it runs.
    pub fn spawn<W: Write + Send + 'static>(
        mut self,
        mut session: Session,
        cycles: Option<u64>,
        mut trace: TraceWriter<W>,
    ) -> RunThread<W> {
        let thread = std::thread::spawn(move || {
            let result = self.run(&mut session, cycles, &mut trace);
            RunOutcome {
                session,
                trace,
                result,
                real_time: self.setup_report.take(),
            }
        });
        RunThread { thread }
    }
}

/// Sleeps until deadlines given as `Instant`s, in slices of at most
/// [`MAX_SLEEP`] so that a stop is seen soon.
struct Sleeper {
    #[cfg(target_os = "linux")]
    origin: (Instant, libc::timespec),
}

impl Sleeper {
    /// `Instant` is `CLOCK_MONOTONIC` on Linux, but it does not give its
    /// `timespec` out: the two are read together once, and each deadline
    /// is turned into an absolute `timespec` from its distance to `origin`.
    fn new(origin: Instant) -> Sleeper {
        #[cfg(target_os = "linux")]
        {
            let mut ts = libc::timespec {
                tv_sec: 0,
                tv_nsec: 0,
            };
            // SAFETY: `ts` is a valid timespec to write.
            unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut ts) };
            let origin = (origin, ts);
            Sleeper { origin }
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = origin;
            Sleeper {}
        }
    }

    /// Sleeps until `deadline`, returning false as soon as a stop is asked.
    fn sleep_until(&self, deadline: Instant, stop: &super::stop::StopHandle) -> bool {
        loop {
            if stop.is_stop_requested() {
                return false;
            }
            let now = Instant::now();
            if now >= deadline {
                return true;
            }
            let wake = if deadline - now > MAX_SLEEP {
                now + MAX_SLEEP
            } else {
                deadline
            };
            self.sleep_to(wake, now);
        }
    }

    #[cfg(target_os = "linux")]
    fn sleep_to(&self, wake: Instant, _now: Instant) {
        let (instant, ts) = self.origin;
        let after = wake.saturating_duration_since(instant);
        let nanos = ts.tv_nsec as u64 + u64::from(after.subsec_nanos());
        let target = libc::timespec {
            tv_sec: ts.tv_sec
                + after.as_secs() as libc::time_t
                + (nanos / 1_000_000_000) as libc::time_t,
            tv_nsec: (nanos % 1_000_000_000) as libc::c_long,
        };
        // SAFETY: `target` is a valid timespec; no remainder is asked for
        // (with TIMER_ABSTIME an interrupted sleep is simply restarted by
        // the loop above).
        unsafe {
            libc::clock_nanosleep(
                libc::CLOCK_MONOTONIC,
                libc::TIMER_ABSTIME,
                &target,
                std::ptr::null_mut(),
            )
        };
    }

    #[cfg(not(target_os = "linux"))]
    fn sleep_to(&self, wake: Instant, now: Instant) {
        std::thread::sleep(wake - now);
    }
}
