//! The cyclic task scheduler: which program instances run at a tick of the
//! virtual clock, and in which order.
//!
//! The base tick is the greatest common divisor of the cyclic tasks'
//! intervals (or the implicit task's cycle time when there is no
//! configuration). At each tick, a cyclic task is due when the clock is a
//! multiple of its interval, a SINGLE task on the rising edge of its
//! trigger; the due tasks' programs run by task priority (0 first), then
//! in declaration order.

use crate::ir::image::{ProgramInstance, Task};

/// Greatest common divisor.
fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a.abs() } else { gcd(b, a % b) }
}

/// The schedule of one program, and the trigger memory of its SINGLE tasks.
#[derive(Debug, Clone)]
pub(crate) struct Scheduler {
    base_tick: i64,
    /// The number of the next base tick: its scheduled time is
    /// `next_tick × base_tick` (ticks a real-time run skips are counted).
    next_tick: u64,
    /// Program instance indexes by task priority, then declaration.
    order: Vec<usize>,
    /// Each SINGLE task's trigger at the previous tick.
    single_prev: Vec<bool>,
    /// Which tasks are due at the current tick.
    due: Vec<bool>,
}

impl Scheduler {
    /// The schedule of `tasks` and `programs`; `cycle_time` (ns) is the
    /// base tick when no task is cyclic.
    pub(crate) fn new(tasks: &[Task], programs: &[ProgramInstance], cycle_time: i64) -> Self {
        let base_tick = tasks
            .iter()
            .filter(|t| t.interval > 0)
            .map(|t| t.interval)
            .reduce(gcd)
            .unwrap_or(cycle_time)
            .max(1);
        let mut order: Vec<usize> = (0..programs.len()).collect();
        order.sort_by_key(|&i| (tasks[programs[i].task].priority, i));
        Scheduler {
            base_tick,
            next_tick: 0,
            order,
            single_prev: vec![false; tasks.len()],
            due: vec![false; tasks.len()],
        }
    }

    /// The base tick in nanoseconds.
    pub(crate) fn base_tick(&self) -> i64 {
        self.base_tick
    }

    /// The number of the next base tick.
    pub(crate) fn next_tick(&self) -> u64 {
        self.next_tick
    }

    /// The scheduled time of the next base tick, in nanoseconds.
    #[inline]
    pub(crate) fn scheduled_time(&self) -> i64 {
        (self.next_tick as i64).saturating_mul(self.base_tick)
    }

    /// Moves on to the next base tick.
    #[inline]
    pub(crate) fn end_tick(&mut self) {
        self.next_tick += 1;
    }

    /// Skips ahead so that the next base tick is `tick` (a real-time run
    /// that fell behind); never goes back.
    pub(crate) fn skip_to(&mut self, tick: u64) {
        self.next_tick = self.next_tick.max(tick);
    }

    /// Whether task `task` is due at the current tick (after
    /// [`Self::start_tick`]).
    #[cfg(test)]
    pub(crate) fn is_due(&self, task: usize) -> bool {
        self.due.get(task).copied().unwrap_or(false)
    }

    /// How many activations of a cyclic task of `interval` ns fall on the
    /// ticks `from..to` (0 for an event task).
    pub(crate) fn activations_between(&self, interval: i64, from: u64, to: u64) -> u64 {
        if interval <= 0 || to <= from {
            return 0;
        }
        // Multiples of `interval` in [a, b) are ceil(b / i) - ceil(a / i).
        let a = i128::from(from) * i128::from(self.base_tick);
        let b = i128::from(to) * i128::from(self.base_tick);
        let i = i128::from(interval);
        let ceil = |x: i128| (x + i - 1) / i;
        u64::try_from(ceil(b) - ceil(a)).unwrap_or(0)
    }

    /// Decides which tasks are due at clock `now`; a SINGLE task reads its
    /// trigger in `memory`.
    pub(crate) fn start_tick(&mut self, tasks: &[Task], now: i64, memory: &[u64]) {
        for (i, t) in tasks.iter().enumerate() {
            self.due[i] = match t.single {
                Some(addr) => {
                    let v = memory.get(addr as usize).is_some_and(|&x| x != 0);
                    let rising = v && !self.single_prev[i];
                    self.single_prev[i] = v;
                    rising
                }
                None => t.interval > 0 && now % t.interval == 0,
            };
        }
    }

