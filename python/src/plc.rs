//! `plcrun.Plc`: a compiled program with its running state, on the
//! library's `Session` (a `Plc` with stimulus and trace), on a virtual
//! clock.

use crate::errors::{RetainError, compile_error, diagnostics_list, runtime_fault, variable_error};
use crate::errors::{bad_option, variable_message};
use crate::sources::{CompileArgs, duration_ns, source_map};
use crate::values::{literal_for, timedelta, to_py};
use plcrun::{
    Area, OnlineChangeError, Plc, RestoreMode, RuntimeFault, Session, Value, VarInfo, VarRef,
    VarShape,
};
use pyo3::exceptions::{PyTimeoutError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyDict, PyList};
use std::collections::HashMap;
use std::sync::Mutex;

/// Cycles run between two checks for Ctrl-C while the GIL is released.
pub const CHUNK: u64 = 4096;

/// A compiled IEC 61131-3 program running on a virtual clock.
///
/// Build one with `Plc.compile(sources, cycle_time="10ms")`; run cycles
/// with `run_cycle()` or `run(cycles=N)`; read and write variables with
/// `plc["Main.motor"]` (named as on the command line: `x`, `fb.Q`,
/// `arr[3]`, `S1.X`, `%IX0.1`). Every cycle advances the virtual clock by
/// the cycle time; nothing waits for the wall clock.
#[pyclass(name = "Plc", module = "plcrun")]
pub struct PyPlc {
    /// The PLC with its stimulus and trace state. Python objects must be
    /// `Sync` and a `Session` is not (its hooks are `Send` only): the
    /// mutex gives that, and costs nothing on the usual path, where
    /// PyO3's own borrow gives `&mut self` ([`Self::s`] uses `get_mut`).
    session: Mutex<Session>,
    /// Handles resolved so far, by name as given.
    refs: HashMap<String, VarRef>,
}

impl PyPlc {
    /// The session (exclusive access: no lock taken).
    pub fn s(&mut self) -> &mut Session {
        self.session.get_mut().unwrap_or_else(|e| e.into_inner())
    }

    /// A handle for `name`, resolved once.
    pub fn var(&mut self, py: Python<'_>, name: &str) -> PyResult<VarRef> {
        if let Some(r) = self.refs.get(name) {
            return Ok(r.clone());
        }
        let r = self
            .s()
            .plc()
            .resolve(name)
            .map_err(|e| variable_error(py, name, &e))?;
        self.refs.insert(name.to_string(), r.clone());
        Ok(r)
    }

    /// The value of `name`.
    pub fn value(&mut self, py: Python<'_>, name: &str) -> PyResult<Value> {
        if !self.refs.contains_key(name) {
            self.var(py, name)?;
        }
        // Borrowed from the cache, not cloned: a read allocates nothing
        // but the value.
        let session = self.session.get_mut().unwrap_or_else(|e| e.into_inner());
        match self.refs.get(name) {
            Some(r) => session
                .plc()
                .get(r)
                .map_err(|e| variable_error(py, name, &e)),
            None => Err(variable_message(
                py,
                name,
                format!("unknown variable `{name}`"),
            )),
        }
    }

    /// The library's value for the Python object `obj` written to `name`.
    pub fn value_for(
        &mut self,
        py: Python<'_>,
        name: &str,
        obj: &Bound<'_, PyAny>,
    ) -> PyResult<(VarRef, Value)> {
        let r = self.var(py, name)?;
        let plc = self.s().plc();
        let current = plc.get(&r).map_err(|e| variable_error(py, name, &e))?;
        let literal = literal_for(py, name, &current, obj)?;
        let v = plc
            .parse_value(&r, &literal)
            .map_err(|e| variable_error(py, name, &e))?;
        Ok((r, v))
    }

    /// Runs `cycles` cycles with the GIL released, checking for Ctrl-C
    /// between chunks.
    fn run_cycles(&mut self, py: Python<'_>, cycles: u64) -> PyResult<()> {
        let mut left = cycles;
        while left > 0 {
            let n = left.min(CHUNK);
            let plc = self.s().plc_mut();
            let result: Result<(), RuntimeFault> = py.detach(|| {
                for _ in 0..n {
                    plc.run_cycle()?;
                }
                Ok(())
            });
            result.map_err(|f| runtime_fault(py, &f))?;
            left -= n;
            py.check_signals()?;
        }
        Ok(())
    }

