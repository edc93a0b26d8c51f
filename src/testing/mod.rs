//! The unit-test runner behind `plcrun test`: finds the test PROGRAMs and
//! FUNCTION_BLOCKs (names starting with `TEST_`), runs each on a fresh
//! [`crate::Plc`] in virtual time with the assertion functions
//! (`AssertEquals`, `AssertTrue`, ...) built in, and reports the outcome
//! as text or JUnit XML. docs/testing.md describes the convention.

mod assertions;
mod blank_globals;
mod check;
mod discover;
mod junit;
mod keep_going;
mod run_one;
mod tcunit;
mod text;

use crate::diagnostics::Diagnostics;
use crate::progress::Progress;
use crate::runtime::engine::{CompileError, RuntimeFault};
use crate::runtime::host_blocks::HostDeclError;
use crate::source::SourceMap;
use std::fmt;
use std::time::{Duration, Instant};

pub use discover::TEST_PREFIX;

/// How to run the tests.
#[derive(Debug, Clone)]
pub struct TestOptions {
    /// Run only the tests whose name contains this text (ignoring case).
    pub filter: Option<String>,
    /// Cycle time of the virtual clock, in nanoseconds (default 10 ms).
    pub cycle_time: i64,
    /// Wall-clock limit of one cycle of a test (default 1 s); `None`
    /// disables it. A test that exceeds it fails with fault R008.
    pub watchdog: Option<Duration>,
    /// Pure IEC 61131-3: every compatibility-extension warning (W300-W399)
    /// is an error (default false).
    pub strict: bool,
    /// How direct addresses are numbered (`--addressing`); `None` (the
    /// default) chooses from the sources, as [`crate::Options::addressing`].
    pub addressing: Option<crate::address::Addressing>,
    /// Leave out the files that do not compile (and those that need them)
    /// and run the tests of the others; the tests of the files left out
    /// are reported as errors (`--keep-going`, default false: any error
    /// stops the run before a test runs).
    pub keep_going: bool,
    /// Links of the I/O configuration from the PLC's outputs to its inputs
    /// ([`crate::project_io_links`]): before each cycle of the TcUnit
    /// suites, each input of a suite takes its output's value (default
    /// none).
    pub io_links: Vec<crate::address::IoLink>,
    /// The NC axes of the configuration and the `AXIS_REF`s they are
    /// linked to ([`crate::project_nc_axes`]): before the first cycle,
    /// each linked axis of a suite takes the axis' id, name and
    /// parameters (default none).
    pub nc_axes: Vec<crate::address::NcAxis>,
}

impl Default for TestOptions {
    fn default() -> Self {
        TestOptions {
            filter: None,
            cycle_time: 10_000_000,
            watchdog: Some(Duration::from_secs(1)),
            strict: false,
            addressing: None,
            keep_going: false,
            io_links: Vec::new(),
            nc_axes: Vec::new(),
        }
    }
}

/// One failed assertion.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AssertionFailure {
    /// `file:line:column` of the assertion call.
    pub location: String,
    /// The expected value, as an IEC literal.
    pub expected: String,
    /// The actual value, as an IEC literal.
    pub actual: String,
    /// The array index of the first differing element (`AssertArrayEquals`).
    pub index: Option<i64>,
    /// The path of the first differing element of a multi-dimensional
    /// array or an array of structures (`[2,3]`, `[1].x`; `AssertArrayEquals`).
    pub element: Option<String>,
    /// The assertion's message.
    pub message: String,
    /// The cycle it failed in (from 0).
    pub cycle: u64,
}

/// The verdict on one test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TestOutcome {
    /// Every assertion held and the test ran to its end.
    Passed,
    /// An assertion failed, or the test never set `TEST_DONE`.
    Failed,
    /// The test stopped on a runtime fault (JUnit `<error>`).
    Errored,
    /// A TcUnit test disabled by its name (`TEST('DISABLED_x')`): not
    /// run, as TcUnit skips it (JUnit `<skipped>`).
    Skipped,
}

/// What happened in one test.
#[derive(Debug, Clone)]
pub struct TestCase {
    /// The test POU's name, or the name a TcUnit test gave to `TEST`.
    pub name: String,
    /// The TcUnit suite instance the test belongs to (`PRG_TEST.fbSuite`);
    /// `None` for a `TEST_` POU.
    pub suite: Option<String>,
    /// The file declaring it.
    pub file: String,
    /// Cycles run (including a faulting one).
    pub cycles: u64,
    /// Wall-clock time spent, compile included.
    pub elapsed: Duration,
    /// The failed assertions, in order (at most 100 kept).
    pub failures: Vec<AssertionFailure>,
    /// Failed assertions beyond those kept.
    pub more_failures: usize,
    /// The runtime fault that stopped it.
    pub fault: Option<RuntimeFault>,
    /// It declares `TEST_DONE` and had not set it when its cycles ran out
    /// (a TcUnit test: it had not called `TEST_FINISHED`).
    pub unfinished: bool,
    /// The assertion calls a TcUnit test ran (each counted once however
    /// many cycles it ran in); 0 for a `TEST_` POU.
    pub assertions: usize,
    /// The lines a TcUnit test logged with `TCUNIT_ADSLOGSTR`.
    pub output: Vec<String>,
    /// Why it did not run: its file was left out because it does not
    /// compile (`TestOptions::keep_going`).
    pub left_out: Option<String>,
    /// A TcUnit test disabled by its name, `DISABLED_` before it (the
    /// name here is without it): its assertions are ignored.
    pub skipped: bool,
}

