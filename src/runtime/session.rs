//! A run as the command line does it, as a library type: a compiled
//! program, the stimulus bound to its variables, the traced variables, and
//! one trace row per cycle.
//!
//! ```
//! use plcrun::{Options, Plc, Session, TraceFormat, TraceWriter};
//!
//! let src = "PROGRAM P VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT n : INT; END_VAR
//!            IF go THEN n := n + 1; END_IF END_PROGRAM";
//! let plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
//! let names = plc.default_trace(); // the VAR_OUTPUTs: ["n"]
//! let mut session = Session::new(plc);
//! session.set_trace(&names)?;
//! session.bind_stimulus(plcrun::parse_stimulus("cycle,go\n1,TRUE\n")?)?;
//! let mut out = TraceWriter::new(Vec::new(), TraceFormat::Csv, session.trace_names().to_vec(), false);
//! session.run(3, &mut out)?;
//! let csv = String::from_utf8(out.finish()?)?;
//! assert_eq!(csv, "cycle,time,n\n0,T#0s,0\n1,T#10ms,1\n2,T#20ms,2\n");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::change_report::{ChangeReport, SessionChangeError};
use super::default_trace::is_trace_column;
use super::engine::{Plc, RuntimeFault};
use super::live_stimulus::{LiveStimulus, LiveStimulusError};
use super::names::VarRef;
use super::plc_value::Value;
use super::stimulus::{Stimulus, StimulusCursor};
use super::trace::{TraceCell, TraceWriter};
use super::trace_vcd::{VcdSignal, vcd_signal};
use super::var_error::VarError;
use crate::progress::Progress;
use std::fmt;
use std::io::{self, Write};
use std::time::{Duration, Instant};

/// A stimulus column or cell that does not fit the program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StimulusBindError {
    /// The header of the column concerned.
    pub column: String,
    /// The 1-based line of the stimulus file, for a cell (`None` for the
    /// header).
    pub line: Option<usize>,
    /// What does not fit.
    pub error: VarError,
}

impl fmt::Display for StimulusBindError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: column `{}`: {}", self.column, self.error),
            None => write!(f, "column `{}`: {}", self.column, self.error),
        }
    }
}

impl std::error::Error for StimulusBindError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// Why [`Session::run`] stopped before its last cycle.
#[derive(Debug)]
pub enum RunError {
    /// The program faulted; the PLC is stopped.
    Fault(RuntimeFault),
    /// The trace could not be written.
    Trace(io::Error),
    /// A row of a live stimulus could not be read or does not fit.
    Stimulus(LiveStimulusError),
    /// The hook run at a clean stop ([`Session::set_on_stop`]) failed.
    OnStop(StopHookError),
    /// The PLC was given a new program version through
    /// [`Session::plc_mut`] rather than [`Session::online_change`], and a
    /// traced name or stimulus column does not fit it.
    PlcChanged(SessionChangeError),
    /// A real-time run could not prepare its thread (priority, CPU).
    RealTime(crate::runtime::rt_thread::RealTimeError),
}

/// The error a stop hook returns.
pub type StopHookError = Box<dyn std::error::Error + Send + Sync>;

/// A hook run after each cycle, between cycles (see [`Session::set_cycle_hook`]).
pub type CycleHook = Box<dyn FnMut(&mut Plc) + Send>;

/// A hook run at a clean stop (see [`Session::set_on_stop`]).
pub type StopHook = Box<dyn FnMut(&mut Plc) -> Result<(), StopHookError> + Send>;

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Fault(fault) => fault.fmt(f),
            RunError::Trace(e) => write!(f, "cannot write the trace: {e}"),
            RunError::Stimulus(e) => e.fmt(f),
            RunError::OnStop(e) => write!(f, "at the stop: {e}"),
            RunError::PlcChanged(e) => write!(
                f,
                "the program was changed outside the session and no longer fits it: {e}"
            ),
            RunError::RealTime(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for RunError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            RunError::Fault(fault) => Some(fault),
            RunError::Trace(e) => Some(e),
            RunError::Stimulus(e) => Some(e),
            RunError::OnStop(e) => Some(e.as_ref()),
            RunError::PlcChanged(e) => Some(e),
            RunError::RealTime(e) => Some(e),
        }
    }
}

