//! `--online-change-at N:FILE`: a run that loads new versions of the
//! program at given cycles, for tests and demonstrations of online change.

use plcrun::{Diagnostics, Options, Plc, RunError, Session, TraceWriter, load_files_with};
use std::io::Write;
use std::path::PathBuf;

/// A new version to load before a cycle.
pub(super) struct PlannedChange {
    /// The cycle before which it is loaded.
    at: u64,
    /// The file holding the whole new version.
    file: PathBuf,
}

/// Reads the `N:FILE` items, sorted by cycle (stable for equal cycles).
pub(super) fn planned(items: &[String]) -> Result<Vec<PlannedChange>, String> {
    let mut changes = Vec::with_capacity(items.len());
    for item in items {
        let bad = || format!("--online-change-at `{item}`: expected N:FILE (N a cycle number)");
        let (n, file) = item.split_once(':').ok_or_else(bad)?;
        let at: u64 = n.trim().parse().map_err(|_| bad())?;
        if file.is_empty() {
            return Err(bad());
        }
        changes.push(PlannedChange {
            at,
            file: PathBuf::from(file),
        });
    }
    changes.sort_by_key(|c| c.at);
    Ok(changes)
}

/// Runs `cycles` cycles, applying each change before its cycle. A change
/// that cannot apply is reported on standard error and the running
/// program goes on, as a PLC does.
pub(super) fn run<W: Write>(
    session: &mut Session,
    cycles: u64,
    writer: &mut TraceWriter<W>,
    changes: &[PlannedChange],
    options: &Options,
) -> Result<(), RunError> {
    let end = session.plc().cycle().saturating_add(cycles);
    for change in changes.iter().filter(|c| c.at < end) {
        let now = session.plc().cycle();
        session.run(change.at.saturating_sub(now), writer)?;
        apply(session, change, options);
    }
    let now = session.plc().cycle();
    session.run(end.saturating_sub(now), writer)
}

/// Compiles the new version and applies it, saying what happened.
fn apply(session: &mut Session, change: &PlannedChange, options: &Options) {
    let at = session.plc().cycle();
    let mut diags = Diagnostics::new();
    let sources = match load_files_with(
        std::slice::from_ref(&change.file),
        options.encoding,
        &mut diags,
    ) {
        Ok(s) => s,
        Err(e) => {
            sayln!("online change before cycle {at} refused: {e}");
            return;
        }
    };
    if diags.has_errors() {
        say!("{}", diags.render(&sources));
        sayln!("online change before cycle {at} refused; the program runs on");
        return;
    }
    let new = match Plc::compile(sources, options) {
        Ok(plc) => plc,
        Err(e) => {
            say!("{e}");
            sayln!(
                "online change before cycle {at} refused: `{}` does not compile; the program runs on",
                change.file.display()
            );
            return;
        }
    };
    match session.online_change(new) {
        Ok(report) => {
            sayln!(
                "online change before cycle {at}: `{}` loaded",
                change.file.display()
            );
            for line in report.to_string().lines() {
                sayln!("  {line}");
            }
        }
        Err(e) => sayln!("{e} (before cycle {at}); the program runs on"),
    }
}
