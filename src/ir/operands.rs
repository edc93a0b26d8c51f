//! Enumerates the frame-slot operands of an instruction, for relocation
//! (constant slots are numbered after emission) and for the link-time
//! verifier that lets the executor skip per-operand bounds checks.

use super::op::Op;

/// Calls `f` on every frame-relative slot operand of `op` (destinations,
/// sources, pointer slots, instance bases). Absolute addresses, jump
/// targets and table indexes are not slots and are not visited. Operands
/// that start a run of consecutive slots are visited once; see
/// [`slot_span`] for the run length.
pub fn for_each_slot(op: &mut Op, f: &mut impl FnMut(&mut u32)) {
    use Op::*;
    match op {
        Nop | Jmp { .. } | CallFn { .. } | Ret | Sfc { .. } => {}
        LoadK { d, .. } | LoadI { d, .. } | LoadAbs { d, .. } | Clock { d } => f(d),
        StoreAbs { s, .. } => f(s),
        Mov { d, s } | StrMov { d, s } => {
            f(d);
            f(s);
        }
        LoadInd { d, p, .. } | AddrAdd { d, p, .. } => {
            f(d);
            f(p);
        }
        StoreInd { p, s, .. } => {
            f(p);
            f(s);
        }
        AddrOf { d, off } => {
            f(d);
            f(off);
        }
        LoadElem { d, idx, .. }
        | ElemAddr { d, idx, .. }
        | ElemRef { d, idx, .. }
        | LoadElemU { d, idx, .. } => {
            f(d);
            f(idx);
        }
        StoreElem { idx, s, .. } | StoreStep { idx, s, .. } | StoreElemU { idx, s, .. } => {
            f(idx);
            f(s);
        }
        IndexStep { acc, idx, .. } => {
            f(acc);
            f(idx);
        }
        AddS { d, a, b, .. }
        | AddU { d, a, b, .. }
        | SubS { d, a, b, .. }
        | SubU { d, a, b, .. }
        | MulS { d, a, b, .. }
        | MulU { d, a, b, .. }
        | DivS { d, a, b, .. }
        | DivU { d, a, b, .. }
        | ModS { d, a, b, .. }
        | ModU { d, a, b, .. }
        | PowS { d, a, b, .. }
        | AddF32 { d, a, b }
        | SubF32 { d, a, b }
        | MulF32 { d, a, b }
        | DivF32 { d, a, b }
        | PowF32 { d, a, b }
        | AddF64 { d, a, b }
        | SubF64 { d, a, b }
        | MulF64 { d, a, b }
        | DivF64 { d, a, b }
        | PowF64 { d, a, b }
        | And { d, a, b }
        | Or { d, a, b }
        | Xor { d, a, b }
        | AndN { d, a, b }
        | OrN { d, a, b }
        | Shift { d, a, b, .. }
        | CmpS { d, a, b, .. }
        | CmpU { d, a, b, .. }
        | CmpF32 { d, a, b, .. }
        | CmpF64 { d, a, b, .. }
        | CmpStr { d, a, b, .. }
        | MinMaxS { d, a, b, .. }
        | MinMaxU { d, a, b, .. }
        | MinMaxF32 { d, a, b, .. }
        | MinMaxF64 { d, a, b, .. }
        | MulTimeF64 { d, a, b }
        | DivTimeF64 { d, a, b }
        | MulAddF32 { d, a, b }
        | MulAddF64 { d, a, b } => {
            f(d);
            f(a);
            f(b);
        }
        AddSI { d, a, .. }
        | ModSI { d, a, .. }
        | NegS { d, a, .. }
        | AbsS { d, a, .. }
        | NegF32 { d, a }
        | NegF64 { d, a }
        | MathF32 { d, a, .. }
        | MathF64 { d, a, .. }
        | NotB { d, a }
        | NotW { d, a, .. }
        | CmpSI { d, a, .. }
        | Convert { d, a, .. }
        | ToStr { d, a, .. }
        | FromStr { d, a, .. }
        | StrCall { d, a, .. } => {
            f(d);
            f(a);
        }
        CMov { d, c, s } => {
            f(d);
            f(c);
            f(s);
        }
        Mux { d, k, first, .. } => {
            f(d);
            f(k);
            f(first);
        }
        StrConst { d, .. } => f(d),
        Operand { s } => f(s),
        Jz { c, .. } | Jnz { c, .. } => f(c),
        JnCmpSI { a, .. } => f(a),
        JzElem { idx, .. } | JnzElem { idx, .. } => f(idx),
        FillElems { i, v, .. } => {
            f(i);
            f(v);
        }
        AddBr { d, b, .. } => {
            f(d);
            f(b);
        }
        JnCmpS { a, b, .. } | JnCmpF32 { a, b, .. } | JnCmpF64 { a, b, .. } => {
            f(a);
            f(b);
        }
        ForNext { i, .. } | ForScan { i, .. } => f(i),
        ForNextS { i, lim, .. } => {
            f(i);
            f(lim);
        }
        CallFb { inst, .. } | CallNative { inst, .. } => f(inst),
        CallFbInd { p, .. } | CallNativeInd { p, .. } => f(p),
        MemCopy { d, s, .. } => {
            f(d);
            f(s);
        }
    }
}