/// How cycles are paced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pacing {
    /// As fast as possible; the clock is virtual (the default).
    #[default]
    Virtual,
    /// Each cycle starts no earlier than its clock time after the run
    /// started, measured on the wall clock.
    WallClock,
}

/// A stimulus whose columns are resolved and whose cells are decoded.
struct BoundStimulus {
    stimulus: Stimulus,
    columns: Vec<VarRef>,
    /// Per row, the decoded non-empty cells: `(column, value)`.
    rows: Vec<Vec<(usize, Value)>>,
    cursor: StimulusCursor,
    /// Rows applied so far (the cursor hands out contiguous runs).
    applied: usize,
}

/// A program running against a stimulus, with its traced variables.
pub struct Session {
    plc: Plc,
    stimulus: Option<BoundStimulus>,
    names: Vec<String>,
    traced: Vec<VarRef>,
    cells: Vec<TraceCell>,
    /// Per traced name, whether its value was forced in the last cycle
    /// (empty while nothing has been forced).
    forced: Vec<bool>,
    pacing: Pacing,
    /// Stimulus rows arriving while the program runs (`--stimulus -`).
    live: Option<LiveStimulus>,
    cycle_hook: Option<CycleHook>,
    on_stop: Option<StopHook>,
    /// Retained values saved every so many cycles by [`Self::run`].
    retain: Option<(super::retain::saver::RetainSaver, u64)>,
}

impl Session {
    /// A session over `plc` with no stimulus and nothing traced yet (see
    /// [`Self::set_trace`]; [`Plc::default_trace`] gives the names the
    /// command line traces by default).
    pub fn new(plc: Plc) -> Session {
        Session {
            plc,
            stimulus: None,
            names: Vec::new(),
            traced: Vec::new(),
            cells: Vec::new(),
            forced: Vec::new(),
            pacing: Pacing::Virtual,
            live: None,
            cycle_hook: None,
            on_stop: None,
            retain: None,
        }
    }

    /// The PLC (to read variables, the cycle number, the clock).
    pub fn plc(&self) -> &Plc {
        &self.plc
    }

    /// The PLC, mutably (to write variables between cycles).
    ///
    /// Load a new program version through [`Self::online_change`], not
    /// through this PLC's own `online_change`: the session's traced names
    /// and stimulus columns are resolved handles, which only
    /// [`Self::online_change`] re-binds to the new version's layout.
    pub fn plc_mut(&mut self) -> &mut Plc {
        &mut self.plc
    }

    /// Ends the session and hands the PLC back.
    pub fn into_plc(self) -> Plc {
        self.plc
    }

    /// Sets how cycles are paced (virtual by default).
    pub fn set_pacing(&mut self, pacing: Pacing) {
        self.pacing = pacing;
    }

    /// Has every [`Self::step`] (so every run, virtual or real-time) hand the
    /// retained values to `saver` after every `every`-th cycle (counted by cycle number; 0 is taken as 1).
    pub fn save_retain_every(&mut self, saver: super::retain::saver::RetainSaver, every: u64) {
        self.retain = Some((saver, every.max(1)));
    }

    /// Takes back the saver given to [`Self::save_retain_every`].
    pub fn take_retain_saver(&mut self) -> Option<super::retain::saver::RetainSaver> {
        self.retain.take().map(|(saver, _)| saver)
    }

    /// Traces these variables, in this order; names are kept as written
    /// (trimmed) for the trace header. Each must name a single value (not
    /// an array, structure or FB instance). On error the previous trace
    /// list stays.
    pub fn set_trace<S: AsRef<str>>(&mut self, names: &[S]) -> Result<(), VarError> {
        let names: Vec<String> = names
            .iter()
            .map(|n| n.as_ref().trim().to_string())
            .collect();
        if let Some(clash) = names.iter().find(|n| is_trace_column(n)) {
            return Err(VarError::TraceColumn {
                name: clash.clone(),
            });
        }
        let traced = names
            .iter()
            .map(|n| self.plc.resolve(n))
            .collect::<Result<Vec<_>, _>>()?;
        self.traced = traced;
        self.set_names(names);
        Ok(())
    }

