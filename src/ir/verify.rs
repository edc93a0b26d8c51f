//! Link-time verification of an image, and the only way to a runnable one.
//!
//! The executor reads and writes frame slots without bounds checks; this
//! pass is what makes that sound. It reads every operand of every
//! instruction through [`operands`], generated from the one instruction
//! list, and checks each by its role (the match below has no wildcard: a
//! new role does not compile until it is checked here): every frame operand
//! lies inside the block's frame, every jump inside the block and never
//! onto an operand word, every table index inside its table, every callee
//! of the right kind and, when called on a frame slot, inside the frame.
//! Every block ends with `Ret`; every two-word and fused instruction has
//! its partner; every frame a block can run on, every chart's state and
//! every address a task or a program connection names lies inside memory.
//!
//! Only [`verify`] makes a [`VerifiedImage`], and only a `VerifiedImage`
//! can be run (`vm::Machine` takes nothing else).

use super::chart::{ActionKind, Chart, Condition, Duration, action_layout as al, header as hd};
use super::image::{CodeBlock, CodeKind, Image};
use super::op::{CodeIdx, Op};
use super::operands::{ArrayUse, Callee, Operand, Shape, operands, shape};
use super::type_table::step_layout as sl;
use std::fmt;

/// An image the verifier accepted: the executor may run it without
/// per-operand bounds checks. Built only by [`verify`]; read-only after.
///
/// Nothing outside the crate can name or build one, nor run anything else:
///
/// ```compile_fail,E0603
/// use plcrun::ir::verify::VerifiedImage; // the IR is internal
/// ```
///
/// ```compile_fail,E0603
/// use plcrun::vm::Machine; // so is the executor
/// ```
///
/// The image a [`crate::Plc`] runs can be read, not changed:
///
/// ```compile_fail,E0596
/// let plc = plcrun::Plc::compile_files(
///     &[("p.st", "PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM")],
///     &plcrun::Options::default(),
/// )
/// .unwrap();
/// plc.image().codes.clear();
/// ```
#[derive(Debug, Clone)]
pub struct VerifiedImage {
    image: Image,
}

impl VerifiedImage {
    /// The image (read-only).
    pub fn image(&self) -> &Image {
        &self.image
    }
}

impl std::ops::Deref for VerifiedImage {
    type Target = Image;

    fn deref(&self) -> &Image {
        &self.image
    }
}

/// Why an image was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Problem {
    /// A block does not end with `Ret`.
    NoRet,
    /// A block's span table and instruction count differ.
    SpanTable,
    /// A function's static frame is not inside memory.
    FunctionFrameOutsideMemory,
    /// A slot reset at block entry is outside the frame.
    EntryResetOutsideFrame,
    /// A string reset at block entry names a slot or a string out of range.
    EntryStringOutOfRange,
    /// A frame slot operand is outside the frame.
    SlotOutsideFrame,
    /// A run of consecutive slots reaches past the frame.
    RunOutsideFrame,
    /// A callee instance at a frame slot reaches past the frame.
    InstanceOutsideFrame,
    /// A jump target is outside the block or on an operand word.
    BadTarget,
    /// A two-word instruction is not followed by its `Operand` word.
    MissingOperandWord,
    /// A loop superinstruction is no longer next to its partner.
    MissingPartner,
    /// A constant index is out of range.
    ConstOutOfRange,
    /// A constant-string index is out of range.
    StrConstOutOfRange,
    /// An array-descriptor index is out of range.
    ArrayOutOfRange,
    /// An array descriptor's extent is not inside the frame as its use needs.
    ArrayOutsideFrame,
    /// A scalar-type index is out of range.
    ScalarTypeOutOfRange,
    /// A code-block index is out of range.
    CodeOutOfRange,
    /// A called block is not of the kind the call needs.
    WrongCalleeKind,
    /// A chart index is out of range.
    ChartOutOfRange,
    /// A chart table refers to a step, transition or action it does not have.
    ChartIndex,
    /// A chart's state is not inside the frame of the block running it.
    ChartOutsideFrame,
    /// A host-body index is out of range.
    HostOutOfRange,
    /// An absolute address is outside memory.
    AbsOutsideMemory,
    /// A program instance's code block is missing or not a PROGRAM body.
    ProgramCode,
    /// A program instance is not inside memory.
    ProgramOutsideMemory,
    /// A program instance's task does not exist.
    ProgramTask,
    /// A connection of a program instance is outside memory.
    ConnectionOutsideMemory,
    /// A SINGLE task's trigger is outside memory.
    TriggerOutsideMemory,
    /// A start or exit call names a missing block, or its frame or flag
    /// is outside memory.
    InstanceCall,
    /// A retained variable's slot is outside memory, or its string is not
    /// the one its slot holds.
    RetainedOutsideMemory,
    /// A `__TRY` region is outside the block, resumes at instruction 0 or
    /// onto an operand word, or its `__CATCH` variable is outside the frame.
    BadHandler,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Problem::NoRet => "block does not end with Ret",
            Problem::SpanTable => "span table length differs from the instruction count",
            Problem::FunctionFrameOutsideMemory => "function frame outside memory",
            Problem::EntryResetOutsideFrame => "entry reset outside the frame",
            Problem::EntryStringOutOfRange => "entry string reset out of range",
            Problem::SlotOutsideFrame => "frame operand outside the frame",
            Problem::RunOutsideFrame => "run of slots past the frame",
            Problem::InstanceOutsideFrame => "callee instance past the frame",
            Problem::BadTarget => "jump target outside the block or onto an operand word",
            Problem::MissingOperandWord => "two-word instruction without its operand word",
            Problem::MissingPartner => "loop superinstruction without its partner instruction",
            Problem::ConstOutOfRange => "constant index out of range",
            Problem::StrConstOutOfRange => "string constant index out of range",
            Problem::ArrayOutOfRange => "array descriptor index out of range",
            Problem::ArrayOutsideFrame => "array outside the frame",
            Problem::ScalarTypeOutOfRange => "scalar type index out of range",
            Problem::CodeOutOfRange => "code block index out of range",
            Problem::WrongCalleeKind => "callee of the wrong kind",
            Problem::ChartOutOfRange => "chart index out of range",
            Problem::ChartIndex => "chart table index out of range",
            Problem::ChartOutsideFrame => "chart state outside the frame",
            Problem::HostOutOfRange => "host body index out of range",
            Problem::AbsOutsideMemory => "absolute address outside memory",
            Problem::ProgramCode => "program instance without a PROGRAM body",
            Problem::ProgramOutsideMemory => "program instance outside memory",
            Problem::ProgramTask => "program instance on a missing task",
            Problem::ConnectionOutsideMemory => "program connection outside memory",
            Problem::TriggerOutsideMemory => "task trigger outside memory",
            Problem::InstanceCall => "instance call outside the code or memory",
            Problem::RetainedOutsideMemory => "retained variable outside memory or strings",
            Problem::BadHandler => "exception handler outside the block or its frame",
        })
    }
}

