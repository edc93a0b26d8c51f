//! The web monitor (`--web`, docs/web.md) through the real binary and a
//! real HTTP client: values that move, writes that need the token and
//! reach the program, forcing, the faulted state and its reset, the event
//! stream, the charts, and `/metrics` read by a strict parser of the
//! Prometheus text format.

use crate::support::cli::{plcrun, temp_file};
use crate::support::http::{Answer, Events, get, post, request};
use serde_json::json;
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const TOKEN: &str = "test-token-42";

const PROGRAM: &str = "
PROGRAM Main
VAR_INPUT go : BOOL; setpoint : INT; END_VAR
VAR_OUTPUT n : DINT; doubled : INT; running : BOOL; END_VAR
n := n + 1;
doubled := setpoint * 2;
running := go;
END_PROGRAM
";

/// A `plcrun` run with the monitor, stopped by SIGTERM when dropped.
pub struct Monitor {
    child: Child,
    /// `HOST:PORT` of the monitor.
    pub addr: String,
    /// The token printed at start, when none was given.
    pub drawn_token: Option<String>,
}

impl Monitor {
    /// Starts `plcrun ARGS --realtime --web 127.0.0.1:0` and reads where
    /// it listens from standard error.
    pub fn start(args: &[&str]) -> Monitor {
        let mut child = Command::new(env!("CARGO_BIN_EXE_plcrun"))
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(["--realtime", "--web", "127.0.0.1:0", "--no-trace"])
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("plcrun starts");
        let mut err = BufReader::new(child.stderr.take().unwrap());
        let mut addr = None;
        let mut drawn_token = None;
        let mut seen = String::new();
        while addr.is_none() || (drawn_token.is_none() && !args.contains(&"--web-token")) {
            let mut line = String::new();
            if err.read_line(&mut line).unwrap() == 0 {
                panic!("plcrun ended before its monitor listened:\n{seen}");
            }
            seen.push_str(&line);
            if let Some(a) = line.trim().strip_prefix("web: listening on http://") {
                addr = Some(a.trim_end_matches('/').to_string());
            }
            if let Some(t) = line.trim().strip_prefix("web: token for changes: ") {
                drawn_token = Some(t.to_string());
            }
        }
        std::thread::spawn(move || std::io::copy(&mut err, &mut std::io::sink()));
        Monitor {
            child,
            addr: addr.unwrap(),
            drawn_token,
        }
    }

    /// Asks for a clean stop (SIGTERM) and returns the exit status.
    pub fn stop(mut self) -> i32 {
        self.terminate()
    }

