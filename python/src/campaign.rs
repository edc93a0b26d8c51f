//! `plcrun._plcrun.ComparePair`: the two programs of `plcrun compare`,
//! compiled once, for `plcrun.campaign` to run chunks of random seeds on
//! the workers of any executor and to write the merged report.
//!
//! A chunk runs each seed as the library's `run_seeds` does (the seed's
//! random plan, one paired run, the cycles it took); the report is the
//! library's `CompareReport`, whose text is what `plcrun compare` prints.

use crate::errors::{PlcError, bad_option, compile_error};
use crate::sources::{duration_ns, source_map};
use plcrun::{CompareError, parse_map};
use plcrun::{CompareOptions, CompareReport, Options, Pair, Plc, RandomStimulus, StimulusSource};
use pyo3::prelude::*;
use std::sync::Mutex;

/// Two programs paired as `plcrun compare A -- B` pairs them, with the
/// random stimulus settings, compiled once (docs/python.md, "Campaigns").
#[pyclass(name = "ComparePair", module = "plcrun")]
pub struct PyComparePair {
    /// The pair (a mutex for `Sync`; `get_mut` on the usual path).
    pair: Mutex<Pair>,
    settings: RandomStimulus,
    cycles: u64,
    a_label: String,
    b_label: String,
}

fn compare_error(e: CompareError) -> PyErr {
    PlcError::new_err(e.to_string())
}

impl PyComparePair {
    fn pair(&mut self) -> &mut Pair {
        self.pair.get_mut().unwrap_or_else(|e| e.into_inner())
    }
}

#[pymethods]
impl PyComparePair {
    /// Compiles `a` and `b` (paths or `{name: text}`) and pairs them.
    /// `a_label`/`b_label` name them in the report (`plcrun compare`
    /// names them by their files). The keywords are `plcrun compare`'s
    /// options: `cycles`, `cycle_time`, `program_a`, `program_b`, `map`
    /// (`["A.x=B.y"]`), `ignore`, `lag`, `change_prob`, `min_hold`,
    /// `max_hold`.
    #[new]
    #[pyo3(signature = (a, b, *, a_label, b_label, cycles, cycle_time=None, program_a=None, program_b=None, map=Vec::new(), ignore=Vec::new(), lag=0, change_prob=0.1, min_hold=1, max_hold=20))]
    #[allow(clippy::too_many_arguments)] // Python keyword arguments
    fn new(
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        b: &Bound<'_, PyAny>,
        a_label: String,
        b_label: String,
        cycles: u64,
        cycle_time: Option<&Bound<'_, PyAny>>,
        program_a: Option<String>,
        program_b: Option<String>,
        map: Vec<String>,
        ignore: Vec<String>,
        lag: u64,
        change_prob: f64,
        min_hold: u64,
        max_hold: u64,
    ) -> PyResult<PyComparePair> {
        let mut base = Options::default();
        if let Some(ct) = cycle_time {
            base.cycle_time = duration_ns("cycle_time", ct)?;
            if base.cycle_time <= 0 {
                return Err(bad_option("cycle_time must be positive"));
            }
        }
        let compile = |sources: &Bound<'_, PyAny>, program: Option<String>| -> PyResult<Plc> {
            let options = Options {
                program,
                ..base.clone()
            };
            Plc::compile(source_map(py, sources)?, &options).map_err(|e| compile_error(py, &e))
        };
        let (pa, pb) = (compile(a, program_a)?, compile(b, program_b)?);
        let map = map
            .iter()
            .map(|m| parse_map(m).map_err(|e| bad_option(e.to_string())))
            .collect::<PyResult<Vec<_>>>()?;
        let options = CompareOptions { map, ignore, lag };
        let pair = Pair::new(pa, pb, &options).map_err(compare_error)?;
        let settings = RandomStimulus {
            change_prob,
            min_hold,
            max_hold,
        };
        settings.validate().map_err(compare_error)?;
        Ok(PyComparePair {
            pair: Mutex::new(pair),
            settings,
            cycles,
            a_label,
            b_label,
        })
    }

    /// Runs every seed in `start..stop` (the GIL released) and returns
    /// `(differing seeds, cycles run)`.
    fn run_seeds(&mut self, py: Python<'_>, start: u64, stop: u64) -> PyResult<(Vec<u64>, u64)> {
        let (settings, cycles) = (self.settings, self.cycles);
        let pair = self.pair();
        py.detach(|| {
            let mut differing = Vec::new();
            let mut ran = 0;
            for seed in start..stop {
                let plan = pair.random_plan(&settings, seed, cycles);
                let d = pair.run(&plan)?;
                ran += d.as_ref().map_or(cycles, |d| d.cycle + 1);
                if d.is_some() {
                    differing.push(seed);
                }
            }
            Ok((differing, ran))
        })
        .map_err(compare_error)
    }

    /// The text `plcrun compare --random START --seeds (STOP - START)`
    /// prints, for the merged `differing` seeds (ascending): the lowest
    /// one is run again here and its plan shrunk.
    fn report(
        &mut self,
        py: Python<'_>,
        start: u64,
        stop: u64,
        differing: Vec<u64>,
    ) -> PyResult<String> {
        let (settings, cycles) = (self.settings, self.cycles);
        let (a_label, b_label) = (self.a_label.clone(), self.b_label.clone());
        let pair = self.pair();
        let found = match differing.first() {
            None => None,
            Some(&seed) => {
                let plan = pair.random_plan(&settings, seed, cycles);
                let d = py.detach(|| pair.run(&plan)).map_err(compare_error)?;
                let d = d.ok_or_else(|| {
                    PlcError::new_err(format!(
                        "seed {seed} was reported differing but does not differ here"
                    ))
                })?;
                let shrunk = py
                    .detach(|| pair.shrink(&plan, &d))
                    .map_err(compare_error)?;
                Some((Some(seed), plan, d, shrunk))
            }
        };
        let report = CompareReport {
            a_label,
            b_label,
            pairing: pair.pairing().clone(),
            lag: pair.lag(),
            cycles,
            stimulus: StimulusSource::Random {
                settings,
                seeds: start..stop,
            },
            differing_seeds: differing,
            found,
        };
        Ok(report.to_string())
    }
}
