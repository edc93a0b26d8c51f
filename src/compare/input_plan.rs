//! The stimulus of one comparison run: a list of input changes, read from
//! a stimulus CSV or drawn by the random generator, and written back as a
//! stimulus CSV that `plcrun A --stimulus FILE` replays.

use super::error::CompareError;
use super::pairing::Pairing;
use crate::runtime::stimulus::{StimulusKey, parse_stimulus};

/// From cycle `cycle` on (applied before that cycle runs, like a stimulus
/// row), input `input` (an index into [`Pairing::inputs`]) holds `value`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputChange {
    /// The cycle (from 0).
    pub cycle: u64,
    /// The input's index in [`Pairing::inputs`].
    pub input: usize,
    /// The new value, an IEC literal.
    pub value: String,
}

/// A run of `cycles` cycles and the input changes in it, in cycle order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputPlan {
    /// How many cycles to run.
    pub cycles: u64,
    /// The changes, sorted by cycle (stable: a later change of the same
    /// input in the same cycle wins).
    pub changes: Vec<InputChange>,
}

impl InputPlan {
    /// Reads a stimulus CSV (see `docs/cli.md`) whose columns name driven
    /// inputs (by A's or B's name). A `time` key is turned into cycles on
    /// the virtual clock: a row at time `t` applies before the first cycle
    /// starting at or after `t` (`ceil(t / tick)`), as in a run.
    pub fn parse_csv(
        text: &str,
        pairing: &Pairing,
        cycles: u64,
        tick_ns: i64,
    ) -> Result<InputPlan, CompareError> {
        let stim = parse_stimulus(text).map_err(CompareError::Stimulus)?;
        let mut columns = Vec::new();
        for name in &stim.columns {
            let i = pairing
                .input_index(name)
                .ok_or_else(|| CompareError::NotAnInput {
                    column: name.clone(),
                })?;
            columns.push(i);
        }
        let mut changes = Vec::new();
        for row in &stim.rows {
            let cycle = match stim.key {
                StimulusKey::Cycle => row.at as u64,
                StimulusKey::Time => (row.at.max(0) as u64).div_ceil(tick_ns.max(1) as u64),
            };
            if cycle >= cycles {
                break;
            }
            for (cell, &input) in row.cells.iter().zip(&columns) {
                if let Some(value) = cell {
                    changes.push(InputChange {
                        cycle,
                        input,
                        value: value.clone(),
                    });
                }
            }
        }
        Ok(InputPlan { cycles, changes })
    }

    /// The plan cut to its first `cycles` cycles.
    pub fn truncated(&self, cycles: u64) -> InputPlan {
        InputPlan {
            cycles: cycles.min(self.cycles),
            changes: self
                .changes
                .iter()
                .filter(|c| c.cycle < cycles)
                .cloned()
                .collect(),
        }
    }

    /// The plan as a stimulus CSV keyed by `cycle`, with A's input names
    /// as columns and one row per cycle with a change (empty cells leave an
    /// input unchanged). `comment` lines come first, each behind `# `.
    pub fn to_csv(&self, pairing: &Pairing, comment: &[String]) -> String {
        let mut out = String::new();
        for line in comment {
            out.push_str("# ");
            out.push_str(line);
            out.push('\n');
        }
        // Only the inputs the plan changes, in pairing order.
        let mut used: Vec<usize> = self.changes.iter().map(|c| c.input).collect();
        used.sort_unstable();
        used.dedup();
        out.push_str("cycle");
        for &i in &used {
            out.push(',');
            out.push_str(&csv_field(&pairing.inputs[i].a));
        }
        out.push('\n');
        let mut k = 0;
        while k < self.changes.len() {
            let cycle = self.changes[k].cycle;
            let mut cells: Vec<Option<&str>> = vec![None; used.len()];
            while k < self.changes.len() && self.changes[k].cycle == cycle {
                let c = &self.changes[k];
                if let Ok(col) = used.binary_search(&c.input) {
                    cells[col] = Some(&c.value);
                }
                k += 1;
            }
            out.push_str(&cycle.to_string());
            for cell in cells {
                out.push(',');
                out.push_str(&cell.map(csv_field).unwrap_or_default());
            }
            out.push('\n');
        }
        out
    }
}

/// A CSV field: quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}
