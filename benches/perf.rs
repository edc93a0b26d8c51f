//! Benchmark harness: plcrun against hand-written native Rust and C
//! references.
//!
//! For every benchmark program the harness runs the native Rust reference,
//! the C reference (when a C compiler is found) and plcrun alternately,
//! `rounds` times each; the Rust reference and plcrun in this process, the C
//! reference (`benches/c/`, built with `cc -O2` when the harness starts) in
//! a child process that times its own loop of cycles the same way. Every batch
//! uses a fresh instance, starts at cycle 0 on the virtual clock (cycle `k`
//! at `k × 10 ms`) and stops at a cycle count for which the benchmark README
//! gives the checksum, so every batch is also a correctness check. The
//! table shows the median ns/cycle of each runner, plcrun's ratio to each
//! reference and whether all checksums matched, plus the geometric means of
//! the ratios of the four main benchmarks (a, b, c unrolled, d). The process exits with status 1 if
//! any checksum is wrong.
//!
//! Usage: `cargo bench --bench perf -- [--quick]
//! [--rounds=N] [NAME...]` (`PLCRUN_BENCH_ENGINE=native` for the native
//! tier) — `--quick` (or `PLCRUN_BENCH_QUICK=1`) uses
//! small cycle counts; names select benchmarks by prefix (`a`, `c`,
//! `c_fb_array`, `empty`, ...).

// Shared with tests/native_reference.rs, which uses all of it.
#[allow(dead_code)]
#[path = "native/mod.rs"]
mod native;

#[path = "generate.rs"]
mod generate;
// benches/generate.rs takes its random numbers from here.
#[path = "../tests/support/rng.rs"]
mod rng;

use native::{BenchA, BenchB, BenchC, BenchD, BenchEmpty, Reference, cycle_time_ns};
use std::time::Instant;

/// Something that executes a benchmark program cycle by cycle.
trait Runner {
    /// Runner name for messages (`native`, `plcrun`).
    fn name(&self) -> &str;
    /// Runs one cycle whose clock value is `now_ns`.
    fn cycle(&mut self, now_ns: i64);
    /// The program's checksum variable.
    fn checksum(&self) -> i64;
    /// Runs cycles `first .. first + n`. Runners may override this to avoid
    /// a dynamic call per cycle; the default calls [`Runner::cycle`].
    fn run(&mut self, first: u64, n: u64) {
        for k in first..first + n {
            self.cycle(cycle_time_ns(k));
        }
    }
}

/// A native reference as a [`Runner`].
struct Native<R: Reference>(R);

impl<R: Reference> Runner for Native<R> {
    fn name(&self) -> &str {
        "native"
    }
    fn cycle(&mut self, now_ns: i64) {
        self.0.step(now_ns);
    }
    fn checksum(&self) -> i64 {
        i64::from(self.0.value())
    }
    fn run(&mut self, first: u64, n: u64) {
        // Monomorphic loop: no dynamic dispatch per cycle.
        for k in first..first + n {
            self.0.step(cycle_time_ns(k));
        }
    }
}

fn native_runner<R: Reference + 'static>() -> Box<dyn Runner> {
    Box::new(Native(R::fresh()))
}

/// Cycle count with its expected checksum.
#[derive(Clone, Copy)]
struct Target {
    cycles: u64,
    checksum: i64,
}

/// One benchmark program.
struct Case {
    /// Row name in the table.
    name: &'static str,
    /// File name of the program (as given to plcrun).
    file: &'static str,
    /// Program text.
    source: &'static str,
    /// Variable holding the checksum.
    checksum_var: &'static str,
    /// Full and `--quick` cycle counts (README values).
    full: Target,
    quick: Target,
    /// Allowed checksum deviation (REAL rounding).
    tolerance: i64,
    /// Counted in the geometric mean.
    in_geomean: bool,
    /// Fresh native reference.
    native: fn() -> Box<dyn Runner>,
    /// Name of the C reference in `benches/c/main.c` (`None`: there is none).
    c_name: Option<&'static str>,
}

