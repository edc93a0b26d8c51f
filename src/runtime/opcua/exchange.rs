//! The scan side of an OPC UA server: between two cycles, copy the served
//! values the cycle left into the frame the server is not reading, wake
//! the server, and apply the writes clients queued, so that the next cycle
//! sees them.
//!
//! Bounded and non-blocking: one slot copy per served value (a string's
//! text only when it changed), a `try_lock`, a wake-up, and at most the
//! queue's capacity of writes.

use super::model::Leaf;
use super::published::Frame;
use super::server::Shared;
use super::stats::add;
use crate::runtime::engine::Plc;
use crate::runtime::plc_value::Value;
use crate::runtime::session::Session;
use std::sync::Arc;
use std::sync::mpsc::Receiver;
use std::time::SystemTime;

/// One client write: values for leaves, applied together.
pub(crate) type ClientWrite = Vec<(usize, Value)>;

/// What one [`OpcUaExchange::exchange`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OpcUaExchangeReport {
    /// True when the cycle's values were published (false: the server
    /// still read the other frame; the next exchange publishes).
    pub published: bool,
    /// Client writes applied to the PLC.
    pub writes_applied: usize,
}

/// The scan side of a [`crate::OpcUaServer`]: call
/// [`exchange`](Self::exchange) between cycles (docs/opcua.md,
/// "Consistency with the scan").
pub struct OpcUaExchange {
    pub(crate) shared: Arc<Shared>,
    pub(crate) writes: Receiver<ClientWrite>,
    /// At most this many client writes per exchange.
    pub(crate) per_exchange: usize,
}

impl std::fmt::Debug for OpcUaExchange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OpcUaExchange")
            .field("values", &self.shared.model.leaves.len())
            .finish_non_exhaustive()
    }
}

impl OpcUaExchange {
    /// Between two cycles: publishes the served values of `plc` (the cycle
    /// just completed), then applies the writes clients queued since the
    /// last exchange, as [`Plc::set`] does (a forced variable keeps its
    /// forced value). Never blocks.
    pub fn exchange(&mut self, plc: &mut Plc) -> OpcUaExchangeReport {
        let shared = &self.shared;
        let published = shared
            .published
            .try_publish(|frame| capture(plc, &shared.model.leaves, frame));
        if published {
            add(&shared.counters.publishes, 1);
            shared.wake.notify_one();
        } else {
            add(&shared.counters.publishes_deferred, 1);
        }
        let mut applied = 0;
        while applied < self.per_exchange {
            let Ok(write) = self.writes.try_recv() else {
                break;
            };
            for (leaf, value) in &write {
                // Checked when queued; a refusal here (the PLC was
                // replaced by an online change) leaves the value as is.
                let _ = plc.set(&shared.model.leaves[*leaf].var, value);
            }
            applied += 1;
        }
        if applied > 0 {
            add(&shared.counters.writes_applied, applied as u64);
        }
        OpcUaExchangeReport {
            published,
            writes_applied: applied,
        }
    }

    /// The exchange as a [`crate::TaskRunner::set_between_ticks`] hook
    /// (call [`exchange`](Self::exchange) once before the run, so that
    /// clients read the initial values until the first tick ends).
    pub fn into_between_ticks(mut self) -> impl FnMut(&mut Session) + Send + 'static {
        move |session: &mut Session| {
            self.exchange(session.plc_mut());
        }
    }
}

/// Copies the served values of `plc` into `frame`.
pub(crate) fn capture(plc: &Plc, leaves: &[Leaf], frame: &mut Frame) {
    let mem = &plc.machine.mem;
    frame.cycle = plc.cycle();
    frame.at = SystemTime::now();
    for (i, leaf) in leaves.iter().enumerate() {
        let var = &leaf.var;
        let raw = match var.view {
            Some(view) => view.read(mem, var.addr),
            None => mem.get(var.addr as usize).copied().unwrap_or(0),
        };
        frame.raw[i] = raw;
        if matches!(leaf.kind, super::types::Kind::Str { .. }) {
            let text = plc
                .machine
                .strings
                .get(raw as usize)
                .map_or("", |s| s.text.as_str());
            if frame.text[i] != text {
                frame.text[i].clear();
                frame.text[i].push_str(text);
            }
        }
    }
}
