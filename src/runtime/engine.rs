//! The embeddable soft-PLC: compile sources, run cycles on the virtual
//! clock, read and write variables by name.

use super::default_trace;
use super::scheduler::Scheduler;
use super::stop::StopHandle;
use crate::diagnostics::Diagnostics;
use crate::driver::{self, CompileOptions};
use crate::ir::image::Image;
use crate::ir::verify::VerifiedImage;
use crate::source::{SourceMap, Span};
use crate::vm::{Fault, Machine};
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// How to build and run a program.
#[derive(Debug, Clone)]
pub struct Options {
    /// Cycle time of the implicit task, in nanoseconds (default 10 ms).
    pub cycle_time: i64,
    /// The PROGRAM to run when the sources hold several (and no configuration).
    pub program: Option<String>,
    /// Wall-clock limit for one cycle (default 1 s); `None` disables it.
    pub watchdog: Option<Duration>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            cycle_time: 10_000_000,
            program: None,
            watchdog: Some(Duration::from_secs(1)),
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
    /// Name of the POU.
    pub pou: String,
    /// Cycle number (from 0).
    pub cycle: u64,
}

impl fmt::Display for RuntimeFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "runtime fault in cycle {} at {} (in {}): {}\n    {}",
            self.cycle,
            self.location,
            self.pou,
            self.fault.kind,
            self.excerpt.trim()
        )
    }
}

impl std::error::Error for RuntimeFault {}

/// A compiled program with its running state.
pub struct Plc {
    pub(super) image: VerifiedImage,
    pub(super) machine: Machine,
    sources: SourceMap,
    warnings: Diagnostics,
    cycle: u64,
    pub(super) scheduler: Scheduler,
    /// Tells this PLC's variable handles from another's.
    pub(super) id: u64,
    /// Stop requests from other threads.
    stop: StopHandle,
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

    /// Compiles every file of `sources`.
    pub fn compile(sources: SourceMap, options: &Options) -> Result<Plc, CompileError> {
        let mut diags = Diagnostics::new();
        let build = CompileOptions {
            program: options.program.clone(),
            cycle_time: options.cycle_time,
            check_only: false,
        };
        let image = driver::compile(&sources, &build, &mut diags);
        match image {
            Some(image) if !diags.has_errors() => {
                Ok(Plc::from_image(image, sources, diags, options))
            }
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
    ) -> Plc {
        let mut machine = Machine::new(&image);
        machine.set_watchdog(options.watchdog);
        let scheduler = Scheduler::new(&image.tasks, &image.programs, options.cycle_time);
        Plc {
            image,
            machine,
            sources,
            warnings,
            cycle: 0,
            scheduler,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            stop: StopHandle::default(),
        }
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

    /// The clock value of the next cycle, in nanoseconds.
    pub fn time(&self) -> i64 {
        (self.cycle as i64).saturating_mul(self.scheduler.base_tick())
    }

    /// Runs one cycle: every task due at this tick runs its programs.
    pub fn run_cycle(&mut self) -> Result<(), RuntimeFault> {
        let now = self.time();
        self.machine.now = now;
        self.machine.start_cycle();
        self.scheduler
            .start_tick(&self.image.tasks, now, &self.machine.mem);
        for k in 0..self.scheduler.len() {
            let Some(p) = self.scheduler.due_program(k, &self.image.programs) else {
                continue;
            };
            let inst = &self.image.programs[p];
            let (code, base) = (inst.code, inst.base);
            for &(from, to) in &inst.inputs {
                self.machine.mem[to as usize] = self.machine.mem[from as usize];
            }
            if let Err(fault) = self.machine.run(&self.image, code, base) {
                return Err(self.locate(fault));
            }
            let inst = &self.image.programs[p];
            for &(from, to) in &inst.outputs {
                self.machine.mem[to as usize] = self.machine.mem[from as usize];
            }
        }
        self.cycle += 1;
        Ok(())
    }

    fn locate(&self, fault: Fault) -> RuntimeFault {
        let block = &self.image.codes[fault.code.index()];
        let span: Span = block
            .spans
            .get(fault.pc as usize)
            .copied()
            .unwrap_or_default();
        let file = self.sources.file(span.file);
        let (line, _) = file.line_col(span.start);
        RuntimeFault {
            location: self.sources.location(span),
            excerpt: file.line_text(line).to_string(),
            pou: block.name.clone(),
            cycle: self.cycle,
            fault,
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
