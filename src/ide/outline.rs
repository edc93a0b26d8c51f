//! A file's outline (its declarations as a tree), the ranges an editor can
//! fold, and the classification of every name for semantic highlighting.

use super::Analysis;
use super::symbol::{SymbolId, SymbolKind, VarSection};
use crate::source::{FileId, Span};
use crate::syntax::ast::{Body, Item, SfcElement, Stmt, StmtKind};

/// One entry of a file's outline.
#[derive(Debug, Clone, PartialEq)]
pub struct OutlineItem {
    /// The declared symbol.
    pub symbol: SymbolId,
    /// Its members that are declared in the same file.
    pub children: Vec<OutlineItem>,
}

/// A foldable region: byte offsets of its first and last character.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fold {
    /// Where it starts.
    pub start: u32,
    /// Where it ends.
    pub end: u32,
}

/// How a name is highlighted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TokenKind {
    /// A PROGRAM, FUNCTION_BLOCK, interface or standard block.
    Class,
    /// A structure or other type.
    Type,
    /// An enumeration type.
    Enum,
    /// An enumeration value.
    EnumMember,
    /// A FUNCTION.
    Function,
    /// A METHOD.
    Method,
    /// An input, output or in-out of a POU.
    Parameter,
    /// Any other variable.
    Variable,
    /// A structure field or a block's pin.
    Property,
    /// A step, action, transition, label, task or configuration element.
    Label,
}

/// The highlighting of one name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TokenMark {
    /// Where the name is.
    pub span: Span,
    /// What it is.
    pub kind: TokenKind,
    /// Where it is declared (not used).
    pub declaration: bool,
    /// A CONSTANT.
    pub readonly: bool,
}

impl Analysis {
    /// The declarations of `file`, top-level ones first, with their
    /// members nested.
    pub fn outline(&self, file: FileId) -> Vec<OutlineItem> {
        let in_file = |id: SymbolId| {
            self.symbol(id)
                .location
                .is_some_and(|span| span.file == file)
        };
        let mut roots: Vec<SymbolId> = (0..self.table.symbols.len() as u32)
            .map(SymbolId)
            .filter(|&id| in_file(id) && self.symbol(id).parent.is_none())
            .collect();
        roots.sort_by_key(|&id| self.symbol(id).location.map(|s| s.start));
        roots
            .into_iter()
            .map(|id| self.outline_item(id, &in_file, 0))
            .collect()
    }

    fn outline_item(
        &self,
        id: SymbolId,
        in_file: &dyn Fn(SymbolId) -> bool,
        depth: usize,
    ) -> OutlineItem {
        let children = if depth < 8 {
            self.table
                .children_of(id)
                .iter()
                .copied()
                .filter(|&c| in_file(c))
                .map(|c| self.outline_item(c, in_file, depth + 1))
                .collect()
        } else {
            Vec::new()
        };
        OutlineItem {
            symbol: id,
            children,
        }
    }

    /// The regions of `file` an editor can fold: POUs, methods, variable
    /// sections, types, compound statements, chart elements.
    pub fn folds(&self, file: FileId) -> Vec<Fold> {
        let mut spans = Vec::new();
        for item in &self.units[file.0 as usize].items {
            match item {
                Item::Pou(pou) => {
                    spans.push(pou.span);
                    spans.extend(pou.var_blocks.iter().map(|b| b.span));
                    body_folds(&pou.body, &mut spans);
                    for method in pou.oop.iter().flat_map(|o| &o.methods) {
                        spans.push(method.span);
                        spans.extend(method.var_blocks.iter().map(|b| b.span));
                        body_folds(&method.body, &mut spans);
                    }
                }
                Item::Types(types) => spans.extend(types.iter().map(|t| t.span)),
                Item::Configuration(c) => {
                    spans.push(c.span);
                    spans.extend(c.resources.iter().map(|r| r.span));
                }
                Item::Globals(block) => spans.push(block.span),
                Item::Interface(i) => spans.push(i.span),
            }
        }
        let text = self.text(file);
        spans
            .into_iter()
            .filter(|s| s.file == file)
            .filter(|s| {
                text.get(s.start as usize..s.end as usize)
                    .is_some_and(|t| t.contains('\n'))
            })
            .map(|s| Fold {
                start: s.start,
                end: s.end.saturating_sub(1).max(s.start),
            })
            .collect()
    }

