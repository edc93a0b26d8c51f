//! Debugging a running PLC: breakpoints on source lines, stepping by
//! statement or by cycle, pausing, stopping on a fault — for a debugger
//! front end (`plcrun debug`'s Debug Adapter Protocol server, or an
//! embedder's own).
//!
//! [`Plc::attach_debugger`] gives the PLC a [`DebugFrontEnd`] and returns
//! the [`DebugControl`] the front end's other threads use (breakpoints,
//! pause, detach). When the PLC stops, its own thread calls
//! [`DebugFrontEnd::stopped`] with a [`StoppedPlc`] (the stack, the
//! variables, writes and forces) and resumes as the call answers.
//!
//! Cost: a PLC without a debugger runs the plain executor, which has no
//! debugging code at all (see `vm::debug`); with one attached, the
//! executor's debugging variant runs, which calls the debugger at every
//! statement start.
//!
//! ```
//! use plcrun::{DebugFrontEnd, Options, Plc, Resume, StopReason, StoppedPlc};
//! use std::sync::{Arc, Mutex};
//!
//! struct Record(Arc<Mutex<Vec<String>>>);
//! impl DebugFrontEnd for Record {
//!     fn stopped(&mut self, _why: StopReason, plc: &mut StoppedPlc<'_>) -> Resume {
//!         let top = &plc.frames()[0];
//!         let n = plc.evaluate(0, "n").unwrap();
//!         self.0.lock().unwrap().push(format!("{}:{} n={n}", top.name, top.line));
//!         Resume::Continue
//!     }
//! }
//! let src = "PROGRAM P\nVAR n : INT; END_VAR\nn := n + 1;\nn := n * 2;\nEND_PROGRAM";
//! let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
//! let seen = Arc::new(Mutex::new(Vec::new()));
//! let control = plc.attach_debugger(Box::new(Record(seen.clone())), false);
//! control.set_breakpoints("p.st", &[plcrun::Breakpoint::at(4)]);
//! plc.run_cycle()?;
//! plc.run_cycle()?;
//! assert_eq!(*seen.lock().unwrap(), ["P:4 n=1", "P:4 n=3"]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::debug_lines::{LineTable, SfcElement};
use super::debug_view::{self, StoppedPlc};
use super::engine::{Plc, RuntimeFault};
use crate::ir::image::Image;
use crate::ir::op::{ChartIdx, CodeIdx};
use crate::source::SourceMap;
use crate::vm::{ChartEvent, DebugFrame, DebugHook, FaultKind, Machine};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// A breakpoint asked for on a source line.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Breakpoint {
    /// The 1-based line.
    pub line: u32,
    /// Stop only when this ST expression is TRUE (evaluated in the
    /// stopping instance).
    pub condition: Option<String>,
    /// Stop only on some hits: `N` or `>= N` (from the Nth hit on), `> N`,
    /// `== N` or `= N` (the Nth only), `% N` (every Nth).
    pub hit_condition: Option<String>,
}

impl Breakpoint {
    /// A plain breakpoint on `line`.
    pub fn at(line: u32) -> Breakpoint {
        Breakpoint {
            line,
            ..Breakpoint::default()
        }
    }
}

/// Where a breakpoint was set.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BreakpointPlace {
    /// Its number (in [`StopReason::Breakpoint`]).
    pub id: u32,
    /// Whether a statement was found for it.
    pub verified: bool,
    /// The line it was set on: the line asked for, or the next line with a
    /// statement.
    pub line: u32,
    /// Why it was not set.
    pub message: Option<String>,
}

/// Why the PLC stopped.
#[derive(Debug, Clone)]
pub enum StopReason {
    /// Before the first cycle (`stop_on_entry`).
    Entry,
    /// At a breakpoint (their numbers).
    Breakpoint(Vec<u32>),
    /// A step ended.
    Step,
    /// A pause was asked.
    Pause,
    /// At a cycle boundary, before the cycle [`StoppedPlc::cycle`] runs (a
    /// cycle step ended, or a pause at the boundary was asked).
    Cycle,
    /// A runtime fault stopped the PLC; it stays stopped after the resume.
    Fault(Box<RuntimeFault>),
}

