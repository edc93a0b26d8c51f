//! Generic inputs of user POUs (CODESYS V3, TwinCAT 3): a VAR_INPUT of a
//! FUNCTION, FUNCTION_BLOCK or METHOD declared `ANY` or one of the narrower
//! `ANY_<class>` takes an argument of any type of its class. In the body
//! the input is a structure of three fields the call fills
//! (`any_args.rs`): `TypeClass` (the argument's `__SYSTEM.TYPE_CLASS`),
//! `pValue` (a `POINTER TO BYTE` to the argument: a byte view, §23 of
//! docs/semantics.md) and `diSize` (its size in bytes, as `SIZEOF`).
//!
//! This file holds the declaration side: the classes, the type of such
//! an input, the enumeration `TYPE_CLASS` with CODESYS's values, and the
//! type class of an argument's type.

use super::declare::Declarer;
use super::refs::intern_ref;
use crate::elementary::ElemType;
use crate::ir::type_table::{Member, RefFlavor, TypeDef, TypeId, TypeKind, TypeTable};
use crate::syntax::ast::{Ident, Pou, PouKind, TypeSpec, VarBlock, VarDecl, VarKind};

/// The name of the built-in enumeration of type classes (CODESYS's
/// `__SYSTEM.TYPE_CLASS`; a type named with a namespace is the type of its
/// last name, so `__SYSTEM.TYPE_CLASS` is this one).
pub(super) const TYPE_CLASS: &str = "TYPE_CLASS";

/// `__SYSTEM.TYPE_CLASS`'s values as CODESYS documents them (the Base
/// Interfaces library lists the same numbers for its `TypeClass`).
const TYPE_CLASS_VALUES: [&str; 49] = [
    "TYPE_BOOL",
    "TYPE_BIT",
    "TYPE_BYTE",
    "TYPE_WORD",
    "TYPE_DWORD",
    "TYPE_LWORD",
    "TYPE_SINT",
    "TYPE_INT",
    "TYPE_DINT",
    "TYPE_LINT",
    "TYPE_USINT",
    "TYPE_UINT",
    "TYPE_UDINT",
    "TYPE_ULINT",
    "TYPE_REAL",
    "TYPE_LREAL",
    "TYPE_STRING",
    "TYPE_WSTRING",
    "TYPE_TIME",
    "TYPE_DATE",
    "TYPE_DATEANDTIME",
    "TYPE_TIMEOFDAY",
    "TYPE_POINTER",
    "TYPE_REFERENCE",
    "TYPE_SUBRANGE",
    "TYPE_ENUM",
    "TYPE_ARRAY",
    "TYPE_PARAMS",
    "TYPE_USERDEF",
    "TYPE_NONE",
    "TYPE_ANY",
    "TYPE_ANYBIT",
    "TYPE_ANYDATE",
    "TYPE_ANYINT",
    "TYPE_ANYNUM",
    "TYPE_ANYREAL",
    "TYPE_LAZY",
    "TYPE_LTIME",
    "TYPE_BITCONST",
    "TYPE_UXINT",
    "TYPE_XWORD",
    "TYPE_XINT",
    "TYPE_XSTRING",
    "TYPE_VARLENARRAY",
    "TYPE_ANYSTRING",
    "TYPE_VECTOR",
    "TYPE_LDATE",
    "TYPE_LDATEANDTIME",
    "TYPE_LTIMEOFDAY",
];

/// Type class numbers used below (indexes into [`TYPE_CLASS_VALUES`]).
mod tc {
    pub const BOOL: u32 = 0;
    pub const BYTE: u32 = 2;
    pub const LWORD: u32 = 5;
    pub const SINT: u32 = 6;
    pub const LINT: u32 = 9;
    pub const USINT: u32 = 10;
    pub const ULINT: u32 = 13;
    pub const REAL: u32 = 14;
    pub const LREAL: u32 = 15;
    pub const STRING: u32 = 16;
    pub const WSTRING: u32 = 17;
    pub const TIME: u32 = 18;
    pub const DATE: u32 = 19;
    pub const DT: u32 = 20;
    pub const TOD: u32 = 21;
    pub const POINTER: u32 = 22;
    pub const SUBRANGE: u32 = 24;
    pub const ENUM: u32 = 25;
    pub const ARRAY: u32 = 26;
    pub const USERDEF: u32 = 28;
    pub const LTIME: u32 = 37;
    pub const LDATE: u32 = 46;
    pub const LDT: u32 = 47;
    pub const LTOD: u32 = 48;
}