/// A refused image: what and where (it indicates a compiler bug, never a
/// user error).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VerifyError {
    /// Where: the block and instruction, the program instance or the task.
    pub place: String,
    /// What.
    pub problem: Problem,
}

impl fmt::Display for VerifyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.place, self.problem)
    }
}

impl std::error::Error for VerifyError {}

/// Checks the invariants the executor relies on and seals the image; the
/// error names the first violation.
pub fn verify(mut image: Image) -> Result<VerifiedImage, VerifyError> {
    for (ci, c) in image.codes.iter().enumerate() {
        check_block(&image, c).map_err(|(pc, problem)| VerifyError {
            place: format!("code {ci} `{}` op {pc}", c.name),
            problem,
        })?;
    }
    check_programs(&image)?;
    check_retained(&image)?;
    image.names = crate::ir::name_index::NameIndex::build(&image.types, &image.globals);
    Ok(VerifiedImage { image })
}

/// A problem at an instruction index.
type Located = (usize, Problem);

/// `Ok` when `ok`, else `problem`.
fn ensure(ok: bool, problem: Problem) -> Result<(), Problem> {
    if ok { Ok(()) } else { Err(problem) }
}

/// Whether `n` slots from `start` lie in a frame of `size` slots (an empty
/// run still needs its start inside, as every slot operand does).
fn fits(start: u32, n: u64, size: u64) -> bool {
    start as u64 + n.max(1) <= size
}

fn check_block(image: &Image, c: &CodeBlock) -> Result<(), Located> {
    let at0 = |problem| (0, problem);
    let size = c.frame_size as u64;
    if !matches!(c.ops.last(), Some(Op::Ret)) {
        return Err((c.ops.len(), Problem::NoRet));
    }
    ensure(c.spans.len() == c.ops.len(), Problem::SpanTable).map_err(at0)?;
    if c.kind == CodeKind::Function {
        let inside = c.frame as u64 + size <= image.memory.len() as u64;
        ensure(inside, Problem::FunctionFrameOutsideMemory).map_err(at0)?;
    }
    for &(slot, _) in &c.entry_init {
        ensure(fits(slot.get(), 1, size), Problem::EntryResetOutsideFrame).map_err(at0)?;
    }
    for &(slot, k) in &c.entry_strings {
        let ok = fits(slot.get(), 1, size) && k.index() < image.str_consts.len();
        ensure(ok, Problem::EntryStringOutOfRange).map_err(at0)?;
    }
    for pc in 0..c.ops.len() {
        check_op(image, c, pc).map_err(|p| (pc, p))?;
    }
    for h in &c.handlers {
        let resumes = c
            .ops
            .get(h.catch as usize)
            .is_some_and(|o| !matches!(shape(o), Shape::OperandWord));
        let ok = h.start < h.end
            && h.end as usize <= c.ops.len()
            && h.catch > 0
            && resumes
            && fits(h.exception.get(), 1, size);
        ensure(ok, Problem::BadHandler).map_err(|p| (h.catch as usize, p))?;
    }
    Ok(())
}

