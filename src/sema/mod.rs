//! Semantic analysis and lowering: resolves every name, types every
//! expression (IEC implicit widening only), folds constants, and emits the
//! typed IR for each POU body in the same walk. All diagnostics are
//! collected; nothing stops at the first error.

mod bounds;
mod calls;
pub mod consts;
mod declare;
mod emit;
mod expr;
mod il;
mod link;
pub mod model;
mod sfc;
mod stdfuncs;
mod stmt;
mod typeck;

use crate::diagnostics::Diagnostics;
use crate::ir::image::{ArrayDesc, CodeBlock, Image, StringInit};
use crate::ir::types::{TypeId, TypeTable};
use crate::source::Span;
use crate::syntax::ast::CompilationUnit;
use crate::types::ElemType;
use indexmap::{IndexMap, IndexSet};
use model::{ConstInit, LayoutState, PouInfo, VarInfo};
use std::collections::HashMap;

/// What to build.
#[derive(Debug, Clone, Default)]
pub struct CompileOptions {
    /// The PROGRAM to run when there is no CONFIGURATION (or to pick one).
    pub program: Option<String>,
    /// Cycle time in nanoseconds for the implicit task.
    pub cycle_time: i64,
    /// Only check; do not require a runnable program.
    pub check_only: bool,
}

/// Checks and lowers parsed files into an [`Image`]. Returns `None` when
/// there were errors (all of them are in `diags`).
pub fn compile(
    units: &[CompilationUnit],
    options: &CompileOptions,
    diags: &mut Diagnostics,
) -> Option<Image> {
    let mut c = Compiler::new(units, diags);
    c.declare_all();
    c.emit_all();
    let image = c.link(options);
    if c.diags.has_errors() { None } else { image }
}

/// Upper bound of the whole PLC memory, in 8-byte slots (2 GiB).
pub const MAX_MEMORY_SLOTS: usize = 256 << 20;

/// Upper bound of one POU instance or structure, in slots.
pub const MAX_FRAME_SLOTS: u32 = 64 << 20;

/// State of one compilation.
pub(crate) struct Compiler<'a> {
    units: &'a [CompilationUnit],
    diags: &'a mut Diagnostics,
    types: TypeTable,
    pous: Vec<PouInfo>,
    pou_index: HashMap<String, usize>,
    pou_state: Vec<LayoutState>,
    type_decls: HashMap<String, (usize, usize, usize)>,
    type_ids: HashMap<String, TypeId>,
    type_state: HashMap<String, LayoutState>,
    type_inits: HashMap<TypeId, ConstInit>,
    enum_values: HashMap<String, Vec<(TypeId, i64)>>,
    globals: IndexMap<String, VarInfo>,
    located: HashMap<String, (u32, TypeId)>,
    memory: Vec<u64>,
    strings: Vec<StringInit>,
    codes: Vec<CodeBlock>,
    consts: IndexSet<u64>,
    str_consts: IndexSet<String>,
    arrays: Vec<ArrayDesc>,
    scalar_types: IndexSet<ElemType>,
    /// Call graph edges between code blocks (for recursion detection).
    calls: Vec<(u32, u32, Span)>,
    /// Emission state of each POU body.
    emit_state: Vec<LayoutState>,
    /// Function-frame relocations: (code block, instruction, callee POU).
    fixups: Vec<(u32, usize, usize)>,
    /// Memory exhaustion has been reported.
    memory_exhausted: bool,
    /// Step tables of chart bodies.
    charts: Vec<crate::ir::chart::Chart>,
    /// SFC blocks of the POU being emitted whose constant and pinned slots
    /// still need placing: (code block, constants, pin count).
    pending_blocks: Vec<(u32, IndexSet<u64>, u32)>,
    /// SFC blocks of the POU being emitted (they share its frame size).
    owned_blocks: Vec<u32>,
}

impl<'a> Compiler<'a> {
    fn new(units: &'a [CompilationUnit], diags: &'a mut Diagnostics) -> Compiler<'a> {
        Compiler {
            units,
            diags,
            types: TypeTable::new(),
            pous: Vec::new(),
            pou_index: HashMap::new(),
            pou_state: Vec::new(),
            type_decls: HashMap::new(),
            type_ids: HashMap::new(),
            type_state: HashMap::new(),
            type_inits: HashMap::new(),
            enum_values: HashMap::new(),
            globals: IndexMap::new(),
            located: HashMap::new(),
            memory: Vec::new(),
            strings: Vec::new(),
            codes: Vec::new(),
            consts: IndexSet::new(),
            str_consts: IndexSet::new(),
            arrays: Vec::new(),
            scalar_types: IndexSet::new(),
            calls: Vec::new(),
            emit_state: Vec::new(),
            fixups: Vec::new(),
            memory_exhausted: false,
            charts: Vec::new(),
            pending_blocks: Vec::new(),
            owned_blocks: Vec::new(),
        }
    }

    /// Reserves `size` slots of absolute memory.
    fn alloc_abs(&mut self, size: u32) -> u32 {
        let at = self.memory.len();
        if at + size as usize > MAX_MEMORY_SLOTS {
            if !self.memory_exhausted {
                self.memory_exhausted = true;
                self.diags.error(
                    "E206",
                    Span::default(),
                    format!(
                        "the program needs more than {} MiB of PLC memory",
                        (MAX_MEMORY_SLOTS * 8) >> 20
                    ),
                );
            }
            // Nothing is allocated; the program will not link.
            return at as u32;
        }
        self.memory.resize(at + size as usize, 0);
        at as u32
    }

    /// Interns a 64-bit constant.
    fn konst(&mut self, v: u64) -> u32 {
        self.consts.insert_full(v).0 as u32
    }

    /// Interns a constant string.
    fn str_const(&mut self, s: &str) -> u32 {
        match self.str_consts.get_index_of(s) {
            Some(i) => i as u32,
            None => self.str_consts.insert_full(s.to_string()).0 as u32,
        }
    }

    /// Index of an elementary type in the `ToStr`/`FromStr` list.
    fn scalar_index(&mut self, e: ElemType) -> u8 {
        self.scalar_types.insert_full(e).0 as u8
    }
}
