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

pub use crate::value::convert::Conv;
pub use crate::value::encode::{wrap_s, wrap_u};

pub use super::index::{
    ArrayIdx, ChartIdx, CodeIdx, ConstIdx, HostIdx, ScalarTypeIdx, ShortArrayIdx, ShortTarget,
    Slot, StrConstIdx, Target,
};

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
    /// `__PLCRUN_JSON_OF_SYMBOL(type name, pointer image)`: the JSON text
    /// of the value of that type the pointer designates, '' when there is
    /// none (`vm::json_of_symbol`; Tc3_JsonXml's `...FromSymbol` methods).
    JsonOfSymbol,
    /// `__PLCRUN_SYMBOL_FROM_JSON(json text, type name, pointer image)`:
    /// writes the value the JSON text gives into the value of that type
    /// the pointer designates; 1 in `d`, or 0 with nothing written
    /// (`vm::symbol_from_json`; Tc3_JsonXml's `SetSymbolFromJson`).
    SymbolFromJson,
}

/// The most characters of [`StrFn::JsonOfSymbol`]'s text (the capacity of
/// the STRING it is returned in).
pub const JSON_OF_SYMBOL_MAX: u32 = 8191;

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
    /// RTC (real-time clock, IEC 61131-3 edition 1)
    Rtc,
}

impl NativeFb {
    /// How many slots an instance occupies (its pins and hidden state, in
    /// the order `stdlib::interface` lists them). The verifier keeps a
    /// native instance inside its frame with it.
    pub fn instance_slots(self) -> u32 {
        match self {
            NativeFb::RTrig | NativeFb::FTrig | NativeFb::Sr | NativeFb::Rs => 3,
            NativeFb::Ctu(_) | NativeFb::Ctd(_) => 6,
            NativeFb::Ctud(_) => 10,
            NativeFb::Ton | NativeFb::Tof | NativeFb::Tp => 7,
            NativeFb::Rtc => 6,
        }
    }
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

/// Generates [`Op`] and its names from the list in [`super::op_list`].
macro_rules! define_op {
    ($(
        $(#[$meta:meta])*
        $name:ident $({ $($field:ident : $ty:ident => $role:ident $(($($arg:tt)*))?),* $(,)? })?
        $(@ $shape:ident $(($partner:path))?)?;
    )*) => {
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
        /// a FOR variable and its limit. The role of every field is declared in
        /// [`super::op_list`].
        #[allow(missing_docs)]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum Op {
            $( $(#[$meta])* $name $({ $($field: $ty),* })?, )*
        }

        impl Op {
            /// The name of every instruction, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($name)),*];

            /// The instruction's name (its variant name).
            pub fn name(&self) -> &'static str {
                match self {
                    $( Op::$name { .. } => stringify!($name), )*
                }
            }
        }
    };
}

super::op_list::for_each_op!(define_op);

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
