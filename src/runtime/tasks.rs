//! A PLC's tasks from outside: listing them, running one cycle of one task,
//! and running a base tick while timing each task (for statistics).
//!
//! ```
//! use plcrun::{Options, Plc};
//!
//! let src = "
//! PROGRAM Fast VAR_OUTPUT n : INT; END_VAR n := n + 1; END_PROGRAM
//! PROGRAM Slow VAR_OUTPUT n : INT; END_VAR n := n + 1; END_PROGRAM
//! CONFIGURATION C RESOURCE R ON PLC
//!   TASK T_fast(INTERVAL := T#2ms, PRIORITY := 1);
//!   TASK T_slow(INTERVAL := T#5ms, PRIORITY := 0);
//!   PROGRAM fast WITH T_fast : Fast;
//!   PROGRAM slow WITH T_slow : Slow;
//! END_RESOURCE END_CONFIGURATION";
//! let mut plc = Plc::compile_files(&[("c.st", src)], &Options::default())?;
//! let names: Vec<String> = plc.tasks().into_iter().map(|t| t.name).collect();
//! assert_eq!(names, ["T_fast", "T_slow"]);
//! assert_eq!(plc.cycle_time(), 1_000_000); // the base tick: gcd(2 ms, 5 ms)
//! for _ in 0..10 {
//!     plc.run_cycle()?; // one base tick: ticks 0..9 = 0 ms..9 ms
//! }
//! assert_eq!(plc.read("fast.n")?.to_literal(), "5"); // 0, 2, 4, 6, 8 ms
//! assert_eq!(plc.read("slow.n")?.to_literal(), "2"); // 0, 5 ms
//! plc.run_task("T_slow")?; // one cycle of one task, now
//! assert_eq!(plc.read("slow.n")?.to_literal(), "3");
//! assert!(plc.run_task("T_medium").is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::engine::{Plc, RuntimeFault};
use super::task_stats::TaskStatsHandle;
use std::fmt;
use std::time::Instant;

/// A task of the program's configuration (or the implicit task, named
/// `default`, of a program run without one).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TaskInfo {
    /// The task's name as declared.
    pub name: String,
    /// Its INTERVAL in nanoseconds (0 for a SINGLE task).
    pub interval_ns: i64,
    /// Its PRIORITY (0 runs first).
    pub priority: i64,
    /// True for a SINGLE (event) task.
    pub single: bool,
}

/// Why [`Plc::run_task`] did not run the task's cycle.
#[derive(Debug, Clone, PartialEq)]
pub enum TaskStepError {
    /// No task has this name.
    UnknownTask {
        /// The name asked for.
        name: String,
        /// The tasks there are.
        known: Vec<String>,
    },
    /// The task's program faulted.
    Fault(RuntimeFault),
}

impl fmt::Display for TaskStepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TaskStepError::UnknownTask { name, known } => {
                write!(f, "no task `{name}` (the tasks are: {})", known.join(", "))
            }
            TaskStepError::Fault(fault) => fault.fmt(f),
        }
    }
}

impl std::error::Error for TaskStepError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TaskStepError::Fault(fault) => Some(fault),
            TaskStepError::UnknownTask { .. } => None,
        }
    }
}

impl From<RuntimeFault> for TaskStepError {
    fn from(fault: RuntimeFault) -> Self {
        TaskStepError::Fault(fault)
    }
}

/// Per task, when its first program of the current tick started and how
/// long its programs have run; kept across ticks so that timing a tick
/// does not allocate.
#[derive(Debug, Default)]
pub(crate) struct TickTiming {
    started: Vec<Option<Instant>>,
    ran_ns: Vec<i64>,
}

impl Plc {
    /// The tasks, in declaration order.
    pub fn tasks(&self) -> Vec<TaskInfo> {
        self.image
            .tasks
            .iter()
            .map(|t| TaskInfo {
                name: t.name.clone(),
                interval_ns: t.interval,
                priority: t.priority,
                single: t.single.is_some(),
            })
            .collect()
    }

