//! The keys of `plcrun.toml` as serde reads them (docs/project-file.md).
//! Every table refuses keys it does not know; values keep their place in
//! the file so that a bad one is reported at its line and column.

use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectFile {
    /// Source files, folders, `.plcproj` files or globs, relative to the
    /// file's folder.
    pub sources: Spanned<Vec<Spanned<String>>>,
    /// The PROGRAM to run when the sources hold several and no configuration.
    pub program: Option<Spanned<String>>,
    /// Cycle time of the implicit task (`"10ms"`, `"T#100ms"`).
    pub cycle_time: Option<Spanned<String>>,
    /// Wall-clock limit of one cycle; `"0"` turns it off.
    pub watchdog: Option<Spanned<String>>,
    /// IEC 60848 GRAFCET evolution of the charts.
    pub grafcet: Option<bool>,
    /// `false` runs on the plain instruction forms (`--no-optimize`).
    pub optimize: Option<bool>,
    /// Most MiB of program data.
    pub max_data_mib: Option<Spanned<i64>>,
    /// How the sources are encoded (`--encoding`).
    pub encoding: Option<Spanned<String>>,
    /// How direct addresses are numbered (`--addressing`).
    pub addressing: Option<Spanned<String>>,
    /// Compatibility warnings are errors (`--strict`).
    pub strict: Option<bool>,
    /// Stimulus CSV file.
    pub stimulus: Option<Spanned<String>>,
    /// Watch the sources and load new versions by online change.
    pub reload: Option<bool>,
    /// Statistics printed when the run ends: `"off"`, `"text"`, `"json"`.
    pub stats: Option<Spanned<String>>,
    /// Scheduling of the cycle's thread.
    pub realtime: Option<Spanned<RealTime>>,
    /// Retained variables.
    pub retain: Option<Spanned<Retain>>,
    /// Initial values, applied before the first cycle.
    pub set: Option<Spanned<BTreeMap<String, Spanned<toml::Value>>>>,
    /// Values forced from the start.
    pub force: Option<Spanned<BTreeMap<String, Spanned<toml::Value>>>>,
    /// The trace (none unless this table is given).
    pub trace: Option<Spanned<Trace>>,
    /// The Modbus TCP server.
    pub modbus: Option<Spanned<Modbus>>,
    /// The OPC UA server.
    pub opcua: Option<Spanned<OpcUa>>,
    /// The web monitor (docs/web.md).
    pub web: Option<Spanned<Web>>,
}

/// `[realtime]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RealTime {
    /// SCHED_FIFO priority, 1-99.
    pub priority: Option<Spanned<i64>>,
    /// The only CPU the cycle's thread runs on (0-based).
    pub cpu: Option<Spanned<i64>>,
    /// Lock the process's memory (default true).
    pub lock_memory: Option<bool>,
    /// Let idle CPUs sleep deeply (default false).
    pub cpu_sleep: Option<bool>,
}

/// `[retain]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Retain {
    /// The retained data file.
    pub file: Spanned<String>,
    /// Save every N cycles (default 10).
    pub every: Option<Spanned<i64>>,
    /// Restore what still fits a changed program.
    pub partial: Option<bool>,
}

/// `[trace]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Trace {
    /// The traced variables (default: outputs and %Q).
    pub variables: Option<Vec<String>>,
    /// `"csv"`, `"table"`, `"jsonl"` or `"vcd"`.
    pub format: Option<Spanned<String>>,
    /// Rows only when a value changed.
    pub changes_only: Option<bool>,
    /// Where the trace goes (default standard output).
    pub output: Option<Spanned<String>>,
}

/// `[modbus]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Modbus {
    /// `ADDR:PORT` to listen on.
    pub listen: Spanned<String>,
    /// Clients connected at once.
    pub max_clients: Option<Spanned<i64>>,
    /// Idle connections are closed after this long.
    pub idle_timeout: Option<Spanned<String>>,
}

/// `[opcua]` (read in every build, so that its keys are checked; used
/// only with the `opcua` feature).
#[derive(Debug, Deserialize)]
#[cfg_attr(not(feature = "opcua"), allow(dead_code))]
#[serde(deny_unknown_fields)]
pub struct OpcUa {
    /// `ADDR:PORT` or a port alone.
    pub listen: Spanned<String>,
    /// Globs of the served variables.
    pub expose: Option<Vec<String>>,
    /// The users file.
    pub users: Option<Spanned<String>>,
    /// The certificate folder.
    pub pki: Option<Spanned<String>>,
    /// Also serve the None security policy.
    pub allow_insecure: Option<bool>,
    /// Accept every client certificate.
    pub trust_clients: Option<bool>,
}

/// `[web]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Web {
    /// `ADDR:PORT` the monitor will listen on.
    pub listen: Option<Spanned<String>>,
    /// The token that will allow writes.
    pub token: Option<Spanned<String>>,
}
