//! What an editor asks of the sources: diagnostics, the symbol under the
//! cursor, its definition and references, hover text, completion,
//! signature help, outlines, folding and renaming. `plcrun lsp` answers
//! the Language Server Protocol with it (docs/editors.md); it works on
//! byte offsets, the protocol layer converts positions.

mod collect;
mod complete;
mod doc_comment;
mod hover;
mod live_names;
mod outline;
mod rename;
mod resolve;
mod signature;
mod std_functions;
mod symbol;
mod table;
mod text_context;

pub use complete::{Completion, CompletionKind};
pub use hover::Hover;
pub use live_names::LiveName;
pub use outline::{Fold, OutlineItem, TokenKind, TokenMark};
pub use rename::RenameError;
pub use resolve::Occurrence;
pub use signature::{Signature, SignatureParam};
pub use std_functions::{StdFunction, std_function, std_functions};
pub use symbol::{Shape, Symbol, SymbolId, SymbolKind, VarSection};

use crate::diagnostics::Diagnostics;
use crate::driver::{CheckOptions, check};
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::ast::CompilationUnit;
use table::Table;

/// The sources of one project, checked and indexed.
pub struct Analysis {
    sources: SourceMap,
    units: Vec<CompilationUnit>,
    table: Table,
    /// Every declaration and use, ordered by file and position.
    occurrences: Vec<Occurrence>,
    diagnostics: Diagnostics,
}

impl Analysis {
    /// Checks `sources` as `plcrun check` would with `options`, and
    /// indexes their declarations and the uses of every name.
    pub fn new(sources: SourceMap, options: &CheckOptions) -> Analysis {
        let diagnostics = check(&sources, options).diagnostics;
        Analysis::with_diagnostics(sources, diagnostics)
    }

    /// Indexes `sources` whose diagnostics are already known.
    pub fn with_diagnostics(sources: SourceMap, diagnostics: Diagnostics) -> Analysis {
        let mut ignored = Diagnostics::new();
        let units: Vec<CompilationUnit> = sources
            .files()
            .iter()
            .enumerate()
            .map(|(i, f)| crate::syntax::parse_source(FileId(i as u32), f, &mut ignored))
            .collect();
        let table = collect::collect(&sources, &units);
        let mut occurrences = resolve::resolve(&table, &units);
        occurrences.extend(table.symbols.iter().enumerate().filter_map(|(i, s)| {
            Some(Occurrence {
                span: s.location?,
                symbol: SymbolId(i as u32),
                declaration: true,
            })
        }));
        occurrences.sort_by_key(|o| (o.span.file, o.span.start, !o.declaration));
        occurrences.dedup_by_key(|o| (o.span.file, o.span.start));
        Analysis {
            sources,
            units,
            table,
            occurrences,
            diagnostics,
        }
    }

