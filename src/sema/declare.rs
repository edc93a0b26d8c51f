//! The declaration phase: collects POUs, types and globals into the
//! [`Model`], resolves type specifications and lays out instance memory.
//! It is the only writer of the model. A function block's instance size
//! includes its temporaries, so laying out a POU that holds an instance
//! first has the FB's body emitted (by a [`BodyBuilder`] that reads the
//! model as it stands) and records the resulting frame size.

use super::body::BodyBuilder;
use super::decl_consts::DeclConsts;
use super::model::{LayoutState, Model, PouInfo, Storage, VarInfo};
use super::program::Program;
use crate::diagnostics::Diagnostics;
use crate::elementary::ElemType;
use crate::ir::type_table::{MemberKind, TypeDef, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::stdlib;
use crate::syntax::ast::{
    AddrSize, Area, CompilationUnit, DirectAddress, Item, Pou, PouKind, TypeDecl, TypeSpec,
    VarBlock, VarDecl,
};
use indexmap::IndexMap;
use std::collections::HashMap;

/// State of the declaration phase.
pub(super) struct Declarer<'a> {
    /// The parsed files.
    pub(super) units: &'a [CompilationUnit],
    /// Where errors go.
    pub(super) diags: &'a mut Diagnostics,
    /// What is known so far (complete when the phase ends).
    pub(super) model: Model,
    /// All types (bodies may intern more: the results of string functions).
    pub(super) types: TypeTable,
    /// The program's output tables.
    pub(super) out: Program,
    /// Layout progress of each POU.
    pub(super) pou_state: Vec<LayoutState>,
    /// Emission progress of each POU body.
    pub(super) emit_state: Vec<LayoutState>,
    /// TYPE declarations by case-folded name: (unit, item, declaration).
    pub(super) type_decls: HashMap<String, (usize, usize, usize)>,
    /// Resolution progress of each user type.
    pub(super) type_state: HashMap<String, LayoutState>,
    /// Enumeration TYPEs, in resolution order, while TYPE declarations are
    /// being resolved (empty afterwards).
    pub(super) pending_enums: Vec<String>,
    /// The POUs being laid out, outermost first (to name an instance cycle).
    pub(super) layout_path: Vec<usize>,
    /// Ids given to STRUCT TYPEs before their fields are resolved (so a
    /// field may refer to its own structure: `self_ref_types.rs`).
    pub(super) reserved_structs: HashMap<String, TypeId>,
    /// Type ids given to function blocks before their layout was finished,
    /// by POU index (self_ref_types.rs).
    pub(super) reserved_fbs: HashMap<usize, TypeId>,
}

/// What the declaration phase hands to the linker.
pub(super) struct Declared {
    /// The read-only declarations.
    pub(super) model: Model,
    /// All types.
    pub(super) types: TypeTable,
    /// The output tables with every body emitted.
    pub(super) out: Program,
}

/// Normalised text of a direct address: `%` area, size letter, fields.
pub fn normalize_address(a: &DirectAddress) -> String {
    let area = match a.area {
        Area::Input => 'I',
        Area::Output => 'Q',
        Area::Memory => 'M',
    };
    let size = match a.size {
        AddrSize::Bit => 'X',
        AddrSize::Byte => 'B',
        AddrSize::Word => 'W',
        AddrSize::Dword => 'D',
        AddrSize::Lword => 'L',
    };
    let fields: Vec<String> = a.fields.iter().map(|f| f.to_string()).collect();
    format!("%{area}{size}{}", fields.join("."))
}

/// The elementary type a direct address denotes when used undeclared.
pub fn address_type(a: &DirectAddress) -> ElemType {
    match a.size {
        AddrSize::Bit => ElemType::Bool,
        AddrSize::Byte => ElemType::Byte,
        AddrSize::Word => ElemType::Word,
        AddrSize::Dword => ElemType::Dword,
        AddrSize::Lword => ElemType::Lword,
    }
}

