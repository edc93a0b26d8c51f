//! The embeddable soft-PLC: compile sources, run cycles on the virtual
//! clock, read and write variables by name.

use super::clock::Clock;
use super::default_trace;
use super::fault_path::{self, FaultFrame, FaultPlace};
use super::forcing::Forces;
use super::host_blocks::{HOST_SOURCE, HostBlocks, HostDispatcher};
use super::process_image::ProcessImage;
use super::scheduler::Scheduler;
use super::stop::StopHandle;
use super::watchdog::{Watchdog, WatchdogTrip};
use crate::address::Addressing;
use crate::diagnostics::Diagnostics;
use crate::driver::{self, CompileOptions};
use crate::ir::image::Image;
use crate::ir::verify::VerifiedImage;
use crate::source::encoding::SourceEncoding;
use crate::source::{SourceMap, Span};
use crate::vm::{Fault, HostLink, Machine};
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How to build and run a program.
#[derive(Debug, Clone)]
pub struct Options {
    /// Cycle time of the implicit task, in nanoseconds (default 10 ms).
    pub cycle_time: i64,
    /// The PROGRAM to run when the sources hold several (and no configuration).
    pub program: Option<String>,
    /// Wall-clock limit for one run of a task's programs (default 1 s),
    /// for every task ([`Plc::set_task_watchdog`] changes one task's);
    /// `None` disables it.
    pub watchdog: Option<Duration>,
    /// FUNCTIONs and FUNCTION_BLOCKs implemented by the host (none by default).
    pub hosts: HostBlocks,
    /// Run charts by IEC 60848 GRAFCET evolution (stable situations,
    /// forcing orders of partial grafcets) instead of IEC 61131-3 SFC
    /// evolution (default `false`; see docs/grafcet.md).
    pub grafcet: bool,
    /// Most bytes of program data (variables, FB instances, constants) the
    /// compiled program may hold (default 512 MiB); larger programs are
    /// refused with E120.
    pub max_data_bytes: usize,
    /// Pure IEC 61131-3 (`--strict`): every compatibility-extension
    /// warning (`W300`-`W399`) is an error with the same code (default
    /// `false`).
    pub strict: bool,
    /// How [`Plc::compile_bytes`] reads its files (default: detected).
    pub encoding: SourceEncoding,
    /// Emit the fused superinstructions (loop pairs, compare-and-branch,
    /// multiply-add...) and drop the bounds checks that a FOR loop's
    /// constant range proves (default `true`). Off, the same program runs
    /// on the plain instruction forms only, with the same results: the
    /// fuzzer compares both (docs/robustness.md, "Fuzzing").
    pub optimize: bool,
    /// How direct addresses are numbered (`--addressing`; see
    /// docs/runtime.md, "Addressing"): which bytes of the process image
    /// `%QW1` is, and which located variables overlap (W204). `None`
    /// (the default) chooses from the sources: `byte` for S7-200 STL,
    /// `openplc` for a PLCopen project from the OpenPLC Editor or
    /// Beremiz, `iec` otherwise.
    pub addressing: Option<Addressing>,
    /// Which executor runs the code blocks (`--engine`; default
    /// [`crate::vm::native::Engine::Interp`]). With [`crate::vm::native::Engine::Native`] the
    /// blocks are compiled to machine code when the program is built and
    /// every block the tier cannot compile runs in the interpreter;
    /// [`Plc::native_report`] tells which.
    pub engine: crate::vm::native::Engine,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            cycle_time: 10_000_000,
            program: None,
            watchdog: Some(Duration::from_secs(1)),
            hosts: HostBlocks::default(),
            grafcet: false,
            max_data_bytes: crate::driver::DEFAULT_MAX_DATA_BYTES,
            strict: false,
            encoding: SourceEncoding::Detect,
            optimize: true,
            addressing: None,
            engine: crate::vm::native::Engine::Interp,
        }
    }
}

/// Compiles `image` for `machine` when `engine` asks for native code; the
/// report of what was compiled.
fn native_code(
    machine: &mut Machine,
    image: &VerifiedImage,
    engine: crate::vm::native::Engine,
) -> Option<crate::vm::native::NativeReport> {
    if engine != crate::vm::native::Engine::Native {
        return None;
    }
    #[cfg(feature = "native")]
    {
        let compiled = crate::vm::native::compile(image);
        let report = compiled.report().clone();
        machine.set_native(Some(Box::new(compiled)));
        Some(report)
    }
    #[cfg(not(feature = "native"))]
    {
        let _ = machine;
        Some(crate::vm::native::unavailable(image.image()))
    }
}

