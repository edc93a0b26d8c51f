//! A scripted Language Server Protocol client: starts `plcrun lsp`, frames
//! JSON-RPC messages with `Content-Length` headers on its standard input,
//! and reads its answers and notifications from its standard output, so
//! tests speak the real protocol to the real binary.
#![allow(dead_code)]

use super::framed::read_message;
use serde_json::{Value, json};
use std::io::{BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

/// How long any answer may take before the test fails.
const PATIENCE: Duration = Duration::from_secs(30);

/// A running `plcrun lsp` and what it sent that no request took.
pub struct LspClient {
    child: Child,
    stdin: ChildStdin,
    incoming: Receiver<Value>,
    next_id: i64,
    /// Notifications received (publishDiagnostics...), oldest first.
    pub notifications: Vec<Value>,
}

/// The `file://` URI of an absolute path (ASCII paths, as tests use).
pub fn uri(path: &Path) -> String {
    let path = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    format!("file://{}", path.display()).replace(' ', "%20")
}

impl LspClient {
    /// Starts the server with `root` as the workspace folder and completes
    /// the initialisation handshake; returns the client and the server's
    /// capabilities.
    pub fn start(root: &Path) -> (LspClient, Value) {
        LspClient::start_with(root, &[], json!({}))
    }

    /// [`LspClient::start`] with more command-line arguments for `plcrun
    /// lsp` and the client capabilities to announce.
    pub fn start_with(root: &Path, args: &[&str], capabilities: Value) -> (LspClient, Value) {
        let mut child = Command::new(env!("CARGO_BIN_EXE_plcrun"))
            .args(["lsp", "--stdio"])
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("plcrun lsp starts");
        let stdin = child.stdin.take().expect("piped");
        let stdout = child.stdout.take().expect("piped");
        let (send, incoming) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            while let Some(message) = read_message(&mut reader) {
                if send.send(message).is_err() {
                    break;
                }
            }
        });
        let mut client = LspClient {
            child,
            stdin,
            incoming,
            next_id: 1,
            notifications: Vec::new(),
        };
        let root_uri = uri(root);
        let init = client.request(
            "initialize",
            json!({
                "processId": null,
                "rootUri": root_uri,
                "workspaceFolders": [{"uri": root_uri, "name": "test"}],
                "capabilities": capabilities
            }),
        );
        client.notify("initialized", json!({}));
        (client, init["capabilities"].clone())
    }

    fn send(&mut self, message: Value) {
        let body = message.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).expect("server reads");
        self.stdin.flush().expect("server reads");
    }

    fn receive(&mut self, deadline: Instant) -> Option<Value> {
        let left = deadline.saturating_duration_since(Instant::now());
        match self.incoming.recv_timeout(left) {
            Ok(m) => Some(m),
            Err(RecvTimeoutError::Timeout) => None,
            Err(RecvTimeoutError::Disconnected) => panic!("plcrun lsp closed its output"),
        }
    }

    /// Sends a request and returns its result or its error object.
    pub fn call(&mut self, method: &str, params: Value) -> Result<Value, Value> {
        let id = self.next_id;
        self.next_id += 1;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        let deadline = Instant::now() + PATIENCE;
        loop {
            let message = self
                .receive(deadline)
                .unwrap_or_else(|| panic!("no answer to {method} in {PATIENCE:?}"));
            // A request from the server may carry the same number.
            if message["id"] == json!(id) && message.get("method").is_none() {
                return match message.get("error") {
                    Some(e) => Err(e.clone()),
                    None => Ok(message["result"].clone()),
                };
            }
            self.notifications.push(message);
        }
    }

    /// Sends a request that must succeed; returns its result.
    pub fn request(&mut self, method: &str, params: Value) -> Value {
        self.call(method, params)
            .unwrap_or_else(|e| panic!("{method} failed: {e}"))
    }

    /// Sends a notification.
    pub fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Opens `path` with `text` in the server.
    pub fn open(&mut self, path: &Path, text: &str) {
        let language = match path.extension().and_then(|e| e.to_str()) {
            Some("il") => "iec-il",
            Some("sfc") => "iec-sfc",
            _ => "iec-st",
        };
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri(path), "languageId": language, "version": 1, "text": text}}),
        );
    }

    /// Replaces the text of the open document `path`.
    pub fn change(&mut self, path: &Path, version: i64, text: &str) {
        self.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri(path), "version": version},
                   "contentChanges": [{"text": text}]}),
        );
    }

    /// Waits for the next diagnostics published for `path` and returns
    /// them; with `min_count`, keeps waiting until a publication has that
    /// many (an earlier one may predate the last edit).
    pub fn diagnostics(&mut self, path: &Path, min_count: usize) -> Vec<Value> {
        let target = uri(path);
        let deadline = Instant::now() + PATIENCE;
        loop {
            let message = self
                .receive(deadline)
                .unwrap_or_else(|| panic!("no diagnostics for {target} in {PATIENCE:?}"));
            if message["method"] == "textDocument/publishDiagnostics"
                && message["params"]["uri"] == json!(target)
            {
                let list = message["params"]["diagnostics"]
                    .as_array()
                    .cloned()
                    .unwrap_or_default();
                if list.len() >= min_count {
                    return list;
                }
            }
            self.notifications.push(message);
        }
    }

    /// Asks the server to shut down and exit; returns its exit status.
    pub fn shutdown(mut self) -> Option<i32> {
        self.request("shutdown", Value::Null);
        self.notify("exit", Value::Null);
        let deadline = Instant::now() + PATIENCE;
        while Instant::now() < deadline {
            if let Ok(Some(status)) = self.child.try_wait() {
                return status.code();
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        None
    }
}

impl Drop for LspClient {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `{"textDocument": {"uri"}, "position": {line, character}}` for the
/// `nth` (0-based) occurrence of `needle` in `text`, `shift` characters
/// into it.
pub fn position_of(path: &Path, text: &str, needle: &str, nth: usize, shift: usize) -> Value {
    let offset = text
        .match_indices(needle)
        .nth(nth)
        .unwrap_or_else(|| panic!("`{needle}` #{nth} is not in the text"))
        .0
        + shift;
    let line = text[..offset].matches('\n').count();
    let column = offset - text[..offset].rfind('\n').map_or(0, |i| i + 1);
    json!({"textDocument": {"uri": uri(path)}, "position": {"line": line, "character": column}})
}
