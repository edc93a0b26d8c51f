//! The `run` and `check` commands, over the library's public API.

use super::args::{CheckArgs, RunArgs, StatsFormat};
use super::given::Given;
use super::{EXIT_COMPILE, EXIT_FAULT, EXIT_OK, EXIT_USAGE};
use plcrun::{
    CheckOptions, Diagnostics, LiveStimulus, ModbusExchange, Options, Plc, RealTimeSetup, RunError,
    Session, TaskRunner, TraceFormat, TraceWriter, VcdTimescale, format_stats_table,
    load_files_with, parse_stimulus, parse_time_literal,
};
use std::io::{IsTerminal, Read, Write};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The scan side of the OPC UA server (none without the `opcua` feature).
#[cfg(feature = "opcua")]
type OpcUaSide = plcrun::OpcUaExchange;
/// The scan side of the OPC UA server (none without the `opcua` feature).
#[cfg(not(feature = "opcua"))]
type OpcUaSide = std::convert::Infallible;

/// Exchanges with the OPC UA server between two ticks.
#[cfg(feature = "opcua")]
fn opcua_exchange(side: &mut OpcUaSide, plc: &mut Plc) {
    side.exchange(plc);
}

/// Without the `opcua` feature there is no server to exchange with.
#[cfg(not(feature = "opcua"))]
fn opcua_exchange(side: &mut OpcUaSide, _plc: &mut Plc) {
    match *side {}
}

/// Exit status after a third Ctrl-C or SIGTERM (128 + SIGINT, as shells
/// report an interrupted command).
const EXIT_INTERRUPTED: i32 = 130;

fn usage_error(msg: impl std::fmt::Display) -> i32 {
    sayln!("error: {msg}");
    EXIT_USAGE
}

/// `plcrun check FILES...` (or the sources of a project file); `given`
/// says which flags were typed.
pub fn check(args: &CheckArgs, given: &Given) -> i32 {
    let (files, reading) = match super::project::sources_or_project(
        &args.files,
        args.project.as_deref(),
        &args.reading,
        given,
    ) {
        Ok(found) => found,
        Err(rendered) => {
            say!("{rendered}");
            return EXIT_USAGE;
        }
    };
    let mut diags = Diagnostics::new();
    let sources = match load_files_with(&files, reading.encoding, &mut diags) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    let options = CheckOptions {
        program: args.program.clone(),
        ir_listing: args.dump_ir,
        address_map: args.map,
        grafcet: args.grafcet,
        max_data_bytes: (args.max_data_mib as usize) << 20,
        strict: reading.strict,
        addressing: reading.addressing,
    };
    let bar = super::progress_bar::Bar::new("check");
    let report = check_as_cli(&sources, &options, super::progress_bar::receiver(&bar));
    drop(bar);
    let report = match report {
        Ok(report) => report,
        Err(e) => return usage_error(e),
    };
    diags.extend(report.diagnostics);
    if let Some(listing) = &report.ir_listing {
        print!("{listing}");
    }
    if let Some(map) = &report.address_map {
        print!("{map}");
    }
    say!("{}", diags.render(&sources));
    if diags.has_errors() {
        EXIT_COMPILE
    } else {
        let n = sources.files().len();
        if !super::style::quiet() {
            sayln!("ok: {n} file{} checked", if n == 1 { "" } else { "s" });
        }
        EXIT_OK
    }
}

/// What `plcrun check` reports for `sources` (and `plcrun lsp` shows):
/// the check, where sources holding TcUnit suites are checked as `plcrun
/// test` compiles them.
pub(super) fn check_as_cli(
    sources: &plcrun::SourceMap,
    options: &CheckOptions,
    progress: &dyn plcrun::Progress,
) -> Result<plcrun::CheckReport, plcrun::TestError> {
    let mut report = plcrun::check_reporting(sources, options, progress);
    if !(options.ir_listing || options.address_map) {
        let test_options = plcrun::TestOptions {
            strict: options.strict,
            addressing: options.addressing,
            ..plcrun::TestOptions::default()
        };
        if let Some(found) = plcrun::check_test_sources(sources, &test_options) {
            report.diagnostics = found?;
        }
    }
    Ok(report)
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
        grafcet: args.grafcet,
        max_data_bytes: (args.max_data_mib as usize) << 20,
        strict: args.reading.strict,
        encoding: args.reading.encoding,
        optimize: !args.no_optimize,
        addressing: args.reading.addressing,
        engine: args.engine,
        ..Options::default()
    })
}

