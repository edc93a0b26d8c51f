//! The symbol table of a workspace: every declaration of the parsed files,
//! and the maps names are looked up in.

use super::symbol::{Shape, Symbol, SymbolId, SymbolKind, VarSection};
use crate::stdlib::{ParamDir, interface, lookup_native};
use std::collections::HashMap;

/// The standard blocks plcrun runs natively, by name (the typed counters
/// of edition 3 included).
const STANDARD_BLOCKS: &[&str] = &[
    "R_TRIG",
    "F_TRIG",
    "SR",
    "RS",
    "TON",
    "TOF",
    "TP",
    "CTU",
    "CTD",
    "CTUD",
    "CTU_DINT",
    "CTD_DINT",
    "CTUD_DINT",
    "CTU_LINT",
    "CTD_LINT",
    "CTUD_LINT",
    "CTU_UDINT",
    "CTD_UDINT",
    "CTUD_UDINT",
    "CTU_ULINT",
    "CTD_ULINT",
    "CTUD_ULINT",
];

/// Every declared name and how to find it.
#[derive(Debug, Default)]
pub(crate) struct Table {
    /// All symbols; a [`SymbolId`] indexes this.
    pub symbols: Vec<Symbol>,
    /// POUs, types, interfaces and configurations by key.
    pub units: HashMap<String, SymbolId>,
    /// Global variables by key.
    pub globals: HashMap<String, SymbolId>,
    /// Enumeration values by key (unqualified use).
    pub enum_values: HashMap<String, Vec<SymbolId>>,
    /// Members of a symbol by key (variables of a POU, fields of a
    /// structure, steps of a chart...).
    children: HashMap<(SymbolId, String), SymbolId>,
    /// Members of a symbol in declaration order.
    ordered: HashMap<SymbolId, Vec<SymbolId>>,
    /// Symbols by where their name is declared.
    by_location: HashMap<crate::source::Span, SymbolId>,
}

impl Table {
    /// Adds `symbol`, registering it under its parent.
    pub fn add(&mut self, symbol: Symbol) -> SymbolId {
        let id = SymbolId(self.symbols.len() as u32);
        if let Some(parent) = symbol.parent {
            self.children.entry((parent, symbol.key())).or_insert(id);
            self.ordered.entry(parent).or_default().push(id);
        }
        if let Some(span) = symbol.location {
            self.by_location.entry(span).or_insert(id);
        }
        self.symbols.push(symbol);
        id
    }

    /// The symbol `id`.
    pub fn get(&self, id: SymbolId) -> &Symbol {
        &self.symbols[id.0 as usize]
    }

    /// The symbol whose name is declared at `span`.
    pub fn declared_at(&self, span: crate::source::Span) -> Option<SymbolId> {
        self.by_location.get(&span).copied()
    }

    /// The member `key` of `parent`, without inheritance.
    pub fn child(&self, parent: SymbolId, key: &str) -> Option<SymbolId> {
        self.children.get(&(parent, key.to_string())).copied()
    }

    /// The members of `parent`, in declaration order.
    pub fn children_of(&self, parent: SymbolId) -> &[SymbolId] {
        self.ordered.get(&parent).map(Vec::as_slice).unwrap_or(&[])
    }

    /// The member `key` of `owner` or of what it extends (blocks and
    /// structures), nearest first.
    pub fn member(&self, owner: SymbolId, key: &str) -> Option<SymbolId> {
        self.lineage(owner)
            .into_iter()
            .find_map(|s| self.child(s, key))
    }

