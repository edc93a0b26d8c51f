//! Per-task statistics of a run: cycles, execution time, start jitter,
//! overruns.
//!
//! Recording a sample never allocates: each distribution keeps its count,
//! minimum, maximum and sum, and a fixed histogram with 16 sub-buckets per
//! power of two, from which the 99th percentile is read (to within 1/16 of
//! its value, rounded up, never above the maximum).

use serde::Serialize;
use std::sync::{Arc, Mutex, PoisonError};

/// Buckets: values 0..16 exactly, then 16 per power of two up to 2^63.
const SUB_BITS: u32 = 4;
const SUB: usize = 1 << SUB_BITS;
const BUCKETS: usize = (64 - SUB_BITS as usize + 1) * SUB;

fn bucket_of(v: u64) -> usize {
    if v < SUB as u64 {
        return v as usize;
    }
    let exp = 63 - v.leading_zeros();
    let sub = ((v >> (exp - SUB_BITS)) as usize) & (SUB - 1);
    (exp - SUB_BITS + 1) as usize * SUB + sub
}

/// The largest value that falls in bucket `b`.
fn bucket_top(b: usize) -> u64 {
    if b < SUB {
        return b as u64;
    }
    let exp = (b / SUB) as u32 + SUB_BITS - 1;
    let sub = (b % SUB) as u64;
    let low = (SUB as u64 + sub) << (exp - SUB_BITS);
    low.saturating_add((1u64 << (exp - SUB_BITS)) - 1)
}

/// A distribution of durations in nanoseconds.
#[derive(Clone)]
pub(crate) struct Distribution {
    count: u64,
    min: i64,
    max: i64,
    sum: i128,
    /// Negative samples are counted in bucket 0.
    histogram: Box<[u32; BUCKETS]>,
}

impl Default for Distribution {
    fn default() -> Self {
        Distribution {
            count: 0,
            min: i64::MAX,
            max: i64::MIN,
            sum: 0,
            histogram: Box::new([0; BUCKETS]),
        }
    }
}

impl Distribution {
    pub(crate) fn record(&mut self, ns: i64) {
        self.count += 1;
        self.min = self.min.min(ns);
        self.max = self.max.max(ns);
        self.sum += i128::from(ns);
        let b = bucket_of(ns.max(0) as u64);
        self.histogram[b] = self.histogram[b].saturating_add(1);
    }

    /// The summary, or `None` before the first sample.
    fn summary(&self) -> Option<TimeStats> {
        if self.count == 0 {
            return None;
        }
        // The rank of the 99th percentile: the smallest value that at least
        // 99 % of the samples do not exceed.
        let rank = self.count - self.count / 100;
        let mut seen = 0u64;
        let mut p99 = self.max;
        for (b, &n) in self.histogram.iter().enumerate() {
            seen += u64::from(n);
            if seen >= rank {
                p99 = i64::try_from(bucket_top(b)).unwrap_or(i64::MAX);
                break;
            }
        }
        Some(TimeStats {
            min_ns: self.min,
            mean_ns: (self.sum / i128::from(self.count)) as i64,
            max_ns: self.max,
            p99_ns: p99.clamp(self.min, self.max),
        })
    }
}

impl Distribution {
    /// The samples as a cumulative histogram over [`histogram_bounds`].
    fn histogram(&self) -> Histogram {
        let bounds = histogram_bounds();
        let mut buckets = Vec::with_capacity(bounds.len());
        let mut seen = 0u64;
        let mut b = 0usize;
        for bound in bounds {
            let last = bucket_of(bound as u64);
            while b <= last {
                seen += u64::from(self.histogram[b]);
                b += 1;
            }
            buckets.push((bound, seen));
        }
        Histogram {
            count: self.count,
            sum_ns: self.sum,
            buckets,
        }
    }
}

/// The upper bounds of [`Histogram::buckets`], in nanoseconds: for each of
/// 1, 2 and 5 × 10^k ns from 1 µs to 10 s, the top of the statistics'
/// own bucket holding it (at most 1/16 above it), so that every count is
/// exact: the samples at most that bound.
pub fn histogram_bounds() -> Vec<i64> {
    let mut out: Vec<i64> = Vec::new();
    let mut decade = 1_000i64;
    while decade <= 10_000_000_000 {
        for m in [1, 2, 5] {
            let v = decade * m;
            if v > 10_000_000_000 {
                break;
            }
            let top = i64::try_from(bucket_top(bucket_of(v as u64))).unwrap_or(i64::MAX);
            if out.last() != Some(&top) {
                out.push(top);
            }
        }
        decade *= 10;
    }
    out
}

/// A cumulative histogram of durations, as monitoring systems read them
/// (Prometheus' `_bucket`, `_sum`, `_count`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Histogram {
    /// How many samples.
    pub count: u64,
    /// Their sum in nanoseconds.
    pub sum_ns: i128,
    /// Increasing upper bounds in nanoseconds ([`histogram_bounds`]), each
    /// with the number of samples at most that bound (negative samples
    /// count as 0); samples above the last bound are in `count` only.
    pub buckets: Vec<(i64, u64)>,
}