macro_rules! program {
    ($file:literal) => {
        ($file, include_str!(concat!("programs/", $file)))
    };
}

fn cases() -> Vec<Case> {
    let t = |cycles, checksum| Target { cycles, checksum };
    type Program = (&'static str, &'static str);
    let case = |name: &'static str,
                (file, source): Program,
                full: Target,
                quick: Target,
                tolerance: i64,
                in_geomean: bool,
                native: fn() -> Box<dyn Runner>,
                c_name: Option<&'static str>| Case {
        name,
        file,
        source,
        checksum_var: "checksum",
        full,
        quick,
        tolerance,
        in_geomean,
        native,
        c_name,
    };
    let mut empty = case(
        "empty",
        program!("bench_empty.st"),
        t(10_000_000, 10_000_000),
        t(100_000, 100_000),
        0,
        false,
        native_runner::<BenchEmpty>,
        None,
    );
    empty.checksum_var = "x";
    vec![
        case(
            "a_bool_logic",
            program!("bench_a_bool_logic.st"),
            t(100_000, 32_083_051),
            t(1000, 310_000),
            0,
            true,
            native_runner::<BenchA>,
            Some("a"),
        ),
        case(
            "b_int_sieve",
            program!("bench_b_int_sieve.st"),
            t(2000, 122_935_960),
            t(1000, 122_909_001),
            0,
            true,
            native_runner::<BenchB>,
            Some("b"),
        ),
        case(
            "c_fb_unrolled",
            program!("bench_c_fb_unrolled.st"),
            t(10_000, 263_227),
            t(1000, 50_281_112),
            0,
            true,
            native_runner::<BenchC>,
            Some("c"),
        ),
        case(
            "c_fb_array",
            program!("bench_c_fb_array.st"),
            t(10_000, 263_227),
            t(1000, 50_281_112),
            0,
            false,
            native_runner::<BenchC>,
            Some("c"),
        ),
        case(
            "d_real_math",
            program!("bench_d_real_math.st"),
            t(8000, 486_464),
            t(1000, 466_426),
            1,
            true,
            native_runner::<BenchD>,
            Some("d"),
        ),
        empty,
    ]
}

// ---------------------------------------------------------------------------
// plcrun runner. Written against the intended engine API:
//
//     let mut plc = plcrun::Plc::compile_files(&[(file, text)], &plcrun::Options::default())?;
//     plc.run_cycle()?;                  // one cycle on the virtual clock (10 ms)
//     let v = plc.read_i64("checksum")?;
// ---------------------------------------------------------------------------

mod plc {
    use super::Runner;

    /// A program compiled by plcrun, run on plcrun's own virtual clock.
    pub struct PlcRunner {
        plc: plcrun::Plc,
        var: &'static str,
    }

    impl PlcRunner {
        /// Compiles `text` (named `file` in diagnostics).
        /// `PLCRUN_BENCH_ENGINE=native` runs the native tier instead of
        /// the interpreter.
        pub fn compile(file: &str, text: &str, var: &'static str) -> Result<Self, String> {
            let engine = match std::env::var("PLCRUN_BENCH_ENGINE") {
                Ok(name) => name
                    .parse()
                    .map_err(|e| format!("PLCRUN_BENCH_ENGINE: {e}"))?,
                Err(_) => plcrun::Engine::Interp,
            };
            let options = plcrun::Options {
                engine,
                ..plcrun::Options::default()
            };
            let plc = plcrun::Plc::compile_files(&[(file, text)], &options)
                .map_err(|e| format!("{file} does not compile:\n{e}"))?;
            Ok(Self { plc, var })
        }
    }

    impl Runner for PlcRunner {
        fn name(&self) -> &str {
            "plcrun"
        }
        fn cycle(&mut self, _now_ns: i64) {
            // plcrun's scheduler owns the clock; it is at k × 10 ms in cycle
            // k, like the `now_ns` the harness passes.
            if let Err(e) = self.plc.run_cycle() {
                panic!("plcrun cycle failed: {e}");
            }
        }
        fn checksum(&self) -> i64 {
            match self.plc.read_i64(self.var) {
                Ok(v) => v,
                Err(e) => panic!("cannot read `{}`: {e}", self.var),
            }
        }
    }
}

