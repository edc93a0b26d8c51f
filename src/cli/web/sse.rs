//! `GET /api/events`: server-sent events, on the connection's thread. Each
//! stream looks at the snapshot [`POLL`] times a second at most and sends
//! an event when a new one was published: the first event carries every
//! value, the next ones only the values that changed since the event
//! before, with the charts' active steps, the task statistics and the
//! faulted state each time.

use super::api::{Reply, fault_json, plotted, task_stats};
use super::http::write_reply;
use super::state::{Shared, Snapshot, bump};
use serde_json::{Value as Json, json};
use std::io::Write;
use std::net::TcpStream;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// How often a stream looks for a new snapshot.
const POLL: Duration = Duration::from_millis(250);

/// How long a quiet stream waits before a comment keeps it open.
const KEEP_ALIVE: Duration = Duration::from_secs(15);

/// The most streams open at once.
const MAX_STREAMS: u64 = 32;

/// Keeps `conn` as an event stream, on the calling thread (the
/// connection's own), or refuses it (503) when [`MAX_STREAMS`] are open.
pub(super) fn open(mut conn: TcpStream, shared: &Shared) {
    bump(&shared.counters.requests);
    let open = shared.counters.streams.fetch_add(1, Ordering::AcqRel);
    if open >= MAX_STREAMS || shared.is_closing() {
        shared.counters.streams.fetch_sub(1, Ordering::AcqRel);
        let reply = Reply::error(503, format!("{MAX_STREAMS} event streams are open already"));
        let _ = write_reply(&mut conn, &reply, false);
        return;
    }
    let _ = stream(&mut conn, shared);
    shared.counters.streams.fetch_sub(1, Ordering::AcqRel);
}

/// Writes the stream until the client leaves or the run ends.
fn stream(out: &mut TcpStream, shared: &Shared) -> std::io::Result<()> {
    out.write_all(
        b"HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-cache\r\n\
          Connection: close\r\nX-Accel-Buffering: no\r\n\r\nretry: 2000\n\n",
    )?;
    out.flush()?;
    let mut sent: Option<Vec<(String, bool)>> = None;
    let mut seq = 0u64;
    let mut quiet_since = Instant::now();
    while !shared.is_closing() {
        let snapshot = shared.snapshot();
        if snapshot.seq != seq && snapshot.seq > 0 {
            seq = snapshot.seq;
            let event = event(shared, &snapshot, &mut sent);
            write!(out, "data: {event}\n\n")?;
            out.flush()?;
            quiet_since = Instant::now();
        } else if quiet_since.elapsed() >= KEEP_ALIVE {
            out.write_all(b": keep-alive\n\n")?;
            out.flush()?;
            quiet_since = Instant::now();
        }
        drop(snapshot);
        std::thread::sleep(POLL);
    }
    Ok(())
}

/// The event for `snapshot`, with the values that differ from `sent`
/// (all of them the first time), and `sent` brought up to date.
fn event(shared: &Shared, snapshot: &Snapshot, sent: &mut Option<Vec<(String, bool)>>) -> Json {
    let first = sent.is_none();
    let last = sent.get_or_insert_with(Vec::new);
    last.resize(snapshot.values.len(), (String::new(), false));
    let mut changes = Vec::new();
    for (i, value) in snapshot.values.iter().enumerate() {
        let literal = value.to_literal();
        let forced = snapshot.forced.get(i).copied().unwrap_or(false);
        if first || last[i].0 != literal || last[i].1 != forced {
            changes.push(json!([i, literal, plotted(value), forced]));
            last[i] = (literal, forced);
        }
    }
    json!({
        "seq": snapshot.seq,
        "cycle": snapshot.cycle,
        "time_ns": snapshot.time_ns,
        "full": first,
        "changes": changes,
        "charts": snapshot.active,
        "fault": fault_json(snapshot),
        "tasks": task_stats(shared),
    })
}