/// How the PLC goes on after a stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resume {
    /// Run until a breakpoint, a pause or a fault.
    Continue,
    /// To the next statement of this block or its callers (step over).
    Next,
    /// To the next statement, entering calls (step into).
    StepIn,
    /// To the next statement of a caller (step out); from a program's body,
    /// to the next program run.
    StepOut,
    /// To the next cycle boundary (one cycle further).
    Cycle,
    /// Run on without the debugger stopping again.
    Detach,
}

/// What a debugger does when the PLC stops (called on the PLC's thread,
/// which waits for the answer).
pub trait DebugFrontEnd: Send {
    /// The PLC stopped for `reason`; `plc` is what can be seen and changed
    /// until the answer, which says how to go on.
    fn stopped(&mut self, reason: StopReason, plc: &mut StoppedPlc<'_>) -> Resume;
}

/// A breakpoint as set: where it stops, and when.
#[derive(Debug, Clone)]
struct SetBreakpoint {
    id: u32,
    places: Vec<(CodeIdx, u32)>,
    /// The SFC elements it watches (a line of a step, an association or
    /// a transition header).
    sfc: Vec<(ChartIdx, SfcElement)>,
    condition: Option<String>,
    hit: Option<HitCondition>,
}

/// When a breakpoint's hits stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum HitCondition {
    AtLeast(u64),
    Exactly(u64),
    Every(u64),
}

impl HitCondition {
    fn parse(text: &str) -> Option<HitCondition> {
        let t = text.trim();
        let num = |s: &str| s.trim().parse::<u64>().ok();
        if let Some(r) = t.strip_prefix(">=") {
            return num(r).map(HitCondition::AtLeast);
        }
        if let Some(r) = t.strip_prefix('>') {
            return num(r).map(|n| HitCondition::AtLeast(n + 1));
        }
        if let Some(r) = t.strip_prefix("==").or_else(|| t.strip_prefix('=')) {
            return num(r).map(HitCondition::Exactly);
        }
        if let Some(r) = t.strip_prefix('%') {
            return num(r).filter(|n| *n > 0).map(HitCondition::Every);
        }
        num(t).map(HitCondition::AtLeast)
    }

    fn stops(self, hits: u64) -> bool {
        match self {
            HitCondition::AtLeast(n) => hits >= n,
            HitCondition::Exactly(n) => hits == n,
            HitCondition::Every(n) => hits.is_multiple_of(n),
        }
    }
}

/// A force or unforce asked while the PLC was stopped in a cycle: applied
/// at the next cycle boundary (the value is written at once).
#[derive(Debug, Clone)]
pub(crate) enum ForceRequest {
    Force(String, String),
    Unforce(String),
}

