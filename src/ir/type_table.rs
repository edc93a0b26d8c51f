//! The table of all data types of a compiled program, with their memory
//! layout in slots. Shared by the checker (typing), the image (naming
//! variables from outside) and the runtime (reading and writing values).

use crate::elementary::ElemType;
use crate::ir::op::NativeFb;

/// Index of a type in a [`TypeTable`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TypeId(pub u32);

/// One dimension of an array: inclusive bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dim {
    /// Lower bound.
    pub lo: i64,
    /// Upper bound.
    pub hi: i64,
}

impl Dim {
    /// Number of elements.
    pub fn len(&self) -> u64 {
        (self.hi - self.lo + 1).max(0) as u64
    }

    /// True for an empty range (never produced by the checker).
    pub fn is_empty(&self) -> bool {
        self.hi < self.lo
    }
}

/// The row-major element number of `values` in an array of `dims`, if
/// every index is inside its bounds.
pub fn linear_index(dims: &[Dim], values: &[i128]) -> Option<u64> {
    let mut linear: u64 = 0;
    for (d, &v) in dims.iter().zip(values) {
        if v < i128::from(d.lo) || v > i128::from(d.hi) {
            return None;
        }
        linear = linear
            .checked_mul(d.len())?
            .checked_add((v - i128::from(d.lo)) as u64)?;
    }
    Some(linear)
}

/// How a member of a struct or POU may be used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemberKind {
    /// A struct field.
    Field,
    /// VAR_INPUT
    Input,
    /// VAR_OUTPUT
    Output,
    /// VAR_IN_OUT (the slot holds a pointer)
    InOut,
    /// VAR (private to the POU)
    Local,
    /// VAR_TEMP (reset at each call)
    Temp,
    /// VAR_EXTERNAL (the slot is unused; the global is accessed)
    External,
    /// An SFC step (type is the step record).
    Step,
    /// An SFC action's control record.
    Action,
    /// Hidden state of a native block.
    Hidden,
}

/// A named member with its slot offset.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    /// Name as declared.
    pub name: String,
    /// Type.
    pub ty: TypeId,
    /// Slot offset inside the parent.
    pub offset: u32,
    /// Role.
    pub kind: MemberKind,
    /// Declared CONSTANT.
    pub constant: bool,
    /// Declared in a RETAIN, NON_RETAIN or PERSISTENT block.
    pub retain: Retention,
}

impl Member {
    /// A plain structure field: not constant, retained as its parent.
    pub fn field(name: &str, ty: TypeId, offset: u32) -> Member {
        Member {
            name: name.to_string(),
            ty,
            offset,
            kind: MemberKind::Field,
            constant: false,
            retain: Retention::Inherit,
        }
    }
}

/// Whether a variable keeps its value over a restart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Retention {
    /// Not qualified: retained only as part of a retained FB instance or
    /// structure.
    #[default]
    Inherit,
    /// `NON_RETAIN`: never retained, even inside a retained FB instance.
    NonRetain,
    /// `RETAIN`.
    Retain,
    /// `PERSISTENT` (alone or with `RETAIN`).
    Persistent,
}

