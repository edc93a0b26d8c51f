//! The emission context of one code block (instruction buffer,
//! temporaries, loop targets, constant and pinned slots), and the
//! value/place vocabulary the expression checker uses.

use super::body::BodyBuilder;
use super::consts::Const;
use super::model::VarInfo;
use crate::elementary::ElemType;
use crate::ir::image::StringInit;
use crate::ir::op::{ArrayIdx, Op, Slot, Target};
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use indexmap::IndexSet;

/// The type of an expression: a known type, or an untyped literal that
/// adapts to its context.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ty {
    /// A resolved type.
    T(TypeId),
    /// An untyped integer constant.
    AnyInt,
    /// An untyped real constant.
    AnyReal,
}

impl Ty {
    /// The resolved type, if any.
    pub fn id(self) -> Option<TypeId> {
        match self {
            Ty::T(t) => Some(t),
            _ => None,
        }
    }
}

/// A checked expression value.
#[derive(Debug, Clone, PartialEq)]
pub enum Val {
    /// Known at compile time.
    Const(Const, Ty),
    /// In a frame slot.
    Slot(Slot, TypeId),
    /// After an error (type ERROR), or a call without result.
    None(TypeId),
}

impl Val {
    /// The value's type.
    pub fn ty(&self) -> Ty {
        match self {
            Val::Const(_, t) => *t,
            Val::Slot(_, t) | Val::None(t) => Ty::T(*t),
        }
    }

    /// The error placeholder.
    pub fn error() -> Val {
        Val::None(TypeTable::error())
    }

    /// True for the error placeholder.
    pub fn is_error(&self) -> bool {
        matches!(self, Val::None(t) if *t == TypeTable::error())
    }
}

/// Where an assignable (or readable) value lives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Place {
    /// A frame slot.
    Frame(Slot),
    /// An absolute address.
    Abs(u32),
    /// `mem[mem[base + p] + off]`.
    Ind {
        /// Frame slot holding the address.
        p: Slot,
        /// Static offset.
        off: u32,
    },
    /// The elementary value a `POINTER TO` in slot `r` designates, read
    /// with `RefLoad` and written with `RefStore` (which also serve byte
    /// views, `ir::refs::VIEW`); `elem` is its type's code.
    View {
        /// Frame slot holding the pointer.
        r: Slot,
        /// `ir::refs::elem_code` of the value's type.
        elem: u8,
    },
    /// A checked element of a 1-D array in the frame.
    Elem {
        /// Frame slot holding the index.
        idx: Slot,
        /// Array descriptor.
        desc: ArrayIdx,
    },
}

/// A place with its type and access rights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaceRef {
    /// Location.
    pub place: Place,
    /// Type.
    pub ty: TypeId,
    /// Writable by the current body.
    pub writable: bool,
    /// Why not writable (for the message).
    pub readonly_reason: Option<&'static str>,
    /// A located `%I` input (writing it warns).
    pub input_image: bool,
}

/// Loop bookkeeping for EXIT and CONTINUE.
#[derive(Debug, Default, Clone)]
pub struct LoopCtx {
    /// Jumps to patch to the loop's end.
    pub exits: Vec<usize>,
    /// Jumps to patch to the loop's continue point.
    pub continues: Vec<usize>,
}

/// A `__FINALLY` part the statements being emitted are inside (in the
/// guarded or the `__CATCH` statements of its `__TRY`): RETURN, and EXIT
/// or CONTINUE of a loop around the `__TRY`, run a copy of it first.
#[derive(Debug, Clone)]
pub struct PendingFinally {
    /// The `__FINALLY` statements.
    pub stmts: Vec<crate::syntax::ast::Stmt>,
    /// How many loops enclosed the `__TRY`.
    pub loops: usize,
}

