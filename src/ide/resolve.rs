//! Finds what every name in the sources refers to: walks declarations and
//! bodies with the scope rules of IEC 61131-3 (a method's variables, then
//! its block's and those it inherits, then globals, POUs and types, then
//! enumeration values) and records each use as an [`Occurrence`].

use super::symbol::{Shape, SymbolId, SymbolKind};
use super::table::Table;
use crate::source::Span;
use crate::syntax::ast::{
    Arg, Body, CaseLabel, CompilationUnit, Configuration, Expr, ExprKind, Ident, IlInstrKind,
    IlLine, Initializer, Item, LiteralValue, Pou, SfcElement, Stmt, StmtKind, TransitionCondition,
    TypeDecl, TypeSpec, VarBlock,
};
use crate::syntax::oop::Method;

/// A name written in the sources and the symbol it stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Occurrence {
    /// Where the name is written.
    pub span: Span,
    /// What it names.
    pub symbol: SymbolId,
    /// True where the name is declared, false where it is used.
    pub declaration: bool,
}

/// Every use of a name in `units` that resolves to a symbol of `table`.
pub(crate) fn resolve(table: &Table, units: &[CompilationUnit]) -> Vec<Occurrence> {
    let mut r = Resolver {
        table,
        found: Vec::new(),
        scope: Vec::new(),
    };
    for unit in units {
        for item in &unit.items {
            r.item(item);
        }
    }
    r.found
}

/// What an expression stands for, as far as names go.
#[derive(Default)]
struct Meaning {
    symbol: Option<SymbolId>,
    shape: Option<Shape>,
}

struct Resolver<'a> {
    table: &'a Table,
    found: Vec<Occurrence>,
    /// The POU or method whose names are in scope, innermost first.
    scope: Vec<SymbolId>,
}