/// Checks every operand of `c.ops[pc]` by its role, then its shape.
fn check_op(image: &Image, c: &CodeBlock, pc: usize) -> Result<(), Problem> {
    let mut op = c.ops[pc];
    let mut result = Ok(());
    operands(&mut op, &mut |o| {
        if result.is_ok() {
            result = check_operand(image, c, o);
        }
    });
    result?;
    match shape(&c.ops[pc]) {
        Shape::Single | Shape::OperandWord => Ok(()),
        Shape::TakesOperandWord => ensure(
            matches!(c.ops.get(pc + 1), Some(Op::Operand { .. })),
            Problem::MissingOperandWord,
        ),
        Shape::Fused(partner) => ensure(partner(&c.ops, pc), Problem::MissingPartner),
    }
}

/// One operand of an instruction of block `c`.
fn check_operand(image: &Image, c: &CodeBlock, o: Operand<'_>) -> Result<(), Problem> {
    let size = c.frame_size as u64;
    let mem = image.memory.len() as u64;
    let target = |t: usize| {
        let ok = c
            .ops
            .get(t)
            .is_some_and(|o| !matches!(shape(o), Shape::OperandWord));
        ensure(ok, Problem::BadTarget)
    };
    let code = |i: CodeIdx, kind: CodeKind| {
        let callee = image.codes.get(i.index()).ok_or(Problem::CodeOutOfRange)?;
        ensure(callee.kind == kind, Problem::WrongCalleeKind)?;
        Ok(callee)
    };
    match o {
        Operand::Slot(s, _) => ensure(fits(s.get(), 1, size), Problem::SlotOutsideFrame),
        Operand::Run(s, n) => ensure(fits(s.get(), n as u64, size), Problem::RunOutsideFrame),
        Operand::Instance(s, Callee::Fb(i)) => {
            let callee = code(i, CodeKind::FunctionBlock)?;
            let n = callee.frame_size as u64;
            ensure(fits(s.get(), n, size), Problem::InstanceOutsideFrame)
        }
        Operand::Instance(s, Callee::Native(fb)) => {
            let n = fb.instance_slots() as u64;
            ensure(fits(s.get(), n, size), Problem::InstanceOutsideFrame)
        }
        Operand::Target(t) => target(t.index()),
        Operand::ShortTarget(t) => target(t.index()),
        Operand::Const(k) => ensure(k.index() < image.consts.len(), Problem::ConstOutOfRange),
        Operand::StrConst(k) => ensure(
            k.index() < image.str_consts.len(),
            Problem::StrConstOutOfRange,
        ),
        Operand::Array(desc, used) => {
            let d = image
                .arrays
                .get(desc.index())
                .ok_or(Problem::ArrayOutOfRange)?;
            let extent = d.offset as u64 + d.len.saturating_mul(d.stride as u64);
            let ok = match used {
                ArrayUse::Any => true,
                ArrayUse::Span => extent <= size,
                ArrayUse::Elems => d.stride >= 1 && extent <= size,
                ArrayUse::Dense => d.stride == 1 && extent <= size,
            };
            ensure(ok, Problem::ArrayOutsideFrame)
        }
        Operand::ScalarType(ty) => ensure(
            ty.index() < image.scalar_types.len(),
            Problem::ScalarTypeOutOfRange,
        ),
        Operand::Code(i, kind) => code(i, kind).map(|_| ()),
        Operand::Chart(i) => {
            let chart = image
                .charts
                .get(i.index())
                .ok_or(Problem::ChartOutOfRange)?;
            check_chart(image, chart, size)
        }
        Operand::Host(i) => ensure(i.index() < image.hosts.len(), Problem::HostOutOfRange),
        Operand::Abs(a) => ensure((a as u64) < mem, Problem::AbsOutsideMemory),
    }
}