    fn set_names(&mut self, names: Vec<String>) {
        self.cells = names
            .iter()
            .map(|_| TraceCell::from_string("", false))
            .collect();
        self.names = names;
    }

    /// The traced names, in column order.
    pub fn trace_names(&self) -> &[String] {
        &self.names
    }

    /// The VCD type of each traced name, in column order (for
    /// [`TraceWriter::vcd`]).
    pub fn vcd_signals(&self) -> Vec<VcdSignal> {
        self.traced
            .iter()
            .map(|r| vcd_signal(self.plc.image(), r))
            .collect()
    }

    /// Binds a stimulus: resolves every column and decodes every cell now,
    /// so that a bad cell is reported before the first cycle runs. Replaces
    /// any stimulus bound before.
    pub fn bind_stimulus(&mut self, stimulus: Stimulus) -> Result<(), StimulusBindError> {
        self.stimulus = Some(bind(&self.plc, stimulus)?);
        Ok(())
    }

    /// Applies an online change ([`Plc::online_change`]) and binds the
    /// traced names and the stimulus to the new version, where the
    /// stimulus goes on from the row it had reached. A traced name or a
    /// stimulus column that does not fit the new version refuses the
    /// change, and nothing changes.
    pub fn online_change(&mut self, new: Plc) -> Result<ChangeReport, SessionChangeError> {
        let rebound = self.rebind(&new)?;
        // The handles were resolved by `new`, whose identity the PLC takes.
        let report = self.plc.online_change(new)?;
        self.adopt(rebound);
        Ok(report)
    }

    /// The traced names, the stimulus and the live stimulus resolved in
    /// `plc`, without changing the session.
    fn rebind(&self, plc: &Plc) -> Result<Rebound, SessionChangeError> {
        let traced = self
            .names
            .iter()
            .map(|n| plc.resolve(n))
            .collect::<Result<Vec<_>, _>>()
            .map_err(SessionChangeError::Trace)?;
        let stimulus = match &self.stimulus {
            Some(old) => {
                let mut bound =
                    bind(plc, old.stimulus.clone()).map_err(SessionChangeError::Stimulus)?;
                bound.cursor = old.cursor.clone();
                bound.applied = old.applied;
                Some(bound)
            }
            None => None,
        };
        Ok(Rebound { traced, stimulus })
    }

    /// Takes the handles of [`Self::rebind`] (a live stimulus re-binds
    /// itself when it sees a new PLC).
    fn adopt(&mut self, rebound: Rebound) {
        self.traced = rebound.traced;
        if rebound.stimulus.is_some() {
            self.stimulus = rebound.stimulus;
        }
    }

    /// True when a handle of the session was resolved by another PLC than
    /// the one it runs (a new version loaded through [`Self::plc_mut`]).
    #[inline]
    fn is_stale(&self) -> bool {
        let id = self.plc.id;
        self.traced.first().is_some_and(|r| r.owner != id)
            || self
                .stimulus
                .as_ref()
                .and_then(|s| s.columns.first())
                .is_some_and(|r| r.owner != id)
    }

    /// Re-binds every handle to the PLC the session runs now (see
    /// [`Self::is_stale`]).
    #[cold]
    fn follow_plc(&mut self) -> Result<(), RunError> {
        let rebound = self.rebind(&self.plc).map_err(RunError::PlcChanged)?;
        self.adopt(rebound);
        Ok(())
    }

    /// Sets the hook run after every cycle of [`Self::step`] (and so of
    /// every run), once the traced values are sampled: the PLC is between
    /// two cycles, its outputs can be read and its inputs written for the
    /// next one (a simulated plant, a host's I/O). Replaces any hook set
    /// before.
    pub fn set_cycle_hook(&mut self, hook: impl FnMut(&mut Plc) + Send + 'static) {
        self.cycle_hook = Some(Box::new(hook));
    }

    /// Adds a hook run after every cycle, after those set or added before
    /// (as [`Self::set_cycle_hook`], which replaces them all).
    pub fn add_cycle_hook(&mut self, mut hook: impl FnMut(&mut Plc) + Send + 'static) {
        self.cycle_hook = Some(match self.cycle_hook.take() {
            None => Box::new(hook),
            Some(mut before) => Box::new(move |plc: &mut Plc| {
                before(plc);
                hook(plc);
            }),
        });
    }

