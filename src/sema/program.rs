//! The program being built: the append-only tables that body emission and
//! linking fill (memory, code blocks, constant pools, array descriptors,
//! charts, the call graph) and that become the [`crate::ir::image::Image`].
//! Pools are interned, so a value is stored once however often it is used.

use super::declare::normalize_address;
use crate::diagnostics::Diagnostics;
use crate::elementary::ElemType;
use crate::ir::chart::Chart;
use crate::ir::image::{ArrayDesc, CodeBlock, StringInit};
use crate::ir::op::{ArrayIdx, CodeIdx, ConstIdx, ScalarTypeIdx, StrConstIdx};
use crate::ir::type_table::{TypeId, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{AddrSize, DirectAddress};
use indexmap::{IndexMap, IndexSet};

/// The output tables of one compilation.
#[derive(Debug, Default)]
pub(crate) struct Program {
    /// Initial contents of the PLC memory.
    pub memory: Vec<u64>,
    /// Memory exhaustion has been reported.
    memory_exhausted: bool,
    /// Most slots of absolute memory (the configurable data limit); 0
    /// until set, meaning [`super::DEFAULT_MAX_DATA_BYTES`].
    pub(super) data_limit_slots: usize,
    /// Located addresses (`%IX0.1`) with their slot and type.
    pub located: IndexMap<String, (u32, TypeId)>,
    /// Where each entry of `located` was first written (same order).
    pub located_spans: Vec<Span>,
    /// String variables and temporaries (index = string id).
    pub strings: Vec<StringInit>,
    /// Code blocks (index = code number).
    pub codes: Vec<CodeBlock>,
    /// 64-bit constants of `LoadK`.
    pub consts: IndexSet<u64>,
    /// Constant strings.
    pub str_consts: IndexSet<String>,
    /// Array descriptors.
    pub arrays: Vec<ArrayDesc>,
    /// Elementary types of `ToStr`/`FromStr`.
    pub scalar_types: IndexSet<ElemType>,
    /// The byte layouts of the aggregates references are taken of, by
    /// type (`RefMake`'s codes from `ir::refs::FIRST_AGGREGATE_LAYOUT`).
    pub byte_layouts: IndexMap<TypeId, crate::ir::byte_layout::ByteLayout>,
    /// Call graph edges between code blocks (for recursion detection).
    pub calls: Vec<(CodeIdx, CodeIdx, Span)>,
    /// The calls among them of a method on the caller's own instance
    /// (`M()`, `THIS^.M()`): a cycle of those is recursion for certain.
    pub own_instance_calls: std::collections::HashSet<(CodeIdx, CodeIdx)>,
    /// Function-frame relocations: (code block, instruction, callee POU).
    pub fixups: Vec<(CodeIdx, usize, usize)>,
    /// Step tables of chart bodies.
    pub charts: Vec<Chart>,
    /// Hidden method variables reached through interfaces, whose offsets
    /// the linker fills in: (FB's POU, variable key) (`sema/oop/calls.rs`).
    pub oop_offsets: Vec<(usize, String)>,
}

impl Program {
    /// Reserves `size` slots of absolute memory.
    pub(super) fn alloc_abs(&mut self, diags: &mut Diagnostics, size: u32) -> u32 {
        let at = self.memory.len();
        let limit = self.data_limit();
        if at.saturating_add(size as usize) > limit {
            if !self.memory_exhausted {
                self.memory_exhausted = true;
                diags.error(
                    "E120",
                    Span::default(),
                    format!(
                        "the program needs more than {} of data, the memory limit",
                        format_bytes(limit * 8)
                    ),
                );
            }
            // Nothing is allocated; the program will not link.
            return at as u32;
        }
        self.memory.resize(at + size as usize, 0);
        at as u32
    }

    /// The data limit in slots.
    pub(super) fn data_limit(&self) -> usize {
        if self.data_limit_slots == 0 {
            super::DEFAULT_MAX_DATA_BYTES / 8
        } else {
            self.data_limit_slots
        }
    }

    /// Interns a 64-bit constant.
    pub(super) fn konst(&mut self, v: u64) -> ConstIdx {
        ConstIdx::new(self.consts.insert_full(v).0 as u32)
    }

    /// Interns a constant string.
    pub(super) fn str_const(&mut self, s: &str) -> StrConstIdx {
        let i = match self.str_consts.get_index_of(s) {
            Some(i) => i,
            None => self.str_consts.insert_full(s.to_string()).0,
        };
        StrConstIdx::new(i as u32)
    }

    /// Index of an elementary type in the `ToStr`/`FromStr` list.
    pub(super) fn scalar_index(&mut self, e: ElemType) -> ScalarTypeIdx {
        ScalarTypeIdx::new(self.scalar_types.insert_full(e).0 as u8)
    }

    /// Adds an array descriptor (one per access site: it carries the span).
    pub(super) fn array_desc(&mut self, d: ArrayDesc) -> ArrayIdx {
        self.arrays.push(d);
        ArrayIdx::new(self.arrays.len() as u32 - 1)
    }

    /// Absolute slot of a located variable (shared by every declaration of
    /// the same address).
    pub(super) fn located_slot(
        &mut self,
        types: &TypeTable,
        diags: &mut Diagnostics,
        a: &DirectAddress,
        ty: TypeId,
    ) -> Option<u32> {
        let key = normalize_address(a);
        let elem = types.scalar(ty);
        let ok = match (a.size, elem) {
            (AddrSize::Bit, Some(ElemType::Bool)) => true,
            (AddrSize::Bit, _) => false,
            (size, Some(e)) => {
                let bits = match size {
                    AddrSize::Byte => 8,
                    AddrSize::Word => 16,
                    AddrSize::Dword => 32,
                    _ => 64,
                };
                e.bits() == bits || (bits == 32 && matches!(e, ElemType::Time))
            }
            _ => false,
        };
        if !ok {
            diags.error(
                "E207",
                a.span,
                format!(
                    "`{}` cannot hold a {}: the address size does not match the type",
                    a.text,
                    types.name(ty)
                ),
            );
            return None;
        }
        if let Some(&(addr, prev)) = self.located.get(&key) {
            if prev != ty {
                diags.error(
                    "E207",
                    a.span,
                    format!(
                        "`{}` is already declared as {}, not {}",
                        a.text,
                        types.name(prev),
                        types.name(ty)
                    ),
                );
                return None;
            }
            return Some(addr);
        }
        let addr = self.alloc_abs(diags, 1);
        self.located.insert(key, (addr, ty));
        self.located_spans.push(a.span);
        Some(addr)
    }
}

/// `bytes` as KiB, MiB or GiB when a whole number of them, else bytes.
pub(super) fn format_bytes(bytes: usize) -> String {
    for (unit, shift) in [("GiB", 30), ("MiB", 20), ("KiB", 10)] {
        if bytes >= 1 << shift && bytes.is_multiple_of(1 << shift) {
            return format!("{} {unit}", bytes >> shift);
        }
    }
    format!("{bytes} bytes")
}

/// [`format_bytes`] of a count that may exceed `usize`.
pub(super) fn format_bytes_u64(bytes: u64) -> String {
    match usize::try_from(bytes) {
        Ok(b) => format_bytes(b),
        Err(_) => format!("{bytes} bytes"),
    }
}
