//! The HTTP side of the web monitor: a few worker threads take requests
//! from `tiny_http` and answer them (the page, `/metrics`, the API); an
//! event stream gets a thread of its own ([`super::sse`]).

use super::api::{Asked, Reply, route};
use super::state::{Shared, bump};
use std::io::Read;
use std::net::{SocketAddr, TcpListener};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::thread::JoinHandle;

/// The page, served at `/`.
const PAGE: &str = include_str!("page.html");

/// Threads answering requests.
const WORKERS: usize = 4;

/// The largest request body read.
const MAX_BODY: usize = 64 * 1024;

/// A running web monitor's HTTP server (stopped by [`Self::shutdown`] or
/// when dropped).
pub struct WebServer {
    server: Arc<tiny_http::Server>,
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
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
    /// Serves on `listener`. The server's threads are started from a
    /// thread that first leaves a real-time policy the process may run
    /// under (`chrt -f 50 plcrun ...`), so that they and every thread they
    /// start leave the CPU to the scan.
    pub(super) fn start(listener: TcpListener, shared: Arc<Shared>) -> Result<WebServer, String> {
        let local_addr = listener
            .local_addr()
            .map_err(|e| format!("E962: web: cannot listen: {e}"))?;
        let for_starter = Arc::clone(&shared);
        let starter = std::thread::Builder::new()
            .name("web-start".into())
            .spawn(move || {
                plcrun::leave_real_time();
                serve(listener, local_addr, &for_starter)
            })
            .map_err(|e| format!("E962: web: cannot start a thread: {e}"))?;
        let (server, workers) = starter
            .join()
            .map_err(|_| "E962: web: the server's start failed".to_string())??;
        Ok(WebServer {
            server,
            shared,
            workers,
            local_addr,
        })
    }

    /// The address it listens on (the port the system chose for port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// Closes the streams and stops the workers.
    pub fn shutdown(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        self.shared.closing.store(true, Ordering::Release);
        for _ in 0..self.workers.len() {
            self.server.unblock();
        }
        for worker in self.workers.drain(..) {
            let _ = worker.join();
        }
    }
}

impl Drop for WebServer {
    fn drop(&mut self) {
        self.stop();
    }
}

/// The server and its workers, started on the calling thread.
type Started = (Arc<tiny_http::Server>, Vec<JoinHandle<()>>);

/// Starts `tiny_http` on `listener` and the workers taking its requests.
fn serve(
    listener: TcpListener,
    local_addr: SocketAddr,
    shared: &Arc<Shared>,
) -> Result<Started, String> {
    let server = tiny_http::Server::from_listener(listener, None)
        .map_err(|e| format!("E962: web: cannot listen on {local_addr}: {e}"))?;
    let server = Arc::new(server);
    let mut workers = Vec::with_capacity(WORKERS);
    for _ in 0..WORKERS {
        let (server, shared) = (Arc::clone(&server), Arc::clone(shared));
        let worker = std::thread::Builder::new()
            .name("web".into())
            .spawn(move || {
                while let Ok(request) = server.recv() {
                    answer(request, &shared);
                }
            })
            .map_err(|e| format!("E962: web: cannot start a thread: {e}"))?;
        workers.push(worker);
    }
    Ok((server, workers))
}

/// Answers one request.
fn answer(mut request: tiny_http::Request, shared: &Arc<Shared>) {
    let url = request.url().to_string();
    let (raw_path, query) = url.split_once('?').unwrap_or((url.as_str(), ""));
    let Some(path) = percent_decode(raw_path, false) else {
        bump(&shared.counters.requests);
        return respond(
            request,
            Reply::error(400, "the path is not valid percent-encoded UTF-8"),
        );
    };
    let method = request.method().as_str().to_ascii_uppercase();
    if path == "/api/events" && method == "GET" {
        super::sse::open(request, Arc::clone(shared));
        return;
    }
    bump(&shared.counters.requests);
    let reply = match path.as_str() {
        "/" | "/index.html" if method == "GET" || method == "HEAD" => {
            Reply::body("text/html; charset=utf-8", PAGE)
        }
        "/metrics" if method == "GET" || method == "HEAD" => Reply::body(
            "text/plain; version=0.0.4; charset=utf-8",
            super::metrics::render(shared),
        ),
        "/" | "/index.html" | "/metrics" => Reply::error(405, "read it with GET"),
        p if p == "/api" || p.starts_with("/api/") => {
            let mut body = Vec::new();
            let limited = request
                .as_reader()
                .take(MAX_BODY as u64 + 1)
                .read_to_end(&mut body);
            if limited.is_err() {
                return respond(request, Reply::error(400, "the body could not be read"));
            }
            if body.len() > MAX_BODY {
                return respond(request, Reply::error(413, "the body is over 64 KiB"));
            }
            let authorised = super::auth::presented(request.headers())
                .is_some_and(|t| super::auth::matches(t, &shared.token));
            let search = query
                .split('&')
                .filter_map(|kv| kv.split_once('='))
                .find(|(k, _)| *k == "q")
                .and_then(|(_, v)| percent_decode(v, true));
            let asked = Asked {
                method: &method,
                path: p,
                search,
                authorised,
                body: &body,
            };
            route(shared, &asked)
        }
        _ => Reply::error(
            404,
            format!("nothing at {path}: the page is at /, the API under /api/"),
        ),
    };
    let reply = if method == "HEAD" {
        Reply {
            body: Vec::new(),
            ..reply
        }
    } else {
        reply
    };
    respond(request, reply);
}

/// Sends `reply` (a client gone meanwhile is no error of ours).
pub(super) fn respond(request: tiny_http::Request, reply: Reply) {
    let mut response = tiny_http::Response::from_data(reply.body).with_status_code(reply.status);
    let mut headers = vec![
        ("Content-Type", reply.content_type.to_string()),
        ("Cache-Control", "no-store".to_string()),
        ("X-Content-Type-Options", "nosniff".to_string()),
    ];
    if let Some((name, value)) = reply.extra {
        headers.push((name, value));
    }
    for (name, value) in headers {
        if let Ok(h) = tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes()) {
            response.add_header(h);
        }
    }
    let _ = request.respond(response);
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
