//! programs/chariot.sfc in a closed loop with the simulated plant
//! (plant.rs), on the virtual clock: each cycle the host writes the
//! button and the limit switches, runs the cycle, reads the contactors and
//! moves the cart. Variables are resolved once and accessed by handle.

use super::plant::{Cart, Operator, PlantError};
use plcrun::{
    CompileError, ElemType, Options, Plc, RunError, RuntimeFault, Value, VarError, VarRef,
};
use std::fmt;

/// The chart, as in the repository.
pub const CHART: &str = include_str!("../../programs/chariot.sfc");

/// The waiting time at B for the simulation (the program's default is
/// ten minutes).
pub const WAIT_AT_B: &str = "T#1s";

/// The signals of one cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Signals {
    /// Start button.
    pub dcy: bool,
    /// Limit switch A.
    pub fca: bool,
    /// Limit switch B.
    pub fcb: bool,
    /// Forward contactor.
    pub kmav: bool,
    /// Reverse contactor.
    pub kmar: bool,
    /// "At origin" lamp.
    pub vom: bool,
    /// The active step.
    pub step: &'static str,
}

/// A cycle in which some signal changed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Event {
    /// The cycle's number.
    pub cycle: u64,
    /// Its clock, in nanoseconds.
    pub time_ns: i64,
    /// Where the cart was during the cycle.
    pub position_mm: i64,
    /// What the PLC saw and did.
    pub signals: Signals,
}

/// A finished run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The changes, in order.
    pub events: Vec<Event>,
    /// The cycles in which the cart came back to A from B.
    pub round_trips: Vec<u64>,
}

/// What can stop the loop.
#[derive(Debug)]
pub enum LoopError {
    /// The chart did not compile.
    Compile(Box<CompileError>),
    /// A variable the loop needs is missing or of another type.
    Variable(VarError),
    /// The PLC faulted.
    Fault(Box<RuntimeFault>),
    /// The PLC drove the plant into a crash.
    Plant(PlantError),
    /// A real-time run ended on another error than a fault.
    Run(Box<RunError>),
}