impl Options {
    /// What the compiler needs of these options for `sources` (whose
    /// addressing convention decides when none is given). `check_only`
    /// checks every POU without choosing a program to run.
    pub(crate) fn compile_options(&self, sources: &SourceMap, check_only: bool) -> CompileOptions {
        CompileOptions {
            program: if check_only {
                None
            } else {
                self.program.clone()
            },
            cycle_time: self.cycle_time,
            check_only,
            host_pous: self.hosts.names(),
            grafcet: self.grafcet,
            max_data_bytes: self.max_data_bytes,
            strict: self.strict,
            unoptimized: !self.optimize,
            addressing: self
                .addressing
                .unwrap_or_else(|| driver::addressing_of(sources)),
            codesys_files: driver::codesys_files(sources),
            checked_files: driver::checked_files(sources),
            library_files: driver::library_files(sources),
        }
    }
}

/// Compilation failed: the diagnostics and the sources they point into.
#[derive(Debug, Clone)]
pub struct CompileError {
    /// Every diagnostic (errors and warnings).
    pub diagnostics: Diagnostics,
    /// The sources, for rendering.
    pub sources: SourceMap,
}

impl fmt::Display for CompileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.diagnostics.render(&self.sources))
    }
}

impl std::error::Error for CompileError {}

impl CompileError {
    /// True when the only errors say that the sources hold several
    /// PROGRAMs and none was chosen ([`Options::program`] picks one): a
    /// usage problem rather than a fault of the sources.
    pub fn needs_program_choice(&self) -> bool {
        self.diagnostics
            .iter()
            .all(|d| d.code == driver::AMBIGUOUS_PROGRAM)
    }
}

/// A runtime fault with its place in the source and the cycle it happened in.
#[derive(Debug, Clone, PartialEq)]
pub struct RuntimeFault {
    /// What happened.
    pub fault: Fault,
    /// `file:line:column` of the faulting instruction.
    pub location: String,
    /// The source line.
    pub excerpt: String,
    /// Name of the POU: a PROGRAM, FUNCTION_BLOCK or FUNCTION name,
    /// `FB.Method` for a method, `P.Action` for an SFC action or transition.
    pub pou: String,
    /// Cycle number (from 0).
    pub cycle: u64,
    /// For a watchdog fault: the task, its limit and the time spent
    /// (boxed: other faults do not pay for it).
    pub watchdog: Option<Box<WatchdogTrip>>,
    /// Where in the running program it happened (boxed: the fault stays
    /// small enough to return by value; see [`Self::instance`],
    /// [`Self::callers`]).
    pub(crate) place: Box<FaultPlace>,
}

impl RuntimeFault {
    /// The fault's stable code (`R001`...; see [`crate::FaultKind::code`]).
    pub fn code(&self) -> &'static str {
        self.fault.kind.code()
    }

    /// The instance path of the POU that faulted, from its program
    /// instance down: `Main.line.conveyor1.motor` for an FB instance
    /// (array elements as `motors[2]`), the instance path and the method,
    /// action or transition name (`Main.line.motor.Start`, `Main.Fill`)
    /// for those; for a FUNCTION, its name (the instance that called it is
    /// the first of [`Self::callers`]).
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let src = "FUNCTION_BLOCK Div VAR_INPUT a, b : INT; END_VAR VAR_OUTPUT q : INT; END_VAR
    ///            q := a / b; END_FUNCTION_BLOCK
    ///            PROGRAM P VAR d : ARRAY[1..2] OF Div; END_VAR d[2](a := 1, b := 0); END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// let fault = plc.run_cycle().unwrap_err();
    /// assert_eq!((fault.pou.as_str(), fault.instance()), ("Div", "P.d[2]"));
    /// assert_eq!(fault.callers()[0].instance, "P");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn instance(&self) -> &str {
        &self.place.instance
    }

    /// The calls that led to the fault, innermost first: the caller of the
    /// faulting POU first, the program instance the task ran last; empty
    /// for a fault in a program's own body.
    pub fn callers(&self) -> &[FaultFrame] {
        &self.place.callers
    }

    /// `instance`, with the POU's type when the name does not say it
    /// (`Main.line.motor : MOTOR`).
    fn place(instance: &str, pou: &str) -> String {
        if instance.eq_ignore_ascii_case(pou) {
            instance.to_string()
        } else {
            format!("{instance} : {pou}")
        }
    }
}