/// A generic type a user POU's input may be declared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum GenericClass {
    Any,
    Elementary,
    Magnitude,
    Num,
    Real,
    Int,
    Signed,
    Unsigned,
    Duration,
    Bit,
    String,
    Date,
}

impl GenericClass {
    /// Every class with its name.
    const ALL: [(GenericClass, &'static str); 12] = [
        (GenericClass::Any, "ANY"),
        (GenericClass::Elementary, "ANY_ELEMENTARY"),
        (GenericClass::Magnitude, "ANY_MAGNITUDE"),
        (GenericClass::Num, "ANY_NUM"),
        (GenericClass::Real, "ANY_REAL"),
        (GenericClass::Int, "ANY_INT"),
        (GenericClass::Signed, "ANY_SIGNED"),
        (GenericClass::Unsigned, "ANY_UNSIGNED"),
        (GenericClass::Duration, "ANY_DURATION"),
        (GenericClass::Bit, "ANY_BIT"),
        (GenericClass::String, "ANY_STRING"),
        (GenericClass::Date, "ANY_DATE"),
    ];

    /// The class a type name (any case) names.
    pub(crate) fn from_name(name: &str) -> Option<GenericClass> {
        Self::ALL
            .iter()
            .find(|(_, n)| n.eq_ignore_ascii_case(name))
            .map(|(c, _)| *c)
    }

    /// The class's name.
    pub(crate) fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(c, _)| *c == self)
            .map_or("ANY", |(_, n)| n)
    }

    /// True when an argument of type class `t` belongs to the class (the
    /// hierarchy of IEC 61131-3's generic types, which CODESYS follows;
    /// BIT is read as BOOL, so TYPE_BIT never occurs).
    pub(crate) fn accepts(self, t: u32) -> bool {
        let int = (tc::SINT..=tc::ULINT).contains(&t);
        let real = t == tc::REAL || t == tc::LREAL;
        let duration = t == tc::TIME || t == tc::LTIME;
        let date = (tc::DATE..=tc::TOD).contains(&t) || (tc::LDATE..=tc::LTOD).contains(&t);
        let string = t == tc::STRING || t == tc::WSTRING;
        let bit = (tc::BOOL..=tc::LWORD).contains(&t);
        match self {
            GenericClass::Any => true,
            GenericClass::Elementary => int || real || duration || date || string || bit,
            GenericClass::Magnitude => int || real || duration,
            GenericClass::Num => int || real,
            GenericClass::Real => real,
            GenericClass::Int => int,
            GenericClass::Signed => (tc::SINT..=tc::LINT).contains(&t),
            GenericClass::Unsigned => (tc::USINT..=tc::ULINT).contains(&t),
            GenericClass::Duration => duration,
            GenericClass::Bit => bit,
            GenericClass::String => string,
            GenericClass::Date => date,
        }
    }

    /// True when every argument `other` accepts, this class accepts too
    /// (an input of class `other` may be passed on to one of this class).
    pub(crate) fn includes(self, other: GenericClass) -> bool {
        (0..TYPE_CLASS_VALUES.len() as u32).all(|t| !other.accepts(t) || self.accepts(t))
    }
}

/// The type class of a value of elementary type `e` (`None` for CHAR and
/// WCHAR, which `__SYSTEM.TYPE_CLASS` has no value for).
fn elem_class(e: ElemType) -> Option<u32> {
    Some(match e {
        ElemType::Bool => tc::BOOL,
        ElemType::Byte => tc::BYTE,
        ElemType::Word => 3,
        ElemType::Dword => 4,
        ElemType::Lword => tc::LWORD,
        ElemType::Sint => tc::SINT,
        ElemType::Int => 7,
        ElemType::Dint => 8,
        ElemType::Lint => tc::LINT,
        ElemType::Usint => tc::USINT,
        ElemType::Uint => 11,
        ElemType::Udint => 12,
        ElemType::Ulint => tc::ULINT,
        ElemType::Real => tc::REAL,
        ElemType::Lreal => tc::LREAL,
        ElemType::String => tc::STRING,
        ElemType::WString => tc::WSTRING,
        ElemType::Time => tc::TIME,
        ElemType::Ltime => tc::LTIME,
        ElemType::Date => tc::DATE,
        ElemType::Dt => tc::DT,
        ElemType::Tod => tc::TOD,
        ElemType::Ldate => tc::LDATE,
        ElemType::Ldt => tc::LDT,
        ElemType::Ltod => tc::LTOD,
        ElemType::Char | ElemType::Wchar => return None,
    })
}

