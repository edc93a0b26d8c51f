//! The JSON API under `/api/` (docs/web.md): the routes, the reading
//! answers built from the last snapshot, and the changes handed to the
//! scan. Every refusal is an HTTP status with `{"error": "..."}`.

use super::state::{Command, Shared, Snapshot};
use plcrun::{Value, VarInfo};
use serde_json::{Value as Json, json};
use std::sync::mpsc::{RecvTimeoutError, TrySendError, sync_channel};
use std::time::{Duration, UNIX_EPOCH};

/// How long a change waits for the scan to carry it out.
const COMMAND_TIMEOUT: Duration = Duration::from_secs(5);

/// An answer: status, content type, body.
#[derive(Debug)]
pub(super) struct Reply {
    /// HTTP status.
    pub(super) status: u16,
    /// `Content-Type`.
    pub(super) content_type: &'static str,
    /// The body.
    pub(super) body: Vec<u8>,
    /// `Allow` for a 405, `WWW-Authenticate` for a 401.
    pub(super) extra: Option<(&'static str, String)>,
}

impl Reply {
    /// A JSON answer.
    pub(super) fn json(status: u16, value: &Json) -> Reply {
        Reply {
            status,
            content_type: "application/json",
            body: value.to_string().into_bytes(),
            extra: None,
        }
    }

    /// A refusal: `{"error": message}`.
    pub(super) fn error(status: u16, message: impl Into<String>) -> Reply {
        Reply::json(status, &json!({ "error": message.into() }))
    }

    /// Any other body.
    pub(super) fn body(content_type: &'static str, body: impl Into<Vec<u8>>) -> Reply {
        Reply {
            status: 200,
            content_type,
            body: body.into(),
            extra: None,
        }
    }

    fn with(mut self, header: &'static str, value: impl Into<String>) -> Reply {
        self.extra = Some((header, value.into()));
        self
    }
}

/// A request as the routes see it.
#[derive(Debug)]
pub(super) struct Asked<'a> {
    /// `GET`, `POST`...
    pub(super) method: &'a str,
    /// The path, percent-decoded.
    pub(super) path: &'a str,
    /// The query's `q` parameter, decoded.
    pub(super) search: Option<String>,
    /// Whether the request carries the right token.
    pub(super) authorised: bool,
    /// The body (POST).
    pub(super) body: &'a [u8],
}

/// Answers one request of the API (`/api/...`).
pub(super) fn route(shared: &Shared, asked: &Asked<'_>) -> Reply {
    let path = asked.path.trim_end_matches('/');
    let reading = |only: fn(&Shared, &Asked<'_>) -> Reply| {
        if asked.method == "GET" || asked.method == "HEAD" {
            only(shared, asked)
        } else {
            Reply::error(405, format!("{path} is read with GET")).with("Allow", "GET, HEAD")
        }
    };
    match path {
        "/api" => reading(index),
        "/api/variables" => reading(variables),
        "/api/forces" => reading(forces),
        "/api/stats" => reading(stats),
        "/api/charts" => reading(charts),
        "/api/state" => reading(state),
        "/api/write" | "/api/force" | "/api/unforce" | "/api/reset" => change(shared, asked),
        _ => {
            if let Some(name) = path.strip_prefix("/api/variables/") {
                return reading_one(shared, asked, name);
            }
            if let Some(file) = path.strip_prefix("/api/charts/") {
                return reading_chart(shared, asked, file);
            }
            Reply::error(
                404,
                format!("no such endpoint: {path} (GET /api lists them)"),
            )
        }
    }
}

/// `GET /api`: what there is.
fn index(_: &Shared, _: &Asked<'_>) -> Reply {
    Reply::json(
        200,
        &json!({
            "endpoints": [
                "GET /api/variables[?q=TEXT]", "GET /api/variables/PATH",
                "POST /api/write", "POST /api/force", "POST /api/unforce",
                "GET /api/forces", "GET /api/stats", "GET /api/charts",
                "GET /api/charts/N.svg", "GET /api/state", "POST /api/reset",
                "GET /api/events", "GET /metrics"
            ],
            "docs": "docs/web.md"
        }),
    )
}

/// A value as a number for plots (BOOL 0/1, integers, reals, durations
/// in nanoseconds), or null.
pub(super) fn plotted(v: &Value) -> Json {
    match v.as_bool() {
        Some(b) => json!(u8::from(b)),
        None => v
            .as_f64()
            .filter(|x| x.is_finite())
            .map_or(Json::Null, |x| json!(x)),
    }
}

