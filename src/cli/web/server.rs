//! The HTTP side of the web monitor: a thread accepts connections and
//! gives each its own thread (at most [`MAX_CONNECTIONS`] at once), which
//! reads one request and answers it (the page, `/metrics`, the API) or
//! keeps the connection as an event stream ([`super::sse`]).

use super::api::{Asked, Reply, route};
use super::http::{Request, read_request, write_reply};
use super::state::{Shared, bump};
use std::io::BufReader;
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

/// The page, served at `/`.
const PAGE: &str = include_str!("page.html");

/// Connections served at once; one more is answered 503 and closed.
const MAX_CONNECTIONS: u64 = 64;

/// How long a client may take to send its request, or to take an answer.
const IO_TIMEOUT: Duration = Duration::from_secs(10);

/// A running web monitor's HTTP server (stopped by [`Self::shutdown`] or
/// when dropped).
pub struct WebServer {
    shared: Arc<Shared>,
    acceptor: Option<JoinHandle<()>>,
    local_addr: SocketAddr,
}

impl std::fmt::Debug for WebServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WebServer")
            .field("local_addr", &self.local_addr)
            .finish_non_exhaustive()
    }
}

impl WebServer {
    /// Serves on `listener`. The accepting thread first leaves a
    /// real-time policy the process may run under (`chrt -f 50 plcrun
    /// ...`), so that it and every connection's thread, which inherit its
    /// policy, leave the CPU to the scan.
    pub(super) fn start(listener: TcpListener, shared: Arc<Shared>) -> Result<WebServer, String> {
        let local_addr = listener
            .local_addr()
            .map_err(|e| format!("E962: web: cannot listen: {e}"))?;
        let for_thread = Arc::clone(&shared);
        let acceptor = std::thread::Builder::new()
            .name("web-accept".into())
            .spawn(move || {
                plcrun::leave_real_time();
                accept(&listener, &for_thread);
            })
            .map_err(|e| format!("E962: web: cannot start a thread: {e}"))?;
        Ok(WebServer {
            shared,
            acceptor: Some(acceptor),
            local_addr,
        })
    }

    /// The address it listens on (the port the system chose for port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// Stops accepting and closes the streams.
    pub fn shutdown(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        let Some(acceptor) = self.acceptor.take() else {
            return;
        };
        self.shared
            .closing
            .store(true, std::sync::atomic::Ordering::Release);
        // Wake the accepting thread with a connection of our own.
        let mut wake = self.local_addr;
        if wake.ip().is_unspecified() {
            wake.set_ip(std::net::Ipv4Addr::LOCALHOST.into());
        }
        let _ = TcpStream::connect_timeout(&wake, Duration::from_secs(1));
        let _ = acceptor.join();
    }
}

impl Drop for WebServer {
    fn drop(&mut self) {
        self.stop();
    }
}

/// Accepts connections until the run ends.
fn accept(listener: &TcpListener, shared: &Arc<Shared>) {
    let open = Arc::new(AtomicU64::new(0));
    for conn in listener.incoming() {
        if shared.is_closing() {
            return;
        }
        let Ok(conn) = conn else {
            // A connection reset before it was accepted, or no file
            // descriptor left: wait a little rather than spin.
            std::thread::sleep(Duration::from_millis(10));
            continue;
        };
        let _ = conn.set_read_timeout(Some(IO_TIMEOUT));
        let _ = conn.set_write_timeout(Some(IO_TIMEOUT));
        if open.fetch_add(1, Ordering::AcqRel) >= MAX_CONNECTIONS {
            open.fetch_sub(1, Ordering::AcqRel);
            let reply = Reply::error(503, "too many connections");
            let mut conn = conn;
            let _ = write_reply(&mut conn, &reply, false);
            continue;
        }
        let (shared, open) = (Arc::clone(shared), Arc::clone(&open));
        let spawned = std::thread::Builder::new()
            .name("web".into())
            .spawn(move || {
                serve(conn, &shared);
                open.fetch_sub(1, Ordering::AcqRel);
            });
        if spawned.is_err() {
            // The connection went with the closure and is closed.
            std::thread::sleep(Duration::from_millis(10));
        }
    }
}

