//! Command-line options, declared with clap.
//!
//! `plcrun FILES... --cycles N` runs a program (the `run` subcommand is
//! implied when the first argument is not a subcommand's name);
//! `plcrun check FILES...` only checks.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// The whole command line.
#[derive(Debug, Parser)]
#[command(
    name = "plcrun",
    version,
    about = "Run IEC 61131-3 programs (IL, ST, SFC) on a virtual clock and print a trace",
    after_help = "Exit status: 0 ok, 1 compile errors, 2 usage errors, 3 runtime fault.",
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true
)]
pub struct Cli {
    /// A subcommand; without one, the arguments are those of `run`.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// `plcrun FILES... --cycles N` (same as `plcrun run ...`).
    #[command(flatten)]
    pub run: RunArgs,
    /// Colour the output: auto (on a terminal, unless NO_COLOR is set),
    /// always or never.
    #[arg(long, global = true, value_enum, default_value_t, value_name = "WHEN")]
    pub color: super::style::ColorChoice,
    /// No progress bars and no "ok" lines; errors, warnings and results
    /// are still printed.
    #[arg(long, short = 'q', global = true)]
    pub quiet: bool,
}

/// The subcommands.
// Parsed once per process: the size of `RunArgs` does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a program and print a trace (the default command).
    Run(Box<RunArgs>),
    /// Parse and check sources; exit 0 iff there is no error.
    Check(CheckArgs),
    /// Draw the chart (SFC) of a program, or FBD networks and LD rungs, as SVG.
    Draw(DrawArgs),
    /// Run two programs side by side and compare their outputs
    /// (`plcrun compare A_FILES... -- B_FILES... --cycles N`).
    Compare(Box<super::compare::CompareArgs>),
    /// Write sources (IL, ST, SFC, PLCopen FBD/LD) as one PLCopen XML project.
    Export(ExportArgs),
    /// Run the unit tests written in IEC (`plcrun test FILES...`; docs/testing.md).
    Test(super::test::TestArgs),
    /// Run the project of a plcrun.toml in real time until stopped
    /// (Ctrl-C, SIGTERM); flags of `run` given here override the file
    /// (docs/project-file.md).
    #[command(
        mut_arg("files", |a| a
            .required(false)
            .num_args(0..=1)
            .action(clap::ArgAction::Set)
            .value_name("FILE")
            .help("The project file (default: ./plcrun.toml)")),
        // Real time is implied: flags that need --realtime are accepted
        // alone. A flag's default is not what serve uses: the file's is.
        mut_args(|a| {
            let takes_values = a.get_action().takes_values();
            a.requires(clap::builder::Resettable::Reset)
                .hide_default_value(takes_values)
        }),
    )]
    Serve(Box<super::serve::ServeArgs>),
    /// Write a commented plcrun.toml to start a project from.
    Init(super::init::InitArgs),
    /// Serve the Language Server Protocol on standard input and output,
    /// for editors (docs/editors.md).
    Lsp(super::lsp::LspArgs),
    /// Serve the Debug Adapter Protocol on standard input and output: run
    /// a program under a debugger from an editor (docs/editors.md).
    Debug(super::debug::DebugArgs),
    /// Ask a running plcrun's web monitor whether its PLC runs: exit 0 if
    /// it runs, 1 if it is faulted or does not answer (container health
    /// checks; docs/web.md).
    Health(super::health::HealthArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish,
    /// powershell): `plcrun completions bash > /etc/bash_completion.d/plcrun`.
    Completions(super::completions::CompletionsArgs),
    /// Print the manual page, or write every page into a folder.
    Man(super::completions::ManArgs),
    /// Manage the users file of the OPC UA server (`plcrun opcua-user add
    /// FILE NAME`, the password on standard input; docs/opcua.md).
    #[cfg(feature = "opcua")]
    #[command(name = "opcua-user")]
    OpcUaUser(super::opcua::UserArgs),
}