    /// The members of `owner` and of what it extends, the nearest
    /// declaration of each name only.
    pub fn members(&self, owner: SymbolId) -> Vec<SymbolId> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for s in self.lineage(owner) {
            for &c in self.children_of(s) {
                if seen.insert(self.get(c).key()) {
                    out.push(c);
                }
            }
        }
        out
    }

    /// `owner`, then what it extends, then what that extends (cycles cut).
    pub fn lineage(&self, owner: SymbolId) -> Vec<SymbolId> {
        let mut chain = vec![owner];
        let mut current = owner;
        while let Some(base) = self.get(current).extends.as_ref() {
            match self.units.get(base) {
                Some(&next) if !chain.contains(&next) => {
                    chain.push(next);
                    current = next;
                }
                _ => break,
            }
        }
        chain
    }

    /// The type symbol a shape designates after aliases are followed:
    /// a structure, enumeration, block or interface (or an inline type's
    /// owner). Arrays and references are not looked through.
    pub fn type_of_shape(&self, shape: &Shape) -> Option<SymbolId> {
        let mut shape = shape.clone();
        for _ in 0..32 {
            match shape {
                Shape::Inline(id) => return Some(id),
                Shape::Named(ref key) => {
                    let id = *self.units.get(key)?;
                    let symbol = self.get(id);
                    match (&symbol.kind, &symbol.shape) {
                        (SymbolKind::Alias, Some(inner)) => shape = inner.clone(),
                        (kind, _) if kind.is_type() => return Some(id),
                        _ => return None,
                    }
                }
                Shape::Array(_) | Shape::Ref(_) | Shape::Opaque => return None,
            }
        }
        None
    }

    /// `shape` with aliases followed until it is an array, a reference or
    /// a type symbol.
    pub fn unalias(&self, shape: &Shape) -> Shape {
        let mut shape = shape.clone();
        for _ in 0..32 {
            let Shape::Named(ref key) = shape else {
                return shape;
            };
            match self.units.get(key).map(|&id| self.get(id)) {
                Some(Symbol {
                    kind: SymbolKind::Alias,
                    shape: Some(inner),
                    ..
                }) => shape = inner.clone(),
                _ => return shape,
            }
        }
        shape
    }

    /// The symbol `key` names from inside `scope` (a method, then its
    /// block; or a POU): their members and inherited members, then global
    /// variables, POUs and types, then enumeration values.
    pub fn lookup(&self, scope: &[SymbolId], key: &str) -> Option<SymbolId> {
        for &owner in scope {
            if let Some(id) = self.member(owner, key) {
                return Some(id);
            }
        }
        self.globals
            .get(key)
            .or_else(|| self.units.get(key))
            .copied()
            .or_else(|| self.enum_values.get(key)?.first().copied())
    }

    /// The shape a symbol's value has: a variable's type, a function's or
    /// method's result; a type name stands for its own type (`Color.Red`).
    pub fn value_shape(&self, id: SymbolId) -> Option<Shape> {
        let symbol = self.get(id);
        match symbol.kind {
            k if k.is_type() => Some(Shape::Named(symbol.key())),
            _ => symbol.shape.clone(),
        }
    }

    /// The symbol whose members follow a `.` on a value of `shape`
    /// (references are looked through, as CODESYS does for REFERENCE TO).
    pub fn owner_of(&self, shape: &Shape) -> Option<SymbolId> {
        let mut shape = self.unalias(shape);
        for _ in 0..32 {
            match shape {
                Shape::Ref(inner) => shape = self.unalias(&inner),
                other => return self.type_of_shape(&other),
            }
        }
        None
    }

    /// Adds the standard blocks plcrun provides, where no user POU of the
    /// same name hides them.
    pub fn add_standard_blocks(&mut self) {
        for &name in STANDARD_BLOCKS {
            let Some(fb) = lookup_native(name) else {
                continue;
            };
            if self.units.contains_key(name) {
                continue;
            }
            let block = self.add(Symbol {
                name: name.to_string(),
                kind: SymbolKind::StandardBlock,
                location: None,
                extent: None,
                parent: None,
                type_text: None,
                shape: None,
                constant: false,
                extends: None,
            });
            self.units.insert(name.to_string(), block);
            for pin in interface(fb) {
                let section = match pin.dir {
                    ParamDir::Input => VarSection::Input,
                    ParamDir::Output => VarSection::Output,
                    ParamDir::Hidden => continue,
                };
                self.add(Symbol {
                    name: pin.name.to_string(),
                    kind: SymbolKind::StandardPin(section),
                    location: None,
                    extent: None,
                    parent: Some(block),
                    type_text: Some(pin.ty.name().to_string()),
                    shape: Some(Shape::Named(pin.ty.name().to_string())),
                    constant: false,
                    extends: None,
                });
            }
        }
    }
}
