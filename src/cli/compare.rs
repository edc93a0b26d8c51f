//! `plcrun compare A_FILES... -- B_FILES... --cycles N`: runs two programs
//! side by side and compares their outputs (see docs/compare.md).
//! Exit status: 0 equivalent, 1 a difference found, 2 usage or compile
//! errors.

use super::args::ReadingArgs;
use super::given::Given;
use super::{EXIT_OK, EXIT_USAGE};
use clap::Args;
use plcrun::{
    CompareOptions, CompareReport, Diagnostics, InputPlan, Options, Pair, Plc, RandomStimulus,
    SourceMap, StimulusSource, load_files_with, parse_map, parse_time_literal, run_seeds_reporting,
};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Exit status when the programs differ.
const EXIT_DIFFERENT: i32 = 1;

/// `plcrun compare A_FILES... -- B_FILES... --cycles N [options]`.
#[derive(Debug, Args)]
#[command(
    after_help = "Exit status: 0 equivalent on every run, 1 a difference found, 2 usage or compile errors. See docs/compare.md."
)]
pub struct CompareArgs {
    /// Source files of program A (default: the sources of ./plcrun.toml
    /// or --project).
    pub a_files: Vec<PathBuf>,
    /// Program A is the project of this file (docs/project-file.md).
    #[arg(long, value_name = "FILE", conflicts_with = "a_files")]
    pub project: Option<PathBuf>,
    /// Source files of program B (after `--`).
    #[arg(last = true, required = true)]
    pub b_files: Vec<PathBuf>,
    /// Cycles per run.
    #[arg(long)]
    pub cycles: u64,
    /// Drive both programs with this stimulus CSV (A's or B's input names).
    #[arg(long, conflicts_with = "random")]
    pub stimulus: Option<PathBuf>,
    /// Drive both programs with random stimulus, from seed SEED.
    #[arg(long, value_name = "SEED")]
    pub random: Option<u64>,
    /// Number of seeds (SEED, SEED+1, ...), run in parallel.
    #[arg(long, default_value_t = 1, requires = "random",
          value_parser = clap::value_parser!(u64).range(1..))]
    pub seeds: u64,
    /// Threads for --seeds (default: the available parallelism).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub jobs: Option<u64>,
    /// Probability that an input not held changes at a cycle.
    #[arg(long, default_value_t = 0.1)]
    pub change_prob: f64,
    /// Fewest cycles a new input value is held.
    #[arg(long, default_value_t = 1)]
    pub min_hold: u64,
    /// Most cycles a new input value is held.
    #[arg(long, default_value_t = 20)]
    pub max_hold: u64,
    /// Pair A's variable X with B's Y (inputs or outputs). Repeatable.
    #[arg(long = "map", value_name = "A.X=B.Y")]
    pub map: Vec<String>,
    /// Do not drive this input / compare this output. Repeatable.
    #[arg(long = "ignore", value_name = "NAME")]
    pub ignore: Vec<String>,
    /// B may follow A by up to K cycles (see docs/compare.md).
    #[arg(long, default_value_t = 0, value_name = "K")]
    pub lag: u64,
    /// How the sources of both programs are read and how strictly they are checked.
    #[command(flatten)]
    pub reading: ReadingArgs,
    /// Write the shrunk counterexample to FILE as a stimulus CSV.
    #[arg(long, value_name = "FILE")]
    pub counterexample: Option<PathBuf>,
    /// The PROGRAM of A to run when its files hold several.
    #[arg(long)]
    pub program_a: Option<String>,
    /// The PROGRAM of B to run when its files hold several.
    #[arg(long)]
    pub program_b: Option<String>,
    /// Cycle time of both programs' implicit task.
    #[arg(long, default_value = "10ms")]
    pub cycle_time: String,
    /// Print the cycles compared and the throughput on standard error.
    #[arg(long)]
    pub timing: bool,
    /// The executor of program A: interp or native (see `plcrun run --engine`).
    #[arg(long, value_name = "ENGINE", default_value = "interp")]
    pub engine_a: plcrun::Engine,
    /// The executor of program B: interp or native. The same files as A
    /// with `--engine-b native` compare the native tier with the
    /// interpreter.
    #[arg(long, value_name = "ENGINE", default_value = "interp")]
    pub engine_b: plcrun::Engine,
}