/// Compiles the files; on failure, the exit status after printing why.
fn compile(args: &RunArgs, options: &Options) -> Result<Plc, i32> {
    let mut diags = Diagnostics::new();
    let files = args
        .reading
        .with_libraries(&args.files)
        .map_err(usage_error)?;
    let sources = load_files_with(&files, options.encoding, &mut diags).map_err(usage_error)?;
    if diags.has_errors() {
        say!("{}", diags.render(&sources));
        return Err(EXIT_COMPILE);
    }
    // Warnings of loading (an encoding assumed): shown before the program's.
    if !diags.is_empty() {
        say!("{}", diags.render(&sources));
    }
    let plc = Plc::compile(sources, options).map_err(|e| {
        say!("{e}");
        // Only "which program?": the user must pick one.
        if e.needs_program_choice() {
            EXIT_USAGE
        } else {
            EXIT_COMPILE
        }
    })?;
    if !plc.warnings().is_empty() {
        say!("{}", plc.warnings().render(plc.sources()));
    }
    if args.native_report {
        match plc.native_report() {
            Some(report) => say!("{report}"),
            None => sayln!("native: not used (--engine interp)"),
        }
    }
    Ok(plc)
}

/// The program of `args` compiled as the run compiles it, with nothing
/// printed but the reason it failed (for `plcrun serve --check`, which has
/// printed the diagnostics already); `Err` is the exit status.
pub(super) fn compile_quietly(args: &RunArgs) -> Result<Plc, i32> {
    let options = options(args).map_err(usage_error)?;
    let mut diags = Diagnostics::new();
    let files = args
        .reading
        .with_libraries(&args.files)
        .map_err(usage_error)?;
    let sources = load_files_with(&files, options.encoding, &mut diags).map_err(usage_error)?;
    if diags.has_errors() {
        return Err(EXIT_COMPILE);
    }
    Plc::compile(sources, &options).map_err(|e| {
        say!("{e}");
        if e.needs_program_choice() {
            EXIT_USAGE
        } else {
            EXIT_COMPILE
        }
    })
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
    for item in &args.force {
        let Some((name, value)) = item.split_once('=') else {
            return Err(format!("--force `{item}`: expected NAME=VALUE"));
        };
        plc.force(name.trim(), value)
            .map_err(|e| format!("--force {item}: {e}"))?;
    }
    let names: Vec<String> = if args.no_trace {
        Vec::new()
    } else if args.trace.is_empty() {
        for (name, values) in plc.default_trace_left_out() {
            sayln!(
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
    match &args.stimulus {
        // Live from standard input: rows applied as they arrive.
        Some(path) if path.as_os_str() == "-" && args.realtime => {
            let live =
                LiveStimulus::start(session.plc(), std::io::BufReader::new(std::io::stdin()))
                    .map_err(|e| format!("standard input: {e}"))?;
            session.set_live_stimulus(live);
        }
        Some(path) => {
            let text = read_stimulus(path)?;
            let stimulus = parse_stimulus(&text).map_err(|e| format!("{}: {e}", path.display()))?;
            session
                .bind_stimulus(stimulus)
                .map_err(|e| format!("{}: {e}", path.display()))?;
        }
        None => {}
    }
    session
        .set_trace(&names)
        .map_err(|e| format!("--trace: {e}"))?;
    print_ads_log(&mut session);
    Ok(session)
}

/// Prints on standard error, after each cycle, the messages a TwinCAT
/// program gave the ADS logger (`ADSLOGSTR`...) during it.
fn print_ads_log(session: &mut Session) {
    if !plcrun::AdsLog::present(session.plc()) {
        return;
    }
    let mut log = plcrun::AdsLog::new();
    session.add_cycle_hook(move |plc| {
        let news = log.read_new(plc);
        // The hook runs after the cycle: its number is the one just run.
        let cycle = plc.cycle().saturating_sub(1);
        if news.lost > 0 {
            sayln!(
                "ADS log, cycle {cycle}: {} earlier message(s) of this cycle lost (16 are kept between cycles)",
                news.lost
            );
        }
        for m in news.messages {
            sayln!("ADS log, cycle {cycle}, {}: {}", m.kind(), m.text);
        }
    });
}

/// The text of a stimulus file; `-` is standard input, read to its end.
fn read_stimulus(path: &std::path::Path) -> Result<String, String> {
    if path.as_os_str() == "-" {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| format!("cannot read the stimulus from standard input: {e}"))?;
        return Ok(text);
    }
    std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read stimulus `{}`: {e}", path.display()))
}

/// The scan sides of the servers of a run, exchanged between two ticks.
struct Servers {
    modbus: Option<ModbusExchange>,
    opcua: Option<OpcUaSide>,
    web: Option<(super::web::ScanSide, super::web::WebLinks)>,
}

/// Runs the session: plain virtual cycles, or through a task runner (real
/// time, or virtual with statistics), with Ctrl-C and SIGTERM asking for a
/// stop at the next cycle boundary. Prints the statistics if asked.
fn drive<W: Write>(
    args: &RunArgs,
    session: &mut Session,
    cycles: Option<u64>,
    writer: &mut TraceWriter<W>,
    reloader: Option<super::reload::Reloader>,
    servers: Servers,
) -> Result<(), Box<RunError>> {
    let Servers { modbus, opcua, web } = servers;
    let stop = session.plc().stop_handle();
    let stop_after_fault = session.plc().stop_handle();
    // First signal: stop at the cycle boundary; second: interrupt the
    // cycle under way; third: leave at once (a cycle stuck where it
    // cannot be interrupted).
    let on_signal = move || {
        if stop.is_abort_requested() {
            std::process::exit(EXIT_INTERRUPTED);
        } else if stop.is_stop_requested() {
            stop.abort();
        } else {
            stop.stop();
        }
    };
    // A second handler cannot be set in one process; the run works without.
    if let Err(e) = ctrlc::set_handler(on_signal) {
        sayln!("warning: Ctrl-C and SIGTERM will not stop cleanly: {e}");
    }
    if !args.realtime && !args.stats && modbus.is_none() && opcua.is_none() && web.is_none() {
        // Virtual time without statistics: the plain loop, with a bar on
        // a terminal for a long run.
        let cycles = cycles.unwrap_or(0);
        let trace_to_terminal =
            !args.no_trace && args.output.is_none() && std::io::stdout().is_terminal();
        return match super::progress_bar::Bar::for_run(trace_to_terminal) {
            Some(bar) => session.run_reporting(cycles, writer, &bar),
            None => session.run(cycles, writer),
        }
        .map_err(Box::new);
    }
    let mut runner = if args.realtime {
        let mut runner = TaskRunner::real_time(session.plc());
        runner.set_real_time_setup(RealTimeSetup {
            priority: args.rt_priority,
            cpu: args.cpu,
            lock_memory: !args.no_lock_memory,
            keep_cpu_awake: !args.allow_cpu_sleep,
        });
        runner
    } else {
        TaskRunner::virtual_time(session.plc())
    };
    // The monitor's scan side serves the hook and, after a fault, the
    // wait for a reset; the hook only ever tries its lock.
    let web = web.map(|(scan, links)| {
        links.set_stats(runner.stats());
        Arc::new(Mutex::new(scan))
    });
    let web_hook = web.clone();
    if reloader.is_some() || modbus.is_some() || opcua.is_some() || web_hook.is_some() {
        let mut modbus = modbus;
        let mut opcua = opcua;
        if let Some(exchange) = &mut modbus {
            exchange.exchange(session.plc_mut()); // clients see the initial image
        }
        if let Some(side) = &mut opcua {
            opcua_exchange(side, session.plc_mut());
        }
        runner.set_between_ticks(move |session| {
            if let Some(reloader) = &reloader {
                reloader.apply_pending(session);
            }
            if let Some(exchange) = &mut modbus {
                exchange.exchange(session.plc_mut());
            }
            if let Some(side) = &mut opcua {
                opcua_exchange(side, session.plc_mut());
            }
            if let Some(scan) = &web_hook
                && let Ok(mut scan) = scan.try_lock()
            {
                scan.between_ticks(session.plc_mut());
            }
        });
    }
    let mut result = runner.run(session, cycles, writer);
    // With the monitor, a fault leaves the PLC in its faulted state,
    // shown on the page, until a reset from it or a stop.
    while let (Err(RunError::Fault(fault)), Some(scan)) = (&result, &web) {
        sayln!(
            "web: the PLC is stopped by fault {} in cycle {}; reset it from the monitor, or stop it (Ctrl-C)",
            fault.code(),
            fault.cycle
        );
        let after = scan
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .wait_in_fault(session.plc_mut(), &stop_after_fault);
        if after == super::web::AfterFault::Stop {
            break;
        }
        sayln!("web: reset from the monitor; running again");
        result = runner.run(session, cycles, writer);
    }
    if let Some(report) = runner.real_time_report() {
        if let Err(why) = &report.memory_lock {
            sayln!(
                "note: memory was not locked ({why}): page faults may delay cycles; run as \
                 root, give the binary CAP_IPC_LOCK, raise `ulimit -l`, or pass --no-lock-memory"
            );
        }
        if let Err(why) = &report.cpu_awake {
            sayln!(
                "note: the CPUs were not kept awake (/dev/cpu_dma_latency: {why}): waking from \
                 idle may delay cycles; run as root, or pass --allow-cpu-sleep"
            );
        }
    }
    if args.stats {
        let stats = runner.stats().snapshot();
        if args.stats_format == StatsFormat::Json {
            match serde_json::to_string(&stats) {
                Ok(json) => sayln!("{json}"),
                Err(e) => sayln!("error: cannot print the statistics: {e}"),
            }
        } else {
            say!("{}", format_stats_table(&stats));
        }
    }
    result.map_err(Box::new)
}

/// The server of the run's OPC UA server (none without the feature).
#[cfg(feature = "opcua")]
type OpcUaServerOf = plcrun::OpcUaServer;
/// The server of the run's OPC UA server (none without the feature).
#[cfg(not(feature = "opcua"))]
type OpcUaServerOf = ();

/// A started web monitor: its server, and its scan side for the run.
type WebParts = (
    Option<super::web::WebServer>,
    Option<(super::web::ScanSide, super::web::WebLinks)>,
);

/// Starts the monitor `--web` asks for, with the other servers' counters
/// on its `/metrics`.
fn start_web(
    args: &RunArgs,
    plc: &Plc,
    modbus: &Option<Arc<plcrun::ModbusServer>>,
    opcua: &Option<Arc<OpcUaServerOf>>,
) -> Result<WebParts, String> {
    let started = super::web::start(args.web.as_deref(), args.web_token.as_deref(), plc)?;
    let Some((server, scan, links)) = started else {
        return Ok((None, None));
    };
    if let Some(m) = modbus {
        links.add_modbus(Arc::clone(m));
    }
    #[cfg(feature = "opcua")]
    if let Some(o) = opcua {
        links.add_opcua(Arc::clone(o));
    }
    #[cfg(not(feature = "opcua"))]
    let _ = opcua;
    Ok((Some(server), Some((scan, links))))
}

/// Why the flags of `args` cannot go together, if they cannot.
fn refused_combination(args: &RunArgs) -> Option<&'static str> {
    if args.cycles.is_none() && !args.realtime {
        return Some("--cycles is required (or --realtime, which runs until stopped)");
    }
    if args.reload && !args.realtime {
        return Some("--reload watches the sources of a --realtime run; add --realtime");
    }
    if args.modbus.is_some() && !args.online_change_at.is_empty() {
        return Some("--online-change-at cannot be combined with --modbus");
    }
    if args.web.is_some() && args.reload {
        // The monitor lists the variables of the program it started with.
        return Some("--reload cannot be combined with --web");
    }
    #[cfg(feature = "opcua")]
    if args.opcua.opcua.is_some() && (!args.online_change_at.is_empty() || args.reload) {
        // Both replace the PLC, whose variables the server has resolved.
        return Some("--online-change-at and --reload cannot be combined with --opcua");
    }
    None
}

/// `plcrun FILES... --cycles N ...`
pub fn run(args: &RunArgs) -> i32 {
    run_with(args, &mut |_| {})
}

/// [`run`], with `prepare` given the PLC once it is compiled and set up
/// (`--set`, `--force`, stimulus), before anything runs (`plcrun debug`
/// attaches its debugger there).
pub(super) fn run_with(args: &RunArgs, prepare: &mut dyn FnMut(&mut Plc)) -> i32 {
    if let Some(why) = refused_combination(args) {
        return usage_error(why);
    }
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
    prepare(session.plc_mut());
    if let Some(saver) = saver {
        session.save_retain_every(saver, args.retain_every);
    }
    let pictures = match super::draw::prepare(args, &mut session) {
        Ok(p) => p,
        Err(e) => return usage_error(e),
    };
    let out: Box<dyn Write> = match &args.output {
        // No trace: the rows (cycle and time only) go nowhere.
        _ if args.no_trace => Box::new(std::io::sink()),
        Some(p) => match std::fs::File::create(p) {
            Ok(f) => Box::new(std::io::BufWriter::new(f)),
            Err(e) => return usage_error(format!("cannot write `{}`: {e}", p.display())),
        },
        None => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
    };
    let changes = match super::online::planned(&args.online_change_at) {
        Ok(c) => c,
        Err(e) => return usage_error(e),
    };
    let names = session.trace_names().to_vec();
    let mut writer = if format == TraceFormat::Vcd {
        // Exact timestamps: the base tick's unit on the virtual clock of a
        // fixed program, nanoseconds where the clock or the tick can vary.
        let timescale = if args.realtime || args.reload || !changes.is_empty() {
            VcdTimescale::NANOSECOND
        } else {
            VcdTimescale::for_cycle(session.plc().cycle_time(), session.plc().time())
        };
        let signals = session.vcd_signals();
        TraceWriter::vcd(out, names, signals, timescale, args.changes_only)
    } else {
        TraceWriter::new(out, format, names, args.changes_only)
    };
    let reloader = args
        .reload
        .then(|| super::reload::start(args.files.clone(), options.clone()));
    let modbus = match super::modbus::start(args) {
        Ok(m) => m,
        Err(e) => return usage_error(e),
    };
    let (modbus_server, exchange) = modbus.unzip();
    let modbus_server = modbus_server.map(Arc::new);
    #[cfg(feature = "opcua")]
    let (opcua_server, opcua) = match super::opcua::start(&args.opcua, session.plc()) {
        Ok(o) => o.unzip(),
        Err(e) => return usage_error(e),
    };
    #[cfg(feature = "opcua")]
    let opcua_server = opcua_server.map(Arc::new);
    #[cfg(not(feature = "opcua"))]
    let opcua: Option<OpcUaSide> = None;
    #[cfg(not(feature = "opcua"))]
    let opcua_server: Option<Arc<()>> = None;
    let (web_server, web) = match start_web(args, session.plc(), &modbus_server, &opcua_server) {
        Ok(started) => started,
        Err(e) => return usage_error(e),
    };
    let result = if changes.is_empty() {
        drive(
            args,
            &mut session,
            args.cycles,
            &mut writer,
            reloader,
            Servers {
                modbus: exchange,
                opcua,
                web,
            },
        )
        .map_err(|e| *e)
    } else if args.realtime {
        return usage_error(
            "--online-change-at runs in virtual time; it cannot be combined with --realtime",
        );
    } else {
        let cycles = args.cycles.unwrap_or(0);
        super::online::run(&mut session, cycles, &mut writer, &changes, &options)
    };
    if let Some(server) = web_server {
        server.shutdown();
    }
    let result = result.and_then(|()| unload(&mut session));
    if let Err(e) = last_retain_save(&mut session, &result) {
        sayln!("error: {e}");
        return EXIT_USAGE;
    }
    let status = match result {
        Ok(()) => EXIT_OK,
        Err(RunError::Fault(fault)) => {
            // Starts with `error[R...]:`, like a compile diagnostic.
            sayln!("{fault}");
            EXIT_FAULT
        }
        Err(RunError::Trace(e)) if super::broken_pipe::is_broken_pipe(&e) => {
            return super::broken_pipe::BROKEN_PIPE_STATUS;
        }
        Err(e @ RunError::Trace(_)) => {
            sayln!("error: {e}");
            return EXIT_USAGE;
        }
        Err(e) => {
            sayln!("error: {e}");
            EXIT_USAGE
        }
    };
    if let Some(pictures) = pictures
        && let Err(e) = super::draw::finish(args, pictures, &session)
    {
        sayln!("error: {e}");
        return EXIT_USAGE;
    }
    finish_trace(writer).unwrap_or(status)
}

/// Writes the end of the trace; the exit status when that fails.
fn finish_trace<W: Write>(writer: TraceWriter<W>) -> Option<i32> {
    match writer.finish() {
        Ok(mut w) => {
            let _ = w.flush();
            None
        }
        Err(e) if super::broken_pipe::is_broken_pipe(&e) => {
            Some(super::broken_pipe::BROKEN_PIPE_STATUS)
        }
        Err(e) => {
            sayln!("error: cannot write the trace: {e}");
            Some(EXIT_USAGE)
        }
    }
}

/// Unloads the program after a run that ended at a cycle boundary: its
/// FB_exit methods run (docs/semantics.md §24) before the last retain save.
fn unload(session: &mut Session) -> Result<(), RunError> {
    session.plc_mut().unload().map_err(RunError::Fault)
}

/// The last retain save, if the run saves: only after a run that ended at
/// a cycle boundary (a fault leaves the faulting cycle half done, so the
/// last periodic save is the consistent one). Its error, or one met by
/// the saver during the run.
fn last_retain_save(session: &mut Session, result: &Result<(), RunError>) -> Result<(), String> {
    let boundary = !matches!(result, Err(RunError::Fault(_)));
    match session.take_retain_saver() {
        Some(saver) => super::retain::finish(saver, session.plc(), boundary),
        None => Ok(()),
    }
}
