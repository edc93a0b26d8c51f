//! Which instructions the native tier compiles. A block with any other
//! instruction runs wholly in the interpreter: a block is never half
//! native, so an unsupported instruction can only cost speed, never
//! change a result. The match below names every instruction (no
//! wildcard), so a new one does not compile until it is placed here.

use crate::ir::image::{CodeBlock, Image};
use crate::ir::op::Op;

/// Why `block` cannot be compiled (the first instruction the tier does
/// not handle), or `None` when it can.
pub(super) fn unsupported(img: &Image, block: &CodeBlock) -> Option<String> {
    // A fault in a `__TRY` region resumes the block at its `__CATCH`,
    // which only the interpreter does (`vm::exec::guarded`).
    if !block.handlers.is_empty() {
        return Some("a `__TRY` region (exception handlers)".into());
    }
    block.ops.iter().enumerate().find_map(|(pc, op)| {
        refused(img, op).map(|why| format!("instruction {pc} ({}): {why}", op.name()))
    })
}

/// How the tier runs one instruction.
enum Lowering {
    /// Inline machine code (lower/).
    Inline,
    /// A call into Rust that runs it as the interpreter does (helpers.rs,
    /// `step`).
    OutOfLine,
    /// Not at all: its block stays in the interpreter, for this reason.
    Refused(&'static str),
}

/// Why the tier does not compile `op`, or `None` when it does.
fn refused(img: &Image, op: &Op) -> Option<&'static str> {
    match (*op, lowering(op)) {
        (Op::FillElems { desc, .. }, _) if img.arrays[desc.index()].stride != 1 => {
            Some("array fill over a strided array")
        }
        (_, Lowering::Refused(why)) => Some(why),
        _ => None,
    }
}

/// Whether `op` runs out of line through the `step` helper.
pub(super) fn out_of_line(op: &Op) -> bool {
    matches!(lowering(op), Lowering::OutOfLine)
}

/// Whether out-of-line `op` only reads its input slots and writes its
/// result slot (so held slots other than those stay held across it).
pub(super) fn pure(op: &Op) -> bool {
    matches!(
        op,
        Op::PowS { .. }
            | Op::PowF32 { .. }
            | Op::PowF64 { .. }
            | Op::Convert { .. }
            | Op::MinMaxF32 { .. }
            | Op::MinMaxF64 { .. }
            | Op::MulTimeF64 { .. }
            | Op::DivTimeF64 { .. }
    )
}

/// How `op` runs (the array a `FillElems` fills is checked by
/// [`refused`]).
fn lowering(op: &Op) -> Lowering {
    match *op {
        Op::Sfc { .. } => Lowering::Refused("SFC charts run in the interpreter"),
        Op::CallHost { .. } => Lowering::Refused("host-registered POUs run in the interpreter"),
        Op::OpenIndexStep { .. } => Lowering::Refused("ARRAY[*] indexing is not lowered yet"),
        // The interpreter would panic on these: leave them to it.
        Op::ModSI { imm: 0, .. } => Lowering::Refused("MOD by a zero immediate"),
        Op::Shift { bits, .. } if bits == 0 || bits > 64 => {
            Lowering::Refused("shift of an unusual width")
        }
        // Inline machine code (lower/).
        Op::Nop
        | Op::LoadK { .. }
        | Op::LoadI { .. }
        | Op::Mov { .. }
        | Op::LoadAbs { .. }
        | Op::StoreAbs { .. }
        | Op::LoadInd { .. }
        | Op::StoreInd { .. }
        | Op::AddrOf { .. }
        | Op::AddrAdd { .. }
        | Op::LoadElem { .. }
        | Op::StoreElem { .. }
        | Op::ElemAddr { .. }
        | Op::ElemRef { .. }
        | Op::IndexStep { .. }
        | Op::AddS { .. }
        | Op::AddU { .. }
        | Op::AddSI { .. }
        | Op::SubS { .. }
        | Op::SubU { .. }
        | Op::MulS { .. }
        | Op::MulU { .. }
        | Op::DivS { .. }
        | Op::DivU { .. }
        | Op::ModS { .. }
        | Op::ModU { .. }
        | Op::ModSI { .. }
        | Op::NegS { .. }
        | Op::AbsS { .. }
        | Op::AddF32 { .. }
        | Op::SubF32 { .. }
        | Op::MulF32 { .. }
        | Op::DivF32 { .. }
        | Op::NegF32 { .. }
        | Op::AddF64 { .. }
        | Op::SubF64 { .. }
        | Op::MulF64 { .. }
        | Op::DivF64 { .. }
        | Op::NegF64 { .. }
        | Op::And { .. }
        | Op::Or { .. }
        | Op::Xor { .. }
        | Op::NotB { .. }
        | Op::NotW { .. }
        | Op::AndN { .. }
        | Op::OrN { .. }
        | Op::Shift { .. }
        | Op::CmpS { .. }
        | Op::CmpU { .. }
        | Op::CmpF32 { .. }
        | Op::CmpF64 { .. }
        | Op::CmpSI { .. }
        | Op::MulAddF32 { .. }
        | Op::MulAddF64 { .. }
        | Op::Operand { .. }
        | Op::CMov { .. }
        | Op::MinMaxS { .. }
        | Op::MinMaxU { .. }
        | Op::Jmp { .. }
        | Op::Jz { .. }
        | Op::Jnz { .. }
        | Op::JnCmpSI { .. }
        | Op::JnCmpS { .. }
        | Op::FillElems { .. }
        | Op::JzElem { .. }
        | Op::JnzElem { .. }
        | Op::AddBr { .. }
        | Op::JnCmpF32 { .. }
        | Op::JnCmpF64 { .. }
        | Op::ForNext { .. }
        | Op::ForNextS { .. }
        | Op::LoadElemU { .. }
        | Op::StoreElemU { .. }
        | Op::StoreStep { .. }
        | Op::ForScan { .. }
        | Op::CallFb { .. }
        | Op::CallFbInd { .. }
        | Op::CallNative { .. }
        | Op::CallNativeInd { .. }
        | Op::CallFn { .. }
        | Op::Clock { .. }
        | Op::MathF32 { .. }
        | Op::MathF64 { .. }
        | Op::Ret => Lowering::Inline,
        // Out of line: a call into Rust that runs the instruction as the
        // interpreter does (helpers.rs, `step`).
        Op::PowS { .. }
        | Op::PowF32 { .. }
        | Op::PowF64 { .. }
        | Op::Convert { .. }
        | Op::MinMaxF32 { .. }
        | Op::MinMaxF64 { .. }
        | Op::Mux { .. }
        | Op::MulTimeF64 { .. }
        | Op::DivTimeF64 { .. }
        | Op::MemCopy { .. }
        | Op::CmpStr { .. }
        | Op::StrMov { .. }
        | Op::StrCall { .. }
        | Op::StrConst { .. }
        | Op::ToStr { .. }
        | Op::FromStr { .. }
        | Op::RefMake { .. }
        | Op::RefAddr { .. }
        | Op::RefIndex { .. }
        | Op::PtrAdd { .. }
        | Op::RefValid { .. }
        | Op::FaultNullItf
        | Op::FaultReentry
        | Op::FaultRaise { .. }
        | Op::RefLoad { .. }
        | Op::RefStore { .. }
        | Op::RefView { .. }
        | Op::PtrToInt { .. }
        | Op::IntToPtr { .. } => Lowering::OutOfLine,
    }
}
