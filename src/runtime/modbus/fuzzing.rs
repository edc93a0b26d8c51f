//! The request path of the Modbus server without a socket, for the fuzz
//! targets (fuzz/src/targets.rs): the bytes a client sends go through the
//! same frame reader and request handler as a TCP connection's.

use super::connection::serve_frames;
use super::server::{ModbusConfig, Shared};
use std::io::{Read, Write};
use std::sync::mpsc::sync_channel;

/// A connection whose client sends `input` and then closes its side.
struct Replay<'a> {
    input: &'a [u8],
    output: Vec<u8>,
}

impl Read for Replay<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        self.input.read(buf)
    }
}

impl Write for Replay<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.output.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Serves `input` as the byte stream of one client connection and returns
/// what the server answered, and how many writes it queued for the scan.
pub fn serve_bytes(input: &[u8]) -> (Vec<u8>, usize) {
    let shared = Shared::new(ModbusConfig::default());
    let (writes, queued) = sync_channel(shared.config.write_queue);
    let mut connection = Replay {
        input,
        output: Vec::new(),
    };
    serve_frames(&mut connection, &shared, &writes);
    drop(writes);
    (connection.output, queued.try_iter().count())
}