/// A copy of a `__FINALLY` part emitted before a jump out of its `__TRY`:
/// the instructions `from..to`, of the part at `level` of
/// [`Fcx::finally`]. A fault there is not for the `__TRY`s at that level
/// and inside it to catch, as one in the part itself would not be.
#[derive(Debug, Clone, Copy)]
pub struct FinallyCopy {
    /// First instruction of the copy.
    pub from: u32,
    /// One past its last.
    pub to: u32,
    /// The index in [`Fcx::finally`] of the part copied.
    pub level: usize,
}

/// Emission state of one code block (a POU body or one of its SFC blocks),
/// owned by the body builder while the block is emitted.
#[derive(Debug, Clone)]
pub struct Fcx {
    /// POU index.
    pub pou: usize,
    /// Instructions.
    pub ops: Vec<Op>,
    /// Their spans.
    pub spans: Vec<Span>,
    /// Span attached to emitted instructions.
    pub span: Span,
    /// First temporary slot.
    pub temp_base: u32,
    /// Next free temporary.
    pub temp_next: u32,
    /// High-water mark.
    pub temp_max: u32,
    /// Enclosing loops.
    pub loops: Vec<LoopCtx>,
    /// Jumps to the end of the body (RETURN).
    pub returns: Vec<usize>,
    /// The `__FINALLY` parts around the statements being emitted,
    /// outermost first.
    pub finally: Vec<PendingFinally>,
    /// The copies of `__FINALLY` parts emitted so far.
    pub finally_copies: Vec<FinallyCopy>,
    /// Index of the last instruction whose destination may be retargeted.
    pub last_def: Option<(usize, Slot)>,
    /// Instructions whose address operand is relative to a called
    /// function's frame, to be relocated at link time: (instruction, POU).
    pub fixups: Vec<(usize, usize)>,
    /// Constant values that live in frame slots (numbered with
    /// [`CONST_TAG`] until the frame size is known).
    pub consts: IndexSet<u64>,
    /// Number of pinned slots (numbered with [`PIN_TAG`] until placed).
    pub pins: u32,
    /// Element addresses computed in the current basic block.
    pub elem_cache: Vec<ElemEntry>,
    /// Size of the declared variables (slots below it are variables).
    pub vars_size: u32,
    /// Control variables of the FOR loops being emitted (read-only inside).
    pub for_vars: Vec<Slot>,
    /// The IL current result while it is visible as a hidden variable
    /// (to call arguments built from it).
    pub il_cr: Option<VarInfo>,
    /// The `__TRY` regions emitted so far.
    pub handlers: Vec<crate::ir::handler::Handler>,
}

/// A cached element address: the element of the frame array described by
/// `key` (frame offset, lower bound, length, stride) at index variable `idx`
/// is at the address held in pinned slot `ptr`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElemEntry {
    /// Array identity.
    pub key: (u32, i64, u64, u32),
    /// Index variable slot.
    pub idx: Slot,
    /// Pinned slot with the element's address.
    pub ptr: Slot,
}

/// Marks a provisional pinned-slot number during emission.
pub const PIN_TAG: u32 = 0x4000_0000;

/// Marks a provisional constant-slot number during emission.
pub const CONST_TAG: u32 = 0x8000_0000;

impl Fcx {
    /// A fresh context whose temporaries start at `temp_base`.
    pub fn new(pou: usize, temp_base: u32) -> Fcx {
        Fcx {
            pou,
            ops: Vec::new(),
            spans: Vec::new(),
            span: Span::default(),
            temp_base,
            temp_next: temp_base,
            temp_max: temp_base,
            loops: Vec::new(),
            returns: Vec::new(),
            finally: Vec::new(),
            finally_copies: Vec::new(),
            last_def: None,
            fixups: Vec::new(),
            consts: IndexSet::new(),
            pins: 0,
            elem_cache: Vec::new(),
            vars_size: temp_base,
            for_vars: Vec::new(),
            il_cr: None,
            handlers: Vec::new(),
        }
    }

