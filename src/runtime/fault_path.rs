//! Where a runtime fault happened in the running program: the instance
//! path of the POU that faulted (`Main.line.conveyor1.motor`) and the chain
//! of calls that led there, innermost first.
//!
//! The executor records nothing on the normal path: while a fault unwinds,
//! each calling block notes its call instruction and its own frame base
//! (`vm::CallSite`). Here, after the fact, those bases become names
//! by walking the memory layout from the program instances and the global
//! variables down to the instance at that base — the same layout
//! [`super::names`] resolves paths against, in the other direction.

use crate::ir::image::{CodeKind, Image};
use crate::ir::op::{CodeIdx, Op};
use crate::ir::type_table::{MemberKind, TypeId, TypeKind};
use crate::source::{SourceMap, Span};
use crate::vm::CallSite;

/// One call on the way to a runtime fault: which POU instance made it and
/// where in the source (see [`crate::RuntimeFault::callers`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaultFrame {
    /// The calling POU's name as [`crate::RuntimeFault::pou`] gives it: a
    /// PROGRAM, FUNCTION_BLOCK or FUNCTION name, `FB.Method` for a method,
    /// `P.Action` for an SFC action or transition.
    pub pou: String,
    /// The calling instance's path (see [`crate::RuntimeFault::instance`]).
    pub instance: String,
    /// `file:line:column` of the call.
    pub location: String,
}

/// Where a fault happened: the faulting instance and the calls that led
/// there (kept boxed in [`crate::RuntimeFault`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FaultPlace {
    /// See [`crate::RuntimeFault::instance`].
    pub instance: String,
    /// See [`crate::RuntimeFault::callers`].
    pub callers: Vec<FaultFrame>,
}

/// A block that ran: its code, the instruction, and the frame base.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub code: CodeIdx,
    pub pc: u32,
    pub base: usize,
}

/// The instance path of the faulting block and its callers, innermost
/// first, from the fault's block and instruction, the calls it unwound
/// through, the memory as the fault left it, and the base of the program
/// instance the cycle ran.
pub(super) fn trace(
    image: &Image,
    sources: &SourceMap,
    mem: &[u64],
    fault: (CodeIdx, u32),
    callers: &[CallSite],
    program_base: usize,
) -> (String, Vec<FaultFrame>) {
    let frames = fault_frames(image, mem, fault, callers, program_base);
    let mut names = frame_names(image, &frames);
    let chain = frames
        .iter()
        .zip(&names)
        .skip(1)
        .map(|(f, name)| FaultFrame {
            pou: image.codes[f.code.index()].name.clone(),
            instance: name.clone(),
            location: sources.location(span_of(image, f.code, f.pc)),
        })
        .collect();
    (names.swap_remove(0), chain)
}

/// The instance path of each frame of `frames` (innermost first), as a
/// fault names them.
pub(super) fn frame_names(image: &Image, frames: &[Frame]) -> Vec<String> {
    // Named outermost first: a FUNCTION's local instance is named after
    // its caller.
    let mut names = vec![String::new(); frames.len()];
    for k in (0..frames.len()).rev() {
        let caller = names.get(k + 1).map(String::as_str);
        names[k] = frame_name(image, frames[k], caller);
    }
    names
}

/// The frames of a fault, innermost first (as [`trace`] names them).
pub(super) fn fault_frames(
    image: &Image,
    mem: &[u64],
    fault: (CodeIdx, u32),
    callers: &[CallSite],
    program_base: usize,
) -> Vec<Frame> {
    let innermost = Frame {
        code: fault.0,
        pc: fault.1,
        base: callers
            .first()
            .map_or(program_base, |site| callee_base(image, mem, site)),
    };
    let mut frames: Vec<Frame> = std::iter::once(innermost)
        .chain(callers.iter().map(|site| Frame {
            code: site.code,
            pc: site.pc,
            base: site.base,
        }))
        .collect();
    // A fault raised by the chart runtime itself (unstable GRAFCET) is
    // located at the chart's instruction, which also appears as its caller.
    frames.dedup_by(|outer, inner| inner.code == outer.code && inner.pc == outer.pc);
    frames
}