/// The debugger's controls, shared with any thread: breakpoints, pause,
/// detach.
#[derive(Debug)]
pub struct DebugControl {
    lines: LineTable,
    breakpoints: Mutex<BTreeMap<usize, Vec<SetBreakpoint>>>,
    next_id: AtomicU64,
    version: AtomicU64,
    pause: AtomicBool,
    pause_at_cycle: AtomicBool,
    detached: AtomicBool,
    /// A step (in, over, out) is under way: every statement start is
    /// looked at.
    stepping: AtomicBool,
    pub(crate) forces: Mutex<Vec<ForceRequest>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl DebugControl {
    /// The program's line table.
    pub fn lines(&self) -> &LineTable {
        &self.lines
    }

    /// Replaces the breakpoints of source file `file` (its name as loaded,
    /// or its path); says where each was set.
    pub fn set_breakpoints(&self, file: &str, wanted: &[Breakpoint]) -> Vec<BreakpointPlace> {
        let index = self.lines.file_index(file);
        let mut set = Vec::new();
        let mut places = Vec::new();
        for b in wanted {
            let id = self.next_id.fetch_add(1, Ordering::Relaxed) as u32 + 1;
            let hit = match &b.hit_condition {
                Some(text) if !text.trim().is_empty() => match HitCondition::parse(text) {
                    Some(h) => Some(h),
                    None => {
                        places.push(BreakpointPlace {
                            id,
                            verified: false,
                            line: b.line,
                            message: Some(format!(
                                "hit count `{text}`: expected N, >= N, > N, == N or % N"
                            )),
                        });
                        continue;
                    }
                },
                _ => None,
            };
            let sfc: Vec<(ChartIdx, SfcElement)> = index
                .map(|f| self.lines.sfc_at(f, b.line))
                .unwrap_or_default()
                .into_iter()
                .map(|p| (p.chart, p.element))
                .collect();
            if !sfc.is_empty() {
                set.push(SetBreakpoint {
                    id,
                    places: Vec::new(),
                    sfc,
                    condition: b.condition.clone().filter(|c| !c.trim().is_empty()),
                    hit,
                });
                places.push(BreakpointPlace {
                    id,
                    verified: true,
                    line: b.line,
                    message: None,
                });
                continue;
            }
            let found = index.and_then(|f| self.lines.statements_at(f, b.line));
            match found {
                Some((line, at)) => {
                    set.push(SetBreakpoint {
                        id,
                        places: at,
                        sfc: Vec::new(),
                        condition: b.condition.clone().filter(|c| !c.trim().is_empty()),
                        hit,
                    });
                    places.push(BreakpointPlace {
                        id,
                        verified: true,
                        line,
                        message: None,
                    });
                }
                None => places.push(BreakpointPlace {
                    id,
                    verified: false,
                    line: b.line,
                    message: Some(match index {
                        None => format!("`{file}` is not a source of the program"),
                        Some(_) => "no statement on or after this line".to_string(),
                    }),
                }),
            }
        }
        if let Some(f) = index {
            lock(&self.breakpoints).insert(f, set);
            self.version.fetch_add(1, Ordering::Release);
        }
        places
    }

    /// Asks the PLC to stop at the next statement it runs (or at the next
    /// cycle boundary, should that come first).
    pub fn pause(&self) {
        self.pause.store(true, Ordering::Release);
    }

    /// Asks the PLC to stop at the next cycle boundary.
    pub fn pause_at_cycle(&self) {
        self.pause_at_cycle.store(true, Ordering::Release);
    }

    /// Lets the PLC run on without stopping again (the next stop does not
    /// happen; a stop under way ends when its front end answers).
    pub fn detach(&self) {
        self.detached.store(true, Ordering::Release);
    }

    /// Whether [`Self::detach`] was called.
    pub fn is_detached(&self) -> bool {
        self.detached.load(Ordering::Acquire)
    }

    /// Queues a force (or unforce, `value` `None`) for the next cycle
    /// boundary, for a front end whose PLC runs (not stopped).
    pub fn force_later(&self, path: &str, value: Option<&str>) {
        let request = match value {
            Some(v) => ForceRequest::Force(path.to_string(), v.to_string()),
            None => ForceRequest::Unforce(path.to_string()),
        };
        lock(&self.forces).push(request);
    }
}

/// How the next statements are looked at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Run,
    StepIn,
    /// Stop at a depth at most this.
    Over(usize),
    /// Stop at a depth below this; from depth 1, at the next program run.
    Out(usize, (CodeIdx, usize, u32)),
    Cycle,
}

/// The debugger's state on the PLC's thread.
pub(crate) struct Core {
    control: Arc<DebugControl>,
    front: Box<dyn DebugFrontEnd>,
    sources: SourceMap,
    mode: Mode,
    entry: bool,
    /// The breakpoint version the flags below were built from.
    seen: u64,
    /// Per code block, per instruction: the breakpoints there (indexes
    /// into `set`), empty for none.
    flags: Vec<Vec<Vec<usize>>>,
    set: Vec<SetBreakpoint>,
    /// The breakpoints on SFC elements (indexes into `set`).
    sfc_flags: BTreeMap<(ChartIdx, SfcElement), Vec<usize>>,
    hits: BTreeMap<u32, u64>,
}

