//! `Plc.simulate`: a session run, as `plcrun FILES --cycles N --stimulus S
//! --trace ...` does it, with the stimulus given as a dict of lists, a
//! pandas DataFrame or a CSV, the trace returned as a dict of lists, a dict
//! of NumPy arrays or a DataFrame, and an optional per-cycle callback (a
//! plant model written in Python).
//!
//! The stimulus is handed to the library's `Session` (which applies the
//! rows due before each cycle); the binding only turns Python values into
//! IEC literals and samples the traced variables after each cycle.

use crate::errors::{StimulusError, bad_option, runtime_fault, variable_error};
use crate::plc::{CHUNK, PyPlc};
use crate::values::{literal_for, timedelta, timedelta_nanos, to_py};
use plcrun::{RunError, Stimulus, StimulusKey, StimulusRow, Value, VarRef, parse_stimulus};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList, PyString};

/// The rows sampled by a run: the cycle and clock of each row, then one
/// column of values per traced name.
struct Samples {
    cycles: Vec<u64>,
    times: Vec<i64>,
    columns: Vec<Vec<Value>>,
}

impl Samples {
    /// Runs one session cycle and samples `refs` after it.
    fn step(&mut self, plc: &mut PyPlc, refs: &[VarRef]) -> Result<(), RunError> {
        let (cycle, time) = (plc.s().plc().cycle(), plc.s().plc().time());
        plc.s().step()?;
        self.cycles.push(cycle);
        self.times.push(time);
        for (col, r) in self.columns.iter_mut().zip(refs) {
            // Resolved by this PLC just before the run: reading cannot fail.
            if let Ok(v) = plc.s().plc().get(r) {
                col.push(v);
            }
        }
        Ok(())
    }
}

/// See [`PyPlc::simulate`]; docs/python.md, "Session runs".
pub fn simulate(
    slf: &Bound<'_, PyPlc>,
    cycles: u64,
    stimulus: Option<&Bound<'_, PyAny>>,
    csv: Option<String>,
    trace: Option<Vec<String>>,
    on_cycle: Option<&Bound<'_, PyAny>>,
    output: &str,
) -> PyResult<Py<PyAny>> {
    let py = slf.py();
    if !matches!(output, "dict" | "numpy" | "pandas") {
        return Err(bad_option("output: \"dict\", \"numpy\" or \"pandas\""));
    }
    let (names, refs) = {
        let mut me = slf.borrow_mut();
        let stim = match (stimulus, csv) {
            (Some(_), Some(_)) => return Err(bad_option("give a stimulus or a csv, not both")),
            (Some(s), None) => stimulus_from_py(&mut me, s)?,
            (None, Some(csv)) => stimulus_from_csv(&csv)?,
            (None, None) => Stimulus {
                key: StimulusKey::Cycle,
                columns: vec![],
                rows: vec![],
            },
        };
        me.s()
            .bind_stimulus(stim)
            .map_err(|e| StimulusError::new_err(e.to_string()))?;
        // The session samples nothing itself: the values are read below.
        me.s()
            .set_trace::<&str>(&[])
            .map_err(|e| variable_error(py, "", &e))?;
        let names = trace.unwrap_or_else(|| me.s().plc().default_trace());
        let refs = names
            .iter()
            .map(|n| me.var(py, n))
            .collect::<PyResult<Vec<_>>>()?;
        (names, refs)
    };
    let mut samples = Samples {
        cycles: Vec::new(),
        times: Vec::new(),
        columns: vec![Vec::new(); refs.len()],
    };
    match on_cycle {
        None => run_detached(slf, cycles, &refs, &mut samples)?,
        Some(callback) => {
            for _ in 0..cycles {
                {
                    let mut me = slf.borrow_mut();
                    samples.step(&mut me, &refs).map_err(|e| run_error(py, e))?;
                }
                let verdict = callback.call1((slf,))?;
                if verdict.is_instance_of::<pyo3::types::PyBool>() && !verdict.is_truthy()? {
                    break;
                }
            }
        }
    }
    build_output(py, &names, samples, output)
}

