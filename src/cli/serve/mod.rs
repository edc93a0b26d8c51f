//! `plcrun serve [FILE]`: runs the project of a `plcrun.toml` in real time
//! until stopped (Ctrl-C, SIGTERM: a clean stop at a cycle boundary, the
//! retained values saved), through the same path as `plcrun run
//! --realtime`. Flags of `run` given with it override the file.

mod command_line;
mod overrides;

use super::args::{CheckArgs, ReadingArgs, RunArgs};
use super::given::Given;
use super::{EXIT_USAGE, project};
use clap::Args;
use project::Assignment;
use std::path::{Path, PathBuf};

/// `plcrun serve [FILE] [--check] [flags of run]`.
#[derive(Debug, Args)]
#[command(
    after_help = "Keys of the file: docs/project-file.md. Exit status: 0 stopped cleanly, 1 compile errors, 2 usage errors or a bad project file, 3 runtime fault."
)]
pub struct ServeArgs {
    /// Check the project file and its sources, print the `plcrun run`
    /// command it amounts to on standard output, and do not run.
    #[arg(long)]
    pub check: bool,
    /// The options of the run (the file's, unless given here).
    #[command(flatten)]
    pub run: RunArgs,
}

/// `plcrun serve [FILE] ...`
pub fn serve(args: &ServeArgs, given: &Given) -> i32 {
    let explicit = args.run.files.first().map(PathBuf::as_path);
    let project = match project::find(explicit) {
        Ok(p) => p,
        Err(rendered) => {
            say!("{rendered}");
            return EXIT_USAGE;
        }
    };
    let mut run = project.run;
    if !project.traced {
        run.no_trace = true;
    }
    if let Err(e) = overrides::apply(&mut run, &args.run, given) {
        sayln!("error: {e}");
        return EXIT_USAGE;
    }
    if args.check {
        return check(&run, &project.path, &project.assignments);
    }
    sayln!(
        "serve: {} ({} source file{})",
        project.path.display(),
        run.files.len(),
        if run.files.len() == 1 { "" } else { "s" }
    );
    super::run::run(&run)
}

/// `--check`: the sources checked as `plcrun check` checks them, the
/// `[set]` and `[force]` names and values against the compiled program,
/// then the equivalent command on standard output.
fn check(run: &RunArgs, path: &Path, assignments: &[Assignment]) -> i32 {
    let args = CheckArgs {
        files: run.files.clone(),
        project: None,
        dump_ir: false,
        map: false,
        program: run.program.clone(),
        grafcet: run.grafcet,
        max_data_mib: run.max_data_mib,
        reading: ReadingArgs {
            strict: run.reading.strict,
            encoding: run.reading.encoding,
            addressing: run.reading.addressing,
            library_path: run.reading.library_path.clone(),
        },
    };
    let status = super::run::check(&args, &Given::default());
    if status != super::EXIT_OK {
        return status;
    }
    if !assignments.is_empty() {
        let mut plc = match super::run::compile_quietly(run) {
            Ok(plc) => plc,
            Err(status) => return status,
        };
        if let Err(rendered) = project::check_assignments(path, assignments, &mut plc) {
            say!("{rendered}");
            return EXIT_USAGE;
        }
    }
    println!("{}", command_line::command_line(run));
    super::EXIT_OK
}
