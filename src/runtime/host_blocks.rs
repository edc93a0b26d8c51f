//! Host extension points: FUNCTIONs and FUNCTION_BLOCKs whose interface is
//! declared to the compiler and whose body is Rust code of the host.
//!
//! A host lists the pins of each POU with [`HostSignature`] (names and
//! elementary types, so a bad declaration cannot reach the compiler) and
//! gives a closure; [`HostBlocks`] holds them and goes into
//! [`crate::Options::hosts`]. At compile time each signature becomes an
//! ordinary IEC declaration with an empty body (in a source file named
//! [`HOST_SOURCE`]); the checker types calls to it exactly as calls to a
//! POU written in IEC, and emits its body as one `Op::CallHost`. At run time
//! that instruction hands the frame to the closure through [`HostIo`].
//!
//! A FUNCTION_BLOCK gets a fresh closure per instance (from the factory
//! given at registration), so per-instance state lives in what the closure
//! captures. A closure that returns an error or panics stops the PLC with
//! the runtime fault [`crate::FaultKind::HostFunction`].

use super::plc_value::Value;
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::op::HostIdx;
use crate::ir::type_table::TypeKind;
use crate::value::encode::{int_to_slot, is_canonical, real_to_slot};
use crate::vm::{FaultKind, HostDispatch, HostFrame};
use std::collections::HashMap;
use std::fmt;
use std::sync::{Arc, Mutex};

/// The name of the source file holding the generated declarations (a
/// diagnostic about a host POU points into it).
pub const HOST_SOURCE: &str = "<host>";

/// What a host body returns: any error stops the PLC with a runtime fault
/// carrying its text.
pub type HostResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// The code of a host FUNCTION, or of one instance of a host FUNCTION_BLOCK.
type BodyFn = Box<dyn FnMut(&mut HostIo<'_>) -> HostResult + Send>;

/// Makes the code of a new FUNCTION_BLOCK instance.
type Factory = Box<dyn Fn() -> BodyFn + Send + Sync>;

/// Direction of a pin.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PinDir {
    /// VAR_INPUT: the program writes it, the host reads it.
    Input,
    /// VAR_OUTPUT: the host writes it, the program reads it.
    Output,
    /// A FUNCTION's result (the pin is named as the function).
    Result,
}

/// One pin of a host POU.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HostPin {
    /// Name as the program spells it.
    pub name: String,
    /// Direction.
    pub dir: PinDir,
    /// Type (STRING and WSTRING pins hold up to 254 characters).
    pub ty: ElemType,
}

/// The IEC interface of a host FUNCTION or FUNCTION_BLOCK.
///
/// ```
/// use plcrun::{ElemType, HostSignature};
/// let motor = HostSignature::block("MotorDrive")
///     .input("run", ElemType::Bool)
///     .input("speed", ElemType::Real)
///     .output("ready", ElemType::Bool);
/// assert_eq!(
///     motor.declaration(),
///     "FUNCTION_BLOCK MotorDrive\nVAR_INPUT\n  run : BOOL;\n  speed : REAL;\nEND_VAR\n\
///      VAR_OUTPUT\n  ready : BOOL;\nEND_VAR\nEND_FUNCTION_BLOCK\n"
/// );
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HostSignature {
    name: String,
    result: Option<ElemType>,
    pins: Vec<HostPin>,
}

impl HostSignature {
    /// A FUNCTION named `name` returning a `result`.
    pub fn function(name: &str, result: ElemType) -> HostSignature {
        HostSignature {
            name: name.to_string(),
            result: Some(result),
            pins: Vec::new(),
        }
    }

    /// A FUNCTION_BLOCK named `name`.
    pub fn block(name: &str) -> HostSignature {
        HostSignature {
            name: name.to_string(),
            result: None,
            pins: Vec::new(),
        }
    }

    /// Adds a VAR_INPUT (in call order: non-formal calls follow it).
    pub fn input(mut self, name: &str, ty: ElemType) -> HostSignature {
        self.pins.push(HostPin {
            name: name.to_string(),
            dir: PinDir::Input,
            ty,
        });
        self
    }

