//! A compiled, linked program: code blocks, constants, array descriptors,
//! the initial memory image and the directory of runnable program instances.

use crate::elementary::ElemType;
use crate::ir::op::{CodeIdx, Op, Slot, StrConstIdx};
use crate::ir::type_table::{Member, TypeId, TypeTable};
use crate::source::Span;

/// What a code block belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CodeKind {
    /// A PROGRAM body (runs at its instance's base).
    Program,
    /// A FUNCTION_BLOCK body (runs at the called instance's base).
    FunctionBlock,
    /// A FUNCTION body (runs at its static frame).
    Function,
    /// An SFC action or transition condition (runs at the owner's base).
    Block,
}

/// One compiled body.
#[derive(Debug, Clone)]
pub struct CodeBlock {
    /// POU (or `POU.action`) name for messages.
    pub name: String,
    /// Kind.
    pub kind: CodeKind,
    /// The instructions; the last one is `Ret`.
    pub ops: Vec<Op>,
    /// Source span of each instruction (for runtime faults).
    pub spans: Vec<Span>,
    /// Slots reset at every call (VAR_TEMP, function locals): `(slot, value)`.
    pub entry_init: Vec<(Slot, u64)>,
    /// Strings reset at every call: `(slot holding the string index, constant string index)`.
    pub entry_strings: Vec<(Slot, StrConstIdx)>,
    /// For functions: absolute address of the static frame.
    pub frame: u32,
    /// Size of one frame/instance in slots.
    pub frame_size: u32,
    /// The `__TRY` regions of the block, in the order they were emitted
    /// (empty for almost every block).
    pub handlers: Vec<crate::ir::handler::Handler>,
}

/// Bounds of one array dimension used by checked indexing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArrayDesc {
    /// Slot offset of element 0 (relative to the base the instruction uses).
    pub offset: u32,
    /// Lower bound.
    pub lo: i64,
    /// Number of elements.
    pub len: u64,
    /// Slots per element.
    pub stride: u32,
    /// Source span of the indexing expression (for the fault message).
    pub span: Span,
}

/// The initial state of one string variable.
#[derive(Debug, Clone, PartialEq)]
pub struct StringInit {
    /// Maximum length in characters.
    pub max: u32,
    /// WSTRING.
    pub wide: bool,
    /// Initial value.
    pub init: String,
}

/// A variable reachable by name from outside (trace, stimulus, API).
#[derive(Debug, Clone, PartialEq)]
pub struct RootVar {
    /// Name as declared.
    pub name: String,
    /// Type.
    pub ty: TypeId,
    /// Absolute slot address.
    pub addr: u32,
    /// Role in the program (`Input`, `Output`, `Local`...).
    pub kind: crate::ir::type_table::MemberKind,
    /// Located address text, normalised (e.g. `%QX0.0.0.0.1`), if any.
    pub location: Option<String>,
    /// Declared CONSTANT.
    pub constant: bool,
}

/// The address a VAR_IN_OUT holds until a call connects it: outside any
/// memory, so an access through it faults (R999) instead of reaching a
/// variable, and `__ISVALIDREF` of it is FALSE.
pub const NOT_CONNECTED: u64 = u32::MAX as u64;

/// A program instance the scheduler runs.
#[derive(Debug, Clone)]
pub struct ProgramInstance {
    /// Instance name (the PROGRAM name when there is no configuration).
    pub name: String,
    /// The PROGRAM type name.
    pub type_name: String,
    /// Code block of its body.
    pub code: CodeIdx,
    /// Absolute base address of its instance memory.
    pub base: u32,
    /// Its type (for naming its variables).
    pub ty: TypeId,
    /// Task it runs under (index into `tasks`).
    pub task: usize,
    /// Copied before each run: `(from, to)` absolute slots (connected inputs).
    pub inputs: Vec<(u32, u32)>,
    /// Copied after each run: `(from, to)` absolute slots (connected outputs).
    pub outputs: Vec<(u32, u32)>,
}

/// A block the runtime runs outside the cycles: the `FB_init` calls of
/// the instances of a program instance or of the global lists before the
/// first cycle and after each reset, or their `FB_exit` calls when the
/// program is unloaded (`src/sema/instance_calls/`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InstanceCall {
    /// The code block (a method of the program, or a function).
    pub code: CodeIdx,
    /// The absolute base it runs at.
    pub base: u32,
    /// The absolute slot of its BOOL input (`bInitRetains` at start,
    /// `bInCopyCode` at exit), set before the run.
    pub flag: u32,
}

