//! A scripted Debug Adapter Protocol client: starts `plcrun debug`, frames
//! requests with `Content-Length` headers on its standard input, and reads
//! responses and events from its standard output, so tests speak the real
//! protocol to the real binary.
#![allow(dead_code)]

use super::framed::read_message;
use serde_json::{Value, json};
use std::io::{BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

/// How long any message may take before the test fails.
const PATIENCE: Duration = Duration::from_secs(30);

/// A running `plcrun debug`, with the messages it sent that no wait took.
pub struct DapClient {
    child: Child,
    stdin: Option<ChildStdin>,
    incoming: Receiver<Value>,
    seq: i64,
    /// Messages received and not yet looked at, oldest first.
    pending: Vec<Value>,
    /// Every message received, for failure messages.
    pub log: Vec<Value>,
}

impl DapClient {
    /// Starts `plcrun debug` in the package's folder.
    pub fn start() -> DapClient {
        let mut child = Command::new(env!("CARGO_BIN_EXE_plcrun"))
            .arg("debug")
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("plcrun debug starts");
        let stdin = child.stdin.take().unwrap();
        let mut stdout = BufReader::new(child.stdout.take().unwrap());
        let (tx, incoming) = channel();
        std::thread::spawn(move || {
            while let Some(m) = read_message(&mut stdout) {
                if tx.send(m).is_err() {
                    break;
                }
            }
        });
        DapClient {
            child,
            stdin: Some(stdin),
            incoming,
            seq: 0,
            pending: Vec::new(),
            log: Vec::new(),
        }
    }

    /// Sends a request; its sequence number.
    pub fn send(&mut self, command: &str, arguments: Value) -> i64 {
        self.seq += 1;
        let body = serde_json::to_vec(&json!({
            "seq": self.seq,
            "type": "request",
            "command": command,
            "arguments": arguments,
        }))
        .unwrap();
        let stdin = self.stdin.as_mut().expect("the client's input is open");
        write!(stdin, "Content-Length: {}\r\n\r\n", body.len()).unwrap();
        stdin.write_all(&body).unwrap();
        stdin.flush().unwrap();
        self.seq
    }

    /// The first message (pending or arriving) that `want` accepts.
    fn wait(&mut self, what: &str, want: impl Fn(&Value) -> bool) -> Value {
        if let Some(k) = self.pending.iter().position(&want) {
            return self.pending.remove(k);
        }
        loop {
            match self.incoming.recv_timeout(PATIENCE) {
                Ok(m) => {
                    self.log.push(m.clone());
                    if want(&m) {
                        return m;
                    }
                    self.pending.push(m);
                }
                Err(_) => panic!("no {what} within {PATIENCE:?}; received: {:#?}", self.log),
            }
        }
    }

    /// Sends a request and waits for its response (successful or not).
    pub fn request(&mut self, command: &str, arguments: Value) -> Value {
        let seq = self.send(command, arguments);
        self.wait(&format!("response to {command}"), |m| {
            m["type"] == "response" && m["request_seq"] == seq
        })
    }

    /// [`Self::request`], asserting success; the response's body.
    pub fn ok(&mut self, command: &str, arguments: Value) -> Value {
        let r = self.request(command, arguments);
        assert_eq!(r["success"], true, "{command} failed: {r:#}");
        r["body"].clone()
    }

    /// Waits for event `name`; its body.
    pub fn event(&mut self, name: &str) -> Value {
        let m = self.wait(&format!("event {name}"), |m| {
            m["type"] == "event" && m["event"] == name
        });
        m["body"].clone()
    }

    /// Waits for the process to end; its exit status.
    pub fn finish(mut self) -> i32 {
        drop(self.stdin.take());
        self.child.wait().ok().and_then(|s| s.code()).unwrap_or(-1)
    }
}

impl Drop for DapClient {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
