//! The Debug Adapter Protocol's framing: each message is a
//! `Content-Length: N` header block (other headers are allowed and
//! skipped), an empty line, and N bytes of JSON.

use std::io::{self, BufRead, Write};

/// Reads the next message; `None` at the end of the input.
pub(super) fn read_message(input: &mut impl BufRead) -> io::Result<Option<serde_json::Value>> {
    let mut length: Option<usize> = None;
    let mut line = String::new();
    loop {
        line.clear();
        if input.read_line(&mut line)? == 0 {
            return Ok(None);
        }
        let header = line.trim_end_matches(['\r', '\n']);
        if header.is_empty() {
            if length.is_some() {
                break;
            }
            // Blank lines between messages.
            continue;
        }
        if let Some((name, value)) = header.split_once(':')
            && name.trim().eq_ignore_ascii_case("Content-Length")
        {
            let n = value.trim().parse().map_err(|_| {
                io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!("bad Content-Length `{}`", value.trim()),
                )
            })?;
            length = Some(n);
        }
    }
    let mut body = vec![0u8; length.unwrap_or(0)];
    input.read_exact(&mut body)?;
    serde_json::from_slice(&body)
        .map(Some)
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

/// Writes one message.
pub(super) fn write_message(out: &mut impl Write, message: &serde_json::Value) -> io::Result<()> {
    let body = serde_json::to_vec(message).map_err(io::Error::other)?;
    write!(out, "Content-Length: {}\r\n\r\n", body.len())?;
    out.write_all(&body)?;
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_round_trips_and_extra_headers_are_skipped() {
        let mut buf = Vec::new();
        write_message(&mut buf, &serde_json::json!({"seq": 1, "type": "request"})).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let with_header = text.replacen("\r\n\r\n", "\r\nContent-Type: x\r\n\r\n", 1);
        let mut input = io::BufReader::new(with_header.as_bytes());
        let m = read_message(&mut input).unwrap().unwrap();
        assert_eq!(m["seq"], 1);
        assert!(read_message(&mut input).unwrap().is_none());
    }
}