    /// After a new program version: handles resolved before are refused.
    fn forget_handles(&mut self) {
        self.refs.clear();
    }
}

#[pymethods]
impl PyPlc {
    /// Compiles `sources` into a PLC ready to run its first cycle.
    ///
    /// `sources`: a path, a list of paths, or a dict `{file name: text}`.
    /// `cycle_time`: the implicit task's cycle (`"10ms"`, `"T#100ms"` or a
    /// `datetime.timedelta`; default 10 ms). `program`: which PROGRAM to
    /// run when there are several. `watchdog`: wall-clock limit of one
    /// cycle (default 1 s; `"0s"` disables it). `strict`: every
    /// compatibility warning is an error. `grafcet`: IEC 60848 chart
    /// evolution. `addressing`: `"iec"`, `"openplc"` or `"byte"`.
    /// Raises `CompileError` with every diagnostic.
    #[staticmethod]
    #[allow(clippy::too_many_arguments)] // Python keyword arguments
    #[pyo3(signature = (sources, *, cycle_time=None, program=None, watchdog=None, strict=false, grafcet=false, addressing=None))]
    fn compile(
        py: Python<'_>,
        sources: &Bound<'_, PyAny>,
        cycle_time: Option<&Bound<'_, PyAny>>,
        program: Option<String>,
        watchdog: Option<&Bound<'_, PyAny>>,
        strict: bool,
        grafcet: bool,
        addressing: Option<String>,
    ) -> PyResult<PyPlc> {
        let args = CompileArgs {
            cycle_time,
            program,
            watchdog,
            strict,
            grafcet,
            addressing,
        };
        let options = args.options()?;
        let map = source_map(py, sources)?;
        let plc = py
            .detach(|| Plc::compile(map, &options))
            .map_err(|e| compile_error(py, &e))?;
        Ok(PyPlc {
            session: Mutex::new(Session::new(plc)),
            refs: HashMap::new(),
        })
    }

    /// Runs one cycle: reads the inputs, runs the tasks due, publishes the
    /// outputs, advances the virtual clock. Raises `RuntimeFault`.
    fn run_cycle(&mut self, py: Python<'_>) -> PyResult<()> {
        self.s()
            .plc_mut()
            .run_cycle()
            .map_err(|f| runtime_fault(py, &f))
    }

    /// Runs `cycles` cycles without returning to Python in between (the
    /// GIL is released: other Python threads run meanwhile).
    #[pyo3(signature = (cycles=1))]
    fn run(&mut self, py: Python<'_>, cycles: u64) -> PyResult<()> {
        self.run_cycles(py, cycles)
    }

    /// Runs `n` cycles (the pytest plugin's name for `run`).
    #[pyo3(signature = (n=1))]
    fn scan(&mut self, py: Python<'_>, n: u64) -> PyResult<()> {
        self.run_cycles(py, n)
    }

