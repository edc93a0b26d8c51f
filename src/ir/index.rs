//! Typed indices: frame slots, jump targets and the entries of an image's
//! tables. Each is its integer underneath (`#[repr(transparent)]`, the
//! width the instruction encoding has always used), so an [`super::op::Op`]
//! stays 16 bytes and reading one costs nothing; what the types add is
//! that a field of one kind cannot be filled with another, and that the
//! instruction list's roles and its field types must agree.
//!
//! `Debug` prints the bare number, so IR listings read as they always have.

use std::fmt;

/// Declares one index newtype over `$int` with `new`, `get` and `index`.
macro_rules! index_type {
    ($(#[$meta:meta])* $name:ident($int:ty)) => {
        $(#[$meta])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        #[repr(transparent)]
        pub struct $name($int);

        impl $name {
            /// The index with this number.
            #[inline(always)]
            pub const fn new(n: $int) -> Self {
                Self(n)
            }

            /// Its number.
            #[inline(always)]
            pub const fn get(self) -> $int {
                self.0
            }

            /// Its number as a `usize`, for indexing.
            #[inline(always)]
            pub const fn index(self) -> usize {
                self.0 as usize
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(&self.0, f)
            }
        }
    };
}

index_type!(
    /// A frame-relative slot index.
    Slot(u32)
);

impl Slot {
    /// The slot `n` slots after this one (element and member addressing).
    #[inline(always)]
    pub const fn offset(self, n: u32) -> Slot {
        Slot(self.0 + n)
    }
}

index_type!(
    /// An index into the instruction vector of a code block.
    Target(u32)
);
impl Target {
    /// The target a jump holds until the emitter patches it.
    pub const UNPATCHED: Target = Target(0);
}

index_type!(
    /// A jump target in 16 bits, for instructions that need the room.
    ShortTarget(u16)
);
index_type!(
    /// An index into `Image::consts`.
    ConstIdx(u32)
);
index_type!(
    /// An index into `Image::str_consts`.
    StrConstIdx(u32)
);
index_type!(
    /// An index into `Image::arrays`.
    ArrayIdx(u32)
);
index_type!(
    /// An index into `Image::arrays` in 16 bits, for instructions that need
    /// the room.
    ShortArrayIdx(u16)
);
index_type!(
    /// An index into `Image::codes`.
    CodeIdx(u32)
);
index_type!(
    /// An index into `Image::charts`.
    ChartIdx(u32)
);
index_type!(
    /// An index into `Image::hosts`: a FUNCTION or FUNCTION_BLOCK whose
    /// body the host registered.
    HostIdx(u32)
);
index_type!(
    /// An index into `Image::scalar_types`.
    ScalarTypeIdx(u8)
);

impl From<ShortTarget> for Target {
    fn from(t: ShortTarget) -> Target {
        Target(t.0.into())
    }
}

impl From<ShortArrayIdx> for ArrayIdx {
    fn from(d: ShortArrayIdx) -> ArrayIdx {
        ArrayIdx(d.0.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn debug_prints_the_bare_number() {
        assert_eq!(format!("{:?}", Slot::new(7)), "7");
        assert_eq!(format!("{:?}", ShortTarget::new(12)), "12");
        assert_eq!(format!("{:?}", ScalarTypeIdx::new(3)), "3");
    }

    #[test]
    fn indices_are_their_integers() {
        use std::mem::size_of;
        assert_eq!(size_of::<Slot>(), 4);
        assert_eq!(size_of::<ShortTarget>(), 2);
        assert_eq!(size_of::<ShortArrayIdx>(), 2);
        assert_eq!(size_of::<ScalarTypeIdx>(), 1);
        assert_eq!(Target::from(ShortTarget::new(9)), Target::new(9));
        assert_eq!(Slot::new(4).offset(3).index(), 7);
    }
}