/// The type class CODESYS gives an argument of type `t`; `None` for a
/// type it has no class for (CHAR, WCHAR) or that has none (VOID, ERROR).
pub(super) fn type_class_of(types: &TypeTable, t: TypeId) -> Option<u32> {
    Some(match &types.get(t).kind {
        TypeKind::Elem(e) => elem_class(*e)?,
        TypeKind::Str { wide, .. } => {
            if *wide {
                tc::WSTRING
            } else {
                tc::STRING
            }
        }
        TypeKind::Enum { .. } => tc::ENUM,
        TypeKind::Subrange { .. } => tc::SUBRANGE,
        TypeKind::Array { .. } => tc::ARRAY,
        TypeKind::Ref { .. } => tc::POINTER,
        TypeKind::Struct { .. } | TypeKind::Pou { .. } | TypeKind::NativeFb(_) => tc::USERDEF,
        TypeKind::OpenArray { .. } | TypeKind::Step | TypeKind::Void | TypeKind::Error => {
            return None;
        }
    })
}

/// The name of type class `t` (`TYPE_INT`).
pub(super) fn type_class_name(t: u32) -> &'static str {
    TYPE_CLASS_VALUES.get(t as usize).copied().unwrap_or("?")
}

/// The enumeration `TYPE_CLASS` (interned). CODESYS declares its values
/// as DWORDs; plcrun stores them as UDINT, the unsigned integer of the
/// same width, so that `UDINT_TO_INT(x.TypeClass)` (as TcUnit writes it)
/// takes one without a conversion of its own.
pub(super) fn type_class_enum(types: &mut TypeTable) -> TypeId {
    types.intern(TypeDef {
        name: TYPE_CLASS.to_string(),
        kind: TypeKind::Enum {
            base: ElemType::Udint,
            values: TYPE_CLASS_VALUES
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), i as i64))
                .collect(),
        },
        size: 1,
    })
}

/// The fields of a generic input, in slot order.
pub(super) const FIELDS: [&str; 3] = ["TypeClass", "pValue", "diSize"];

/// The structure a generic input of `class` is in its POU's body: one
/// type per class (named after it, so messages say `ANY_INT`), three
/// slots: the type class, a `POINTER TO BYTE` and the size in bytes.
fn any_struct(types: &mut TypeTable, class: GenericClass) -> TypeId {
    let class_ty = type_class_enum(types);
    let byte_ptr = intern_ref(types, TypeTable::elem(ElemType::Byte), RefFlavor::Pointer);
    let field = Member::field;
    let fields = vec![
        field(FIELDS[0], class_ty, 0),
        field(FIELDS[1], byte_ptr, 1),
        field(FIELDS[2], TypeTable::elem(ElemType::Dint), 2),
    ];
    types.intern(TypeDef {
        name: class.name().to_string(),
        kind: TypeKind::Struct { fields },
        size: FIELDS.len() as u32,
    })
}