/// Moves the options written after B's files in front of the `--`, so that
/// `compare A... -- B... --cycles N` parses (after `--` clap would take
/// every word as a file). B's files are the words after `--` up to the
/// first one starting with `-`.
pub fn reorder(args: Vec<OsString>) -> Vec<OsString> {
    let is_compare = args.get(1).is_some_and(|a| a == "compare");
    let Some(dash) = args.iter().position(|a| a == "--") else {
        return args;
    };
    if !is_compare {
        return args;
    }
    let after = &args[dash + 1..];
    let files = after
        .iter()
        .position(|a| a.to_string_lossy().starts_with('-'))
        .unwrap_or(after.len());
    let mut out: Vec<OsString> = args[..dash].to_vec();
    out.extend_from_slice(&after[files..]);
    out.push("--".into());
    out.extend_from_slice(&after[..files]);
    out
}

fn usage_error(msg: impl std::fmt::Display) -> i32 {
    sayln!("error: {msg}");
    EXIT_USAGE
}

/// One program's sources and options, compiled again for each thread.
struct Program {
    label: String,
    sources: SourceMap,
    options: Options,
}

impl Program {
    fn load(
        files: &[PathBuf],
        program: &Option<String>,
        cycle_time: i64,
        reading: &ReadingArgs,
        engine: plcrun::Engine,
    ) -> Result<Program, i32> {
        let mut diags = Diagnostics::new();
        let sources = load_files_with(files, reading.encoding, &mut diags).map_err(usage_error)?;
        if !diags.is_empty() {
            say!("{}", diags.render(&sources));
        }
        if diags.has_errors() {
            return Err(EXIT_USAGE);
        }
        let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
        Ok(Program {
            label: names.join(" "),
            sources,
            options: Options {
                cycle_time,
                program: program.clone(),
                strict: reading.strict,
                encoding: reading.encoding,
                addressing: reading.addressing,
                engine,
                ..Options::default()
            },
        })
    }

    fn compile(&self) -> Result<Plc, plcrun::CompileError> {
        Plc::compile(self.sources.clone(), &self.options)
    }
}

/// `plcrun compare ...`; without A's files, A is the project file's
/// sources (read as it says unless `given` flags say otherwise).
pub fn compare(mut args: Box<CompareArgs>, given: &Given) -> i32 {
    match super::project::sources_or_project(
        &args.a_files,
        args.project.as_deref(),
        &args.reading,
        given,
    ) {
        Ok((files, reading)) => (args.a_files, args.reading) = (files, reading),
        Err(rendered) => {
            say!("{rendered}");
            return EXIT_USAGE;
        }
    }
    let args = &*args;
    match prepare(args) {
        Ok((a, b, options, pair)) => match execute(args, &a, &b, &options, pair) {
            Ok(status) => status,
            Err(msg) => usage_error(msg),
        },
        Err(status) => status,
    }
}

/// Loads and compiles both programs and pairs them.
fn prepare(args: &CompareArgs) -> Result<(Program, Program, CompareOptions, Pair), i32> {
    let cycle_time = match parse_time_literal(&args.cycle_time) {
        Ok(ns) if ns > 0 => ns,
        Ok(_) => return Err(usage_error("--cycle-time must be positive")),
        Err(e) => return Err(usage_error(format!("--cycle-time: {e}"))),
    };
    if args.stimulus.is_none() && args.random.is_none() {
        return Err(usage_error(
            "give the stimulus: --stimulus FILE, or --random SEED (with --seeds K)",
        ));
    }
    let a = Program::load(
        &args.a_files,
        &args.program_a,
        cycle_time,
        &args.reading,
        args.engine_a,
    )?;
    let b = Program::load(
        &args.b_files,
        &args.program_b,
        cycle_time,
        &args.reading,
        args.engine_b,
    )?;
    let mut map = Vec::new();
    for item in &args.map {
        map.push(parse_map(item).map_err(usage_error)?);
    }
    let options = CompareOptions {
        map,
        ignore: args.ignore.clone(),
        lag: args.lag,
    };
    let compiled = |p: &Program, side: &str| {
        p.compile().map_err(|e| {
            say!("{e}");
            sayln!("error: program {side} ({}) does not compile", p.label);
            EXIT_USAGE
        })
    };
    let (pa, pb) = (compiled(&a, "A")?, compiled(&b, "B")?);
    for (plc, p) in [(&pa, &a), (&pb, &b)] {
        if !plc.warnings().is_empty() {
            say!("{}", plc.warnings().render(&p.sources));
        }
    }
    let pair = Pair::new(pa, pb, &options).map_err(usage_error)?;
    Ok((a, b, options, pair))
}