/// What a type is.
#[derive(Debug, Clone, PartialEq)]
pub enum TypeKind {
    /// An elementary type (one slot).
    Elem(ElemType),
    /// STRING/WSTRING with a maximum length (one slot: the string index).
    Str {
        /// WSTRING.
        wide: bool,
        /// Maximum length in characters.
        max: u32,
    },
    /// An array.
    Array {
        /// Dimensions.
        dims: Vec<Dim>,
        /// Element type.
        elem: TypeId,
    },
    /// `ARRAY[*, ...] OF elem`: the type of a VAR_IN_OUT whose bounds come
    /// with the argument. The parameter holds the argument's address, then
    /// its lower and upper bound per dimension ([`open_array_layout`]);
    /// the type itself has no size.
    OpenArray {
        /// Number of dimensions.
        rank: u32,
        /// Element type.
        elem: TypeId,
    },
    /// A structure.
    Struct {
        /// Fields in declaration order.
        fields: Vec<Member>,
    },
    /// An enumeration: values stored as integers of `base`.
    Enum {
        /// Storage type.
        base: ElemType,
        /// `(name, value)` in declaration order.
        values: Vec<(String, i64)>,
    },
    /// An integer subrange.
    Subrange {
        /// Base integer type.
        base: ElemType,
        /// Lower bound.
        lo: i64,
        /// Upper bound.
        hi: i64,
    },
    /// A native standard FB.
    NativeFb(NativeFb),
    /// A user FUNCTION_BLOCK or PROGRAM (its instance layout).
    Pou {
        /// Index of the POU's code block.
        code: crate::ir::op::CodeIdx,
        /// Members (variables, steps, actions) in declaration order.
        members: Vec<Member>,
        /// True for PROGRAM.
        program: bool,
    },
    /// An SFC step record: X, T, plus hidden activation time.
    Step,
    /// No value (a function without result).
    Void,
    /// Placeholder after an error (suppresses follow-up diagnostics).
    Error,
    /// A reference or pointer (one slot: see [`crate::ir::refs`]).
    Ref {
        /// The type of the variable it designates.
        target: TypeId,
        /// `REF_TO`, `POINTER TO` or `REFERENCE TO`.
        flavor: RefFlavor,
    },
}

/// Which reference type a [`TypeKind::Ref`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RefFlavor {
    /// IEC 61131-3 edition 3 `REF_TO`.
    RefTo,
    /// CODESYS `POINTER TO` (byte arithmetic).
    Pointer,
    /// CODESYS `REFERENCE TO` (dereferenced implicitly).
    Reference,
    /// The type of `NULL`, assignable to every reference type.
    Null,
}

/// A type with its name and size.
#[derive(Debug, Clone, PartialEq)]
pub struct TypeDef {
    /// Display name (`INT`, `ARRAY[0..3] OF BOOL`, `MyStruct`).
    pub name: String,
    /// What it is.
    pub kind: TypeKind,
    /// Size in slots.
    pub size: u32,
}

/// All types of a program. Elementary types come first, at ids equal to
/// their index in [`ElemType::ALL`].
#[derive(Debug, Clone)]
pub struct TypeTable {
    defs: Vec<TypeDef>,
}

/// Slot layout of an `ARRAY[*]` parameter: the address of the array it
/// refers to, then `lo, hi` for each dimension.
pub mod open_array_layout {
    /// Slots of a parameter of `rank` dimensions.
    pub fn size(rank: u32) -> u32 {
        1 + 2 * rank
    }
    /// Offset of dimension `k`'s lower bound (`k` from 0); the upper
    /// bound follows it.
    pub fn lower(k: u32) -> u32 {
        1 + 2 * k
    }
}

/// Slot layout of a step record.
pub mod step_layout {
    /// `.X`: active.
    pub const X: u32 = 0;
    /// `.T`: time since activation.
    pub const T: u32 = 1;
    /// Hidden: clock value at activation.
    pub const START: u32 = 2;
    /// Size in slots.
    pub const SIZE: u32 = 3;
}

impl Default for TypeTable {
    fn default() -> Self {
        Self::new()
    }
}

impl TypeTable {
    /// A table holding the elementary types, VOID, ERROR and the step record.
    pub fn new() -> TypeTable {
        let mut defs: Vec<TypeDef> = ElemType::ALL
            .iter()
            .map(|e| TypeDef {
                name: e.name().to_string(),
                kind: match e {
                    ElemType::String => TypeKind::Str {
                        wide: false,
                        max: 254,
                    },
                    ElemType::WString => TypeKind::Str {
                        wide: true,
                        max: 254,
                    },
                    _ => TypeKind::Elem(*e),
                },
                size: 1,
            })
            .collect();
        defs.push(TypeDef {
            name: "VOID".into(),
            kind: TypeKind::Void,
            size: 0,
        });
        defs.push(TypeDef {
            name: "<error>".into(),
            kind: TypeKind::Error,
            size: 1,
        });
        defs.push(TypeDef {
            name: "STEP".into(),
            kind: TypeKind::Step,
            size: step_layout::SIZE,
        });
        TypeTable { defs }
    }

