//! The `Content-Length` framing that the Language Server Protocol and the
//! Debug Adapter Protocol share, read by both scripted clients.

use serde_json::Value;
use std::io::BufRead;

/// Reads one framed message; `None` at the end of the stream. Blank lines
/// before a header are skipped.
pub fn read_message(reader: &mut impl BufRead) -> Option<Value> {
    let mut length = None;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim_end();
        if line.is_empty() {
            if length.is_some() {
                break;
            }
            continue;
        }
        if let Some(n) = line.strip_prefix("Content-Length:") {
            length = n.trim().parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    reader.read_exact(&mut body).ok()?;
    serde_json::from_slice(&body).ok()
}