impl<'a> Declarer<'a> {
    /// A phase that has seen nothing yet.
    pub(super) fn new(units: &'a [CompilationUnit], diags: &'a mut Diagnostics) -> Declarer<'a> {
        Declarer {
            units,
            diags,
            model: Model::default(),
            types: TypeTable::new(),
            out: Program::default(),
            pou_state: Vec::new(),
            emit_state: Vec::new(),
            type_decls: HashMap::new(),
            type_state: HashMap::new(),
            pending_enums: Vec::new(),
            layout_path: Vec::new(),
            reserved_structs: HashMap::new(),
            reserved_fbs: HashMap::new(),
        }
    }

    /// The folder of declaration constants over the model as it stands.
    pub(super) fn consts(&mut self) -> DeclConsts<'_> {
        DeclConsts {
            types: &self.types,
            model: &self.model,
            diags: self.diags,
            same_block: &[],
            globals_at_start: true,
        }
    }

    /// Emits every body not emitted yet and ends the phase.
    /// Names the POUs whose bodies the host provides.
    pub(super) fn set_host_pous(&mut self, names: &[String]) {
        self.model.host_pous = names.iter().map(|n| n.to_ascii_uppercase()).collect();
    }

    /// Selects IEC 60848 evolution for every chart.
    pub(super) fn set_grafcet(&mut self, grafcet: bool) {
        self.model.grafcet = grafcet;
    }

    /// The files in the CODESYS V3 / TwinCAT dialect (`CompileOptions`).
    pub(super) fn set_codesys_files(&mut self, files: &[crate::source::FileId]) {
        self.model.codesys_files = files.iter().copied().collect();
    }

    /// The user's TwinCAT files (`CompileOptions::checked_files`).
    pub(super) fn set_checked_files(&mut self, files: &[crate::source::FileId]) {
        self.model.checked_files = files.iter().copied().collect();
    }

    /// The files of library projects, where no implicit check is called.
    pub(super) fn set_library_files(&mut self, files: &[crate::source::FileId]) {
        self.model.library_files = files.iter().copied().collect();
    }

    /// Turns the fusions and the bounds proofs off (or on again).
    pub(super) fn set_unoptimized(&mut self, unoptimized: bool) {
        self.model.unoptimized = unoptimized;
    }

    /// Sets the data limit (in slots) checked by array types and memory
    /// allocation (E120).
    pub(super) fn set_data_limit(&mut self, slots: usize) {
        self.out.data_limit_slots = slots;
    }

    pub(super) fn finish(mut self) -> Declared {
        for p in 0..self.model.pous.len() {
            self.ensure_emitted(p);
        }
        super::implicit_checks::warn_other_signatures(&self.model, self.diags);
        self.model.emitted = self
            .emit_state
            .iter()
            .map(|s| *s == LayoutState::Done)
            .collect();
        Declared {
            model: self.model,
            types: self.types,
            out: self.out,
        }
    }

    /// Emits POU `p` (after laying it out) unless already done, and records
    /// its frame size and constant slots.
    pub(super) fn ensure_emitted(&mut self, p: usize) {
        self.layout_pou(p);
        if self.pou_state[p] != LayoutState::Done || self.emit_state[p] != LayoutState::Pending {
            return;
        }
        self.emit_state[p] = LayoutState::InProgress;
        self.resolve_pending_enums();
        let (u, i) = self.model.pous[p].ast;
        let units = self.units;
        let Item::Pou(pou) = &units[u].items[i] else {
            return;
        };
        self.layout_callees(pou);
        let builder = BodyBuilder::new(&self.model, &mut self.types, &mut self.out, self.diags, p);
        let built = builder.build(pou);
        self.model.pous[p].consts = built.consts;
        let ty = self.model.pous[p].ty;
        let mut def: TypeDef = self.types.get(ty).clone();
        def.size = built.frame_size;
        self.types.set(ty, def);
        self.emit_state[p] = LayoutState::Done;
    }
}

