//! The embeddable soft-PLC: compile sources, run cycles on the virtual
//! clock, read and write variables by name.

use super::names::{self, VarRef};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::ir::image::Image;
use crate::ir::types::TypeKind;
use crate::ir::verify::VerifiedImage;
use crate::sema::{self, CompileOptions};
use crate::source::{SourceMap, Span};
use crate::types::ElemType;
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
            Value::Scalar(t, raw) => super::format::format_value(*t, *raw),
            Value::String(s, wide) => super::format::format_string(s, *wide),
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
}

/// A compiled program with its running state.
pub struct Plc {
    image: VerifiedImage,
    machine: Machine,
    sources: SourceMap,
    warnings: Diagnostics,
    cycle: u64,
    base_tick: i64,
    single_prev: Vec<bool>,
    order: Vec<usize>,
    due: Vec<bool>,
}

/// Greatest common divisor.
fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a.abs() } else { gcd(b, a % b) }
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
        let image = check_sources(&sources, options, false, &mut diags);
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
        let base_tick = image
            .tasks
            .iter()
            .filter(|t| t.interval > 0)
            .map(|t| t.interval)
            .reduce(gcd)
            .unwrap_or(options.cycle_time)
            .max(1);
        // Program instances ordered by task priority, then declaration.
        let mut order: Vec<usize> = (0..image.programs.len()).collect();
        order.sort_by_key(|&i| (image.tasks[image.programs[i].task].priority, i));
        let single_prev = vec![false; image.tasks.len()];
        Plc {
            image,
            machine,
            sources,
            warnings,
            cycle: 0,
            base_tick,
            due: vec![false; single_prev.len()],
            single_prev,
            order,
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
        self.base_tick
    }

    /// The clock value of the next cycle, in nanoseconds.
    pub fn time(&self) -> i64 {
        (self.cycle as i64).saturating_mul(self.base_tick)
    }

    /// Runs one cycle: every task due at this tick runs its programs.
    pub fn run_cycle(&mut self) -> Result<(), RuntimeFault> {
        let now = self.time();
        self.machine.now = now;
        self.machine.start_cycle();
        // SINGLE tasks run on the rising edge of their trigger.
        for (i, t) in self.image.tasks.iter().enumerate() {
            self.due[i] = match t.single {
                Some(addr) => {
                    let v = self.machine.mem[addr as usize] != 0;
                    let rising = v && !self.single_prev[i];
                    self.single_prev[i] = v;
                    rising
                }
                None => t.interval > 0 && now % t.interval == 0,
            };
        }
        for k in 0..self.order.len() {
            let inst = &self.image.programs[self.order[k]];
            if !self.due[inst.task] {
                continue;
            }
            let (code, base) = (inst.code, inst.base);
            for &(from, to) in &inst.inputs {
                self.machine.mem[to as usize] = self.machine.mem[from as usize];
            }
            if let Err(fault) = self.machine.run(&self.image, code, base) {
                return Err(self.locate(fault));
            }
            let inst = &self.image.programs[self.order[k]];
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
    pub fn resolve(&self, name: &str) -> Result<VarRef, String> {
        let r = names::resolve(&self.image, name)?;
        match &self.image.types.get(r.ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => Ok(r),
            _ => Err(format!(
                "`{name}` is a {}, not a single value",
                self.image.types.name(r.ty)
            )),
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
    pub fn read(&self, name: &str) -> Result<Value, String> {
        Ok(self.get(&self.resolve(name)?))
    }

    /// Reads an integer variable by name.
    pub fn read_i64(&self, name: &str) -> Result<i64, String> {
        self.read(name)?
            .as_i64()
            .ok_or_else(|| format!("`{name}` is not an integer"))
    }

    /// Decodes an IEC literal for the type of `r` (checks it fits).
    pub fn parse_value(&self, r: &VarRef, text: &str) -> Result<Value, String> {
        let t = text.trim();
        match &self.image.types.get(r.ty).kind {
            TypeKind::Str { wide, .. } => {
                let lit = crate::syntax::parse_literal(t)?;
                match lit.value {
                    crate::syntax::ast::LiteralValue::String { value, .. } => {
                        Ok(Value::String(value, *wide))
                    }
                    _ => Err(format!("`{t}` is not a string literal (write 'text')")),
                }
            }
            TypeKind::Enum { values, .. } => {
                let name = t.rsplit('#').next().unwrap_or(t);
                values
                    .iter()
                    .find(|(n, _)| n.eq_ignore_ascii_case(name))
                    .map(|(n, v)| Value::Enum(n.clone(), *v))
                    .ok_or_else(|| {
                        format!("`{t}` is not a value of {}", self.image.types.name(r.ty))
                    })
            }
            TypeKind::Subrange { base, lo, hi } => {
                let raw = sema::consts::parse_scalar(t, *base).ok_or_else(|| {
                    format!("`{t}` is not a valid {}", self.image.types.name(r.ty))
                })?;
                let v = raw as i64;
                if v < *lo || v > *hi {
                    return Err(format!("{v} is outside {}", self.image.types.name(r.ty)));
                }
                Ok(Value::Scalar(*base, raw))
            }
            _ => {
                let e = self.image.types.scalar(r.ty).unwrap_or(ElemType::Lint);
                let raw = sema::consts::parse_scalar(t, e)
                    .ok_or_else(|| format!("`{t}` is not a valid {e} value"))?;
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
    pub fn write(&mut self, name: &str, literal: &str) -> Result<(), String> {
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

/// Parses and checks `sources`; returns the image when there is no error.
pub fn check_sources(
    sources: &SourceMap,
    options: &Options,
    check_only: bool,
    diags: &mut Diagnostics,
) -> Option<VerifiedImage> {
    let mut units = Vec::new();
    for (i, file) in sources.files().iter().enumerate() {
        let id = crate::source::FileId(i as u32);
        units.push(crate::syntax::parse(id, &file.text, diags));
    }
    let opts = CompileOptions {
        program: options.program.clone(),
        cycle_time: options.cycle_time,
        check_only,
    };
    let image = sema::compile(&units, &opts, diags);
    if diags.has_errors() { None } else { image }
}

/// A diagnostic for a file that is not valid UTF-8.
pub fn invalid_utf8(file: crate::source::FileId, offset: usize) -> Diagnostic {
    Diagnostic::error(
        "E011",
        Span::new(file, offset, offset + 1),
        "the file is not valid UTF-8 (invalid bytes replaced by U+FFFD)",
    )
}