/// The histograms of one task (see [`TaskStatsHandle::histograms`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TaskHistograms {
    /// The task's name.
    pub name: String,
    /// How long its programs ran per activation.
    pub execution: Histogram,
    /// How late each activation started after its deadline (no samples
    /// in virtual time).
    pub start_jitter: Histogram,
}

/// Minimum, mean, maximum and 99th percentile of a duration, in
/// nanoseconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct TimeStats {
    /// The smallest sample.
    pub min_ns: i64,
    /// The arithmetic mean (rounded toward zero).
    pub mean_ns: i64,
    /// The largest sample.
    pub max_ns: i64,
    /// The 99th percentile, to within 1/16 of its value (rounded up).
    pub p99_ns: i64,
}

/// What one task did during a run (see [`TaskStatsHandle::snapshot`]).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct TaskStats {
    /// The task's name (`(implicit)` for the task of a program run without a
    /// configuration).
    pub name: String,
    /// Its INTERVAL in nanoseconds (0 for a SINGLE task).
    pub interval_ns: i64,
    /// Its PRIORITY (0 runs first).
    pub priority: i64,
    /// How many times it ran.
    pub cycles: u64,
    /// Activations missed because the runtime was still busy when the
    /// task was due again (each counted and skipped, never queued).
    pub overruns: u64,
    /// How long its programs ran per activation (`None` before its first).
    pub execution: Option<TimeStats>,
    /// How late each activation started after its deadline (`None` in
    /// virtual time, which has no deadlines).
    pub start_jitter: Option<TimeStats>,
}

/// The live statistics of one task.
#[derive(Clone)]
pub(crate) struct TaskRecord {
    name: String,
    interval_ns: i64,
    priority: i64,
    cycles: u64,
    overruns: u64,
    execution: Distribution,
    start_jitter: Distribution,
}

impl TaskRecord {
    pub(crate) fn new(name: &str, interval_ns: i64, priority: i64) -> Self {
        TaskRecord {
            name: name.to_string(),
            interval_ns,
            priority,
            cycles: 0,
            overruns: 0,
            execution: Distribution::default(),
            start_jitter: Distribution::default(),
        }
    }

    /// One activation: how late it started (`None` without a deadline) and
    /// how long it ran.
    pub(crate) fn record(&mut self, jitter_ns: Option<i64>, execution_ns: i64) {
        self.cycles += 1;
        if let Some(j) = jitter_ns {
            self.start_jitter.record(j);
        }
        self.execution.record(execution_ns);
    }

    pub(crate) fn add_overruns(&mut self, n: u64) {
        self.overruns += n;
    }

    fn snapshot(&self) -> TaskStats {
        TaskStats {
            name: self.name.clone(),
            interval_ns: self.interval_ns,
            priority: self.priority,
            cycles: self.cycles,
            overruns: self.overruns,
            execution: self.execution.summary(),
            start_jitter: self.start_jitter.summary(),
        }
    }
}

/// A shared, thread-safe view of a run's per-task statistics: clone it,
/// hand it to another thread, read it at any time, during the run or
/// after it.
#[derive(Clone, Default)]
pub struct TaskStatsHandle {
    records: Arc<Mutex<Vec<TaskRecord>>>,
}

impl std::fmt::Debug for TaskStatsHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.snapshot()).finish()
    }
}

impl TaskStatsHandle {
    pub(crate) fn new(records: Vec<TaskRecord>) -> Self {
        TaskStatsHandle {
            records: Arc::new(Mutex::new(records)),
        }
    }

    /// The statistics so far, one entry per task, in the order of the
    /// configuration's task declarations.
    pub fn snapshot(&self) -> Vec<TaskStats> {
        self.with(|records| records.iter().map(TaskRecord::snapshot).collect())
    }

    /// The execution time and start jitter of each task as cumulative
    /// histograms, in the order of [`Self::snapshot`].
    pub fn histograms(&self) -> Vec<TaskHistograms> {
        self.with(|records| {
            records
                .iter()
                .map(|r| TaskHistograms {
                    name: r.name.clone(),
                    execution: r.execution.histogram(),
                    start_jitter: r.start_jitter.histogram(),
                })
                .collect()
        })
    }

    /// Runs `f` on the records under the lock (a panic elsewhere while
    /// holding it leaves plain counters, still worth reading).
    pub(crate) fn with<R>(&self, f: impl FnOnce(&mut [TaskRecord]) -> R) -> R {
        let mut guard = self.records.lock().unwrap_or_else(PoisonError::into_inner);
        f(&mut guard)
    }
}

