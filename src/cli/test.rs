//! `plcrun test FILES...`: runs the unit tests written in IEC (see
//! docs/testing.md). Exit status: 0 every test passed, 1 a test failed or
//! errored, compile errors or no test found, 2 usage errors.

use super::args::ReadingArgs;
use super::given::Given;
use super::{EXIT_COMPILE, EXIT_OK, EXIT_USAGE};
use clap::Args;
use plcrun::{
    Diagnostics, TestError, TestOptions, load_files_with, parse_time_literal, run_tests_reporting,
};
use std::path::PathBuf;
use std::time::Duration;

/// Exit status when a test failed or errored.
const EXIT_FAILED: i32 = 1;

/// `plcrun test FILES... [options]`.
#[derive(Debug, Args)]
#[command(
    after_help = "A test is a PROGRAM or FUNCTION_BLOCK whose name starts with TEST_. Exit status: 0 every test passed, 1 a test failed, compile errors or no test, 2 usage errors. See docs/testing.md."
)]
pub struct TestArgs {
    /// Source files: the code under test and the tests (default: the
    /// sources of ./plcrun.toml or --project).
    pub files: Vec<PathBuf>,
    /// Test the sources of this project file (docs/project-file.md).
    #[arg(long, value_name = "FILE", conflicts_with = "files")]
    pub project: Option<PathBuf>,
    /// Run only the tests whose name contains PATTERN (ignoring case).
    #[arg(long, value_name = "PATTERN")]
    pub filter: Option<String>,
    /// Cycle time of the virtual clock (e.g. 10ms, T#100ms).
    #[arg(long, default_value = "10ms")]
    pub cycle_time: String,
    /// Write a JUnit XML report to FILE.
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Wall-clock limit of one cycle of a test (e.g. 1s, 250ms); 0 disables it.
    #[arg(long, default_value = "1s")]
    pub watchdog: String,
    /// Leave out the files that do not compile (and those that need them),
    /// run the tests of the others, and report the tests left out as
    /// errors (a library that references one plcrun does not have).
    #[arg(long)]
    pub keep_going: bool,
    /// How the sources are read and how strictly they are checked.
    #[command(flatten)]
    pub reading: ReadingArgs,
}

fn usage_error(msg: impl std::fmt::Display) -> i32 {
    sayln!("error: {msg}");
    EXIT_USAGE
}

fn options(args: &TestArgs) -> Result<TestOptions, String> {
    let cycle_time = match parse_time_literal(&args.cycle_time) {
        Ok(ns) if ns > 0 => ns,
        Ok(_) => return Err("--cycle-time must be positive".into()),
        Err(e) => return Err(format!("--cycle-time: {e}")),
    };
    let text = if args.watchdog.trim() == "0" {
        "0s"
    } else {
        args.watchdog.as_str()
    };
    let watchdog = match parse_time_literal(text) {
        Ok(0) => None,
        Ok(ns) if ns > 0 => Some(Duration::from_nanos(ns as u64)),
        Ok(_) => return Err("--watchdog must not be negative".into()),
        Err(e) => return Err(format!("--watchdog: {e}")),
    };
    Ok(TestOptions {
        filter: args.filter.clone(),
        cycle_time,
        watchdog,
        strict: args.reading.strict,
        addressing: args.reading.addressing,
        keep_going: args.keep_going,
        // The loopback links of the TwinCAT solutions (docs/testing.md).
        io_links: plcrun::project_io_links(&args.files),
        nc_axes: plcrun::project_nc_axes(&args.files),
    })
}

/// `plcrun test FILES...` (or the sources of a project file, read as it
/// says unless `given` flags say otherwise).
pub fn test(mut args: TestArgs, given: &Given) -> i32 {
    match super::project::sources_or_project(
        &args.files,
        args.project.as_deref(),
        &args.reading,
        given,
    ) {
        Ok((files, reading)) => (args.files, args.reading) = (files, reading),
        Err(rendered) => {
            say!("{rendered}");
            return EXIT_USAGE;
        }
    }
    let args = &args;
    let options = match options(args) {
        Ok(o) => o,
        Err(e) => return usage_error(e),
    };
    let mut diags = Diagnostics::new();
    let sources = match load_files_with(&args.files, args.reading.encoding, &mut diags) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    if !diags.is_empty() {
        say!("{}", diags.render(&sources));
    }
    if diags.has_errors() {
        return EXIT_COMPILE;
    }
    let bar = super::progress_bar::Bar::new("test");
    let report = run_tests_reporting(&sources, &options, super::progress_bar::receiver(&bar));
    drop(bar);
    let report = match report {
        Ok(r) => r,
        Err(TestError::Compile(e)) => {
            say!("{e}");
            return EXIT_COMPILE;
        }
        Err(e) => {
            sayln!("error: {e}");
            return EXIT_FAILED;
        }
    };
    if !report.warnings.is_empty() {
        say!("{}", report.warnings.render(&sources));
    }
    if !report.left_out.is_empty() {
        sayln!(
            "note: --keep-going left out {} file(s) or global variable(s) that do not compile, or need one that does not:",
            report.left_out.len()
        );
        for (file, why) in &report.left_out {
            sayln!("  {file}: {why}");
        }
    }
    print!("{}", super::style::report(&report.to_text()));
    if let Some(path) = &args.junit
        && let Err(e) = std::fs::write(path, report.to_junit("plcrun"))
    {
        return usage_error(format!("cannot write `{}`: {e}", path.display()));
    }
    if report.all_passed() {
        EXIT_OK
    } else {
        EXIT_FAILED
    }
}
