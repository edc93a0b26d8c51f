//! The lowering pass: flattens inheritance, turns method variables into
//! hidden FB variables and interfaces into structure types, and checks the
//! declarations (E901-E917). Runs before the declaration phase, only on a
//! program that uses object orientation (others are not copied).

use super::model::{
    ADDR_FIELD, BODY, FbOop, ItfInfo, ItfMethod, OopInfo, ParamSig, Signature, TID_FIELD, Version,
};
use crate::diagnostics::Diagnostics;
use crate::source::Span;
use crate::syntax::ast::{
    Body, CompilationUnit, Ident, Item, Pou, PouKind, StmtKind, TypeDecl, TypeSpec, VarBlock,
    VarDecl, VarKind,
};
use crate::syntax::oop::{Interface, Method, PouOop};
use indexmap::IndexMap;
use std::collections::{HashMap, HashSet};

/// The lowered sources and what they declare, or `None` when no source uses
/// object orientation (then the sources are compiled as they are).
pub(crate) fn lower(
    units: &[CompilationUnit],
    guarded: &HashSet<String>,
    diags: &mut Diagnostics,
) -> Option<(Vec<CompilationUnit>, OopInfo)> {
    let uses_oop = units.iter().flat_map(|u| &u.items).any(|i| match i {
        Item::Interface(_) => true,
        Item::Pou(p) => p.oop.is_some(),
        _ => false,
    });
    if !uses_oop {
        return None;
    }
    let mut l = Lowering {
        units: units.to_vec(),
        diags,
        info: OopInfo::default(),
        fb_at: HashMap::new(),
        itf_closure: HashMap::new(),
        flat: HashMap::new(),
        guarded,
    };
    l.index_fbs();
    l.lower_interfaces();
    let order = l.fb_order();
    for key in order {
        l.lower_fb(&key);
    }
    l.check_abstract_instances();
    super::class::collect(units, &mut l.info, l.diags);
    super::var_access::collect(units, &mut l.info);
    super::property::check_names(units, &l.info, l.diags);
    Some((l.units, l.info))
}

struct Lowering<'d> {
    units: Vec<CompilationUnit>,
    diags: &'d mut Diagnostics,
    info: OopInfo,
    /// Every FUNCTION_BLOCK: key -> (unit, item).
    fb_at: HashMap<String, (usize, usize)>,
    /// Every interface with those it extends, directly or not.
    itf_closure: HashMap<String, Vec<String>>,
    /// Flattened variable blocks of each lowered FB.
    flat: HashMap<String, Vec<VarBlock>>,
    /// Methods (`ORIGIN.METHOD`) that get a re-entry guard.
    guarded: &'d HashSet<String>,
}

/// The hidden name of variable `var` of method `method` declared in `origin`.
pub(crate) fn hidden_name(origin: &str, method: &str, var: &str) -> String {
    format!("{origin}__{method}__{var}")
}

/// A type written in a declaration, as comparable text (no positions).
fn spec_text(t: &TypeSpec) -> String {
    let dbg = format!("{t:?}");
    let mut out = String::with_capacity(dbg.len());
    let mut rest = dbg.as_str();
    while let Some(at) = rest.find("span: Span {") {
        out.push_str(&rest[..at]);
        let after = &rest[at..];
        let close = after.find('}').map(|c| c + 1).unwrap_or(after.len());
        rest = &after[close..];
    }
    out.push_str(rest);
    out.to_ascii_uppercase()
}