    /// The id of an elementary type.
    pub fn elem(e: ElemType) -> TypeId {
        TypeId(ElemType::ALL.iter().position(|x| *x == e).unwrap_or(0) as u32)
    }

    /// The VOID type.
    pub fn void() -> TypeId {
        TypeId(ElemType::ALL.len() as u32)
    }

    /// The error placeholder type.
    pub fn error() -> TypeId {
        TypeId(ElemType::ALL.len() as u32 + 1)
    }

    /// The SFC step record type.
    pub fn step() -> TypeId {
        TypeId(ElemType::ALL.len() as u32 + 2)
    }

    /// Adds a type and returns its id.
    pub fn add(&mut self, def: TypeDef) -> TypeId {
        self.defs.push(def);
        TypeId(self.defs.len() as u32 - 1)
    }

    /// Replaces a type (used to complete recursive definitions).
    pub fn set(&mut self, id: TypeId, def: TypeDef) {
        self.defs[id.0 as usize] = def;
    }

    /// The definition of `id`.
    pub fn get(&self, id: TypeId) -> &TypeDef {
        &self.defs[id.0 as usize]
    }

    /// Whether `a` and `b` are both STRINGs or both WSTRINGs, of any
    /// lengths: one string's slot may be read as the other (a string's
    /// buffer keeps its own length).
    pub fn same_width_strings(&self, a: TypeId, b: TypeId) -> bool {
        matches!(
            (&self.get(a).kind, &self.get(b).kind),
            (TypeKind::Str { wide: x, .. }, TypeKind::Str { wide: y, .. }) if x == y
        )
    }

    /// Size in slots.
    pub fn size(&self, id: TypeId) -> u32 {
        self.get(id).size
    }

    /// The innermost element type of nested arrays (`id` itself
    /// otherwise).
    pub fn innermost(&self, mut id: TypeId) -> TypeId {
        while let TypeKind::Array { elem, .. } = self.get(id).kind {
            id = elem;
        }
        id
    }

    /// Display name.
    pub fn name(&self, id: TypeId) -> &str {
        &self.get(id).name
    }

    /// The elementary type a value of `id` is stored as (enums and
    /// subranges as their base), if it is a scalar.
    pub fn scalar(&self, id: TypeId) -> Option<ElemType> {
        match &self.get(id).kind {
            TypeKind::Elem(e) => Some(*e),
            TypeKind::Str { wide, .. } => Some(if *wide {
                ElemType::WString
            } else {
                ElemType::String
            }),
            TypeKind::Enum { base, .. } | TypeKind::Subrange { base, .. } => Some(*base),
            _ => None,
        }
    }

    /// Finds an existing type with the same definition, or adds it.
    pub fn intern(&mut self, def: TypeDef) -> TypeId {
        if let Some(i) = self.defs.iter().position(|d| *d == def) {
            return TypeId(i as u32);
        }
        self.add(def)
    }

    /// The members of a struct or POU type, if any.
    pub fn members(&self, id: TypeId) -> &[Member] {
        match &self.get(id).kind {
            TypeKind::Struct { fields } => fields,
            TypeKind::Pou { members, .. } => members,
            _ => &[],
        }
    }

    /// Number of types.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// True if the table is empty (never: elementary types are always present).
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::{Dim, linear_index};

    #[test]
    fn row_major_element_numbers() {
        let dims = [Dim { lo: 1, hi: 3 }, Dim { lo: 0, hi: 1 }];
        assert_eq!(linear_index(&dims, &[1, 0]), Some(0));
        assert_eq!(linear_index(&dims, &[2, 1]), Some(3));
        assert_eq!(linear_index(&dims, &[3, 1]), Some(5));
        assert_eq!(linear_index(&dims, &[4, 0]), None);
        assert_eq!(linear_index(&dims, &[0, 0]), None);
    }
}
