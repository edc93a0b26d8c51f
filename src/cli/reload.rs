//! `--reload` with `--realtime`: the source files are watched and each new
//! version is loaded into the running PLC by online change.
//!
//! Everything slow happens off the cycle's path, on a watcher thread: it
//! polls the files' modification times and sizes every [`POLL`] (plain
//! `std::fs::metadata`, no file-notification dependency), and compiles a
//! changed version there. The runner only checks a channel between two
//! ticks and, when a compiled version is waiting, applies it with
//! `Session::online_change`. What happened — the change report, or why
//! the version was refused — goes to standard error; a refused version
//! leaves the running program as it is.

use plcrun::{Diagnostics, Options, Plc, Session, load_files_with};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::{Duration, SystemTime};

/// How often the watcher looks at the files.
const POLL: Duration = Duration::from_millis(250);

/// A version the watcher has prepared.
enum Version {
    /// Compiled, with its warnings rendered (possibly empty).
    Compiled { plc: Box<Plc>, warnings: String },
    /// Did not load or compile: the rendered diagnostics.
    Refused(String),
}

/// The runner's end of the watcher: applies what it prepared.
pub(super) struct Reloader {
    versions: Receiver<Version>,
    /// Tells the watcher to end when the run does.
    done: Arc<AtomicBool>,
}

impl Drop for Reloader {
    fn drop(&mut self) {
        self.done.store(true, Ordering::Relaxed);
    }
}

/// Starts watching `files`; new versions are compiled with `options`.
pub(super) fn start(files: Vec<PathBuf>, options: Options) -> Reloader {
    let (tx, versions) = mpsc::channel();
    let done = Arc::new(AtomicBool::new(false));
    let watcher_done = Arc::clone(&done);
    std::thread::spawn(move || watch(&files, &options, &tx, &watcher_done));
    Reloader { versions, done }
}

/// The files' modification times and sizes (`None` for one that cannot be
/// read right now, e.g. while an editor replaces it).
fn stamps(files: &[PathBuf]) -> Vec<Option<(SystemTime, u64)>> {
    files
        .iter()
        .map(|f| {
            let meta = std::fs::metadata(f).ok()?;
            Some((meta.modified().ok()?, meta.len()))
        })
        .collect()
}

/// Polls until the run ends, compiling each changed version.
fn watch(files: &[PathBuf], options: &Options, tx: &Sender<Version>, done: &AtomicBool) {
    let mut seen = stamps(files);
    while !done.load(Ordering::Relaxed) {
        std::thread::sleep(POLL);
        let now = stamps(files);
        if now == seen || now.iter().any(Option::is_none) {
            continue;
        }
        seen = now;
        if tx.send(compile(files, options)).is_err() {
            return;
        }
    }
}

/// Loads and compiles the files as they are now.
fn compile(files: &[PathBuf], options: &Options) -> Version {
    let mut diags = Diagnostics::new();
    let sources = match load_files_with(files, options.encoding, &mut diags) {
        Ok(s) => s,
        Err(e) => return Version::Refused(format!("error: {e}\n")),
    };
    if diags.has_errors() {
        return Version::Refused(diags.render(&sources));
    }
    match Plc::compile(sources, options) {
        Ok(plc) => {
            let warnings = plc.warnings().render(plc.sources());
            Version::Compiled {
                plc: Box::new(plc),
                warnings,
            }
        }
        Err(e) => Version::Refused(e.to_string()),
    }
}

impl Reloader {
    /// Between two ticks: applies the version the watcher prepared, if
    /// any, and says on standard error what happened.
    pub(super) fn apply_pending(&self, session: &mut Session) {
        let Ok(version) = self.versions.try_recv() else {
            return;
        };
        let at = session.plc().cycle();
        match version {
            Version::Refused(diagnostics) => {
                say!("{diagnostics}");
                sayln!(
                    "reload before cycle {at} refused: the sources do not compile; the program runs on"
                );
            }
            Version::Compiled { plc, warnings } => {
                say!("{warnings}");
                match session.online_change(*plc) {
                    Ok(report) => {
                        sayln!("reload before cycle {at}: new version loaded");
                        for line in report.to_string().lines() {
                            sayln!("  {line}");
                        }
                    }
                    Err(e) => {
                        sayln!("reload before cycle {at} refused: {e}; the program runs on")
                    }
                }
            }
        }
    }
}
