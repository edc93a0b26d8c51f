//! Equivalence checking of two programs: run A and B side by side on the
//! same inputs, cycle by cycle, and compare a mapping of their outputs.
//!
//! Both programs are ordinary [`Plc`]s, compiled by the normal pipeline, so
//! any front-end works. A [`Pair`] decides which variables are driven
//! (the inputs both programs read from outside: program `VAR_INPUT`s and
//! `%I` located variables) and which are compared (A's default trace
//! outputs that B also has, plus `--map`ped names), runs an [`InputPlan`]
//! (a list of input changes, from a stimulus CSV or the seeded random
//! generator of [`RandomStimulus`]) and reports the first [`Difference`];
//! [`Pair::shrink`] reduces a failing plan by delta debugging.
//!
//! ```
//! use plcrun::{CompareOptions, InputPlan, Options, Pair, Plc};
//!
//! let a = "PROGRAM A VAR_INPUT x : BOOL; END_VAR VAR_OUTPUT y : BOOL; END_VAR
//!          y := x; END_PROGRAM";
//! // B copies x one cycle late.
//! let b = "PROGRAM B VAR_INPUT x : BOOL; END_VAR VAR_OUTPUT y : BOOL; END_VAR
//!          VAR old : BOOL; END_VAR y := old; old := x; END_PROGRAM";
//! let plc = |src: &str| Plc::compile_files(&[("p.st", src)], &Options::default());
//! let mut pair = Pair::new(plc(a)?, plc(b)?, &CompareOptions::default())?;
//! let plan = InputPlan::parse_csv("cycle,x\n3,TRUE\n", pair.pairing(), 10, 10_000_000)?;
//! let diff = pair.run(&plan)?.expect("B is one cycle late");
//! assert_eq!(diff.cycle, 3);
//! // With a lag of one cycle allowed, B follows A.
//! let lagged = CompareOptions { lag: 1, ..CompareOptions::default() };
//! let mut pair = Pair::new(plc(a)?, plc(b)?, &lagged)?;
//! assert!(pair.run(&plan)?.is_none());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod follow;
mod input_plan;
mod pairing;
mod report;
mod run_pair;
mod seeds;
mod shrink;
mod stimulus_gen;

pub use error::{CompareError, Side};
pub use input_plan::{InputChange, InputPlan};
pub use pairing::{CompareOptions, InputKind, PairedVar, Pairing, parse_map};
pub use report::{CompareReport, StimulusSource};
pub use run_pair::{Difference, Mismatch, OutputDifference, Pair};
pub use seeds::{SeedsOutcome, run_seeds, run_seeds_reporting};
pub use shrink::Shrunk;
pub use stimulus_gen::RandomStimulus;

#[cfg(doc)]
use crate::runtime::engine::Plc;