impl Resolver<'_> {
    fn record(&mut self, name: &Ident, symbol: SymbolId) {
        self.found.push(Occurrence {
            span: name.span,
            symbol,
            declaration: false,
        });
    }

    /// The symbol `key` names from the current scope.
    fn lookup(&self, key: &str) -> Option<SymbolId> {
        self.table.lookup(&self.scope, key)
    }

    fn unit_named(&mut self, name: &Ident) -> Option<SymbolId> {
        let id = *self.table.units.get(&name.key())?;
        self.record(name, id);
        Some(id)
    }

    fn value_shape(&self, id: SymbolId) -> Option<Shape> {
        self.table.value_shape(id)
    }

    fn owner_of(&self, shape: &Shape) -> Option<SymbolId> {
        self.table.owner_of(shape)
    }

    /// The POU or method a call's arguments are parameters of.
    fn callee_owner(&self, callee: &Meaning) -> Option<SymbolId> {
        let id = callee.symbol?;
        match self.table.get(id).kind {
            SymbolKind::Function | SymbolKind::Method => Some(id),
            SymbolKind::FunctionBlock | SymbolKind::StandardBlock | SymbolKind::Program => Some(id),
            _ => self.owner_of(callee.shape.as_ref()?),
        }
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Pou(pou) => self.pou(pou),
            Item::Types(types) => types.iter().for_each(|t| self.type_decl(t)),
            Item::Configuration(config) => self.configuration(config),
            Item::Globals(block) => self.var_block(block, None),
            Item::Interface(interface) => {
                if let Some(&id) = self.table.units.get(&interface.name.key()) {
                    for base in &interface.extends {
                        self.unit_named(base);
                    }
                    self.scope = vec![id];
                    for method in &interface.methods {
                        self.method(method, id);
                    }
                    self.scope.clear();
                }
            }
        }
    }

    fn pou(&mut self, pou: &Pou) {
        let Some(id) = self.table.declared_at(pou.name.span) else {
            return;
        };
        self.scope = vec![id];
        if let Some(ret) = &pou.return_type {
            self.type_spec(ret);
        }
        if let Some(oop) = &pou.oop {
            if let Some(base) = &oop.extends {
                self.unit_named(base);
            }
            for i in &oop.implements {
                self.unit_named(i);
            }
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
        self.scope.clear();
    }

    fn method(&mut self, method: &Method, owner: SymbolId) {
        let Some(id) = self.table.declared_at(method.name.span) else {
            return;
        };
        self.scope = vec![id, owner];
        if let Some(ret) = &method.return_type {
            self.type_spec(ret);
        }
        for block in &method.var_blocks {
            self.var_block(block, Some(id));
        }
        self.body(&method.body, id);
        for accessor in method.property.iter().flatten() {
            self.body(&accessor.body, id);
        }
        self.scope = vec![owner];
    }

    fn var_block(&mut self, block: &VarBlock, owner: Option<SymbolId>) {
        for decl in &block.decls {
            self.type_spec(&decl.ty);
            let Some(init) = &decl.init else { continue };
            let shape = decl
                .names
                .first()
                .and_then(|n| self.declared_in(owner, n))
                .and_then(|id| self.table.get(id).shape.clone());
            self.initializer(init, shape.as_ref());
        }
    }

    fn declared_in(&self, owner: Option<SymbolId>, name: &Ident) -> Option<SymbolId> {
        match owner {
            Some(o) => self.table.child(o, &name.key()),
            None => self.table.globals.get(&name.key()).copied(),
        }
    }

    fn initializer(&mut self, init: &Initializer, shape: Option<&Shape>) {
        match init {
            Initializer::Expr(e) => {
                self.expr(e);
            }
            Initializer::Array(elems, _) => {
                let inner = shape.map(|s| self.table.unalias(s)).and_then(|s| match s {
                    Shape::Array(inner) => Some(*inner),
                    _ => None,
                });
                for elem in elems {
                    if let Some(r) = &elem.repeat {
                        self.expr(r);
                    }
                    if let Some(v) = &elem.value {
                        self.initializer(v, inner.as_ref());
                    }
                }
            }
            Initializer::Struct(fields, _) => {
                let owner = shape.and_then(|s| self.owner_of(s));
                for (name, value) in fields {
                    let field = owner.and_then(|o| self.table.member(o, &name.key()));
                    if let Some(f) = field {
                        self.record(name, f);
                    }
                    let inner = field.and_then(|f| self.table.get(f).shape.clone());
                    self.initializer(value, inner.as_ref());
                }
            }
        }
    }

    fn type_spec(&mut self, ty: &TypeSpec) {
        match ty {
            TypeSpec::Named(name) => {
                self.unit_named(name);
            }
            TypeSpec::String { len, .. } => {
                if let Some(len) = len {
                    self.expr(len);
                }
            }
            TypeSpec::Array { ranges, elem, .. } => {
                for (lo, hi) in ranges {
                    self.expr(lo);
                    self.expr(hi);
                }
                self.type_spec(elem);
            }
            TypeSpec::OpenArray { elem, .. } => self.type_spec(elem),
            TypeSpec::Subrange { lo, hi, .. } => {
                self.expr(lo);
                self.expr(hi);
            }
            TypeSpec::Enum { base, values, .. } => {
                if let Some(base) = base {
                    self.unit_named(base);
                }
                for (_, value) in values {
                    if let Some(v) = value {
                        self.expr(v);
                    }
                }
            }
            TypeSpec::Struct {
                extends, fields, ..
            } => {
                if let Some(base) = extends {
                    self.unit_named(base);
                }
                for field in fields {
                    self.type_spec(&field.ty);
                    if let Some(init) = &field.init {
                        self.initializer(init, None);
                    }
                }
            }
            TypeSpec::Ref { target, .. } => self.type_spec(target),
        }
    }

    fn type_decl(&mut self, ty: &TypeDecl) {
        self.type_spec(&ty.ty);
        if let Some(init) = &ty.init {
            let shape = self
                .table
                .units
                .get(&ty.name.key())
                .and_then(|&id| self.table.get(id).shape.clone());
            self.initializer(init, shape.as_ref());
        }
    }

    fn body(&mut self, body: &Body, owner: SymbolId) {
        match body {
            Body::St(stmts) => self.stmts(stmts),
            Body::Il(lines) => self.il(lines, owner),
            Body::Sfc(elements) => self.chart(elements, owner),
        }
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for stmt in stmts {
            self.stmt(stmt);
        }
    }

    fn stmt(&mut self, stmt: &Stmt) {
        match &stmt.kind {
            StmtKind::Assign { target, value } | StmtKind::RefAssign { target, value } => {
                self.expr(target);
                self.expr(value);
            }
            StmtKind::Call(call) => {
                self.call(&call.callee, &call.args);
            }
            StmtKind::If {
                branches,
                else_branch,
            } => {
                for (cond, body) in branches {
                    self.expr(cond);
                    self.stmts(body);
                }
                if let Some(body) = else_branch {
                    self.stmts(body);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_branch,
            } => {
                self.expr(selector);
                for arm in arms {
                    for label in &arm.labels {
                        match label {
                            CaseLabel::Value(v) => {
                                self.expr(v);
                            }
                            CaseLabel::Range(lo, hi) => {
                                self.expr(lo);
                                self.expr(hi);
                            }
                        }
                    }
                    self.stmts(&arm.body);
                }
                if let Some(body) = else_branch {
                    self.stmts(body);
                }
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                self.expr(var);
                self.expr(from);
                self.expr(to);
                if let Some(by) = by {
                    self.expr(by);
                }
                self.stmts(body);
            }
            StmtKind::While { cond, body } => {
                self.expr(cond);
                self.stmts(body);
            }
            StmtKind::Repeat { body, until } => {
                self.stmts(body);
                self.expr(until);
            }
            StmtKind::Try {
                body,
                catch,
                finally,
            } => {
                self.stmts(body);
                if let Some((name, c)) = catch {
                    // The variable, so that hover and go-to-definition
                    // reach it as any other use.
                    self.expr(&Expr {
                        kind: ExprKind::Name(name.clone()),
                        span: name.span,
                    });
                    self.stmts(c);
                }
                if let Some(f) = finally {
                    self.stmts(f);
                }
            }
            StmtKind::Exit | StmtKind::Continue | StmtKind::Return | StmtKind::Empty => {}
        }
    }

    /// A call: the callee, then each argument, formal names resolved as
    /// the callee's parameters.
    fn call(&mut self, callee: &Expr, args: &[Arg]) -> Meaning {
        let target = self.expr(callee);
        let owner = self.callee_owner(&target);
        self.args(owner, args);
        let shape = match target.symbol.map(|s| self.table.get(s).kind) {
            Some(SymbolKind::Function | SymbolKind::Method) => {
                target.symbol.and_then(|s| self.table.get(s).shape.clone())
            }
            _ => None,
        };
        Meaning {
            symbol: None,
            shape,
        }
    }

    fn args(&mut self, owner: Option<SymbolId>, args: &[Arg]) {
        for arg in args {
            match arg {
                Arg::Positional(e) => {
                    self.expr(e);
                }
                Arg::Input { name, value } => {
                    self.param(owner, name);
                    self.expr(value);
                }
                Arg::Output { name, target, .. } => {
                    self.param(owner, name);
                    self.expr(target);
                }
            }
        }
    }

    fn param(&mut self, owner: Option<SymbolId>, name: &Ident) {
        if let Some(p) = owner.and_then(|o| self.table.member(o, &name.key())) {
            self.record(name, p);
        }
    }

    fn expr(&mut self, expr: &Expr) -> Meaning {
        match &expr.kind {
            ExprKind::Name(name) => self.name(name),
            ExprKind::Member(base, member) => self.member(base, member),
            ExprKind::Index(base, indices) => {
                let base = self.expr(base);
                for i in indices {
                    self.expr(i);
                }
                let shape = base
                    .shape
                    .map(|s| self.table.unalias(&s))
                    .and_then(|s| match s {
                        Shape::Array(inner) => Some(*inner),
                        _ => None,
                    });
                Meaning {
                    symbol: None,
                    shape,
                }
            }
            ExprKind::Deref(base) => {
                let base = self.expr(base);
                let shape = base
                    .shape
                    .map(|s| self.table.unalias(&s))
                    .and_then(|s| match s {
                        Shape::Ref(inner) => Some(*inner),
                        _ => None,
                    });
                Meaning {
                    symbol: None,
                    shape,
                }
            }
            ExprKind::BitAccess(base, _) => {
                self.expr(base);
                Meaning::default()
            }
            ExprKind::Unary(_, e) => {
                self.expr(e);
                Meaning::default()
            }
            ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => {
                self.expr(a);
                self.expr(b);
                Meaning::default()
            }
            ExprKind::Paren(e) => {
                let inner = self.expr(e);
                Meaning {
                    symbol: None,
                    shape: inner.shape,
                }
            }
            ExprKind::Call(call) => self.call(&call.callee, &call.args),
            ExprKind::Literal(lit) => {
                if let Some(prefix) = &lit.type_prefix
                    && let Some(ty) = self.unit_named(prefix)
                    && let LiteralValue::EnumValue(value) = &lit.value
                    && let Some(v) = self.table.member(ty, &value.key())
                {
                    self.record(value, v);
                }
                Meaning::default()
            }
            ExprKind::Direct(_) => Meaning::default(),
        }
    }

    fn name(&mut self, name: &Ident) -> Meaning {
        let key = name.key();
        let this_block = || self.scope.last().copied();
        if key == "THIS" || key == "SUPER" {
            let block = this_block();
            let shape = block.and_then(|b| {
                let symbol = self.table.get(b);
                let target = if key == "THIS" {
                    Some(symbol.key())
                } else {
                    symbol.extends.clone()
                };
                target.map(|t| Shape::Ref(Box::new(Shape::Named(t))))
            });
            return Meaning {
                symbol: None,
                shape,
            };
        }
        match self.lookup(&key) {
            Some(id) => {
                self.record(name, id);
                Meaning {
                    symbol: Some(id),
                    shape: self.value_shape(id),
                }
            }
            None => Meaning::default(),
        }
    }

    fn member(&mut self, base: &Expr, member: &Ident) -> Meaning {
        let unresolved_name =
            matches!(&base.kind, ExprKind::Name(n) if self.lookup(&n.key()).is_none());
        let base = self.expr(base);
        let key = member.key();
        let found = if unresolved_name {
            // `GVL.x`: a global list's name qualifies its variables.
            self.table.globals.get(&key).copied()
        } else {
            base.shape
                .as_ref()
                .and_then(|s| self.owner_of(s))
                .and_then(|o| self.table.member(o, &key))
        };
        match found {
            Some(id) => {
                self.record(member, id);
                Meaning {
                    symbol: Some(id),
                    shape: self.table.get(id).shape.clone(),
                }
            }
            None => Meaning::default(),
        }
    }

    fn il(&mut self, lines: &[IlLine], owner: SymbolId) {
        for line in lines {
            let Some(instr) = &line.instr else { continue };
            match &instr.kind {
                IlInstrKind::Simple { operand, .. } | IlInstrKind::Deferred { operand, .. } => {
                    if let Some(e) = operand {
                        self.expr(e);
                    }
                }
                IlInstrKind::Close | IlInstrKind::Return { .. } => {}
                IlInstrKind::Jump { label, .. } => {
                    if let Some(l) = self.table.child(owner, &label.key()) {
                        self.record(label, l);
                    }
                }
                IlInstrKind::Call {
                    instance,
                    args,
                    outputs,
                    ..
                } => {
                    let target = self.expr(instance);
                    let fb = self.callee_owner(&target);
                    self.args(fb, args);
                    for copy in outputs {
                        if let Some(dest) = &copy.dest {
                            self.expr(dest);
                        }
                        self.param(fb, &copy.output);
                    }
                }
                IlInstrKind::FbInput { pin, instance } => {
                    let target = self.expr(instance);
                    let fb = self.callee_owner(&target);
                    self.param(fb, pin);
                }
                IlInstrKind::FunctionCall { name, args } => {
                    let function = self.unit_named(name);
                    self.args(function, args);
                }
            }
        }
    }

    fn chart(&mut self, elements: &[SfcElement], owner: SymbolId) {
        for element in elements {
            match element {
                SfcElement::Step(step) => {
                    for assoc in &step.actions {
                        if let Some(a) = self.lookup(&assoc.action.key()) {
                            self.record(&assoc.action, a);
                        }
                        if let Some(d) = &assoc.duration {
                            self.expr(d);
                        }
                        for indicator in &assoc.indicators {
                            self.name(indicator);
                        }
                    }
                }
                SfcElement::Transition(t) => {
                    for step in t.from.iter().chain(&t.to) {
                        if let Some(s) = self.table.child(owner, &step.key()) {
                            self.record(step, s);
                        }
                    }
                    if let Some(p) = &t.priority {
                        self.expr(p);
                    }
                    match &t.condition {
                        TransitionCondition::Expr(e) => {
                            self.expr(e);
                        }
                        TransitionCondition::Il(lines) => self.il(lines, owner),
                    }
                }
                SfcElement::Action(action) => {
                    let id = self.table.child(owner, &action.name.key()).unwrap_or(owner);
                    self.body(&action.body, id);
                }
                SfcElement::Statement(stmt) => self.stmt(stmt),
            }
        }
    }

    fn configuration(&mut self, config: &Configuration) {
        for block in &config.globals {
            self.var_block(block, None);
        }
        let Some(&config_id) = self.table.units.get(&config.name.key()) else {
            return;
        };
        for resource in &config.resources {
            let res = self
                .table
                .child(config_id, &resource.name.key())
                .unwrap_or(config_id);
            for block in &resource.globals {
                self.var_block(block, None);
            }
            for task in &resource.tasks {
                for (_, value) in &task.settings {
                    self.expr(value);
                }
            }
            for program in &resource.programs {
                if let Some(task) = &program.task
                    && let Some(t) = self.table.child(res, &task.key())
                {
                    self.record(task, t);
                }
                let pou = self.unit_named(&program.type_name);
                self.args(pou, &program.args);
            }
        }
    }
}
