//! What the web monitor's threads share with the scan: the catalogue of
//! variables and charts (fixed at start), the last published snapshot,
//! the queue of commands for the scan, and the counters.

use plcrun::{TaskStatsHandle, Value, VarInfo};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, SyncSender};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::SystemTime;

/// One SFC chart instance and its drawing.
#[derive(Debug)]
pub(super) struct Chart {
    /// The instance owning it (`Chariot`, `Main.seq`).
    pub(super) path: String,
    /// The POU whose body it is.
    pub(super) pou: String,
    /// Its SVG, as `plcrun draw` makes it (no step marked).
    pub(super) svg: String,
}

/// Why the PLC is stopped, as the monitor shows it.
#[derive(Debug, Clone)]
pub(super) struct FaultView {
    /// The fault's stable code (`R001`...).
    pub(super) code: String,
    /// The whole message, location included.
    pub(super) message: String,
    /// The cycle it happened in.
    pub(super) cycle: u64,
}

/// The values of one completed cycle, as published to the monitor.
#[derive(Debug)]
pub(super) struct Snapshot {
    /// Publication number, from 1 (0: nothing published yet).
    pub(super) seq: u64,
    /// The PLC's cycle counter.
    pub(super) cycle: u64,
    /// The PLC's clock in nanoseconds.
    pub(super) time_ns: i64,
    /// When it was taken.
    pub(super) at: SystemTime,
    /// One value per catalogue variable.
    pub(super) values: Vec<Value>,
    /// Whether each catalogue variable is forced.
    pub(super) forced: Vec<bool>,
    /// The active steps of each catalogue chart.
    pub(super) active: Vec<Vec<String>>,
    /// The fault that stopped the PLC, if it is stopped.
    pub(super) fault: Option<FaultView>,
}

impl Snapshot {
    /// The snapshot before the first publication.
    pub(super) fn empty() -> Snapshot {
        Snapshot {
            seq: 0,
            cycle: 0,
            time_ns: 0,
            at: SystemTime::UNIX_EPOCH,
            values: Vec::new(),
            forced: Vec::new(),
            active: Vec::new(),
            fault: None,
        }
    }
}

/// A request the scan carries out between two cycles.
#[derive(Debug)]
pub(super) enum Command {
    /// A soft write of an IEC literal (a force wins).
    Write { path: String, literal: String },
    /// Forces a variable to an IEC literal.
    Force { path: String, literal: String },
    /// Removes a force.
    Unforce { path: String },
    /// Leaves the faulted state: `warm` keeps RETAIN values.
    Reset { warm: bool },
}

/// What the scan answers to a [`Command`]: a sentence, or an HTTP status
/// and why.
pub(super) type Outcome = Result<String, (u16, String)>;

/// A command with the channel its outcome goes back on.
pub(super) type Envelope = (Command, SyncSender<Outcome>);

/// Counters of the monitor, for `/metrics`.
#[derive(Debug, Default)]
pub(super) struct Counters {
    /// HTTP requests answered.
    pub(super) requests: AtomicU64,
    /// Event streams open now.
    pub(super) streams: AtomicU64,
    /// Commands carried out by the scan.
    pub(super) commands: AtomicU64,
    /// Writes refused for want of the token.
    pub(super) refused: AtomicU64,
    /// Snapshots published.
    pub(super) publishes: AtomicU64,
    /// Publications put off because a reader held the slot.
    pub(super) publishes_deferred: AtomicU64,
}

/// Adds one to a counter.
pub(super) fn bump(c: &AtomicU64) {
    c.fetch_add(1, Ordering::Relaxed);
}

/// Everything the monitor's threads share.
pub(super) struct Shared {
    /// Every variable, in [`plcrun::Plc::variables`] order.
    pub(super) variables: Vec<VarInfo>,
    /// Every chart instance.
    pub(super) charts: Vec<Chart>,
    /// The last snapshot.
    pub(super) snapshot: Mutex<Arc<Snapshot>>,
    /// Where commands for the scan go (bounded: a full queue is a 503).
    pub(super) commands: SyncSender<Envelope>,
    /// The run's task statistics, once the runner exists.
    pub(super) stats: OnceLock<TaskStatsHandle>,
    /// The token writes need.
    pub(super) token: String,
    /// The monitor's counters.
    pub(super) counters: Counters,
    /// Other servers' counters as metric lines (Modbus, OPC UA).
    pub(super) extra_metrics: Mutex<Vec<super::metrics::Source>>,
    /// Set when the run ends: streams close.
    pub(super) closing: std::sync::atomic::AtomicBool,
}

impl Shared {
    /// The current snapshot (a reference count taken under a lock the
    /// scan only ever tries).
    pub(super) fn snapshot(&self) -> Arc<Snapshot> {
        Arc::clone(&self.snapshot.lock().unwrap_or_else(PoisonError::into_inner))
    }

    /// The catalogue index of `path` (case-insensitive).
    pub(super) fn find(&self, path: &str) -> Option<usize> {
        self.variables
            .iter()
            .position(|v| v.path.eq_ignore_ascii_case(path))
    }

    /// Whether the run is ending.
    pub(super) fn is_closing(&self) -> bool {
        self.closing.load(Ordering::Acquire)
    }
}

/// The scan's end of the command queue.
pub(super) type CommandQueue = Receiver<Envelope>;
