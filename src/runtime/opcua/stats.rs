//! Counters of an OPC UA server, updated by the scan side and the server's
//! tasks and read at any time.

use std::sync::atomic::{AtomicU64, Ordering};

/// What an OPC UA server has done so far (see
/// [`crate::OpcUaServer::stats`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct OpcUaStats {
    /// Cycles whose values were published to the server.
    pub publishes: u64,
    /// Publishes put off to the next cycle because the server was still
    /// reading the frame they would have filled.
    pub publishes_deferred: u64,
    /// Published frames the server took into its address space (fewer
    /// than `publishes` when cycles are faster than the server).
    pub frames_served: u64,
    /// Values that changed between two frames the server took in.
    pub values_changed: u64,
    /// Client writes accepted and queued for the scan (a whole-array
    /// write counts once).
    pub writes_queued: u64,
    /// Client writes refused with BadResourceUnavailable because the
    /// queue was full.
    pub writes_refused_busy: u64,
    /// Queued writes applied between two cycles.
    pub writes_applied: u64,
    /// Client sessions open now.
    pub sessions: u64,
    /// Client sessions created since the server started.
    pub sessions_total: u64,
}

/// The live counters behind [`OpcUaStats`].
#[derive(Debug, Default)]
pub(crate) struct Counters {
    pub(crate) publishes: AtomicU64,
    pub(crate) publishes_deferred: AtomicU64,
    pub(crate) frames_served: AtomicU64,
    pub(crate) values_changed: AtomicU64,
    pub(crate) writes_queued: AtomicU64,
    pub(crate) writes_refused_busy: AtomicU64,
    pub(crate) writes_applied: AtomicU64,
}

/// Adds `n` to a counter.
pub(crate) fn add(counter: &AtomicU64, n: u64) {
    counter.fetch_add(n, Ordering::Relaxed);
}

impl Counters {
    /// The counters' values now.
    pub(crate) fn snapshot(&self) -> OpcUaStats {
        let get = |c: &AtomicU64| c.load(Ordering::Relaxed);
        OpcUaStats {
            publishes: get(&self.publishes),
            publishes_deferred: get(&self.publishes_deferred),
            frames_served: get(&self.frames_served),
            values_changed: get(&self.values_changed),
            writes_queued: get(&self.writes_queued),
            writes_refused_busy: get(&self.writes_refused_busy),
            writes_applied: get(&self.writes_applied),
            sessions: 0,
            sessions_total: 0,
        }
    }
}
