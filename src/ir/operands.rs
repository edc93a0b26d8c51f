//! The operands of an instruction, as the one instruction list
//! ([`super::op_list`]) declares them: each field with its role. Relocation
//! (constant slots are numbered after emission), the emitter (jump
//! patching, retargeting a result), the fusion pass and the link-time
//! verifier that lets the executor skip per-operand bounds checks all read
//! operands through [`operands`] and [`shape`], which are generated from
//! that list; nothing here lists instructions by hand.
//!
//! [`Operand`] is the closed set of roles. Its users match it without a
//! wildcard, so a new role cannot be added without every user (above all
//! the verifier) saying what it does with it.

use super::image::CodeKind;
use super::op::{
    ArrayIdx, ChartIdx, CodeIdx, ConstIdx, HostIdx, NativeFb, Op, ScalarTypeIdx, ShortTarget, Slot,
    StrConstIdx, Target,
};

/// How an instruction uses a single frame slot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Read.
    In,
    /// Written with the instruction's result only (the emitter may point it
    /// at another slot).
    Out,
    /// Written beside other effects, or holding more than a plain result.
    Def,
    /// Read and written (accumulators, loop variables).
    InOut,
}

/// What a code block called with an instance slot is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Callee {
    /// A user FB body (code-block index): its instance is its frame.
    Fb(CodeIdx),
    /// A native FB: its instance is its pins.
    Native(NativeFb),
}

/// How an instruction uses an array descriptor, which says how much of it
/// must lie inside the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArrayUse {
    /// Only address arithmetic (the address is checked where it is used).
    Any,
    /// The whole array (`offset + len * stride`) lies in the frame.
    Span,
    /// Elements are read or written in the frame without a bounds check:
    /// the whole array lies in the frame and `stride >= 1`.
    Elems,
    /// As `Elems` with one slot per element (filled as one range).
    Dense,
}

