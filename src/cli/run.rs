//! The `run` and `check` commands.

use super::args::{CheckArgs, RunArgs};
use super::{EXIT_COMPILE, EXIT_FAULT, EXIT_OK, EXIT_USAGE};
use plcrun::diagnostics::Diagnostics;
use plcrun::runtime::engine::{Options, Plc, Value, check_sources};
use plcrun::runtime::names::VarRef;
use plcrun::runtime::stimulus::{StimulusCursor, parse_stimulus};
use plcrun::runtime::trace::{TraceCell, TraceFormat, TraceWriter};
use plcrun::syntax::literal::parse_duration_body;
use std::io::Write;
use std::time::{Duration, Instant};

fn usage_error(msg: impl std::fmt::Display) -> i32 {
    eprintln!("error: {msg}");
    EXIT_USAGE
}

/// Parses `10ms`, `T#10ms`, `TIME#1s`.
fn duration(text: &str) -> Result<i64, String> {
    let t = text.trim();
    let upper = t.to_ascii_uppercase();
    let body = if let Some(r) = upper.strip_prefix("TIME#") {
        &t[t.len() - r.len()..]
    } else if let Some(r) = upper.strip_prefix("T#") {
        &t[t.len() - r.len()..]
    } else {
        t
    };
    parse_duration_body(body)
}

/// `plcrun check FILES...`
pub fn check(args: &CheckArgs) -> i32 {
    let mut diags = Diagnostics::new();
    let sources = match super::load::load(&args.files, &mut diags) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    let options = Options {
        program: args.program.clone(),
        ..Options::default()
    };
    let image = check_sources(&sources, &options, !args.dump_ir, &mut diags);
    if let (true, Some(image)) = (args.dump_ir, &image) {
        print!("{}", image.dump());
    }
    eprint!("{}", diags.render(&sources));
    if diags.has_errors() {
        EXIT_COMPILE
    } else {
        let n = args.files.len();
        eprintln!("ok: {n} file{} checked", if n == 1 { "" } else { "s" });
        EXIT_OK
    }
}

