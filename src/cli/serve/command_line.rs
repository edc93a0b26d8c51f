//! The `plcrun run` command a project amounts to, printed by `plcrun serve
//! --check`: the file's settings said in the flags they stand for (those
//! that differ from the flags' defaults).

use super::super::args::{RunArgs, StatsFormat};
use super::super::project::default_run_args;
use std::path::Path;

/// `plcrun run FLAGS... -- FILES...`, each word quoted when needed.
pub fn command_line(run: &RunArgs) -> String {
    let defaults = default_run_args(&[]).ok();
    let mut words: Vec<String> = vec!["plcrun".into(), "run".into()];
    let mut flag = |name: &str, value: Option<String>| {
        words.push(format!("--{name}"));
        if let Some(value) = value {
            words.push(value);
        }
    };
    let path = |p: &Path| p.display().to_string();
    macro_rules! changed {
        ($($field:ident).+) => {
            defaults.as_ref().is_none_or(|d| d.$($field).+ != run.$($field).+)
        };
    }
    if let Some(n) = run.cycles {
        flag("cycles", Some(n.to_string()));
    }
    if run.realtime {
        flag("realtime", None);
    }
    if changed!(cycle_time) {
        flag("cycle-time", Some(run.cycle_time.clone()));
    }
    if let Some(p) = &run.program {
        flag("program", Some(p.clone()));
    }
    if changed!(watchdog) {
        flag("watchdog", Some(run.watchdog.clone()));
    }
    if run.grafcet {
        flag("grafcet", None);
    }
    if run.no_optimize {
        flag("no-optimize", None);
    }
    if changed!(max_data_mib) {
        flag("max-data-mib", Some(run.max_data_mib.to_string()));
    }
    if changed!(reading.encoding) {
        flag("encoding", Some(run.reading.encoding.name().to_string()));
    }
    if let Some(a) = run.reading.addressing {
        flag("addressing", Some(a.to_string()));
    }
    if run.reading.strict {
        flag("strict", None);
    }
    if let Some(p) = &run.stimulus {
        flag("stimulus", Some(path(p)));
    }
    if run.reload {
        flag("reload", None);
    }
    if run.stats {
        flag("stats", None);
        if run.stats_format == StatsFormat::Json {
            flag("stats-format", Some("json".into()));
        }
    }
    if let Some(n) = run.rt_priority {
        flag("rt-priority", Some(n.to_string()));
    }
    if let Some(n) = run.cpu {
        flag("cpu", Some(n.to_string()));
    }
    if run.no_lock_memory {
        flag("no-lock-memory", None);
    }
    if run.allow_cpu_sleep {
        flag("allow-cpu-sleep", None);
    }
    if let Some(p) = &run.retain {
        flag("retain", Some(path(p)));
        if changed!(retain_every) {
            flag("retain-every", Some(run.retain_every.to_string()));
        }
    }
    if run.cold {
        flag("cold", None);
    }
    if run.retain_partial {
        flag("retain-partial", None);
    }
    for item in &run.set {
        flag("set", Some(item.clone()));
    }
    for item in &run.force {
        flag("force", Some(item.clone()));
    }
    if run.no_trace {
        flag("no-trace", None);
    }
    if !run.trace.is_empty() {
        flag("trace", Some(run.trace.join(",")));
    }
    if changed!(format) {
        flag("format", Some(run.format.clone()));
    }
    if run.changes_only {
        flag("changes-only", None);
    }
    if let Some(p) = &run.output {
        flag("output", Some(path(p)));
    }
    if let Some(a) = &run.modbus {
        flag("modbus", Some(a.clone()));
        if changed!(modbus_max_clients) {
            flag(
                "modbus-max-clients",
                Some(run.modbus_max_clients.to_string()),
            );
        }
        if changed!(modbus_idle_timeout) {
            flag("modbus-idle-timeout", Some(run.modbus_idle_timeout.clone()));
        }
    }
    if let Some(a) = &run.web {
        flag("web", Some(a.clone()));
        if let Some(t) = &run.web_token {
            flag("web-token", Some(t.clone()));
        }
    }
    #[cfg(feature = "opcua")]
    if let Some(a) = &run.opcua.opcua {
        flag("opcua", Some(a.clone()));
        for glob in &run.opcua.opcua_expose {
            flag("opcua-expose", Some(glob.clone()));
        }
        if let Some(p) = &run.opcua.opcua_users {
            flag("opcua-users", Some(path(p)));
        }
        if changed!(opcua.opcua_pki) {
            flag("opcua-pki", Some(path(&run.opcua.opcua_pki)));
        }
        if run.opcua.opcua_allow_insecure {
            flag("opcua-allow-insecure", None);
        }
        if run.opcua.opcua_trust_clients {
            flag("opcua-trust-clients", None);
        }
    }
    words.push("--".into());
    words.extend(run.files.iter().map(|f| path(f)));
    words
        .iter()
        .map(|w| quoted(w))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `word` as a POSIX shell reads it back.
fn quoted(word: &str) -> String {
    let plain = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./:=,#@%+".contains(c));
    if plain {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}