impl fmt::Display for LoopError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoopError::Compile(e) => write!(f, "{e}"),
            LoopError::Variable(e) => write!(f, "{e}"),
            LoopError::Fault(e) => write!(f, "{e}"),
            LoopError::Plant(e) => write!(f, "{e}"),
            LoopError::Run(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for LoopError {}

impl From<VarError> for LoopError {
    fn from(e: VarError) -> LoopError {
        LoopError::Variable(e)
    }
}

/// The chart's steps, in the order of the listing.
const STEPS: [&str; 4] = ["INIT", "AV", "ATT", "AR"];

/// The PLC's variables the loop touches, resolved once.
pub struct Io {
    dcy: VarRef,
    fca: VarRef,
    fcb: VarRef,
    kmav: VarRef,
    kmar: VarRef,
    vom: VarRef,
    steps: Vec<VarRef>,
}

impl Io {
    /// Resolves the chart's inputs, outputs and step flags in `plc`.
    pub fn resolve(plc: &Plc) -> Result<Io, VarError> {
        Ok(Io {
            dcy: plc.resolve("Dcy")?,
            fca: plc.resolve("FcA")?,
            fcb: plc.resolve("FcB")?,
            kmav: plc.resolve("KMAV")?,
            kmar: plc.resolve("KMAR")?,
            vom: plc.resolve("VOM")?,
            steps: STEPS
                .iter()
                .map(|s| plc.resolve(&format!("{s}.X")))
                .collect::<Result<_, _>>()?,
        })
    }

    /// Writes the button and the limit switches for the next cycle.
    pub fn write_inputs(&self, plc: &mut Plc, dcy: bool, cart: &Cart) -> Result<(), VarError> {
        write_bool(plc, &self.dcy, dcy)?;
        write_bool(plc, &self.fca, cart.at_a())?;
        write_bool(plc, &self.fcb, cart.at_b())
    }

    /// The "at origin" lamp as the last cycle left it.
    pub fn lamp(&self, plc: &Plc) -> Result<bool, VarError> {
        read_bool(plc, &self.vom)
    }

    /// What the PLC saw (`dcy` and the cart's switches) and did in the
    /// cycle just run.
    pub fn signals(&self, plc: &Plc, dcy: bool, cart: &Cart) -> Result<Signals, VarError> {
        let mut step = "-";
        for (name, r) in STEPS.iter().zip(&self.steps) {
            if read_bool(plc, r)? {
                step = name;
            }
        }
        Ok(Signals {
            dcy,
            fca: cart.at_a(),
            fcb: cart.at_b(),
            kmav: read_bool(plc, &self.kmav)?,
            kmar: read_bool(plc, &self.kmar)?,
            vom: read_bool(plc, &self.vom)?,
            step,
        })
    }
}

fn write_bool(plc: &mut Plc, r: &VarRef, b: bool) -> Result<(), VarError> {
    plc.set(r, &Value::Scalar(ElemType::Bool, u64::from(b)))
}

fn read_bool(plc: &Plc, r: &VarRef) -> Result<bool, VarError> {
    let v = plc.get(r)?;
    v.as_bool().ok_or_else(|| VarError::WrongValue {
        path: r.name().to_string(),
        ty: "BOOL".to_string(),
        value: v.to_literal(),
    })
}

/// Runs the loop for `cycles` cycles of 10 ms from the cart at A.
pub fn run(cycles: u64) -> Result<Run, LoopError> {
    let mut plc = Plc::compile_files(&[("chariot.sfc", CHART)], &Options::default())
        .map_err(|e| LoopError::Compile(Box::new(e)))?;
    plc.write("tX3", WAIT_AT_B)?;
    let io = Io::resolve(&plc)?;
    let (mut cart, mut operator) = (Cart::new(), Operator::new());
    let mut run = Run {
        events: Vec::new(),
        round_trips: Vec::new(),
    };
    let mut been_at_b = false;
    for cycle in 0..cycles {
        if cart.at_a() && been_at_b {
            run.round_trips.push(cycle);
        }
        been_at_b = (been_at_b || cart.at_b()) && !cart.at_a();
        // Inputs: the operator sees the lamp as the last cycle left it.
        let dcy = operator.button(io.lamp(&plc)?);
        io.write_inputs(&mut plc, dcy, &cart)?;
        let time_ns = plc.time();
        plc.run_cycle().map_err(|f| LoopError::Fault(Box::new(f)))?;
        let signals = io.signals(&plc, dcy, &cart)?;
        if run.events.last().is_none_or(|e| e.signals != signals) {
            run.events.push(Event {
                cycle,
                time_ns,
                position_mm: cart.position_mm,
                signals: signals.clone(),
            });
        }
        cart.advance(cycle, signals.kmav, signals.kmar)
            .map_err(LoopError::Plant)?;
    }
    Ok(run)
}

impl fmt::Display for Event {
    /// `   4.50 s      0 mm  INIT  in: FcA          out: VOM`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.signals;
        let names = |list: &[(bool, &str)]| {
            let on: Vec<&str> = list.iter().filter(|(b, _)| *b).map(|(_, n)| *n).collect();
            if on.is_empty() {
                "-".to_string()
            } else {
                on.join(" ")
            }
        };
        let inputs = names(&[(s.dcy, "Dcy"), (s.fca, "FcA"), (s.fcb, "FcB")]);
        let outputs = names(&[(s.kmav, "KMAV"), (s.kmar, "KMAR"), (s.vom, "VOM")]);
        write!(
            f,
            "{:>4}.{:02} s  {:>5} mm  {:<4}  in: {inputs:<12} out: {outputs}",
            self.time_ns / 1_000_000_000,
            self.time_ns / 10_000_000 % 100,
            self.position_mm,
            s.step,
        )
    }
}