/// Runs the comparison, prints the report, writes the counterexample.
fn execute(
    args: &CompareArgs,
    a: &Program,
    b: &Program,
    options: &CompareOptions,
    mut pair: Pair,
) -> Result<i32, String> {
    let started = Instant::now();
    let (stimulus, differing, first, cycles_run) = match (&args.stimulus, args.random) {
        (Some(path), _) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("cannot read stimulus `{}`: {e}", path.display()))?;
            let plan = InputPlan::parse_csv(&text, pair.pairing(), args.cycles, pair.tick())
                .map_err(|e| format!("{}: {e}", path.display()))?;
            let d = pair.run(&plan).map_err(|e| e.to_string())?;
            let ran = d.as_ref().map_or(args.cycles, |d| d.cycle + 1);
            let source = StimulusSource::Csv {
                path: path.display().to_string(),
            };
            (source, Vec::new(), d.map(|d| (None, plan, d)), ran)
        }
        (None, seed) => {
            let seed = seed.unwrap_or(0);
            let settings = RandomStimulus {
                change_prob: args.change_prob,
                min_hold: args.min_hold,
                max_hold: args.max_hold,
            };
            let seeds = seed..seed.saturating_add(args.seeds);
            let jobs = args.jobs.map_or_else(
                || std::thread::available_parallelism().map_or(1, |n| n.get()),
                |j| j as usize,
            );
            let make = || {
                let worker = |e: plcrun::CompileError| plcrun::CompareError::Worker {
                    message: e.to_string(),
                };
                Pair::new(
                    a.compile().map_err(worker)?,
                    b.compile().map_err(worker)?,
                    options,
                )
            };
            let bar = super::progress_bar::Bar::new("compare");
            let outcome = run_seeds_reporting(
                make,
                &settings,
                seeds.clone(),
                args.cycles,
                jobs,
                super::progress_bar::receiver(&bar),
            );
            drop(bar);
            let outcome = outcome.map_err(|e| e.to_string())?;
            let first = outcome.first.map(|(seed, d)| {
                let plan = pair.random_plan(&settings, seed, args.cycles);
                (Some(seed), plan, d)
            });
            let source = StimulusSource::Random { settings, seeds };
            (source, outcome.differing, first, outcome.cycles_run)
        }
    };
    let elapsed = started.elapsed();
    let found = match first {
        Some((seed, plan, d)) => {
            let shrunk = pair.shrink(&plan, &d).map_err(|e| e.to_string())?;
            Some((seed, plan, d, shrunk))
        }
        None => None,
    };
    if args.timing {
        let secs = elapsed.as_secs_f64().max(1e-9);
        sayln!(
            "timing: {cycles_run} cycles compared in {secs:.3} s: {:.0} cycles/s",
            cycles_run as f64 / secs
        );
    }
    let report = CompareReport {
        a_label: a.label.clone(),
        b_label: b.label.clone(),
        pairing: pair.pairing().clone(),
        lag: pair.lag(),
        cycles: args.cycles,
        stimulus,
        differing_seeds: differing,
        found,
    };
    print!("{}", super::style::report(&report.to_string()));
    let Some((_, _, _, shrunk)) = &report.found else {
        if let Some(path) = &args.counterexample {
            sayln!(
                "note: no difference: no counterexample written to {}",
                path.display()
            );
        }
        return Ok(EXIT_OK);
    };
    if let Some(path) = &args.counterexample {
        write_counterexample(path, &report, shrunk, &args.a_files)?;
    }
    Ok(EXIT_DIFFERENT)
}

fn write_counterexample(
    path: &Path,
    report: &CompareReport,
    shrunk: &plcrun::Shrunk,
    a_files: &[PathBuf],
) -> Result<(), String> {
    let files: Vec<String> = a_files.iter().map(|f| f.display().to_string()).collect();
    let mut comment = vec![
        format!(
            "plcrun compare counterexample: A = {}, B = {}",
            report.a_label, report.b_label
        ),
        format!(
            "they differ at cycle {}; replay: plcrun {} --stimulus {} --cycles {}",
            shrunk.difference.cycle,
            files.join(" "),
            path.display(),
            shrunk.plan.cycles
        ),
    ];
    let renamed: Vec<String> = report
        .pairing
        .inputs
        .iter()
        .filter(|v| v.a != v.b)
        .map(|v| format!("{} (B: {})", v.a, v.b))
        .collect();
    if !renamed.is_empty() {
        comment.push(format!("columns named as in A: {}", renamed.join(", ")));
    }
    let text = shrunk.plan.to_csv(&report.pairing, &comment);
    std::fs::write(path, text).map_err(|e| format!("cannot write `{}`: {e}", path.display()))
}