/// A fresh plcrun runner for `case` (`Some(Err)` when the program does not
/// compile).
fn plcrun_runner(case: &Case) -> Option<Result<Box<dyn Runner>, String>> {
    Some(
        plc::PlcRunner::compile(case.file, case.source, case.checksum_var)
            .map(|r| Box::new(r) as Box<dyn Runner>),
    )
}

// ---------------------------------------------------------------------------
// Measurement.
// ---------------------------------------------------------------------------

/// Command-line / environment options.
struct Opts {
    quick: bool,
    rounds: usize,
    filters: Vec<String>,
}

fn parse_opts() -> Opts {
    let mut quick = std::env::var_os("PLCRUN_BENCH_QUICK").is_some_and(|v| v != "0");
    let mut rounds = None;
    let mut filters = Vec::new();
    // `cargo bench` passes `--bench`; other flags are ignored too.
    for arg in std::env::args().skip(1) {
        if arg == "--quick" {
            quick = true;
        } else if let Some(n) = arg.strip_prefix("--rounds=") {
            rounds = Some(n.parse().expect("--rounds=N"));
        } else if !arg.starts_with('-') {
            filters.push(arg);
        }
    }
    let rounds = rounds.unwrap_or(if quick { 3 } else { 5 }).max(1);
    Opts {
        quick,
        rounds,
        filters,
    }
}

