//! `/metrics`: the run in the Prometheus text exposition format (version
//! 0.0.4): per task cycles, overruns, and histograms of execution time and
//! start jitter; the PLC's state; the monitor's own counters; and the
//! Modbus and OPC UA servers' counters when they run.

use super::state::Shared;
use plcrun::{Histogram, TaskHistograms};
use std::fmt::Write as _;
use std::sync::atomic::Ordering;

/// Metric lines of another server, appended to the page.
pub(super) type Source = Box<dyn Fn(&mut Page) + Send + Sync>;

/// The page being written: each family once, with its HELP and TYPE.
#[derive(Debug, Default)]
pub(super) struct Page {
    text: String,
}

impl Page {
    /// Starts a family.
    pub(super) fn family(&mut self, name: &str, kind: &str, help: &str) {
        let _ = writeln!(self.text, "# HELP {name} {help}");
        let _ = writeln!(self.text, "# TYPE {name} {kind}");
    }

    /// One sample, with its labels (`name="value"` pairs).
    pub(super) fn sample(&mut self, name: &str, labels: &[(&str, &str)], value: f64) {
        self.text.push_str(name);
        if !labels.is_empty() {
            self.text.push('{');
            for (i, (k, v)) in labels.iter().enumerate() {
                if i > 0 {
                    self.text.push(',');
                }
                let _ = write!(self.text, "{k}=\"{}\"", escape(v));
            }
            self.text.push('}');
        }
        let _ = writeln!(self.text, " {}", number(value));
    }

    /// A family of one unlabelled sample.
    pub(super) fn single(&mut self, name: &str, kind: &str, help: &str, value: f64) {
        self.family(name, kind, help);
        self.sample(name, &[], value);
    }
}

/// A label value with `\`, `"` and newlines escaped.
fn escape(v: &str) -> String {
    v.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', "\\n")
}

/// A sample value as the format writes it (`+Inf`, `NaN`, integers
/// without a fraction).
fn number(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "+Inf" } else { "-Inf" }.into()
    } else if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

/// Nanoseconds as seconds.
fn seconds(ns: f64) -> f64 {
    ns / 1e9
}

/// The whole page.
pub(super) fn render(shared: &Shared) -> String {
    let mut page = Page::default();
    let snapshot = shared.snapshot();
    page.single(
        "plcrun_cycle",
        "gauge",
        "The PLC's cycle counter at the last published cycle.",
        snapshot.cycle as f64,
    );
    page.single(
        "plcrun_faulted",
        "gauge",
        "1 when a runtime fault stopped the PLC, 0 while it runs.",
        f64::from(u8::from(snapshot.fault.is_some())),
    );
    if let Some(stats) = shared.stats.get() {
        tasks(&mut page, stats);
    }
    monitor(&mut page, shared);
    let sources = shared
        .extra_metrics
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    for source in sources.iter() {
        source(&mut page);
    }
    page.text
}

/// The per-task families.
fn tasks(page: &mut Page, stats: &plcrun::TaskStatsHandle) {
    let snapshot = stats.snapshot();
    page.family(
        "plcrun_task_cycles_total",
        "counter",
        "Activations of the task.",
    );
    for t in &snapshot {
        page.sample(
            "plcrun_task_cycles_total",
            &[("task", &t.name)],
            t.cycles as f64,
        );
    }
    page.family(
        "plcrun_task_overruns_total",
        "counter",
        "Activations missed because the runtime was still busy.",
    );
    for t in &snapshot {
        page.sample(
            "plcrun_task_overruns_total",
            &[("task", &t.name)],
            t.overruns as f64,
        );
    }
    let histograms = stats.histograms();
    let families: [(&str, &str, Pick); 2] = [
        (
            "plcrun_task_execution_seconds",
            "How long the task's programs ran per activation.",
            execution,
        ),
        (
            "plcrun_task_start_jitter_seconds",
            "How late each activation started after its deadline.",
            start_jitter,
        ),
    ];
    for (name, help, pick) in families {
        page.family(name, "histogram", help);
        for t in &histograms {
            let h = pick(t);
            let bucket = format!("{name}_bucket");
            for &(bound, n) in &h.buckets {
                let le = number(seconds(bound as f64));
                page.sample(&bucket, &[("task", &t.name), ("le", &le)], n as f64);
            }
            page.sample(
                &bucket,
                &[("task", &t.name), ("le", "+Inf")],
                h.count as f64,
            );
            page.sample(
                &format!("{name}_sum"),
                &[("task", &t.name)],
                seconds(h.sum_ns as f64),
            );
            page.sample(
                &format!("{name}_count"),
                &[("task", &t.name)],
                h.count as f64,
            );
        }
    }
}

