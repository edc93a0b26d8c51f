//! Running two programs side by side on one input plan, cycle by cycle.

use super::error::{CompareError, Side};
use super::follow::Follower;
use super::input_plan::InputPlan;
use super::pairing::{CompareOptions, InputKind, Pairing};
use super::stimulus_gen::RandomStimulus;
use crate::runtime::engine::Plc;
use crate::runtime::names::VarRef;
use crate::runtime::plc_value::Value;

/// Why an output counts as different at a cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mismatch {
    /// Without lag: the values differ.
    Values,
    /// A changed at `a_changed_at` to `value` and B had not followed within
    /// the lag.
    NotFollowed {
        /// The cycle of A's change.
        a_changed_at: u64,
        /// A's new value.
        value: String,
    },
    /// B changed while A had no change pending.
    BChangedAlone,
    /// B changed to another value than A's next one.
    WrongValue {
        /// A's next value.
        expected: String,
    },
}

/// One compared output that differs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputDifference {
    /// Index into [`Pairing::outputs`].
    pub output: usize,
    /// A's value after the cycle.
    pub a_value: String,
    /// B's value after the cycle.
    pub b_value: String,
    /// Why it counts as different.
    pub why: Mismatch,
}

impl OutputDifference {
    pub(crate) fn new(output: usize, a: &Value, b: &Value, why: Mismatch) -> OutputDifference {
        OutputDifference {
            output,
            a_value: a.to_literal(),
            b_value: b.to_literal(),
            why,
        }
    }
}

/// The first cycle where the programs differ.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Difference {
    /// The cycle (from 0).
    pub cycle: u64,
    /// Every compared output that differs at that cycle.
    pub outputs: Vec<OutputDifference>,
    /// A's runtime fault in that cycle, if it faulted (as `R...: what`).
    pub fault_a: Option<String>,
    /// B's runtime fault in that cycle.
    pub fault_b: Option<String>,
}

/// One program of the pair, with its resolved handles.
struct Runner {
    plc: Plc,
    inputs: Vec<VarRef>,
    outputs: Vec<VarRef>,
    values: Vec<Value>,
}

impl Runner {
    fn new(plc: Plc, side: Side, pairing: &Pairing) -> Result<Runner, CompareError> {
        let pick = |p: &super::pairing::PairedVar| match side {
            Side::A => p.a.clone(),
            Side::B => p.b.clone(),
        };
        let resolve = |name: String| {
            plc.resolve(&name)
                .map_err(|error| CompareError::UnknownName { side, name, error })
        };
        let inputs = pairing
            .inputs
            .iter()
            .map(|p| resolve(pick(p)))
            .collect::<Result<_, _>>()?;
        let outputs = pairing
            .outputs
            .iter()
            .map(|p| resolve(pick(p)))
            .collect::<Result<_, _>>()?;
        Ok(Runner {
            plc,
            inputs,
            outputs,
            values: Vec::new(),
        })
    }

    /// Reads the compared outputs into `values`.
    fn sample(&mut self) {
        self.values.clear();
        for r in &self.outputs {
            // Resolved by this PLC: reading cannot fail.
            if let Ok(v) = self.plc.get(r) {
                self.values.push(v);
            }
        }
    }
}

/// Two compiled programs, paired for comparison.
pub struct Pair {
    a: Runner,
    b: Runner,
    pairing: Pairing,
    lag: u64,
}

impl Pair {
    /// Pairs `a` and `b` (see [`Pairing`]); refuses unknown names, programs
    /// without common inputs or compared outputs, and different base ticks.
    pub fn new(a: Plc, b: Plc, options: &CompareOptions) -> Result<Pair, CompareError> {
        if a.cycle_time() != b.cycle_time() {
            return Err(CompareError::TicksDiffer {
                a: a.cycle_time(),
                b: b.cycle_time(),
            });
        }
        let pairing = Pairing::new(&a, &b, options)?;
        Ok(Pair {
            a: Runner::new(a, Side::A, &pairing)?,
            b: Runner::new(b, Side::B, &pairing)?,
            pairing,
            lag: options.lag,
        })
    }

    /// What is driven and what is compared.
    pub fn pairing(&self) -> &Pairing {
        &self.pairing
    }

    /// The allowed lag in cycles.
    pub fn lag(&self) -> u64 {
        self.lag
    }

    /// The base tick (cycle time) of both programs, in nanoseconds.
    pub fn tick(&self) -> i64 {
        self.a.plc.cycle_time()
    }