impl Declarer<'_> {
    /// Lays out the FUNCTIONs `pou`'s body and methods name before the
    /// body is emitted: a body can be emitted while the declarations are
    /// still being laid out (an FB instance's size includes its body's
    /// temporaries), and a call binds its arguments to the callee's laid
    /// out parameters.
    fn layout_callees(&mut self, pou: &Pou) {
        let mut names: Vec<String> = Vec::new();
        let mut note = |name: &str| {
            names.push(name.to_ascii_uppercase());
            false
        };
        super::body_names::any_name(&pou.body, &mut note);
        if let Some(oop) = &pou.oop {
            for m in &oop.methods {
                super::body_names::any_name(&m.body, &mut note);
                for accessor in m.property.iter().flatten() {
                    super::body_names::any_name(&accessor.body, &mut note);
                }
            }
        }
        // The project's implicit checks: the body may call them though it
        // does not name them.
        names.extend(super::implicit_checks::names().map(str::to_string));
        for name in names {
            if let Some(&q) = self.model.pou_index.get(&name)
                && self.model.pous[q].kind == PouKind::Function
                && self.pou_state[q] == LayoutState::Pending
            {
                self.layout_pou(q);
            }
        }
    }

    /// Resolves the enumeration TYPEs not resolved yet, for a body emitted
    /// while TYPE declarations are still being resolved (an FB instance in
    /// a structure): the body reads types from the model and cannot resolve
    /// one on demand, and an enumeration's resolution lays out and emits
    /// nothing.
    fn resolve_pending_enums(&mut self) {
        for k in std::mem::take(&mut self.pending_enums) {
            if !self.model.type_ids.contains_key(&k) {
                let span = self.type_decl_span(&k);
                self.user_type(&k, span);
            }
            self.pending_enums.push(k);
        }
    }

    /// Collects every declaration and lays out all POUs.
    pub(super) fn declare_all(&mut self) {
        let units = self.units;
        for (u, unit) in units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                match item {
                    Item::Pou(p) => self.register_pou(p, (u, i)),
                    Item::Types(decls) => self.register_types(decls, u, i),
                    Item::Configuration(_) | Item::Globals(_) | Item::Interface(_) => {}
                }
            }
        }
        self.report_type_pou_clashes();
        self.register_type_class();
        self.register_exception_code();
        // Constants of plain values first: a TYPE may size an array with
        // one (TwinCAT's parameter lists, `ARRAY[1..GVL.MaxN]`).
        let mut early: Vec<((usize, usize), Vec<usize>)> = Vec::new();
        for (u, unit) in units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                if let Item::Globals(block) = item {
                    let plain = super::const_order::plain_constants(block);
                    self.declare_global_decls(block, &|d| plain.contains(&d), false);
                    early.push(((u, i), plain));
                }
            }
        }
        // Then the structure and array constants (a TYPE's field default
        // may copy one), which may use the plain ones.
        let variables: std::collections::HashSet<String> = units
            .iter()
            .flat_map(|u| &u.items)
            .filter_map(|item| match item {
                Item::Globals(b) if !b.constant => Some(b),
                _ => None,
            })
            .flat_map(|b| &b.decls)
            .flat_map(|d| &d.names)
            .map(|n| n.key())
            .collect();
        for ((u, i), plain) in early.iter_mut() {
            let Item::Globals(block) = &units[*u].items[*i] else {
                continue;
            };
            let is_block = |key: &str| self.model.pou_index.contains_key(key);
            let values = super::const_order::value_constants(block, &variables, &is_block);
            self.declare_global_decls(block, &|d| values.contains(&d), false);
            plain.extend(values);
        }
        // Resolving a TYPE that holds a function block instance emits the
        // block's body, which may read a global: when one does, the
        // globals of elementary types (and strings) come first too. Other
        // programs keep their globals' order.
        if self.a_type_holds_a_block() {
            for ((u, i), plain) in early.iter_mut() {
                let Item::Globals(block) = &units[*u].items[*i] else {
                    continue;
                };
                let simple: Vec<usize> = (0..block.decls.len())
                    .filter(|&d| !plain.contains(&d) && is_elementary(&block.decls[d]))
                    .collect();
                self.declare_global_decls(block, &|d| simple.contains(&d), false);
                plain.extend(simple);
            }
        }
        self.resolve_types();
        // Globals: top-level lists, their function block instances and
        // references to blocks last (laying one out emits the block's body,
        // which may use a global the list declares after it: TwinCAT's
        // `TcUnitRunner : FB_TcUnitRunner;` first in its list), then
        // configurations and resources.
        let mut instances: Vec<(&VarBlock, Vec<usize>)> = Vec::new();
        for unit in units.iter() {
            for item in &unit.items {
                if let Item::Globals(block) = item {
                    let held = self.instance_decls(block);
                    instances.push((block, held));
                }
            }
        }
        for (u, unit) in units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                if let Item::Globals(block) = item {
                    let plain = early
                        .iter()
                        .find(|(at, _)| *at == (u, i))
                        .map(|(_, p)| p.as_slice())
                        .unwrap_or_default();
                    let held = instances
                        .iter()
                        .find(|(b, _)| std::ptr::eq(*b, block))
                        .map(|(_, h)| h.as_slice())
                        .unwrap_or_default();
                    let pick = |d: usize| !plain.contains(&d) && !held.contains(&d);
                    self.declare_global_decls(block, &pick, true);
                }
            }
        }
        // One call per run of declarations in written order within a list.
        let order = self.instance_order(&instances);
        for run in order.chunk_by(|a, b| a.0 == b.0 && a.1 < b.1) {
            let block = instances[run[0].0].0;
            let pick = |d: usize| run.binary_search_by_key(&d, |&(_, x)| x).is_ok();
            self.declare_global_decls(block, &pick, false);
        }
        for unit in units.iter() {
            for item in &unit.items {
                if let Item::Configuration(cfg) = item {
                    for b in &cfg.globals {
                        self.declare_globals(b);
                    }
                    for r in &cfg.resources {
                        for b in &r.globals {
                            self.declare_globals(b);
                        }
                    }
                }
            }
        }
        // Host POUs first: a body may be emitted while laying out a later
        // POU, and the test assertions call host functions it cannot name.
        let is_host =
            |m: &Model, p: usize| m.host_pous.contains(&m.pous[p].name.to_ascii_uppercase());
        let n = self.model.pous.len();
        let hosts: Vec<usize> = (0..n).filter(|&p| is_host(&self.model, p)).collect();
        // Then the FUNCTIONs' interfaces (laying one out emits no body): an
        // FB body emitted while laying out an earlier POU may call a
        // function declared after it (OSCAT does), and binds its arguments
        // to the parameters.
        let functions: Vec<usize> = (0..n)
            .filter(|&p| self.model.pous[p].kind == PouKind::Function)
            .collect();
        for p in hosts.into_iter().chain(functions).chain(0..n) {
            self.layout_pou(p);
        }
    }

    /// Registers POU `p` at `ast` (unit, item), unless its name is taken.
    fn register_pou(&mut self, p: &Pou, ast: (usize, usize)) {
        let (u, i) = ast;
        let key = p.name.key();
        if let Some(&prev) = self.model.pou_index.get(&key) {
            let prev_span = self.model.pous[prev].span;
            let loc = prev_span;
            self.diags.push(
                crate::diagnostics::Diagnostic::error(
                    "E202",
                    p.name.span,
                    format!("`{}` is declared twice", p.name.name),
                )
                .with_note(format!(
                    "the first declaration is at byte {} of the same or another file",
                    loc.start
                )),
            );
            return;
        }
        if let Some(w) = super::assert_shadow::assertion_shadow_warning(p, &self.model.host_pous) {
            self.diags.push(w);
        }
        if super::stdfuncs::is_standard_function(&p.name.name) {
            // The user's definition wins (OSCAT defines its own TIME_TO_TOD).
            self.diags.push(super::std_shadow::shadow_warning(p));
        } else if stdlib::lookup_native(&p.name.name).is_some() {
            self.diags.error(
                "E202",
                p.name.span,
                format!("`{}` is the name of a standard function block", p.name.name),
            );
            return;
        }
        self.model.pou_index.insert(key, self.model.pous.len());
        self.model.pous.push(PouInfo {
            name: p.name.name.clone(),
            kind: p.kind,
            ast: (u, i),
            ty: TypeTable::error(),
            ret: TypeTable::void(),
            vars: IndexMap::new(),
            params: Vec::new(),
            code: crate::ir::op::CodeIdx::new(u32::MAX),
            vars_size: 0,
            consts: Vec::new(),
            span: p.name.span,
            no_check: p.no_check,
        });
        self.pou_state.push(LayoutState::Pending);
        self.emit_state.push(LayoutState::Pending);
    }

    /// Registers the TYPE declarations of item `i` of unit `u`.
    fn register_types(&mut self, decls: &[TypeDecl], u: usize, i: usize) {
        for (d, decl) in decls.iter().enumerate() {
            let key = decl.name.key();
            if self.type_decls.contains_key(&key) || ElemType::from_name(&key).is_some() {
                self.diags.error(
                    "E202",
                    decl.name.span,
                    format!("type `{}` is declared twice", decl.name.name),
                );
                continue;
            }
            self.type_decls.insert(key, (u, i, d));
        }
    }

    /// Reports names declared both as a type and as a POU.
    fn report_type_pou_clashes(&mut self) {
        let units = self.units;
        // Types that clash with POU names.
        let mut clashes: Vec<(String, Span)> = Vec::new();
        for (k, &(u, i, d)) in &self.type_decls {
            if let (true, Item::Types(decls)) =
                (self.model.pou_index.contains_key(k), &units[u].items[i])
            {
                clashes.push((k.clone(), decls[d].name.span));
            }
        }
        clashes.sort_by_key(|(_, span)| (span.file, span.start));
        for (k, span) in clashes {
            self.diags.error(
                "E202",
                span,
                format!("`{k}` is declared both as a type and as a POU"),
            );
        }
    }

    /// Resolves every TYPE declaration, in source order.
    fn resolve_types(&mut self) {
        let units = self.units;
        let mut keys: Vec<(usize, usize, usize, String)> = self
            .type_decls
            .iter()
            .map(|(k, &(u, i, d))| (u, i, d, k.clone()))
            .collect();
        keys.sort();
        self.pending_enums = keys
            .iter()
            .filter(|(u, i, d, _)| {
                matches!(&units[*u].items[*i], Item::Types(decls)
                    if matches!(decls[*d].ty, TypeSpec::Enum { .. }))
            })
            .map(|(_, _, _, k)| k.clone())
            .collect();
        for (_, _, _, k) in keys {
            let span = self.type_decl_span(&k);
            self.user_type(&k, span);
        }
        self.pending_enums.clear();
    }

    /// The span of TYPE declaration `key`.
    fn type_decl_span(&self, key: &str) -> Span {
        let Some(&(u, i, d)) = self.type_decls.get(key) else {
            return Span::default();
        };
        match &self.units[u].items[i] {
            Item::Types(decls) => decls[d].name.span,
            _ => Span::default(),
        }
    }

    /// E121: constants whose initial values depend on each other in a ring.
    pub(super) fn report_constant_cycle(&mut self, block: &VarBlock, cycle: &[usize]) {
        let names: Vec<&str> = cycle
            .iter()
            .filter_map(|&d| block.decls[d].names.first())
            .map(|n| n.name.as_str())
            .collect();
        let first = names.first().copied().unwrap_or_default();
        self.diags.error(
            super::const_order::CONSTANT_CYCLE,
            block.decls[cycle[0]].span,
            format!(
                "constants defined in terms of each other: {} -> {first}",
                names.join(" -> ")
            ),
        );
    }

    /// Whether a field of a STRUCT type holds instances of a user
    /// FUNCTION_BLOCK, alone or in an array (`Axis : AXIS_REF;` in
    /// `ST_MotionStage`).
    fn a_type_holds_a_block(&self) -> bool {
        self.units
            .iter()
            .flat_map(|u| &u.items)
            .any(|item| match item {
                Item::Types(decls) => decls.iter().any(|t| match &t.ty {
                    TypeSpec::Struct { fields, .. } => {
                        fields.iter().any(|f| self.holds_block(&f.ty))
                    }
                    _ => false,
                }),
                _ => false,
            })
    }

    /// Whether `ty` names a user FUNCTION_BLOCK or is an array of them.
    fn holds_block(&self, ty: &TypeSpec) -> bool {
        match ty {
            TypeSpec::Named(id) => self
                .model
                .pou_index
                .get(&id.key())
                .is_some_and(|&p| self.model.pous[p].kind == PouKind::FunctionBlock),
            TypeSpec::Array { elem, .. } => self.holds_block(elem),
            _ => false,
        }
    }

    /// Declares the globals of one VAR_GLOBAL block: storage, initial value,
    /// constants after the constants they are computed from.
    fn declare_globals(&mut self, block: &VarBlock) {
        self.declare_global_decls(block, &|_| true, true);
    }

    /// Declares the declarations `pick` accepts of a VAR_GLOBAL block;
    /// `report` says whether the block's own errors (E210, E121) are
    /// reported by this call.
    fn declare_global_decls(
        &mut self,
        block: &VarBlock,
        pick: &dyn Fn(usize) -> bool,
        report: bool,
    ) {
        use crate::ir::type_table::Retention;
        let retained = matches!(
            super::layout::retention(block),
            Retention::Retain | Retention::Persistent
        );
        if retained && block.constant && report {
            self.diags.error(
                "E210",
                block.span,
                "RETAIN and PERSISTENT cannot apply here: a CONSTANT never changes",
            );
        }
        let (order, cycles) = super::const_order::dependency_order(block);
        for cycle in cycles.iter().filter(|_| report) {
            self.report_constant_cycle(block, cycle);
        }
        for decl in order.iter().filter(|&&d| pick(d)).map(|&d| &block.decls[d]) {
            let ty = self.resolve_type(&decl.ty, None);
            if matches!(self.types.get(ty).kind, TypeKind::Pou { program: true, .. }) {
                self.diags.error(
                    "E209",
                    decl.ty.span(),
                    "a PROGRAM cannot be used as a variable type",
                );
                continue;
            }
            let no_value = self.static_reference_init(decl, ty, "a global variable");
            let init = decl
                .init
                .as_ref()
                .filter(|_| !no_value)
                .and_then(|i| self.consts().resolve_init(i, ty, None));
            for name in &decl.names {
                let key = name.key();
                if self.model.globals.contains_key(&key) {
                    self.diags.error(
                        "E202",
                        name.span,
                        format!("global `{}` is declared twice", name.name),
                    );
                    continue;
                }
                let (addr, location) = match &decl.location {
                    Some(a) => match self.out.located_slot(&self.types, self.diags, a, ty) {
                        Some(addr) => (addr, Some(normalize_address(a))),
                        None => continue,
                    },
                    None => (self.out.alloc_abs(self.diags, self.types.size(ty)), None),
                };
                let value = if block.constant {
                    init.as_ref().and_then(super::decl_consts::init_const)
                } else {
                    None
                };
                if block.constant && value.is_none() && !self.is_aggregate(ty) {
                    self.diags.error(
                        "E205",
                        name.span,
                        format!("constant `{}` needs a constant initial value", name.name),
                    );
                }
                let retention = super::layout::retention(block);
                if retention != crate::ir::type_table::Retention::Inherit {
                    self.model.global_retention.insert(key.clone(), retention);
                }
                self.model.globals.insert(
                    key,
                    VarInfo {
                        name: name.name.clone(),
                        ty,
                        kind: MemberKind::Local,
                        storage: Storage::Abs(addr),
                        constant: block.constant,
                        value,
                        init: init.clone(),
                        location,
                    },
                );
            }
        }
    }

    /// True for arrays and structures (their CONSTANT needs no folded value).
    pub(super) fn is_aggregate(&self, ty: TypeId) -> bool {
        matches!(
            self.types.get(ty).kind,
            TypeKind::Array { .. } | TypeKind::Struct { .. }
        )
    }
}

