//! The comparison's report, as the `compare` command prints it: what was
//! paired, the verdict, the first difference with the input history
//! leading to it, and the shrunk counterexample. Only the run's facts go
//! in (no times), so the same run gives the same bytes.

use super::input_plan::InputPlan;
use super::pairing::{PairedVar, Pairing};
use super::run_pair::{Difference, Mismatch};
use super::shrink::Shrunk;
use super::stimulus_gen::RandomStimulus;
use std::fmt::{self, Write};
use std::ops::Range;

/// Where the stimulus came from.
#[derive(Debug, Clone, PartialEq)]
pub enum StimulusSource {
    /// A stimulus CSV file.
    Csv {
        /// The file as named.
        path: String,
    },
    /// The random generator over a range of seeds.
    Random {
        /// The generator's settings.
        settings: RandomStimulus,
        /// The seeds.
        seeds: Range<u64>,
    },
}

/// The whole report (its `Display` is the text).
#[derive(Debug, Clone, PartialEq)]
pub struct CompareReport {
    /// How program A is named (its files and program).
    pub a_label: String,
    /// How program B is named.
    pub b_label: String,
    /// What was driven and compared.
    pub pairing: Pairing,
    /// The allowed lag in cycles.
    pub lag: u64,
    /// Cycles per run.
    pub cycles: u64,
    /// The stimulus.
    pub stimulus: StimulusSource,
    /// The differing seeds (random stimulus only).
    pub differing_seeds: Vec<u64>,
    /// The first difference found, if any: its seed (random stimulus),
    /// the plan that showed it, the difference, and the shrunk plan.
    pub found: Option<(Option<u64>, InputPlan, Difference, Shrunk)>,
}

impl fmt::Display for CompareReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.pairing;
        writeln!(f, "A: {}", self.a_label)?;
        writeln!(f, "B: {}", self.b_label)?;
        writeln!(
            f,
            "inputs driven ({}): {}",
            p.inputs.len(),
            names(&p.inputs)
        )?;
        writeln!(
            f,
            "outputs compared ({}): {}",
            p.outputs.len(),
            names(&p.outputs)
        )?;
        if !p.unpaired_inputs.is_empty() {
            writeln!(
                f,
                "inputs of one program only, not driven: {}",
                p.unpaired_inputs.join(", ")
            )?;
        }
        if !p.unpaired_outputs.is_empty() {
            writeln!(
                f,
                "outputs of one program only, not compared: {}",
                p.unpaired_outputs.join(", ")
            )?;
        }
        if !p.ignored.is_empty() {
            writeln!(f, "ignored: {}", p.ignored.join(", "))?;
        }
        match self.lag {
            0 => writeln!(f, "lag: none (equal after every cycle)")?,
            k => writeln!(f, "lag: B may follow A by up to {k} cycle{}", plural(k))?,
        }
        self.write_stimulus(f)?;
        self.write_verdict(f)?;
        if let Some((seed, plan, diff, shrunk)) = &self.found {
            let at = seed.map(|s| format!(" (seed {s})")).unwrap_or_default();
            writeln!(f)?;
            writeln!(f, "first difference: cycle {}{at}", diff.cycle)?;
            write_difference(f, p, diff, self.lag, "  ")?;
            let history = plan.truncated(diff.cycle + 1);
            writeln!(
                f,
                "inputs up to cycle {} ({}):",
                diff.cycle,
                count(&history)
            )?;
            write_changes(f, p, &history, 20)?;
            writeln!(f)?;
            writeln!(
                f,
                "shrunk counterexample: {}, {} cycle{} (from {}, {} cycles; {} runs)",
                count(&shrunk.plan),
                shrunk.plan.cycles,
                plural(shrunk.plan.cycles),
                count(&history),
                history.cycles,
                shrunk.runs
            )?;
            write_changes(f, p, &shrunk.plan, usize::MAX)?;
            writeln!(f, "  difference at cycle {}:", shrunk.difference.cycle)?;
            write_difference(f, p, &shrunk.difference, self.lag, "    ")?;
        }
        Ok(())
    }
}

impl CompareReport {
    fn write_stimulus(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.stimulus {
            StimulusSource::Csv { path } => {
                writeln!(f, "stimulus: {path}, {} cycles", self.cycles)
            }
            StimulusSource::Random { settings, seeds } => {
                let fixed: Vec<&str> = (self.pairing.inputs.iter())
                    .filter(|v| v.kind == super::pairing::InputKind::Fixed)
                    .map(|v| v.a.as_str())
                    .collect();
                if !fixed.is_empty() {
                    writeln!(
                        f,
                        "inputs the generator does not draw (they keep their initial value): {}",
                        fixed.join(", ")
                    )?;
                }
                writeln!(
                    f,
                    "stimulus: random, seeds {}..={} ({} seed{}), {} cycles each; change probability {}, hold {}..={} cycles",
                    seeds.start,
                    seeds.end.saturating_sub(1),
                    seeds.end - seeds.start,
                    plural(seeds.end - seeds.start),
                    self.cycles,
                    settings.change_prob,
                    settings.min_hold,
                    settings.max_hold
                )
            }
        }
    }