    /// Appends an instruction.
    pub fn emit(&mut self, op: Op) -> usize {
        self.invalidate(&op);
        self.ops.push(op);
        self.spans.push(self.span);
        self.last_def = dest_of(&op).map(|d| (self.ops.len() - 1, d));
        self.ops.len() - 1
    }

    /// Index of the next instruction (a jump target). A label ends the
    /// basic block, so cached element addresses are forgotten.
    pub fn here(&mut self) -> Target {
        self.last_def = None;
        self.elem_cache.clear();
        Target::new(self.ops.len() as u32)
    }

    /// A slot that keeps its value across statements (for cached addresses).
    pub fn pin(&mut self) -> Slot {
        self.pins += 1;
        Slot::new(PIN_TAG | (self.pins - 1))
    }

    /// Forgets cached element addresses that `op` may make stale: any write
    /// to a cached index variable, user calls (which may write variables
    /// through VAR_IN_OUT), and stores through pointers that are not cached
    /// element addresses.
    fn invalidate(&mut self, op: &Op) {
        if self.elem_cache.is_empty() {
            return;
        }
        let clear_all = match op {
            Op::CallFb { .. } | Op::CallFbInd { .. } | Op::CallFn { .. } | Op::MemCopy { .. } => {
                true
            }
            Op::StoreInd { p, .. } => !self.elem_cache.iter().any(|e| e.ptr == *p),
            Op::RefStore { .. } => true,
            Op::AddrOf { .. } => true,
            _ => false,
        };
        if clear_all {
            self.elem_cache.clear();
            return;
        }
        let written = match op {
            Op::ForNext { i, .. } | Op::ForNextS { i, .. } => Some(*i),
            _ => dest_of(op),
        };
        if let Some(w) = written {
            self.elem_cache.retain(|e| e.idx != w && e.ptr != w);
        }
    }

    /// Points the jump at `at` to `target`.
    pub fn patch(&mut self, at: usize, target: Target) {
        if let Some(t) = crate::ir::operands::target_mut(&mut self.ops[at]) {
            *t = target;
        }
    }

    /// Closes the innermost loop at the current position: its EXITs and
    /// `exits` jump here, its CONTINUEs to `cont`.
    pub fn end_loop(&mut self, cont: Target, exits: Vec<usize>) {
        let lp = self.loops.pop().unwrap_or_default();
        let end = self.here();
        for j in exits.into_iter().chain(lp.exits) {
            self.patch(j, end);
        }
        for j in lp.continues {
            self.patch(j, cont);
        }
    }

    /// A fresh temporary slot.
    pub fn temp(&mut self) -> Slot {
        let t = self.temp_next;
        self.temp_next += 1;
        self.temp_max = self.temp_max.max(self.temp_next);
        Slot::new(t)
    }

    /// `n` consecutive temporaries.
    pub fn temps(&mut self, n: u32) -> Slot {
        let t = self.temp_next;
        self.temp_next += n;
        self.temp_max = self.temp_max.max(self.temp_next);
        Slot::new(t)
    }

    /// True if `s` is a temporary.
    pub fn is_temp(&self, s: Slot) -> bool {
        s.get() >= self.temp_base && s.get() < PIN_TAG
    }

    /// A read-only frame slot holding `bits`, initialised once per instance.
    pub fn const_slot(&mut self, bits: u64) -> Slot {
        Slot::new(CONST_TAG | self.consts.insert_full(bits).0 as u32)
    }

    /// Gives this body's constant and pinned slots their final numbers
    /// from `first` on; returns the end of the region and the constants'
    /// `(slot, value)` list.
    pub fn place_consts(&mut self, first: u32) -> (u32, Vec<(Slot, u64)>) {
        place_tagged(&mut self.ops, &self.consts, self.pins, first)
    }
}