impl Lowering<'_> {
    /// Whether `key` names an elementary type, a standard block, or a POU,
    /// type or interface of the sources.
    fn declares(&self, key: &str) -> bool {
        if crate::elementary::ElemType::from_name(key).is_some()
            || crate::stdlib::lookup_native(key).is_some()
        {
            return true;
        }
        self.units
            .iter()
            .flat_map(|u| &u.items)
            .any(|item| match item {
                Item::Pou(p) => p.name.key() == key,
                Item::Types(ts) => ts.iter().any(|t| t.name.key() == key),
                Item::Interface(i) => i.name.key() == key,
                Item::Globals(_) | Item::Configuration(_) => false,
            })
    }

    fn pou(&self, at: (usize, usize)) -> Option<&Pou> {
        match &self.units[at.0].items[at.1] {
            Item::Pou(p) => Some(p),
            _ => None,
        }
    }

    fn index_fbs(&mut self) {
        for (u, unit) in self.units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                // A PROGRAM with methods is lowered as its one instance's FB.
                if let Item::Pou(p) = item
                    && (p.kind == PouKind::FunctionBlock
                        || (p.kind == PouKind::Program && p.oop.is_some()))
                {
                    self.fb_at.entry(p.name.key()).or_insert((u, i));
                }
            }
        }
    }

    /// Interfaces: closure of EXTENDS, method tables, and the two structure
    /// types each becomes (the value, and the signature that types its
    /// parameters).
    fn lower_interfaces(&mut self) {
        let mut src: IndexMap<String, ((usize, usize), Interface)> = IndexMap::new();
        for (u, unit) in self.units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                if let Item::Interface(x) = item {
                    src.entry(x.name.key()).or_insert(((u, i), x.clone()));
                }
            }
        }
        for (key, (_, x)) in &src {
            let mut seen = vec![key.clone()];
            let mut todo: Vec<&Ident> = x.extends.iter().collect();
            while let Some(e) = todo.pop() {
                let k = e.key();
                if k == *key {
                    self.diags.error(
                        "E903",
                        e.span,
                        format!(
                            "interface `{}` extends itself through `{}`",
                            x.name.name, e.name
                        ),
                    );
                    continue;
                }
                if seen.contains(&k) {
                    continue;
                }
                match src.get(&k) {
                    Some((_, parent)) => {
                        seen.push(k);
                        todo.extend(parent.extends.iter());
                    }
                    None => self.diags.error(
                        "E911",
                        e.span,
                        format!("`{}` is not an interface", e.name),
                    ),
                }
            }
            self.itf_closure.insert(key.clone(), seen);
        }
        for (key, ((u, i), x)) in &src {
            let mut methods: IndexMap<String, ItfMethod> = IndexMap::new();
            let mut fields: Vec<VarDecl> = Vec::new();
            for k in self.itf_closure.get(key).cloned().unwrap_or_default() {
                let Some((_, owner)) = src.get(&k) else {
                    continue;
                };
                for m in &owner.methods {
                    if methods.contains_key(&m.name.key()) {
                        continue;
                    }
                    if k == *key && !body_is_empty(&m.body) {
                        self.diags.error(
                            "E917",
                            m.name.span,
                            format!(
                                "method `{}` of interface `{}` is a prototype: it cannot have statements",
                                m.name.name, x.name.name
                            ),
                        );
                    }
                    let (v, blocks) = self.method_version(&owner.name.name, m);
                    for b in blocks.into_iter().filter(|b| b.kind != VarKind::External) {
                        fields.extend(b.decls);
                    }
                    methods.insert(
                        m.name.key(),
                        ItfMethod {
                            name: m.name.clone(),
                            params: v.params,
                            ret: v.ret,
                            sig: v.sig,
                        },
                    );
                }
            }
            let sig_name = format!("{}__SIG", x.name.name);
            if fields.is_empty() {
                fields.push(field("__NONE", "BOOL", x.span));
            }
            let value = TypeDecl {
                name: x.name.clone(),
                ty: TypeSpec::Struct {
                    extends: None,
                    fields: vec![
                        field(ADDR_FIELD, "ULINT", x.span),
                        field(TID_FIELD, "UDINT", x.span),
                    ],
                    span: x.span,
                    union: false,
                },
                init: None,
                span: x.span,
                qualified_only: false,
                strict: false,
            };
            let sig = TypeDecl {
                name: Ident {
                    name: sig_name.clone(),
                    span: x.name.span,
                },
                ty: TypeSpec::Struct {
                    extends: None,
                    fields,
                    span: x.span,
                    union: false,
                },
                init: None,
                span: x.span,
                qualified_only: false,
                strict: false,
            };
            self.units[*u].items[*i] = Item::Types(vec![value, sig]);
            self.info.interfaces.insert(
                key.clone(),
                ItfInfo {
                    name: x.name.name.clone(),
                    methods,
                    sig_type: sig_name.to_ascii_uppercase(),
                    ancestors: self.itf_closure.get(key).cloned().unwrap_or_default(),
                },
            );
        }
    }

    /// The FBs to lower (those using OOP, and their ancestors), parents
    /// first. Breaks EXTENDS cycles (E903) and bad parents (E902, E904).
    fn fb_order(&mut self) -> Vec<String> {
        let mut parent: HashMap<String, String> = HashMap::new();
        let mut members: Vec<String> = Vec::new();
        let oop_fbs: Vec<String> = self
            .fb_at
            .iter()
            .filter(|(_, at)| self.pou(**at).is_some_and(|p| p.oop.is_some()))
            .map(|(k, _)| k.clone())
            .collect();
        let mut todo = oop_fbs;
        todo.sort_by_key(|k| self.fb_at[k]);
        while let Some(k) = todo.pop() {
            if members.contains(&k) {
                continue;
            }
            members.push(k.clone());
            let Some(oop) = self.pou(self.fb_at[&k]).and_then(|p| p.oop.clone()) else {
                continue;
            };
            let Some(ext) = &oop.extends else { continue };
            let pk = ext.key();
            let Some(&pat) = self.fb_at.get(&pk) else {
                let why = if self.declares(&pk) {
                    "is not a FUNCTION_BLOCK: only function blocks can be extended"
                } else {
                    "is not declared: there is no function block of that name to extend"
                };
                self.diags
                    .error("E902", ext.span, format!("`{}` {why}", ext.name));
                continue;
            };
            if self
                .pou(pat)
                .and_then(|p| p.oop.as_ref())
                .is_some_and(|o| o.mods.is_final)
            {
                self.diags.error(
                    "E904",
                    ext.span,
                    format!("`{}` is FINAL: it cannot be extended", ext.name),
                );
            }
            parent.insert(k.clone(), pk.clone());
            todo.push(pk);
        }
        // Cycles: walk each chain at most `members.len()` steps.
        let mut depth: HashMap<String, usize> = HashMap::new();
        members.sort_by_key(|k| self.fb_at[k]);
        for k in &members {
            let mut seen = HashSet::new();
            let mut at = k.clone();
            let mut d = 0;
            seen.insert(at.clone());
            while let Some(p) = parent.get(&at) {
                if !seen.insert(p.clone()) {
                    let ext = self
                        .pou(self.fb_at[k])
                        .and_then(|p| p.oop.as_ref())
                        .and_then(|o| o.extends.clone());
                    let span = ext.map(|e| e.span).unwrap_or_default();
                    self.diags.error(
                        "E903",
                        span,
                        format!("`{}` extends itself (a cycle of EXTENDS)", self.name_of(k)),
                    );
                    d = usize::MAX;
                    break;
                }
                at = p.clone();
                d += 1;
            }
            depth.insert(k.clone(), d);
        }
        members.retain(|k| depth[k] != usize::MAX);
        members.sort_by_key(|k| (depth[k], self.fb_at[k]));
        for (n, k) in members.iter().enumerate() {
            let pou = self.pou(self.fb_at[k]).cloned();
            let Some(pou) = pou else { continue };
            let oop = pou.oop.as_deref().cloned().unwrap_or_default();
            self.info.fbs.insert(
                k.clone(),
                FbOop {
                    name: pou.name.name.clone(),
                    tid: n as u32 + 1,
                    parent: parent.get(k).cloned(),
                    is_abstract: oop.mods.is_abstract,
                    versions: Vec::new(),
                    dispatch: IndexMap::new(),
                    interfaces: Vec::new(),
                    codes: Vec::new(),
                },
            );
        }
        members
    }

    fn name_of(&self, key: &str) -> String {
        self.fb_at
            .get(key)
            .and_then(|at| self.pou(*at))
            .map(|p| p.name.name.clone())
            .unwrap_or_else(|| key.to_string())
    }

    /// Lowers one FB whose parent (if any) is lowered already.
    fn lower_fb(&mut self, key: &str) {
        let at = self.fb_at[key];
        let Some(pou) = self.pou(at).cloned() else {
            return;
        };
        let oop: PouOop = pou.oop.as_deref().cloned().unwrap_or_default();
        let parent = self.info.fbs[key].parent.clone();
        let mut flat = Vec::new();
        let mut versions = Vec::new();
        let mut dispatch = IndexMap::new();
        let mut interfaces = Vec::new();
        if let Some(p) = &parent {
            flat = self.flat.get(p).cloned().unwrap_or_default();
            let pf = &self.info.fbs[p];
            versions = pf.versions.clone();
            dispatch = pf.dispatch.clone();
            interfaces = pf.interfaces.clone();
            if let Some(pp) = self.pou(self.fb_at[p])
                && !matches!(pp.body, Body::Sfc(_))
                && !body_is_empty(&pp.body)
            {
                versions.push(Version {
                    origin: p.clone(),
                    name: Ident {
                        name: BODY.to_string(),
                        span: pp.name.span,
                    },
                    mods: Default::default(),
                    params: Vec::new(),
                    ret: None,
                    locals: HashMap::new(),
                    resets: Vec::new(),
                    body: pp.body.clone(),
                    span: pp.span,
                    sig: (Vec::new(), String::new()),
                    guard: None,
                    no_check: pp.no_check,
                });
            }
        }
        flat.extend(pou.var_blocks.iter().cloned());
        let mut own: HashSet<String> = HashSet::new();
        for m in &oop.methods {
            let mk = m.name.key();
            if !own.insert(mk.clone()) {
                self.diags.error(
                    "E916",
                    m.name.span,
                    format!(
                        "method `{}` is declared twice in `{}`",
                        m.name.name, pou.name.name
                    ),
                );
                continue;
            }
            let (mut v, blocks) = self.method_version(&pou.name.name, m);
            v.origin = key.to_string();
            if let Some(&old) = dispatch.get(&mk) {
                let o: &Version = &versions[old];
                if o.mods.is_final {
                    self.diags.error(
                        "E905",
                        m.name.span,
                        format!(
                            "method `{}` is FINAL in `{}`: it cannot be overridden",
                            m.name.name,
                            self.name_of(&o.origin)
                        ),
                    );
                }
                // A derived FB_init repeats its parent's parameters and may
                // add more (CODESYS, TwinCAT).
                let extends_init =
                    mk == "FB_INIT" && v.sig.0.starts_with(&o.sig.0) && v.sig.1 == o.sig.1;
                if o.sig != v.sig && !extends_init {
                    self.diags.error(
                        "E906",
                        m.name.span,
                        format!(
                            "method `{}` overrides `{}.{}` with another signature (parameters, their sections and types, and the result type must be the same)",
                            m.name.name,
                            self.name_of(&o.origin),
                            o.name.name
                        ),
                    );
                }
            }
            if m.mods.is_abstract && !oop.mods.is_abstract {
                self.diags.error(
                    "E908",
                    m.name.span,
                    format!(
                        "method `{}` is ABSTRACT but `{}` is not: declare the FB ABSTRACT",
                        m.name.name, pou.name.name
                    ),
                );
            }
            dispatch.insert(mk, versions.len());
            versions.push(v);
            for b in blocks {
                push_method_block(&mut flat, b);
            }
        }
        for i in &oop.implements {
            match self.itf_closure.get(&i.key()) {
                Some(c) => {
                    for k in c {
                        if !interfaces.contains(k) {
                            interfaces.push(k.clone());
                        }
                    }
                }
                None => {
                    self.diags
                        .error("E911", i.span, format!("`{}` is not an interface", i.name))
                }
            }
        }
        if !oop.mods.is_abstract {
            self.check_complete(&pou, &versions, &dispatch, &interfaces);
        }
        let fb = self.info.fbs.get_mut(key).expect("registered in fb_order");
        fb.versions = versions;
        fb.dispatch = dispatch;
        fb.interfaces = interfaces;
        if pou.oop.is_some()
            && let Item::Pou(p) = &mut self.units[at.0].items[at.1]
        {
            p.var_blocks = flat.clone();
        }
        self.flat.insert(key.to_string(), flat);
    }

    /// E908 (an abstract method left without implementation), E909/E910
    /// (interface methods missing or with another signature).
    fn check_complete(
        &mut self,
        pou: &Pou,
        versions: &[Version],
        dispatch: &IndexMap<String, usize>,
        interfaces: &[String],
    ) {
        for &v in dispatch.values() {
            let v = &versions[v];
            if v.mods.is_abstract {
                self.diags.error(
                    "E908",
                    pou.name.span,
                    format!(
                        "`{}` must implement the ABSTRACT method `{}` of `{}` (or be declared ABSTRACT)",
                        pou.name.name,
                        v.name.name,
                        self.name_of(&v.origin)
                    ),
                );
            }
        }
        for i in interfaces {
            let Some(itf) = self.info.interfaces.get(i).cloned() else {
                continue;
            };
            for (mk, m) in &itf.methods {
                match dispatch.get(mk) {
                    None => self.diags.error(
                        "E909",
                        pou.name.span,
                        format!(
                            "`{}` implements `{}` but has no method `{}`",
                            pou.name.name, itf.name, m.name.name
                        ),
                    ),
                    Some(&v) if versions[v].sig != m.sig => self.diags.error(
                        "E910",
                        versions[v].name.span,
                        format!(
                            "method `{}` does not match its prototype in interface `{}` (parameters, their sections and types, and the result type must be the same)",
                            m.name.name, itf.name
                        ),
                    ),
                    Some(_) => {}
                }
            }
        }
    }

    /// A method's version and the hidden variable blocks that hold its
    /// variables (`origin` is the declaring FB's or interface's name).
    fn method_version(&mut self, origin: &str, m: &Method) -> (Version, Vec<VarBlock>) {
        let mut params = Vec::new();
        let mut locals = HashMap::new();
        let mut resets = Vec::new();
        let mut sig = Vec::new();
        let mut blocks = Vec::new();
        // Every name first: a declaration may use a constant declared after it.
        for b in &m.var_blocks {
            if matches!(
                b.kind,
                VarKind::Input
                    | VarKind::InOut
                    | VarKind::Output
                    | VarKind::Local
                    | VarKind::Temp
                    | VarKind::Inst
                    | VarKind::Stat
            ) {
                for n in b.decls.iter().flat_map(|d| &d.names) {
                    let hidden = hidden_name(origin, &m.name.name, &n.name);
                    locals.insert(n.key(), hidden.to_ascii_uppercase());
                }
            }
        }
        for b in &m.var_blocks {
            if b.kind == VarKind::External {
                // The globals keep their names; the FB declares each once.
                blocks.push(b.clone());
                continue;
            }
            let input = match b.kind {
                VarKind::Input | VarKind::InOut => Some(true),
                VarKind::Output => Some(false),
                VarKind::Local | VarKind::Temp | VarKind::Inst | VarKind::Stat => None,
                _ => {
                    self.diags.error(
                        "E915",
                        b.span,
                        "a METHOD may declare VAR_INPUT, VAR_OUTPUT, VAR_IN_OUT, VAR_EXTERNAL, VAR, VAR_TEMP, VAR_INST and VAR_STAT only",
                    );
                    continue;
                }
            };
            let in_out = b.kind == VarKind::InOut;
            let mut decls = Vec::new();
            for d in &b.decls {
                let mut names = Vec::new();
                for n in &d.names {
                    let hidden = hidden_name(origin, &m.name.name, &n.name);
                    let hk = hidden.to_ascii_uppercase();
                    locals.insert(n.key(), hk.clone());
                    match input {
                        Some(inp) => {
                            params.push(ParamSig {
                                name: n.name.clone(),
                                input: inp,
                                hidden: hk.clone(),
                                in_out,
                            });
                            let ty = match in_out {
                                true => format!("VAR_IN_OUT {}", spec_text(&d.ty)),
                                false => spec_text(&d.ty),
                            };
                            sig.push((n.key(), inp, ty));
                            if !inp {
                                resets.push(hk);
                            }
                        }
                        // VAR_INST keeps its value from call to call.
                        None if matches!(b.kind, VarKind::Inst | VarKind::Stat) => {}
                        None => resets.push(hk),
                    }
                    names.push(Ident {
                        name: hidden,
                        span: n.span,
                    });
                }
                let scoped = super::method_scope::in_method_scope(d, &locals);
                decls.push(VarDecl {
                    names,
                    location: None,
                    ty: scoped.ty,
                    init: scoped.init,
                    span: d.span,
                    edge: None,
                    init_args: None,
                });
            }
            blocks.push(VarBlock {
                kind: match b.kind {
                    _ if in_out => VarKind::InOut,
                    // A method's statics stay statics of its block.
                    VarKind::Stat => VarKind::Stat,
                    _ => VarKind::Local,
                },
                constant: b.constant,
                retain: None,
                decls,
                span: b.span,
            });
        }
        let (ret, ret_text) = match method_result(origin, m, &mut locals, &mut resets) {
            Some((key, text, block)) => {
                blocks.push(block);
                (Some(key), text)
            }
            None => (None, String::new()),
        };
        let guard = self.reentry_guard(origin, m, &mut blocks);
        let sig: Signature = (sig, ret_text);
        let v = Version {
            origin: origin.to_ascii_uppercase(),
            name: m.name.clone(),
            mods: m.mods,
            params,
            ret,
            locals,
            resets,
            body: m.body.clone(),
            span: m.span,
            sig,
            guard,
            no_check: m.no_check,
        };
        (v, blocks)
    }

    /// For a method a cycle of calls may reach again (`guarded`, from a
    /// first pass: `sema::reentry`), the hidden BOOL that marks it running
    /// on its instance, added to `blocks`; its key.
    fn reentry_guard(
        &self,
        origin: &str,
        m: &Method,
        blocks: &mut Vec<VarBlock>,
    ) -> Option<String> {
        let key = format!("{}.{}", origin.to_ascii_uppercase(), m.name.key());
        if !self.guarded.contains(&key) {
            return None;
        }
        // No identifier is empty: no variable of the method has this name.
        let hidden = hidden_name(origin, &m.name.name, "");
        blocks.push(VarBlock {
            kind: VarKind::Local,
            constant: false,
            retain: None,
            decls: vec![field(&hidden, "BOOL", m.name.span)],
            span: m.name.span,
        });
        Some(hidden.to_ascii_uppercase())
    }

    /// E901: a variable whose type is an ABSTRACT FB (an instance of it).
    fn check_abstract_instances(&mut self) {
        let abstract_fbs: HashSet<String> = self
            .info
            .fbs
            .iter()
            .filter(|(_, f)| f.is_abstract)
            .map(|(k, _)| k.clone())
            .collect();
        if abstract_fbs.is_empty() {
            return;
        }
        let mut found = Vec::new();
        for unit in &self.units {
            for item in &unit.items {
                let blocks: Vec<&VarBlock> = match item {
                    Item::Pou(p) => p.var_blocks.iter().collect(),
                    Item::Globals(b) => vec![b],
                    Item::Configuration(c) => c.globals.iter().collect(),
                    _ => Vec::new(),
                };
                for b in blocks.into_iter().filter(|b| b.kind != VarKind::InOut) {
                    for d in &b.decls {
                        if let TypeSpec::Named(t) = &d.ty
                            && abstract_fbs.contains(&t.key())
                        {
                            found.push((t.span, t.name.clone()));
                        }
                    }
                }
            }
        }
        for (span, name) in found {
            self.diags.error(
                "E901",
                span,
                format!("`{name}` is ABSTRACT: it cannot be instantiated (extend it, or hold it through an interface)"),
            );
        }
    }
}

