//! Counters of a Modbus server, updated by its threads and read at any
//! time.

use std::sync::atomic::{AtomicU64, Ordering};

/// What a Modbus server has done so far (see [`crate::ModbusServer::stats`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct ModbusStats {
    /// Connections accepted and served.
    pub connections_accepted: u64,
    /// Connections closed at once because `max_clients` were connected.
    pub connections_refused: u64,
    /// Connections closed because the client sent no complete request
    /// for the idle timeout (idle or half-open).
    pub connections_timed_out: u64,
    /// Connections closed because of a frame that cannot be read (protocol
    /// identifier not 0, length field out of range).
    pub connections_dropped_malformed: u64,
    /// Connections open now.
    pub connections_open: u64,
    /// Requests answered (normal or exception responses).
    pub requests: u64,
    /// Exception responses among them.
    pub exceptions: u64,
    /// Client writes queued for the scan.
    pub writes_queued: u64,
    /// Client writes refused with exception 06 (server busy) because the
    /// queue was full.
    pub writes_refused_busy: u64,
    /// Client writes applied to the image between two cycles.
    pub writes_applied: u64,
    /// Cycles whose image was published to the clients.
    pub publishes: u64,
    /// Publishes put off to the next cycle because a client was still
    /// reading the buffer they would have filled.
    pub publishes_deferred: u64,
}

/// The live counters behind [`ModbusStats`].
#[derive(Debug, Default)]
pub(crate) struct Counters {
    pub(crate) connections_accepted: AtomicU64,
    pub(crate) connections_refused: AtomicU64,
    pub(crate) connections_timed_out: AtomicU64,
    pub(crate) connections_dropped_malformed: AtomicU64,
    pub(crate) connections_open: AtomicU64,
    pub(crate) requests: AtomicU64,
    pub(crate) exceptions: AtomicU64,
    pub(crate) writes_queued: AtomicU64,
    pub(crate) writes_refused_busy: AtomicU64,
    pub(crate) writes_applied: AtomicU64,
    pub(crate) publishes: AtomicU64,
    pub(crate) publishes_deferred: AtomicU64,
}

/// Adds one to a counter.
pub(crate) fn bump(counter: &AtomicU64) {
    counter.fetch_add(1, Ordering::Relaxed);
}

impl Counters {
    /// The counters now.
    pub(crate) fn snapshot(&self) -> ModbusStats {
        let get = |c: &AtomicU64| c.load(Ordering::Relaxed);
        ModbusStats {
            connections_accepted: get(&self.connections_accepted),
            connections_refused: get(&self.connections_refused),
            connections_timed_out: get(&self.connections_timed_out),
            connections_dropped_malformed: get(&self.connections_dropped_malformed),
            connections_open: get(&self.connections_open),
            requests: get(&self.requests),
            exceptions: get(&self.exceptions),
            writes_queued: get(&self.writes_queued),
            writes_refused_busy: get(&self.writes_refused_busy),
            writes_applied: get(&self.writes_applied),
            publishes: get(&self.publishes),
            publishes_deferred: get(&self.publishes_deferred),
        }
    }
}
