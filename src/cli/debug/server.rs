//! The protocol thread of `plcrun debug`: reads the client's requests,
//! answers those it can (initialize, launch, breakpoints, threads, pause,
//! disconnect), and passes those about a stopped PLC to the PLC's thread
//! ([`super::front`]).

use super::framing::read_message;
use super::front::{Front, THREAD_ID, force_expression, source_path, word_after};
use super::protocol::{Files, ForceArgs, LaunchArgs, Output, Request, SetBreakpointsArgs};
use plcrun::{Breakpoint, DebugControl, StopHandle};
use serde_json::{Value, json};
use std::io::BufRead;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Sender};
use std::thread::JoinHandle;

/// A launched program.
struct Launched {
    control: Arc<DebugControl>,
    stop: StopHandle,
    /// Lets the run start (sent at `configurationDone`).
    go: Option<Sender<()>>,
    /// Requests for the PLC's thread while it is stopped.
    to_plc: Sender<Request>,
    stopped: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

/// What the PLC's thread says when it is ready to run.
pub(super) struct Ready {
    pub control: Arc<DebugControl>,
    pub stop: StopHandle,
}

/// Serves the client on `input` until it disconnects or closes the input.
pub(super) fn serve(mut input: impl BufRead, out: Arc<Output>) {
    let mut launched: Option<Launched> = None;
    loop {
        let message = match read_message(&mut input) {
            Ok(Some(m)) => m,
            Ok(None) => break,
            Err(e) => {
                out.event(
                    "output",
                    json!({"category": "stderr", "output": format!("plcrun debug: {e}\n")}),
                );
                break;
            }
        };
        if message.get("type").and_then(Value::as_str) != Some("request") {
            continue;
        }
        let req: Request = match serde_json::from_value(message) {
            Ok(r) => r,
            Err(e) => {
                out.event(
                    "output",
                    json!({"category": "stderr", "output": format!("plcrun debug: bad request: {e}\n")}),
                );
                continue;
            }
        };
        match req.command.as_str() {
            "initialize" => out.respond(&req, Ok(capabilities())),
            "launch" => {
                if launched.is_some() {
                    out.respond(&req, Err("a program is launched already".into()));
                    continue;
                }
                match launch(&req, &out) {
                    Ok(l) => {
                        launched = Some(l);
                        out.respond(&req, Ok(Value::Null));
                        out.event("initialized", Value::Null);
                    }
                    Err(e) => out.respond(&req, Err(e)),
                }
            }
            "setBreakpoints" => {
                let answer = req.args::<SetBreakpointsArgs>().and_then(|a| {
                    let l = launched.as_ref().ok_or("launch the program first")?;
                    Ok(set_breakpoints(&l.control, a))
                });
                out.respond(&req, answer);
            }
            "setExceptionBreakpoints" => out.respond(&req, Ok(json!({"breakpoints": []}))),
            "configurationDone" => {
                if let Some(go) = launched.as_mut().and_then(|l| l.go.take()) {
                    let _ = go.send(());
                }
                out.respond(&req, Ok(Value::Null));
            }
            "threads" => out.respond(
                &req,
                Ok(json!({"threads": [{"id": THREAD_ID, "name": "PLC"}]})),
            ),
            "pause" | "pauseAtCycle" => {
                if let Some(l) = &launched {
                    if req.command == "pause" {
                        l.control.pause();
                    } else {
                        l.control.pause_at_cycle();
                    }
                }
                out.respond(&req, Ok(Value::Null));
            }
            // `terminate` ends the program and waits for the `disconnect`
            // that follows; `disconnect` ends both.
            "disconnect" | "terminate" => {
                if let Some(l) = launched.take() {
                    if l.stopped.load(Ordering::Acquire) {
                        let _ = l.to_plc.send(req.clone());
                    }
                    end(l);
                }
                out.respond(&req, Ok(Value::Null));
                if req.command == "disconnect" {
                    break;
                }
            }
            _ => {
                let Some(l) = &launched else {
                    out.respond(
                        &req,
                        Err(format!("`{}`: launch the program first", req.command)),
                    );
                    continue;
                };
                if l.stopped.load(Ordering::Acquire) {
                    if matches!(
                        req.command.as_str(),
                        "continue" | "next" | "stepIn" | "stepOut" | "cycleStep"
                    ) {
                        l.stopped.store(false, Ordering::Release);
                    }
                    if l.to_plc.send(req.clone()).is_err() {
                        out.respond(&req, Err("the program has ended".into()));
                    }
                } else {
                    out.respond(&req, while_running(&req, &l.control));
                }
            }
        }
    }
    // The input ended without a disconnect: stop the program.
    if let Some(l) = launched {
        end(l);
    }
}

/// Ends a launched program: the debugger lets go, the run stops at the
/// next cycle boundary, and its thread is waited for.
fn end(mut l: Launched) {
    l.control.detach();
    l.stop.stop();
    if let Some(go) = l.go.take() {
        let _ = go.send(());
    }
    drop(l.to_plc);
    if let Some(t) = l.thread.take() {
        let _ = t.join();
    }
}

/// What the adapter can do.
fn capabilities() -> Value {
    json!({
        "supportsConfigurationDoneRequest": true,
        "supportsConditionalBreakpoints": true,
        "supportsHitConditionalBreakpoints": true,
        "supportsSetVariable": true,
        "supportsEvaluateForHovers": true,
        "supportsTerminateRequest": true,
    })
}

/// A request about the PLC while it runs: forces are queued for the next
/// cycle boundary; the rest needs a stop.
fn while_running(req: &Request, control: &DebugControl) -> Result<Value, String> {
    match req.command.as_str() {
        "force" | "unforce" => {
            let a: ForceArgs = req.args()?;
            let value = (req.command == "force")
                .then(|| a.value.clone().ok_or("force: a `value` is needed"))
                .transpose()?;
            control.force_later(&a.name, value.as_deref());
            Ok(Value::Null)
        }
        "evaluate" => {
            let expr = req
                .arguments
                .get("expression")
                .and_then(Value::as_str)
                .unwrap_or("");
            if let Some((name, value)) = force_expression(expr) {
                control.force_later(name, Some(value));
                return Ok(
                    json!({"result": format!("{name} forced from the next cycle"), "variablesReference": 0}),
                );
            }
            if let Some(name) = word_after(expr, "unforce") {
                control.force_later(name, None);
                return Ok(
                    json!({"result": format!("{name} unforced from the next cycle"), "variablesReference": 0}),
                );
            }
            Err("the PLC is running: pause it to evaluate".into())
        }
        other => Err(format!("`{other}`: the PLC is running; pause it first")),
    }
}

/// Sets a file's breakpoints; the answer's body.
fn set_breakpoints(control: &DebugControl, a: SetBreakpointsArgs) -> Value {
    let file = a.source.path.or(a.source.name).unwrap_or_default();
    let wanted: Vec<Breakpoint> = a
        .breakpoints
        .into_iter()
        .map(|b| Breakpoint {
            line: b.line,
            condition: b.condition,
            hit_condition: b.hit_condition,
        })
        .collect();
    let places = control.set_breakpoints(&file, &wanted);
    let shown: Vec<Value> = places
        .into_iter()
        .map(|p| {
            let mut b = json!({
                "id": p.id,
                "verified": p.verified,
                "line": p.line,
                "source": {"path": source_path(&file)},
            });
            if let Some(m) = p.message {
                b["message"] = json!(m);
            }
            b
        })
        .collect();
    json!({"breakpoints": shown})
}

/// Starts the program's thread: compiles as `plcrun run` with the launch's
/// arguments, attaches the debugger, and waits for `configurationDone`.
fn launch(req: &Request, out: &Arc<Output>) -> Result<Launched, String> {
    let a: LaunchArgs = req.args()?;
    if let Some(cwd) = &a.cwd {
        std::env::set_current_dir(cwd).map_err(|e| format!("cwd `{cwd}`: {e}"))?;
    }
    let mut words = vec!["plcrun".to_string(), "run".to_string()];
    match a.program {
        Files::One(f) => words.push(f),
        Files::Many(fs) => words.extend(fs),
    }
    words.extend(a.args);
    let args = super::run_args(&words)?;
    let (ready_tx, ready_rx) = mpsc::channel::<Ready>();
    let (go_tx, go_rx) = mpsc::channel::<()>();
    let (to_plc, requests) = mpsc::channel::<Request>();
    let stopped = Arc::new(AtomicBool::new(false));
    let front = Front {
        out: out.clone(),
        requests,
        stopped: stopped.clone(),
    };
    let stop_on_entry = a.stop_on_entry;
    let thread_out = out.clone();
    let thread = std::thread::Builder::new()
        .name("plc".into())
        .spawn(move || {
            let mut front = Some(front);
            let status = super::super::run::run_with(&args, &mut |plc| {
                let Some(front) = front.take() else {
                    return;
                };
                let control = plc.attach_debugger(Box::new(front), stop_on_entry);
                let _ = ready_tx.send(Ready {
                    control,
                    stop: plc.stop_handle(),
                });
                // Until configurationDone (or the client leaving).
                let _ = go_rx.recv();
            });
            // A program that never started is told in the launch's answer.
            if front.is_none() {
                thread_out.event("exited", json!({"exitCode": status}));
                thread_out.event("terminated", Value::Null);
            }
        })
        .map_err(|e| format!("cannot start the program's thread: {e}"))?;
    match ready_rx.recv() {
        Ok(ready) => Ok(Launched {
            control: ready.control,
            stop: ready.stop,
            go: Some(go_tx),
            to_plc,
            stopped,
            thread: Some(thread),
        }),
        Err(_) => {
            let _ = thread.join();
            Err("the program did not start: see the messages above (standard error)".into())
        }
    }
}