impl Core {
    /// Rebuilds the breakpoint flags when the breakpoints changed.
    fn refresh(&mut self, image: &Image) {
        let version = self.control.version.load(Ordering::Acquire);
        if version == self.seen && !self.flags.is_empty() {
            return;
        }
        self.seen = version;
        self.set = lock(&self.control.breakpoints)
            .values()
            .flatten()
            .cloned()
            .collect();
        self.flags = image
            .codes
            .iter()
            .map(|c| vec![Vec::new(); c.ops.len()])
            .collect();
        self.sfc_flags.clear();
        for (k, b) in self.set.iter().enumerate() {
            for &e in &b.sfc {
                self.sfc_flags.entry(e).or_default().push(k);
            }
            for &(code, pc) in &b.places {
                if let Some(slot) = self
                    .flags
                    .get_mut(code.index())
                    .and_then(|f| f.get_mut(pc as usize))
                {
                    slot.push(k);
                }
            }
        }
    }

    /// Stops: asks the front end, takes its answer as the next mode.
    fn stop(&mut self, reason: StopReason, view: StoppedPlc<'_>) {
        let mode = ask(&mut self.front, &self.control, reason, view);
        self.set_mode(mode);
    }

    /// The next mode; the hook's fast path learns whether a step is under way.
    fn set_mode(&mut self, mode: Mode) {
        self.mode = mode;
        let stepping = matches!(mode, Mode::StepIn | Mode::Over(_) | Mode::Out(..));
        self.control.stepping.store(stepping, Ordering::Release);
    }

    /// Which of the breakpoints `here` (indexes into `set`) stop now:
    /// their conditions hold and their hit counts say so.
    fn hits_of(
        &mut self,
        here: &[usize],
        img: &Image,
        m: &mut Machine,
        stack: &[DebugFrame],
    ) -> Vec<u32> {
        let mut hit = Vec::new();
        for &k in here {
            let b = self.set[k].clone();
            if let Some(cond) = &b.condition {
                let view = StoppedPlc::in_cycle(img, &self.sources, m, stack, &self.control);
                match view.evaluate(0, cond) {
                    Ok(v) if v.as_bool() == Some(true) => {}
                    Ok(_) => continue,
                    // A condition that cannot be evaluated stops, so that
                    // the user sees why.
                    Err(_) => {}
                }
            }
            let n = self.hits.entry(b.id).or_insert(0);
            *n += 1;
            if b.hit.is_none_or(|h| h.stops(*n)) {
                hit.push(b.id);
            }
        }
        hit
    }

    /// An SFC chart's event: a breakpoint on its element stops, shown as
    /// a frame at the element's line above the program's.
    fn chart_event(
        &mut self,
        img: &Image,
        m: &mut Machine,
        stack: &[DebugFrame],
        chart: ChartIdx,
        event: ChartEvent,
    ) {
        if self.control.is_detached() {
            return;
        }
        self.refresh(img);
        let element = match event {
            ChartEvent::Step(s) => SfcElement::Step(s),
            ChartEvent::Fired(t) => SfcElement::Transition(t),
            ChartEvent::Action(a) => SfcElement::Action(a),
        };
        let Some(here) = self.sfc_flags.get(&(chart, element)).cloned() else {
            return;
        };
        let hit = self.hits_of(&here, img, m, stack);
        if hit.is_empty() {
            return;
        }
        let place = self.control.lines.sfc_place(chart, element).map(|p| {
            let file = self.control.lines.file_name(p.file).map(str::to_string);
            (p.name.clone(), file, p.line)
        });
        let mut view = StoppedPlc::in_cycle(img, &self.sources, m, stack, &self.control);
        if let Some((name, file, line)) = place {
            view.push_sfc_frame(&name, file, line);
        }
        let mode = ask(
            &mut self.front,
            &self.control,
            StopReason::Breakpoint(hit),
            view,
        );
        self.set_mode(mode);
    }