/// One operand of an instruction, by role.
#[derive(Debug, PartialEq, Eq)]
pub enum Operand<'a> {
    /// A frame slot.
    Slot(&'a mut Slot, Access),
    /// The first of a run of consecutive frame slots read, and its length.
    Run(&'a mut Slot, u32),
    /// The frame slot where a callee's instance starts.
    Instance(&'a mut Slot, Callee),
    /// A jump target.
    Target(&'a mut Target),
    /// A 16-bit jump target (not patched by the emitter).
    ShortTarget(&'a mut ShortTarget),
    /// An index into `Image::consts`.
    Const(ConstIdx),
    /// An index into `Image::str_consts`.
    StrConst(StrConstIdx),
    /// An index into `Image::arrays`.
    Array(ArrayIdx, ArrayUse),
    /// An index into `Image::scalar_types`.
    ScalarType(ScalarTypeIdx),
    /// A code-block index that must be of the given kind.
    Code(CodeIdx, CodeKind),
    /// An index into `Image::charts`.
    Chart(ChartIdx),
    /// An index into `Image::hosts`.
    Host(HostIdx),
    /// An absolute memory address.
    Abs(u32),
}

/// How an instruction relates to its neighbours.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// It stands alone.
    Single,
    /// The next instruction is its `Operand` word, consumed with it.
    TakesOperandWord,
    /// It is the operand word of the instruction before it (never a jump target).
    OperandWord,
    /// A loop superinstruction; the check says whether its partner
    /// instruction is still in place at `ops[at]` (the executor relies on it).
    Fused(fn(&[Op], usize) -> bool),
}

/// Turns one field of the list into the visitor call its role asks for.
macro_rules! role {
    ($f:ident, $x:ident, Out) => {
        $f(Operand::Slot($x, Access::Out))
    };
    ($f:ident, $x:ident, Def) => {
        $f(Operand::Slot($x, Access::Def))
    };
    ($f:ident, $x:ident, InOut) => {
        $f(Operand::Slot($x, Access::InOut))
    };
    ($f:ident, $x:ident, In) => {
        $f(Operand::Slot($x, Access::In))
    };
    ($f:ident, $x:ident, Run($len:ident)) => {
        $f(Operand::Run($x, u32::from(*$len)))
    };
    ($f:ident, $x:ident, Run($len:literal)) => {
        $f(Operand::Run($x, $len))
    };
    ($f:ident, $x:ident, FbInstance($code:ident)) => {
        $f(Operand::Instance($x, Callee::Fb(*$code)))
    };
    ($f:ident, $x:ident, NativeInstance($fb:ident)) => {
        $f(Operand::Instance($x, Callee::Native(*$fb)))
    };
    ($f:ident, $x:ident, Target) => {
        $f(Operand::Target($x))
    };
    ($f:ident, $x:ident, ShortTarget) => {
        $f(Operand::ShortTarget($x))
    };
    ($f:ident, $x:ident, Const) => {
        $f(Operand::Const(*$x))
    };
    ($f:ident, $x:ident, StrConst) => {
        $f(Operand::StrConst(*$x))
    };
    ($f:ident, $x:ident, Array($use:ident)) => {
        $f(Operand::Array(ArrayIdx::from(*$x), ArrayUse::$use))
    };
    ($f:ident, $x:ident, ScalarType) => {
        $f(Operand::ScalarType(*$x))
    };
    ($f:ident, $x:ident, Code($kind:ident)) => {
        $f(Operand::Code(*$x, CodeKind::$kind))
    };
    ($f:ident, $x:ident, Chart) => {
        $f(Operand::Chart(*$x))
    };
    ($f:ident, $x:ident, Host) => {
        $f(Operand::Host(*$x))
    };
    ($f:ident, $x:ident, Abs) => {
        $f(Operand::Abs(*$x))
    };
    ($f:ident, $x:ident, Data) => {
        let _ = $x;
    };
}

/// Refuses, at compile time, a typed index declared as plain `Data`
/// (the verifier would not check it). The other direction needs no rule
/// here: every other role hands its field to an [`Operand`] variant of one
/// index type (`Array` also takes the 16-bit form, through `From`), so a
/// field of another type does not compile there.
macro_rules! type_fits_role {
    ($ty:ident, Data) => {
        type_fits_role!(@data $ty)
    };
    ($ty:ident, $role:ident) => {};
    (@data Slot) => { type_fits_role!(@refuse Slot) };
    (@data Target) => { type_fits_role!(@refuse Target) };
    (@data ShortTarget) => { type_fits_role!(@refuse ShortTarget) };
    (@data ConstIdx) => { type_fits_role!(@refuse ConstIdx) };
    (@data StrConstIdx) => { type_fits_role!(@refuse StrConstIdx) };
    (@data ArrayIdx) => { type_fits_role!(@refuse ArrayIdx) };
    (@data ShortArrayIdx) => { type_fits_role!(@refuse ShortArrayIdx) };
    (@data ScalarTypeIdx) => { type_fits_role!(@refuse ScalarTypeIdx) };
    (@data CodeIdx) => { type_fits_role!(@refuse CodeIdx) };
    (@data ChartIdx) => { type_fits_role!(@refuse ChartIdx) };
    (@data HostIdx) => { type_fits_role!(@refuse HostIdx) };
    (@data $ty:ident) => {};
    (@refuse $ty:ident) => {
        compile_error!(concat!("a `", stringify!($ty), "` field declared `Data`"));
    };
}

/// The shape an instruction declares (none: it stands alone).
macro_rules! shape {
    () => {
        Shape::Single
    };
    (TakesOperandWord) => {
        Shape::TakesOperandWord
    };
    (OperandWord) => {
        Shape::OperandWord
    };
    (Fused($check:path)) => {
        Shape::Fused($check)
    };
}

/// Generates [`operands`] and [`shape`] from the instruction list.
macro_rules! define_operands {
    ($(
        $(#[$meta:meta])*
        $name:ident $({ $($field:ident : $ty:ident => $role:ident $(($($arg:tt)*))?),* $(,)? })?
        $(@ $shape:ident $(($partner:path))?)?;
    )*) => {
        /// Calls `f` on every operand of `op` that is not plain data, in
        /// field order, with its role.
        pub fn operands<'a>(op: &'a mut Op, f: &mut impl FnMut(Operand<'a>)) {
            match op {
                $( Op::$name $({ $($field),* })? => {
                    $($(
                        type_fits_role!($ty, $role);
                        role!(f, $field, $role $(($($arg)*))?);
                    )*)?
                } )*
            }
        }

        /// How `op` relates to its neighbours.
        pub fn shape(op: &Op) -> Shape {
            match op {
                $( Op::$name { .. } => shape!($($shape $(($partner))?)?), )*
            }
        }

        /// One instance of every instruction, each field a different small
        /// value (slot fields distinct), for tests that must cover them all.
        #[cfg(test)]
        pub fn examples() -> Vec<Op> {
            vec![$({
                let mut next = 0u8;
                let mut _value = || {
                    next += 1;
                    next
                };
                Op::$name $({ $($field: example::Example::example(_value())),* })?
            }),*]
        }
    };
}

super::op_list::for_each_op!(define_operands);

/// Calls `f` on every frame-relative slot operand of `op` (destinations,
/// sources, pointer slots, run starts, instance bases). Absolute addresses,
/// jump targets and table indexes are not slots and are not visited.
pub fn for_each_slot(op: &mut Op, f: &mut impl FnMut(&mut Slot)) {
    operands(op, &mut |o| match o {
        Operand::Slot(s, _) | Operand::Run(s, _) | Operand::Instance(s, _) => f(s),
        Operand::Target(_)
        | Operand::ShortTarget(_)
        | Operand::Const(_)
        | Operand::StrConst(_)
        | Operand::Array(..)
        | Operand::ScalarType(_)
        | Operand::Code(..)
        | Operand::Chart(_)
        | Operand::Host(_)
        | Operand::Abs(_) => {}
    });
}

/// The jump target of a branch instruction (the 32-bit targets the
/// emitter patches).
pub fn target_mut(op: &mut Op) -> Option<&mut Target> {
    let mut found = None;
    operands(op, &mut |o| {
        if let Operand::Target(t) = o {
            found = Some(t);
        }
    });
    found
}

/// The frame slot an instruction writes by name. (Array elements, memory
/// reached through addresses and called code are not named slots.)
pub struct Writes<'a> {
    /// The frame slot written by name, if any.
    pub slot: Option<&'a mut Slot>,
    /// Whether that slot only receives the instruction's result, so the
    /// emitter may point it elsewhere (false for accumulators, loop
    /// variables and slots written beside other effects).
    pub result: bool,
}

/// What `op` writes, from the roles of its fields (`Out`: a result;
/// `Def`, `InOut`: written, not a plain result).
pub fn writes(op: &mut Op) -> Writes<'_> {
    let mut w = Writes {
        slot: None,
        result: false,
    };
    operands(op, &mut |o| {
        if let Operand::Slot(s, access) = o {
            let result = match access {
                Access::In => return,
                Access::Out => true,
                Access::Def | Access::InOut => false,
            };
            w = Writes {
                slot: Some(s),
                result,
            };
        }
    });
    w
}

/// Field values for [`examples`].
#[cfg(test)]
mod example {
    use crate::ir::op::{
        ArrayIdx, ChartIdx, Cmp, CodeIdx, ConstIdx, Conv, HostIdx, MathFn, NativeFb, ScalarTypeIdx,
        ShiftKind, ShortArrayIdx, ShortTarget, Slot, StrConstIdx, StrFn, Target,
    };

    /// A value of a field type made from a small number.
    pub trait Example {
        fn example(n: u8) -> Self;
    }

    macro_rules! from_number {
        ($($t:ty),*) => { $(impl Example for $t {
            fn example(n: u8) -> Self {
                n.into()
            }
        })* };
    }
    from_number!(u16, u32, i16, i32);

    macro_rules! index_from_number {
        ($($t:ident),*) => { $(impl Example for $t {
            fn example(n: u8) -> Self {
                $t::new(n.into())
            }
        })* };
    }
    index_from_number!(
        Slot,
        Target,
        ShortTarget,
        ConstIdx,
        StrConstIdx,
        ArrayIdx,
        ShortArrayIdx,
        CodeIdx,
        ChartIdx,
        HostIdx,
        ScalarTypeIdx
    );

    impl Example for u8 {
        fn example(n: u8) -> Self {
            n
        }
    }
    impl Example for i8 {
        fn example(n: u8) -> Self {
            n as i8
        }
    }
    impl Example for bool {
        fn example(n: u8) -> Self {
            n % 2 == 1
        }
    }
    impl Example for Cmp {
        fn example(_: u8) -> Self {
            Cmp::Le
        }
    }
    impl Example for Conv {
        fn example(_: u8) -> Self {
            Conv::ToBool
        }
    }
    impl Example for MathFn {
        fn example(_: u8) -> Self {
            MathFn::Sqrt
        }
    }
    impl Example for ShiftKind {
        fn example(_: u8) -> Self {
            ShiftKind::Rol
        }
    }
    impl Example for StrFn {
        fn example(_: u8) -> Self {
            StrFn::Concat
        }
    }
    impl Example for NativeFb {
        fn example(_: u8) -> Self {
            NativeFb::Ton
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_instruction_has_an_example_and_a_name() {
        let all = examples();
        assert_eq!(all.len(), Op::NAMES.len());
        for (op, name) in all.iter().zip(Op::NAMES) {
            assert_eq!(op.name(), *name);
        }
    }

    #[test]
    fn an_instruction_writes_at_most_one_named_slot() {
        for mut op in examples() {
            let mut written = 0;
            operands(&mut op, &mut |o| {
                if matches!(o, Operand::Slot(_, a) if a != Access::In) {
                    written += 1;
                }
            });
            assert!(written <= 1, "{op:?}");
        }
    }

    #[test]
    fn relocation_reaches_every_slot_field() {
        // Every example's fields differ, so moving all slots by 100 changes
        // exactly the slot fields; the verifier sees the same ones.
        for op in examples() {
            let mut moved = op;
            let mut n = 0;
            for_each_slot(&mut moved, &mut |s| {
                *s = s.offset(100);
                n += 1;
            });
            assert_eq!(n > 0, moved != op, "{op:?}");
        }
    }

    #[test]
    fn branches_expose_their_target() {
        let c = Slot::new(1);
        let mut jz = Op::Jz {
            c,
            t: Target::new(7),
        };
        *target_mut(&mut jz).expect("a branch") = Target::new(9);
        assert_eq!(
            jz,
            Op::Jz {
                c,
                t: Target::new(9)
            }
        );
        assert!(target_mut(&mut Op::Ret).is_none());
        let mut load = Op::LoadK {
            d: Slot::new(3),
            k: ConstIdx::new(4),
        };
        let w = writes(&mut load);
        assert!(w.result && w.slot.is_some_and(|s| *s == Slot::new(3)));
    }
}
