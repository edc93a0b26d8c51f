//! The messages of the Debug Adapter Protocol that `plcrun debug` reads
//! (requests and their arguments) and writes (responses and events, through
//! one [`Output`] shared by the protocol thread and the PLC's thread).

use super::framing::write_message;
use serde::Deserialize;
use serde_json::{Value, json};
use std::io::Write;
use std::sync::Mutex;

/// A request from the client.
#[derive(Debug, Clone, Deserialize)]
pub(super) struct Request {
    pub seq: i64,
    pub command: String,
    #[serde(default)]
    pub arguments: Value,
}

impl Request {
    /// The arguments as `T`, or the error message to answer.
    pub fn args<T: for<'de> Deserialize<'de>>(&self) -> Result<T, String> {
        let args = if self.arguments.is_null() {
            json!({})
        } else {
            self.arguments.clone()
        };
        serde_json::from_value(args).map_err(|e| format!("{}: bad arguments: {e}", self.command))
    }
}

/// `launch`'s arguments: the sources and the flags of `plcrun run`.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct LaunchArgs {
    /// One source file, or several.
    pub program: Files,
    /// More flags of `plcrun run` (`--cycles 100`, `--stimulus s.csv`,
    /// `--realtime`, `--modbus ADDR`...).
    #[serde(default)]
    pub args: Vec<String>,
    #[serde(default)]
    pub stop_on_entry: bool,
    /// The folder relative paths are read from.
    pub cwd: Option<String>,
}

/// One file or a list of files.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum Files {
    One(String),
    Many(Vec<String>),
}

/// A `source` argument.
#[derive(Debug, Default, Deserialize)]
pub(super) struct Source {
    pub path: Option<String>,
    pub name: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct SourceBreakpoint {
    pub line: u32,
    pub condition: Option<String>,
    pub hit_condition: Option<String>,
}

#[derive(Debug, Deserialize)]
pub(super) struct SetBreakpointsArgs {
    #[serde(default)]
    pub source: Source,
    #[serde(default)]
    pub breakpoints: Vec<SourceBreakpoint>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct StackTraceArgs {
    pub start_frame: Option<usize>,
    pub levels: Option<usize>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct ScopesArgs {
    pub frame_id: usize,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct VariablesArgs {
    pub variables_reference: usize,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct SetVariableArgs {
    pub variables_reference: usize,
    pub name: String,
    pub value: String,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct EvaluateArgs {
    pub expression: String,
    pub frame_id: Option<usize>,
}

/// The custom `force` and `unforce` requests' arguments.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct ForceArgs {
    pub name: String,
    pub value: Option<String>,
    pub frame_id: Option<usize>,
}

/// The writing side, shared by the threads: numbers the messages.
pub(super) struct Output {
    inner: Mutex<(Box<dyn Write + Send>, i64)>,
}

impl Output {
    pub fn new(out: Box<dyn Write + Send>) -> Output {
        Output {
            inner: Mutex::new((out, 0)),
        }
    }

    fn send(&self, mut message: Value) {
        let mut inner = self
            .inner
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        inner.1 += 1;
        message["seq"] = json!(inner.1);
        // A client gone is noticed by the reader (end of input).
        let _ = write_message(&mut inner.0, &message);
    }

    /// Answers `req`: a body, or an error message.
    pub fn respond(&self, req: &Request, result: Result<Value, String>) {
        let mut m = json!({
            "type": "response",
            "request_seq": req.seq,
            "command": req.command,
        });
        match result {
            Ok(body) => {
                m["success"] = json!(true);
                if !body.is_null() {
                    m["body"] = body;
                }
            }
            Err(message) => {
                m["success"] = json!(false);
                m["message"] = json!(message);
                m["body"] = json!({"error": {"id": 1, "format": message}});
            }
        }
        self.send(m);
    }

    /// Sends event `event` with `body`.
    pub fn event(&self, event: &str, body: Value) {
        let mut m = json!({"type": "event", "event": event});
        if !body.is_null() {
            m["body"] = body;
        }
        self.send(m);
    }
}