/// The frame base the call at `site` gave its callee: the instance in the
/// caller's frame, the instance a pointer slot held (the fault stopped the
/// PLC, so the slot still holds it), a FUNCTION's static frame, or, for
/// a chart's actions and transitions, the caller's own base.
fn callee_base(image: &Image, mem: &[u64], site: &CallSite) -> usize {
    let call = image.codes[site.code.index()].ops.get(site.pc as usize);
    match call {
        Some(Op::CallFb { inst, .. }) => site.base + inst.index(),
        Some(Op::CallFbInd { p, .. }) => mem
            .get(site.base + p.index())
            .map_or(usize::MAX, |&a| a as usize),
        Some(Op::CallFn { code }) => image.codes[code.index()].frame as usize,
        _ => site.base,
    }
}

/// The source span of instruction `pc` of `code`.
pub(super) fn span_of(image: &Image, code: CodeIdx, pc: u32) -> Span {
    image.codes[code.index()]
        .spans
        .get(pc as usize)
        .copied()
        .unwrap_or_default()
}

/// The name of one frame: a FUNCTION's name; otherwise the path of the
/// instance it ran on, and for a method or an SFC action or transition
/// (blocks named `Owner.Name`) that path with the name added.
fn frame_name(image: &Image, f: Frame, caller: Option<&str>) -> String {
    let block = &image.codes[f.code.index()];
    if block.kind == CodeKind::Function {
        return block.name.clone();
    }
    let owner = match block.name.split_once('.') {
        Some((owner, _)) => owner,
        None => block.name.as_str(),
    };
    let path = instance_at(image, f.base, f.code, owner).unwrap_or_else(|| {
        // An instance outside the named variables (a FUNCTION's local
        // instance): named after the caller that holds it.
        match caller {
            Some(c) => format!("{c}.<{owner} instance>"),
            None => format!("<{owner} instance>"),
        }
    });
    match block.name.split_once('.') {
        Some((_, member)) => format!("{path}.{member}"),
        None => path,
    }
}

/// The path of the PROGRAM or FUNCTION_BLOCK instance whose first slot is
/// `base`, found from the program instances and the global variables.
/// Several instances can start at one slot (an FB whose first variable is
/// an FB): the one of the block's type wins, else the outermost.
fn instance_at(image: &Image, base: usize, code: CodeIdx, owner: &str) -> Option<String> {
    let roots = image
        .programs
        .iter()
        .map(|p| (p.name.as_str(), p.base, p.ty))
        .chain(
            image
                .globals
                .iter()
                .map(|g| (g.name.as_str(), g.addr, g.ty)),
        );
    for (name, addr, ty) in roots {
        let addr = addr as usize;
        if base < addr || base >= addr + image.types.size(ty) as usize {
            continue;
        }
        if let Some(path) = descend(image, name.to_string(), ty, base - addr, code, owner) {
            return Some(path);
        }
    }
    None
}

/// Walks from a variable of type `ty` named `path` to the instance at
/// offset `rel` inside it.
fn descend(
    image: &Image,
    mut path: String,
    mut ty: TypeId,
    mut rel: usize,
    code: CodeIdx,
    owner: &str,
) -> Option<String> {
    let mut outermost: Option<String> = None;
    loop {
        let kind = &image.types.get(ty).kind;
        if rel == 0
            && let TypeKind::Pou { code: own, .. } = kind
        {
            if *own == code || image.types.name(ty).eq_ignore_ascii_case(owner) {
                return Some(path);
            }
            outermost.get_or_insert_with(|| path.clone());
        }
        match kind {
            TypeKind::Pou { members, .. } | TypeKind::Struct { fields: members } => {
                // VAR_IN_OUT slots hold addresses, not the instance.
                let Some(m) = members.iter().find(|m| {
                    let at = m.offset as usize;
                    m.kind != MemberKind::InOut
                        && rel >= at
                        && rel < at + image.types.size(m.ty) as usize
                }) else {
                    return outermost;
                };
                path = format!("{path}.{}", super::names::shown_member(image, &m.name));
                rel -= m.offset as usize;
                ty = m.ty;
            }
            TypeKind::Array { dims, elem } => {
                let size = (image.types.size(*elem) as usize).max(1);
                let mut linear = (rel / size) as u64;
                rel %= size;
                // Row-major: the last subscript varies fastest.
                let mut subscripts = vec![0i64; dims.len()];
                for (k, d) in dims.iter().enumerate().rev() {
                    let len = d.len().max(1);
                    subscripts[k] = d.lo + (linear % len) as i64;
                    linear /= len;
                }
                let text: Vec<String> = subscripts.iter().map(i64::to_string).collect();
                path = format!("{path}[{}]", text.join(","));
                ty = *elem;
            }
            _ => return outermost,
        }
    }
}
