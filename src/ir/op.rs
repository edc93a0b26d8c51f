//! The instruction set of the typed register IR.
//!
//! Every operand is a *slot*: an index relative to the current frame base
//! (the PROGRAM/FB instance or the function frame being executed). Operations
//! carry their concrete type in the opcode (`AddS` with a sign-extension
//! shift, `AddF32`, ...), so the executor never inspects a value's type.
//! Absolute memory (globals, located variables, function frames seen from a
//! caller) is reached only through the `*Abs` and `*Ind` instructions.
//!
//! Integer results are wrapped at their type's width with a shift pair:
//! `shift = 64 - bits`; signed kinds sign-extend, unsigned kinds zero-extend.
//! Every instruction fits in 16 bytes.

/// A frame-relative slot index.
pub type Slot = u32;
/// An index into the instruction vector of a code block.
pub type Target = u32;

/// Elementary math functions on REAL/LREAL.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MathFn {
    /// ABS
    Abs,
    /// SQRT
    Sqrt,
    /// LN
    Ln,
    /// LOG (base 10)
    Log,
    /// EXP
    Exp,
    /// SIN
    Sin,
    /// COS
    Cos,
    /// TAN
    Tan,
    /// ASIN
    Asin,
    /// ACOS
    Acos,
    /// ATAN
    Atan,
}

macro_rules! math_fn_apply {
    ($name:ident, $t:ty) => {
        /// Applies the function to a value of this width.
        pub fn $name(self, x: $t) -> $t {
            match self {
                MathFn::Abs => x.abs(),
                MathFn::Sqrt => x.sqrt(),
                MathFn::Ln => x.ln(),
                MathFn::Log => x.log10(),
                MathFn::Exp => x.exp(),
                MathFn::Sin => x.sin(),
                MathFn::Cos => x.cos(),
                MathFn::Tan => x.tan(),
                MathFn::Asin => x.asin(),
                MathFn::Acos => x.acos(),
                MathFn::Atan => x.atan(),
            }
        }
    };
}

impl MathFn {
    math_fn_apply!(apply_f32, f32);
    math_fn_apply!(apply_f64, f64);
}

/// Comparison predicates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cmp {
    /// `=`
    Eq,
    /// `<>`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

impl Cmp {
    /// Applies the predicate to an ordering.
    #[inline(always)]
    pub fn test(self, ord: std::cmp::Ordering) -> bool {
        use std::cmp::Ordering::*;
        match self {
            Cmp::Eq => ord == Equal,
            Cmp::Ne => ord != Equal,
            Cmp::Lt => ord == Less,
            Cmp::Le => ord != Greater,
            Cmp::Gt => ord == Greater,
            Cmp::Ge => ord != Less,
        }
    }
}

/// Conversions between slot encodings. `S`/`U` = signed/unsigned integer,
/// `F32`/`F64` = REAL/LREAL. Integer targets carry a shift (`64 - bits`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Conv {
    /// Integer to signed integer, wrapping (e.g. DINT_TO_INT).
    WrapS(u8),
    /// Integer to unsigned integer or bit string, wrapping.
    WrapU(u8),
    /// Signed integer to REAL.
    SToF32,
    /// Unsigned integer to REAL.
    UToF32,
    /// Signed integer to LREAL.
    SToF64,
    /// Unsigned integer to LREAL.
    UToF64,
    /// REAL to LREAL.
    F32ToF64,
    /// LREAL to REAL.
    F64ToF32,
    /// REAL to signed integer, rounding half away from zero; out of range faults.
    F32ToS(u8),
    /// REAL to unsigned integer, rounding; out of range faults.
    F32ToU(u8),
    /// LREAL to signed integer, rounding; out of range faults.
    F64ToS(u8),
    /// LREAL to unsigned integer, rounding; out of range faults.
    F64ToU(u8),
    /// TRUNC of REAL to signed integer; out of range faults.
    TruncF32ToS(u8),
    /// TRUNC of LREAL to signed integer; out of range faults.
    TruncF64ToS(u8),
    /// TRUNC of REAL to unsigned integer.
    TruncF32ToU(u8),
    /// TRUNC of LREAL to unsigned integer.
    TruncF64ToU(u8),
    /// Integer to BOOL (non-zero is TRUE).
    ToBool,
    /// Signed integer checked into a signed range (faults when it does not fit).
    CheckS(u8),
    /// Integer checked into an unsigned range.
    CheckU(u8),
    /// Signed integer checked into an unsigned range (negative values fault).
    CheckSToU(u8),
    /// Binary to BCD (value of `bits` width); faults if it does not fit.
    ToBcd(u8),
    /// BCD to binary; faults on an invalid nibble.
    FromBcd,
    /// Nanoseconds to whole milliseconds (`TIME_TO_<int>`), then wrap as signed.
    NsToMsS(u8),
    /// Nanoseconds to whole milliseconds, then wrap as unsigned.
    NsToMsU(u8),
    /// Milliseconds (signed) to nanoseconds (`<int>_TO_TIME`).
    MsToNsS,
    /// Milliseconds (unsigned) to nanoseconds.
    MsToNsU,
    /// TIME to REAL milliseconds.
    NsToMsF32,
    /// TIME to LREAL milliseconds.
    NsToMsF64,
    /// REAL milliseconds to TIME.
    MsF32ToNs,
    /// LREAL milliseconds to TIME.
    MsF64ToNs,
    /// DT to DATE (drop the time of day).
    DtToDate,
    /// DT to TOD (keep the time of day).
    DtToTod,
}