impl TestCase {
    /// The name in reports: `Suite.Test` for a TcUnit test, as
    /// TcUnit-Runner names it, the POU's name otherwise.
    pub fn full_name(&self) -> String {
        match &self.suite {
            Some(s) => format!("{s}.{}", self.name),
            None => self.name.clone(),
        }
    }
}

impl TestCase {
    /// The verdict.
    pub fn outcome(&self) -> TestOutcome {
        if self.fault.is_some() || self.left_out.is_some() {
            TestOutcome::Errored
        } else if self.skipped {
            TestOutcome::Skipped
        } else if !self.failures.is_empty() || self.unfinished {
            TestOutcome::Failed
        } else {
            TestOutcome::Passed
        }
    }
}

/// The outcome of [`run_tests`].
#[derive(Debug, Clone)]
pub struct TestReport {
    /// Every test run, in file and declaration order.
    pub cases: Vec<TestCase>,
    /// Wall-clock time of the whole run.
    pub elapsed: Duration,
    /// The sources' warnings, as `plcrun check` gives them (spans in the
    /// sources given to [`run_tests`]).
    pub warnings: Diagnostics,
    /// The files left out because they do not compile
    /// ([`TestOptions::keep_going`]), in the order given, each with its
    /// first error (`code: message at file:line:col`), then the global
    /// variables left out of their lists (`file, global `name``).
    pub left_out: Vec<(String, String)>,
}

impl TestReport {
    /// How many tests had outcome `o`.
    pub fn count(&self, o: TestOutcome) -> usize {
        self.cases.iter().filter(|c| c.outcome() == o).count()
    }

    /// True when there was at least one test and every test passed (or
    /// was disabled).
    pub fn all_passed(&self) -> bool {
        !self.cases.is_empty()
            && self.count(TestOutcome::Passed) + self.count(TestOutcome::Skipped)
                == self.cases.len()
    }

    /// The human-readable report: one line per test, the details of each
    /// failure, and a summary line.
    pub fn to_text(&self) -> String {
        text::render(self)
    }

    /// The report as JUnit XML (one `<testsuite>` named `suite`).
    pub fn to_junit(&self, suite: &str) -> String {
        junit::render(self, suite)
    }
}

/// Why the tests could not be run at all.
#[derive(Debug)]
pub enum TestError {
    /// The sources (with the assertions declared) do not compile.
    Compile(CompileError),
    /// No test matched (none declared, or none passed the filter).
    NoTests,
    /// The assertion functions could not be declared (an internal error).
    Host(HostDeclError),
}

impl fmt::Display for TestError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TestError::Compile(e) => e.fmt(f),
            TestError::NoTests => write!(
                f,
                "no test found: a test is a PROGRAM or FUNCTION_BLOCK whose name starts with {TEST_PREFIX}, or a TEST of a TcUnit suite (a FUNCTION_BLOCK extending FB_TestSuite)"
            ),
            TestError::Host(e) => write!(f, "cannot declare the assertions: {e}"),
        }
    }
}

impl std::error::Error for TestError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TestError::Compile(e) => Some(e),
            TestError::NoTests => None,
            TestError::Host(e) => Some(e),
        }
    }
}

/// When `sources` hold tests (TcUnit suites, or plcrun's `TEST_` POUs):
/// every diagnostic of `sources` checked as `plcrun test` compiles them,
/// with the assertions (and TcUnit's functions) declared, so that `plcrun
/// check` accepts what the test runner accepts; `None` when they hold no
/// test, and a plain check is the whole answer.
pub fn check_test_sources(
    sources: &SourceMap,
    options: &TestOptions,
) -> Option<Result<Diagnostics, TestError>> {
    // A suite extends FB_TestSuite and a test's name starts with TEST_, so
    // those words are written somewhere: without them, the sources need
    // not be parsed a second time.
    let files = sources.files();
    if files.iter().any(|f| tcunit::names_the_base(&f.text)) {
        let plan = tcunit::plan(sources, &mut Diagnostics::new());
        if !plan.suites.is_empty() {
            return Some(check::check(sources, options, &plan));
        }
    }
    let prefix = TEST_PREFIX.as_bytes();
    let writes_prefix = |text: &str| {
        text.as_bytes()
            .windows(prefix.len())
            .any(|w| w.eq_ignore_ascii_case(prefix))
    };
    if !files.iter().any(|f| writes_prefix(&f.text)) {
        return None;
    }
    if discover::find_tests(sources, &mut Diagnostics::new()).is_empty() {
        return None;
    }
    Some(check::check(sources, options, &tcunit::Plan::default()))
}