    /// Runs cycles until variable `name` equals `value` (default `True`),
    /// at most `timeout` of virtual time (`"5s"` or a timedelta). Returns
    /// the virtual time it took; raises `TimeoutError` when it did not happen.
    #[pyo3(signature = (name, timeout, value=None))]
    fn until(
        &mut self,
        py: Python<'_>,
        name: &str,
        timeout: &Bound<'_, PyAny>,
        value: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyAny>> {
        let limit = duration_ns("timeout", timeout)?;
        let wanted = match value {
            Some(v) => self.value_for(py, name, v)?.1,
            None => {
                self.value_for(py, name, pyo3::types::PyBool::new(py, true).as_any())?
                    .1
            }
        };
        let r = self.var(py, name)?;
        let start = self.s().plc().time();
        let plc = self.s().plc_mut();
        let outcome: Result<bool, RuntimeFault> = py.detach(|| {
            loop {
                if plc.get(&r).is_ok_and(|v| v == wanted) {
                    return Ok(true);
                }
                if plc.time() - start >= limit {
                    return Ok(false);
                }
                plc.run_cycle()?;
            }
        });
        let reached = outcome.map_err(|f| runtime_fault(py, &f))?;
        let took = self.s().plc().time() - start;
        if !reached {
            return Err(PyTimeoutError::new_err(format!(
                "`{name}` did not become {} within {} of virtual time",
                wanted.to_literal(),
                plcrun::format_duration(limit, "T#")
            )));
        }
        timedelta(py, took)
    }

    /// The value of a variable as a Python value (see the module's help
    /// for the types). Raises `VariableError`.
    fn __getitem__(&mut self, py: Python<'_>, name: &str) -> PyResult<Py<PyAny>> {
        let v = self.value(py, name)?;
        to_py(py, &v)
    }

    /// Writes a variable; a soft write (a forced variable keeps its forced
    /// value). Range checks are the library's: an `int` too large for an
    /// INT raises `VariableError`; a value of the wrong Python type
    /// `TypeError`.
    fn __setitem__(
        &mut self,
        py: Python<'_>,
        name: &str,
        value: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (r, v) = self.value_for(py, name, value)?;
        self.s()
            .plc_mut()
            .set(&r, &v)
            .map_err(|e| variable_error(py, name, &e))
    }

    /// True when `name` names a readable variable.
    fn __contains__(&mut self, py: Python<'_>, name: &str) -> bool {
        self.value(py, name).is_ok()
    }

    /// `plc[name]`, or `default` when there is no such variable.
    #[pyo3(signature = (name, default=None))]
    fn get(
        &mut self,
        py: Python<'_>,
        name: &str,
        default: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyAny>> {
        match self.value(py, name) {
            Ok(v) => to_py(py, &v),
            Err(_) => Ok(default.unwrap_or_else(|| py.None())),
        }
    }

    /// The value of `name` as an IEC literal (`T#1s`, `16#FF`, `'text'`).
    fn literal(&mut self, py: Python<'_>, name: &str) -> PyResult<String> {
        Ok(self.value(py, name)?.to_literal())
    }

    /// The number of the next cycle (cycles run so far).
    #[getter]
    fn cycle(&mut self) -> u64 {
        self.s().plc().cycle()
    }

    /// The virtual clock, as a `datetime.timedelta`.
    #[getter]
    fn time(&mut self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        timedelta(py, self.s().plc().time())
    }

    /// The virtual clock in nanoseconds.
    #[getter]
    fn time_ns(&mut self) -> i64 {
        self.s().plc().time()
    }

    /// The base tick of the clock, as a `datetime.timedelta`.
    #[getter]
    fn cycle_time(&mut self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        timedelta(py, self.s().plc().cycle_time())
    }

    /// The compiler's warnings, as `Diagnostic`s.
    #[getter]
    fn warnings<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let plc = self.s().plc();
        diagnostics_list(py, plc.warnings(), plc.sources())
    }

    /// Every variable the host can read (arrays, structures and FB
    /// instances expanded), as `Variable`s with path, type, direction,
    /// address and writability.
    fn variables(&mut self) -> Vec<PyVariable> {
        self.s()
            .plc()
            .variables()
            .iter()
            .map(PyVariable::new)
            .collect()
    }

    /// Forces `name` to `value`: neither the program nor writes change it
    /// until `unforce`.
    fn force(&mut self, py: Python<'_>, name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let (r, v) = self.value_for(py, name, value)?;
        self.s()
            .plc_mut()
            .force_value(&r, &v)
            .map_err(|e| variable_error(py, name, &e))
    }

    /// Releases the force on `name`; False when it was not forced.
    fn unforce(&mut self, py: Python<'_>, name: &str) -> PyResult<bool> {
        let r = self.var(py, name)?;
        Ok(self.s().plc_mut().unforce_ref(&r))
    }

    /// Releases every force.
    fn unforce_all(&mut self) {
        self.s().plc_mut().unforce_all();
    }

    /// The forced variables: `{path: value}`.
    fn forces<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for f in self.s().plc().forces() {
            d.set_item(&f.path, to_py(py, &f.value)?)?;
        }
        Ok(d)
    }