impl fmt::Display for RuntimeFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Laid out like a compile diagnostic: `error[R001]: ...`.
        write!(
            f,
            "error[{}]: runtime fault in cycle {} at {} (in {}): ",
            self.code(),
            self.cycle,
            self.location,
            Self::place(self.instance(), &self.pou)
        )?;
        match &self.watchdog {
            Some(trip) => write!(f, "{trip}")?,
            None => write!(f, "{}", self.fault.kind)?,
        }
        write!(f, "\n    {}", self.excerpt.trim())?;
        // One note per caller, innermost first, as rustc shows a chain.
        for c in self.callers() {
            write!(
                f,
                "\n  = note: called from {} at {}",
                Self::place(&c.instance, &c.pou),
                c.location
            )?;
        }
        Ok(())
    }
}

impl std::error::Error for RuntimeFault {}

/// A compiled program with its running state.
pub struct Plc {
    pub(super) image: VerifiedImage,
    pub(super) machine: Machine,
    pub(super) sources: SourceMap,
    pub(super) warnings: Diagnostics,
    pub(super) cycle: u64,
    pub(super) scheduler: Scheduler,
    /// Where `now` comes from (virtual by default).
    pub(super) clock: Clock,
    /// Tells this PLC's variable handles from another's.
    pub(super) id: u64,
    /// Stop requests from other threads.
    pub(super) stop: StopHandle,
    /// The fault that stopped the PLC (see `life_cycle`).
    pub(super) faulted: Option<RuntimeFault>,
    /// Per-task cycle-time limits and their timer thread.
    pub(super) watchdog: Watchdog,
    /// The `%I`, `%Q`, `%M` areas exchanged with located variables.
    pub(super) io: ProcessImage,
    /// Forced variables, applied around every program run.
    pub(super) forces: Forces,
    /// The host bodies' dispatcher (also linked into the machine), kept
    /// typed for online change to move host instances' state.
    pub(super) host_code: Option<Arc<Mutex<HostDispatcher>>>,
    /// The attached debugger (see [`super::debugger`]), if any.
    pub(super) debugger: Option<Arc<Mutex<super::debugger::Core>>>,
    /// What the native tier compiled (`None` with the interpreter).
    pub(super) native_report: Option<crate::vm::native::NativeReport>,
    /// TwinCAT's task information, when the program declares it.
    pub(super) task_info: Option<super::task_info::TaskInfo>,
}

/// The next PLC identity (handles resolved by one PLC are refused by another).
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

impl Plc {
    /// Compiles named source texts (`(file name, text)`).
    pub fn compile_files(files: &[(&str, &str)], options: &Options) -> Result<Plc, CompileError> {
        let mut sources = SourceMap::new();
        for (name, text) in files {
            sources.add(*name, *text);
        }
        Plc::compile(sources, options)
    }

    /// Compiles files given as bytes, each read in `options.encoding`
    /// (detected by default: UTF-8, or Windows-1252 with warning W020).
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let src = b"PROGRAM P (* Z\xe4hler *) VAR n : INT; END_VAR n := n + 1; END_PROGRAM";
    /// let plc = Plc::compile_bytes(&[("p.st", &src[..])], &Options::default())?;
    /// assert_eq!(plc.warnings().iter().next().map(|d| d.code), Some("W020"));
    /// # Ok::<(), plcrun::CompileError>(())
    /// ```
    pub fn compile_bytes(files: &[(&str, &[u8])], options: &Options) -> Result<Plc, CompileError> {
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        for (name, bytes) in files {
            driver::add_source_bytes(&mut sources, *name, bytes, options.encoding, &mut diags);
        }
        if diags.has_errors() {
            return Err(CompileError {
                diagnostics: diags,
                sources,
            });
        }
        Plc::compile_reported(sources, options, diags)
    }

    /// Compiles every file of `sources`.
    pub fn compile(sources: SourceMap, options: &Options) -> Result<Plc, CompileError> {
        Plc::compile_reported(sources, options, Diagnostics::new())
    }

