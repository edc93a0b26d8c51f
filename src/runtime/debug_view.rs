//! What a debugger sees of a stopped PLC: the stack as instance paths
//! with their source lines, the variables of each frame by scope, and the
//! writes and forces it may make.

use super::access::{parse_for, store_in, value_in};
use super::debugger::{DebugControl, ForceRequest};
use super::engine::Plc;
use super::fault_path::{self, Frame};
use super::names;
use super::plc_value::Value;
use super::var_error::{ReadOnlyReason, VarError};
use crate::elementary::ElemType;
use crate::ir::image::{CodeKind, Image};
use crate::ir::op::CodeIdx;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind};
use crate::source::SourceMap;
use crate::vm::{DebugFrame, Machine};

/// One frame of the stack of a stopped PLC.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StackFrame {
    /// The instance path (`Main.line.motor`; `P.Action` for an SFC action
    /// or transition; the FUNCTION's name for a function).
    pub name: String,
    /// The POU (`FB`, `FB.Method`, `P.Action`).
    pub pou: String,
    /// The source file, as loaded.
    pub file: Option<String>,
    /// The 1-based line (0 when unknown).
    pub line: u32,
    /// The 1-based column (0 when unknown).
    pub column: u32,
}

/// A group of variables to list: a scope of a frame, or the members of a
/// structured variable (opaque; get one from [`StoppedPlc::scopes`] or a
/// [`DebugVariable::children`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Container(Group);

#[derive(Debug, Clone, PartialEq)]
enum Group {
    /// Members of a POU instance or structure at `addr`, filtered.
    Members {
        addr: u32,
        ty: TypeId,
        path: String,
        which: Which,
    },
    /// The elements of an array.
    Array { addr: u32, ty: TypeId, path: String },
    /// The pins of a native block instance.
    Native {
        addr: u32,
        fb: crate::ir::op::NativeFb,
        path: String,
    },
    /// An SFC step's `.X` and `.T`.
    Step { addr: u32, path: String },
    /// The global variables (`located`: those with a `%` address, else
    /// the others).
    Globals { located: bool },
}

/// Which members of an instance a scope shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Which {
    Locals,
    Interface,
    All,
}

/// A scope of a frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Scope {
    /// `Locals`, `Inputs/Outputs`, `Globals`, `Process image`.
    pub name: &'static str,
    /// Its variables.
    pub container: Container,
}

/// One variable as a debugger lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct DebugVariable {
    /// Its name in the group (`motor`, `[3]`, `X`).
    pub name: String,
    /// Its value as an IEC literal, or its type's name when structured.
    pub value: String,
    /// Its type's name.
    pub type_name: String,
    /// Its full path, to read, write or force it by name.
    pub path: String,
    /// Its members, when structured.
    pub children: Option<Container>,
}

/// A PLC stopped under a debugger (see [`super::debugger`]).
pub struct StoppedPlc<'a> {
    image: &'a Image,
    sources: &'a SourceMap,
    machine: &'a mut Machine,
    control: &'a DebugControl,
    /// Innermost first.
    raw: Vec<Frame>,
    frames: Vec<StackFrame>,
    /// The path each frame's variables are named under (its instance).
    instances: Vec<String>,
    /// The number of the running cycle, or of the next one at a boundary.
    cycle: Option<u64>,
    depth: usize,
}

/// The stop of a PLC at a cycle boundary: the program instances as frames.
pub(super) fn at_boundary<'a>(plc: &'a mut Plc, control: &'a DebugControl) -> StoppedPlc<'a> {
    let image = plc.image.image();
    let raw: Vec<Frame> = image
        .programs
        .iter()
        .map(|p| Frame {
            code: p.code,
            pc: first_statement(control, p.code),
            base: p.base as usize,
        })
        .collect();
    let cycle = plc.cycle;
    StoppedPlc::new(
        image,
        &plc.sources,
        &mut plc.machine,
        control,
        raw,
        Some(cycle),
        0,
    )
}

/// The stop of a PLC on a fault: the frames the fault unwound through.
pub(super) fn at_fault<'a>(
    plc: &'a mut Plc,
    control: &'a DebugControl,
    raw: Vec<Frame>,
) -> StoppedPlc<'a> {
    let depth = raw.len();
    let cycle = plc.cycle;
    StoppedPlc::new(
        plc.image.image(),
        &plc.sources,
        &mut plc.machine,
        control,
        raw,
        Some(cycle),
        depth,
    )
}