    /// The `k`-th program instance in run order if its task is due at this
    /// tick (`None` when it is not, or past the end).
    pub(crate) fn due_program(&self, k: usize, programs: &[ProgramInstance]) -> Option<usize> {
        let p = *self.order.get(k)?;
        self.due[programs[p].task].then_some(p)
    }

    /// Takes over the tick count and the SINGLE triggers' memory of `old`, a
    /// schedule of the same tasks (online change): the clock goes on, and a
    /// trigger already high does not count as a new rising edge.
    pub(crate) fn carry_over(&mut self, old: &Scheduler) {
        self.next_tick = old.next_tick;
        if old.single_prev.len() == self.single_prev.len() {
            self.single_prev.clone_from(&old.single_prev);
        }
    }

    /// How many program instances there are.
    pub(crate) fn len(&self) -> usize {
        self.order.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::type_table::TypeId;

    fn task(name: &str, interval: i64, priority: i64, single: Option<u32>) -> Task {
        Task {
            name: name.into(),
            interval,
            priority,
            single,
        }
    }

    fn program(task: usize) -> ProgramInstance {
        ProgramInstance {
            name: String::new(),
            type_name: String::new(),
            code: crate::ir::op::CodeIdx::new(0),
            base: 0,
            ty: TypeId(0),
            task,
            inputs: Vec::new(),
            outputs: Vec::new(),
        }
    }

    fn due(s: &Scheduler, programs: &[ProgramInstance]) -> Vec<usize> {
        (0..s.len())
            .filter_map(|k| s.due_program(k, programs))
            .collect()
    }

    #[test]
    fn the_base_tick_divides_every_interval() {
        let tasks = [
            task("fast", 20_000_000, 1, None),
            task("slow", 50_000_000, 0, None),
        ];
        let s = Scheduler::new(&tasks, &[program(0)], 10_000_000);
        assert_eq!(s.base_tick(), 10_000_000);
        let s = Scheduler::new(&[], &[], 7);
        assert_eq!(s.base_tick(), 7);
    }

    #[test]
    fn due_programs_run_by_priority_then_declaration() {
        let tasks = [task("fast", 20, 1, None), task("slow", 50, 0, None)];
        let programs = [program(0), program(1), program(0)];
        let mut s = Scheduler::new(&tasks, &programs, 10);
        s.start_tick(&tasks, 0, &[]);
        assert_eq!(due(&s, &programs), [1, 0, 2]);
        s.start_tick(&tasks, 20, &[]);
        assert_eq!(due(&s, &programs), [0, 2]);
        s.start_tick(&tasks, 50, &[]);
        assert_eq!(due(&s, &programs), [1]);
    }

    #[test]
    fn ticks_advance_skip_and_count_missed_activations() {
        let tasks = [task("fast", 20, 1, None), task("slow", 50, 0, None)];
        let mut s = Scheduler::new(&tasks, &[program(0)], 10);
        assert_eq!((s.next_tick(), s.scheduled_time()), (0, 0));
        s.end_tick();
        assert_eq!(s.scheduled_time(), 10);
        s.skip_to(7);
        s.skip_to(3);
        assert_eq!((s.next_tick(), s.scheduled_time()), (7, 70));
        // Ticks 1..7 are 10..60: "fast" is due at 20, 40, 60, "slow" at 50.
        assert_eq!(s.activations_between(20, 1, 7), 3);
        assert_eq!(s.activations_between(50, 1, 7), 1);
        assert_eq!(s.activations_between(50, 0, 1), 1);
        assert_eq!(s.activations_between(0, 0, 100), 0);
        assert_eq!(s.activations_between(20, 5, 5), 0);
    }

    #[test]
    fn a_single_task_runs_on_the_rising_edge_of_its_trigger() {
        let tasks = [task("event", 0, 0, Some(3))];
        let programs = [program(0)];
        let mut s = Scheduler::new(&tasks, &programs, 10);
        let mut memory = [0u64; 4];
        let mut runs = Vec::new();
        for (tick, trigger) in [0, 1, 1, 0, 1].into_iter().enumerate() {
            memory[3] = trigger;
            s.start_tick(&tasks, tick as i64 * 10, &memory);
            runs.push(due(&s, &programs).len());
        }
        assert_eq!(runs, [0, 1, 0, 0, 1]);
    }
}