    /// A copy of one area of the process image (`"I"`, `"Q"` or `"M"`) as
    /// a `bytearray`, little-endian as docs/runtime.md lays it out.
    fn image<'py>(&mut self, py: Python<'py>, area: &str) -> PyResult<Bound<'py, PyByteArray>> {
        let a = parse_area(area)?;
        Ok(PyByteArray::new(py, self.s().plc().process_image().area(a)))
    }

    /// Writes `data` (bytes, bytearray, memoryview...) into the inputs
    /// (`"I"`) or memory (`"M"`) at byte `offset`; the program sees it from
    /// the next cycle. Outputs are the program's.
    #[pyo3(signature = (area, data, offset=0))]
    fn write_image(&mut self, area: &str, data: Vec<u8>, offset: usize) -> PyResult<()> {
        let image = self.s().plc_mut().process_image_mut();
        let table = match parse_area(area)? {
            Area::Input => image.inputs_mut(),
            Area::Memory => image.memory_mut(),
            Area::Output => return Err(bad_option("the outputs (%Q) are written by the program")),
        };
        let end = offset
            .checked_add(data.len())
            .filter(|end| *end <= table.len())
            .ok_or_else(|| {
                bad_option(format!(
                    "{} bytes at offset {offset} do not fit the {} bytes of %{area}",
                    data.len(),
                    table.len()
                ))
            })?;
        table[offset..end].copy_from_slice(&data);
        Ok(())
    }

    /// The active steps of every chart: `{instance path: [step names]}`.
    fn chart_states<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for c in self.s().plc().chart_states() {
            d.set_item(&c.path, c.active)?;
        }
        Ok(d)
    }

    /// The RETAIN and PERSISTENT variables: `[(name, type, persistent)]`.
    fn retained(&mut self) -> Vec<(String, String, bool)> {
        self.s()
            .plc()
            .retained()
            .into_iter()
            .map(|r| (r.name, r.type_name, r.persistent))
            .collect()
    }

    /// Writes the retained values to the JSON file `path` (atomically).
    fn save_retain(&mut self, path: std::path::PathBuf) -> PyResult<()> {
        self.s()
            .plc()
            .save_retain(path)
            .map_err(|e| RetainError::new_err(e.to_string()))
    }

    /// Restores retained values from `path`. With `partial=False` a file of
    /// another program version is refused (`RetainError`); with `True` the
    /// values that still fit are restored. Returns `{"restored": n,
    /// "cycle": c, "not_in_file": [...], "not_in_program": [...],
    /// "changed_type": [(name, file type, program type)]}`.
    #[pyo3(signature = (path, partial=false))]
    fn restore_retain<'py>(
        &mut self,
        py: Python<'py>,
        path: std::path::PathBuf,
        partial: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mode = if partial {
            RestoreMode::Partial
        } else {
            RestoreMode::Exact
        };
        let report = self
            .s()
            .plc_mut()
            .restore_retain(path, mode)
            .map_err(|e| RetainError::new_err(e.to_string()))?;
        let d = PyDict::new(py);
        d.set_item("restored", report.restored)?;
        d.set_item("cycle", report.cycle)?;
        let diff = &report.differences;
        d.set_item("not_in_file", &diff.not_in_file)?;
        d.set_item("not_in_program", &diff.not_in_program)?;
        let changed: Vec<(String, String, String)> = diff
            .changed_type
            .iter()
            .map(|c| (c.name.clone(), c.file.clone(), c.program.clone()))
            .collect();
        d.set_item("changed_type", changed)?;
        Ok(d)
    }

    /// Re-initialises everything but the retained values (a warm restart).
    fn reset_warm(&mut self) {
        self.s().plc_mut().reset_warm();
    }

    /// Re-initialises everything and clears a fault (a cold restart).
    fn reset_cold(&mut self) {
        self.s().plc_mut().reset_cold();
    }

    /// Loads a new version of the program between two cycles (online
    /// change): unchanged variables keep their values, timers keep timing.
    /// Takes the arguments of `compile`; returns `{"kept": [...],
    /// "initialised": [...], "dropped": [...], "retyped": [...],
    /// "charts_restarted": [...]}`. Refused versions raise `CompileError`
    /// or `PlcError`, and the old version runs on.
    #[pyo3(signature = (sources, *, cycle_time=None, program=None, watchdog=None, strict=false, grafcet=false, addressing=None))]
    #[allow(clippy::too_many_arguments)] // Python keyword arguments
    fn online_change<'py>(
        &mut self,
        py: Python<'py>,
        sources: &Bound<'py, PyAny>,
        cycle_time: Option<&Bound<'py, PyAny>>,
        program: Option<String>,
        watchdog: Option<&Bound<'py, PyAny>>,
        strict: bool,
        grafcet: bool,
        addressing: Option<String>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let args = CompileArgs {
            cycle_time,
            program,
            watchdog,
            strict,
            grafcet,
            addressing,
        };
        let options = args.options()?;
        let map = source_map(py, sources)?;
        let new = Plc::compile(map, &options).map_err(|e| compile_error(py, &e))?;
        let report = match self.s().plc_mut().online_change(new) {
            Ok(r) => r,
            Err(OnlineChangeError::Compile(e)) => return Err(compile_error(py, &e)),
            Err(e) => return Err(crate::errors::PlcError::new_err(e.to_string())),
        };
        self.forget_handles();
        let d = PyDict::new(py);
        d.set_item("kept", &report.kept)?;
        d.set_item("initialised", &report.initialised)?;
        d.set_item("dropped", &report.dropped)?;
        let retyped: Vec<(String, String, String)> = report
            .retyped
            .iter()
            .map(|r| (r.path.clone(), r.old_type.clone(), r.new_type.clone()))
            .collect();
        d.set_item("retyped", retyped)?;
        d.set_item("charts_restarted", &report.charts_restarted)?;
        Ok(d)
    }

    /// The names traced when none are given (every output, expanded).
    fn default_trace(&mut self) -> Vec<String> {
        self.s().plc().default_trace()
    }

    fn __repr__(&mut self) -> String {
        let plc = self.s().plc();
        format!(
            "<plcrun.Plc cycle={} time={}>",
            plc.cycle(),
            plcrun::format_duration(plc.time(), "T#")
        )
    }

    /// Runs `cycles` cycles as `plcrun FILES --cycles N --stimulus S
    /// --trace ...` does and returns the trace.
    ///
    /// `stimulus`: a dict `{name: [values]}` (row `i` before the `i`-th
    /// cycle of the run; a `"cycle"` or `"time"` entry keys the rows from
    /// the current cycle or clock; `None`/NaN leaves a variable unchanged)
    /// or a pandas DataFrame; or `csv`: a stimulus file or its text.
    /// `trace`: the names to sample after each cycle (default: every
    /// output). `on_cycle(plc)`: called after each cycle (a plant model);
    /// returning `False` ends the run. `output`: `"dict"` (lists),
    /// `"numpy"` (arrays) or `"pandas"` (a DataFrame); the trace has
    /// `cycle` and `time` first. Raises `StimulusError`, `VariableError`,
    /// `RuntimeFault`.
    #[pyo3(signature = (cycles, stimulus=None, *, csv=None, trace=None, on_cycle=None, output="dict"))]
    #[allow(clippy::too_many_arguments)] // Python keyword arguments
    fn simulate(
        slf: &Bound<'_, Self>,
        cycles: u64,
        stimulus: Option<&Bound<'_, PyAny>>,
        csv: Option<String>,
        trace: Option<Vec<String>>,
        on_cycle: Option<&Bound<'_, PyAny>>,
        output: &str,
    ) -> PyResult<Py<PyAny>> {
        crate::simulate::simulate(slf, cycles, stimulus, csv, trace, on_cycle, output)
    }
}