    /// The classification of every name in `file`, in position order.
    pub fn tokens(&self, file: FileId) -> Vec<TokenMark> {
        self.occurrences_in(file)
            .iter()
            .map(|o| {
                let s = self.symbol(o.symbol);
                TokenMark {
                    span: o.span,
                    kind: token_kind(s.kind),
                    declaration: o.declaration,
                    readonly: s.constant,
                }
            })
            .collect()
    }
}

fn token_kind(kind: SymbolKind) -> TokenKind {
    match kind {
        SymbolKind::Program
        | SymbolKind::FunctionBlock
        | SymbolKind::Interface
        | SymbolKind::StandardBlock => TokenKind::Class,
        SymbolKind::Struct | SymbolKind::Alias => TokenKind::Type,
        SymbolKind::Enum => TokenKind::Enum,
        SymbolKind::EnumValue => TokenKind::EnumMember,
        SymbolKind::Function => TokenKind::Function,
        SymbolKind::Method => TokenKind::Method,
        SymbolKind::Variable(v) if v.is_interface() => TokenKind::Parameter,
        SymbolKind::Variable(VarSection::Local | VarSection::Temp | VarSection::External)
        | SymbolKind::Variable(VarSection::Inst)
        | SymbolKind::Variable(_)
        | SymbolKind::Global
        | SymbolKind::ProgramInstance => TokenKind::Variable,
        SymbolKind::Field | SymbolKind::StandardPin(_) => TokenKind::Property,
        SymbolKind::Step
        | SymbolKind::Action
        | SymbolKind::Transition
        | SymbolKind::Label
        | SymbolKind::Configuration
        | SymbolKind::Resource
        | SymbolKind::Task => TokenKind::Label,
    }
}

fn body_folds(body: &Body, out: &mut Vec<Span>) {
    match body {
        Body::St(stmts) => stmt_folds(stmts, out),
        Body::Il(_) => {}
        Body::Sfc(elements) => {
            for element in elements {
                match element {
                    SfcElement::Step(s) => out.push(s.span),
                    SfcElement::Transition(t) => out.push(t.span),
                    SfcElement::Action(a) => {
                        out.push(a.span);
                        body_folds(&a.body, out);
                    }
                    SfcElement::Statement(s) => stmt_folds(std::slice::from_ref(s), out),
                }
            }
        }
    }
}

fn stmt_folds(stmts: &[Stmt], out: &mut Vec<Span>) {
    for stmt in stmts {
        let inner: Vec<&[Stmt]> = match &stmt.kind {
            StmtKind::If {
                branches,
                else_branch,
            } => branches
                .iter()
                .map(|(_, b)| b.as_slice())
                .chain(else_branch.as_deref())
                .collect(),
            StmtKind::Case {
                arms, else_branch, ..
            } => arms
                .iter()
                .map(|a| a.body.as_slice())
                .chain(else_branch.as_deref())
                .collect(),
            StmtKind::For { body, .. }
            | StmtKind::While { body, .. }
            | StmtKind::Repeat { body, .. } => vec![body.as_slice()],
            StmtKind::Try {
                body,
                catch,
                finally,
            } => std::iter::once(body.as_slice())
                .chain(catch.iter().map(|(_, c)| c.as_slice()))
                .chain(finally.as_deref())
                .collect(),
            _ => continue,
        };
        out.push(stmt.span);
        for body in inner {
            stmt_folds(body, out);
        }
    }
}