    /// Sets the hook run when a run ends cleanly — its cycles done, or a
    /// stop asked through the PLC's [`crate::StopHandle::stop`] (Ctrl-C,
    /// SIGTERM in the command line) — after the last trace row is written:
    /// the place to save retained data. Not run after a fault. Replaces
    /// any hook set before.
    pub fn set_on_stop(
        &mut self,
        hook: impl FnMut(&mut Plc) -> Result<(), StopHookError> + Send + 'static,
    ) {
        self.on_stop = Some(Box::new(hook));
    }

    /// Runs the stop hook (the runs do it when they end cleanly; a host
    /// driving [`Self::step`] itself calls it when it stops).
    pub fn run_on_stop(&mut self) -> Result<(), RunError> {
        match &mut self.on_stop {
            Some(hook) => hook(&mut self.plc).map_err(RunError::OnStop),
            None => Ok(()),
        }
    }

    /// Feeds the stimulus from rows arriving while the program runs (see
    /// [`LiveStimulus`]); replaces any live stimulus set before. The runs
    /// apply its rows before each cycle; a host driving [`Self::step`]
    /// calls [`Self::apply_live_stimulus`].
    pub fn set_live_stimulus(&mut self, live: LiveStimulus) {
        self.live = Some(live);
    }

    /// Applies the live stimulus rows that have arrived and are due at the
    /// next cycle (nothing without a live stimulus).
    #[inline]
    pub fn apply_live_stimulus(&mut self) -> Result<(), LiveStimulusError> {
        match &mut self.live {
            Some(live) => live.apply_due(&mut self.plc),
            None => Ok(()),
        }
    }

    /// Runs one cycle: applies the stimulus rows due at this cycle, runs
    /// the tasks due, and samples the traced variables (see [`Self::cells`]).
    /// A session whose PLC was given a new program version through
    /// [`Self::plc_mut`] re-binds its traced names and stimulus first
    /// ([`RunError::PlcChanged`] when they no longer fit).
    pub fn step(&mut self) -> Result<(), RunError> {
        self.step_by(Plc::run_cycle)
    }

    /// [`Self::step`] with `run` running the tick (timed or not).
    pub(crate) fn step_by(
        &mut self,
        run: impl FnOnce(&mut Plc) -> Result<(), RuntimeFault>,
    ) -> Result<(), RunError> {
        if self.is_stale() {
            self.follow_plc()?;
        }
        if let Some(bound) = &mut self.stimulus {
            let (cycle, time) = (self.plc.cycle(), self.plc.time());
            let due = bound.cursor.due(&bound.stimulus, cycle, time).len();
            for cells in &bound.rows[bound.applied..bound.applied + due] {
                for (col, value) in cells {
                    // Decoded for these handles by this PLC in `bind_stimulus`.
                    self.plc.store(&bound.columns[*col], value);
                }
            }
            bound.applied += due;
        }
        run(&mut self.plc).map_err(RunError::Fault)?;
        self.mark_forced();
        for (cell, r) in self.cells.iter_mut().zip(&self.traced) {
            match self.plc.value_at(r) {
                Value::Scalar(t, raw) => cell.set_value(t, raw),
                Value::String(s, wide) => *cell = TraceCell::from_string(&s, wide),
                Value::Enum(name, v) => {
                    *cell = TraceCell {
                        text: name,
                        json: serde_json::Value::from(v),
                    }
                }
            }
        }
        if let Some((saver, every)) = &self.retain
            && self.plc.cycle().is_multiple_of(*every)
        {
            // The saver was made for this PLC by its owner; a saver of
            // another PLC only refuses to save.
            let _ = saver.offer(&self.plc);
        }
        if let Some(hook) = &mut self.cycle_hook {
            hook(&mut self.plc);
        }
        Ok(())
    }

    /// The traced values after the last [`Self::step`], one per name.
    pub fn cells(&self) -> &[TraceCell] {
        &self.cells
    }

    /// Which traced values were forced in the last [`Self::step`], one per
    /// name; empty when nothing is forced.
    pub fn forced_cells(&self) -> &[bool] {
        &self.forced
    }