/// Bit-string shifts and rotations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShiftKind {
    /// SHL
    Shl,
    /// SHR
    Shr,
    /// ROL
    Rol,
    /// ROR
    Ror,
}

/// String functions; arguments are in consecutive slots starting at `a`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StrFn {
    /// LEN(a) → integer in `d`.
    Len,
    /// LEFT(a, n)
    Left,
    /// RIGHT(a, n)
    Right,
    /// MID(a, len, pos)
    Mid,
    /// CONCAT(a, b)
    Concat,
    /// INSERT(a, b, pos)
    Insert,
    /// DELETE(a, len, pos)
    Delete,
    /// REPLACE(a, b, len, pos)
    Replace,
    /// FIND(a, b) → integer position (1-based, 0 if absent).
    Find,
}

/// The native standard function blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NativeFb {
    /// R_TRIG
    RTrig,
    /// F_TRIG
    FTrig,
    /// SR (set dominant)
    Sr,
    /// RS (reset dominant)
    Rs,
    /// CTU on a counter type given by the range index (see `CounterRange`).
    Ctu(CounterRange),
    /// CTD
    Ctd(CounterRange),
    /// CTUD
    Ctud(CounterRange),
    /// TON
    Ton,
    /// TOF
    Tof,
    /// TP
    Tp,
}

/// Value range of a counter's PV/CV.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CounterRange {
    /// INT
    Int,
    /// DINT
    Dint,
    /// LINT
    Lint,
    /// UDINT
    Udint,
    /// ULINT
    Ulint,
}