    /// Runs one cycle of one task, named case-insensitively, now: its
    /// programs in declaration order, at the clock's current value (on the
    /// virtual clock, the next base tick's time, which this does not
    /// advance; with [`Plc::set_clock`] a host runs tasks on its own
    /// schedule). Counts as a cycle ([`Plc::cycle`]).
    pub fn run_task(&mut self, name: &str) -> Result<(), TaskStepError> {
        let Some(task) = self
            .image
            .tasks
            .iter()
            .position(|t| t.name.eq_ignore_ascii_case(name))
        else {
            return Err(TaskStepError::UnknownTask {
                name: name.to_string(),
                known: self.image.tasks.iter().map(|t| t.name.clone()).collect(),
            });
        };
        self.begin_tick()?;
        for p in 0..self.image.programs.len() {
            if self.image.programs[p].task == task {
                self.run_program(p)?;
            }
        }
        self.end_programs();
        self.cycle += 1;
        Ok(())
    }

    /// Runs one base tick like [`Plc::run_cycle`], timing each task that
    /// runs: how long after `deadline` its first program started (when
    /// there is a deadline and the task is cyclic) and how long its
    /// programs ran, recorded in `stats`.
    pub(crate) fn run_tick_timed(
        &mut self,
        deadline: Option<Instant>,
        timing: &mut TickTiming,
        stats: &TaskStatsHandle,
    ) -> Result<(), RuntimeFault> {
        let tasks = self.image.tasks.len();
        timing.started.clear();
        timing.started.resize(tasks, None);
        timing.ran_ns.clear();
        timing.ran_ns.resize(tasks, 0);
        let scheduled = self.begin_tick()?;
        self.scheduler
            .start_tick(&self.image.tasks, scheduled, &self.machine.mem);
        for k in 0..self.scheduler.len() {
            let Some(p) = self.scheduler.due_program(k, &self.image.programs) else {
                continue;
            };
            let task = self.image.programs[p].task;
            let start = Instant::now();
            timing.started[task].get_or_insert(start);
            self.run_program(p)?;
            timing.ran_ns[task] += nanos(start.elapsed().as_nanos());
        }
        stats.with(|records| {
            for (t, record) in records.iter_mut().enumerate() {
                let Some(Some(started)) = timing.started.get(t) else {
                    continue;
                };
                let cyclic = self.image.tasks[t].single.is_none();
                let jitter = deadline
                    .filter(|_| cyclic)
                    .map(|d| signed_nanos(*started, d));
                record.record(jitter, timing.ran_ns[t]);
            }
        });
        self.end_programs();
        self.scheduler.end_tick();
        self.cycle += 1;
        Ok(())
    }

    /// The number of the next base tick (counting the ticks a real-time
    /// run skipped).
    pub(crate) fn next_tick(&self) -> u64 {
        self.scheduler.next_tick()
    }

    /// Skips the base ticks before `tick`, counting each activation they
    /// held as an overrun of its task in `stats`.
    pub(crate) fn skip_ticks_to(&mut self, tick: u64, stats: &TaskStatsHandle) {
        let from = self.scheduler.next_tick();
        if tick <= from {
            return;
        }
        stats.with(|records| {
            for (record, task) in records.iter_mut().zip(&self.image.tasks) {
                if task.single.is_none() {
                    let missed = self
                        .scheduler
                        .activations_between(task.interval, from, tick);
                    record.add_overruns(missed);
                }
            }
        });
        self.scheduler.skip_to(tick);
    }

    /// Whether task `task` ran at the last tick.
    #[cfg(test)]
    pub(crate) fn task_was_due(&self, task: usize) -> bool {
        self.scheduler.is_due(task)
    }
}

fn nanos(n: u128) -> i64 {
    i64::try_from(n).unwrap_or(i64::MAX)
}

