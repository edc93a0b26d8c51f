//! HTTP/1.1 as the monitor speaks it: one request per connection
//! (`Connection: close`), a head of at most 16 KiB, a body of at most
//! 64 KiB given by `Content-Length`, answers with a length. Small enough
//! to own: the threaded crate first used here queued a new connection
//! behind its pool's busy threads, and event streams keep theirs busy for
//! good, so a stream opened in a burst could wait forever.

use super::api::Reply;
use std::io::{BufRead, Read, Write};

/// The largest request head read.
const MAX_HEAD: usize = 16 * 1024;

/// The largest request body read.
pub(super) const MAX_BODY: usize = 64 * 1024;

/// A request as read from the connection.
#[derive(Debug)]
pub(super) struct Request {
    /// `GET`, `POST`... (upper case).
    pub(super) method: String,
    /// The target as sent (`/api/variables?q=x`).
    pub(super) target: String,
    /// The headers, names in lower case.
    pub(super) headers: Vec<(String, String)>,
    /// The body.
    pub(super) body: Vec<u8>,
}

impl Request {
    /// The value of header `name` (lower case).
    pub(super) fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }
}

/// Reads one request; a malformed one is the answer to send back (`None`
/// when the client sent nothing and left).
pub(super) fn read_request<S: BufRead + Write>(conn: &mut S) -> Result<Request, Option<Reply>> {
    let mut head = Vec::new();
    loop {
        let before = head.len();
        let mut limited = Read::take(&mut *conn, (MAX_HEAD + 1 - before) as u64);
        let n = limited.read_until(b'\n', &mut head).map_err(|_| None)?;
        if n == 0 {
            return Err((before > 0).then(|| Reply::error(400, "the request ended early")));
        }
        if head.len() > MAX_HEAD {
            return Err(Some(Reply::error(431, "the request head is over 16 KiB")));
        }
        if head.ends_with(b"\r\n\r\n") || head.ends_with(b"\n\n") {
            break;
        }
    }
    let text = std::str::from_utf8(&head)
        .map_err(|_| Some(Reply::error(400, "the request head is not UTF-8")))?;
    let mut lines = text.lines();
    let bad = || Some(Reply::error(400, "not an HTTP/1 request line"));
    let mut words = lines.next().ok_or_else(bad)?.split(' ');
    let (Some(method), Some(target), Some(version), None) =
        (words.next(), words.next(), words.next(), words.next())
    else {
        return Err(bad());
    };
    if !version.starts_with("HTTP/1.") || !target.starts_with('/') || method.is_empty() {
        return Err(bad());
    }
    let mut headers = Vec::new();
    for line in lines.take_while(|l| !l.is_empty()) {
        let (name, value) = line
            .split_once(':')
            .ok_or_else(|| Some(Reply::error(400, format!("a header without `:`: {line:?}"))))?;
        headers.push((name.trim().to_ascii_lowercase(), value.trim().to_string()));
    }
    let mut request = Request {
        method: method.to_ascii_uppercase(),
        target: target.to_string(),
        headers,
        body: Vec::new(),
    };
    if request.header("transfer-encoding").is_some() {
        return Err(Some(Reply::error(
            411,
            "send the body with a Content-Length",
        )));
    }
    let length = match request.header("content-length") {
        None => 0,
        Some(v) => v
            .parse::<usize>()
            .map_err(|_| Some(Reply::error(400, "Content-Length is not a number")))?,
    };
    if length > MAX_BODY {
        return Err(Some(Reply::error(413, "the body is over 64 KiB")));
    }
    if length > 0 {
        if request
            .header("expect")
            .is_some_and(|e| e.eq_ignore_ascii_case("100-continue"))
        {
            conn.write_all(b"HTTP/1.1 100 Continue\r\n\r\n")
                .and_then(|()| conn.flush())
                .map_err(|_| None)?;
        }
        request.body = vec![0; length];
        conn.read_exact(&mut request.body).map_err(|_| {
            Some(Reply::error(
                400,
                "the body is shorter than its Content-Length",
            ))
        })?;
    }
    Ok(request)
}

/// The reason phrase of a status.
fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        401 => "Unauthorized",
        404 => "Not Found",
        405 => "Method Not Allowed",
        409 => "Conflict",
        411 => "Length Required",
        413 => "Content Too Large",
        431 => "Request Header Fields Too Large",
        503 => "Service Unavailable",
        504 => "Gateway Timeout",
        _ => "",
    }
}

/// Writes `reply` (its head only for a HEAD request) and closes.
pub(super) fn write_reply(
    conn: &mut impl Write,
    reply: &Reply,
    head_only: bool,
) -> std::io::Result<()> {
    let mut head = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\n\
         Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n",
        reply.status,
        reason(reply.status),
        reply.content_type,
        reply.body.len()
    );
    if let Some((name, value)) = &reply.extra {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    head.push_str("\r\n");
    conn.write_all(head.as_bytes())?;
    if !head_only {
        conn.write_all(&reply.body)?;
    }
    conn.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Cursor;

    /// A connection reading `input`, collecting what is written.
    struct Conn(Cursor<Vec<u8>>, Vec<u8>);

    impl Read for Conn {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            self.0.read(buf)
        }
    }
    impl BufRead for Conn {
        fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
            self.0.fill_buf()
        }
        fn consume(&mut self, n: usize) {
            self.0.consume(n)
        }
    }
    impl Write for Conn {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.1.write(buf)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    fn read(input: &str) -> Result<Request, Option<u16>> {
        let mut conn = Conn(Cursor::new(input.as_bytes().to_vec()), Vec::new());
        read_request(&mut conn).map_err(|e| e.map(|r| r.status))
    }

    #[test]
    fn a_request_is_read_with_its_headers_and_body() {
        let r = read("POST /api/write HTTP/1.1\r\nHost: x\r\nContent-Length: 4\r\nAuthorization: Bearer t\r\n\r\nbody")
            .unwrap();
        assert_eq!(
            (r.method.as_str(), r.target.as_str()),
            ("POST", "/api/write")
        );
        assert_eq!(r.header("authorization"), Some("Bearer t"));
        assert_eq!(r.body, b"body");
    }

    #[test]
    fn bad_requests_are_refused_with_a_status() {
        assert_eq!(read("").unwrap_err(), None);
        assert_eq!(read("GET /\r\n\r\n").unwrap_err(), Some(400));
        assert_eq!(read("GET x HTTP/1.1\r\n\r\n").unwrap_err(), Some(400));
        assert_eq!(
            read("GET / HTTP/1.1\r\nbroken\r\n\r\n").unwrap_err(),
            Some(400)
        );
        assert_eq!(
            read("GET / HTTP/1.1\r\nContent-Length: x\r\n\r\n").unwrap_err(),
            Some(400)
        );
        assert_eq!(
            read("POST / HTTP/1.1\r\nContent-Length: 99999999\r\n\r\n").unwrap_err(),
            Some(413)
        );
        assert_eq!(
            read("POST / HTTP/1.1\r\nContent-Length: 9\r\n\r\nshort").unwrap_err(),
            Some(400)
        );
        assert_eq!(
            read("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n").unwrap_err(),
            Some(411)
        );
        let long = format!("GET / HTTP/1.1\r\nX: {}\r\n\r\n", "a".repeat(MAX_HEAD));
        assert_eq!(read(&long).unwrap_err(), Some(431));
        assert_eq!(
            read("GET / HTTP/1.1\r\nHost: x\r\n").unwrap_err(),
            Some(400)
        );
    }
}