/// Runs one batch on a fresh runner; returns ns/cycle, or a checksum error.
fn batch(runner: &mut dyn Runner, target: Target, tolerance: i64) -> (f64, Result<(), String>) {
    let start = Instant::now();
    runner.run(0, target.cycles);
    let elapsed = start.elapsed();
    let got = runner.checksum();
    let ok = if (got - target.checksum).abs() <= tolerance {
        Ok(())
    } else {
        Err(format!(
            "{}: checksum {got} after {} cycles, expected {}",
            runner.name(),
            target.cycles,
            target.checksum
        ))
    };
    (elapsed.as_nanos() as f64 / target.cycles as f64, ok)
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// Measured result of one benchmark.
struct Row {
    name: &'static str,
    cycles: u64,
    native: f64,
    c: Option<f64>,
    plcrun: Option<f64>,
    errors: Vec<String>,
    in_geomean: bool,
}

fn measure(case: &Case, opts: &Opts, c_bin: Option<&std::path::Path>) -> Row {
    let target = if opts.quick { case.quick } else { case.full };
    let mut native_ns = Vec::new();
    let mut c_ns = Vec::new();
    let mut plcrun_ns = Vec::new();
    let mut errors = Vec::new();
    let mut plcrun_available = true;
    for _ in 0..opts.rounds {
        let mut n = (case.native)();
        let (ns, ok) = batch(n.as_mut(), target, case.tolerance);
        native_ns.push(ns);
        errors.extend(ok.err());

        if let (Some(bin), Some(name)) = (c_bin, case.c_name) {
            match c_ref::batch(bin, name, target.cycles) {
                Ok((ns, got)) => {
                    c_ns.push(ns);
                    if (got - target.checksum).abs() > case.tolerance {
                        errors.push(format!(
                            "C: checksum {got} after {} cycles, expected {}",
                            target.cycles, target.checksum
                        ));
                    }
                }
                Err(e) => errors.push(e),
            }
        }

        // The plcrun runner plugs in here (see `plcrun_runner`).
        if plcrun_available {
            match plcrun_runner(case) {
                None => plcrun_available = false,
                Some(Err(e)) => {
                    errors.push(e);
                    plcrun_available = false;
                }
                Some(Ok(mut p)) => {
                    let (ns, ok) = batch(p.as_mut(), target, case.tolerance);
                    plcrun_ns.push(ns);
                    errors.extend(ok.err());
                }
            }
        }
    }
    errors.dedup();
    Row {
        name: case.name,
        cycles: target.cycles,
        native: median(&mut native_ns),
        c: (!c_ns.is_empty()).then(|| median(&mut c_ns)),
        plcrun: (!plcrun_ns.is_empty()).then(|| median(&mut plcrun_ns)),
        errors,
        in_geomean: case.in_geomean,
    }
}

fn main() {
    let opts = parse_opts();
    let selected: Vec<Case> = cases()
        .into_iter()
        .filter(|c| {
            opts.filters.is_empty() || opts.filters.iter().any(|f| c.name.starts_with(f.as_str()))
        })
        .collect();
    let mut failed = false;
    let c_bin = match c_ref::build() {
        Ok(bin) => bin,
        Err(e) => {
            println!("{e}");
            failed = true;
            None
        }
    };
    println!(
        "plcrun benchmarks: {} rounds, {} cycle counts, median ns/cycle",
        opts.rounds,
        if opts.quick { "quick" } else { "full" }
    );
    println!(
        "{:<14} {:>10} {:>12} {:>12} {:>14} {:>8} {:>8}  checksum",
        "bench", "cycles", "Rust ns/cyc", "C ns/cyc", "plcrun ns/cyc", "÷ Rust", "÷ C"
    );
    let mut log_ratios = Vec::new();
    let mut log_ratios_c = Vec::new();
    for case in &selected {
        let row = measure(case, &opts, c_bin.as_deref());
        let counted = row.in_geomean && row.errors.is_empty();
        let ratio = |reference: Option<f64>, logs: &mut Vec<f64>| match (row.plcrun, reference) {
            (Some(p), Some(r)) => {
                let ratio = p / r;
                if counted {
                    logs.push(ratio.ln());
                }
                format!("{ratio:.2}")
            }
            _ => "-".to_string(),
        };
        let ratio_rust = ratio(Some(row.native), &mut log_ratios);
        let ratio_c = ratio(row.c, &mut log_ratios_c);
        let show = |ns: Option<f64>| ns.map_or("-".to_string(), |ns| format!("{ns:.1}"));
        let status = if row.errors.is_empty() { "ok" } else { "WRONG" };
        println!(
            "{:<14} {:>10} {:>12.1} {:>12} {:>14} {:>8} {:>8}  {status}",
            row.name,
            row.cycles,
            row.native,
            show(row.c),
            show(row.plcrun),
            ratio_rust,
            ratio_c
        );
        for e in &row.errors {
            println!("    {}: {e}", row.name);
        }
        failed |= !row.errors.is_empty();
    }
    for (what, logs) in [("Rust", &log_ratios), ("C", &log_ratios_c)] {
        if logs.is_empty() {
            println!("geomean plcrun ÷ {what}: - (no benchmark of a, b, c unrolled, d measured)");
        } else {
            let geomean = (logs.iter().sum::<f64>() / logs.len() as f64).exp();
            let of = if logs.len() == 4 {
                "a, b, c unrolled, d".to_string()
            } else {
                format!("{} of a, b, c unrolled, d", logs.len())
            };
            println!("geomean plcrun ÷ {what} ({of}): {geomean:.2}");
        }
    }

    {
        failed |= plcrun_only::run(opts.quick);
    }

    if failed {
        eprintln!("checksum or compile errors: see above");
        std::process::exit(1);
    }
}

/// The hand-written C references (`benches/c/`), timed like the others.
///
/// They are compiled when the harness starts, with `$CC` (default `cc`)
/// `-O2 -std=c11 -ffp-contract=off` (ISO C: a float expression is rounded
/// as written, as in plcrun and the Rust references), into one program that
/// runs one batch per invocation: a fresh state, `cycles` cycles in a loop
/// timed with `CLOCK_MONOTONIC` (not the process start, not the
/// allocation), printing ns/cycle and the checksum.
mod c_ref {
    use std::path::{Path, PathBuf};
    use std::process::Command;

    /// Builds the C references: `Ok(None)` (with a message printed) when
    /// there is no C compiler, `Err` when the build fails.
    pub fn build() -> Result<Option<PathBuf>, String> {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/c");
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plcrun-bench-c");
        let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
        let mut files: Vec<PathBuf> = std::fs::read_dir(&src)
            .map_err(|e| format!("C references: cannot read {}: {e}", src.display()))?
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "c"))
            .collect();
        files.sort();
        let output = Command::new(&cc)
            .args(["-O2", "-std=c11", "-ffp-contract=off", "-o"])
            .arg(&out)
            .args(&files)
            .arg("-lm")
            .output();
        match output {
            Err(e) => {
                println!("no C compiler (`{cc}`: {e}): the C references are skipped");
                Ok(None)
            }
            Ok(o) if !o.status.success() => Err(format!(
                "C references: `{cc}` failed:\n{}",
                String::from_utf8_lossy(&o.stderr)
            )),
            Ok(_) => Ok(Some(out)),
        }
    }

    /// Runs one batch of C reference `name` for `cycles` cycles: its
    /// ns/cycle and checksum.
    pub fn batch(bin: &Path, name: &str, cycles: u64) -> Result<(f64, i64), String> {
        let output = Command::new(bin)
            .arg(name)
            .arg(cycles.to_string())
            .output()
            .map_err(|e| format!("C: cannot run {}: {e}", bin.display()))?;
        let text = String::from_utf8_lossy(&output.stdout);
        let mut fields = text.split_whitespace();
        match (
            output.status.success(),
            fields.next().and_then(|f| f.parse().ok()),
            fields.next().and_then(|f| f.parse().ok()),
        ) {
            (true, Some(ns), Some(checksum)) => Ok((ns, checksum)),
            _ => Err(format!(
                "C: `{} {name} {cycles}` failed: {}{}",
                bin.display(),
                text.trim(),
                String::from_utf8_lossy(&output.stderr).trim()
            )),
        }
    }
}

