//! The progress bar of long commands (`compare`, `test`, `check` of many
//! files, long virtual runs): drawn on standard error when it is a
//! terminal, never into a pipe, a file or a CI log, never with `--quiet`,
//! and only once the work has lasted long enough to be worth one.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use plcrun::Progress;
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Work shorter than this shows no bar: no flicker on quick commands.
const SHOW_AFTER: Duration = Duration::from_millis(400);

/// A bar on standard error, hidden until [`SHOW_AFTER`] has passed.
pub struct Bar {
    bar: ProgressBar,
    started: Instant,
    shown: AtomicBool,
}

impl Bar {
    /// A bar labelled `label` (`"check"`, `"test"`...), or `None` where
    /// none may be drawn: `--quiet`, standard error not a terminal, a CI
    /// run (the `CI` variable set, as CI services do) or TERM=dumb.
    pub fn new(label: &'static str) -> Option<Bar> {
        let ci = std::env::var_os("CI").is_some_and(|v| !v.is_empty() && v != "false");
        let dumb = std::env::var_os("TERM").is_some_and(|t| t == "dumb");
        if super::style::quiet() || ci || dumb || !std::io::stderr().is_terminal() {
            return None;
        }
        let bar = ProgressBar::hidden();
        let style = ProgressStyle::with_template(
            "{prefix:>8} [{bar:30}] {pos}/{len} {wide_msg} {elapsed_precise} (ETA {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
        bar.set_style(style);
        bar.set_prefix(label);
        Some(Bar {
            bar,
            started: Instant::now(),
            shown: AtomicBool::new(false),
        })
    }

    /// A bar for a run's cycles, only when the trace does not go to the
    /// terminal too (the two would tear each other's lines).
    pub fn for_run(trace_to_terminal: bool) -> Option<Bar> {
        if trace_to_terminal {
            return None;
        }
        Bar::new("run")
    }
}

impl Progress for Bar {
    fn report(&self, done: u64, total: u64, stage: &str) {
        if !self.shown.load(Ordering::Relaxed)
            && (self.started.elapsed() < SHOW_AFTER || done >= total)
        {
            return;
        }
        self.bar.set_length(total);
        self.bar.set_position(done);
        self.bar.set_message(stage.to_string());
        // Drawn from the first report after the wait, values already set.
        if !self.shown.swap(true, Ordering::Relaxed) {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }
}

impl Drop for Bar {
    /// The bar leaves no line behind: what the command prints next starts
    /// on a clean line.
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// What the library reports to: the bar, or nobody.
pub fn receiver(bar: &Option<Bar>) -> &dyn Progress {
    match bar {
        Some(bar) => bar,
        None => &(),
    }
}