/// True for a body without statements.
/// The hidden variable holding method `m`'s result, when it has one: its
/// key (entered in `locals`, under the property's name too for a GET, and
/// in `resets`), the result type as text, and its declaration.
fn method_result(
    origin: &str,
    m: &Method,
    locals: &mut HashMap<String, String>,
    resets: &mut Vec<String>,
) -> Option<(String, String, VarBlock)> {
    let t = m.return_type.as_ref()?;
    let hidden = hidden_name(origin, &m.name.name, &m.name.name);
    let hk = hidden.to_ascii_uppercase();
    locals.insert(m.name.key(), hk.clone());
    // A property's GET writes its result through the property's name.
    if let Some((p, true)) = crate::syntax::oop_property::property_of(&m.name.name) {
        locals.insert(p.to_ascii_uppercase(), hk.clone());
    }
    resets.push(hk.clone());
    let block = VarBlock {
        kind: VarKind::Local,
        constant: false,
        retain: None,
        decls: vec![VarDecl {
            names: vec![Ident {
                name: hidden,
                span: m.name.span,
            }],
            location: None,
            ty: t.clone(),
            init: None,
            span: m.name.span,
            edge: None,
            init_args: None,
        }],
        span: m.name.span,
    };
    Some((hk, spec_text(t), block))
}