    /// The random plan of `cycles` cycles for `seed` (see [`RandomStimulus`]).
    pub fn random_plan(&mut self, settings: &RandomStimulus, seed: u64, cycles: u64) -> InputPlan {
        self.a.plc.reset_cold();
        let initial: Vec<i64> = self
            .pairing
            .inputs
            .iter()
            .zip(&self.a.inputs)
            .map(|(p, r)| match self.a.plc.get(r) {
                Ok(v) => generator_code(&p.kind, &v),
                Err(_) => 0,
            })
            .collect();
        settings.generate(&self.pairing, &initial, seed, cycles)
    }

    /// Runs both programs from a cold start on `plan` and returns the first
    /// difference, or `None` when they agree for the whole plan (or both
    /// stop with the same runtime fault in the same cycle).
    pub fn run(&mut self, plan: &InputPlan) -> Result<Option<Difference>, CompareError> {
        let values_a = decode(&self.a, Side::A, &self.pairing, plan)?;
        let values_b = decode(&self.b, Side::B, &self.pairing, plan)?;
        self.a.plc.reset_cold();
        self.b.plc.reset_cold();
        self.a.sample();
        self.b.sample();
        let mut judge = Follower::new(self.lag, &self.a.values, &self.b.values);
        let mut found = Vec::new();
        let mut next = 0;
        for cycle in 0..plan.cycles {
            while next < plan.changes.len() && plan.changes[next].cycle <= cycle {
                let input = plan.changes[next].input;
                // Decoded for these handles; `set` still refuses a value
                // outside a subrange.
                let refused = |side, error| CompareError::BadValue {
                    side,
                    input: self.pairing.inputs[input].a.clone(),
                    error,
                };
                (self.a.plc.set(&self.a.inputs[input], &values_a[next]))
                    .map_err(|e| refused(Side::A, e))?;
                (self.b.plc.set(&self.b.inputs[input], &values_b[next]))
                    .map_err(|e| refused(Side::B, e))?;
                next += 1;
            }
            let ra = self.a.plc.run_cycle();
            let rb = self.b.plc.run_cycle();
            if ra.is_err() || rb.is_err() {
                return Ok(faults(cycle, ra, rb));
            }
            self.a.sample();
            self.b.sample();
            judge.observe(cycle, &self.a.values, &self.b.values, &mut found);
            if !found.is_empty() {
                return Ok(Some(Difference {
                    cycle,
                    outputs: found.into_iter().map(|(_, d)| d).collect(),
                    fault_a: None,
                    fault_b: None,
                }));
            }
        }
        Ok(None)
    }
}

/// The outcome of a cycle where a program faulted.
fn faults(
    cycle: u64,
    ra: Result<(), crate::runtime::engine::RuntimeFault>,
    rb: Result<(), crate::runtime::engine::RuntimeFault>,
) -> Option<Difference> {
    let text = |f: &crate::runtime::engine::RuntimeFault| format!("{}: {}", f.code(), f.fault.kind);
    match (&ra, &rb) {
        (Err(fa), Err(fb)) if fa.code() == fb.code() => None,
        _ => Some(Difference {
            cycle,
            outputs: Vec::new(),
            fault_a: ra.err().as_ref().map(text),
            fault_b: rb.err().as_ref().map(text),
        }),
    }
}

/// The plan's values decoded for one program's inputs.
fn decode(
    runner: &Runner,
    side: Side,
    pairing: &Pairing,
    plan: &InputPlan,
) -> Result<Vec<Value>, CompareError> {
    plan.changes
        .iter()
        .map(|c| {
            let r = &runner.inputs[c.input];
            let bad = |error| CompareError::BadValue {
                side,
                input: match side {
                    Side::A => pairing.inputs[c.input].a.clone(),
                    Side::B => pairing.inputs[c.input].b.clone(),
                },
                error,
            };
            runner.plc.parse_value(r, &c.value).map_err(bad)
        })
        .collect()
}

/// A value as the generator counts it (see [`RandomStimulus`]).
fn generator_code(kind: &InputKind, v: &Value) -> i64 {
    match (kind, v) {
        (InputKind::Enum(names), Value::Enum(name, _)) => names
            .iter()
            .position(|n| n.eq_ignore_ascii_case(name))
            .unwrap_or(0) as i64,
        (InputKind::Real, _) => v.as_f64().map_or(0, |f| f.round() as i64),
        (InputKind::Time { .. }, _) => v.as_i64().map_or(0, |ns| ns / 10_000_000),
        (_, Value::Scalar(_, raw)) => v.as_i64().unwrap_or(*raw as i64),
        _ => 0,
    }
}