/// One variable with its value in `snapshot`.
fn variable(info: &VarInfo, i: usize, snapshot: &Snapshot) -> Json {
    let value = snapshot.values.get(i);
    json!({
        "index": i,
        "path": info.path,
        "type": info.type_name,
        "direction": info.direction.name(),
        "address": info.address,
        "writable": info.writable,
        "value": value.map(Value::to_literal),
        "number": value.map_or(Json::Null, plotted),
        "forced": snapshot.forced.get(i).copied().unwrap_or(false),
    })
}

/// Where the values come from.
fn header(snapshot: &Snapshot) -> Json {
    json!({
        "seq": snapshot.seq,
        "cycle": snapshot.cycle,
        "time_ns": snapshot.time_ns,
        "at_ms": snapshot.at.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_millis() as u64),
        "faulted": snapshot.fault.is_some(),
    })
}

/// `GET /api/variables[?q=TEXT]`: every variable (whose path contains
/// TEXT, in any case).
fn variables(shared: &Shared, asked: &Asked<'_>) -> Reply {
    let snapshot = shared.snapshot();
    let wanted = asked.search.as_deref().map(str::to_lowercase);
    let list: Vec<Json> = shared
        .variables
        .iter()
        .enumerate()
        .filter(|(_, v)| {
            wanted
                .as_deref()
                .is_none_or(|w| v.path.to_lowercase().contains(w))
        })
        .map(|(i, v)| variable(v, i, &snapshot))
        .collect();
    let mut out = header(&snapshot);
    out["variables"] = Json::Array(list);
    Reply::json(200, &out)
}

/// `GET /api/variables/PATH`.
fn reading_one(shared: &Shared, asked: &Asked<'_>, name: &str) -> Reply {
    if asked.method != "GET" && asked.method != "HEAD" {
        return Reply::error(
            405,
            "a variable is read with GET; change it with POST /api/write",
        )
        .with("Allow", "GET, HEAD");
    }
    let Some(i) = shared.find(name) else {
        return Reply::error(
            404,
            format!("no variable `{name}` (GET /api/variables lists them)"),
        );
    };
    let snapshot = shared.snapshot();
    let mut out = variable(&shared.variables[i], i, &snapshot);
    out["cycle"] = json!(snapshot.cycle);
    Reply::json(200, &out)
}

/// `GET /api/forces`.
fn forces(shared: &Shared, _: &Asked<'_>) -> Reply {
    let snapshot = shared.snapshot();
    let list: Vec<Json> = shared
        .variables
        .iter()
        .enumerate()
        .filter(|(i, _)| snapshot.forced.get(*i).copied().unwrap_or(false))
        .map(|(i, v)| json!({"path": v.path, "value": snapshot.values.get(i).map(Value::to_literal)}))
        .collect();
    Reply::json(200, &json!({ "forces": list }))
}

/// The task statistics as JSON.
pub(super) fn task_stats(shared: &Shared) -> Json {
    match shared.stats.get() {
        Some(stats) => serde_json::to_value(stats.snapshot()).unwrap_or(Json::Null),
        None => json!([]),
    }
}

/// `GET /api/stats`.
fn stats(shared: &Shared, _: &Asked<'_>) -> Reply {
    let snapshot = shared.snapshot();
    let mut out = header(&snapshot);
    out["tasks"] = task_stats(shared);
    Reply::json(200, &out)
}

/// `GET /api/charts`.
fn charts(shared: &Shared, _: &Asked<'_>) -> Reply {
    let snapshot = shared.snapshot();
    let list: Vec<Json> = shared
        .charts
        .iter()
        .enumerate()
        .map(|(i, c)| {
            json!({
                "index": i,
                "path": c.path,
                "pou": c.pou,
                "svg": format!("/api/charts/{i}.svg"),
                "active": snapshot.active.get(i).cloned().unwrap_or_default(),
            })
        })
        .collect();
    Reply::json(200, &json!({ "cycle": snapshot.cycle, "charts": list }))
}

