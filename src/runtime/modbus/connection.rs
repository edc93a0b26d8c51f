//! One client connection: read a frame, answer it, until the client
//! leaves, stays silent for the idle timeout, sends a frame whose header
//! cannot be trusted, or the server stops.
//!
//! Memory per connection is two fixed buffers of one frame each; a frame's
//! header is checked before its body is read (protocol identifier 0,
//! length 2–254), so a wrong length can neither make the server wait for
//! bytes that never come past the idle timeout nor read past one frame.

use super::exchange::ClientWrite;
use super::request::{HEADER, MAX_FRAME, respond};
use super::server::Shared;
use super::stats::bump;
use std::io::{ErrorKind, Read, Write};
use std::net::TcpStream;
use std::sync::atomic::Ordering;
use std::sync::mpsc::SyncSender;
use std::time::{Duration, Instant};

/// How often a blocked read looks at the stop flag and the idle deadline.
const POLL: Duration = Duration::from_millis(100);
/// The largest MBAP length field: unit identifier and a 253-byte PDU.
const MAX_LENGTH: usize = MAX_FRAME - HEADER + 1;

/// Why a connection ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Ended {
    /// The client closed it, or the socket failed.
    Closed,
    /// No complete request within the idle timeout.
    Idle,
    /// A header that cannot be a Modbus TCP frame.
    Malformed,
    /// The server is stopping.
    Stopped,
}

/// Serves `stream` until it ends; counts how it ended.
pub(crate) fn serve(mut stream: TcpStream, shared: &Shared, writes: &SyncSender<ClientWrite>) {
    let idle = shared.config.idle_timeout;
    let ended = (|| {
        stream.set_read_timeout(Some(POLL.min(idle))).ok()?;
        // A client that does not read its responses cannot hold the
        // thread longer than the idle timeout either.
        stream.set_write_timeout(Some(idle)).ok()?;
        stream.set_nodelay(true).ok()?;
        Some(serve_frames(&mut stream, shared, writes))
    })()
    .unwrap_or(Ended::Closed);
    match ended {
        Ended::Idle => bump(&shared.counters.connections_timed_out),
        Ended::Malformed => bump(&shared.counters.connections_dropped_malformed),
        Ended::Closed | Ended::Stopped => {}
    }
    let _ = stream.shutdown(std::net::Shutdown::Both);
}

pub(crate) fn serve_frames<S: Read + Write>(
    stream: &mut S,
    shared: &Shared,
    writes: &SyncSender<ClientWrite>,
) -> Ended {
    let mut frame = [0u8; MAX_FRAME];
    let mut response = Vec::with_capacity(MAX_FRAME);
    loop {
        let deadline = Instant::now() + shared.config.idle_timeout;
        // Transaction, protocol, length: enough to judge the frame.
        if let Err(ended) = read_full(stream, &mut frame[..HEADER - 1], deadline, shared) {
            return ended;
        }
        let protocol = u16::from_be_bytes([frame[2], frame[3]]);
        let length = usize::from(u16::from_be_bytes([frame[4], frame[5]]));
        if protocol != 0 || !(2..=MAX_LENGTH).contains(&length) {
            return Ended::Malformed;
        }
        let size = HEADER - 1 + length;
        if let Err(ended) = read_full(stream, &mut frame[HEADER - 1..size], deadline, shared) {
            return ended;
        }
        respond(&frame[..size], shared, writes, &mut response);
        if stream.write_all(&response).is_err() {
            return Ended::Closed;
        }
    }
}

/// Reads exactly `buf.len()` bytes before `deadline`.
fn read_full<S: Read>(
    stream: &mut S,
    buf: &mut [u8],
    deadline: Instant,
    shared: &Shared,
) -> Result<(), Ended> {
    let mut got = 0;
    while got < buf.len() {
        if shared.stop.load(Ordering::Relaxed) {
            return Err(Ended::Stopped);
        }
        // Checked even while bytes trickle in: a frame must be complete
        // within the timeout.
        if Instant::now() >= deadline {
            return Err(Ended::Idle);
        }
        match stream.read(&mut buf[got..]) {
            Ok(0) => return Err(Ended::Closed),
            Ok(n) => got += n,
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {}
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(_) => return Err(Ended::Closed),
        }
    }
    Ok(())
}