    /// Adds a VAR_OUTPUT.
    pub fn output(mut self, name: &str, ty: ElemType) -> HostSignature {
        self.pins.push(HostPin {
            name: name.to_string(),
            dir: PinDir::Output,
            ty,
        });
        self
    }

    /// The POU's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its pins, the result first for a FUNCTION.
    pub fn pins(&self) -> Vec<HostPin> {
        let result = self.result.map(|ty| HostPin {
            name: self.name.clone(),
            dir: PinDir::Result,
            ty,
        });
        result
            .into_iter()
            .chain(self.pins.iter().cloned())
            .collect()
    }

    /// The IEC declaration the compiler sees (its body is empty).
    pub fn declaration(&self) -> String {
        let mut text = match self.result {
            Some(ty) => format!("FUNCTION {} : {}\n", self.name, ty.name()),
            None => format!("FUNCTION_BLOCK {}\n", self.name),
        };
        for (dir, section) in [(PinDir::Input, "VAR_INPUT"), (PinDir::Output, "VAR_OUTPUT")] {
            let pins: Vec<&HostPin> = self.pins.iter().filter(|p| p.dir == dir).collect();
            if pins.is_empty() {
                continue;
            }
            text.push_str(section);
            text.push('\n');
            for p in pins {
                text.push_str(&format!("  {} : {};\n", p.name, p.ty.name()));
            }
            text.push_str("END_VAR\n");
        }
        text.push_str(if self.result.is_some() {
            "END_FUNCTION\n"
        } else {
            "END_FUNCTION_BLOCK\n"
        });
        text
    }

    /// Names are identifiers, pins are unique, a FUNCTION has no outputs
    /// and no pin named as itself.
    fn validate(&self) -> Result<(), HostDeclError> {
        let bad = |name: &str| HostDeclError::BadName {
            pou: self.name.clone(),
            name: name.to_string(),
        };
        if !is_identifier(&self.name) {
            return Err(bad(&self.name));
        }
        for (i, p) in self.pins.iter().enumerate() {
            if !is_identifier(&p.name) {
                return Err(bad(&p.name));
            }
            let clash = self.pins[..i]
                .iter()
                .any(|q| q.name.eq_ignore_ascii_case(&p.name))
                || (self.result.is_some() && p.name.eq_ignore_ascii_case(&self.name));
            if clash {
                return Err(HostDeclError::DuplicatePin {
                    pou: self.name.clone(),
                    pin: p.name.clone(),
                });
            }
            if self.result.is_some() && p.dir == PinDir::Output {
                return Err(HostDeclError::FunctionOutput {
                    pou: self.name.clone(),
                    pin: p.name.clone(),
                });
            }
        }
        Ok(())
    }
}

/// An IEC identifier: a letter or `_`, then letters, digits, single `_`.
/// (A keyword passes here and is refused by the compiler, with a
/// diagnostic pointing into [`HOST_SOURCE`].)
fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    let first_ok = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    first_ok && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') && !s.contains("__")
}

/// A host declaration that cannot be registered.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HostDeclError {
    /// A POU or pin name is not an IEC identifier.
    BadName {
        /// The POU.
        pou: String,
        /// The offending name.
        name: String,
    },
    /// Two pins of one POU share a name (or a pin is named as its function).
    DuplicatePin {
        /// The POU.
        pou: String,
        /// The pin.
        pin: String,
    },
    /// A FUNCTION declares a VAR_OUTPUT (it returns its result instead).
    FunctionOutput {
        /// The function.
        pou: String,
        /// The output.
        pin: String,
    },
    /// A POU of this name is already registered.
    DuplicatePou {
        /// The name.
        name: String,
    },
}

impl fmt::Display for HostDeclError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HostDeclError::BadName { pou, name } => {
                write!(f, "host POU `{pou}`: `{name}` is not an IEC identifier")
            }
            HostDeclError::DuplicatePin { pou, pin } => {
                write!(f, "host POU `{pou}`: pin `{pin}` is declared twice")
            }
            HostDeclError::FunctionOutput { pou, pin } => write!(
                f,
                "host FUNCTION `{pou}`: `{pin}` is an output; a function returns its result"
            ),
            HostDeclError::DuplicatePou { name } => {
                write!(f, "host POU `{name}` is registered twice")
            }
        }
    }
}

