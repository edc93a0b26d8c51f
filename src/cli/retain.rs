//! `--retain FILE`: the warm (or cold) start before the run, the saver
//! during it and the last save after it.

use super::args::RunArgs;
use plcrun::{Plc, RestoreMode, RetainSaver};

/// Restores the retained values (unless `--cold` or the file is missing,
/// which are cold starts, said on stderr) and starts the saver. `Ok(None)`
/// without `--retain`; `Err` with the message of a file that cannot be
/// used.
pub fn start(args: &RunArgs, plc: &mut Plc) -> Result<Option<RetainSaver>, String> {
    let Some(path) = &args.retain else {
        return Ok(None);
    };
    let shown = path.display();
    if args.cold {
        sayln!(
            "note: cold start: the values in `{shown}` are not used (the file is overwritten with the initial values)"
        );
    } else {
        let mode = if args.retain_partial {
            RestoreMode::Partial
        } else {
            RestoreMode::Exact
        };
        match plc.restore_retain(path, mode) {
            Ok(report) => {
                sayln!(
                    "note: warm start: {} retained value{} restored from `{shown}` (saved after {} cycles)",
                    report.restored,
                    if report.restored == 1 { "" } else { "s" },
                    report.cycle
                );
                if !report.differences.is_empty() {
                    sayln!("note: not restored: {}", report.differences);
                }
            }
            Err(e) if e.is_missing_file() => {
                sayln!("note: cold start: retain file `{shown}` does not exist yet");
            }
            Err(e @ plcrun::RetainError::Mismatch { .. }) => {
                return Err(format!(
                    "{e}\n  hint: --retain-partial restores the values that fit, --cold starts from the initial values"
                ));
            }
            Err(e) => return Err(e.to_string()),
        }
    }
    // A first save now: a file that cannot be written is reported before
    // the run, not after it.
    plc.save_retain(path).map_err(|e| e.to_string())?;
    RetainSaver::new(plc, path)
        .map(Some)
        .map_err(|e| e.to_string())
}

/// The last save, after a run that ended at a cycle boundary; then the
/// writer is stopped. The message of a save that failed during the run or
/// now.
pub fn finish(saver: RetainSaver, plc: &Plc, save_now: bool) -> Result<(), String> {
    if save_now {
        saver.offer(plc).map_err(|e| e.to_string())?;
    }
    saver.finish().map(|_| ()).map_err(|e| e.to_string())
}
