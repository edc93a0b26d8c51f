//! What the checker knows about declarations: POUs, variables, globals.

use super::consts::Const;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::PouKind;
use indexmap::IndexMap;
use std::collections::HashMap;

/// A resolved initial value.
#[derive(Debug, Clone, PartialEq)]
pub enum ConstInit {
    /// A scalar in slot encoding.
    Scalar(u64),
    /// A string value.
    Str(String),
    /// Array elements in order (missing trailing elements keep their default).
    Array(Vec<ConstInit>),
    /// Struct fields by member index.
    Struct(Vec<(usize, ConstInit)>),
}

/// Where a variable lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Storage {
    /// At a slot of the current frame.
    Frame(u32),
    /// At an absolute address (globals, located variables).
    Abs(u32),
    /// The frame slot holds the address of the variable (VAR_IN_OUT).
    Ref(u32),
}

/// A declared variable.
#[derive(Debug, Clone)]
pub struct VarInfo {
    /// Name as declared.
    pub name: String,
    /// Type.
    pub ty: TypeId,
    /// Section.
    pub kind: MemberKind,
    /// Where it lives.
    pub storage: Storage,
    /// CONSTANT.
    pub constant: bool,
    /// Folded value of a CONSTANT with an initializer.
    pub value: Option<Const>,
    /// Initial value.
    pub init: Option<ConstInit>,
    /// Normalised located address (`%IX0.1`).
    pub location: Option<String>,
}

/// A checked POU.
#[derive(Debug, Clone)]
pub struct PouInfo {
    /// Name as declared.
    pub name: String,
    /// Kind.
    pub kind: PouKind,
    /// Position of the AST: (unit index, item index).
    pub ast: (usize, usize),
    /// Instance/frame type (for FBs and programs: `TypeKind::Pou`).
    pub ty: TypeId,
    /// Function result type (VOID for none).
    pub ret: TypeId,
    /// Variables by case-folded name, in declaration order.
    pub vars: IndexMap<String, VarInfo>,
    /// Keys of VAR_INPUT, VAR_IN_OUT, VAR_OUTPUT in declaration order (call interface).
    pub params: Vec<String>,
    /// Code block index.
    pub code: crate::ir::op::CodeIdx,
    /// Frame size before temporaries.
    pub vars_size: u32,
    /// Constant slots of the frame: `(slot, value)`.
    pub consts: Vec<(crate::ir::op::Slot, u64)>,
    /// Declaration span.
    pub span: Span,
    /// Declared after `{attribute 'no_check'}`: no implicit check calls.
    pub no_check: bool,
}

/// Layout state of a POU while declarations are resolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LayoutState {
    /// Not started.
    Pending,
    /// Being computed (a second visit means a cycle).
    InProgress,
    /// Computed.
    Done,
}

/// The declarations, resolved: what the body builders and the linker read
/// (and never change).
#[derive(Debug, Default)]
pub(crate) struct Model {
    /// Every POU, in source order.
    pub pous: Vec<PouInfo>,
    /// POU index by case-folded name.
    pub pou_index: HashMap<String, usize>,
    /// User types by case-folded name.
    pub type_ids: HashMap<String, TypeId>,
    /// Declared initial values of user types.
    pub type_inits: HashMap<TypeId, ConstInit>,
    /// The structure each structure declared `EXTENDS` extends.
    pub struct_bases: HashMap<TypeId, TypeId>,
    /// The structures that hold a UNION, with its members (unions.rs).
    pub unions: HashMap<TypeId, super::unions::UnionInfo>,
    /// Enumeration values by case-folded name: (enum type, value).
    pub enum_values: HashMap<String, Vec<(TypeId, i64)>>,
    /// Values of the enumerations declared `qualified_only`, by
    /// case-folded name: they are written `Type.Value` only (E433).
    pub qualified_enum_values: HashMap<String, Vec<TypeId>>,
    /// The enumerations declared after `{attribute 'strict'}`: never
    /// converted to or from an integer implicitly (enum_int.rs).
    pub strict_enums: std::collections::HashSet<TypeId>,
    /// Globals by case-folded name, in declaration order.
    pub globals: IndexMap<String, VarInfo>,
    /// Per POU (case-folded name) whose references are initialised once
    /// per initialisation: the frame slot that says it was done, and its
    /// type (`ref_inits.rs`).
    pub ref_init_guards: HashMap<String, (u32, TypeId)>,
    /// The declarations (by span) of variables fresh at each call whose
    /// initial value the body computes (`computed_inits.rs`).
    pub computed_inits: std::collections::HashSet<crate::source::Span>,
    /// The retention of each global declared RETAIN, NON_RETAIN or
    /// PERSISTENT, by case-folded name.
    pub global_retention: HashMap<String, crate::ir::type_table::Retention>,
    /// Located variables of PROGRAMs declared RETAIN or PERSISTENT:
    /// `(name, absolute address, type, persistent)`.
    pub retained_located: Vec<(String, u32, TypeId, bool)>,
    /// Which POU bodies were emitted (the linker places only those).
    pub emitted: Vec<bool>,
    /// Case-folded names of the POUs whose bodies the host provides, by
    /// `Op::CallHost` index.
    pub host_pous: Vec<String>,
    /// Charts follow IEC 60848 evolution (`--grafcet`) instead of IEC
    /// 61131-3's.
    pub grafcet: bool,
    /// The files in the CODESYS V3 / TwinCAT dialect, where CODESYS's
    /// implicit integer conversions are accepted (implicit_int.rs).
    pub codesys_files: std::collections::HashSet<crate::source::FileId>,
    /// The user's TwinCAT files (`CompileOptions::checked_files`).
    pub checked_files: std::collections::HashSet<crate::source::FileId>,
    /// The files of library projects (`CompileOptions::library_files`).
    pub library_files: std::collections::HashSet<crate::source::FileId>,
    /// Methods, inheritance and interfaces (empty without OOP).
    pub oop: super::oop::OopInfo,
    /// The structure types of generic inputs (`x : ANY_NUM`), with their
    /// class (any_params.rs).
    pub any_types: HashMap<TypeId, super::any_params::GenericClass>,
    /// Emit only the plain instruction forms: no fused superinstructions,
    /// no bounds checks dropped by the FOR loop range (`Options::optimize`
    /// off).
    pub unoptimized: bool,
}

impl Model {
    /// The default initial value of a type (zero, empty string, first enum value).
    pub(crate) fn default_init(&self, types: &TypeTable, ty: TypeId) -> ConstInit {
        if let Some(ci) = self.type_inits.get(&ty) {
            return ci.clone();
        }
        match &types.get(ty).kind {
            TypeKind::Enum { values, .. } => {
                ConstInit::Scalar(values.first().map(|v| v.1 as u64).unwrap_or(0))
            }
            TypeKind::Subrange { lo, .. } => ConstInit::Scalar(*lo as u64),
            TypeKind::Str { .. } => ConstInit::Str(String::new()),
            _ => ConstInit::Scalar(0),
        }
    }
}