fn body_is_empty(b: &Body) -> bool {
    match b {
        // A `;` after the header (TwinCAT) is an empty statement.
        Body::St(s) => s.iter().all(|s| matches!(s.kind, StmtKind::Empty)),
        Body::Il(l) => l.iter().all(|l| l.instr.is_none() && l.label.is_none()),
        Body::Sfc(e) => e.is_empty(),
    }
}

/// `name : ty;` as a structure field.
fn field(name: &str, ty: &str, span: Span) -> VarDecl {
    VarDecl::simple(name, ty, span)
}

/// Adds a method's variable block to its FB's flattened blocks; a
/// VAR_EXTERNAL the FB (or another method) declares already is not
/// declared again (the same global, one name).
fn push_method_block(flat: &mut Vec<VarBlock>, mut b: VarBlock) {
    if b.kind == VarKind::External {
        let known: HashSet<String> = flat
            .iter()
            .filter(|f| f.kind == VarKind::External)
            .flat_map(|f| f.decls.iter().flat_map(|d| d.names.iter().map(Ident::key)))
            .collect();
        for d in &mut b.decls {
            d.names.retain(|n| !known.contains(&n.key()));
        }
        b.decls.retain(|d| !d.names.is_empty());
        if b.decls.is_empty() {
            return;
        }
    }
    flat.push(b);
}