/// One IR instruction.
///
/// Operand fields follow one naming convention (documented here rather than
/// on each of the ~300 fields): `d` destination slot; `a`, `b`, `s`, `c`
/// source slots (`c` a condition for jumps and `CMov`); `p` a slot holding an
/// absolute address; `off` a static slot offset; `abs` an absolute address;
/// `k` an index into the constant tables; `imm` an immediate integer; `t` a
/// jump target (instruction index); `shift` the wrap shift `64 - bits`;
/// `desc` an index into the array descriptors; `inst` the frame slot where a
/// function block instance starts; `code` a code-block index; `i` and `lim`
/// a FOR variable and its limit.
#[allow(missing_docs)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Op {
    /// No operation (left where an instruction was removed).
    Nop,
    /// `d := constants[k]`.
    LoadK { d: Slot, k: u32 },
    /// `d := imm` (sign-extended 32-bit immediate).
    LoadI { d: Slot, imm: i32 },
    /// `d := s`.
    Mov { d: Slot, s: Slot },
    /// `d := mem[abs]`.
    LoadAbs { d: Slot, abs: u32 },
    /// `mem[abs] := s`.
    StoreAbs { abs: u32, s: Slot },
    /// `d := mem[mem[p] + off]`.
    LoadInd { d: Slot, p: Slot, off: u32 },
    /// `mem[mem[p] + off] := s`.
    StoreInd { p: Slot, off: u32, s: Slot },
    /// `d := base + off` (absolute address of a frame slot).
    AddrOf { d: Slot, off: Slot },
    /// `d := mem[p] + off` (address arithmetic on a pointer).
    AddrAdd { d: Slot, p: Slot, off: u32 },
    /// Checked 1-D element load: `d := frame[arr + (idx - lo) * stride]` using array descriptor `desc`.
    LoadElem { d: Slot, idx: Slot, desc: u32 },
    /// Checked 1-D element store.
    StoreElem { idx: Slot, s: Slot, desc: u32 },
    /// Element address: `d := d + offset + checked(idx - lo) * stride` where
    /// `d` holds the array's absolute address on entry (descriptor `desc`).
    ElemAddr { d: Slot, idx: Slot, desc: u32 },
    /// Element address in the current frame:
    /// `d := base + offset + checked(idx - lo) * stride` (descriptor `desc`).
    ElemRef { d: Slot, idx: Slot, desc: u32 },
    /// Linearised multi-dimensional index step: `acc := acc * len + checked(idx - lo)`.
    IndexStep { acc: Slot, idx: Slot, desc: u32 },

    /// Signed add wrapped at `64 - shift` bits.
    AddS {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Unsigned add wrapped at `64 - shift` bits.
    AddU {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Signed add of an immediate.
    AddSI {
        d: Slot,
        a: Slot,
        imm: i32,
        shift: u8,
    },
    /// Signed subtract.
    SubS {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Unsigned subtract.
    SubU {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Signed multiply.
    MulS {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Unsigned multiply.
    MulU {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Signed divide (truncating); faults on zero.
    DivS {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Unsigned divide; faults on zero.
    DivU {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Signed MOD (sign of the dividend); faults on zero.
    ModS {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Unsigned MOD; faults on zero.
    ModU {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Signed MOD by a non-zero immediate.
    ModSI {
        d: Slot,
        a: Slot,
        imm: i32,
        shift: u8,
    },
    /// Signed negation.
    NegS { d: Slot, a: Slot, shift: u8 },
    /// Integer power `a ** b` (b >= 0), wrapping.
    PowS {
        d: Slot,
        a: Slot,
        b: Slot,
        shift: u8,
    },
    /// Signed ABS, wrapping.
    AbsS { d: Slot, a: Slot, shift: u8 },

    /// REAL add.
    AddF32 { d: Slot, a: Slot, b: Slot },
    /// REAL subtract.
    SubF32 { d: Slot, a: Slot, b: Slot },
    /// REAL multiply.
    MulF32 { d: Slot, a: Slot, b: Slot },
    /// REAL divide (IEEE: x/0 gives an infinity or NaN).
    DivF32 { d: Slot, a: Slot, b: Slot },
    /// REAL negation.
    NegF32 { d: Slot, a: Slot },
    /// REAL power.
    PowF32 { d: Slot, a: Slot, b: Slot },
    /// REAL math function.
    MathF32 { d: Slot, a: Slot, f: MathFn },
    /// LREAL add.
    AddF64 { d: Slot, a: Slot, b: Slot },
    /// LREAL subtract.
    SubF64 { d: Slot, a: Slot, b: Slot },
    /// LREAL multiply.
    MulF64 { d: Slot, a: Slot, b: Slot },
    /// LREAL divide.
    DivF64 { d: Slot, a: Slot, b: Slot },
    /// LREAL negation.
    NegF64 { d: Slot, a: Slot },
    /// LREAL power.
    PowF64 { d: Slot, a: Slot, b: Slot },
    /// LREAL math function.
    MathF64 { d: Slot, a: Slot, f: MathFn },

    /// Bitwise AND (also BOOL AND).
    And { d: Slot, a: Slot, b: Slot },
    /// Bitwise OR.
    Or { d: Slot, a: Slot, b: Slot },
    /// Bitwise XOR.
    Xor { d: Slot, a: Slot, b: Slot },
    /// BOOL NOT.
    NotB { d: Slot, a: Slot },
    /// Bit-string NOT masked to `64 - shift` bits.
    NotW { d: Slot, a: Slot, shift: u8 },
    /// `d := a AND NOT b` (BOOL).
    AndN { d: Slot, a: Slot, b: Slot },
    /// `d := a OR NOT b` (BOOL).
    OrN { d: Slot, a: Slot, b: Slot },
    /// Shifts/rotations of a `bits`-wide bit string by `n` (slot `b`).
    Shift {
        d: Slot,
        a: Slot,
        b: Slot,
        kind: ShiftKind,
        bits: u8,
    },

    /// Signed comparison (also for unsigned up to 32 bits, TIME, dates).
    CmpS { d: Slot, a: Slot, b: Slot, cmp: Cmp },
    /// Unsigned 64-bit comparison.
    CmpU { d: Slot, a: Slot, b: Slot, cmp: Cmp },
    /// REAL comparison.
    CmpF32 { d: Slot, a: Slot, b: Slot, cmp: Cmp },
    /// LREAL comparison.
    CmpF64 { d: Slot, a: Slot, b: Slot, cmp: Cmp },
    /// Signed comparison with an immediate.
    CmpSI {
        d: Slot,
        a: Slot,
        imm: i32,
        cmp: Cmp,
    },
    /// String comparison.
    CmpStr { d: Slot, a: Slot, b: Slot, cmp: Cmp },

    /// Conversion.
    Convert { d: Slot, a: Slot, conv: Conv },
    /// `d := a * b + c` on REAL (each operation rounded as written, no
    /// fused rounding); `c` is in the `Operand` word that follows.
    MulAddF32 { d: Slot, a: Slot, b: Slot },
    /// `d := a * b + c` on LREAL; `c` is in the following `Operand` word.
    MulAddF64 { d: Slot, a: Slot, b: Slot },
    /// The extra operand of the instruction before it (never executed on
    /// its own: the instruction before it consumes it).
    Operand { s: Slot },
    /// Conditional move: `if c { d := s }` (SEL).
    CMov { d: Slot, c: Slot, s: Slot },
    /// Signed MIN/MAX: `d := if (a < b) == min { a } else { b }`.
    MinMaxS {
        d: Slot,
        a: Slot,
        b: Slot,
        max: bool,
    },
    /// Unsigned 64-bit MIN/MAX.
    MinMaxU {
        d: Slot,
        a: Slot,
        b: Slot,
        max: bool,
    },
    /// REAL MIN/MAX.
    MinMaxF32 {
        d: Slot,
        a: Slot,
        b: Slot,
        max: bool,
    },
    /// LREAL MIN/MAX.
    MinMaxF64 {
        d: Slot,
        a: Slot,
        b: Slot,
        max: bool,
    },
    /// MUX: `d := slots[first + k]` for k = value of `k`, faulting if `k >= n`.
    Mux {
        d: Slot,
        k: Slot,
        first: Slot,
        n: u16,
    },
    /// Duration times REAL/LREAL factor (TIME * REAL), rounding to ns.
    MulTimeF64 { d: Slot, a: Slot, b: Slot },
    /// Duration divided by LREAL.
    DivTimeF64 { d: Slot, a: Slot, b: Slot },

    /// String copy (truncated to the destination's capacity).
    StrMov { d: Slot, s: Slot },
    /// String function, arguments in consecutive slots from `a`.
    StrCall { d: Slot, a: Slot, f: StrFn },
    /// Set string `d` to the constant string `k`.
    StrConst { d: Slot, k: u32 },
    /// Convert a scalar of type `ty` (index into the type list) to its literal text.
    ToStr { d: Slot, a: Slot, ty: u8 },
    /// Parse string `a` as a value of type `ty`.
    FromStr { d: Slot, a: Slot, ty: u8 },

    /// Unconditional jump.
    Jmp { t: Target },
    /// Jump if the BOOL slot is FALSE.
    Jz { c: Slot, t: Target },
    /// Jump if the BOOL slot is TRUE.
    Jnz { c: Slot, t: Target },
    /// Jump if `a cmp imm` is FALSE (fused compare and branch on signed values).
    JnCmpSI {
        a: Slot,
        imm: i32,
        cmp: Cmp,
        t: Target,
    },
    /// Jump if `a cmp b` is FALSE (signed).
    JnCmpS {
        a: Slot,
        b: Slot,
        cmp: Cmp,
        t: Target,
    },

    /// Array fill (`FOR i := start TO lim DO arr[i] := v; END_FOR` with
    /// `i` already set to start): when every index is inside the array and
    /// `lim + 1` fits the type, stores `v` in all elements and sets
    /// `i := lim + 1`; otherwise does nothing (the loop that follows runs as
    /// written and faults where it would).
    FillElems {
        i: Slot,
        v: Slot,
        lim: i32,
        desc: u16,
        shift: u8,
    },
    /// Jump if the BOOL array element `frame[desc][idx]` is FALSE (checked index).
    JzElem { idx: Slot, desc: u32, t: Target },
    /// Jump if the BOOL array element is TRUE.
    JnzElem { idx: Slot, desc: u32, t: Target },
    /// `d := d + b` (signed, wrapped), then jump to `t` if `d cmp imm`
    /// (a WHILE loop stepping its variable just before its test).
    AddBr {
        d: Slot,
        b: Slot,
        imm: i16,
        t: u16,
        cmp: Cmp,
        shift: u8,
    },
    /// Jump if `a cmp b` is FALSE on REAL values (NaN compares FALSE, so it jumps).
    JnCmpF32 {
        a: Slot,
        b: Slot,
        cmp: Cmp,
        t: Target,
    },
    /// Jump if `a cmp b` is FALSE on LREAL values.
    JnCmpF64 {
        a: Slot,
        b: Slot,
        cmp: Cmp,
        t: Target,
    },
    /// FOR back edge: `i := i + step`, then jump to `t` while
    /// `i <= lim` (`step > 0`) or `i >= lim` (`step < 0`). The test uses the
    /// exact sum, so a loop up to its type's largest value ends.
    ForNext {
        i: Slot,
        lim: i32,
        t: Target,
        step: i16,
        shift: u8,
    },
    /// As `ForNext` with the limit in a slot.
    ForNextS {
        i: Slot,
        lim: Slot,
        t: Target,
        step: i16,
        shift: u8,
    },

    /// `d := frame[idx + bias]`: an element of a one-slot-per-element frame
    /// array whose index the compiler proved in range (the control
    /// variable of an enclosing FOR loop over a constant range inside the
    /// array bounds, never written in the loop body). The array check is
    /// gone; the executor still keeps the access inside the frame.
    LoadElemU { d: Slot, idx: Slot, bias: i32 },
    /// `frame[idx + bias] := s`, proved in range as for `LoadElemU`.
    StoreElemU { idx: Slot, s: Slot, bias: i32 },
    /// Loop superinstruction: a `StoreElem` whose next instruction is an
    /// `AddBr` stepping `idx` and jumping back here (a WHILE loop whose
    /// body is one element store, such as striking multiples in a sieve).
    /// Runs the pair until the `AddBr` test fails, then continues after
    /// it, in one dispatch; the `AddBr` stays in place as the second word.
    StoreStep { idx: Slot, s: Slot, desc: u32 },
    /// Loop superinstruction: a `ForNext` whose target `t` is a
    /// `JzElem` (`when` TRUE) or `JnzElem` (`when` FALSE) on `i` that jumps
    /// back here (a FOR loop whose body is guarded by `IF arr[i] THEN`).
    /// Steps `i` over every iteration the element test would skip, then
    /// continues at `t + 1` (the body), at `t` (the index is out of range:
    /// the test faults there) or after the loop.
    ForScan {
        i: Slot,
        lim: i32,
        t: u16,
        desc: u16,
        step: i8,
        shift: u8,
        when: bool,
    },

    /// Call a user FB body (code block `code`) on the instance at frame slot `inst`.
    CallFb { code: u32, inst: Slot },
    /// Call a user FB on the instance whose absolute address is in slot `p`.
    CallFbInd { code: u32, p: Slot },
    /// Call a native FB on the instance at frame slot `inst`.
    CallNative { fb: NativeFb, inst: Slot },
    /// Call a native FB on the instance whose address is in slot `p`.
    CallNativeInd { fb: NativeFb, p: Slot },
    /// Call a function: reset its static frame, run its code at its frame base.
    CallFn { code: u32 },
    /// Copies `n` slots from address `mem[s]` to address `mem[d]` (aggregates by value).
    MemCopy { d: Slot, s: Slot, n: u32 },
    /// `d := current clock value` (PLC_CLOCK).
    Clock { d: Slot },
    /// Return from the current code block.
    Ret,
    /// One call of the SFC chart `chart` (index into `Image::charts`) on
    /// the current instance: evolution, then action control.
    Sfc { chart: u32 },
}

/// Sign-extends or zero-extends `x` from `64 - shift` bits.
#[inline(always)]
pub fn wrap_s(x: u64, shift: u8) -> u64 {
    (((x << shift) as i64) >> shift) as u64
}

/// Zero-extends `x` from `64 - shift` bits.
#[inline(always)]
pub fn wrap_u(x: u64, shift: u8) -> u64 {
    (x << shift) >> shift
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ops_stay_small() {
        assert!(
            std::mem::size_of::<Op>() <= 16,
            "{}",
            std::mem::size_of::<Op>()
        );
    }

    #[test]
    fn wrapping() {
        assert_eq!(wrap_s(32768, 48) as i64, -32768);
        assert_eq!(wrap_s(u64::MAX, 48) as i64, -1);
        assert_eq!(wrap_u(256, 56), 0);
        assert_eq!(wrap_u(u64::MAX, 0), u64::MAX);
    }
}
