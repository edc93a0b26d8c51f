//! How far a long piece of work has got. The library reports; a front end
//! (the command line's progress bar, a window, a log) decides what to show.

/// Receives the progress of a long piece of work: a comparison over many
/// seeds ([`crate::run_seeds_reporting`]), a test run
/// ([`crate::run_tests_reporting`]), a check of many files
/// ([`crate::check_reporting`]), a long virtual run
/// ([`crate::Session::run_reporting`]).
///
/// Reports may come from several threads at once and as often as the work
/// moves (a comparison reports every seed): a receiver that draws should
/// throttle itself. `()` receives nothing, at no cost.
///
/// ```
/// use plcrun::{Progress, SourceMap, CheckOptions, check_reporting};
/// use std::sync::Mutex;
/// struct Log(Mutex<Vec<(u64, u64, String)>>);
/// impl Progress for Log {
///     fn report(&self, done: u64, total: u64, stage: &str) {
///         self.0.lock().unwrap().push((done, total, stage.to_string()));
///     }
/// }
/// let mut sources = SourceMap::new();
/// sources.add("a.st", "PROGRAM A VAR x : INT; END_VAR x := 1; END_PROGRAM");
/// sources.add("b.st", "FUNCTION F : INT F := 2; END_FUNCTION");
/// let log = Log(Mutex::new(Vec::new()));
/// let report = check_reporting(&sources, &CheckOptions::default(), &log);
/// assert!(!report.diagnostics.has_errors());
/// let log = log.0.into_inner().unwrap();
/// assert_eq!(log.first(), Some(&(0, 3, "a.st".to_string())));
/// assert_eq!(log.last(), Some(&(3, 3, "done".to_string())));
/// ```
pub trait Progress: Sync {
    /// `done` of `total` steps are finished; `stage` says what is under way
    /// (a file's name, `"check"`, a test's name, `"cycles"`, `"seeds"`).
    fn report(&self, done: u64, total: u64, stage: &str);
}

/// Nobody watches.
impl Progress for () {
    #[inline(always)]
    fn report(&self, _done: u64, _total: u64, _stage: &str) {}
}
