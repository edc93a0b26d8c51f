//! Random stimulus over many seeds, on several threads.
//!
//! Every seed of the range is run (none is skipped once a difference is
//! found), so the outcome does not depend on the number of threads or on
//! their timing: it is the same on every machine.

use super::error::CompareError;
use super::run_pair::{Difference, Pair};
use super::stimulus_gen::RandomStimulus;
use crate::progress::Progress;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// What a run over seeds found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeedsOutcome {
    /// The seeds run.
    pub seeds: Range<u64>,
    /// The seeds whose plans made the programs differ, ascending.
    pub differing: Vec<u64>,
    /// The lowest differing seed and its first difference.
    pub first: Option<(u64, Difference)>,
    /// Cycles run (each cycle runs both programs once).
    pub cycles_run: u64,
}

/// Runs `cycles` random cycles for every seed in `seeds` on `jobs` threads
/// (at least 1); `make` builds one [`Pair`] per thread.
pub fn run_seeds<F>(
    make: F,
    settings: &RandomStimulus,
    seeds: Range<u64>,
    cycles: u64,
    jobs: usize,
) -> Result<SeedsOutcome, CompareError>
where
    F: Fn() -> Result<Pair, CompareError> + Sync,
{
    run_seeds_reporting(make, settings, seeds, cycles, jobs, &())
}

/// [`run_seeds`], reporting the seeds done to `progress` as they finish.
pub fn run_seeds_reporting<F>(
    make: F,
    settings: &RandomStimulus,
    seeds: Range<u64>,
    cycles: u64,
    jobs: usize,
    progress: &dyn Progress,
) -> Result<SeedsOutcome, CompareError>
where
    F: Fn() -> Result<Pair, CompareError> + Sync,
{
    settings.validate()?;
    let done = Done {
        count: AtomicU64::new(0),
        total: seeds.end.saturating_sub(seeds.start),
        progress,
    };
    done.progress.report(0, done.total, "seeds");
    let next = AtomicU64::new(seeds.start);
    let results: Mutex<Vec<(u64, Option<Difference>, u64)>> = Mutex::new(Vec::new());
    let failure: Mutex<Option<CompareError>> = Mutex::new(None);
    let jobs = jobs
        .max(1)
        .min(seeds.end.saturating_sub(seeds.start).max(1) as usize);
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| {
                if let Err(e) = worker(&make, settings, &seeds, cycles, &next, &results, &done) {
                    // The first error wins; the other workers stop at their next seed.
                    next.store(seeds.end, Ordering::Relaxed);
                    failure
                        .lock()
                        .unwrap_or_else(|p| p.into_inner())
                        .get_or_insert(e);
                }
            });
        }
    });
    if let Some(e) = failure.into_inner().unwrap_or_else(|p| p.into_inner()) {
        return Err(e);
    }
    let mut results = results.into_inner().unwrap_or_else(|p| p.into_inner());
    results.sort_by_key(|r| r.0);
    let cycles_run = results.iter().map(|r| r.2).sum();
    let differing: Vec<u64> = results
        .iter()
        .filter(|r| r.1.is_some())
        .map(|r| r.0)
        .collect();
    let first = results
        .into_iter()
        .find_map(|(seed, d, _)| d.map(|d| (seed, d)));
    Ok(SeedsOutcome {
        seeds,
        differing,
        first,
        cycles_run,
    })
}

type Results = Mutex<Vec<(u64, Option<Difference>, u64)>>;

/// The seeds finished so far, and who is told.
struct Done<'a> {
    count: AtomicU64,
    total: u64,
    progress: &'a dyn Progress,
}

/// One thread: takes the next seed until none is left.
fn worker<F>(
    make: &F,
    settings: &RandomStimulus,
    seeds: &Range<u64>,
    cycles: u64,
    next: &AtomicU64,
    results: &Results,
    done: &Done,
) -> Result<(), CompareError>
where
    F: Fn() -> Result<Pair, CompareError>,
{
    let mut pair = make()?;
    loop {
        let seed = next.fetch_add(1, Ordering::Relaxed);
        if seed >= seeds.end || seed < seeds.start {
            return Ok(());
        }
        let plan = pair.random_plan(settings, seed, cycles);
        let d = pair.run(&plan)?;
        let ran = d.as_ref().map_or(cycles, |d| d.cycle + 1);
        results
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push((seed, d, ran));
        let finished = done.count.fetch_add(1, Ordering::Relaxed) + 1;
        done.progress.report(finished, done.total, "seeds");
    }
}