impl std::error::Error for HostDeclError {}

/// How a registered POU runs.
enum Code {
    /// A FUNCTION: one closure for every call (of every PLC compiled with
    /// these options).
    Function(Mutex<BodyFn>),
    /// A FUNCTION_BLOCK: a closure per instance.
    Block(Factory),
}

struct Entry {
    signature: HostSignature,
    code: Code,
}

/// The host's FUNCTIONs and FUNCTION_BLOCKs, handed to the compiler in
/// [`crate::Options::hosts`]. Cloning shares the registered code.
///
/// ```
/// use plcrun::{ElemType, HostBlocks, HostSignature, Options, Plc};
///
/// let mut hosts = HostBlocks::new();
/// hosts.function(
///     HostSignature::function("Twice", ElemType::Int).input("x", ElemType::Int),
///     |io| {
///         let x = io.get_i64("x")?;
///         io.set_i64("Twice", 2 * x)?;
///         Ok(())
///     },
/// )?;
/// let options = Options { hosts, ..Options::default() };
/// let src = "PROGRAM P VAR y : INT; END_VAR y := Twice(21); END_PROGRAM";
/// let mut plc = Plc::compile_files(&[("p.st", src)], &options)?;
/// plc.run_cycle()?;
/// assert_eq!(plc.read_i64("P.y")?, 42);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Default)]
pub struct HostBlocks {
    entries: Vec<Arc<Entry>>,
}

impl fmt::Debug for HostBlocks {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list()
            .entries(self.entries.iter().map(|e| &e.signature.name))
            .finish()
    }
}

impl HostBlocks {
    /// An empty registry.
    pub fn new() -> HostBlocks {
        HostBlocks::default()
    }

    /// True when nothing is registered.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The registered interfaces, in registration order.
    pub fn signatures(&self) -> impl Iterator<Item = &HostSignature> {
        self.entries.iter().map(|e| &e.signature)
    }

