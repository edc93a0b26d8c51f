//! Builds the symbol table from the parsed files: every POU, method,
//! variable, type, field, enumeration value, step, action, label and
//! configuration element, with its position.

use super::symbol::{Shape, Symbol, SymbolId, SymbolKind, VarSection};
use super::table::Table;
use crate::source::{SourceMap, Span};
use crate::syntax::ast::{
    Body, CompilationUnit, Configuration, IlLine, Item, Pou, PouKind, SfcElement, TypeDecl,
    TypeSpec, VarBlock, VarKind,
};
use crate::syntax::oop::{Interface, Method};

/// Collects the declarations of `units` (parsed from `sources`).
pub(crate) fn collect(sources: &SourceMap, units: &[CompilationUnit]) -> Table {
    let mut c = Collector {
        sources,
        table: Table::default(),
    };
    for unit in units {
        for item in &unit.items {
            c.item(item);
        }
    }
    c.table.add_standard_blocks();
    c.table
}

struct Collector<'a> {
    sources: &'a SourceMap,
    table: Table,
}

/// What a new symbol needs beyond its name.
struct Decl {
    kind: SymbolKind,
    extent: Span,
    parent: Option<SymbolId>,
}

impl Collector<'_> {
    fn text(&self, span: Span) -> String {
        let file = self.sources.file(span.file);
        file.text
            .get(span.start as usize..span.end as usize)
            .unwrap_or("")
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
    }

    fn add(&mut self, name: &crate::syntax::ast::Ident, decl: Decl) -> SymbolId {
        self.table.add(Symbol {
            name: name.name.clone(),
            kind: decl.kind,
            location: Some(name.span),
            extent: Some(decl.extent),
            parent: decl.parent,
            type_text: None,
            shape: None,
            constant: false,
            extends: None,
        })
    }

    fn unit(&mut self, name: &crate::syntax::ast::Ident, decl: Decl) -> SymbolId {
        let id = self.add(name, decl);
        self.table.units.entry(name.key()).or_insert(id);
        id
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Pou(pou) => self.pou(pou),
            Item::Types(types) => {
                for ty in types {
                    self.type_decl(ty);
                }
            }
            Item::Configuration(config) => self.configuration(config),
            Item::Globals(block) => self.var_block(block, None),
            Item::Interface(interface) => self.interface(interface),
        }
    }

    fn pou(&mut self, pou: &Pou) {
        let kind = match pou.kind {
            PouKind::Program => SymbolKind::Program,
            PouKind::Function => SymbolKind::Function,
            PouKind::FunctionBlock => SymbolKind::FunctionBlock,
        };
        let id = self.unit(
            &pou.name,
            Decl {
                kind,
                extent: pou.span,
                parent: None,
            },
        );
        if let Some(ret) = &pou.return_type {
            self.set_type(id, ret);
        }
        if let Some(oop) = &pou.oop {
            self.table.symbols[id.0 as usize].extends = oop.extends.as_ref().map(|e| e.key());
        }
        for block in &pou.var_blocks {
            self.var_block(block, Some(id));
        }
        self.body(&pou.body, id);
        if let Some(oop) = &pou.oop {
            for method in &oop.methods {
                self.method(method, id);
            }
        }
    }

    fn method(&mut self, method: &Method, owner: SymbolId) {
        let id = self.add(
            &method.name,
            Decl {
                kind: SymbolKind::Method,
                extent: method.span,
                parent: Some(owner),
            },
        );
        if let Some(ret) = &method.return_type {
            self.set_type(id, ret);
        }
        for block in &method.var_blocks {
            self.var_block(block, Some(id));
        }
        self.body(&method.body, id);
        for accessor in method.property.iter().flatten() {
            for block in &accessor.var_blocks {
                self.var_block(block, Some(id));
            }
        }
    }

    fn interface(&mut self, interface: &Interface) {
        let id = self.unit(
            &interface.name,
            Decl {
                kind: SymbolKind::Interface,
                extent: interface.span,
                parent: None,
            },
        );
        self.table.symbols[id.0 as usize].extends = interface.extends.first().map(|e| e.key());
        for method in &interface.methods {
            self.method(method, id);
        }
    }

    fn set_type(&mut self, id: SymbolId, ty: &TypeSpec) {
        let shape = self.shape(ty, id);
        let text = self.text(ty.span());
        let symbol = &mut self.table.symbols[id.0 as usize];
        symbol.type_text = Some(text);
        symbol.shape = Some(shape);
    }

    /// The shape of `ty`; the values of an enumeration written in place
    /// become children of `owner`.
    fn shape(&mut self, ty: &TypeSpec, owner: SymbolId) -> Shape {
        match ty {
            TypeSpec::Named(name) => Shape::Named(name.key()),
            TypeSpec::Subrange { base, .. } => Shape::Named(base.key()),
            TypeSpec::String { .. } => Shape::Opaque,
            TypeSpec::Array { elem, .. } | TypeSpec::OpenArray { elem, .. } => {
                Shape::Array(Box::new(self.shape(elem, owner)))
            }
            TypeSpec::Ref { target, .. } => Shape::Ref(Box::new(self.shape(target, owner))),
            TypeSpec::Enum { values, span, .. } => {
                for (value, _) in values {
                    let v = self.add(
                        value,
                        Decl {
                            kind: SymbolKind::EnumValue,
                            extent: *span,
                            parent: Some(owner),
                        },
                    );
                    self.table
                        .enum_values
                        .entry(value.key())
                        .or_default()
                        .push(v);
                }
                Shape::Inline(owner)
            }
            TypeSpec::Struct { fields, .. } => {
                for field in fields {
                    for name in &field.names {
                        let f = self.add(
                            name,
                            Decl {
                                kind: SymbolKind::Field,
                                extent: field.span,
                                parent: Some(owner),
                            },
                        );
                        self.set_type(f, &field.ty);
                    }
                }
                Shape::Inline(owner)
            }
        }
    }

    fn type_decl(&mut self, ty: &TypeDecl) {
        let kind = match &ty.ty {
            TypeSpec::Struct { .. } => SymbolKind::Struct,
            TypeSpec::Enum { .. } => SymbolKind::Enum,
            _ => SymbolKind::Alias,
        };
        let id = self.unit(
            &ty.name,
            Decl {
                kind,
                extent: ty.span,
                parent: None,
            },
        );
        if let TypeSpec::Struct {
            extends: Some(base),
            ..
        } = &ty.ty
        {
            self.table.symbols[id.0 as usize].extends = Some(base.key());
        }
        let shape = self.shape(&ty.ty, id);
        let text = match kind {
            SymbolKind::Alias => self.text(ty.ty.span()),
            _ => ty.name.name.clone(),
        };
        let symbol = &mut self.table.symbols[id.0 as usize];
        symbol.shape = Some(shape);
        symbol.type_text = Some(text);
    }

    fn var_block(&mut self, block: &VarBlock, owner: Option<SymbolId>) {
        let kind = match block.kind {
            VarKind::Global => SymbolKind::Global,
            VarKind::Local => SymbolKind::Variable(VarSection::Local),
            VarKind::Input => SymbolKind::Variable(VarSection::Input),
            VarKind::Output => SymbolKind::Variable(VarSection::Output),
            VarKind::InOut => SymbolKind::Variable(VarSection::InOut),
            VarKind::External => SymbolKind::Variable(VarSection::External),
            VarKind::Temp => SymbolKind::Variable(VarSection::Temp),
            VarKind::Inst => SymbolKind::Variable(VarSection::Inst),
            VarKind::Stat => SymbolKind::Variable(VarSection::Stat),
        };
        for decl in &block.decls {
            for name in &decl.names {
                let id = self.add(
                    name,
                    Decl {
                        kind,
                        extent: decl.span,
                        parent: owner,
                    },
                );
                self.set_type(id, &decl.ty);
                self.table.symbols[id.0 as usize].constant = block.constant;
                if kind == SymbolKind::Global {
                    self.table.globals.entry(name.key()).or_insert(id);
                }
            }
        }
    }

    fn body(&mut self, body: &Body, owner: SymbolId) {
        match body {
            Body::St(_) => {}
            Body::Il(lines) => self.labels(lines, owner),
            Body::Sfc(elements) => self.chart(elements, owner),
        }
    }

    fn labels(&mut self, lines: &[IlLine], owner: SymbolId) {
        for line in lines {
            if let Some(label) = &line.label {
                self.add(
                    label,
                    Decl {
                        kind: SymbolKind::Label,
                        extent: line.span,
                        parent: Some(owner),
                    },
                );
            }
        }
    }

    fn chart(&mut self, elements: &[SfcElement], owner: SymbolId) {
        for element in elements {
            match element {
                SfcElement::Step(step) => {
                    self.add(
                        &step.name,
                        Decl {
                            kind: SymbolKind::Step,
                            extent: step.span,
                            parent: Some(owner),
                        },
                    );
                }
                SfcElement::Action(action) => {
                    let id = self.add(
                        &action.name,
                        Decl {
                            kind: SymbolKind::Action,
                            extent: action.span,
                            parent: Some(owner),
                        },
                    );
                    if let Body::Il(lines) = &action.body {
                        self.labels(lines, id);
                    }
                }
                SfcElement::Transition(t) => {
                    if let Some(name) = &t.name {
                        self.add(
                            name,
                            Decl {
                                kind: SymbolKind::Transition,
                                extent: t.span,
                                parent: Some(owner),
                            },
                        );
                    }
                }
                SfcElement::Statement(_) => {}
            }
        }
    }

    fn configuration(&mut self, config: &Configuration) {
        let id = self.unit(
            &config.name,
            Decl {
                kind: SymbolKind::Configuration,
                extent: config.span,
                parent: None,
            },
        );
        for block in &config.globals {
            self.var_block(block, None);
        }
        for resource in &config.resources {
            // An implicit resource carries the configuration's own name.
            let res = if resource.name.span == config.name.span {
                id
            } else {
                self.add(
                    &resource.name,
                    Decl {
                        kind: SymbolKind::Resource,
                        extent: resource.span,
                        parent: Some(id),
                    },
                )
            };
            for block in &resource.globals {
                self.var_block(block, None);
            }
            for task in &resource.tasks {
                self.add(
                    &task.name,
                    Decl {
                        kind: SymbolKind::Task,
                        extent: task.span,
                        parent: Some(res),
                    },
                );
            }
            for program in &resource.programs {
                let p = self.add(
                    &program.name,
                    Decl {
                        kind: SymbolKind::ProgramInstance,
                        extent: program.span,
                        parent: Some(res),
                    },
                );
                let symbol = &mut self.table.symbols[p.0 as usize];
                symbol.type_text = Some(program.type_name.name.clone());
                symbol.shape = Some(Shape::Named(program.type_name.key()));
            }
        }
    }
}
