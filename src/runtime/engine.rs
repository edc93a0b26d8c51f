//! The embeddable soft-PLC: compile sources, run cycles on the virtual
//! clock, read and write variables by name.

use super::names::{self, VarRef};
use super::scheduler::Scheduler;
use super::var_error::{ValueProblem, VarError};
use crate::diagnostics::Diagnostics;
use crate::driver::{self, Build};
use crate::ir::image::Image;
use crate::ir::types::TypeKind;
use crate::ir::verify::VerifiedImage;
use crate::source::{SourceMap, Span};
use crate::types::ElemType;
use crate::value::text::{Lit, parse_literal_text, parse_scalar};
use crate::vm::{Fault, Machine};
use std::fmt;
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

/// A value read from the PLC.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An elementary value in its slot encoding.
    Scalar(ElemType, u64),
    /// A string.
    String(String, bool),
    /// An enumeration value.
    Enum(String, i64),
}

impl Value {
    /// The value as an IEC literal (`TRUE`, `42`, `T#1s`, `'x'`).
    pub fn to_literal(&self) -> String {
        match self {
            Value::Scalar(t, raw) => crate::value::format::format_value(*t, *raw),
            Value::String(s, wide) => crate::value::format::format_string(s, *wide),
            Value::Enum(name, _) => name.clone(),
        }
    }

    /// The value as a signed integer, if it is an integer-like scalar.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::Scalar(t, raw)
                if t.is_signed_int() || t.family() == crate::types::Family::Duration =>
            {
                Some(*raw as i64)
            }
            Value::Scalar(t, raw) if t.is_int() || t.is_bit() => i64::try_from(*raw).ok(),
            Value::Enum(_, v) => Some(*v),
            _ => None,
        }
    }

    /// The value of a BOOL.
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Scalar(ElemType::Bool, raw) => Some(*raw != 0),
            _ => None,
        }
    }

    /// The value of a REAL or LREAL (a REAL widened exactly), or of an
    /// integer that an f64 holds exactly.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Scalar(ElemType::Real, raw) => Some(f32::from_bits(*raw as u32) as f64),
            Value::Scalar(ElemType::Lreal, raw) => Some(f64::from_bits(*raw)),
            _ => {
                let v = self.as_i64()?;
                let exact = v.unsigned_abs() <= 1 << f64::MANTISSA_DIGITS;
                exact.then_some(v as f64)
            }
        }
    }

    /// The text of a STRING or WSTRING.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::String(s, _) => Some(s),
            _ => None,
        }
    }
}

impl fmt::Display for Value {
    /// The IEC literal, as [`Value::to_literal`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_literal())
    }
}

/// A compiled program with its running state.
pub struct Plc {
    image: VerifiedImage,
    machine: Machine,
    sources: SourceMap,
    warnings: Diagnostics,
    cycle: u64,
    scheduler: Scheduler,
}

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
        let build = Build {
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
        }
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
        let block = &self.image.codes[fault.code as usize];
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

    /// Resolves a variable name (see `docs/cli.md` for the syntax).
    pub fn resolve(&self, name: &str) -> Result<VarRef, VarError> {
        let r = names::resolve(&self.image, name)?;
        match &self.image.types.get(r.ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => Ok(r),
            _ => Err(VarError::NotAValue {
                path: name.to_string(),
                ty: self.image.types.name(r.ty).to_string(),
            }),
        }
    }

    /// Reads a resolved variable.
    pub fn get(&self, r: &VarRef) -> Value {
        let raw = self.machine.mem[r.addr as usize];
        match &self.image.types.get(r.ty).kind {
            TypeKind::Str { wide, .. } => {
                let s = self
                    .machine
                    .strings
                    .get(raw as usize)
                    .map(|s| s.text.clone())
                    .unwrap_or_default();
                Value::String(s, *wide)
            }
            TypeKind::Enum { values, .. } => {
                let v = raw as i64;
                let name = values
                    .iter()
                    .find(|(_, x)| *x == v)
                    .map(|(n, _)| n.clone())
                    .unwrap_or_else(|| v.to_string());
                Value::Enum(name, v)
            }
            _ => Value::Scalar(self.image.types.scalar(r.ty).unwrap_or(ElemType::Lint), raw),
        }
    }

    /// Reads a variable by name.
    pub fn read(&self, name: &str) -> Result<Value, VarError> {
        Ok(self.get(&self.resolve(name)?))
    }

    /// Reads an integer variable by name.
    pub fn read_i64(&self, name: &str) -> Result<i64, VarError> {
        self.read(name)?
            .as_i64()
            .ok_or_else(|| VarError::NotAnInteger {
                path: name.to_string(),
            })
    }

    /// Decodes an IEC literal for the type of `r` (checks it fits).
    pub fn parse_value(&self, r: &VarRef, text: &str) -> Result<Value, VarError> {
        let t = text.trim();
        let bad = |problem| VarError::BadValue {
            literal: t.to_string(),
            ty: self.image.types.name(r.ty).to_string(),
            problem,
        };
        match &self.image.types.get(r.ty).kind {
            TypeKind::Str { wide, .. } => match parse_literal_text(t) {
                Ok((Lit::Str { value, .. }, _)) => Ok(Value::String(value, *wide)),
                _ => Err(bad(ValueProblem::NotAString)),
            },
            TypeKind::Enum { values, .. } => {
                let name = t.rsplit('#').next().unwrap_or(t);
                values
                    .iter()
                    .find(|(n, _)| n.eq_ignore_ascii_case(name))
                    .map(|(n, v)| Value::Enum(n.clone(), *v))
                    .ok_or_else(|| bad(ValueProblem::NotAnEnumValue))
            }
            TypeKind::Subrange { base, lo, hi } => {
                let raw = parse_scalar(t, *base).ok_or_else(|| bad(ValueProblem::Invalid))?;
                let v = raw as i64;
                if v < *lo || v > *hi {
                    return Err(bad(ValueProblem::OutsideSubrange(v)));
                }
                Ok(Value::Scalar(*base, raw))
            }
            _ => {
                let e = self.image.types.scalar(r.ty).unwrap_or(ElemType::Lint);
                let raw = parse_scalar(t, e).ok_or_else(|| bad(ValueProblem::Invalid))?;
                Ok(Value::Scalar(e, raw))
            }
        }
    }

    /// Writes a value into a resolved variable.
    pub fn set(&mut self, r: &VarRef, v: &Value) {
        match v {
            Value::Scalar(_, raw) => self.machine.mem[r.addr as usize] = *raw,
            Value::Enum(_, x) => self.machine.mem[r.addr as usize] = *x as u64,
            Value::String(s, _) => {
                let id = self.machine.mem[r.addr as usize] as usize;
                if let Some(slot) = self.machine.strings.get_mut(id) {
                    slot.set(s);
                }
            }
        }
    }

    /// Writes a variable by name from an IEC literal.
    pub fn write(&mut self, name: &str, literal: &str) -> Result<(), VarError> {
        let r = self.resolve(name)?;
        let v = self.parse_value(&r, literal)?;
        self.set(&r, &v);
        Ok(())
    }

    /// The names traced by default (VAR_OUTPUTs and `%Q` variables).
    pub fn default_trace(&self) -> Vec<String> {
        names::default_trace(&self.image)
    }
}