/// Reads one request from `conn` and answers it.
fn serve(conn: TcpStream, shared: &Arc<Shared>) {
    let Ok(writer) = conn.try_clone() else {
        return;
    };
    let mut reader = BufReader::new(conn);
    let mut both = Duplex {
        reader: &mut reader,
        writer,
    };
    let request = match read_request(&mut both) {
        Ok(r) => r,
        Err(Some(reply)) => {
            bump(&shared.counters.requests);
            let _ = write_reply(&mut both.writer, &reply, false);
            return;
        }
        Err(None) => return,
    };
    let mut writer = both.writer;
    let path_only = request.target.split('?').next().unwrap_or("");
    if path_only == "/api/events" && request.method == "GET" {
        super::sse::open(writer, shared);
        return;
    }
    bump(&shared.counters.requests);
    let reply = answer(&request, shared);
    let _ = write_reply(&mut writer, &reply, request.method == "HEAD");
}

/// A buffered reader and the writer of the same connection, as one.
struct Duplex<'a> {
    reader: &'a mut BufReader<TcpStream>,
    writer: TcpStream,
}

impl std::io::Read for Duplex<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        self.reader.read(buf)
    }
}

impl std::io::BufRead for Duplex<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.reader.fill_buf()
    }
    fn consume(&mut self, n: usize) {
        self.reader.consume(n);
    }
}

impl std::io::Write for Duplex<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.writer.write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.writer.flush()
    }
}

/// The answer to `request`.
fn answer(request: &Request, shared: &Shared) -> Reply {
    let (raw_path, query) = request
        .target
        .split_once('?')
        .unwrap_or((request.target.as_str(), ""));
    let Some(path) = percent_decode(raw_path, false) else {
        return Reply::error(400, "the path is not valid percent-encoded UTF-8");
    };
    let method = request.method.as_str();
    let reading = method == "GET" || method == "HEAD";
    match path.as_str() {
        "/" | "/index.html" if reading => Reply::body("text/html; charset=utf-8", PAGE),
        "/metrics" if reading => Reply::body(
            "text/plain; version=0.0.4; charset=utf-8",
            super::metrics::render(shared),
        ),
        "/" | "/index.html" | "/metrics" => Reply::error(405, "read it with GET"),
        p if p == "/api" || p.starts_with("/api/") => {
            let authorised = super::auth::presented(&request.headers)
                .is_some_and(|t| super::auth::matches(t, &shared.token));
            let search = query
                .split('&')
                .filter_map(|kv| kv.split_once('='))
                .find(|(k, _)| *k == "q")
                .and_then(|(_, v)| percent_decode(v, true));
            let asked = Asked {
                method,
                path: p,
                search,
                authorised,
                body: &request.body,
            };
            route(shared, &asked)
        }
        _ => Reply::error(
            404,
            format!("nothing at {path}: the page is at /, the API under /api/"),
        ),
    }
}

/// Decodes `%XX` escapes (and `+` as a space in a query); `None` for a
/// bad escape or bytes that are not UTF-8.
fn percent_decode(text: &str, query: bool) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'%' => {
                let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
                out.push(u8::from_str_radix(hex, 16).ok()?);
                i += 3;
            }
            b'+' if query => {
                out.push(b' ');
                i += 1;
            }
            b => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::percent_decode;

    #[test]
    fn escapes_are_decoded_and_bad_ones_refused() {
        assert_eq!(percent_decode("/a%5B2%5D", false).as_deref(), Some("/a[2]"));
        assert_eq!(percent_decode("a+b", true).as_deref(), Some("a b"));
        assert_eq!(percent_decode("a+b", false).as_deref(), Some("a+b"));
        assert_eq!(percent_decode("%zz", false), None);
        assert_eq!(percent_decode("%4", false), None);
        assert_eq!(percent_decode("%ff", false), None);
    }
}