impl TypeKind {
    /// True for types whose values can be copied (not FB instances).
    pub fn is_value_type(&self) -> bool {
        !matches!(
            self,
            TypeKind::NativeFb(_) | TypeKind::Pou { .. } | TypeKind::Step
        )
    }
}

/// Whether a global's declaration has an elementary or string type and
/// no location (a located variable is placed with the process image).
fn is_elementary(decl: &VarDecl) -> bool {
    decl.location.is_none()
        && match &decl.ty {
            TypeSpec::Named(id) => ElemType::from_name(&id.name).is_some(),
            TypeSpec::String { .. } => true,
            _ => false,
        }
}

#[cfg(test)]
mod tests {
    use crate::diagnostics::Diagnostics;
    use crate::sema::{CompileOptions, compile};
    use crate::source::FileId;

    /// Compiles one ST source; returns the diagnostic codes.
    fn codes(src: &str) -> Vec<String> {
        let mut diags = Diagnostics::new();
        let unit = crate::syntax::parse(FileId(0), src, &mut diags);
        let options = CompileOptions {
            check_only: true,
            ..CompileOptions::default()
        };
        compile(&[unit], &options, &mut diags);
        diags.iter().map(|d| d.code.to_string()).collect()
    }

    #[test]
    fn an_fb_body_emitted_while_types_are_resolved_sees_later_enumerations() {
        // `S` holds an instance of `Blk`, so `Blk`'s body is emitted while
        // `S` is resolved, before `Color` would be.
        let src = "
TYPE S : STRUCT b : Blk; END_STRUCT; END_TYPE
TYPE Color : (Red, Green); END_TYPE
FUNCTION_BLOCK Blk
VAR x : BOOL; END_VAR
x := Color#Green = Color#Red;
END_FUNCTION_BLOCK
PROGRAM Main
VAR s : S; END_VAR
s.b();
END_PROGRAM
";
        assert_eq!(codes(src), Vec::<String>::new());
    }
}
