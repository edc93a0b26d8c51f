//! The PLC's side of `plcrun debug`: when the PLC stops, tell the client
//! (`stopped` event) and answer the requests the protocol thread passes on
//! (stack, scopes, variables, writes, forces, evaluations) until one
//! resumes it.

use super::protocol::{
    EvaluateArgs, ForceArgs, Output, Request, ScopesArgs, SetVariableArgs, StackTraceArgs,
    VariablesArgs,
};
use plcrun::{Container, DebugFrontEnd, DebugVariable, Resume, StopReason, StoppedPlc};
use serde_json::{Value, json};
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::Receiver;

/// The one thread the client sees: the PLC's.
pub(super) const THREAD_ID: i64 = 1;

/// The front end on the PLC's thread.
pub(super) struct Front {
    pub out: Arc<Output>,
    pub requests: Receiver<Request>,
    /// True while the PLC waits here (the protocol thread passes requests
    /// on only then).
    pub stopped: Arc<AtomicBool>,
}

/// What a stop hands out to the client: variable groups by reference.
struct Handles {
    containers: Vec<Container>,
}

impl Handles {
    fn add(&mut self, c: Container) -> usize {
        self.containers.push(c);
        self.containers.len()
    }

    fn get(&self, reference: usize) -> Result<&Container, String> {
        reference
            .checked_sub(1)
            .and_then(|k| self.containers.get(k))
            .ok_or_else(|| format!("no variables with reference {reference}"))
    }
}

/// The client's frame id of frame `k` (1-based), and back.
fn frame_index(id: Option<usize>) -> usize {
    id.unwrap_or(1).saturating_sub(1)
}

/// The path the client is shown for a source file: absolute when it
/// exists on disk.
pub(super) fn source_path(file: &str) -> String {
    Path::new(file)
        .canonicalize()
        .map(|p| p.display().to_string())
        .unwrap_or_else(|_| file.to_string())
}

impl DebugFrontEnd for Front {
    fn stopped(&mut self, reason: StopReason, plc: &mut StoppedPlc<'_>) -> Resume {
        let (name, description, text, ids) = match &reason {
            StopReason::Entry => (
                "entry",
                "Stopped before the first cycle".to_string(),
                None,
                vec![],
            ),
            StopReason::Breakpoint(ids) => ("breakpoint", "Breakpoint".into(), None, ids.clone()),
            StopReason::Step => ("step", "Step".into(), None, vec![]),
            StopReason::Pause => match plc.cycle() {
                // At a boundary the frames are the program instances.
                Some(n) => (
                    "pause",
                    format!("Paused at the cycle boundary: before cycle {n}"),
                    None,
                    vec![],
                ),
                None => ("pause", "Paused".into(), None, vec![]),
            },
            StopReason::Cycle => (
                "step",
                format!("Cycle boundary: before cycle {}", plc.cycle().unwrap_or(0)),
                None,
                vec![],
            ),
            StopReason::Fault(f) => (
                "exception",
                format!("Fault {} in {}", f.code(), f.instance()),
                Some(f.to_string()),
                vec![],
            ),
        };
        if let Some(text) = &text {
            self.out.event(
                "output",
                json!({"category": "stderr", "output": format!("{text}\n")}),
            );
        }
        self.stopped.store(true, Ordering::Release);
        let mut body = json!({
            "reason": name,
            "description": description,
            "threadId": THREAD_ID,
            "allThreadsStopped": true,
        });
        if let Some(text) = text {
            body["text"] = json!(text);
        }
        if !ids.is_empty() {
            body["hitBreakpointIds"] = json!(ids);
        }
        self.out.event("stopped", body);
        let mut handles = Handles {
            containers: Vec::new(),
        };
        loop {
            let Ok(req) = self.requests.recv() else {
                // The protocol thread is gone: run on.
                self.stopped.store(false, Ordering::Release);
                return Resume::Detach;
            };
            let resume = match req.command.as_str() {
                "continue" => Some(Resume::Continue),
                "next" => Some(Resume::Next),
                "stepIn" => Some(Resume::StepIn),
                "stepOut" => Some(Resume::StepOut),
                "cycleStep" => Some(Resume::Cycle),
                "disconnect" | "terminate" => Some(Resume::Detach),
                _ => None,
            };
            if let Some(resume) = resume {
                self.stopped.store(false, Ordering::Release);
                if resume != Resume::Detach {
                    let body = if req.command == "continue" {
                        json!({"allThreadsContinued": true})
                    } else {
                        Value::Null
                    };
                    self.out.respond(&req, Ok(body));
                }
                return resume;
            }
            let answer = self.answer(&req, plc, &mut handles);
            self.out.respond(&req, answer);
        }
    }
}