/// The first statement start of block `code` (0 when it has none).
fn first_statement(control: &DebugControl, code: CodeIdx) -> u32 {
    control
        .lines()
        .starts()
        .get(code.index())
        .and_then(|s| s.iter().position(|&b| b))
        .unwrap_or(0) as u32
}

impl<'a> StoppedPlc<'a> {
    /// The stop inside a cycle, at the top frame of `stack` (outermost first).
    pub(super) fn in_cycle(
        image: &'a Image,
        sources: &'a SourceMap,
        machine: &'a mut Machine,
        stack: &[DebugFrame],
        control: &'a DebugControl,
    ) -> StoppedPlc<'a> {
        let raw: Vec<Frame> = stack
            .iter()
            .rev()
            .map(|f| Frame {
                code: f.code,
                pc: f.pc,
                base: f.base,
            })
            .collect();
        StoppedPlc::new(image, sources, machine, control, raw, None, stack.len())
    }

    fn new(
        image: &'a Image,
        sources: &'a SourceMap,
        machine: &'a mut Machine,
        control: &'a DebugControl,
        raw: Vec<Frame>,
        cycle: Option<u64>,
        depth: usize,
    ) -> StoppedPlc<'a> {
        let names = fault_path::frame_names(image, &raw);
        let mut frames = Vec::with_capacity(raw.len());
        let mut instances = Vec::with_capacity(raw.len());
        for (f, name) in raw.iter().zip(names) {
            let block = &image.codes[f.code.index()];
            let span = fault_path::span_of(image, f.code, f.pc);
            let (file, line, column) =
                if span.end > 0 && (span.file.0 as usize) < sources.files().len() {
                    let file = sources.file(span.file);
                    let (l, c) = file.line_col(span.start);
                    (Some(file.name.clone()), l as u32, c as u32)
                } else {
                    (None, 0, 0)
                };
            // An action's or a method's variables are its instance's.
            let instance = if block.kind == CodeKind::Function || !block.name.contains('.') {
                name.clone()
            } else {
                name.rsplit_once('.')
                    .map_or(name.clone(), |(i, _)| i.to_string())
            };
            instances.push(instance);
            frames.push(StackFrame {
                name,
                pou: block.name.clone(),
                file,
                line,
                column,
            });
        }
        StoppedPlc {
            image,
            sources,
            machine,
            control,
            raw,
            frames,
            instances,
            cycle,
            depth,
        }
    }

    /// Shows an SFC element (`name` at `file:line`) as a frame above the
    /// top one, whose instance and variables it shares.
    pub(super) fn push_sfc_frame(&mut self, name: &str, file: Option<String>, line: u32) {
        let (Some(raw), Some(top), Some(instance)) = (
            self.raw.first().copied(),
            self.frames.first().cloned(),
            self.instances.first().cloned(),
        ) else {
            return;
        };
        self.raw.insert(0, raw);
        self.instances.insert(0, instance.clone());
        self.frames.insert(
            0,
            StackFrame {
                name: format!("{instance}.{name}"),
                pou: format!("{}.{name}", top.pou),
                file,
                line,
                column: 1,
            },
        );
    }

    /// The stack, innermost first. At a cycle boundary, the program
    /// instances at their first statement.
    pub fn frames(&self) -> &[StackFrame] {
        &self.frames
    }

    /// The cycle about to run, at a boundary or a fault (`None` inside a
    /// cycle).
    pub fn cycle(&self) -> Option<u64> {
        self.cycle
    }

    /// The clock value of the running (or last) cycle, in nanoseconds.
    pub fn time(&self) -> i64 {
        self.machine.now
    }

    /// The source files' names, as loaded.
    pub fn sources(&self) -> &SourceMap {
        self.sources
    }

    /// How many blocks run (0 at a cycle boundary).
    pub(super) fn depth(&self) -> usize {
        self.depth
    }

    /// The top frame's code, base and instruction.
    pub(super) fn top(&self) -> Option<(CodeIdx, usize, u32)> {
        self.raw.first().map(|f| (f.code, f.base, f.pc))
    }

    /// The instance type of frame `k`: the POU whose body its block is (or
    /// owns the action, method or transition).
    fn frame_type(&self, k: usize) -> Option<TypeId> {
        let f = self.raw.get(k)?;
        let block = &self.image.codes[f.code.index()];
        let owner = block
            .name
            .split_once('.')
            .map_or(block.name.as_str(), |(o, _)| o);
        let types = &self.image.types;
        let mut by_name = None;
        for id in 0..types.len() {
            let ty = TypeId(id as u32);
            if let TypeKind::Pou { code, .. } = &types.get(ty).kind {
                if *code == f.code {
                    return Some(ty);
                }
                if by_name.is_none() && types.name(ty).eq_ignore_ascii_case(owner) {
                    by_name = Some(ty);
                }
            }
        }
        by_name
    }

    /// The scopes of frame `k`: its instance's locals and interface, the
    /// globals, the process image (located variables).
    pub fn scopes(&self, k: usize) -> Vec<Scope> {
        let mut scopes = Vec::new();
        if let (Some(ty), Some(f)) = (self.frame_type(k), self.raw.get(k)) {
            let path = self.instances[k].clone();
            let addr = f.base as u32;
            scopes.push(Scope {
                name: "Locals",
                container: Container(Group::Members {
                    addr,
                    ty,
                    path: path.clone(),
                    which: Which::Locals,
                }),
            });
            scopes.push(Scope {
                name: "Inputs/Outputs",
                container: Container(Group::Members {
                    addr,
                    ty,
                    path,
                    which: Which::Interface,
                }),
            });
        }
        scopes.push(Scope {
            name: "Globals",
            container: Container(Group::Globals { located: false }),
        });
        scopes.push(Scope {
            name: "Process image",
            container: Container(Group::Globals { located: true }),
        });
        scopes
    }

    /// The variables of a group.
    pub fn variables(&self, c: &Container) -> Vec<DebugVariable> {
        let types = &self.image.types;
        match &c.0 {
            Group::Members {
                addr,
                ty,
                path,
                which,
            } => types
                .members(*ty)
                .iter()
                .filter(|m| match (which, m.kind) {
                    (_, MemberKind::Hidden | MemberKind::Action | MemberKind::External) => false,
                    (Which::All, _) => true,
                    (Which::Interface, k) => {
                        matches!(
                            k,
                            MemberKind::Input | MemberKind::Output | MemberKind::InOut
                        )
                    }
                    (Which::Locals, k) => !matches!(
                        k,
                        MemberKind::Input | MemberKind::Output | MemberKind::InOut
                    ),
                })
                .map(|m| {
                    let shown = names::shown_member(self.image, &m.name).to_string();
                    let mut at = addr.wrapping_add(m.offset);
                    if m.kind == MemberKind::InOut {
                        at = self.machine.mem.get(at as usize).copied().unwrap_or(0) as u32;
                    }
                    self.variable(shown.clone(), join(path, &shown), at, m.ty)
                })
                .collect(),
            Group::Array { addr, ty, path } => {
                let TypeKind::Array { dims, elem } = &types.get(*ty).kind else {
                    return Vec::new();
                };
                let size = types.size(*elem);
                let total: u64 = dims.iter().map(|d| d.len()).product();
                (0..total.min(1000))
                    .map(|k| {
                        let mut rest = k;
                        let mut idx = vec![0i64; dims.len()];
                        for (j, d) in dims.iter().enumerate().rev() {
                            idx[j] = d.lo + (rest % d.len().max(1)) as i64;
                            rest /= d.len().max(1);
                        }
                        let text: Vec<String> = idx.iter().map(i64::to_string).collect();
                        let name = format!("[{}]", text.join(","));
                        let at = addr.wrapping_add((k as u32).wrapping_mul(size));
                        self.variable(name.clone(), format!("{path}{name}"), at, *elem)
                    })
                    .collect()
            }
            Group::Native { addr, fb, path } => crate::stdlib::interface(*fb)
                .iter()
                .enumerate()
                .filter(|(_, p)| p.dir != crate::stdlib::ParamDir::Hidden)
                .map(|(k, p)| {
                    let raw = self
                        .machine
                        .mem
                        .get(*addr as usize + k)
                        .copied()
                        .unwrap_or(0);
                    DebugVariable {
                        name: p.name.to_string(),
                        value: Value::Scalar(p.ty, raw).to_literal(),
                        type_name: p.ty.name().to_string(),
                        path: join(path, p.name),
                        children: None,
                    }
                })
                .collect(),
            Group::Step { addr, path } => {
                let mem = &self.machine.mem;
                let x = mem.get(*addr as usize).copied().unwrap_or(0);
                let t = mem.get(*addr as usize + 1).copied().unwrap_or(0);
                vec![
                    DebugVariable {
                        name: "X".into(),
                        value: Value::Scalar(ElemType::Bool, x).to_literal(),
                        type_name: "BOOL".into(),
                        path: join(path, "X"),
                        children: None,
                    },
                    DebugVariable {
                        name: "T".into(),
                        value: Value::Scalar(ElemType::Time, t).to_literal(),
                        type_name: "TIME".into(),
                        path: join(path, "T"),
                        children: None,
                    },
                ]
            }
            Group::Globals { located } => self
                .image
                .globals
                .iter()
                .filter(|g| g.location.is_some() == *located)
                .map(|g| {
                    let name = match &g.location {
                        Some(at) if !g.name.starts_with('%') => format!("{} ({at})", g.name),
                        _ => g.name.clone(),
                    };
                    let path = if g.name.is_empty() {
                        g.location.clone().unwrap_or_default()
                    } else {
                        g.name.clone()
                    };
                    self.variable(name, path, g.addr, g.ty)
                })
                .collect(),
        }
    }

    /// The variable of type `ty` at `addr`, named `name` in its group.
    fn variable(&self, name: String, path: String, addr: u32, ty: TypeId) -> DebugVariable {
        let types = &self.image.types;
        let type_name = types.name(ty).to_string();
        let children = match &types.get(ty).kind {
            TypeKind::Pou { .. } | TypeKind::Struct { .. } => Some(Group::Members {
                addr,
                ty,
                path: path.clone(),
                which: Which::All,
            }),
            TypeKind::Array { .. } => Some(Group::Array {
                addr,
                ty,
                path: path.clone(),
            }),
            TypeKind::NativeFb(fb) => Some(Group::Native {
                addr,
                fb: *fb,
                path: path.clone(),
            }),
            TypeKind::Step => Some(Group::Step {
                addr,
                path: path.clone(),
            }),
            _ => None,
        };
        let value = match &children {
            Some(_) => type_name.clone(),
            None => match &types.get(ty).kind {
                TypeKind::Ref { .. } => {
                    let raw = self.machine.mem.get(addr as usize).copied().unwrap_or(0);
                    format!("16#{raw:X}")
                }
                _ => value_in(self.image, self.machine, addr, ty).to_literal(),
            },
        };
        DebugVariable {
            name,
            value,
            type_name,
            path,
            children: children.map(Container),
        }
    }

    /// Resolves `path` as seen from frame `k`: a variable of its instance
    /// first, else a name from outside (globals, `prog.x`, `%IX0.1`).
    fn resolve(
        &self,
        k: usize,
        path: &str,
    ) -> Result<(u32, TypeId, Option<ReadOnlyReason>), VarError> {
        if let Some(instance) = self.instances.get(k)
            && self.image.codes[self.raw[k].code.index()].kind != CodeKind::Function
            && let Ok(r) = names::resolve(self.image, &format!("{instance}.{}", path.trim()), 0)
        {
            return Ok((r.addr, r.ty, r.read_only));
        }
        if let (Some(f), Some(ty)) = (self.raw.get(k), self.frame_type(k))
            && let Some(m) = self
                .image
                .types
                .members(ty)
                .iter()
                .find(|m| m.name.eq_ignore_ascii_case(path.trim()))
        {
            return Ok(((f.base as u32).wrapping_add(m.offset), m.ty, None));
        }
        let r = names::resolve(self.image, path, 0)?;
        Ok((r.addr, r.ty, r.read_only))
    }

    /// The full path under which `path`, as seen from frame `k`, can be
    /// named from outside (for forces).
    fn outside_path(&self, k: usize, path: &str) -> String {
        if let Some(instance) = self.instances.get(k)
            && self.image.codes[self.raw[k].code.index()].kind != CodeKind::Function
        {
            let full = format!("{instance}.{}", path.trim());
            if names::resolve(self.image, &full, 0).is_ok() {
                return full;
            }
        }
        path.trim().to_string()
    }

    /// Reads the single value `path` names from frame `k`.
    pub fn read(&self, k: usize, path: &str) -> Result<Value, VarError> {
        let (addr, ty, _) = self.resolve(k, path)?;
        self.single(path, ty)?;
        Ok(value_in(self.image, self.machine, addr, ty))
    }

    /// Refuses a structured variable where a single value is needed.
    fn single(&self, path: &str, ty: TypeId) -> Result<(), VarError> {
        match &self.image.types.get(ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => Ok(()),
            _ => Err(VarError::NotAValue {
                path: path.to_string(),
                ty: self.image.types.name(ty).to_string(),
            }),
        }
    }

    /// Stores IEC literal `literal` into the resolved variable `path`
    /// (its address, type and why it is read-only, if it is), once it is
    /// known to hold a single writable value. Returns the value stored.
    fn store_literal(
        &mut self,
        path: &str,
        (addr, ty, read_only): (u32, TypeId, Option<ReadOnlyReason>),
        literal: &str,
    ) -> Result<Value, VarError> {
        self.single(path, ty)?;
        if let Some(why) = read_only {
            return Err(VarError::ReadOnly {
                path: path.to_string(),
                why,
            });
        }
        let v = parse_for(self.image, ty, literal)?;
        store_in(self.machine, addr, &v);
        Ok(v)
    }

    /// Writes IEC literal `literal` into `path` as seen from frame `k` (a
    /// soft write: a forced variable keeps its forced value from the next
    /// force application on). Returns the value written.
    pub fn write(&mut self, k: usize, path: &str, literal: &str) -> Result<Value, VarError> {
        let (addr, ty, read_only) = self.resolve(k, path)?;
        let v = self.store_literal(path, (addr, ty, read_only), literal)?;
        Ok(v)
    }

    /// Sets variable `name` of group `c` from IEC literal `literal`; returns
    /// the variable as it now is.
    pub fn set_variable(
        &mut self,
        c: &Container,
        name: &str,
        literal: &str,
    ) -> Result<DebugVariable, VarError> {
        let found = self
            .variables(c)
            .into_iter()
            .find(|v| v.name == name)
            .ok_or_else(|| VarError::Unknown {
                name: name.to_string(),
            })?;
        let r = names::resolve(self.image, &found.path, 0)?;
        let v = self.store_literal(&found.path, (r.addr, r.ty, r.read_only), literal)?;
        Ok(DebugVariable {
            value: v.to_literal(),
            ..found
        })
    }

    /// Forces `path` (as seen from frame `k`) to `literal`: written at once,
    /// held from the next cycle boundary on until unforced.
    pub fn force(&mut self, k: usize, path: &str, literal: &str) -> Result<Value, VarError> {
        let (addr, ty, read_only) = self.resolve(k, path)?;
        let v = self.store_literal(path, (addr, ty, read_only), literal)?;
        let full = self.outside_path(k, path);
        self.control
            .forces
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(ForceRequest::Force(full, literal.trim().to_string()));
        Ok(v)
    }

    /// Releases the force of `path` (as seen from frame `k`) at the next
    /// cycle boundary.
    pub fn unforce(&mut self, k: usize, path: &str) -> Result<(), VarError> {
        self.resolve(k, path)?;
        let full = self.outside_path(k, path);
        self.control
            .forces
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(ForceRequest::Unforce(full));
        Ok(())
    }

    /// Evaluates ST expression `expr` in frame `k` (variables named as
    /// the frame's instance sees them).
    pub fn evaluate(&self, k: usize, expr: &str) -> Result<Value, String> {
        super::debug_eval::evaluate(expr, &|path| self.read(k, path).map_err(|e| e.to_string()))
    }
}

/// `path.member` (or `member` alone at the root).
fn join(path: &str, member: &str) -> String {
    if path.is_empty() {
        member.to_string()
    } else {
        format!("{path}.{member}")
    }
}