    /// Registers a FUNCTION (made with [`HostSignature::function`]): `body`
    /// reads the inputs and sets the result (the pin named as the function)
    /// through [`HostIo`].
    pub fn function<F>(
        &mut self,
        signature: HostSignature,
        body: F,
    ) -> Result<&mut Self, HostDeclError>
    where
        F: FnMut(&mut HostIo<'_>) -> HostResult + Send + 'static,
    {
        self.register(signature, Code::Function(Mutex::new(Box::new(body))))
    }

    /// Registers a FUNCTION_BLOCK (made with [`HostSignature::block`]):
    /// `new_instance` is called once per instance, on its first call, and
    /// returns the code of that instance (its state is what the closure
    /// captures).
    pub fn block<M, F>(
        &mut self,
        signature: HostSignature,
        new_instance: M,
    ) -> Result<&mut Self, HostDeclError>
    where
        M: Fn() -> F + Send + Sync + 'static,
        F: FnMut(&mut HostIo<'_>) -> HostResult + Send + 'static,
    {
        let factory: Factory = Box::new(move || Box::new(new_instance()) as BodyFn);
        self.register(signature, Code::Block(factory))
    }

    fn register(
        &mut self,
        signature: HostSignature,
        code: Code,
    ) -> Result<&mut Self, HostDeclError> {
        signature.validate()?;
        if self
            .entries
            .iter()
            .any(|e| e.signature.name.eq_ignore_ascii_case(&signature.name))
        {
            return Err(HostDeclError::DuplicatePou {
                name: signature.name,
            });
        }
        self.entries.push(Arc::new(Entry { signature, code }));
        Ok(self)
    }

    /// The declarations the compiler reads, one after the other.
    pub(crate) fn declarations(&self) -> String {
        self.entries
            .iter()
            .map(|e| e.signature.declaration())
            .collect()
    }

    /// The POU names, by `Op::CallHost` index.
    pub(crate) fn names(&self) -> Vec<String> {
        self.entries
            .iter()
            .map(|e| e.signature.name.clone())
            .collect()
    }

    /// The dispatcher of one compiled image: each host body with its pins'
    /// offsets in the frame.
    pub(crate) fn dispatcher(&self, image: &Image) -> HostDispatcher {
        let bodies = image
            .hosts
            .iter()
            .filter_map(|name| {
                let entry = self
                    .entries
                    .iter()
                    .find(|e| e.signature.name.eq_ignore_ascii_case(name))?;
                Some(Body {
                    entry: entry.clone(),
                    pins: pins_at(image, &entry.signature),
                    instances: HashMap::new(),
                })
            })
            .collect();
        HostDispatcher { bodies }
    }
}

/// A pin and its slot offset in the frame.
#[derive(Debug, Clone)]
struct PinAt {
    pin: HostPin,
    offset: u32,
}

/// The pins of `sig` with their offsets in the compiled POU's frame (a
/// function's result is at slot 0, as the layout puts it).
fn pins_at(image: &Image, sig: &HostSignature) -> Vec<PinAt> {
    let members = (0..image.types.len() as u32)
        .map(crate::ir::type_table::TypeId)
        .find_map(|id| {
            let def = image.types.get(id);
            match &def.kind {
                TypeKind::Pou { members, .. } if def.name.eq_ignore_ascii_case(&sig.name) => {
                    Some(members.as_slice())
                }
                _ => None,
            }
        })
        .unwrap_or(&[]);
    sig.pins()
        .into_iter()
        .filter_map(|pin| {
            let offset = match pin.dir {
                PinDir::Result => 0,
                _ => {
                    members
                        .iter()
                        .find(|m| m.name.eq_ignore_ascii_case(&pin.name))?
                        .offset
                }
            };
            Some(PinAt { pin, offset })
        })
        .collect()
}

/// One host body linked into a PLC.
struct Body {
    entry: Arc<Entry>,
    pins: Vec<PinAt>,
    /// A FUNCTION_BLOCK's instances by the absolute address of their frame.
    instances: HashMap<usize, BodyFn>,
}

/// Runs the host bodies of one PLC (the executor's [`HostDispatch`]).
pub(crate) struct HostDispatcher {
    bodies: Vec<Body>,
}

impl HostDispatcher {
    /// Takes over the state of FUNCTION_BLOCK instances from `old` (online
    /// change): each `(block, old base, new base)` moves when the block is
    /// registered with the same code in both.
    pub(crate) fn adopt(&mut self, old: &mut HostDispatcher, moves: &[(String, usize, usize)]) {
        for (name, from, to) in moves {
            let named = |b: &&mut Body| b.entry.signature.name.eq_ignore_ascii_case(name);
            let (Some(src), Some(dst)) = (
                old.bodies.iter_mut().find(named),
                self.bodies.iter_mut().find(named),
            ) else {
                continue;
            };
            if !Arc::ptr_eq(&src.entry, &dst.entry) {
                continue;
            }
            if let Some(state) = src.instances.remove(from) {
                dst.instances.insert(*to, state);
            }
        }
    }
}

impl HostDispatch for HostDispatcher {
    fn call(&mut self, id: HostIdx, frame: HostFrame<'_>) -> Result<(), FaultKind> {
        let Some(body) = self.bodies.get_mut(id.index()) else {
            return Err(FaultKind::host(
                format!("#{}", id.get()),
                "no host code is registered for this body",
            ));
        };
        let name = &body.entry.signature.name;
        let mut io = HostIo {
            pou: name,
            pins: &body.pins,
            frame,
        };
        let (code, instances) = (&body.entry.code, &mut body.instances);
        // A panicking body must not unwind through the executor: it
        // becomes a fault, and the PLC stops with defined memory.
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| match code {
            Code::Function(f) => {
                let mut f = f.lock().unwrap_or_else(|p| p.into_inner());
                f(&mut io)
            }
            Code::Block(make) => instances.entry(io.frame.base).or_insert_with(make)(&mut io),
        }));
        let message = match outcome {
            Ok(Ok(())) => return Ok(()),
            Ok(Err(e)) => e.to_string(),
            Err(panic) => panic_text(panic.as_ref()),
        };
        Err(FaultKind::host(name.as_str(), message))
    }
}