/// The cycles of a run without callback, with the GIL released.
fn run_detached(
    slf: &Bound<'_, PyPlc>,
    cycles: u64,
    refs: &[VarRef],
    samples: &mut Samples,
) -> PyResult<()> {
    let py = slf.py();
    let mut left = cycles;
    while left > 0 {
        let n = left.min(CHUNK);
        let mut me = slf.borrow_mut();
        let plc: &mut PyPlc = &mut me;
        let result = py.detach(|| {
            for _ in 0..n {
                samples.step(plc, refs)?;
            }
            Ok(())
        });
        result.map_err(|e| run_error(py, e))?;
        left -= n;
        drop(me);
        py.check_signals()?;
    }
    Ok(())
}

fn run_error(py: Python<'_>, e: RunError) -> PyErr {
    match e {
        RunError::Fault(f) => runtime_fault(py, &f),
        other => crate::errors::PlcError::new_err(other.to_string()),
    }
}

/// A CSV stimulus: the text itself (with a header line), or a file path.
fn stimulus_from_csv(csv: &str) -> PyResult<Stimulus> {
    let text = if csv.contains('\n') {
        csv.to_string()
    } else {
        std::fs::read_to_string(csv)
            .map_err(|e| pyo3::exceptions::PyOSError::new_err(format!("{csv}: {e}")))?
    };
    parse_stimulus(&text).map_err(|e| StimulusError::new_err(e.to_string()))
}

/// A stimulus from a dict of lists (or anything with `to_dict("list")`, as
/// a pandas DataFrame). A `cycle` or `time` column keys the rows (counted
/// from the PLC's current cycle or clock); without one, row `i` is applied
/// before the `i`-th cycle of the run. `None` or NaN leaves the variable
/// unchanged.
fn stimulus_from_py(plc: &mut PyPlc, obj: &Bound<'_, PyAny>) -> PyResult<Stimulus> {
    let py = obj.py();
    let dict = match obj.cast::<PyDict>() {
        Ok(d) => d.clone(),
        Err(_) if obj.hasattr("to_dict")? => obj
            .call_method1("to_dict", ("list",))?
            .cast_into::<PyDict>()
            .map_err(|_| PyTypeError::new_err("stimulus.to_dict(\"list\") is not a dict"))?,
        Err(_) => {
            return Err(PyTypeError::new_err(
                "stimulus: a dict {name: [values]} or a pandas DataFrame",
            ));
        }
    };
    let mut key = None;
    let mut columns = Vec::new();
    let mut cells: Vec<Vec<Option<String>>> = Vec::new();
    let mut rows = None;
    for (name, values) in dict.iter() {
        let name: String = name
            .extract()
            .map_err(|_| PyTypeError::new_err("stimulus column names must be str"))?;
        let values: Vec<Bound<'_, PyAny>> = values
            .try_iter()
            .map_err(|_| PyTypeError::new_err(format!("stimulus column `{name}` is not a list")))?
            .collect::<PyResult<_>>()?;
        if *rows.get_or_insert(values.len()) != values.len() {
            return Err(StimulusError::new_err(format!(
                "stimulus column `{name}` has {} rows, the first column {}",
                values.len(),
                rows.unwrap_or(0)
            )));
        }
        if name == "cycle" || name == "time" {
            key = Some((name, values));
            continue;
        }
        let r = plc.var(py, &name)?;
        let current = plc
            .s()
            .plc()
            .get(&r)
            .map_err(|e| variable_error(py, &name, &e))?;
        let mut column = Vec::with_capacity(values.len());
        for (i, v) in values.iter().enumerate() {
            if is_missing(v)? {
                column.push(None);
                continue;
            }
            let literal = literal_for(py, &name, &current, v)?;
            let value = plc.s().plc().parse_value(&r, &literal).map_err(|e| {
                StimulusError::new_err(format!("stimulus column `{name}`, row {i}: {e}"))
            })?;
            column.push(Some(value.to_literal()));
        }
        columns.push(name);
        cells.push(column);
    }
    let n = rows.unwrap_or(0);
    let (kind, ats) = row_keys(plc, key, n)?;
    let rows = (0..n)
        .map(|i| StimulusRow {
            line: i + 1,
            at: ats[i],
            cells: cells.iter().map(|c| c[i].clone()).collect(),
        })
        .collect();
    Ok(Stimulus {
        key: kind,
        columns,
        rows,
    })
}

