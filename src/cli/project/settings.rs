//! The checked values of a project file, mapped onto [`RunArgs`]: every
//! key lands on the field its command-line flag fills, after the checks
//! the run would make, so that a bad value is reported at its place in
//! the file.

use super::errors::{BAD_VALUE, NO_SOURCE, ProjectError, WRONG_TYPE};
use super::schema::{Modbus, OpcUa, ProjectFile, RealTime, Retain, Trace, Web};
use super::{Project, paths};
use crate::cli::args::{RunArgs, StatsFormat};
use clap::{Args, FromArgMatches};
use plcrun::{Addressing, SourceEncoding, parse_time_literal};
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// One `NAME = value` of `[set]` or `[force]`, with its place, so that a
/// name the program does not have can be reported there.
#[derive(Debug, Clone)]
pub struct Assignment {
    /// `"set"` or `"force"`.
    pub table: &'static str,
    /// The variable's path.
    pub name: String,
    /// The value as an IEC literal.
    pub literal: String,
    /// The value's bytes in the file.
    pub span: Range<usize>,
}

/// The default address of the web monitor.
const WEB_DEFAULT: &str = "127.0.0.1:8080";

/// `RunArgs` as the command line fills it with no flag, for `files`.
pub fn default_run_args(files: &[PathBuf]) -> Result<RunArgs, String> {
    let command = RunArgs::augment_args(clap::Command::new("plcrun-project")).no_binary_name(true);
    let mut argv: Vec<std::ffi::OsString> = vec!["--".into()];
    argv.extend(files.iter().map(|f| f.as_os_str().to_owned()));
    if files.is_empty() {
        argv.push("-".into()); // `files` is required: replaced below
    }
    let matches = command
        .try_get_matches_from(argv)
        .map_err(|e| e.to_string())?;
    let mut args = RunArgs::from_arg_matches(&matches).map_err(|e| e.to_string())?;
    args.files = files.to_vec();
    Ok(args)
}

/// Checks every value of `file` (read from `path`, in `folder`) and fills
/// the options; every error found, when there is one.
pub fn resolve(
    path: &Path,
    folder: &Path,
    file: ProjectFile,
) -> Result<Project, Vec<ProjectError>> {
    let mut errors = Vec::new();
    let sources_span = file.sources.span();
    let sources = paths::sources(folder, file.sources.get_ref(), &mut errors);
    if errors.is_empty() && sources.is_empty() {
        errors.push(
            ProjectError::at(
                NO_SOURCE,
                sources_span,
                "`sources` names no file: the list is empty or its patterns match nothing",
            )
            .note(format!("patterns are relative to `{}`", folder.display())),
        );
    }
    let mut run = match default_run_args(&sources) {
        Ok(run) => run,
        Err(e) => return Err(vec![ProjectError::whole(BAD_VALUE, e)]),
    };
    // `serve` runs in real time; `check`, `test` and `compare` ignore it.
    run.realtime = true;
    let mut assignments = Vec::new();
    let mut into = Filler {
        folder,
        errors: &mut errors,
    };
    into.top_level(&file, &mut run);
    if let Some(t) = &file.realtime {
        into.realtime(t.get_ref(), &mut run);
    }
    if let Some(r) = &file.retain {
        into.retain(r.get_ref(), &mut run);
    }
    if let Some(set) = &file.set {
        run.set = into.assignments("set", set, &mut assignments);
    }
    if let Some(force) = &file.force {
        run.force = into.assignments("force", force, &mut assignments);
    }
    if let Some(t) = &file.trace {
        into.trace(t.get_ref(), &mut run);
    }
    if let Some(m) = &file.modbus {
        into.modbus(m.get_ref(), &mut run);
    }
    if let Some(o) = &file.opcua {
        into.opcua(o, &mut run);
    }
    if let Some(w) = &file.web {
        into.web(w.get_ref(), &mut run);
    }
    if errors.is_empty() {
        Ok(Project {
            path: path.to_path_buf(),
            sources,
            run,
            traced: file.trace.is_some(),
            assignments,
        })
    } else {
        Err(errors)
    }
}

/// Fills [`RunArgs`] from the tables, collecting errors.
struct Filler<'a> {
    folder: &'a Path,
    errors: &'a mut Vec<ProjectError>,
}