/// `plcrun draw FILES... [--program P] [-o OUT.svg]`.
#[derive(Debug, Args)]
pub struct DrawArgs {
    /// Source files (checked first; errors stop the drawing).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The POU whose chart (SFC) or FBD/LD network to draw (needed when
    /// several have a chart; without it and without a chart, every FBD
    /// and LD body is drawn).
    #[arg(long, visible_alias = "pou")]
    pub program: Option<String>,
    /// Write the SVG to FILE instead of standard output.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// How the sources are read and how strictly they are checked.
    #[command(flatten)]
    pub reading: ReadingArgs,
}

/// `plcrun [run] FILES... --cycles N [options]`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Source files (IL, ST and SFC may be mixed; the language is recognised from the content).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Number of cycles (base ticks) to run; required unless --realtime,
    /// which runs until stopped (Ctrl-C, SIGTERM) without it.
    #[arg(long)]
    pub cycles: Option<u64>,
    /// Cycle time of the implicit task (e.g. 10ms, T#100ms).
    #[arg(long, default_value = "10ms")]
    pub cycle_time: String,
    /// The PROGRAM to run when the files hold several.
    #[arg(long)]
    pub program: Option<String>,
    /// Initial value NAME=VALUE (IEC literal), applied before cycle 0. Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Force NAME to VALUE (IEC literal) for the whole run: the program, the stimulus and
    /// --set cannot change it; the trace marks it. Repeatable.
    #[arg(long = "force", value_name = "NAME=VALUE")]
    pub force: Vec<String>,
    /// Stimulus CSV file (first column `cycle` or `time`); `-` reads it from
    /// standard input (live, row by row, with --realtime).
    #[arg(long)]
    pub stimulus: Option<PathBuf>,
    /// Comma-separated variables to trace (default: VAR_OUTPUTs and %Q variables).
    #[arg(long, value_delimiter = ',')]
    pub trace: Vec<String>,
    /// Trace format (vcd: a waveform for GTKWave or Surfer).
    #[arg(long, default_value = "csv", value_parser = ["table", "csv", "jsonl", "vcd"])]
    pub format: String,
    /// Print the first row, then only rows where a traced value changed.
    #[arg(long)]
    pub changes_only: bool,
    /// Write the trace to FILE instead of standard output.
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Write no trace (what `plcrun serve` does when the project has no
    /// `[trace]` table).
    #[arg(long, conflicts_with_all = ["trace", "output", "changes_only"])]
    pub no_trace: bool,
    /// Wall-clock limit of one cycle (e.g. 1s, 250ms); 0 disables it.
    #[arg(long, default_value = "1s")]
    pub watchdog: String,
    /// Run the tasks on the wall clock, each at its INTERVAL, with absolute
    /// deadlines; the program's clock is the real one.
    #[arg(long)]
    pub realtime: bool,
    /// With --realtime: run the cycle's thread under SCHED_FIFO at this
    /// priority (1-99; needs root, CAP_SYS_NICE or `ulimit -r`).
    #[arg(long, value_name = "N", requires = "realtime", value_parser = clap::value_parser!(u8).range(1..=99))]
    pub rt_priority: Option<u8>,
    /// With --realtime: run the cycle's thread on this CPU only (0-based).
    #[arg(long, value_name = "K", requires = "realtime")]
    pub cpu: Option<usize>,
    /// With --realtime: do not lock memory (by default the process's memory
    /// is locked with mlockall and the cycle's stack pre-faulted, when the
    /// system permits it).
    #[arg(long, requires = "realtime")]
    pub no_lock_memory: bool,
    /// With --realtime: let idle CPUs enter deep sleep states (by default
    /// /dev/cpu_dma_latency is held at 0 while the run lasts, when the
    /// system permits it, as cyclictest does).
    #[arg(long, requires = "realtime")]
    pub allow_cpu_sleep: bool,
    /// Print per-task statistics (cycles, execution time, start jitter,
    /// overruns) on standard error at the end of the run.
    #[arg(long)]
    pub stats: bool,
    /// Format of --stats.
    #[arg(long, value_enum, default_value_t = StatsFormat::Text, requires = "stats")]
    pub stats_format: StatsFormat,
    /// Before cycle N, load FILE (the whole new version) into the running
    /// PLC by online change. Repeatable.
    #[arg(long = "online-change-at", value_name = "N:FILE")]
    pub online_change_at: Vec<String>,
    /// With --realtime: watch the source files and load each new version
    /// into the running PLC by online change (compiled off the cycle's path).
    #[arg(long)]
    pub reload: bool,
    /// Retained data file: RETAIN/PERSISTENT values are restored from it at
    /// start (a missing file is a cold start) and saved to it.
    #[arg(long, value_name = "FILE")]
    pub retain: Option<PathBuf>,
    /// Save the retained values every N cycles (and at the end of the run).
    #[arg(long, value_name = "N", default_value_t = 10, requires = "retain",
          value_parser = clap::value_parser!(u64).range(1..))]
    pub retain_every: u64,
    /// Cold start: ignore the retain file's values (it is overwritten when the run starts).
    #[arg(long, requires = "retain")]
    pub cold: bool,
    /// Restore the retained values that still fit the program and name the others,
    /// instead of refusing a file saved by another version of the program.
    #[arg(long, requires = "retain", conflicts_with = "cold")]
    pub retain_partial: bool,
    /// Also write a timing diagram (SVG) of the traced variables to FILE.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// Also write the program's chart (SVG) to FILE, with the steps active
    /// at --svg-chart-cycle marked.
    #[arg(long, value_name = "FILE")]
    pub svg_chart: Option<PathBuf>,
    /// The cycle whose active steps --svg-chart marks (default: the last one run).
    #[arg(long, value_name = "N", requires = "svg_chart")]
    pub svg_chart_cycle: Option<u64>,
    /// Run charts by IEC 60848 GRAFCET evolution: search for a stable
    /// situation, stored actions on activation, forcing orders.
    #[arg(long)]
    pub grafcet: bool,
    /// Serve the process image over Modbus TCP on ADDR:PORT (e.g.
    /// 0.0.0.0:502, 127.0.0.1:0 for a free port); see docs/modbus.md.
    #[arg(long, value_name = "ADDR:PORT")]
    pub modbus: Option<String>,
    /// Modbus clients connected at once; more are closed on arrival.
    #[arg(long, value_name = "N", default_value_t = 16, requires = "modbus",
          value_parser = clap::value_parser!(u64).range(1..10_000))]
    pub modbus_max_clients: u64,
    /// Close a Modbus connection with no complete request for this long.
    #[arg(
        long,
        value_name = "DURATION",
        default_value = "30s",
        requires = "modbus"
    )]
    pub modbus_idle_timeout: String,
    /// OPC UA server options (docs/opcua.md).
    #[cfg(feature = "opcua")]
    #[command(flatten)]
    pub opcua: super::opcua::OpcUaArgs,
    /// With --realtime: serve the web monitor on ADDR:PORT (a port alone
    /// listens on 127.0.0.1; port 0 for a free port): live values, forcing,
    /// statistics, charts, a JSON API and /metrics; see docs/web.md.
    #[arg(long, value_name = "ADDR:PORT", requires = "realtime")]
    pub web: Option<String>,
    /// The token the web monitor's changes need (writes, forces, resets);
    /// without it one is drawn at random and printed at start.
    #[arg(long, value_name = "TOKEN", requires = "web")]
    pub web_token: Option<String>,
    /// Most MiB of program data (variables, FB instances) the program may
    /// hold; a larger one is refused with E120.
    #[arg(long, value_name = "MIB", default_value_t = 512,
          value_parser = clap::value_parser!(u64).range(1..=2048))]
    pub max_data_mib: u64,
    /// How the sources are read and how strictly they are checked.
    #[command(flatten)]
    pub reading: ReadingArgs,
    /// Run on the plain instruction forms only: no fused
    /// superinstructions, no bounds checks dropped (same results, slower;
    /// for checking the optimizations).
    #[arg(long)]
    pub no_optimize: bool,
    /// Which executor runs the program: interp (the interpreter, the
    /// reference) or native (machine code compiled at load with
    /// Cranelift; blocks it cannot compile run in the interpreter). See
    /// docs/performance.md, "The native tier".
    #[arg(long, value_name = "ENGINE", default_value = "interp")]
    pub engine: plcrun::Engine,
    /// With --engine native: print on standard error which code blocks
    /// were compiled and which run in the interpreter (and why).
    #[arg(long)]
    pub native_report: bool,
}