/// Which histogram of a task a family shows.
type Pick = fn(&TaskHistograms) -> &Histogram;

fn execution(h: &TaskHistograms) -> &Histogram {
    &h.execution
}

fn start_jitter(h: &TaskHistograms) -> &Histogram {
    &h.start_jitter
}

/// The monitor's own counters.
fn monitor(page: &mut Page, shared: &Shared) {
    let c = &shared.counters;
    let get = |a: &std::sync::atomic::AtomicU64| a.load(Ordering::Relaxed) as f64;
    page.single(
        "plcrun_web_requests_total",
        "counter",
        "HTTP requests the web monitor answered.",
        get(&c.requests),
    );
    page.single(
        "plcrun_web_streams",
        "gauge",
        "Event streams (/api/events) open now.",
        get(&c.streams),
    );
    page.single(
        "plcrun_web_commands_total",
        "counter",
        "Writes, forces, unforces and resets carried out between cycles.",
        get(&c.commands),
    );
    page.single(
        "plcrun_web_refused_total",
        "counter",
        "Changes refused for want of the token.",
        get(&c.refused),
    );
    page.single(
        "plcrun_web_publishes_total",
        "counter",
        "Snapshots of the variables published by the scan.",
        get(&c.publishes),
    );
}

/// The Modbus server's counters.
pub(super) fn modbus(server: std::sync::Arc<plcrun::ModbusServer>) -> Source {
    Box::new(move |page: &mut Page| {
        let s = server.stats();
        page.single(
            "plcrun_modbus_clients",
            "gauge",
            "Modbus TCP connections open now.",
            s.connections_open as f64,
        );
        page.single(
            "plcrun_modbus_connections_total",
            "counter",
            "Modbus TCP connections accepted.",
            s.connections_accepted as f64,
        );
        page.single(
            "plcrun_modbus_requests_total",
            "counter",
            "Modbus requests answered (exceptions included).",
            s.requests as f64,
        );
        page.single(
            "plcrun_modbus_exceptions_total",
            "counter",
            "Modbus exception responses.",
            s.exceptions as f64,
        );
        page.single(
            "plcrun_modbus_writes_applied_total",
            "counter",
            "Modbus client writes applied between cycles.",
            s.writes_applied as f64,
        );
    })
}

/// The OPC UA server's counters.
#[cfg(feature = "opcua")]
pub(super) fn opcua(server: std::sync::Arc<plcrun::OpcUaServer>) -> Source {
    Box::new(move |page: &mut Page| {
        let s = server.stats();
        page.single(
            "plcrun_opcua_values_changed_total",
            "counter",
            "OPC UA values that changed between two frames the server took in.",
            s.values_changed as f64,
        );
        page.single(
            "plcrun_opcua_writes_applied_total",
            "counter",
            "OPC UA client writes applied between cycles.",
            s.writes_applied as f64,
        );
        page.single(
            "plcrun_opcua_writes_refused_total",
            "counter",
            "OPC UA client writes refused because the queue was full.",
            s.writes_refused_busy as f64,
        );
        page.single(
            "plcrun_opcua_sessions",
            "gauge",
            "OPC UA client sessions open now.",
            s.sessions as f64,
        );
        page.single(
            "plcrun_opcua_sessions_total",
            "counter",
            "OPC UA client sessions created since the server started.",
            s.sessions_total as f64,
        );
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_written_in_the_text_format() {
        let mut page = Page::default();
        page.family("x_total", "counter", "An example.");
        page.sample("x_total", &[("task", "a\"b")], 3.0);
        page.sample("x_total", &[], 0.25);
        page.sample("x_total", &[("le", "+Inf")], f64::INFINITY);
        assert_eq!(
            page.text,
            "# HELP x_total An example.\n# TYPE x_total counter\n\
             x_total{task=\"a\\\"b\"} 3\nx_total 0.25\nx_total{le=\"+Inf\"} +Inf\n"
        );
    }
}