impl Filler<'_> {
    fn bad(&mut self, span: Range<usize>, message: String) {
        self.errors.push(ProjectError::at(BAD_VALUE, span, message));
    }

    fn path(&self, text: &str) -> PathBuf {
        paths::resolve(self.folder, text)
    }

    /// A duration for `key`, checked as the run checks its flag.
    fn duration(
        &mut self,
        key: &str,
        value: &Spanned<String>,
        zero_allowed: bool,
    ) -> Option<String> {
        let text = value.get_ref().trim();
        let parsed = if zero_allowed && text == "0" {
            Ok(0)
        } else {
            parse_time_literal(text)
        };
        match parsed {
            Ok(0) if zero_allowed => Some(text.to_string()),
            Ok(ns) if ns > 0 => Some(text.to_string()),
            Ok(_) => {
                let want = if zero_allowed {
                    "0 or more"
                } else {
                    "positive"
                };
                self.bad(
                    value.span(),
                    format!("`{key}` must be {want}, not `{text}`"),
                );
                None
            }
            Err(e) => {
                self.bad(
                    value.span(),
                    format!(
                        "`{key}`: `{text}` is not a duration ({e}); write e.g. \"10ms\" or \"T#1s\""
                    ),
                );
                None
            }
        }
    }

    /// An integer for `key` within `range`.
    fn integer(&mut self, key: &str, value: &Spanned<i64>, low: i64, high: i64) -> Option<u64> {
        let n = *value.get_ref();
        if (low..=high).contains(&n) {
            u64::try_from(n).ok()
        } else {
            self.bad(
                value.span(),
                format!("`{key}` must be from {low} to {high}, not {n}"),
            );
            None
        }
    }

    /// A `HOST:PORT` for `key` (a port alone too when `port_alone`).
    fn address(&mut self, key: &str, value: &Spanned<String>, port_alone: bool) -> Option<String> {
        let text = value.get_ref().trim();
        let port = match text.rsplit_once(':') {
            Some((host, port)) if !host.is_empty() => port,
            Some(_) => "",
            None if port_alone => text,
            None => "",
        };
        if port.parse::<u16>().is_ok() {
            Some(text.to_string())
        } else {
            let form = if port_alone {
                "HOST:PORT or a port"
            } else {
                "HOST:PORT"
            };
            self.bad(
                value.span(),
                format!("`{key}`: `{text}` is not {form} (e.g. \"127.0.0.1:502\")"),
            );
            None
        }
    }

    fn top_level(&mut self, file: &ProjectFile, run: &mut RunArgs) {
        if let Some(program) = &file.program {
            if program.get_ref().trim().is_empty() {
                self.bad(program.span(), "`program` is empty".into());
            }
            run.program = Some(program.get_ref().trim().to_string());
        }
        if let Some(v) = &file.cycle_time
            && let Some(text) = self.duration("cycle_time", v, false)
        {
            run.cycle_time = text;
        }
        if let Some(v) = &file.watchdog
            && let Some(text) = self.duration("watchdog", v, true)
        {
            run.watchdog = text;
        }
        run.grafcet = file.grafcet.unwrap_or(run.grafcet);
        run.no_optimize = !file.optimize.unwrap_or(!run.no_optimize);
        if let Some(v) = &file.max_data_mib
            && let Some(n) = self.integer("max_data_mib", v, 1, 2048)
        {
            run.max_data_mib = n;
        }
        if let Some(v) = &file.encoding {
            match v.get_ref().parse::<SourceEncoding>() {
                Ok(e) => run.reading.encoding = e,
                Err(e) => self.bad(v.span(), format!("`encoding`: {e}")),
            }
        }
        if let Some(v) = &file.addressing {
            match v.get_ref().parse::<Addressing>() {
                Ok(a) => run.reading.addressing = Some(a),
                Err(e) => self.bad(v.span(), format!("`addressing`: {e}")),
            }
        }
        run.reading.strict = file.strict.unwrap_or(run.reading.strict);
        if let Some(v) = &file.stimulus {
            run.stimulus = Some(self.path(v.get_ref()));
        }
        run.reload = file.reload.unwrap_or(run.reload);
        if let Some(v) = &file.stats {
            match v.get_ref().as_str() {
                "off" => run.stats = false,
                "text" => (run.stats, run.stats_format) = (true, StatsFormat::Text),
                "json" => (run.stats, run.stats_format) = (true, StatsFormat::Json),
                other => self.bad(
                    v.span(),
                    format!("`stats`: `{other}` is not one of \"off\", \"text\", \"json\""),
                ),
            }
        }
    }

    fn realtime(&mut self, t: &RealTime, run: &mut RunArgs) {
        if let Some(v) = &t.priority {
            run.rt_priority = self
                .integer("realtime.priority", v, 1, 99)
                .and_then(|n| u8::try_from(n).ok());
        }
        if let Some(v) = &t.cpu {
            run.cpu = self
                .integer("realtime.cpu", v, 0, 4095)
                .and_then(|n| usize::try_from(n).ok());
        }
        run.no_lock_memory = !t.lock_memory.unwrap_or(true);
        run.allow_cpu_sleep = t.cpu_sleep.unwrap_or(false);
    }

    fn retain(&mut self, r: &Retain, run: &mut RunArgs) {
        if r.file.get_ref().trim().is_empty() {
            self.bad(r.file.span(), "`retain.file` is empty".into());
        }
        run.retain = Some(self.path(r.file.get_ref()));
        if let Some(v) = &r.every
            && let Some(n) = self.integer("retain.every", v, 1, i64::MAX)
        {
            run.retain_every = n;
        }
        run.retain_partial = r.partial.unwrap_or(false);
    }

    /// `[set]` or `[force]`: `NAME = value` lines as `NAME=VALUE` items.
    /// Dotted names (`main.valve = true`) read as TOML nests them.
    fn assignments(
        &mut self,
        table: &'static str,
        entries: &Spanned<BTreeMap<String, Spanned<toml::Value>>>,
        placed: &mut Vec<Assignment>,
    ) -> Vec<String> {
        let mut items = Vec::new();
        for (name, value) in entries.get_ref() {
            let before = items.len();
            self.assignment(table, name, value.get_ref(), value.span(), &mut items);
            for item in &items[before..] {
                if let Some((name, literal)) = item.split_once('=') {
                    placed.push(Assignment {
                        table,
                        name: name.to_string(),
                        literal: literal.to_string(),
                        span: value.span(),
                    });
                }
            }
        }
        items
    }

    fn assignment(
        &mut self,
        table: &str,
        name: &str,
        value: &toml::Value,
        span: Range<usize>,
        items: &mut Vec<String>,
    ) {
        let literal = match value {
            toml::Value::Boolean(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
            toml::Value::Integer(n) => n.to_string(),
            toml::Value::Float(x) if x.is_finite() => format!("{x:?}"),
            toml::Value::String(s) => s.clone(),
            toml::Value::Table(inner) => {
                for (field, v) in inner {
                    self.assignment(table, &format!("{name}.{field}"), v, span.clone(), items);
                }
                return;
            }
            other => {
                self.errors.push(ProjectError::at(
                    WRONG_TYPE,
                    span,
                    format!(
                        "`{table}.{name}`: {} {} is not a value; give a boolean, a number or an IEC literal in a string (\"T#5s\")",
                        if other.type_str().starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" },
                        other.type_str()
                    ),
                ));
                return;
            }
        };
        items.push(format!("{name}={literal}"));
    }

    fn trace(&mut self, t: &Trace, run: &mut RunArgs) {
        if let Some(names) = &t.variables {
            run.trace = names.clone();
        }
        if let Some(v) = &t.format {
            let text = v.get_ref().as_str();
            if ["table", "csv", "jsonl", "vcd"].contains(&text) {
                run.format = text.to_string();
            } else {
                self.bad(
                    v.span(),
                    format!("`trace.format`: `{text}` is not one of \"csv\", \"table\", \"jsonl\", \"vcd\""),
                );
            }
        }
        run.changes_only = t.changes_only.unwrap_or(false);
        if let Some(v) = &t.output {
            run.output = Some(self.path(v.get_ref()));
        }
    }

    fn modbus(&mut self, m: &Modbus, run: &mut RunArgs) {
        run.modbus = self.address("modbus.listen", &m.listen, false);
        if let Some(v) = &m.max_clients
            && let Some(n) = self.integer("modbus.max_clients", v, 1, 9_999)
        {
            run.modbus_max_clients = n;
        }
        if let Some(v) = &m.idle_timeout
            && let Some(text) = self.duration("modbus.idle_timeout", v, false)
        {
            run.modbus_idle_timeout = text;
        }
    }

    #[cfg(feature = "opcua")]
    fn opcua(&mut self, o: &Spanned<OpcUa>, run: &mut RunArgs) {
        let o = o.get_ref();
        let args = &mut run.opcua;
        args.opcua = self.address("opcua.listen", &o.listen, true);
        args.opcua_expose = o.expose.clone().unwrap_or_default();
        args.opcua_users = o.users.as_ref().map(|u| self.path(u.get_ref()));
        // The default folder too is the project's, not the current one.
        let pki = o.pki.as_ref().map_or("opcua-pki", |p| p.get_ref().as_str());
        args.opcua_pki = self.path(pki);
        args.opcua_allow_insecure = o.allow_insecure.unwrap_or(false);
        args.opcua_trust_clients = o.trust_clients.unwrap_or(false);
    }

    #[cfg(not(feature = "opcua"))]
    fn opcua(&mut self, o: &Spanned<OpcUa>, _run: &mut RunArgs) {
        use super::errors::NOT_BUILT;
        self.errors.push(ProjectError::at(
            NOT_BUILT,
            o.span(),
            "`[opcua]`: this plcrun was built without OPC UA (cargo feature `opcua`)",
        ));
    }

    fn web(&mut self, w: &Web, run: &mut RunArgs) {
        let listen = match &w.listen {
            Some(v) => self
                .address("web.listen", v, false)
                .unwrap_or_else(|| WEB_DEFAULT.to_string()),
            None => WEB_DEFAULT.to_string(),
        };
        let token = w.token.as_ref().map(|t| {
            let text = t.get_ref();
            if text.len() < 8 || text.chars().any(|c| c.is_whitespace() || c.is_control()) {
                self.bad(
                    t.span(),
                    "`web.token` must be at least 8 characters, without spaces".into(),
                );
            }
            text.clone()
        });
        run.web = Some(listen);
        run.web_token = token;
    }
}