/// A chart run by `Op::Sfc` on a frame of `size` slots: every index in its
/// tables names an entry it has, its state lies in the frame, and its
/// condition and action blocks run on that frame.
fn check_chart(image: &Image, c: &Chart, size: u64) -> Result<(), Problem> {
    let mem = image.memory.len() as u64;
    let (steps, transitions, actions) = (c.steps.len(), c.transitions.len(), c.actions.len());
    let index = |i: u32, n: usize| ensure((i as usize) < n, Problem::ChartIndex);
    let state = |at: u32, n: u64| ensure(fits(at, n, size), Problem::ChartOutsideFrame);
    let block = |i: CodeIdx| {
        let b = image.codes.get(i.index()).ok_or(Problem::CodeOutOfRange)?;
        ensure(b.kind == CodeKind::Block, Problem::WrongCalleeKind)?;
        ensure(b.frame_size as u64 <= size, Problem::ChartOutsideFrame)
    };
    state(c.header, hd::SIZE as u64)?;
    state(c.active, steps as u64)?;
    state(c.live, actions as u64)?;
    // The transition cache, then the list of transitions fired in a call.
    state(c.cache, 2 * transitions as u64)?;
    for &s in &c.initial {
        index(s, steps)?;
    }
    for s in &c.steps {
        state(s.rec, sl::SIZE as u64)?;
        state(s.scratch, 1)?;
        for &t in &s.out {
            index(t, transitions)?;
        }
        for a in &s.assocs {
            index(a.action, actions)?;
            match a.duration {
                Duration::None | Duration::Const(_) => {}
                Duration::Frame(o) => state(o, 1)?,
                Duration::Abs(at) => ensure((at as u64) < mem, Problem::AbsOutsideMemory)?,
            }
        }
    }
    for t in &c.transitions {
        for &s in t.from.iter().chain(&t.to) {
            index(s, steps)?;
        }
        match t.cond {
            Condition::Const(_) => {}
            Condition::Frame(o) => state(o, 1)?,
            Condition::Code(i) => block(i)?,
        }
    }
    for a in &c.actions {
        state(a.rec, al::SIZE as u64)?;
        match a.kind {
            ActionKind::Body(i) => block(i)?,
            ActionKind::Frame(o) => state(o, 1)?,
            ActionKind::Abs(at) => ensure((at as u64) < mem, Problem::AbsOutsideMemory)?,
        }
    }
    Ok(())
}

/// Program instances and tasks: what the scheduler touches outside code.
fn check_programs(image: &Image) -> Result<(), VerifyError> {
    let mem = image.memory.len() as u64;
    for p in &image.programs {
        let fail = |problem| VerifyError {
            place: format!("program `{}`", p.name),
            problem,
        };
        let c = image
            .codes
            .get(p.code.index())
            .filter(|c| c.kind == CodeKind::Program)
            .ok_or(fail(Problem::ProgramCode))?;
        if p.base as u64 + c.frame_size as u64 > mem {
            return Err(fail(Problem::ProgramOutsideMemory));
        }
        if p.task >= image.tasks.len() {
            return Err(fail(Problem::ProgramTask));
        }
        let mut connections = p.inputs.iter().chain(&p.outputs);
        if connections.any(|&(a, b)| a as u64 >= mem || b as u64 >= mem) {
            return Err(fail(Problem::ConnectionOutsideMemory));
        }
    }
    for s in image.start.iter().chain(&image.exit) {
        let c = image.codes.get(s.code.index());
        let fits = c.is_some_and(|c| s.base as u64 + c.frame_size as u64 <= mem);
        if !fits || s.flag as u64 >= mem {
            return Err(VerifyError {
                place: format!("instance call of code {}", s.code.index()),
                problem: Problem::InstanceCall,
            });
        }
    }
    for c in &image.copy_calls {
        let exit = c.exit.map(|(code, _)| code);
        let known = |k: CodeIdx| k.index() < image.codes.len();
        let flag_in = c.exit.is_none_or(|(_, o)| o < image.types.size(c.ty));
        if !(exit.into_iter().chain(c.reinit).all(known) && flag_in) {
            return Err(VerifyError {
                place: format!("copy calls of type {}", image.types.name(c.ty)),
                problem: Problem::InstanceCall,
            });
        }
    }
    for t in &image.tasks {
        if t.single.is_some_and(|a| a as u64 >= mem) {
            return Err(VerifyError {
                place: format!("task `{}`", t.name),
                problem: Problem::TriggerOutsideMemory,
            });
        }
    }
    Ok(())
}

/// Every retained value's slot is in memory; a string's id is the one its
/// slot holds initially and names an existing string (the runtime copies
/// retained values without further checks).
fn check_retained(image: &Image) -> Result<(), VerifyError> {
    use crate::ir::retained::RetainedStorage;
    for r in &image.retained {
        let ok = match r.storage {
            RetainedStorage::Slot(a) => (a as usize) < image.memory.len(),
            RetainedStorage::Text { slot, string } => {
                image.memory.get(slot as usize) == Some(&(string as u64))
                    && (string as usize) < image.strings.len()
            }
        };
        if !ok {
            return Err(VerifyError {
                place: format!("retained `{}`", r.path),
                problem: Problem::RetainedOutsideMemory,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