/// Relocates provisional constant and pinned slots of `ops` to a region
/// starting at `first`: constants first, then pinned slots. Returns the end
/// of the region and the constants' `(slot, value)` list.
pub fn place_tagged(
    ops: &mut [Op],
    consts: &IndexSet<u64>,
    pins: u32,
    first: u32,
) -> (u32, Vec<(Slot, u64)>) {
    let pins_at = first + consts.len() as u32;
    for op in ops.iter_mut() {
        crate::ir::operands::for_each_slot(op, &mut |s| {
            let n = s.get();
            if n & CONST_TAG != 0 {
                *s = Slot::new(first + (n & !CONST_TAG));
            } else if n & PIN_TAG != 0 {
                *s = Slot::new(pins_at + (n & !PIN_TAG));
            }
        });
    }
    let list = consts
        .iter()
        .enumerate()
        .map(|(k, v)| (Slot::new(first + k as u32), *v))
        .collect();
    (pins_at + pins, list)
}

impl Fcx {
    /// Hands over the provisional constants and pin count (for blocks
    /// relocated later together with their owner).
    pub fn take_tagged(&mut self) -> (IndexSet<u64>, u32) {
        (
            std::mem::take(&mut self.consts),
            std::mem::replace(&mut self.pins, 0),
        )
    }

    /// Writes `s` into `d`: when `s` is a temporary just defined by the last
    /// instruction, that instruction is retargeted instead of adding a move.
    pub fn mov(&mut self, d: Slot, s: Slot) {
        if d == s {
            return;
        }
        // The defining instruction must be the last one (or be followed
        // only by its operand word).
        let last = |at: usize| {
            at + 1 == self.ops.len()
                || (at + 2 == self.ops.len() && matches!(self.ops[at + 1], Op::Operand { .. }))
        };
        if let Some((at, def)) = self.last_def
            && def == s
            && self.is_temp(s)
            && last(at)
        {
            set_dest(&mut self.ops[at], d);
            self.last_def = Some((at, d));
            return;
        }
        // A constant that fits an immediate is written as one: no frame
        // slot to read (`x := 5`, an FB's `PV := 50`).
        if let Some(imm) = self.small_const(s) {
            self.emit(Op::LoadI { d, imm });
            return;
        }
        self.emit(Op::Mov { d, s });
    }

    /// The value of provisional constant slot `s` when it is a 32-bit
    /// signed integer's (as `LoadI` sign-extends it).
    fn small_const(&self, s: Slot) -> Option<i32> {
        if s.get() & CONST_TAG == 0 {
            return None;
        }
        let bits = *self.consts.get_index((s.get() & !CONST_TAG) as usize)?;
        i32::try_from(bits as i64).ok()
    }
}

/// The destination slot an instruction writes, if it writes exactly one.
fn dest_of(op: &Op) -> Option<Slot> {
    let mut copy = *op;
    dest_mut(&mut copy).map(|d| *d)
}

/// Points the instruction's destination at `new`.
fn set_dest(op: &mut Op, new: Slot) {
    if let Some(d) = dest_mut(op) {
        *d = new;
    }
}

/// The destination operand of an instruction that computes one value
/// into one slot.
fn dest_mut(op: &mut Op) -> Option<&mut Slot> {
    let w = crate::ir::operands::writes(op);
    if w.result { w.slot } else { None }
}