/// Finds the tests of `sources` and runs each on its own fresh runtime.
///
/// ```
/// use plcrun::{SourceMap, TestOptions, TestOutcome, run_tests};
///
/// let mut sources = SourceMap::new();
/// sources.add("add_test.st", "
/// FUNCTION Add3 : INT VAR_INPUT a, b, c : INT; END_VAR
///   Add3 := a + b + c;
/// END_FUNCTION
/// PROGRAM TEST_Add3
///   AssertEquals(INT#6, Add3(1, 2, 3), 'small numbers');
///   AssertEquals(INT#7, Add3(1, 2, 3), 'deliberately wrong');
/// END_PROGRAM
/// ");
/// let report = run_tests(&sources, &TestOptions::default())?;
/// let case = &report.cases[0];
/// assert_eq!(case.outcome(), TestOutcome::Failed);
/// assert_eq!(case.failures[0].location, "add_test.st:7:3");
/// assert_eq!((case.failures[0].expected.as_str(), case.failures[0].actual.as_str()), ("7", "6"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run_tests(sources: &SourceMap, options: &TestOptions) -> Result<TestReport, TestError> {
    run_tests_reporting(sources, options, &())
}

/// [`run_tests`], reporting to `progress`: the check of the sources as one
/// step, then each `TEST_` POU as it finishes, then the TcUnit suites (run
/// together, as TcUnit runs them) as one step each.
pub fn run_tests_reporting(
    sources: &SourceMap,
    options: &TestOptions,
    progress: &dyn Progress,
) -> Result<TestReport, TestError> {
    let start = Instant::now();
    let mut diags = Diagnostics::new();
    let found = discover::find_tests(sources, &mut diags);
    let suites = tcunit::plan(sources, &mut Diagnostics::new());
    let wanted = |name: &str| {
        options
            .filter
            .as_ref()
            .is_none_or(|f| name.to_ascii_lowercase().contains(&f.to_ascii_lowercase()))
    };
    let tests: Vec<_> = found.into_iter().filter(|t| wanted(&t.name)).collect();
    let total = 1 + tests.len() as u64 + suites.suites.len() as u64;
    progress.report(0, total, "check");
    // Every problem of every file, as `plcrun check` reports them (a
    // syntax error in one file does not hide the others'), then those of
    // the runner's own reading of the tests.
    let mut checked = check::check(sources, options, &suites)?;
    let mut cases = Vec::with_capacity(tests.len());
    let given = sources;
    let mut left_out = Vec::new();
    let kept;
    let (sources, suites, tests) = if checked.has_errors() && options.keep_going {
        kept = keep_going::leave_out_broken(sources, options, &suites, checked)?;
        // The runner's own reading again, of what is left.
        diags = Diagnostics::new();
        discover::find_tests(&kept.sources, &mut diags);
        cases = keep_going::left_out_cases(&tests, &suites, &kept.left_out);
        left_out = given
            .files()
            .iter()
            .filter_map(|f| {
                kept.left_out
                    .get(&f.name)
                    .map(|w| (f.name.clone(), w.clone()))
            })
            .collect();
        left_out.extend(kept.left_out_globals.iter().cloned());
        checked = kept.checked.clone();
        let remaining = keep_going::remaining(&suites, &kept.sources);
        let names: Vec<&str> = kept
            .sources
            .files()
            .iter()
            .map(|f| f.name.as_str())
            .collect();
        let tests: Vec<_> = tests
            .into_iter()
            .filter(|t| names.contains(&t.file.as_str()))
            .collect();
        (&kept.sources, remaining, tests)
    } else {
        (sources, suites, tests)
    };
    if checked.has_errors() || diags.has_errors() {
        checked.extend(discover::runner_errors(diags));
        return Err(TestError::Compile(CompileError {
            diagnostics: checked,
            sources: sources.clone(),
        }));
    }
    if tests.is_empty() && suites.suites.is_empty() && cases.is_empty() {
        return Err(TestError::NoTests);
    }
    for (i, test) in tests.iter().enumerate() {
        progress.report(1 + i as u64, total, &test.name);
        cases.push(run_one::run(sources, test, options)?);
    }
    if !suites.suites.is_empty() {
        progress.report(1 + tests.len() as u64, total, "TcUnit suites");
        let ran = tcunit::run(sources, &suites, options)?;
        cases.extend(ran.into_iter().filter(|c| wanted(&c.full_name())));
    }
    progress.report(total, total, "done");
    if cases.is_empty() {
        return Err(TestError::NoTests);
    }
    Ok(TestReport {
        cases,
        elapsed: start.elapsed(),
        warnings: check::warnings_in(&checked, sources, given),
        left_out,
    })
}