/// Benchmarks without a native counterpart: compile time of a generated
/// 100 000-line program and SFC chart-size scaling.
mod plcrun_only {
    use super::generate::{large_program, sfc_ring, sfc_ring_checksum};
    use std::time::Instant;

    /// Runs them and prints the results; returns `true` on any failure.
    pub fn run(quick: bool) -> bool {
        let mut failed = false;
        let options = plcrun::Options::default();

        let src = large_program(100_000);
        let start = Instant::now();
        let compiled = plcrun::Plc::compile_files(&[("big.st", src.as_str())], &options);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        match compiled {
            Ok(_) => println!("compile 100 000-line program: {ms:.1} ms (budget 1000 ms)"),
            Err(e) => {
                println!("compile 100 000-line program: FAILED: {e}");
                failed = true;
            }
        }

        let cycles: u64 = if quick { 1000 } else { 20_000 };
        println!("SFC ring, one active step, {cycles} cycles:");
        for steps in [10, 10_000] {
            for advancing in [true, false] {
                let src = sfc_ring(steps, advancing);
                let mode = if advancing { "moving" } else { "idle" };
                let mut plc =
                    match plcrun::Plc::compile_files(&[("sfc_ring.st", src.as_str())], &options) {
                        Ok(p) => p,
                        Err(e) => {
                            println!("  {steps:>6} steps, {mode:<6}: does not compile: {e}");
                            failed = true;
                            continue;
                        }
                    };
                let start = Instant::now();
                for _ in 0..cycles {
                    if let Err(e) = plc.run_cycle() {
                        panic!("SFC ring of {steps} steps: cycle failed: {e}");
                    }
                }
                let ns = start.elapsed().as_nanos() as f64 / cycles as f64;
                let want = i64::from(sfc_ring_checksum(steps, advancing, cycles));
                let got = plc.read_i64("checksum").ok();
                let ok = got == Some(want);
                failed |= !ok;
                println!(
                    "  {steps:>6} steps, {mode:<6}: {ns:>10.1} ns/cycle  checksum {}",
                    if ok {
                        "ok".to_string()
                    } else {
                        format!("WRONG: {got:?}, expected {want}")
                    }
                );
            }
        }
        failed
    }
}
