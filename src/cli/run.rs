//! The `run` and `check` commands, over the library's public API.

use super::args::{CheckArgs, RunArgs};
use super::{EXIT_COMPILE, EXIT_FAULT, EXIT_OK, EXIT_USAGE};
use plcrun::{
    CheckOptions, Diagnostics, Options, Pacing, Plc, RunError, Session, TraceFormat, TraceWriter,
    check as check_sources, load_files, parse_stimulus, parse_time_literal,
};
use std::io::Write;
use std::time::Duration;

fn usage_error(msg: impl std::fmt::Display) -> i32 {
    eprintln!("error: {msg}");
    EXIT_USAGE
}

/// `plcrun check FILES...`
pub fn check(args: &CheckArgs) -> i32 {
    let mut diags = Diagnostics::new();
    let sources = match load_files(&args.files, &mut diags) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    let options = CheckOptions {
        program: args.program.clone(),
        ir_listing: args.dump_ir,
    };
    let report = check_sources(&sources, &options);
    diags.extend(report.diagnostics);
    if let Some(listing) = &report.ir_listing {
        print!("{listing}");
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

/// The options that do not depend on the program.
fn options(args: &RunArgs) -> Result<Options, String> {
    let cycle_time = match parse_time_literal(&args.cycle_time) {
        Ok(ns) if ns > 0 => ns,
        Ok(_) => return Err("--cycle-time must be positive".into()),
        Err(e) => return Err(format!("--cycle-time: {e}")),
    };
    // `0` alone (no unit) is the documented way to turn the watchdog off.
    let watchdog_text = if args.watchdog.trim() == "0" {
        "0s"
    } else {
        args.watchdog.as_str()
    };
    let watchdog = match parse_time_literal(watchdog_text) {
        Ok(0) => None,
        Ok(ns) if ns > 0 => Some(Duration::from_nanos(ns as u64)),
        Ok(_) => return Err("--watchdog must not be negative".into()),
        Err(e) => return Err(format!("--watchdog: {e}")),
    };
    Ok(Options {
        cycle_time,
        program: args.program.clone(),
        watchdog,
    })
}

/// Compiles the files; on failure, the exit status after printing why.
fn compile(args: &RunArgs, options: &Options) -> Result<Plc, i32> {
    let mut diags = Diagnostics::new();
    let sources = load_files(&args.files, &mut diags).map_err(usage_error)?;
    if diags.has_errors() {
        eprint!("{}", diags.render(&sources));
        return Err(EXIT_COMPILE);
    }
    let plc = Plc::compile(sources, options).map_err(|e| {
        eprint!("{e}");
        // Only "which program?": the user must pick one.
        if e.needs_program_choice() {
            EXIT_USAGE
        } else {
            EXIT_COMPILE
        }
    })?;
    if !plc.warnings().is_empty() {
        eprint!("{}", plc.warnings().render(plc.sources()));
    }
    Ok(plc)
}

/// Builds the session: `--set`, the stimulus, the traced names.
fn session(args: &RunArgs, mut plc: Plc) -> Result<Session, String> {
    for item in &args.set {
        let Some((name, value)) = item.split_once('=') else {
            return Err(format!("--set `{item}`: expected NAME=VALUE"));
        };
        plc.write(name.trim(), value)
            .map_err(|e| format!("--set {item}: {e}"))?;
    }
    let names: Vec<String> = if args.trace.is_empty() {
        for (name, values) in plc.default_trace_left_out() {
            eprintln!(
                "note: `{name}` ({values} values) is left out of the default trace; name the values to trace with --trace"
            );
        }
        plc.default_trace()
    } else {
        args.trace
            .iter()
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty())
            .collect()
    };
    let mut session = Session::new(plc);
    if let Some(path) = &args.stimulus {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read stimulus `{}`: {e}", path.display()))?;
        let stimulus = parse_stimulus(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        session
            .bind_stimulus(stimulus)
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    session
        .set_trace(&names)
        .map_err(|e| format!("--trace: {e}"))?;
    if args.realtime {
        session.set_pacing(Pacing::WallClock);
    }
    Ok(session)
}

/// `plcrun FILES... --cycles N ...`
pub fn run(args: &RunArgs) -> i32 {
    let Some(cycles) = args.cycles else {
        return usage_error("--cycles is required");
    };
    let format: TraceFormat = match args.format.parse() {
        Ok(f) => f,
        Err(e) => return usage_error(e),
    };
    let options = match options(args) {
        Ok(o) => o,
        Err(e) => return usage_error(e),
    };
    let mut plc = match compile(args, &options) {
        Ok(plc) => plc,
        Err(status) => return status,
    };
    let saver = match super::retain::start(args, &mut plc) {
        Ok(saver) => saver,
        Err(e) => return usage_error(e),
    };
    let mut session = match session(args, plc) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    if let Some(saver) = saver {
        session.save_retain_every(saver, args.retain_every);
    }
    let out: Box<dyn Write> = match &args.output {
        Some(p) => match std::fs::File::create(p) {
            Ok(f) => Box::new(std::io::BufWriter::new(f)),
            Err(e) => return usage_error(format!("cannot write `{}`: {e}", p.display())),
        },
        None => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
    };
    let names = session.trace_names().to_vec();
    let mut writer = TraceWriter::new(out, format, names, args.changes_only);
    let result = session.run(cycles, &mut writer);
    // A fault leaves the faulting cycle half done: the last periodic save
    // is the consistent one, so only a run ending at a cycle boundary saves.
    let boundary = !matches!(result, Err(RunError::Fault(_)));
    if let Some(saver) = session.take_retain_saver()
        && let Err(e) = super::retain::finish(saver, session.plc(), boundary)
    {
        eprintln!("error: {e}");
        return EXIT_USAGE;
    }
    let status = match result {
        Ok(()) => EXIT_OK,
        Err(RunError::Fault(fault)) => {
            eprintln!("error: {fault}");
            EXIT_FAULT
        }
        Err(e @ RunError::Trace(_)) => {
            eprintln!("error: {e}");
            return EXIT_USAGE;
        }
    };
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
