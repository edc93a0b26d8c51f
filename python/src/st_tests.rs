//! `plcrun.run_st_tests`: the unit tests written in IEC (`TEST_` POUs and
//! TcUnit suites), found and run by the library as `plcrun test` runs
//! them; the pytest plugin turns each case into a pytest item.

use crate::errors::{compile_error, runtime_fault};
use crate::sources::{duration_ns, source_map};
use plcrun::{TestCase, TestError, TestOptions, TestOutcome, run_tests};
use pyo3::prelude::*;
use std::time::Duration;

/// One unit test written in IEC and its outcome.
#[pyclass(name = "StTest", module = "plcrun", frozen, get_all)]
pub struct PyStTest {
    /// The name in reports: the POU's, or `Suite.Test` for TcUnit.
    pub name: String,
    /// The file that declares it.
    pub file: String,
    /// `"passed"`, `"failed"` or `"errored"`.
    pub outcome: String,
    /// Cycles it ran.
    pub cycles: u64,
    /// Assertions checked.
    pub assertions: usize,
    /// Wall-clock seconds it took.
    pub seconds: f64,
    /// One line per failed assertion (`file:line:col: message: expected
    /// E, got A (cycle c)`), the fault, or why it did not finish.
    pub failures: Vec<String>,
    /// What a TcUnit test logged.
    pub output: Vec<String>,
    /// The runtime fault (a `RuntimeFault` exception object) that stopped
    /// it, if any.
    pub fault: Option<Py<PyAny>>,
}

#[pymethods]
impl PyStTest {
    fn __repr__(&self) -> String {
        format!("StTest({:?}, {})", self.name, self.outcome)
    }

    /// The failures as one text, for a test report.
    fn report(&self) -> String {
        self.failures.join("\n")
    }
}

impl PyStTest {
    fn new(py: Python<'_>, case: &TestCase) -> PyStTest {
        let outcome = match case.outcome() {
            TestOutcome::Passed => "passed",
            TestOutcome::Failed => "failed",
            TestOutcome::Errored => "errored",
            TestOutcome::Skipped => "skipped",
        };
        let mut failures: Vec<String> = case
            .failures
            .iter()
            .map(|f| {
                format!(
                    "{}: {}: expected {}, got {} (cycle {})",
                    f.location, f.message, f.expected, f.actual, f.cycle
                )
            })
            .collect();
        if case.more_failures > 0 {
            failures.push(format!(
                "... and {} more failed assertions",
                case.more_failures
            ));
        }
        if let Some(f) = &case.fault {
            failures.push(f.to_string());
        }
        if case.unfinished {
            failures.push(format!(
                "did not finish: TEST_DONE was not set within {} cycles",
                case.cycles
            ));
        }
        PyStTest {
            name: case.full_name(),
            file: case.file.clone(),
            outcome: outcome.to_string(),
            cycles: case.cycles,
            assertions: case.assertions,
            seconds: case.elapsed.as_secs_f64(),
            failures,
            output: case.output.clone(),
            fault: case
                .fault
                .as_ref()
                .map(|f| runtime_fault(py, f).into_value(py).into_any()),
        }
    }
}

/// Finds the `TEST_` PROGRAMs and FUNCTION_BLOCKs (and TcUnit suites) of
/// `sources` (paths or `{name: text}`: the code under test and the tests)
/// and runs each on a fresh PLC, as `plcrun test` does. Returns a list of
/// `StTest` (empty when there is no test); raises `CompileError`.
#[pyfunction]
#[pyo3(signature = (sources, *, cycle_time=None, watchdog=None, filter=None, strict=false))]
pub fn run_st_tests(
    py: Python<'_>,
    sources: &Bound<'_, PyAny>,
    cycle_time: Option<&Bound<'_, PyAny>>,
    watchdog: Option<&Bound<'_, PyAny>>,
    filter: Option<String>,
    strict: bool,
) -> PyResult<Vec<PyStTest>> {
    let mut options = TestOptions {
        filter,
        strict,
        ..TestOptions::default()
    };
    if let Some(ct) = cycle_time {
        let ns = duration_ns("cycle_time", ct)?;
        if ns <= 0 {
            return Err(crate::errors::bad_option("cycle_time must be positive"));
        }
        options.cycle_time = ns;
    }
    if let Some(w) = watchdog {
        let ns = duration_ns("watchdog", w)?;
        options.watchdog = (ns > 0).then(|| Duration::from_nanos(ns as u64));
    }
    let map = source_map(py, sources)?;
    match py.detach(|| run_tests(&map, &options)) {
        Ok(report) => Ok(report.cases.iter().map(|c| PyStTest::new(py, c)).collect()),
        Err(TestError::NoTests) => Ok(Vec::new()),
        Err(TestError::Compile(e)) => Err(compile_error(py, &e)),
        Err(e) => Err(crate::errors::PlcError::new_err(e.to_string())),
    }
}