/// The message of a panic payload.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    let text = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".into());
    format!("panicked: {text}")
}

/// A pin access that cannot be done.
#[derive(Debug, Clone, PartialEq)]
pub enum HostIoError {
    /// The POU has no pin of this name.
    UnknownPin {
        /// The POU.
        pou: String,
        /// The name asked for.
        pin: String,
    },
    /// The pin's type does not hold this kind of value.
    WrongType {
        /// The pin.
        pin: String,
        /// Its type.
        ty: ElemType,
        /// What was read or written (`BOOL`, `an integer`, ...).
        asked: &'static str,
    },
    /// The value does not fit the pin's type.
    OutOfRange {
        /// The pin.
        pin: String,
        /// Its type.
        ty: ElemType,
        /// The value.
        value: String,
    },
    /// Only outputs and a function's result can be written.
    NotWritable {
        /// The pin.
        pin: String,
    },
}

impl fmt::Display for HostIoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HostIoError::UnknownPin { pou, pin } => write!(f, "`{pou}` has no pin `{pin}`"),
            HostIoError::WrongType { pin, ty, asked } => {
                write!(f, "pin `{pin}` is {ty}, not {asked}")
            }
            HostIoError::OutOfRange { pin, ty, value } => {
                write!(f, "{value} does not fit pin `{pin}` of type {ty}")
            }
            HostIoError::NotWritable { pin } => {
                write!(
                    f,
                    "pin `{pin}` is an input: only outputs and the result can be written"
                )
            }
        }
    }
}

impl std::error::Error for HostIoError {}

/// The pins of one host call: read the inputs, write the outputs (and a
/// FUNCTION's result, the pin named as the function). Integer accessors
/// cover every integer, bit-string, TIME and date type (as their slot
/// value: nanoseconds for TIME); real accessors REAL and LREAL.
pub struct HostIo<'a> {
    pou: &'a str,
    pins: &'a [PinAt],
    frame: HostFrame<'a>,
}