/// `GET /api/charts/N.svg`: the drawing of chart N.
fn reading_chart(shared: &Shared, asked: &Asked<'_>, file: &str) -> Reply {
    if asked.method != "GET" && asked.method != "HEAD" {
        return Reply::error(405, "a chart is read with GET").with("Allow", "GET, HEAD");
    }
    let chart = file
        .strip_suffix(".svg")
        .and_then(|n| n.parse::<usize>().ok())
        .and_then(|n| shared.charts.get(n));
    match chart {
        Some(c) => Reply::body("image/svg+xml", c.svg.clone()),
        None => Reply::error(
            404,
            format!("no chart `{file}` (GET /api/charts lists them)"),
        ),
    }
}

/// The faulted state as JSON.
pub(super) fn fault_json(snapshot: &Snapshot) -> Json {
    match &snapshot.fault {
        Some(f) => json!({"code": f.code, "message": f.message, "cycle": f.cycle}),
        None => Json::Null,
    }
}

/// `GET /api/state`.
fn state(shared: &Shared, _: &Asked<'_>) -> Reply {
    let snapshot = shared.snapshot();
    let mut out = header(&snapshot);
    out["state"] = json!(if snapshot.fault.is_some() {
        "faulted"
    } else {
        "running"
    });
    out["fault"] = fault_json(&snapshot);
    Reply::json(200, &out)
}

/// `POST /api/write|force|unforce|reset`: checked here, carried out by
/// the scan between two cycles.
fn change(shared: &Shared, asked: &Asked<'_>) -> Reply {
    if asked.method != "POST" {
        return Reply::error(405, format!("{} changes the PLC with POST", asked.path))
            .with("Allow", "POST");
    }
    if !asked.authorised {
        super::state::bump(&shared.counters.refused);
        return Reply::error(
            401,
            "changes need the token: `Authorization: Bearer TOKEN` (printed at start, or --web-token)",
        )
        .with("WWW-Authenticate", "Bearer realm=\"plcrun\"");
    }
    let body: Json = if asked.body.iter().all(u8::is_ascii_whitespace) {
        json!({})
    } else {
        match serde_json::from_slice(asked.body) {
            Ok(v @ Json::Object(_)) => v,
            Ok(_) => return Reply::error(400, "the body must be a JSON object"),
            Err(e) => return Reply::error(400, format!("the body is not JSON: {e}")),
        }
    };
    let command = match command(asked.path.trim_end_matches('/'), &body) {
        Ok(c) => c,
        Err(why) => return Reply::error(400, why),
    };
    send(shared, command)
}

/// The command a change asks for.
fn command(path: &str, body: &Json) -> Result<Command, String> {
    let text = |key: &str| -> Result<String, String> {
        match body.get(key) {
            Some(Json::String(s)) => Ok(s.clone()),
            Some(Json::Bool(b)) if key == "value" => Ok(if *b { "TRUE" } else { "FALSE" }.into()),
            Some(Json::Number(n)) if key == "value" => Ok(n.to_string()),
            Some(_) => Err(format!("`{key}` must be a string")),
            None => Err(format!("`{key}` is missing")),
        }
    };
    Ok(match path {
        "/api/write" => Command::Write {
            path: text("path")?,
            literal: text("value")?,
        },
        "/api/force" => Command::Force {
            path: text("path")?,
            literal: text("value")?,
        },
        "/api/unforce" => Command::Unforce {
            path: text("path")?,
        },
        _ => {
            let warm = match body.get("kind").and_then(Json::as_str) {
                None | Some("warm") => true,
                Some("cold") => false,
                Some(other) => {
                    return Err(format!("`kind` is \"warm\" or \"cold\", not {other:?}"));
                }
            };
            Command::Reset { warm }
        }
    })
}

/// Queues `command` for the scan and waits for its outcome.
fn send(shared: &Shared, command: Command) -> Reply {
    if shared.is_closing() {
        return Reply::error(503, "the run is ending");
    }
    let (tx, rx) = sync_channel(1);
    match shared.commands.try_send((command, tx)) {
        Ok(()) => {}
        Err(TrySendError::Full(_)) => {
            return Reply::error(503, "too many changes waiting for the scan; try again");
        }
        Err(TrySendError::Disconnected(_)) => return Reply::error(503, "the run has ended"),
    }
    match rx.recv_timeout(COMMAND_TIMEOUT) {
        Ok(Ok(message)) => Reply::json(200, &json!({ "ok": true, "message": message })),
        Ok(Err((status, message))) => Reply::error(status, message),
        Err(RecvTimeoutError::Timeout) => {
            Reply::error(504, "the scan did not carry the change out in 5 s")
        }
        Err(RecvTimeoutError::Disconnected) => Reply::error(503, "the run has ended"),
    }
}