    /// A statement start of the debugging executor.
    fn statement(&mut self, img: &Image, m: &mut Machine, stack: &[DebugFrame]) {
        if self.control.is_detached() {
            return;
        }
        self.refresh(img);
        let Some(top) = stack.last() else {
            return;
        };
        let depth = stack.len();
        let mut reason = match self.mode {
            Mode::StepIn => Some(StopReason::Step),
            Mode::Over(d) if depth <= d => Some(StopReason::Step),
            Mode::Out(d, _) if depth < d => Some(StopReason::Step),
            Mode::Out(1, (code, base, pc))
                if depth == 1 && (top.code != code || top.base != base || top.pc < pc) =>
            {
                Some(StopReason::Step)
            }
            _ => None,
        };
        if self.control.pause.load(Ordering::Relaxed)
            && self.control.pause.swap(false, Ordering::AcqRel)
        {
            reason = Some(StopReason::Pause);
        }
        // Cloned only where a breakpoint is (the hits may stop, which
        // needs `self`).
        let here = self
            .flags
            .get(top.code.index())
            .and_then(|f| f.get(top.pc as usize))
            .filter(|h| !h.is_empty())
            .cloned();
        if let Some(here) = here {
            let hit = self.hits_of(&here, img, m, stack);
            if !hit.is_empty() {
                reason = Some(StopReason::Breakpoint(hit));
            }
        }
        if let Some(reason) = reason {
            let view = StoppedPlc::in_cycle(img, &self.sources, m, stack, &self.control);
            let mode = ask(&mut self.front, &self.control, reason, view);
            self.set_mode(mode);
        }
    }
}

/// Asks `front` at a stop; its answer as the next mode.
fn ask(
    front: &mut Box<dyn DebugFrontEnd>,
    control: &DebugControl,
    reason: StopReason,
    mut view: StoppedPlc<'_>,
) -> Mode {
    match front.stopped(reason, &mut view) {
        Resume::Continue => Mode::Run,
        // At a cycle boundary (no block runs): a step goes to the first
        // statement, a step out to the next boundary.
        Resume::StepIn | Resume::Next if view.depth() == 0 => Mode::StepIn,
        Resume::StepOut if view.depth() == 0 => Mode::Cycle,
        Resume::StepIn => Mode::StepIn,
        Resume::Next => Mode::Over(view.depth()),
        Resume::StepOut => {
            let top = view.top().unwrap_or((CodeIdx::new(0), 0, 0));
            Mode::Out(view.depth(), top)
        }
        Resume::Cycle => Mode::Cycle,
        Resume::Detach => {
            control.detach();
            Mode::Run
        }
    }
}

/// The hook the machine calls (the PLC's thread only).
struct Hook {
    core: Arc<Mutex<Core>>,
    control: Arc<DebugControl>,
    /// Per code block, per instruction: a line breakpoint is there.
    armed: Vec<Vec<bool>>,
    /// The breakpoint version `armed` was built from.
    seen: u64,
}

impl Hook {
    /// Whether the statement at `top` may stop: a breakpoint is there, a
    /// step is under way or a pause was asked (looked at without locking
    /// the debugger's state).
    fn may_stop(&mut self, img: &Image, top: &DebugFrame) -> bool {
        if self.control.is_detached() {
            return false;
        }
        let version = self.control.version.load(Ordering::Acquire);
        if version != self.seen {
            self.seen = version;
            self.armed = img.codes.iter().map(|c| vec![false; c.ops.len()]).collect();
            for b in lock(&self.control.breakpoints).values().flatten() {
                for &(code, pc) in &b.places {
                    if let Some(flag) = self
                        .armed
                        .get_mut(code.index())
                        .and_then(|f| f.get_mut(pc as usize))
                    {
                        *flag = true;
                    }
                }
            }
        }
        let armed = self
            .armed
            .get(top.code.index())
            .and_then(|f| f.get(top.pc as usize))
            .copied()
            .unwrap_or(false);
        armed
            || self.control.stepping.load(Ordering::Acquire)
            || self.control.pause.load(Ordering::Relaxed)
    }
}

impl DebugHook for Hook {
    fn statement(
        &mut self,
        img: &Image,
        m: &mut Machine,
        stack: &[DebugFrame],
    ) -> Result<(), FaultKind> {
        if let Some(top) = stack.last()
            && self.may_stop(img, top)
        {
            lock(&self.core).statement(img, m, stack);
        }
        Ok(())
    }

    fn chart(
        &mut self,
        img: &Image,
        m: &mut Machine,
        stack: &[DebugFrame],
        chart: ChartIdx,
        event: ChartEvent,
    ) {
        lock(&self.core).chart_event(img, m, stack, chart, event);
    }
}