/// The methods an online change calls on an instance of a user FB whose
/// declaration changed (CODESYS and TwinCAT copy such an instance into
/// the new layout): `FB_exit` on the old instance before the copy, with
/// `bInCopyCode` TRUE, and `FB_reinit` on the new one after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CopyCalls {
    /// The FB's instance type.
    pub ty: TypeId,
    /// Its `FB_exit` (own or inherited) and the offset of `bInCopyCode`
    /// in the instance.
    pub exit: Option<(CodeIdx, u32)>,
    /// Its `FB_reinit` (own or inherited).
    pub reinit: Option<CodeIdx>,
}

/// A cyclic (or event) task.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Name.
    pub name: String,
    /// Interval in nanoseconds (0 for an event task).
    pub interval: i64,
    /// Priority (0 runs first).
    pub priority: i64,
    /// For SINGLE tasks: absolute slot of the triggering BOOL.
    pub single: Option<u32>,
}

/// A fully compiled program ready to run.
#[derive(Debug, Clone)]
pub struct Image {
    /// All code blocks.
    pub codes: Vec<CodeBlock>,
    /// 64-bit constants referenced by `LoadK`.
    pub consts: Vec<u64>,
    /// Constant strings referenced by `StrConst` and string resets.
    pub str_consts: Vec<String>,
    /// Array descriptors referenced by indexing instructions.
    pub arrays: Vec<ArrayDesc>,
    /// Initial contents of the whole memory.
    pub memory: Vec<u64>,
    /// Initial string variables (index = string id).
    pub strings: Vec<StringInit>,
    /// All types.
    pub types: TypeTable,
    /// Elementary type list used by `ToStr`/`FromStr` (index = `ty` operand).
    pub scalar_types: Vec<ElemType>,
    /// The byte layouts of the aggregates `RefMake` takes (its layout
    /// codes from `ir::refs::FIRST_AGGREGATE_LAYOUT` up index this).
    pub byte_layouts: Vec<crate::ir::byte_layout::ByteLayout>,
    /// Globals and located variables.
    pub globals: Vec<RootVar>,
    /// Program instances in execution order.
    pub programs: Vec<ProgramInstance>,
    /// Tasks.
    pub tasks: Vec<Task>,
    /// Step tables of the SFC bodies (referenced by `Op::Sfc`).
    pub charts: Vec<crate::ir::chart::Chart>,
    /// Names of the POUs whose bodies the host registered (referenced by
    /// `Op::CallHost`), in the order the compile options list them.
    pub hosts: Vec<String>,
    /// The retained values (RETAIN, PERSISTENT), in declaration order.
    pub retained: Vec<crate::ir::retained::RetainedVar>,
    /// The start calls, in order: the global lists', then each program
    /// instance's.
    pub start: Vec<InstanceCall>,
    /// The exit calls, in order: each program instance's (the last one
    /// first), then the global lists'.
    pub exit: Vec<InstanceCall>,
    /// Per user FB with `FB_exit` or `FB_reinit`, what an online change
    /// calls on its copied instances.
    pub copy_calls: Vec<CopyCalls>,
    /// Look-up of members and globals by name from outside the program
    /// (built by [`crate::ir::verify::verify`]).
    pub names: crate::ir::name_index::NameIndex,
}

impl Image {
    /// Member `name` (any case) of type `ty` that is a place of the
    /// instance (not a VAR_IN_OUT).
    pub fn member_named(&self, ty: TypeId, name: &str) -> Option<&Member> {
        self.names.member(&self.types, ty, name)
    }

    /// The global or located variable named `name` (any case).
    pub fn global_named(&self, name: &str) -> Option<&RootVar> {
        self.names.global(&self.globals, name)
    }

    /// How many instructions named `name` (an `Op` variant name, e.g.
    /// `"StoreStep"`) the code blocks hold; `None` when no instruction has
    /// that name. For tests outside the crate that check what the compiler
    /// emitted, without access to the instruction set itself.
    #[doc(hidden)]
    pub fn instruction_count(&self, name: &str) -> Option<usize> {
        Op::NAMES.contains(&name).then(|| {
            let ops = self.codes.iter().flat_map(|c| &c.ops);
            ops.filter(|op| op.name() == name).count()
        })
    }

    /// A readable listing of every code block (for `plcrun check --dump-ir`).
    pub fn dump(&self) -> String {
        use std::fmt::Write;
        let mut out = String::new();
        for (i, c) in self.codes.iter().enumerate() {
            let _ = writeln!(
                out,
                "code {i} `{}` ({:?}, frame {} slots, frame base {})",
                c.name, c.kind, c.frame_size, c.frame
            );
            for (pc, op) in c.ops.iter().enumerate() {
                let _ = writeln!(out, "  {pc:4}  {op:?}");
            }
            for h in &c.handlers {
                let _ = writeln!(
                    out,
                    "  __TRY {}..{}: __CATCH at {}, code into {}",
                    h.start,
                    h.end,
                    h.catch,
                    h.exception.get()
                );
            }
        }
        out
    }
}