/// How every subcommand that reads sources reads them and how strictly it
/// checks them.
#[derive(Debug, Args)]
pub struct ReadingArgs {
    /// Pure IEC 61131-3: every compatibility-extension warning (W300-W399)
    /// is an error with the same code.
    #[arg(long)]
    pub strict: bool,
    /// How the source files are encoded: utf-8, windows-1252, latin-1, or
    /// detect (UTF-8 if valid, else Windows-1252 with warning W020).
    #[arg(long, value_name = "ENCODING", default_value = "detect")]
    pub encoding: plcrun::SourceEncoding,
    /// How direct addresses are numbered: iec (CODESYS: %QW1 is bytes
    /// 2-3), openplc (matiec: %QX, %QW, %MW, %MD, %ML separate tables),
    /// byte (S7: %QW1 is bytes 1-2). Default: byte for S7-200 STL, openplc
    /// for PLCopen XML from the OpenPLC Editor or Beremiz, iec otherwise.
    #[arg(long, value_name = "CONVENTION")]
    pub addressing: Option<plcrun::Addressing>,
    /// A folder searched for the libraries a TwinCAT project references
    /// that are TwinCAT projects themselves (a `.plcproj` whose title is
    /// the library's name); they are loaded with it. Repeatable.
    #[arg(long = "library-path", value_name = "DIR")]
    pub library_path: Vec<PathBuf>,
}

