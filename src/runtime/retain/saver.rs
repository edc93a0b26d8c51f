//! Saving retained values in the background: the cycle's thread only
//! copies the values into a reserved buffer ([`RetainSaver::offer`]); a
//! writer thread formats and writes the file. A save still waiting when a
//! newer one is offered is replaced by it, so the writer never falls
//! behind and the cycle never waits for the disk.

use super::RetainError;
use super::file::write_atomically;
use super::format::encode;
use super::layout::{RetainLayout, Snapshot};
use crate::runtime::engine::Plc;
use std::path::Path;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// What the cycle's thread and the writer share.
#[derive(Default)]
struct State {
    /// The newest snapshot not yet being written.
    pending: Option<Snapshot>,
    /// Buffers to reuse (at most three exist: one written, one pending,
    /// one being filled).
    spare: Vec<Snapshot>,
    /// The writer is writing a snapshot.
    writing: bool,
    /// The writer waits for work (only then does an offer wake it: a
    /// wake-up is a system call the cycle need not pay otherwise).
    idle: bool,
    /// Time the writer spent formatting and writing files.
    busy: Duration,
    /// Ends the writer once nothing is pending.
    stop: bool,
    /// Files written.
    saves: u64,
    /// Snapshots replaced before they were written.
    replaced: u64,
    /// The first failure not yet taken.
    error: Option<RetainError>,
}

struct Shared {
    state: Mutex<State>,
    /// Signals the writer: a snapshot is pending, or stop.
    work: Condvar,
    /// Signals waiters: the writer finished a snapshot.
    done: Condvar,
}

impl Shared {
    /// The state; a panic elsewhere while holding the lock cannot leave it
    /// inconsistent (every update is a single assignment), so poisoning is
    /// ignored.
    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Saves a PLC's retained values to a file from a background thread.
///
/// ```
/// use plcrun::{Options, Plc, RetainSaver};
/// let src = "PROGRAM P VAR RETAIN n : DINT; END_VAR n := n + 1; END_PROGRAM";
/// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
/// let path = std::env::temp_dir().join(format!("saver-doc-{}.json", std::process::id()));
/// let saver = RetainSaver::new(&plc, &path)?;
/// for _ in 0..100 {
///     plc.run_cycle()?;
///     saver.offer(&plc)?; // a copy of the values; the file is written off this thread
/// }
/// saver.finish()?; // waits for the last save
/// let text = std::fs::read_to_string(&path)?;
/// assert!(text.contains(r#""name":"P.n","type":"DINT","value":"100""#));
/// # std::fs::remove_file(&path)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct RetainSaver {
    layout: Arc<RetainLayout>,
    shared: Arc<Shared>,
    writer: Option<JoinHandle<()>>,
    owner: u64,
}

impl RetainSaver {
    /// A saver of `plc`'s retained values to `path`, with its writer
    /// thread started. Nothing is written before the first
    /// [`Self::offer`].
    pub fn new(plc: &Plc, path: impl AsRef<Path>) -> Result<RetainSaver, RetainError> {
        let path = path.as_ref().to_path_buf();
        let layout = Arc::new(RetainLayout::new(&plc.image));
        let shared = Arc::new(Shared {
            state: Mutex::new(State::default()),
            work: Condvar::new(),
            done: Condvar::new(),
        });
        let writer = {
            let (layout, shared, target) = (layout.clone(), shared.clone(), path.clone());
            std::thread::Builder::new()
                .name("plcrun-retain".into())
                .spawn(move || write_loop(&layout, &shared, &target))
                .map_err(|error| RetainError::Write { path, error })?
        };
        Ok(RetainSaver {
            layout,
            shared,
            writer: Some(writer),
            owner: plc.id,
        })
    }

    /// Takes a snapshot of `plc`'s retained values now (call it between
    /// cycles) and hands it to the writer; returns without waiting for the
    /// disk. A snapshot still waiting to be written is replaced. After the
    /// first few calls it allocates nothing.
    pub fn offer(&self, plc: &Plc) -> Result<(), RetainError> {
        if plc.id != self.owner {
            return Err(RetainError::ForeignPlc);
        }
        let reuse = {
            let mut s = self.shared.lock();
            match s.pending.take() {
                Some(old) => {
                    s.replaced += 1;
                    Some(old)
                }
                None => s.spare.pop(),
            }
        };
        let mut snap = reuse.unwrap_or_else(|| self.layout.buffer());
        self.layout
            .take(&plc.machine, plc.cycle(), plc.time(), &mut snap);
        let mut s = self.shared.lock();
        if let Some(old) = s.pending.replace(snap) {
            s.spare.push(old);
        }
        let wake = s.idle;
        drop(s);
        if wake {
            self.shared.work.notify_one();
        }
        Ok(())
    }

    /// How many files were written so far.
    pub fn saves(&self) -> u64 {
        self.shared.lock().saves
    }

    /// How many snapshots were replaced by a newer one before the writer
    /// got to them.
    pub fn replaced(&self) -> u64 {
        self.shared.lock().replaced
    }

    /// The time the writer thread spent formatting and writing files so
    /// far (divided by [`Self::saves`]: the cost of one save off the
    /// cycle's path).
    pub fn writer_time(&self) -> Duration {
        self.shared.lock().busy
    }

    /// The first write failure since the last call, if any (the writer
    /// goes on trying with the next snapshot).
    pub fn take_error(&self) -> Option<RetainError> {
        self.shared.lock().error.take()
    }

    /// Waits until every offered snapshot is written.
    pub fn flush(&self) {
        let mut s = self.shared.lock();
        while s.pending.is_some() || s.writing {
            s = self.shared.done.wait(s).unwrap_or_else(|e| e.into_inner());
        }
    }

    /// Writes what is pending, stops the writer and returns the number of
    /// files written, or the first failure not yet taken.
    pub fn finish(mut self) -> Result<u64, RetainError> {
        self.stop();
        let mut s = self.shared.lock();
        match s.error.take() {
            Some(e) => Err(e),
            None => Ok(s.saves),
        }
    }

    fn stop(&mut self) {
        self.shared.lock().stop = true;
        self.shared.work.notify_all();
        if let Some(writer) = self.writer.take() {
            // The writer does not panic; if it did, the error is lost with it.
            let _ = writer.join();
        }
    }
}

impl Drop for RetainSaver {
    /// Writes what is pending before the saver goes away.
    fn drop(&mut self) {
        self.stop();
    }
}

/// The writer thread: writes the pending snapshot, again and again, until
/// stopped with nothing pending.
fn write_loop(layout: &RetainLayout, shared: &Shared, path: &Path) {
    loop {
        let snap = {
            let mut s = shared.lock();
            while s.pending.is_none() && !s.stop {
                s.idle = true;
                s = shared.work.wait(s).unwrap_or_else(|e| e.into_inner());
                s.idle = false;
            }
            match s.pending.take() {
                Some(snap) => {
                    s.writing = true;
                    snap
                }
                None => return,
            }
        };
        let started = Instant::now();
        let result = write_atomically(path, &encode(layout, &snap));
        let mut s = shared.lock();
        s.busy += started.elapsed();
        s.writing = false;
        s.spare.push(snap);
        match result {
            Ok(()) => s.saves += 1,
            Err(error) if s.error.is_none() => {
                s.error = Some(RetainError::Write {
                    path: path.to_path_buf(),
                    error,
                })
            }
            Err(_) => {}
        }
        drop(s);
        shared.done.notify_all();
    }
}
