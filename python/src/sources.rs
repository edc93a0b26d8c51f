//! The arguments of `Plc.compile` and `run_st_tests`: sources given as
//! files or as `{name: text}`, and durations given as IEC literals or
//! `datetime.timedelta`.

use crate::errors::{CompileError, bad_option, diagnostics_list};
use crate::values::timedelta_nanos;
use plcrun::{Addressing, Diagnostics, Options, SourceMap, load_files, parse_time_literal};
use pyo3::exceptions::{PyOSError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;
use std::time::Duration;

/// Sources from `obj`: a dict `{file name: text}`, one path (`str` or
/// `os.PathLike`), or a list of paths. Files are read as the command line
/// reads them (UTF-8, or their encoding detected).
pub fn source_map(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<SourceMap> {
    if let Ok(dict) = obj.cast::<PyDict>() {
        let mut sources = SourceMap::new();
        for (name, text) in dict.iter() {
            let name: String = name
                .extract()
                .map_err(|_| PyTypeError::new_err("source names must be str"))?;
            let text: String = text
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("the text of `{name}` must be a str")))?;
            sources.add(name, text);
        }
        return Ok(sources);
    }
    let paths: Vec<PathBuf> = if obj.is_instance_of::<PyString>() || obj.hasattr("__fspath__")? {
        vec![obj.extract()?]
    } else {
        obj.try_iter()
            .map_err(|_| {
                PyTypeError::new_err("sources: a path, a list of paths or a dict {name: text}")
            })?
            .map(|p| p.and_then(|p| p.extract::<PathBuf>()))
            .collect::<PyResult<_>>()?
    };
    if paths.is_empty() {
        return Err(bad_option("no source files given"));
    }
    let mut diags = Diagnostics::new();
    let sources = load_files(&paths, &mut diags).map_err(|e| PyOSError::new_err(e.to_string()))?;
    if diags.has_errors() {
        let err = CompileError::new_err(diags.render(&sources));
        err.value(py)
            .setattr("diagnostics", diagnostics_list(py, &diags, &sources)?)?;
        return Err(err);
    }
    Ok(sources)
}

/// A duration in nanoseconds from an IEC literal (`"10ms"`, `"T#1.5s"`) or
/// a `datetime.timedelta`.
pub fn duration_ns(what: &str, obj: &Bound<'_, PyAny>) -> PyResult<i64> {
    if let Ok(s) = obj.cast::<PyString>() {
        let text = &s.to_cow()?;
        return parse_time_literal(text).map_err(|e| bad_option(format!("{what}: {e}")));
    }
    timedelta_nanos(obj).map_err(|_| {
        PyTypeError::new_err(format!(
            "{what}: a duration as a str (\"10ms\", \"T#1s\") or a datetime.timedelta"
        ))
    })
}

/// The options every compile takes from Python keyword arguments.
pub struct CompileArgs<'a, 'py> {
    /// Cycle time of the implicit task (default 10 ms).
    pub cycle_time: Option<&'a Bound<'py, PyAny>>,
    /// The PROGRAM to run among several.
    pub program: Option<String>,
    /// Wall-clock limit of a cycle (default 1 s; a zero duration disables it).
    pub watchdog: Option<&'a Bound<'py, PyAny>>,
    /// `--strict`.
    pub strict: bool,
    /// IEC 60848 evolution of the charts.
    pub grafcet: bool,
    /// `iec`, `openplc` or `byte`.
    pub addressing: Option<String>,
}

impl CompileArgs<'_, '_> {
    /// The library's options.
    pub fn options(&self) -> PyResult<Options> {
        let mut options = Options {
            program: self.program.clone(),
            strict: self.strict,
            grafcet: self.grafcet,
            ..Options::default()
        };
        if let Some(ct) = self.cycle_time {
            let ns = duration_ns("cycle_time", ct)?;
            if ns <= 0 {
                return Err(bad_option("cycle_time must be positive"));
            }
            options.cycle_time = ns;
        }
        if let Some(w) = self.watchdog {
            let ns = duration_ns("watchdog", w)?;
            options.watchdog = match ns {
                0 => None,
                ns if ns > 0 => Some(Duration::from_nanos(ns as u64)),
                _ => return Err(bad_option("watchdog must not be negative")),
            };
        }
        if let Some(a) = &self.addressing {
            let parsed: Addressing = a.parse().map_err(|e| bad_option(format!("{e}")))?;
            options.addressing = Some(parsed);
        }
        Ok(options)
    }
}
