//! The Python face of plcrun (`import plcrun`): a thin layer of PyO3 over
//! the library's public API (docs/python.md). Nothing here runs a cycle
//! or decodes a value itself: compiling, running, variable access,
//! forcing, retain, online change, stimulus and unit tests are the
//! library's; this crate turns Python values into IEC literals and the
//! library's values and errors into Python ones.

mod campaign;
mod errors;
mod plc;
mod simulate;
mod sources;
mod st_tests;
mod values;

use pyo3::prelude::*;

/// The compiled extension module; `plcrun/__init__.py` re-exports it.
#[pymodule]
fn _plcrun(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<plc::PyPlc>()?;
    m.add_class::<plc::PyVariable>()?;
    m.add_class::<errors::PyDiagnostic>()?;
    m.add_class::<st_tests::PyStTest>()?;
    m.add_class::<campaign::PyComparePair>()?;
    m.add_function(wrap_pyfunction!(st_tests::run_st_tests, m)?)?;
    m.add("PlcError", py.get_type::<errors::PlcError>())?;
    m.add("CompileError", py.get_type::<errors::CompileError>())?;
    m.add("RuntimeFault", py.get_type::<errors::RuntimeFault>())?;
    m.add("VariableError", py.get_type::<errors::VariableError>())?;
    m.add("StimulusError", py.get_type::<errors::StimulusError>())?;
    m.add("RetainError", py.get_type::<errors::RetainError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
