//! The Python exceptions of the package and their construction from the
//! library's typed errors: `CompileError` with its diagnostics,
//! `RuntimeFault` with its code and instance path, `VariableError`.

use plcrun::{CompileError as RsCompileError, Diagnostic, RuntimeFault as RsFault, Severity};
use plcrun::{SourceMap, VarError};
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyList;

pyo3::create_exception!(
    plcrun,
    PlcError,
    PyException,
    "Base class of every error plcrun raises."
);
pyo3::create_exception!(
    plcrun,
    CompileError,
    PlcError,
    "The sources do not compile. `.diagnostics` lists every diagnostic \
     (errors and warnings), each with code, severity, file, line, column and message."
);
pyo3::create_exception!(
    plcrun,
    RuntimeFault,
    PlcError,
    "The program faulted in a cycle (division by zero, index out of range, \
     watchdog...): `.code` (R001...), `.instance` (instance path), `.pou`, \
     `.file`, `.line`, `.column`, `.cycle`. The PLC stays faulted until a reset."
);
pyo3::create_exception!(
    plcrun,
    VariableError,
    PlcError,
    "A variable cannot be read or written: unknown name, bad index, \
     read-only, or a value that does not fit its type (`.path`)."
);
pyo3::create_exception!(
    plcrun,
    StimulusError,
    PlcError,
    "A stimulus (dict, DataFrame or CSV) cannot be applied to the program."
);
pyo3::create_exception!(
    plcrun,
    RetainError,
    PlcError,
    "A retain file cannot be written or does not fit the program."
);

/// One diagnostic of the compiler, with its position resolved.
#[pyclass(name = "Diagnostic", module = "plcrun", frozen, get_all)]
#[derive(Clone)]
pub struct PyDiagnostic {
    /// The stable code (`E201`, `W204`, ...; docs/diagnostics.md).
    pub code: String,
    /// `"error"` or `"warning"`.
    pub severity: String,
    /// The file name as given to the compiler.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// The message.
    pub message: String,
    /// Help notes.
    pub notes: Vec<String>,
}

#[pymethods]
impl PyDiagnostic {
    fn __repr__(&self) -> String {
        format!(
            "Diagnostic({:?}, {}:{}:{}, {:?})",
            self.code, self.file, self.line, self.column, self.message
        )
    }

    fn __str__(&self) -> String {
        format!(
            "{}:{}:{}: {}[{}]: {}",
            self.file, self.line, self.column, self.severity, self.code, self.message
        )
    }
}

impl PyDiagnostic {
    /// `d` with its span turned into file, line and column of `sources`.
    pub fn new(d: &Diagnostic, sources: &SourceMap) -> PyDiagnostic {
        let (file, line, column) = match sources.files().get(d.span.file.0 as usize) {
            Some(f) => {
                let (line, column) = f.line_col(d.span.start);
                (f.name.clone(), line, column)
            }
            None => (String::new(), 0, 0),
        };
        PyDiagnostic {
            code: d.code.to_string(),
            severity: match d.severity {
                Severity::Error => "error",
                Severity::Warning => "warning",
            }
            .to_string(),
            file,
            line,
            column,
            message: d.message.clone(),
            notes: d.notes.clone(),
        }
    }
}

/// The diagnostics of `diags` as Python objects, in the order the compiler
/// sorts them.
pub fn diagnostics_list<'py>(
    py: Python<'py>,
    diags: &plcrun::Diagnostics,
    sources: &SourceMap,
) -> PyResult<Bound<'py, PyList>> {
    let items: Vec<PyDiagnostic> = diags
        .sorted()
        .into_iter()
        .map(|d| PyDiagnostic::new(d, sources))
        .collect();
    PyList::new(py, items)
}

/// A `CompileError` exception carrying the diagnostics of `e`.
pub fn compile_error(py: Python<'_>, e: &RsCompileError) -> PyErr {
    let err = CompileError::new_err(e.to_string());
    match diagnostics_list(py, &e.diagnostics, &e.sources) {
        Ok(list) => match err.value(py).setattr("diagnostics", list) {
            Ok(()) => err,
            Err(e) => e,
        },
        Err(e) => e,
    }
}

/// A `RuntimeFault` exception carrying the code, place and cycle of `f`.
pub fn runtime_fault(py: Python<'_>, f: &RsFault) -> PyErr {
    let err = RuntimeFault::new_err(f.to_string());
    let (file, line, column) = split_location(&f.location);
    let v = err.value(py);
    let set = || -> PyResult<()> {
        v.setattr("code", f.code())?;
        v.setattr("instance", f.instance())?;
        v.setattr("pou", &f.pou)?;
        v.setattr("location", &f.location)?;
        v.setattr("file", file)?;
        v.setattr("line", line)?;
        v.setattr("column", column)?;
        v.setattr("cycle", f.cycle)?;
        v.setattr("kind", f.fault.kind.to_string())?;
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// `file:line:column` split into its parts (the file name may hold colons).
fn split_location(location: &str) -> (String, usize, usize) {
    let mut parts = location.rsplitn(3, ':');
    let column = parts.next().and_then(|c| c.parse().ok());
    let line = parts.next().and_then(|l| l.parse().ok());
    match (parts.next(), line, column) {
        (Some(file), Some(line), Some(column)) => (file.to_string(), line, column),
        _ => (location.to_string(), 0, 0),
    }
}

/// A `VariableError` for `path`, saying what `e` says.
pub fn variable_error(py: Python<'_>, path: &str, e: &VarError) -> PyErr {
    variable_message(py, path, e.to_string())
}

/// A `VariableError` for `path` with a message of our own.
pub fn variable_message(py: Python<'_>, path: &str, message: String) -> PyErr {
    let err = VariableError::new_err(message);
    match err.value(py).setattr("path", path) {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// A `ValueError` for an option given to `compile` or `run`.
pub fn bad_option(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}