impl ReadingArgs {
    /// `files` and the library projects `--library-path` resolves for
    /// them (docs/twincat.md, "Library projects").
    pub fn with_libraries(&self, files: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
        plcrun::with_library_projects(files, &self.library_path).map_err(|e| e.to_string())
    }

    /// Loads `files` and their library projects in this encoding; what
    /// loading reports goes into `diags`, a file that cannot be read is
    /// the error.
    pub fn load(
        &self,
        files: &[PathBuf],
        diags: &mut plcrun::Diagnostics,
    ) -> Result<plcrun::SourceMap, String> {
        let files = self.with_libraries(files)?;
        plcrun::load_files_with(&files, self.encoding, diags).map_err(|e| e.to_string())
    }
}

/// `plcrun check FILES...`: parse and check only.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Source files (default: the sources of ./plcrun.toml or --project).
    pub files: Vec<PathBuf>,
    /// Check the sources of this project file (docs/project-file.md).
    #[arg(long, value_name = "FILE", conflicts_with = "files")]
    pub project: Option<PathBuf>,
    /// Print the compiled IR of every code block (a debugging aid).
    #[arg(long)]
    pub dump_ir: bool,
    /// Print the located variables with their addresses (incomplete
    /// addresses `AT %I*` with the address each got).
    #[arg(long)]
    pub map: bool,
    /// The PROGRAM to build when the files hold several (with --dump-ir).
    #[arg(long)]
    pub program: Option<String>,
    /// Check charts for IEC 60848 GRAFCET evolution (forcing orders allowed).
    #[arg(long)]
    pub grafcet: bool,
    /// Most MiB of program data (variables, FB instances) the program may
    /// hold; a larger one is refused with E120.
    #[arg(long, value_name = "MIB", default_value_t = 512,
          value_parser = clap::value_parser!(u64).range(1..=2048))]
    pub max_data_mib: u64,
    /// How the sources are read and how strictly they are checked.
    #[command(flatten)]
    pub reading: ReadingArgs,
}

/// `plcrun export --plcopen FILES... [-o OUT.xml]`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// Source files (IL, ST, SFC, and PLCopen XML, whose FBD, LD and SFC bodies are written back as drawn).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Write PLCopen TC6 XML 2.01 (the only export format, required).
    #[arg(long, required = true)]
    pub plcopen: bool,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// How the sources are read and how strictly they are checked.
    #[command(flatten)]
    pub reading: ReadingArgs,
}

/// How `--stats` prints the statistics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum StatsFormat {
    /// An aligned table, times in microseconds.
    Text,
    /// One line of JSON, times in nanoseconds.
    Json,
}