    /// The files analysed.
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }

    /// What `plcrun check` reports for them.
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// The symbol `id`.
    pub fn symbol(&self, id: SymbolId) -> &Symbol {
        self.table.get(id)
    }

    /// All symbols, a [`SymbolId`] being an index into it.
    pub fn symbols(&self) -> &[Symbol] {
        &self.table.symbols
    }

    /// The declaration or use of a name at byte `offset` of `file` (the
    /// cursor may stand just after the name).
    pub fn occurrence_at(&self, file: FileId, offset: u32) -> Option<Occurrence> {
        let start = self.occurrences.partition_point(|o| o.span.file < file);
        self.occurrences[start..]
            .iter()
            .take_while(|o| o.span.file == file && o.span.start <= offset)
            .filter(|o| offset <= o.span.end)
            .last()
            .copied()
    }

    /// The symbol named at `offset`.
    pub fn symbol_at(&self, file: FileId, offset: u32) -> Option<SymbolId> {
        self.occurrence_at(file, offset).map(|o| o.symbol)
    }

    /// Where the name at `offset` is declared.
    pub fn definition(&self, file: FileId, offset: u32) -> Option<Span> {
        self.symbol(self.symbol_at(file, offset)?).location
    }

    /// Where the type of the name at `offset` is declared (a variable's
    /// structure, block or enumeration).
    pub fn type_definition(&self, file: FileId, offset: u32) -> Option<Span> {
        let id = self.symbol_at(file, offset)?;
        let symbol = self.symbol(id);
        if symbol.kind.is_type() {
            return symbol.location;
        }
        let mut shape = self.table.unalias(symbol.shape.as_ref()?);
        while let Shape::Array(inner) | Shape::Ref(inner) = shape {
            shape = self.table.unalias(&inner);
        }
        self.symbol(self.table.type_of_shape(&shape)?).location
    }

    /// Every place `id` is declared or used, in file and position order.
    pub fn references(&self, id: SymbolId) -> Vec<Occurrence> {
        self.occurrences
            .iter()
            .filter(|o| o.symbol == id)
            .copied()
            .collect()
    }

    /// The declarations and uses in `file`, in position order.
    pub fn occurrences_in(&self, file: FileId) -> &[Occurrence] {
        let start = self.occurrences.partition_point(|o| o.span.file < file);
        let end = self.occurrences.partition_point(|o| o.span.file <= file);
        &self.occurrences[start..end]
    }

    /// The symbols whose name contains `query` (any case), POUs, types,
    /// globals and methods: what a workspace symbol search lists.
    pub fn workspace_symbols(&self, query: &str) -> Vec<SymbolId> {
        let query = query.to_ascii_uppercase();
        self.table
            .symbols
            .iter()
            .enumerate()
            .filter(|(_, s)| s.location.is_some())
            .filter(|(_, s)| {
                s.parent.is_none()
                    || matches!(
                        s.kind,
                        SymbolKind::Method
                            | SymbolKind::Action
                            | SymbolKind::Step
                            | SymbolKind::Resource
                            | SymbolKind::Task
                            | SymbolKind::ProgramInstance
                    )
            })
            .filter(|(_, s)| s.key().contains(&query))
            .map(|(i, _)| SymbolId(i as u32))
            .collect()
    }

    /// The POU or method `offset` lies in, innermost first (a method,
    /// then its block), for name lookup at a cursor.
    fn scope_at(&self, file: FileId, offset: u32) -> Vec<SymbolId> {
        let contains = |s: &Symbol| {
            s.extent
                .is_some_and(|e| e.file == file && e.start <= offset && offset <= e.end)
        };
        let is_scope = |s: &Symbol| {
            matches!(
                s.kind,
                SymbolKind::Program
                    | SymbolKind::Function
                    | SymbolKind::FunctionBlock
                    | SymbolKind::Method
                    | SymbolKind::Interface
            )
        };
        let innermost = self
            .table
            .symbols
            .iter()
            .enumerate()
            .filter(|(_, s)| is_scope(s) && contains(s))
            .min_by_key(|(_, s)| s.extent.map(|e| e.end - e.start))
            .map(|(i, _)| SymbolId(i as u32))
            .or_else(|| self.pou_before(file, offset));
        let Some(id) = innermost else {
            return Vec::new();
        };
        match self.symbol(id).parent {
            Some(owner) if self.symbol(id).kind == SymbolKind::Method => vec![id, owner],
            _ => vec![id],
        }
    }

    /// The last POU that starts before `offset` in `file`: the scope of an
    /// unfinished edit that the parser could not close.
    fn pou_before(&self, file: FileId, offset: u32) -> Option<SymbolId> {
        self.table
            .symbols
            .iter()
            .enumerate()
            .filter(|(_, s)| {
                matches!(
                    s.kind,
                    SymbolKind::Program | SymbolKind::Function | SymbolKind::FunctionBlock
                )
            })
            .filter(|(_, s)| {
                s.extent
                    .is_some_and(|e| e.file == file && e.start <= offset)
            })
            .max_by_key(|(_, s)| s.extent.map(|e| e.start))
            .map(|(i, _)| SymbolId(i as u32))
    }

    fn text(&self, file: FileId) -> &str {
        &self.sources.file(file).text
    }
}