    /// Notes which traced variables are forced (nothing to do while no
    /// variable is, or has been, forced).
    fn mark_forced(&mut self) {
        if self.plc.forces.is_empty() {
            self.forced.clear();
            return;
        }
        self.forced.clear();
        for r in &self.traced {
            self.forced.push(self.plc.forces.is_forced(r));
        }
    }

    /// Runs `cycles` cycles, writing one trace row per cycle to `out`
    /// (whose names should be [`Self::trace_names`]). Stops at the first
    /// runtime fault or trace write error; the rows of the cycles before
    /// it are written. Ends early, cleanly, at the cycle boundary after a
    /// stop was asked through the PLC's [`crate::StopHandle`]; a clean end
    /// runs the stop hook ([`Self::set_on_stop`]).
    pub fn run<W: Write>(&mut self, cycles: u64, out: &mut TraceWriter<W>) -> Result<(), RunError> {
        self.run_reporting(cycles, out, &())
    }

    /// [`Self::run`], telling `progress` the cycles done every 4096
    /// cycles and at the end. Generic, so that
    /// [`Self::run`]'s loop (`()`: no report) carries no test for it.
    pub fn run_reporting<W: Write, P: Progress + ?Sized>(
        &mut self,
        cycles: u64,
        out: &mut TraceWriter<W>,
        progress: &P,
    ) -> Result<(), RunError> {
        let started = Instant::now();
        let first_time = self.plc.time();
        let stop = self.plc.stop_handle();
        for done in 0..cycles {
            if done % CYCLES_PER_REPORT == 0 {
                progress.report(done, cycles, "cycles");
            }
            if stop.is_stop_requested() {
                break;
            }
            let (cycle, time) = (self.plc.cycle(), self.plc.time());
            if self.pacing == Pacing::WallClock {
                let offset = Duration::from_nanos(time.saturating_sub(first_time).max(0) as u64);
                let due = started + offset;
                let now = Instant::now();
                if due > now {
                    std::thread::sleep(due - now);
                }
            }
            self.apply_live_stimulus().map_err(RunError::Stimulus)?;
            self.step_by(Plc::run_cycle)?;
            out.row_marked(cycle, time, &self.cells, &self.forced)
                .map_err(RunError::Trace)?;
        }
        progress.report(cycles, cycles, "cycles");
        self.run_on_stop()
    }
}

/// How many cycles [`Session::run_reporting`] runs between two reports.
const CYCLES_PER_REPORT: u64 = 4096;

/// Resolves every column of `stimulus` in `plc` and decodes every cell for
/// its column's type.
fn bind(plc: &Plc, stimulus: Stimulus) -> Result<BoundStimulus, StimulusBindError> {
    let columns = stimulus_columns(plc, &stimulus.columns)?;
    let mut rows = Vec::with_capacity(stimulus.rows.len());
    for row in &stimulus.rows {
        let mut cells = Vec::new();
        for (i, cell) in row.cells.iter().enumerate() {
            let Some(text) = cell else { continue };
            let value = plc
                .parse_value(&columns[i], text)
                .map_err(|error| StimulusBindError {
                    column: stimulus.columns[i].clone(),
                    line: Some(row.line),
                    error,
                })?;
            cells.push((i, value));
        }
        rows.push(cells);
    }
    Ok(BoundStimulus {
        stimulus,
        columns,
        rows,
        cursor: StimulusCursor::new(),
        applied: 0,
    })
}

/// Handles resolved in a new version of the program (see `Session::rebind`).
struct Rebound {
    traced: Vec<VarRef>,
    stimulus: Option<BoundStimulus>,
}

/// Resolves stimulus column `names` in `plc`: each must name a variable
/// the host may write (not a CONSTANT, not an SFC flag).
pub(super) fn stimulus_columns(
    plc: &Plc,
    names: &[String],
) -> Result<Vec<VarRef>, StimulusBindError> {
    names
        .iter()
        .map(|name| {
            plc.resolve(name)
                .and_then(|r| plc.writable(&r).map(|()| r))
                .map_err(|error| StimulusBindError {
                    column: name.clone(),
                    line: None,
                    error,
                })
        })
        .collect()
}