/// `plcrun FILES... --cycles N ...`
pub fn run(args: &RunArgs) -> i32 {
    let cycle_time = match duration(&args.cycle_time) {
        Ok(ns) if ns > 0 => ns,
        Ok(_) => return usage_error("--cycle-time must be positive"),
        Err(e) => return usage_error(format!("--cycle-time: {e}")),
    };
    let watchdog = match duration(&args.watchdog) {
        Ok(0) => None,
        Ok(ns) if ns > 0 => Some(Duration::from_nanos(ns as u64)),
        Ok(_) => return usage_error("--watchdog must not be negative"),
        Err(e) => return usage_error(format!("--watchdog: {e}")),
    };
    let format: TraceFormat = match args.format.parse() {
        Ok(f) => f,
        Err(e) => return usage_error(e),
    };
    let mut diags = Diagnostics::new();
    let sources = match super::load::load(&args.files, &mut diags) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    let options = Options {
        cycle_time,
        program: args.program.clone(),
        watchdog,
    };
    if diags.has_errors() {
        eprint!("{}", diags.render(&sources));
        return EXIT_COMPILE;
    }
    let mut plc = match Plc::compile(sources, &options) {
        Ok(p) => p,
        Err(e) => {
            eprint!("{e}");
            // Only "which program?" problems: the user must pick one.
            if e.diagnostics.iter().all(|d| d.code == "E208") {
                return EXIT_USAGE;
            }
            return EXIT_COMPILE;
        }
    };
    if !plc.warnings().is_empty() {
        eprint!("{}", plc.warnings().render(plc.sources()));
    }
    // --set
    for item in &args.set {
        let Some((name, value)) = item.split_once('=') else {
            return usage_error(format!("--set `{item}`: expected NAME=VALUE"));
        };
        if let Err(e) = plc.write(name.trim(), value) {
            return usage_error(format!("--set {item}: {e}"));
        }
    }
    // Stimulus: resolve columns and decode every cell before running.
    let mut stimulus = None;
    if let Some(path) = &args.stimulus {
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => {
                return usage_error(format!("cannot read stimulus `{}`: {e}", path.display()));
            }
        };
        let stim = match parse_stimulus(&text) {
            Ok(s) => s,
            Err(e) => return usage_error(format!("{}: {e}", path.display())),
        };
        let mut columns: Vec<VarRef> = Vec::new();
        for c in &stim.columns {
            match plc.resolve(c) {
                Ok(r) => columns.push(r),
                Err(e) => return usage_error(format!("{}: column `{c}`: {e}", path.display())),
            }
        }
        let mut rows: Vec<(i64, Vec<(usize, Value)>)> = Vec::new();
        for row in &stim.rows {
            let mut cells = Vec::new();
            for (i, cell) in row.cells.iter().enumerate() {
                let Some(text) = cell else { continue };
                match plc.parse_value(&columns[i], text) {
                    Ok(v) => cells.push((i, v)),
                    Err(e) => {
                        return usage_error(format!(
                            "{}: line {}: column `{}`: {e}",
                            path.display(),
                            row.line,
                            stim.columns[i]
                        ));
                    }
                }
            }
            rows.push((row.at, cells));
        }
        stimulus = Some((stim, columns, rows));
    }
    // Trace names.
    let names: Vec<String> = if args.trace.is_empty() {
        plc.default_trace()
    } else {
        args.trace
            .iter()
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty())
            .collect()
    };
    let mut traced: Vec<VarRef> = Vec::new();
    for n in &names {
        match plc.resolve(n) {
            Ok(r) => traced.push(r),
            Err(e) => return usage_error(format!("--trace: {e}")),
        }
    }
    let out: Box<dyn Write> = match &args.output {
        Some(p) => match std::fs::File::create(p) {
            Ok(f) => Box::new(std::io::BufWriter::new(f)),
            Err(e) => return usage_error(format!("cannot write `{}`: {e}", p.display())),
        },
        None => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
    };
    let mut writer = TraceWriter::new(out, format, names, args.changes_only);
    let mut cells: Vec<TraceCell> = traced
        .iter()
        .map(|_| TraceCell::from_string("", false))
        .collect();
    let mut cursor = StimulusCursor::new();
    let mut applied = 0usize;
    let started = Instant::now();
    let mut status = EXIT_OK;
    for _ in 0..args.cycles {
        let cycle = plc.cycle();
        let time = plc.time();
        if args.realtime {
            let due = started + Duration::from_nanos(time.max(0) as u64);
            let now = Instant::now();
            if due > now {
                std::thread::sleep(due - now);
            }
        }
        if let Some((stim, columns, rows)) = &stimulus {
            // The cursor hands out the due rows as the next contiguous run.
            let due = cursor.due(stim, cycle, time).len();
            for (_, cells) in &rows[applied..applied + due] {
                for (col, v) in cells {
                    plc.set(&columns[*col], v);
                }
            }
            applied += due;
        }
        if let Err(fault) = plc.run_cycle() {
            eprintln!("error: {fault}");
            status = EXIT_FAULT;
            break;
        }
        for (cell, r) in cells.iter_mut().zip(&traced) {
            match plc.get(r) {
                Value::Scalar(t, raw) => cell.set_value(t, raw),
                Value::String(s, wide) => *cell = TraceCell::from_string(&s, wide),
                Value::Enum(name, v) => {
                    *cell = TraceCell {
                        text: name,
                        json: serde_json::Value::from(v),
                    }
                }
            }
        }
        if let Err(e) = writer.row(cycle, time, &cells) {
            eprintln!("error: cannot write the trace: {e}");
            return EXIT_USAGE;
        }
    }
    match writer.finish() {
        Ok(mut w) => {
            let _ = w.flush();
        }
        Err(e) => {
            eprintln!("error: cannot write the trace: {e}");
            return EXIT_USAGE;
        }
    }
    status
}