/// How many consecutive slots an instruction reads starting at its run
/// operand (`Mux::first`, `StrCall::a`); 1 for everything else.
pub fn slot_span(op: &Op) -> u32 {
    match op {
        Op::Mux { n, .. } => *n as u32,
        Op::StrCall { .. } => 4,
        _ => 1,
    }
}

/// The jump target of a branch instruction.
pub fn target_mut(op: &mut Op) -> Option<&mut u32> {
    match op {
        Op::Jmp { t }
        | Op::Jz { t, .. }
        | Op::Jnz { t, .. }
        | Op::JnCmpSI { t, .. }
        | Op::JzElem { t, .. }
        | Op::JnzElem { t, .. }
        | Op::JnCmpS { t, .. }
        | Op::JnCmpF32 { t, .. }
        | Op::JnCmpF64 { t, .. }
        | Op::ForNext { t, .. }
        | Op::ForNextS { t, .. } => Some(t),
        _ => None,
    }
}

/// The frame slot an instruction writes by name. (Array elements, memory
/// reached through addresses and called code are not named slots.)
pub struct Writes<'a> {
    /// The frame slot written by name, if any.
    pub slot: Option<&'a mut u32>,
    /// Whether that slot only receives the instruction's result, so the
    /// emitter may point it elsewhere (false for accumulators, loop
    /// variables and slots written beside other effects).
    pub result: bool,
}

/// What `op` writes. The match lists every instruction, so a new one must
/// say what it writes.
pub fn writes(op: &mut Op) -> Writes<'_> {
    use Op::*;
    let (slot, result) = match op {
        Nop | Jmp { .. } | Jz { .. } | Jnz { .. } | JnCmpSI { .. } | JnCmpS { .. } => (None, false),
        JnCmpF32 { .. } | JnCmpF64 { .. } | JzElem { .. } | JnzElem { .. } | Ret => (None, false),
        Operand { .. } => (None, false),
        LoadK { d, .. }
        | LoadI { d, .. }
        | Mov { d, .. }
        | LoadAbs { d, .. }
        | LoadInd { d, .. }
        | LoadElem { d, .. }
        | LoadElemU { d, .. }
        | AddS { d, .. }
        | AddU { d, .. }
        | AddSI { d, .. }
        | SubS { d, .. }
        | SubU { d, .. }
        | MulS { d, .. }
        | MulU { d, .. }
        | DivS { d, .. }
        | DivU { d, .. }
        | ModS { d, .. }
        | ModU { d, .. }
        | ModSI { d, .. }
        | NegS { d, .. }
        | PowS { d, .. }
        | AbsS { d, .. }
        | AddF32 { d, .. }
        | SubF32 { d, .. }
        | MulF32 { d, .. }
        | DivF32 { d, .. }
        | NegF32 { d, .. }
        | PowF32 { d, .. }
        | MathF32 { d, .. }
        | AddF64 { d, .. }
        | SubF64 { d, .. }
        | MulF64 { d, .. }
        | DivF64 { d, .. }
        | NegF64 { d, .. }
        | PowF64 { d, .. }
        | MathF64 { d, .. }
        | And { d, .. }
        | Or { d, .. }
        | Xor { d, .. }
        | NotB { d, .. }
        | NotW { d, .. }
        | AndN { d, .. }
        | OrN { d, .. }
        | Shift { d, .. }
        | CmpS { d, .. }
        | CmpU { d, .. }
        | CmpF32 { d, .. }
        | CmpF64 { d, .. }
        | CmpSI { d, .. }
        | CmpStr { d, .. }
        | Convert { d, .. }
        | CMov { d, .. }
        | MinMaxS { d, .. }
        | MinMaxU { d, .. }
        | MinMaxF32 { d, .. }
        | MinMaxF64 { d, .. }
        | Mux { d, .. }
        | MulTimeF64 { d, .. }
        | MulAddF32 { d, .. }
        | MulAddF64 { d, .. }
        | DivTimeF64 { d, .. }
        | Clock { d } => (Some(d), true),
        AddrOf { d, .. }
        | AddrAdd { d, .. }
        | ElemAddr { d, .. }
        | ElemRef { d, .. }
        | FromStr { d, .. }
        | AddBr { d, .. } => (Some(d), false),
        IndexStep { acc: d, .. }
        | ForNext { i: d, .. }
        | ForNextS { i: d, .. }
        | ForScan { i: d, .. }
        | FillElems { i: d, .. }
        | StoreStep { idx: d, .. }
        // The result slot of a string function may be written (LEN, FIND).
        | StrCall { d, .. } => (Some(d), false),
        // Array elements, memory reached through addresses, strings and
        // called code are not named slots.
        StoreElem { .. }
        | StoreElemU { .. }
        | StoreAbs { .. }
        | StoreInd { .. }
        | MemCopy { .. }
        | StrMov { .. }
        | StrConst { .. }
        | ToStr { .. }
        | Sfc { .. }
        | CallFb { .. }
        | CallFbInd { .. }
        | CallNative { .. }
        | CallNativeInd { .. }
        | CallFn { .. } => (None, false),
    };
    Writes { slot, result }
}