    fn terminate(&mut self) -> i32 {
        let pid = self.child.id().to_string();
        let _ = Command::new("kill").args(["-TERM", &pid]).status();
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            if let Ok(Some(status)) = self.child.try_wait() {
                return status.code().unwrap_or(-1);
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        panic!("plcrun did not stop within 10 s of SIGTERM");
    }
}

impl Drop for Monitor {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// The literal value of `path` as the API gives it. Until the first
/// cycle's values are published the API says `null`: that is waited out
/// (up to 5 s; CI saw it on a loaded machine).
fn value(addr: &str, path: &str) -> String {
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let a = get(addr, &format!("/api/variables/{path}"));
        assert_eq!(a.status, 200, "{path}: {a:?}");
        let json = a.json();
        if let Some(v) = json["value"].as_str() {
            return v.to_string();
        }
        assert!(Instant::now() < deadline, "{path} has no value: {json}");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Waits (up to 5 s) until `path` reads `expected`.
fn wait_for(addr: &str, path: &str, expected: &str) {
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let v = value(addr, path);
        if v == expected {
            return;
        }
        assert!(
            Instant::now() < deadline,
            "{path} stayed {v}, expected {expected}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Checks that `a` is a refusal with `status` and a JSON message.
fn refused(a: &Answer, status: u16) {
    assert_eq!(a.status, status, "{a:?}");
    assert_eq!(a.header("content-type"), Some("application/json"), "{a:?}");
    assert!(
        a.json()["error"].as_str().is_some_and(|m| !m.is_empty()),
        "{a:?}"
    );
}

#[test]
fn values_move_and_writes_need_the_token_and_reach_the_program() {
    let src = temp_file("main.st", PROGRAM);
    let m = Monitor::start(&["--cycle-time", "5ms", "--web-token", TOKEN, &src]);
    let addr = m.addr.as_str();
    let list = get(addr, "/api/variables").json();
    let paths: Vec<&str> = list["variables"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["path"].as_str().unwrap())
        .collect();
    assert_eq!(paths, ["go", "setpoint", "n", "doubled", "running"]);
    let n = &list["variables"][2];
    assert_eq!(
        (n["type"].as_str(), n["direction"].as_str()),
        (Some("DINT"), Some("output"))
    );
    // Two reads 300 ms apart: the counter moved.
    let first: i64 = value(addr, "n").parse().unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let second: i64 = value(addr, "n").parse().unwrap();
    assert!(second > first, "n did not move: {first} then {second}");
    // Search.
    let found = get(addr, "/api/variables?q=DOUB").json();
    assert_eq!(found["variables"].as_array().unwrap().len(), 1);

    // Without the token, or with a wrong one: refused, nothing written.
    let write = json!({"path": "setpoint", "value": "21"});
    let a = post(addr, "/api/write", None, &write);
    refused(&a, 401);
    assert!(
        a.header("www-authenticate")
            .is_some_and(|h| h.starts_with("Bearer"))
    );
    refused(
        &post(addr, "/api/write", Some("wrong-token-42"), &write),
        401,
    );
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(value(addr, "doubled"), "0");
    // With it: written, and the program reacts.
    let a = post(addr, "/api/write", Some(TOKEN), &write);
    assert_eq!(a.status, 200, "{a:?}");
    assert_eq!(a.json()["ok"], true);
    wait_for(addr, "doubled", "42");
    // The other header works too.
    let a = request(
        addr,
        "POST",
        "/api/write",
        &[("X-Plcrun-Token", TOKEN)],
        &json!({"path": "setpoint", "value": 5}).to_string(),
    );
    assert_eq!(a.status, 200, "{a:?}");
    wait_for(addr, "doubled", "10");

    // Force go: the program sees it; a soft write does not beat the force;
    // unforced, go takes the written value.
    let a = post(
        addr,
        "/api/force",
        Some(TOKEN),
        &json!({"path": "go", "value": true}),
    );
    assert_eq!(a.status, 200, "{a:?}");
    wait_for(addr, "running", "TRUE");
    let go = get(addr, "/api/variables/go").json();
    assert_eq!(go["forced"], true, "{go}");
    let forces = get(addr, "/api/forces").json();
    assert_eq!(forces["forces"], json!([{"path": "go", "value": "TRUE"}]));
    let a = post(
        addr,
        "/api/write",
        Some(TOKEN),
        &json!({"path": "go", "value": "FALSE"}),
    );
    assert_eq!(a.status, 200, "{a:?}");
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(value(addr, "running"), "TRUE");
    let a = post(addr, "/api/unforce", Some(TOKEN), &json!({"path": "go"}));
    assert_eq!(a.status, 200, "{a:?}");
    wait_for(addr, "running", "FALSE");
    assert_eq!(get(addr, "/api/variables/go").json()["forced"], false);

    // Bad requests: an HTTP error with a JSON message each.
    refused(
        &post(
            addr,
            "/api/write",
            Some(TOKEN),
            &json!({"path": "nope", "value": "1"}),
        ),
        404,
    );
    refused(
        &post(
            addr,
            "/api/write",
            Some(TOKEN),
            &json!({"path": "setpoint", "value": "abc"}),
        ),
        400,
    );
    refused(
        &post(
            addr,
            "/api/write",
            Some(TOKEN),
            &json!({"path": "setpoint"}),
        ),
        400,
    );
    refused(
        &request(
            addr,
            "POST",
            "/api/force",
            &[("Authorization", &format!("Bearer {TOKEN}"))],
            "{not json",
        ),
        400,
    );
    refused(&get(addr, "/api/variables/nope"), 404);
    refused(&get(addr, "/api/variables/%ZZ"), 400);
    refused(&get(addr, "/api/nothing"), 404);
    refused(&get(addr, "/nothing"), 404);
    refused(&get(addr, "/api/write"), 405);
    refused(&request(addr, "DELETE", "/api/variables", &[], ""), 405);
    refused(&post(addr, "/api/reset", Some(TOKEN), &json!({})), 409);
    refused(
        &post(
            addr,
            "/api/reset",
            Some(TOKEN),
            &json!({"kind": "lukewarm"}),
        ),
        400,
    );

    // The page.
    let page = get(addr, "/");
    assert_eq!(page.status, 200);
    assert!(
        page.header("content-type")
            .unwrap()
            .starts_with("text/html")
    );
    assert!(page.body.contains("<title>plcrun monitor</title>"));

    // The statistics.
    let stats = get(addr, "/api/stats").json();
    assert!(
        stats["tasks"][0]["cycles"].as_u64().unwrap() > 10,
        "{stats}"
    );
    assert_eq!(get(addr, "/api/state").json()["state"], "running");

    // The event stream: every value first, then only what changed.
    let mut events = Events::open(addr, "/api/events");
    assert!(events.head[0].contains("200"), "{:?}", events.head);
    assert!(
        events
            .head
            .iter()
            .any(|h| h.eq_ignore_ascii_case("content-type: text/event-stream"))
    );
    let e1 = events.next();
    assert_eq!(e1["full"], true);
    assert_eq!(e1["changes"].as_array().unwrap().len(), 5, "{e1}");
    let e2 = events.next();
    assert_eq!(e2["full"], false);
    assert!(e2["cycle"].as_u64() > e1["cycle"].as_u64(), "{e1} {e2}");
    // n changes every cycle; setpoint did not.
    let changed: Vec<u64> = e2["changes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c[0].as_u64().unwrap())
        .collect();
    assert!(changed.contains(&2) && !changed.contains(&1), "{e2}");

    assert_eq!(m.stop(), 0, "a clean stop by SIGTERM");
}

#[test]
fn a_token_is_drawn_and_printed_when_none_is_given() {
    let src = temp_file("main.st", PROGRAM);
    let m = Monitor::start(&[&src]);
    let token = m.drawn_token.clone().expect("a token printed");
    assert_eq!(token.len(), 32, "{token}");
    assert!(token.bytes().all(|b| b.is_ascii_hexdigit()), "{token}");
    let write = json!({"path": "setpoint", "value": "3"});
    refused(
        &post(
            &m.addr,
            "/api/write",
            Some("0123456789abcdef0123456789abcdef"),
            &write,
        ),
        401,
    );
    assert_eq!(
        post(&m.addr, "/api/write", Some(&token), &write).status,
        200
    );
    wait_for(&m.addr, "doubled", "6");
}

#[test]
fn a_faulted_plc_is_shown_and_reset_from_the_monitor() {
    // Division by zero once `trip` is written; a reset puts it back.
    let src = temp_file(
        "fault.st",
        "PROGRAM Main
         VAR_INPUT trip : BOOL; END_VAR
         VAR n : INT; z : INT; END_VAR
         n := n + 1;
         IF trip THEN n := n / z; END_IF
         END_PROGRAM",
    );
    let m = Monitor::start(&["--cycle-time", "2ms", "--web-token", TOKEN, &src]);
    // `plcrun health` (the container's health check) says it runs.
    let (code, out, _) = plcrun(&["health", &m.addr]);
    assert_eq!(code, 0, "{out}");
    assert!(out.starts_with("running: cycle "), "{out}");
    refused(&post(&m.addr, "/api/reset", Some(TOKEN), &json!({})), 409);
    let a = post(
        &m.addr,
        "/api/write",
        Some(TOKEN),
        &json!({"path": "trip", "value": true}),
    );
    assert_eq!(a.status, 200, "{a:?}");
    let deadline = Instant::now() + Duration::from_secs(10);
    let state = loop {
        let s = get(&m.addr, "/api/state").json();
        if s["state"] == "faulted" {
            break s;
        }
        assert!(Instant::now() < deadline, "no fault: {s}");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(state["fault"]["code"], "R001", "{state}");
    assert!(
        state["fault"]["message"]
            .as_str()
            .unwrap()
            .contains("fault.st"),
        "{state}"
    );
    let cycle = state["cycle"].as_u64().unwrap();
    let (code, out, _) = plcrun(&["health", &format!("http://{}/", m.addr)]);
    assert_eq!(code, 1, "faulted is unhealthy: {out}");
    assert!(out.starts_with("faulted: R001 in cycle "), "{out}");
    let metrics = get(&m.addr, "/metrics").body;
    assert!(metrics.contains("\nplcrun_faulted 1\n"), "{metrics}");
    // No cycle runs while faulted.
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(
        get(&m.addr, "/api/state").json()["cycle"].as_u64(),
        Some(cycle)
    );
    // Reads still work, changes too; a reset needs the token.
    assert_eq!(value(&m.addr, "trip"), "TRUE");
    refused(
        &post(&m.addr, "/api/reset", None, &json!({"kind": "warm"})),
        401,
    );
    let a = post(
        &m.addr,
        "/api/write",
        Some(TOKEN),
        &json!({"path": "z", "value": "1"}),
    );
    assert_eq!(a.status, 200, "{a:?}");
    let a = post(&m.addr, "/api/reset", Some(TOKEN), &json!({"kind": "cold"}));
    assert_eq!(a.status, 200, "{a:?}");
    // Running again from the start, `trip` back to FALSE.
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let s = get(&m.addr, "/api/state").json();
        if s["state"] == "running" && s["cycle"].as_u64().unwrap() > 10 {
            break;
        }
        assert!(Instant::now() < deadline, "not running again: {s}");
        std::thread::sleep(Duration::from_millis(50));
    }
    assert_eq!(value(&m.addr, "trip"), "FALSE");
    assert_eq!(plcrun(&["health", &m.addr]).0, 0, "healthy again");
    let addr = m.addr.clone();
    assert_eq!(m.stop(), 0, "stopped cleanly after the reset");
    // Nobody answers: unhealthy, saying why.
    let (code, _, err) = plcrun(&["health", &addr, "--timeout", "1s"]);
    assert_eq!(code, 1);
    assert!(err.starts_with(&format!("unreachable: {addr}: ")), "{err}");
}

#[test]
fn the_charts_are_listed_and_drawn_with_their_active_steps() {
    let m = Monitor::start(&["--web-token", TOKEN, "programs/chariot.sfc"]);
    // The initial step is active once the first cycle ran.
    let deadline = Instant::now() + Duration::from_secs(5);
    let charts = loop {
        let c = get(&m.addr, "/api/charts").json();
        if c["cycle"].as_u64() > Some(0) {
            break c;
        }
        assert!(Instant::now() < deadline, "no cycle: {c}");
        std::thread::sleep(Duration::from_millis(50));
    };
    let list = charts["charts"].as_array().unwrap();
    assert_eq!(list.len(), 1, "{charts}");
    assert_eq!(list[0]["path"], "CHARIOT");
    assert!(
        !list[0]["active"].as_array().unwrap().is_empty(),
        "{charts}"
    );
    let svg = get(&m.addr, list[0]["svg"].as_str().unwrap());
    assert_eq!(svg.status, 200);
    assert_eq!(svg.header("content-type"), Some("image/svg+xml"));
    assert!(
        svg.body.contains("<svg") && svg.body.contains("class=\"step initial"),
        "{}",
        &svg.body[..200.min(svg.body.len())]
    );
    refused(&get(&m.addr, "/api/charts/7.svg"), 404);
    refused(&get(&m.addr, "/api/charts/x"), 404);
}

/// One sample of a metrics page.
#[derive(Debug)]
struct Sample {
    name: String,
    labels: BTreeMap<String, String>,
    value: f64,
}

/// A strict reader of the Prometheus text format (0.0.4): every sample
/// belongs to a family announced by `# TYPE` (histograms by their
/// `_bucket`, `_sum` and `_count`), `# HELP` and `# TYPE` come once per
/// family before its samples, names and label names are valid, label
/// values are quoted with only `\\`, `\"` and `\n` escaped, values are
/// floats (or `+Inf`, `-Inf`, `NaN`). Returns the samples and each
/// family's type.
fn parse_metrics(text: &str) -> (Vec<Sample>, BTreeMap<String, String>) {
    let name_ok = |n: &str| {
        let mut chars = n.chars();
        chars
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_' || c == ':')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':')
    };
    let mut types: BTreeMap<String, String> = BTreeMap::new();
    let mut helped: Vec<String> = Vec::new();
    let mut samples = Vec::new();
    assert!(text.ends_with('\n'), "the page ends with a newline");
    for (no, line) in text.lines().enumerate() {
        let at = format!("line {}: {line:?}", no + 1);
        if let Some(rest) = line.strip_prefix("# HELP ") {
            let (name, help) = rest.split_once(' ').expect(&at);
            assert!(name_ok(name) && !help.is_empty(), "{at}");
            assert!(!helped.contains(&name.to_string()), "HELP twice: {at}");
            helped.push(name.to_string());
            continue;
        }
        if let Some(rest) = line.strip_prefix("# TYPE ") {
            let (name, kind) = rest.split_once(' ').expect(&at);
            assert!(name_ok(name), "{at}");
            assert!(
                ["counter", "gauge", "histogram", "summary", "untyped"].contains(&kind),
                "{at}"
            );
            assert!(
                types.insert(name.to_string(), kind.to_string()).is_none(),
                "TYPE twice: {at}"
            );
            assert!(
                !samples.iter().any(|s: &Sample| s.name.starts_with(name)),
                "TYPE after samples: {at}"
            );
            continue;
        }
        assert!(!line.starts_with('#') && !line.is_empty(), "{at}");
        let (series, value) = line.rsplit_once(' ').expect(&at);
        let value: f64 = match value {
            "+Inf" => f64::INFINITY,
            "-Inf" => f64::NEG_INFINITY,
            "NaN" => f64::NAN,
            v => v.parse().unwrap_or_else(|_| panic!("bad value: {at}")),
        };
        let (name, labels) = match series.split_once('{') {
            None => (series, BTreeMap::new()),
            Some((name, rest)) => {
                let body = rest.strip_suffix('}').expect(&at);
                (name, parse_labels(body, &at))
            }
        };
        assert!(name_ok(name), "{at}");
        let family = ["_bucket", "_sum", "_count"]
            .iter()
            .filter_map(|s| name.strip_suffix(s))
            .find(|f| types.get(*f).is_some_and(|t| t == "histogram"))
            .unwrap_or(name);
        assert!(
            types.contains_key(family),
            "sample of no announced family: {at}"
        );
        if name != family {
            assert_eq!(types[family], "histogram", "{at}");
        }
        samples.push(Sample {
            name: name.to_string(),
            labels,
            value,
        });
    }
    (samples, types)
}

/// `a="x",b="y"`, strictly.
fn parse_labels(body: &str, at: &str) -> BTreeMap<String, String> {
    let mut labels = BTreeMap::new();
    let mut rest = body;
    while !rest.is_empty() {
        let (name, after) = rest.split_once("=\"").expect(at);
        assert!(
            !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'),
            "{at}"
        );
        let mut value = String::new();
        let mut chars = after.char_indices();
        let end = loop {
            match chars.next().expect(at) {
                (i, '"') => break i,
                (_, '\\') => match chars.next().expect(at).1 {
                    '\\' => value.push('\\'),
                    '"' => value.push('"'),
                    'n' => value.push('\n'),
                    c => panic!("bad escape \\{c}: {at}"),
                },
                (_, c) => value.push(c),
            }
        };
        assert!(
            labels.insert(name.to_string(), value).is_none(),
            "label twice: {at}"
        );
        rest = &after[end + 1..];
        if let Some(r) = rest.strip_prefix(',') {
            rest = r;
        } else {
            assert!(rest.is_empty(), "{at}");
        }
    }
    labels
}

#[test]
fn metrics_parse_as_prometheus_text_with_cumulative_histograms() {
    let src = temp_file("main.st", PROGRAM);
    let modbus_port = "127.0.0.1:0";
    let m = Monitor::start(&[
        "--cycle-time",
        "2ms",
        "--web-token",
        TOKEN,
        "--modbus",
        modbus_port,
        &src,
    ]);
    std::thread::sleep(Duration::from_millis(400));
    let a = get(&m.addr, "/metrics");
    assert_eq!(a.status, 200);
    assert!(
        a.header("content-type")
            .unwrap()
            .starts_with("text/plain; version=0.0.4")
    );
    let (samples, types) = parse_metrics(&a.body);
    let one = |name: &str| {
        samples
            .iter()
            .find(|s| s.name == name)
            .unwrap_or_else(|| panic!("no {name} in\n{}", a.body))
    };
    assert_eq!(types["plcrun_task_cycles_total"], "counter");
    let cycles = one("plcrun_task_cycles_total");
    let task = get(&m.addr, "/api/stats").json()["tasks"][0]["name"].clone();
    assert_eq!(json!(cycles.labels["task"]), task);
    assert!(cycles.value > 20.0, "{cycles:?}");
    assert_eq!(one("plcrun_faulted").value, 0.0);
    assert_eq!(one("plcrun_modbus_clients").value, 0.0);
    for family in [
        "plcrun_task_execution_seconds",
        "plcrun_task_start_jitter_seconds",
    ] {
        assert_eq!(types[family], "histogram");
        let buckets: Vec<&Sample> = samples
            .iter()
            .filter(|s| s.name == format!("{family}_bucket"))
            .collect();
        let count = one(&format!("{family}_count")).value;
        assert!(count > 20.0, "{family}: {count}");
        let mut last = (f64::NEG_INFINITY, 0.0);
        for b in &buckets {
            let le: f64 = match b.labels["le"].as_str() {
                "+Inf" => f64::INFINITY,
                v => v.parse().unwrap(),
            };
            assert!(
                le > last.0 && b.value >= last.1,
                "{family}: not cumulative at {b:?}"
            );
            last = (le, b.value);
        }
        assert_eq!(last, (f64::INFINITY, count), "{family}: +Inf is the count");
        assert!(one(&format!("{family}_sum")).value > 0.0);
    }
    // A parser that accepts anything would not be worth its name.
    for bad in [
        "x 1\n",
        "# TYPE x counter\nx{a=\"1} 1\n",
        "# TYPE x counter\nx 1\n# TYPE x counter\n",
        "# TYPE x counter\nx one\n",
    ] {
        assert!(
            std::panic::catch_unwind(|| parse_metrics(bad)).is_err(),
            "{bad:?} accepted"
        );
    }
}

#[test]
fn bad_settings_are_usage_errors() {
    let src = temp_file("main.st", PROGRAM);
    let (code, _, err) =
        crate::support::cli::plcrun(&["--web", "127.0.0.1:0", "--cycles", "3", &src]);
    assert_eq!(code, 2, "--web needs --realtime: {err}");
    let (code, _, err) = crate::support::cli::plcrun(&[
        "--realtime",
        "--web",
        "127.0.0.1:0",
        "--web-token",
        "short",
        "--cycles",
        "3",
        &src,
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("E961"), "{err}");
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = taken.local_addr().unwrap().to_string();
    let (code, _, err) =
        crate::support::cli::plcrun(&["--realtime", "--web", &addr, "--cycles", "3", &src]);
    assert_eq!(code, 2);
    assert!(err.contains("E962") && err.contains(&addr), "{err}");
    let (code, _, err) = crate::support::cli::plcrun(&[
        "--realtime",
        "--web",
        "127.0.0.1:0",
        "--reload",
        "--cycles",
        "3",
        &src,
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--reload cannot be combined with --web"),
        "{err}"
    );
}