impl Front {
    /// Answers one request about the stopped PLC.
    fn answer(
        &self,
        req: &Request,
        plc: &mut StoppedPlc<'_>,
        handles: &mut Handles,
    ) -> Result<Value, String> {
        match req.command.as_str() {
            "threads" => Ok(json!({"threads": [{"id": THREAD_ID, "name": "PLC"}]})),
            "pause" => Ok(Value::Null),
            "stackTrace" => {
                let a: StackTraceArgs = req.args()?;
                let start = a.start_frame.unwrap_or(0);
                let frames = plc.frames();
                let levels = a.levels.filter(|n| *n > 0).unwrap_or(frames.len());
                let shown: Vec<Value> = frames
                    .iter()
                    .enumerate()
                    .skip(start)
                    .take(levels)
                    .map(|(k, f)| {
                        let mut frame = json!({
                            "id": k + 1,
                            "name": if f.pou == f.name || f.name.ends_with(&f.pou) {
                                f.name.clone()
                            } else {
                                format!("{} ({})", f.name, f.pou)
                            },
                            "line": f.line,
                            "column": f.column.max(1),
                        });
                        if let Some(file) = &f.file {
                            let name = Path::new(file)
                                .file_name()
                                .map(|n| n.to_string_lossy().to_string())
                                .unwrap_or_else(|| file.clone());
                            frame["source"] = json!({"name": name, "path": source_path(file)});
                        }
                        frame
                    })
                    .collect();
                Ok(json!({"stackFrames": shown, "totalFrames": frames.len()}))
            }
            "scopes" => {
                let a: ScopesArgs = req.args()?;
                let k = frame_index(Some(a.frame_id));
                if k >= plc.frames().len() && !plc.frames().is_empty() {
                    return Err(format!("no frame {}", a.frame_id));
                }
                let scopes: Vec<Value> = plc
                    .scopes(k)
                    .into_iter()
                    .map(|s| {
                        let expensive = s.name == "Globals" || s.name == "Process image";
                        let reference = handles.add(s.container);
                        json!({
                            "name": s.name,
                            "variablesReference": reference,
                            "expensive": expensive,
                        })
                    })
                    .collect();
                Ok(json!({"scopes": scopes}))
            }
            "variables" => {
                let a: VariablesArgs = req.args()?;
                let c = handles.get(a.variables_reference)?.clone();
                let vars: Vec<Value> = plc
                    .variables(&c)
                    .into_iter()
                    .map(|v| variable(v, handles))
                    .collect();
                Ok(json!({"variables": vars}))
            }
            "setVariable" => {
                let a: SetVariableArgs = req.args()?;
                let c = handles.get(a.variables_reference)?.clone();
                let v = plc
                    .set_variable(&c, &a.name, &a.value)
                    .map_err(|e| e.to_string())?;
                Ok(json!({"value": v.value, "type": v.type_name}))
            }
            "evaluate" => {
                let a: EvaluateArgs = req.args()?;
                let k = frame_index(a.frame_id);
                let expr = a.expression.trim();
                if let Some((name, value)) = force_expression(expr) {
                    let v = plc.force(k, name, value).map_err(|e| e.to_string())?;
                    return Ok(
                        json!({"result": format!("{name} forced to {v}"), "variablesReference": 0}),
                    );
                }
                if let Some(name) = word_after(expr, "unforce") {
                    plc.unforce(k, name).map_err(|e| e.to_string())?;
                    return Ok(
                        json!({"result": format!("{name} unforced"), "variablesReference": 0}),
                    );
                }
                let v = plc.evaluate(k, expr)?;
                Ok(json!({"result": v.to_literal(), "variablesReference": 0}))
            }
            "force" | "unforce" => {
                let a: ForceArgs = req.args()?;
                let k = frame_index(a.frame_id);
                if req.command == "unforce" {
                    plc.unforce(k, &a.name).map_err(|e| e.to_string())?;
                    return Ok(Value::Null);
                }
                let value = a.value.ok_or("force: a `value` is needed")?;
                let v = plc.force(k, &a.name, &value).map_err(|e| e.to_string())?;
                Ok(json!({"value": v.to_literal()}))
            }
            other => Err(format!("`{other}` is not supported while stopped")),
        }
    }
}

/// A variable as the protocol shows it.
fn variable(v: DebugVariable, handles: &mut Handles) -> Value {
    let reference = v.children.map_or(0, |c| handles.add(c));
    json!({
        "name": v.name,
        "value": v.value,
        "type": v.type_name,
        "evaluateName": v.path,
        "variablesReference": reference,
    })
}

/// `force NAME := VALUE` → `(NAME, VALUE)`.
pub(super) fn force_expression(expr: &str) -> Option<(&str, &str)> {
    let rest = word_after(expr, "force")?;
    let (name, value) = rest.split_once(":=")?;
    Some((name.trim(), value.trim().trim_end_matches(';').trim()))
}

/// The text after a leading keyword (any case), if `expr` starts with it.
pub(super) fn word_after<'e>(expr: &'e str, keyword: &str) -> Option<&'e str> {
    let head = expr.get(..keyword.len())?;
    let rest = &expr[keyword.len()..];
    (head.eq_ignore_ascii_case(keyword) && rest.starts_with(char::is_whitespace))
        .then(|| rest.trim())
}