/// The key of each of `n` rows, from the PLC's current cycle or time.
fn row_keys(
    plc: &mut PyPlc,
    key: Option<(String, Vec<Bound<'_, PyAny>>)>,
    n: usize,
) -> PyResult<(StimulusKey, Vec<i64>)> {
    let p = plc.s().plc();
    let (kind, ats) = match key {
        None => (
            StimulusKey::Cycle,
            (0..n as i64).map(|i| p.cycle() as i64 + i).collect(),
        ),
        Some((name, values)) if name == "cycle" => {
            let ats = values
                .iter()
                .map(|v| v.extract::<i64>().map(|c| p.cycle() as i64 + c))
                .collect::<PyResult<Vec<_>>>()
                .map_err(|_| PyTypeError::new_err("stimulus `cycle` column: ints"))?;
            (StimulusKey::Cycle, ats)
        }
        Some((_, values)) => {
            let ats = values
                .iter()
                .map(|v| {
                    let ns = match v.cast::<PyString>() {
                        Ok(s) => plcrun::parse_time_literal(&s.to_cow()?)
                            .map_err(|e| StimulusError::new_err(e.to_string()))?,
                        Err(_) => timedelta_nanos(v).map_err(|_| {
                            PyTypeError::new_err("stimulus `time` column: timedelta or \"10ms\"")
                        })?,
                    };
                    Ok(p.time() + ns)
                })
                .collect::<PyResult<Vec<_>>>()?;
            (StimulusKey::Time, ats)
        }
    };
    if ats.windows(2).any(|w| w[0] > w[1]) {
        return Err(StimulusError::new_err("stimulus keys must not decrease"));
    }
    Ok((kind, ats))
}

/// `None`, or a float NaN (pandas' missing value).
fn is_missing(v: &Bound<'_, PyAny>) -> PyResult<bool> {
    if v.is_none() {
        return Ok(true);
    }
    if let Ok(f) = v.cast::<PyFloat>() {
        return Ok(f.value().is_nan());
    }
    Ok(false)
}

/// The trace as a dict of lists, of NumPy arrays, or a pandas DataFrame.
fn build_output(py: Python<'_>, names: &[String], s: Samples, output: &str) -> PyResult<Py<PyAny>> {
    let d = PyDict::new(py);
    d.set_item("cycle", &s.cycles)?;
    match output {
        "dict" => {
            let times = s
                .times
                .iter()
                .map(|t| timedelta(py, *t))
                .collect::<PyResult<Vec<_>>>()?;
            d.set_item("time", times)?;
        }
        _ => {
            let np = py.import("numpy")?;
            let kw = PyDict::new(py);
            kw.set_item("dtype", "timedelta64[ns]")?;
            d.set_item("time", np.call_method("array", (&s.times,), Some(&kw))?)?;
        }
    }
    for (name, col) in names.iter().zip(s.columns) {
        let values = col
            .iter()
            .map(|v| to_py(py, v))
            .collect::<PyResult<Vec<_>>>()?;
        d.set_item(name, PyList::new(py, values)?)?;
    }
    match output {
        "dict" => Ok(d.into_any().unbind()),
        "numpy" => {
            let np = py.import("numpy")?;
            let out = PyDict::new(py);
            for (k, v) in d.iter() {
                out.set_item(k, np.call_method1("asarray", (v,))?)?;
            }
            Ok(out.into_any().unbind())
        }
        _ => Ok(py
            .import("pandas")?
            .call_method1("DataFrame", (d,))?
            .unbind()),
    }
}