impl Plc {
    /// Attaches a debugger (replacing one attached before): from the next
    /// cycle on, the PLC stops where the returned control's breakpoints,
    /// steps and pauses say, and on a fault, calling `front` on its thread.
    /// With `stop_on_entry` it stops before its next cycle.
    pub fn attach_debugger(
        &mut self,
        front: Box<dyn DebugFrontEnd>,
        stop_on_entry: bool,
    ) -> Arc<DebugControl> {
        let lines = LineTable::new(&self.image, &self.sources);
        let starts = lines.starts().clone();
        let control = Arc::new(DebugControl {
            lines,
            breakpoints: Mutex::default(),
            next_id: AtomicU64::new(0),
            version: AtomicU64::new(1),
            pause: AtomicBool::new(false),
            pause_at_cycle: AtomicBool::new(false),
            detached: AtomicBool::new(false),
            stepping: AtomicBool::new(false),
            forces: Mutex::default(),
        });
        let core = Arc::new(Mutex::new(Core {
            control: control.clone(),
            front,
            sources: self.sources.clone(),
            mode: Mode::Run,
            entry: stop_on_entry,
            seen: 0,
            flags: Vec::new(),
            set: Vec::new(),
            sfc_flags: BTreeMap::new(),
            hits: BTreeMap::new(),
        }));
        let hook = Hook {
            core: core.clone(),
            control: control.clone(),
            armed: Vec::new(),
            seen: 0,
        };
        self.machine.attach_debugger(starts, Box::new(hook));
        self.debugger = Some(core);
        control
    }

    /// Detaches the debugger: the PLC runs the plain executor again.
    pub fn detach_debugger(&mut self) {
        if let Some(core) = self.debugger.take() {
            lock(&core).control.detach();
        }
        self.machine.detach_debugger();
    }

    /// At the start of a tick with a debugger attached: applies the forces
    /// asked meanwhile, and stops when a cycle step, a pause at the
    /// boundary or the entry stop asks.
    #[cold]
    #[inline(never)]
    pub(super) fn debug_boundary(&mut self) {
        let Some(core) = self.debugger.clone() else {
            return;
        };
        let mut core = lock(&core);
        self.apply_debug_forces(&core.control);
        if core.control.is_detached() {
            drop(core);
            self.detach_debugger();
            return;
        }
        let reason = if std::mem::take(&mut core.entry) {
            Some(StopReason::Entry)
        } else if core.mode == Mode::Cycle
            || core.control.pause_at_cycle.swap(false, Ordering::AcqRel)
        {
            Some(StopReason::Cycle)
        } else if core.control.pause.swap(false, Ordering::AcqRel) {
            Some(StopReason::Pause)
        } else {
            None
        };
        let Some(reason) = reason else {
            return;
        };
        let control = core.control.clone();
        let view = debug_view::at_boundary(self, &control);
        // After a cycle step, the mode stays `Cycle`: the next boundary stops.
        core.stop(reason, view);
        drop(core);
        self.apply_debug_forces(&control);
    }

    /// Applies the forces the front end asked for while the PLC was stopped
    /// in a cycle or running.
    fn apply_debug_forces(&mut self, control: &DebugControl) {
        let requests = std::mem::take(&mut *lock(&control.forces));
        for r in requests {
            // Checked when asked (`StoppedPlc::force`); a PLC changed since
            // may refuse, which the front end has no one to tell.
            let _ = match r {
                ForceRequest::Force(path, value) => self.force(&path, &value),
                ForceRequest::Unforce(path) => self.unforce(&path).map(|_| ()),
            };
        }
    }

    /// A fault with a debugger attached: the front end sees it, with the
    /// stack as the fault left it, before the PLC stops.
    #[cold]
    #[inline(never)]
    pub(super) fn debug_fault(
        &mut self,
        fault: &RuntimeFault,
        frames: Vec<super::fault_path::Frame>,
    ) {
        let Some(core) = self.debugger.clone() else {
            return;
        };
        let mut core = lock(&core);
        if core.control.is_detached() {
            return;
        }
        let control = core.control.clone();
        let view = debug_view::at_fault(self, &control, frames);
        core.stop(StopReason::Fault(Box::new(fault.clone())), view);
    }
}
