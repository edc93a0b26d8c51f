//! The server's side of the hand-over: woken after each publish, it takes
//! the current frame (a copy under a lock the scan never waits on), finds
//! the Variables whose values changed since the frame it took before, and
//! sets them in the address space, which notifies the monitored items.
//! Reads and subscriptions thus see the last completed cycle the server
//! took in; when cycles come faster than it, it skips to the newest.

use super::node_manager::{PlcNodes, node_value};
use super::published::Frame;
use super::server::Shared;
use super::stats::add;
use async_opcua::server::SubscriptionCache;
use async_opcua::server::node_manager::memory::InMemoryNodeManager;
use async_opcua::types::{DataValue, DateTime, NodeId, StatusCode};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{SystemTime, UNIX_EPOCH};
use tokio_util::sync::CancellationToken;

/// Runs until `stop` is cancelled.
pub(crate) async fn pump(
    shared: Arc<Shared>,
    manager: Arc<InMemoryNodeManager<PlcNodes>>,
    subscriptions: Arc<SubscriptionCache>,
    stop: CancellationToken,
) {
    let ns = shared.namespace.load(Ordering::Acquire);
    let model = &shared.model;
    // The Variables, their NodeIds and leaves.
    let variables: Vec<(usize, NodeId)> = model
        .nodes
        .iter()
        .enumerate()
        .filter(|(i, _)| model.leaves_of(*i).is_some())
        .map(|(i, n)| (i, NodeId::new(ns, n.id.clone())))
        .collect();
    let mut last = shared.published.read(Frame::clone);
    let mut now = last.clone();
    let mut changed_leaf = vec![false; model.leaves.len()];
    loop {
        tokio::select! {
            () = shared.wake.notified() => {}
            () = stop.cancelled() => return,
        }
        shared.published.read(|f| copy_frame(f, &mut now));
        let mut any = false;
        for (l, flag) in changed_leaf.iter_mut().enumerate() {
            *flag = now.raw[l] != last.raw[l] || now.text[l] != last.text[l];
            any |= *flag;
        }
        add(&shared.counters.frames_served, 1);
        if !any {
            continue;
        }
        let at = date_time(now.at);
        let server_time = DateTime::now();
        let mut updates: Vec<(&NodeId, DataValue)> = Vec::new();
        for (node, id) in &variables {
            let leaves = model.leaves_of(*node).unwrap_or(&[]);
            if !leaves.iter().any(|&l| changed_leaf[l]) {
                continue;
            }
            let value = node_value(&shared, *node, &now.raw, &now.text);
            updates.push((
                id,
                DataValue {
                    value: Some(value),
                    status: Some(StatusCode::Good),
                    source_timestamp: Some(at),
                    server_timestamp: Some(server_time),
                    ..DataValue::null()
                },
            ));
        }
        add(&shared.counters.values_changed, updates.len() as u64);
        let _ = manager.set_values(
            &subscriptions,
            updates.into_iter().map(|(id, dv)| (id, None, dv)),
        );
        std::mem::swap(&mut last, &mut now);
    }
}

/// Copies `from` into `to`, reusing `to`'s allocations.
fn copy_frame(from: &Frame, to: &mut Frame) {
    to.cycle = from.cycle;
    to.at = from.at;
    to.raw.copy_from_slice(&from.raw);
    for (t, f) in to.text.iter_mut().zip(&from.text) {
        if t != f {
            t.clone_from(f);
        }
    }
}

/// The OPC UA DateTime of a system time.
fn date_time(t: SystemTime) -> DateTime {
    let ns = t
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| i64::try_from(d.as_nanos()).unwrap_or(i64::MAX));
    super::types::date_time(ns)
}