/// `at - reference` in nanoseconds, negative when `at` is earlier.
fn signed_nanos(at: Instant, reference: Instant) -> i64 {
    match at.checked_duration_since(reference) {
        Some(d) => nanos(d.as_nanos()),
        None => -nanos(reference.duration_since(at).as_nanos()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runtime::engine::Options;
    use crate::runtime::task_stats::TaskRecord;

    const TWO_TASKS: &str = "
        PROGRAM Count VAR_OUTPUT n : INT; END_VAR n := n + 1; END_PROGRAM
        CONFIGURATION C RESOURCE R ON PLC
          TASK fast(INTERVAL := T#2ms, PRIORITY := 1);
          TASK slow(INTERVAL := T#5ms, PRIORITY := 0);
          PROGRAM a WITH fast : Count;
          PROGRAM b WITH slow : Count;
        END_RESOURCE END_CONFIGURATION";

    /// Without a watchdog: these tests check schedules and statistics, and
    /// under valgrind (scripts/memcheck) on a loaded machine a first cycle
    /// has taken longer than the default second (tests/watchdog.rs tests
    /// the watchdog).
    fn plc() -> Plc {
        let options = Options {
            watchdog: None,
            ..Options::default()
        };
        Plc::compile_files(&[("c.st", TWO_TASKS)], &options).unwrap()
    }

    fn stats(plc: &Plc) -> TaskStatsHandle {
        let records = plc
            .tasks()
            .iter()
            .map(|t| TaskRecord::new(&t.name, t.interval_ns, t.priority))
            .collect();
        TaskStatsHandle::new(records)
    }

    #[test]
    fn base_ticks_run_the_due_tasks() {
        let mut plc = plc();
        let mut ran = Vec::new();
        for _ in 0..11 {
            plc.run_cycle().unwrap();
            ran.push((plc.task_was_due(0), plc.task_was_due(1)));
        }
        let fast: Vec<usize> = (0..11).filter(|&k| ran[k].0).collect();
        let slow: Vec<usize> = (0..11).filter(|&k| ran[k].1).collect();
        assert_eq!(fast, [0, 2, 4, 6, 8, 10]);
        assert_eq!(slow, [0, 5, 10]);
        assert_eq!(plc.time(), 11_000_000);
    }

    #[test]
    fn timed_ticks_run_the_same_schedule_and_record_it() {
        let (mut timed, mut plain) = (plc(), plc());
        let handle = stats(&timed);
        let mut timing = TickTiming::default();
        for _ in 0..20 {
            timed.run_tick_timed(None, &mut timing, &handle).unwrap();
            plain.run_cycle().unwrap();
        }
        for name in ["a.n", "b.n"] {
            assert_eq!(timed.read(name).unwrap(), plain.read(name).unwrap());
        }
        let s = handle.snapshot();
        assert_eq!((s[0].cycles, s[1].cycles), (10, 4));
        assert!(s[0].execution.is_some() && s[0].start_jitter.is_none());
    }

    #[test]
    fn skipped_ticks_count_overruns_and_never_run() {
        let mut plc = plc();
        let handle = stats(&plc);
        plc.run_cycle().unwrap(); // tick 0
        plc.skip_ticks_to(10, &handle); // ticks 1..9 missed
        assert_eq!(plc.time(), 10_000_000);
        let s = handle.snapshot();
        assert_eq!((s[0].overruns, s[1].overruns), (4, 1)); // 2,4,6,8 and 5
        assert_eq!(plc.read("a.n").unwrap().to_literal(), "1");
    }

    #[test]
    fn one_task_runs_alone() {
        let mut plc = plc();
        plc.run_task("SLOW").unwrap();
        assert_eq!(plc.read("a.n").unwrap().to_literal(), "0");
        assert_eq!(plc.read("b.n").unwrap().to_literal(), "1");
        assert_eq!((plc.cycle(), plc.time()), (1, 0));
        let err = plc.run_task("medium").unwrap_err();
        assert_eq!(
            err.to_string(),
            "no task `medium` (the tasks are: fast, slow)"
        );
    }
}