/// The statistics as a table for a terminal, times in microseconds.
pub fn format_stats_table(stats: &[TaskStats]) -> String {
    use std::fmt::Write as _;
    let us = |ns: i64| format!("{:.1}", ns as f64 / 1000.0);
    let times = |t: &Option<TimeStats>| match t {
        Some(t) => [us(t.min_ns), us(t.mean_ns), us(t.max_ns), us(t.p99_ns)],
        None => ["-".into(), "-".into(), "-".into(), "-".into()],
    };
    let header = [
        "task",
        "interval",
        "prio",
        "cycles",
        "overruns",
        "exec_min",
        "exec_mean",
        "exec_max",
        "exec_p99",
        "jit_min",
        "jit_mean",
        "jit_max",
        "jit_p99",
    ];
    let mut rows: Vec<Vec<String>> = vec![header.iter().map(|h| h.to_string()).collect()];
    for s in stats {
        let mut row = vec![
            s.name.clone(),
            crate::value::literal::format_duration(s.interval_ns, "T#"),
            s.priority.to_string(),
            s.cycles.to_string(),
            s.overruns.to_string(),
        ];
        row.extend(times(&s.execution));
        row.extend(times(&s.start_jitter));
        rows.push(row);
    }
    let widths: Vec<usize> = (0..header.len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::from("task statistics (times in microseconds):\n");
    for row in &rows {
        let mut line = String::new();
        for (c, cell) in row.iter().enumerate() {
            let _ = write!(line, "{cell:<w$}  ", w = widths[c]);
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_value_falls_in_a_bucket_whose_top_is_at_least_it() {
        for v in (0..10_000u64).chain([u64::MAX, 1 << 40, (1 << 40) + 12345, 999_999_999]) {
            let b = bucket_of(v);
            assert!(b < BUCKETS);
            assert!(bucket_top(b) >= v, "{v}");
            // ... and within 1/16 of it.
            assert!(bucket_top(b) - v <= v / 16, "{v}: {}", bucket_top(b));
            if b > 0 {
                assert!(bucket_top(b - 1) < v, "{v}");
            }
        }
    }

    #[test]
    fn the_summary_gives_min_mean_max_and_p99() {
        let mut d = Distribution::default();
        assert_eq!(d.summary(), None);
        for v in 1..=1000 {
            d.record(v * 1000);
        }
        let s = d.summary().unwrap();
        assert_eq!((s.min_ns, s.max_ns, s.mean_ns), (1000, 1_000_000, 500_500));
        // The 990th smallest sample is 990 µs.
        assert!(
            (990_000..=990_000 + 990_000 / 16).contains(&s.p99_ns),
            "{s:?}"
        );
    }

    #[test]
    fn histogram_counts_are_the_samples_at_most_each_bound() {
        let mut d = Distribution::default();
        let samples = [
            -5i64,
            0,
            999,
            1_000,
            1_060,
            1_100,
            2_500,
            70_000,
            20_000_000_000,
        ];
        for v in samples {
            d.record(v);
        }
        let h = d.histogram();
        assert_eq!(h.count, samples.len() as u64);
        assert_eq!(
            h.sum_ns,
            samples.iter().map(|&v| i128::from(v)).sum::<i128>()
        );
        let mut last = 0;
        for &(bound, n) in &h.buckets {
            let expected = samples.iter().filter(|&&v| v.max(0) <= bound).count() as u64;
            assert_eq!(n, expected, "bound {bound}");
            assert!(n >= last);
            last = n;
        }
        // The bounds sit within 1/16 above 1, 2, 5 x 10^k ns.
        let bounds = histogram_bounds();
        assert_eq!(bounds.len(), 22);
        assert!(
            (1_000..=1_000 + 1_000 / 16).contains(&bounds[0]),
            "{bounds:?}"
        );
        assert!(bounds.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn a_single_sample_is_its_own_percentile() {
        let mut d = Distribution::default();
        d.record(12_345);
        let s = d.summary().unwrap();
        assert_eq!(
            (s.min_ns, s.mean_ns, s.max_ns, s.p99_ns),
            (12_345, 12_345, 12_345, 12_345)
        );
    }

    #[test]
    fn records_serialise_as_json() {
        let handle = TaskStatsHandle::new(vec![TaskRecord::new("fast", 2_000_000, 0)]);
        handle.with(|r| {
            r[0].record(Some(1_500), 20_000);
            r[0].add_overruns(2);
        });
        let json = serde_json::to_value(handle.snapshot()).unwrap();
        assert_eq!(json[0]["name"], "fast");
        assert_eq!(json[0]["cycles"], 1);
        assert_eq!(json[0]["overruns"], 2);
        assert_eq!(json[0]["execution"]["max_ns"], 20_000);
        assert_eq!(json[0]["start_jitter"]["p99_ns"], 1_500);
        let table = format_stats_table(&handle.snapshot());
        assert!(table.contains("fast"), "{table}");
        assert!(table.contains("T#2ms"), "{table}");
    }
}