    fn write_verdict(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let found = self.found.is_some();
        match (&self.stimulus, found) {
            (StimulusSource::Random { seeds, .. }, true) => writeln!(
                f,
                "verdict: DIFFERENT ({} of {} seeds differ; first: seed {})",
                self.differing_seeds.len(),
                seeds.end - seeds.start,
                self.differing_seeds.first().copied().unwrap_or(seeds.start)
            ),
            (StimulusSource::Random { seeds, .. }, false) => writeln!(
                f,
                "verdict: EQUIVALENT on all {} seeds",
                seeds.end - seeds.start
            ),
            (StimulusSource::Csv { .. }, true) => writeln!(f, "verdict: DIFFERENT"),
            (StimulusSource::Csv { .. }, false) => {
                writeln!(f, "verdict: EQUIVALENT on this stimulus")
            }
        }
    }
}

fn plural(n: u64) -> &'static str {
    if n == 1 { "" } else { "s" }
}

fn pair_name(v: &PairedVar) -> String {
    if v.a == v.b {
        v.a.clone()
    } else {
        format!("{}={}", v.a, v.b)
    }
}

fn names(vars: &[PairedVar]) -> String {
    if vars.is_empty() {
        return "none".into();
    }
    vars.iter().map(pair_name).collect::<Vec<_>>().join(", ")
}

/// `5 input changes at 3 cycles`.
fn count(plan: &InputPlan) -> String {
    let mut cycles: Vec<u64> = plan.changes.iter().map(|c| c.cycle).collect();
    cycles.dedup();
    let n = plan.changes.len() as u64;
    format!(
        "{n} input change{} at {} cycle{}",
        plural(n),
        cycles.len(),
        plural(cycles.len() as u64)
    )
}

/// One line per cycle with changes (`cycle 12: S1=TRUE, S2=FALSE`), the
/// last `limit` of them.
fn write_changes(
    f: &mut fmt::Formatter<'_>,
    p: &Pairing,
    plan: &InputPlan,
    limit: usize,
) -> fmt::Result {
    let mut lines: Vec<String> = Vec::new();
    for c in &plan.changes {
        let item = format!("{}={}", p.inputs[c.input].a, c.value);
        match lines.last_mut() {
            Some(line) if line.starts_with(&format!("  cycle {}:", c.cycle)) => {
                let _ = write!(line, ", {item}");
            }
            _ => lines.push(format!("  cycle {}: {item}", c.cycle)),
        }
    }
    if lines.is_empty() {
        return writeln!(f, "  (none: the programs differ without any input change)");
    }
    if lines.len() > limit {
        writeln!(
            f,
            "  ... {} earlier cycles with changes",
            lines.len() - limit
        )?;
        lines.drain(..lines.len() - limit);
    }
    for line in lines {
        writeln!(f, "{line}")?;
    }
    Ok(())
}

fn write_difference(
    f: &mut fmt::Formatter<'_>,
    p: &Pairing,
    d: &Difference,
    lag: u64,
    indent: &str,
) -> fmt::Result {
    if d.fault_a.is_some() || d.fault_b.is_some() {
        let show = |x: &Option<String>| x.clone().unwrap_or_else(|| "ran normally".into());
        writeln!(f, "{indent}A: {}", show(&d.fault_a))?;
        writeln!(f, "{indent}B: {}", show(&d.fault_b))?;
    }
    for o in &d.outputs {
        let v = &p.outputs[o.output];
        let why = match &o.why {
            Mismatch::Values => String::new(),
            Mismatch::NotFollowed {
                a_changed_at,
                value,
            } => format!(
                "  (A changed to {value} at cycle {a_changed_at}; B did not follow within {lag} cycle{})",
                plural(lag)
            ),
            Mismatch::BChangedAlone => "  (B changed, A had no change for it to follow)".into(),
            Mismatch::WrongValue { expected } => {
                format!(
                    "  (B changed to {}, A's next value is {expected})",
                    o.b_value
                )
            }
        };
        writeln!(
            f,
            "{indent}{}: A = {}, B = {}{why}",
            pair_name(v),
            o.a_value,
            o.b_value
        )?;
    }
    Ok(())
}