impl BodyBuilder<'_> {
    /// A string temporary of capacity `max`: a fresh string id (private to
    /// this POU, safe because IEC forbids recursion) loaded into a temporary.
    pub(super) fn string_temp(&mut self, max: u32, wide: bool) -> Slot {
        self.out.strings.push(StringInit {
            max,
            wide,
            init: String::new(),
        });
        // The slot only holds the string's id, which never changes.
        self.block.const_slot(self.out.strings.len() as u64 - 1)
    }

    /// Puts a value into a slot (constants are loaded into a temporary).
    pub(super) fn materialize(&mut self, v: &Val) -> Slot {
        match v {
            Val::Slot(s, _) => *s,
            Val::None(_) => self.block.temp(),
            Val::Const(c, ty) => {
                let bits = match c {
                    Const::Bits(b) => *b,
                    Const::Int(i) => *i as i64 as u64,
                    Const::Real(r) => r.to_bits(),
                    Const::Str(s) => {
                        let (max, wide) = match ty.id().map(|t| &self.types.get(t).kind) {
                            Some(TypeKind::Str { max, wide }) => (*max, *wide),
                            _ => (254, false),
                        };
                        let t = self.string_temp(max.max(s.chars().count() as u32), wide);
                        let k = self.out.str_const(s);
                        self.block.emit(Op::StrConst { d: t, k });
                        self.block.last_def = None;
                        return t;
                    }
                };
                self.block.const_slot(bits)
            }
        }
    }

    /// Reads a place into a slot.
    pub(super) fn read_place(&mut self, p: &PlaceRef) -> Val {
        let slot = match p.place {
            Place::Frame(s) => s,
            Place::Abs(abs) => {
                let t = self.block.temp();
                self.block.emit(Op::LoadAbs { d: t, abs });
                t
            }
            Place::Ind { p: ptr, off } => {
                let t = self.block.temp();
                self.block.emit(Op::LoadInd { d: t, p: ptr, off });
                t
            }
            Place::Elem { idx, desc } => {
                let t = self.block.temp();
                self.block.emit(Op::LoadElem { d: t, idx, desc });
                t
            }
            Place::View { r, elem } => {
                let t = self.block.temp();
                self.block.emit(Op::RefLoad { d: t, r, elem });
                t
            }
        };
        Val::Slot(slot, p.ty)
    }

    /// Stores slot `s` into a scalar place.
    pub(super) fn write_place(&mut self, p: &PlaceRef, s: Slot) {
        let is_string = matches!(self.types.get(p.ty).kind, TypeKind::Str { .. });
        if is_string {
            // Strings are copied by content; the place holds the target's string id.
            let target = match self.read_place(p) {
                Val::Slot(t, _) => t,
                _ => return,
            };
            self.block.emit(Op::StrMov { d: target, s });
            return;
        }
        match p.place {
            Place::Frame(d) => self.block.mov(d, s),
            Place::Abs(abs) => {
                self.block.emit(Op::StoreAbs { abs, s });
            }
            Place::Ind { p: ptr, off } => {
                self.block.emit(Op::StoreInd { p: ptr, off, s });
            }
            Place::Elem { idx, desc } => {
                self.block.emit(Op::StoreElem { idx, s, desc });
            }
            Place::View { r, elem } => {
                self.block.emit(Op::RefStore { r, s, elem });
            }
        }
    }

    /// An absolute-address pointer to a place, in a slot.
    pub(super) fn address_of(&mut self, p: &PlaceRef) -> Slot {
        if let Place::Ind { p: ptr, off: 0 } = p.place {
            return ptr;
        }
        let t = self.block.temp();
        match p.place {
            Place::Frame(s) => {
                self.block.emit(Op::AddrOf { d: t, off: s });
            }
            Place::Abs(abs) => {
                let k = self.out.konst(abs as u64);
                self.block.emit(Op::LoadK { d: t, k });
            }
            Place::Ind { p: ptr, off } => {
                self.block.emit(Op::AddrAdd { d: t, p: ptr, off });
            }
            Place::Elem { idx, desc } => {
                self.block.emit(Op::ElemRef { d: t, idx, desc });
            }
            Place::View { r, .. } => {
                // Typed pointers only: a byte view has no slot address (R034).
                self.block.emit(Op::RefAddr { d: t, r, width: 1 });
            }
        }
        self.block.last_def = None;
        t
    }

    /// Elementary storage type of `t`, if scalar.
    pub(super) fn scalar(&self, t: TypeId) -> Option<ElemType> {
        self.types.scalar(t)
    }
}