/// `"I"`, `"Q"`, `"M"` (or `"%I"`, `"input"`, ...) as an area.
fn parse_area(area: &str) -> PyResult<Area> {
    match area.trim_start_matches('%').to_ascii_lowercase().as_str() {
        "i" | "input" | "inputs" => Ok(Area::Input),
        "q" | "output" | "outputs" => Ok(Area::Output),
        "m" | "memory" => Ok(Area::Memory),
        _ => Err(PyTypeError::new_err(format!(
            "unknown area `{area}`: I, Q or M"
        ))),
    }
}

/// One variable as `Plc.variables()` lists it.
#[pyclass(name = "Variable", module = "plcrun", frozen, get_all)]
pub struct PyVariable {
    /// The path that reads it (`n`, `t1.ET`, `arr[2]`, `S1.X`).
    pub path: String,
    /// Its type's name (`INT`, `STRING[20]`, `Color`).
    pub r#type: String,
    /// `"input"`, `"output"`, `"local"`, `"global"`, `"step"` or `"action"`.
    pub direction: String,
    /// Its located address (`%IX0.1`), if any.
    pub address: Option<String>,
    /// Whether the host may write it.
    pub writable: bool,
    /// For an enumeration, its value names; else empty.
    pub values: Vec<String>,
}

impl PyVariable {
    fn new(v: &VarInfo) -> PyVariable {
        let direction = v.direction.name();
        let values = match &v.shape {
            VarShape::Enum { values } => values.clone(),
            _ => Vec::new(),
        };
        PyVariable {
            path: v.path.clone(),
            r#type: v.type_name.clone(),
            direction: direction.to_string(),
            address: v.address.clone(),
            writable: v.writable,
            values,
        }
    }
}

#[pymethods]
impl PyVariable {
    fn __repr__(&self) -> String {
        format!(
            "Variable({:?}, {}, {}{})",
            self.path,
            self.r#type,
            self.direction,
            if self.writable { "" } else { ", read-only" }
        )
    }
}