    /// [`Plc::compile`] after `diags` were reported (by loading the files).
    fn compile_reported(
        mut sources: SourceMap,
        options: &Options,
        mut diags: Diagnostics,
    ) -> Result<Plc, CompileError> {
        if !options.hosts.is_empty() {
            sources.add(HOST_SOURCE, options.hosts.declarations());
        }
        crate::driver::twincat_library::add_library(&mut sources);
        let build = options.compile_options(&sources, false);
        let image = driver::compile(&sources, &build, &mut diags);
        match image {
            Some(image) if !diags.has_errors() => Ok(Plc::from_image(
                image,
                sources,
                diags,
                options,
                build.addressing,
            )),
            _ => Err(CompileError {
                diagnostics: diags,
                sources,
            }),
        }
    }

    fn from_image(
        image: VerifiedImage,
        sources: SourceMap,
        warnings: Diagnostics,
        options: &Options,
        addressing: Addressing,
    ) -> Plc {
        let mut machine = Machine::new(&image);
        let native_report = native_code(&mut machine, &image, options.engine);
        let stop = StopHandle::interrupting(machine.interrupt().clone());
        let watchdog = Watchdog::new(
            machine.interrupt().clone(),
            image.tasks.len(),
            options.watchdog,
        );
        let host_code = (!image.hosts.is_empty())
            .then(|| Arc::new(Mutex::new(options.hosts.dispatcher(&image))));
        if let Some(code) = &host_code {
            machine.host = HostLink(Some(code.clone()));
        }
        let scheduler = Scheduler::new(&image.tasks, &image.programs, options.cycle_time);
        let io = ProcessImage::new(&image, &machine.mem, addressing);
        let mut task_info = super::task_info::TaskInfo::of(&image);
        if let Some(info) = &mut task_info {
            info.reset(&image, &mut machine, scheduler.base_tick());
        }
        let mut plc = Plc {
            image,
            machine,
            sources,
            warnings,
            cycle: 0,
            scheduler,
            clock: Clock::default(),
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            stop,
            faulted: None,
            watchdog,
            io,
            forces: Forces::default(),
            host_code,
            debugger: None,
            native_report,
            task_info,
        };
        plc.start(true);
        plc
    }

    /// What [`crate::vm::native::Engine::Native`] did with this program's code blocks:
    /// which run as machine code, which in the interpreter and why, the
    /// size of the code and the time it took (`None` when the program
    /// runs on the interpreter, [`Options::engine`]'s default).
    pub fn native_report(&self) -> Option<&crate::vm::native::NativeReport> {
        self.native_report.as_ref()
    }

    /// A handle that asks this PLC's run to stop, from any thread.
    pub fn stop_handle(&self) -> StopHandle {
        self.stop.clone()
    }

    /// Warnings the compilation produced.
    pub fn warnings(&self) -> &Diagnostics {
        &self.warnings
    }

