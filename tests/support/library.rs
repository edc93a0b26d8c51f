//! What `plcrun` prints, obtained through the library instead of spawning
//! the binary: the CSV trace of a run (`Plc` + `Session` + `TraceWriter`)
//! and the diagnostics of `plcrun check` (`plcrun::check`). The command
//! line is a thin driver over the same calls, so the texts are the same
//! byte for byte; the end-to-end tests that do run the binary
//! (`support/cli.rs`) compare the two.
#![allow(dead_code)]

use plcrun::{
    CheckOptions, Options, Plc, RunError, Session, SourceMap, TraceFormat, TraceWriter, check,
    parse_stimulus,
};

/// A run as the command line's options describe it:
/// `--cycles`, `--stimulus`, `--trace`, `--changes-only`, with
/// `--format csv` and the default cycle time and watchdog.
#[derive(Debug, Clone, Copy, Default)]
pub struct TraceRequest<'a> {
    /// Number of cycles.
    pub cycles: u64,
    /// The stimulus CSV text (not a path).
    pub stimulus: Option<&'a str>,
    /// Comma-separated names to trace; `None` traces the default
    /// (VAR_OUTPUTs and `%Q` variables).
    pub trace: Option<&'a str>,
    /// Print the first row, then only rows where a traced value changed.
    pub changes_only: bool,
}

/// Reads repository files (paths relative to the repository root), each
/// named by its path as given, as `plcrun` names the files it reads.
pub fn repo_files(paths: &[&str]) -> Vec<(String, String)> {
    paths
        .iter()
        .map(|p| (p.to_string(), repo_text(p)))
        .collect()
}

/// The text of a repository file.
pub fn repo_text(path: &str) -> String {
    let full = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("read {path}: {e}"))
}

/// Compiles `files` (`(name, text)`) and runs `request`. Returns the CSV
/// text of the cycles that ran and how the run ended: a runtime fault
/// stops it after the rows of the cycles before it, as on the command
/// line. Panics with the message the command line would print when the
/// program does not compile or the stimulus or trace names do not fit it.
pub fn run_csv(
    files: &[(impl AsRef<str>, impl AsRef<str>)],
    request: &TraceRequest,
) -> (String, Result<(), RunError>) {
    run_csv_with(files, request, &Options::default())
}

/// [`run_csv`] with the program compiled with `options`.
pub fn run_csv_with(
    files: &[(impl AsRef<str>, impl AsRef<str>)],
    request: &TraceRequest,
    options: &Options,
) -> (String, Result<(), RunError>) {
    let named: Vec<(&str, &str)> = files
        .iter()
        .map(|(name, text)| (name.as_ref(), text.as_ref()))
        .collect();
    let plc = Plc::compile_files(&named, options).unwrap_or_else(|e| panic!("compile error:\n{e}"));
    let names: Vec<String> = match request.trace {
        None => plc.default_trace(),
        Some(list) => list
            .split(',')
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty())
            .collect(),
    };
    let mut session = Session::new(plc);
    if let Some(text) = request.stimulus {
        let stimulus = parse_stimulus(text).unwrap_or_else(|e| panic!("stimulus: {e}"));
        session
            .bind_stimulus(stimulus)
            .unwrap_or_else(|e| panic!("stimulus: {e}"));
    }
    session
        .set_trace(&names)
        .unwrap_or_else(|e| panic!("--trace: {e}"));
    let mut writer = TraceWriter::new(
        Vec::new(),
        TraceFormat::Csv,
        session.trace_names().to_vec(),
        request.changes_only,
    );
    let outcome = session.run(request.cycles, &mut writer);
    let bytes = writer.finish().expect("a trace in memory cannot fail");
    let csv = String::from_utf8(bytes).expect("the trace is UTF-8");
    (csv, outcome)
}

/// [`run_csv`] for a run that must not fault: the CSV trace.
pub fn csv_trace(files: &[(impl AsRef<str>, impl AsRef<str>)], request: &TraceRequest) -> String {
    match run_csv(files, request) {
        (csv, Ok(())) => csv,
        (_, Err(e)) => panic!("the run stopped: {e}"),
    }
}

/// Checks `files` as `plcrun check` does. Returns whether they have no
/// error, and the diagnostics as the command prints them on standard error.
pub fn check_rendered(files: &[(&str, &str)]) -> (bool, String) {
    let mut sources = SourceMap::new();
    for (name, text) in files {
        sources.add(*name, *text);
    }
    let report = check(&sources, &CheckOptions::default());
    (report.is_ok(), report.diagnostics.render(&sources))
}