impl HostIo<'_> {
    /// The clock of the current cycle, in nanoseconds.
    pub fn now(&self) -> i64 {
        self.frame.now
    }

    fn pin(&self, name: &str) -> Result<&PinAt, HostIoError> {
        self.pins
            .iter()
            .find(|p| p.pin.name.eq_ignore_ascii_case(name))
            .ok_or_else(|| HostIoError::UnknownPin {
                pou: self.pou.to_string(),
                pin: name.to_string(),
            })
    }

    fn raw(&self, at: &PinAt) -> u64 {
        self.frame
            .frame
            .get(at.offset as usize)
            .copied()
            .unwrap_or(0)
    }

    /// Any pin's value.
    pub fn get(&self, pin: &str) -> Result<Value, HostIoError> {
        let at = self.pin(pin)?;
        let raw = self.raw(at);
        Ok(if at.pin.ty.is_string() {
            let text = self.frame.strings.get(raw as usize).map(|s| s.text.clone());
            Value::String(text.unwrap_or_default(), at.pin.ty == ElemType::WString)
        } else {
            Value::Scalar(at.pin.ty, raw)
        })
    }

    fn wrong(&self, pin: &str, asked: &'static str) -> HostIoError {
        let ty = self.pin(pin).map(|p| p.pin.ty).unwrap_or(ElemType::Bool);
        HostIoError::WrongType {
            pin: pin.to_string(),
            ty,
            asked,
        }
    }

    /// A BOOL pin.
    pub fn get_bool(&self, pin: &str) -> Result<bool, HostIoError> {
        self.get(pin)?
            .as_bool()
            .ok_or_else(|| self.wrong(pin, "BOOL"))
    }

    /// An integer-like pin (integers, bit strings, TIME in ns, dates).
    pub fn get_i64(&self, pin: &str) -> Result<i64, HostIoError> {
        let at = self.pin(pin)?;
        let ty = at.pin.ty;
        if ty.is_real() || ty.is_string() || ty == ElemType::Bool {
            return Err(self.wrong(pin, "an integer"));
        }
        let raw = self.raw(at);
        if ty.is_unsigned_int() || ty.is_bit() {
            i64::try_from(raw).map_err(|_| HostIoError::OutOfRange {
                pin: pin.to_string(),
                ty,
                value: raw.to_string(),
            })
        } else {
            Ok(raw as i64)
        }
    }

    /// A REAL or LREAL pin.
    pub fn get_f64(&self, pin: &str) -> Result<f64, HostIoError> {
        match self.get(pin)? {
            v @ Value::Scalar(ElemType::Real | ElemType::Lreal, _) => {
                v.as_f64().ok_or_else(|| self.wrong(pin, "a real"))
            }
            _ => Err(self.wrong(pin, "a real")),
        }
    }

    /// A STRING or WSTRING pin.
    pub fn get_str(&self, pin: &str) -> Result<String, HostIoError> {
        match self.get(pin)? {
            Value::String(s, _) => Ok(s),
            _ => Err(self.wrong(pin, "a string")),
        }
    }

    /// The pin to write, if it is an output or the result.
    fn writable(&self, pin: &str) -> Result<PinAt, HostIoError> {
        let at = self.pin(pin)?;
        if at.pin.dir == PinDir::Input {
            return Err(HostIoError::NotWritable {
                pin: pin.to_string(),
            });
        }
        Ok(at.clone())
    }

    fn store(&mut self, at: &PinAt, raw: u64) {
        if let Some(slot) = self.frame.frame.get_mut(at.offset as usize) {
            *slot = raw;
        }
    }

    /// Writes a BOOL output.
    pub fn set_bool(&mut self, pin: &str, v: bool) -> Result<(), HostIoError> {
        let at = self.writable(pin)?;
        if at.pin.ty != ElemType::Bool {
            return Err(self.wrong(pin, "BOOL"));
        }
        self.store(&at, u64::from(v));
        Ok(())
    }

    /// Writes an integer-like output (integers, bit strings, TIME in ns,
    /// dates); a value outside the type's range is refused.
    pub fn set_i64(&mut self, pin: &str, v: i64) -> Result<(), HostIoError> {
        let at = self.writable(pin)?;
        let ty = at.pin.ty;
        if ty.is_real() || ty.is_string() || ty == ElemType::Bool {
            return Err(self.wrong(pin, "an integer"));
        }
        let raw = int_to_slot(i128::from(v), ty).ok_or_else(|| HostIoError::OutOfRange {
            pin: pin.to_string(),
            ty,
            value: v.to_string(),
        })?;
        self.store(&at, raw);
        Ok(())
    }

    /// Writes a REAL or LREAL output (a finite value too large for REAL is
    /// refused).
    pub fn set_f64(&mut self, pin: &str, v: f64) -> Result<(), HostIoError> {
        let at = self.writable(pin)?;
        let ty = at.pin.ty;
        if !ty.is_real() {
            return Err(self.wrong(pin, "a real"));
        }
        let raw = real_to_slot(v, ty).ok_or_else(|| HostIoError::OutOfRange {
            pin: pin.to_string(),
            ty,
            value: v.to_string(),
        })?;
        self.store(&at, raw);
        Ok(())
    }

    /// Writes a STRING or WSTRING output (truncated to 254 characters).
    pub fn set_str(&mut self, pin: &str, v: &str) -> Result<(), HostIoError> {
        let at = self.writable(pin)?;
        if !at.pin.ty.is_string() {
            return Err(self.wrong(pin, "a string"));
        }
        let id = self.raw(&at) as usize;
        if let Some(s) = self.frame.strings.get_mut(id) {
            s.set(v);
        }
        Ok(())
    }

    /// Writes any output from a [`Value`] of its type.
    pub fn set(&mut self, pin: &str, v: &Value) -> Result<(), HostIoError> {
        let at = self.writable(pin)?;
        match v {
            Value::String(s, _) => self.set_str(pin, s),
            Value::Scalar(t, raw) if *t == at.pin.ty && is_canonical(*t, *raw) => {
                self.store(&at, *raw);
                Ok(())
            }
            _ => Err(HostIoError::WrongType {
                pin: pin.to_string(),
                ty: at.pin.ty,
                asked: "this value",
            }),
        }
    }
}