    /// The sources (for rendering diagnostics).
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }

    /// The compiled image.
    pub fn image(&self) -> &Image {
        &self.image
    }

    /// The number of the next cycle to run.
    pub fn cycle(&self) -> u64 {
        self.cycle
    }

    /// Duration of one base tick (the cycle time) in nanoseconds.
    pub fn cycle_time(&self) -> i64 {
        self.scheduler.base_tick()
    }

    /// The clock value of the next cycle, in nanoseconds: on the virtual
    /// clock the next base tick's time, on another clock its current
    /// reading.
    #[inline]
    pub fn time(&self) -> i64 {
        self.clock.now(self.scheduler.scheduled_time())
    }

    /// The clock value the last cycle ran at (the `now` its timers saw), in
    /// nanoseconds; 0 before the first cycle.
    pub fn last_cycle_time(&self) -> i64 {
        self.machine.now
    }

    /// Replaces the clock (see [`Clock`]); the schedule is unchanged.
    pub fn set_clock(&mut self, clock: Clock) {
        self.clock = clock;
    }

    /// The clock in use.
    pub fn clock(&self) -> &Clock {
        &self.clock
    }

    /// Runs one base tick: every task due at this tick runs its programs,
    /// by priority. After a fault the PLC is stopped: this runs nothing and
    /// returns the same fault until a reset (see [`Self::state`],
    /// [`Self::reset_cold`]).
    ///
    /// Around the programs: at the start, located variables take the
    /// `%I`/`%M` bits the host changed in the
    /// [process image](Self::process_image) and forced variables take their
    /// forced values; after each program, forces are applied again; at the
    /// end, `%Q`/`%M` variables the cycle changed are published into the
    /// image.
    pub fn run_cycle(&mut self) -> Result<(), RuntimeFault> {
        let scheduled = self.begin_tick()?;
        self.scheduler
            .start_tick(&self.image.tasks, scheduled, &self.machine.mem);
        for k in 0..self.scheduler.len() {
            let Some(p) = self.scheduler.due_program(k, &self.image.programs) else {
                continue;
            };
            self.run_program(p)?;
        }
        self.end_programs();
        self.scheduler.end_tick();
        self.cycle += 1;
        Ok(())
    }

    /// Starts a tick or a task step: refuses while faulted, reads the
    /// clock, latches the process image's inputs, applies forces. Returns
    /// the tick's scheduled time.
    #[inline(always)]
    pub(super) fn begin_tick(&mut self) -> Result<i64, RuntimeFault> {
        if let Some(fault) = &self.faulted {
            return Err(fault.clone());
        }
        if self.debugger.is_some() {
            self.debug_boundary();
        }
        let scheduled = self.scheduler.scheduled_time();
        self.machine.now = self.clock.now(scheduled);
        if !self.io.is_empty() {
            self.io.latch(&mut self.machine.mem);
        }
        if !self.forces.is_empty() {
            self.apply_forces();
        }
        Ok(scheduled)
    }

    /// Ends the programs of a tick or task step: publishes the process
    /// image's outputs, tells the watchdog no task runs.
    #[inline(always)]
    pub(super) fn end_programs(&mut self) {
        if !self.io.is_empty() {
            self.io.publish(&self.machine.mem);
        }
        self.watchdog.leave();
    }

    /// Runs program instance `p`: copies its task-bound inputs in, runs
    /// its body under its task's watchdog, copies its outputs out, applies
    /// forces again.
    #[inline(always)]
    pub(super) fn run_program(&mut self, p: usize) -> Result<(), RuntimeFault> {
        let inst = &self.image.programs[p];
        let (code, base, task) = (inst.code, inst.base, inst.task);
        self.watchdog.enter(task);
        if self.task_info.is_some() {
            self.enter_task(task);
        }
        let inst = &self.image.programs[p];
        for &(from, to) in &inst.inputs {
            self.machine.mem[to as usize] = self.machine.mem[from as usize];
        }
        if let Err(fault) = self.machine.run(&self.image, code, base) {
            return Err(self.fail(fault, base as usize));
        }
        let inst = &self.image.programs[p];
        for &(from, to) in &inst.outputs {
            self.machine.mem[to as usize] = self.machine.mem[from as usize];
        }
        if !self.forces.is_empty() {
            self.apply_forces();
        }
        Ok(())
    }

    /// TwinCAT's task information before a program of `task` runs; out
    /// of the cycle's inlined path, which only tests for it.
    #[cold]
    #[inline(never)]
    fn enter_task(&mut self, task: usize) {
        if let Some(info) = &mut self.task_info {
            info.enter(task, self.cycle, self.machine.now, &mut self.machine.mem);
        }
    }

    /// Gives a fault of the program instance at `program_base` its source
    /// location, instance path and callers (the calls the machine noted
    /// while the fault unwound).
    pub(super) fn locate(&mut self, fault: Fault, program_base: usize) -> RuntimeFault {
        let callers = self.machine.take_callers();
        let image = self.image.image();
        let span: Span = fault_path::span_of(image, fault.code, fault.pc);
        let file = self.sources.file(span.file);
        let (line, _) = file.line_col(span.start);
        let (instance, callers) = fault_path::trace(
            image,
            &self.sources,
            &self.machine.mem,
            (fault.code, fault.pc),
            &callers,
            program_base,
        );
        RuntimeFault {
            location: self.sources.location(span),
            excerpt: file.line_text(line).to_string(),
            pou: image.codes[fault.code.index()].name.clone(),
            cycle: self.cycle,
            fault,
            watchdog: None,
            place: Box::new(FaultPlace { instance, callers }),
        }
    }

    /// The names traced by default: the single values inside every
    /// VAR_OUTPUT and `%Q` variable (array elements, structure fields, FB
    /// outputs expanded), in declaration order.
    pub fn default_trace(&self) -> Vec<String> {
        default_trace::default_trace(&self.image).names
    }

    /// The VAR_OUTPUT and `%Q` variables left out of [`Self::default_trace`]
    /// because they hold more than 256 values, each with its count.
    pub fn default_trace_left_out(&self) -> Vec<(String, usize)> {
        default_trace::default_trace(&self.image).left_out
    }
}