impl Declarer<'_> {
    /// Makes `TYPE_CLASS` a type of the program unless a source declares
    /// a TYPE or POU of that name (then theirs is the one meant).
    pub(super) fn register_type_class(&mut self) {
        let key = TYPE_CLASS;
        if self.type_decls.contains_key(key) || self.model.pou_index.contains_key(key) {
            return;
        }
        let t = type_class_enum(&mut self.types);
        self.model.type_ids.insert(key.to_string(), t);
        // Strict, as TwinCAT has it: another enumeration (the Base
        // Interfaces' TypeClass) does not meet it without a conversion
        // (TcUnit writes `UDINT_TO_INT(x.TypeClass)`).
        self.model.strict_enums.insert(t);
    }

    /// The type of declaration `decl` of `block` in `pou` when it names a
    /// generic type (and no TYPE of that name exists): the structure of a
    /// generic input, or E212 where only a VAR_INPUT of a FUNCTION,
    /// FUNCTION_BLOCK or METHOD may have it.
    pub(super) fn any_param(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        decl: &VarDecl,
    ) -> Option<TypeId> {
        let TypeSpec::Named(id) = &decl.ty else {
            return None;
        };
        let class = GenericClass::from_name(&id.name)?;
        if self.type_decls.contains_key(&id.key()) {
            return None;
        }
        let input = match pou.kind {
            PouKind::Function | PouKind::FunctionBlock => block.kind == VarKind::Input,
            PouKind::Program => false,
        };
        let method_input = block.kind == VarKind::Local
            && decl
                .names
                .iter()
                .all(|n| self.is_method_input(pou, &n.key()));
        if !(input || method_input) {
            return Some(self.generic_refused(id));
        }
        let t = any_struct(&mut self.types, class);
        self.model.any_types.insert(t, class);
        Some(t)
    }

    /// The type of field `decl` of an interface's signature structure
    /// (oop/lower.rs) when it holds a generic input of one of the
    /// interface's method prototypes; `None` otherwise (then a generic
    /// type there is E212 as anywhere else).
    pub(super) fn any_signature_field(&mut self, decl: &VarDecl) -> Option<TypeId> {
        let TypeSpec::Named(id) = &decl.ty else {
            return None;
        };
        let class = GenericClass::from_name(&id.name)?;
        if self.type_decls.contains_key(&id.key()) {
            return None;
        }
        let prototypes = self.model.oop.interfaces.values();
        let params = prototypes.flat_map(|i| i.methods.values().flat_map(|m| &m.params));
        let input = |hidden: &str| {
            params
                .clone()
                .any(|p| p.hidden == hidden && p.input && !p.in_out)
        };
        if !decl.names.iter().all(|n| input(&n.key())) {
            return None;
        }
        let t = any_struct(&mut self.types, class);
        self.model.any_types.insert(t, class);
        Some(t)
    }

    /// True when `hidden` is the hidden variable of a method's VAR_INPUT
    /// in FB `pou` (methods' variables are the FB's, oop/lower.rs).
    fn is_method_input(&self, pou: &Pou, hidden: &str) -> bool {
        let Some(fb) = self.model.oop.fbs.get(&pou.name.key()) else {
            return false;
        };
        fb.versions
            .iter()
            .flat_map(|v| &v.params)
            .any(|p| p.hidden == hidden && p.input && !p.in_out)
    }

    /// E212 for generic type `id` where no generic is allowed.
    pub(super) fn generic_refused(&mut self, id: &Ident) -> TypeId {
        self.diags.error(
            "E212",
            id.span,
            format!(
                "`{}` is a generic type: only a VAR_INPUT of a FUNCTION, FUNCTION_BLOCK or METHOD may be declared with it (the argument of each call gives the type)",
                id.name
            ),
        );
        TypeTable::error()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_classes_nest_as_iec_draws_them() {
        use GenericClass::*;
        assert!(Any.includes(Num) && Num.includes(Int) && Num.includes(Real));
        assert!(Magnitude.includes(Duration) && !Num.includes(Duration));
        assert!(Elementary.includes(String) && !Elementary.includes(Any));
        assert!(!Int.includes(Num) && !Bit.includes(Int));
        assert_eq!(type_class_name(7), "TYPE_INT");
        assert_eq!(type_class_name(37), "TYPE_LTIME");
        assert_eq!(type_class_name(48), "TYPE_LTIMEOFDAY");
    }

    #[test]
    fn every_elementary_type_but_the_characters_has_a_class_its_own_class_accepts() {
        for e in ElemType::ALL {
            let Some(t) = elem_class(e) else {
                assert!(matches!(e, ElemType::Char | ElemType::Wchar));
                continue;
            };
            assert!(GenericClass::Elementary.accepts(t), "{e:?}");
        }
    }
}
