//! The implicit `FB_init` calls of CODESYS V3 and TwinCAT 3.
//!
//! A FUNCTION_BLOCK may declare a method `FB_init` (inputs `bInitRetains`,
//! `bInCopyCode`, then its own); each instance of it, declared with or
//! without arguments (`fb : FB_X(a := 1);`), has it called once before
//! the first cycle and again at every reset. This pass writes those calls
//! as ST, in hidden methods the rest of the compiler builds like any other:
//!
//! - every FUNCTION_BLOCK and PROGRAM whose instances hold such instances
//!   (directly, in arrays, or deeper down) gets a method
//!   [`MEMBERS`]`(bInitRetains)` that, for each of its own members in
//!   declaration order, first runs the member's own `MEMBERS` (the innermost
//!   instances are initialised first), then the member's `FB_init` with the
//!   declaration's arguments; a block extending another runs its parent's
//!   first (`SUPER^`);
//! - an explicit `FB_init` of a block whose ancestor has one starts by
//!   calling the ancestor's with the same arguments (TwinCAT runs the base
//!   block's first);
//! - the global variable lists get a FUNCTION [`GLOBALS`]`(bInitRetains)`.
//!
//! The linker lists these entry points ([`crate::ir::image::StartCall`]);
//! the runtime calls them with `bInitRetains` TRUE after loading and a cold
//! reset, FALSE after a warm reset (docs/semantics.md).

use crate::diagnostics::Diagnostics;
use crate::source::Span;
use crate::syntax::ast::{
    Arg, BinaryOp, Body, Call, CompilationUnit, Expr, ExprKind, Ident, Item, Literal, LiteralValue,
    Pou, PouKind, Stmt, StmtKind, TypeSpec, VarBlock, VarDecl, VarKind,
};
use crate::syntax::oop::{Method, Modifiers, PouOop, SUPER};
use std::collections::HashMap;

/// The hidden method that initialises an instance's members (a name no
/// identifier can spell).
pub(crate) const MEMBERS: &str = "FB_init@members";
/// The hidden FUNCTION that initialises the global variable lists.
pub(crate) const GLOBALS: &str = "FB_init@globals";
/// The input of both.
pub(crate) const RETAINS: &str = "bInitRetains";
/// The method a block declares to be initialised.
const FB_INIT: &str = "FB_INIT";

/// What the pass knows of one FUNCTION_BLOCK or PROGRAM.
struct Block<'a> {
    pou: &'a Pou,
    /// Where it is: (unit, item).
    at: (usize, usize),
    /// The parent's key.
    parent: Option<String>,
    /// Its own `FB_init`, if it declares one.
    fb_init: Option<&'a Method>,
    /// Its own methods declared after `{attribute 'call_after_init'}`.
    after_init: Vec<&'a Ident>,
}

/// The blocks by key, and what each needs (computed once).
struct Index<'a> {
    blocks: HashMap<String, Block<'a>>,
    /// The keys of the declared TYPEs, POUs and interfaces.
    types: std::collections::HashSet<String>,
    tree: HashMap<String, bool>,
}

/// The key of a type name written `Name` or `Namespace.Name`.
fn type_key(name: &Ident) -> String {
    let last = name.name.rsplit('.').next().unwrap_or(&name.name);
    last.to_ascii_uppercase()
}

impl<'a> Index<'a> {
    fn new(units: &'a [CompilationUnit]) -> Self {
        let mut blocks = HashMap::new();
        let items = units.iter().enumerate().flat_map(|(u, unit)| {
            unit.items
                .iter()
                .enumerate()
                .map(move |(i, it)| ((u, i), it))
        });
        for (at, item) in items {
            let Item::Pou(pou) = item else { continue };
            if pou.kind == PouKind::Function {
                continue;
            }
            let oop = pou.oop.as_deref();
            let fb_init = oop.and_then(|o| o.methods.iter().find(|m| m.name.key() == FB_INIT));
            let after_init = oop
                .iter()
                .flat_map(|o| &o.methods)
                .filter(|m| m.call_after_init)
                .map(|m| &m.name)
                .collect();
            blocks.entry(pou.name.key()).or_insert(Block {
                pou,
                at,
                after_init,
                parent: oop.and_then(|o| o.extends.as_ref()).map(type_key),
                fb_init,
            });
        }
        let types = units
            .iter()
            .flat_map(|u| &u.items)
            .flat_map(|i| match i {
                Item::Types(t) => t.iter().map(|t| t.name.key()).collect(),
                Item::Pou(p) => vec![p.name.key()],
                Item::Interface(x) => vec![x.name.key()],
                _ => Vec::new(),
            })
            .collect();
        Index {
            blocks,
            types,
            tree: HashMap::new(),
        }
    }

    /// The ancestors of `key`, itself first (stops at a cycle, which the
    /// lowering reports).
    fn lineage(&self, key: &str) -> Vec<&Block<'a>> {
        let mut out: Vec<&Block<'a>> = Vec::new();
        let mut next = Some(key.to_string());
        while let Some(k) = next {
            let Some(b) = self.blocks.get(&k) else { break };
            if out.iter().any(|o| std::ptr::eq(o.pou, b.pou)) {
                break;
            }
            next = b.parent.clone();
            out.push(b);
        }
        out
    }

    /// The methods to call on an instance of `key` right after its
    /// `FB_init` (its own and its ancestors', each name once, parents'
    /// first).
    fn after_init_of(&self, key: &str) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for b in self.lineage(key).iter().rev() {
            for m in &b.after_init {
                if !out.iter().any(|o| o.eq_ignore_ascii_case(&m.name)) {
                    out.push(m.name.clone());
                }
            }
        }
        out
    }

    /// Whether a declared type is one the compiler knows without this
    /// pass (an elementary type, a string, a declared TYPE...): an unknown
    /// name is reported once, as an unknown type, elsewhere.
    fn is_known_type(&self, ty: &TypeSpec) -> bool {
        match ty {
            TypeSpec::Named(n) => {
                let k = type_key(n);
                crate::elementary::ElemType::from_name(&k).is_some()
                    || crate::stdlib::lookup_native(&k).is_some()
                    || self.types.contains(&k)
            }
            TypeSpec::Array { elem, .. } => self.is_known_type(elem),
            _ => true,
        }
    }

    /// The `FB_init` a call on an instance of `key` runs (its own or the
    /// nearest ancestor's).
    fn fb_init_of(&self, key: &str) -> Option<&'a Method> {
        self.lineage(key).iter().find_map(|b| b.fb_init)
    }

    /// The block a declared type names, if it is a FUNCTION_BLOCK (through
    /// arrays: with their dimensions).
    fn block_type<'t>(&self, ty: &'t TypeSpec) -> Option<(String, Vec<&'t (Expr, Expr)>)> {
        match ty {
            TypeSpec::Named(n) => {
                let k = type_key(n);
                let b = self.blocks.get(&k)?;
                (b.pou.kind == PouKind::FunctionBlock).then_some((k, Vec::new()))
            }
            TypeSpec::Array { ranges, elem, .. } => {
                let (k, mut dims) = self.block_type(elem)?;
                let mut all: Vec<&(Expr, Expr)> = ranges.iter().collect();
                all.append(&mut dims);
                Some((k, all))
            }
            _ => None,
        }
    }

    /// Whether an instance of `key` needs anything done at start: an
    /// `FB_init` of its own or inherited, or members that do.
    fn needs_start(&mut self, key: &str, depth: usize) -> bool {
        self.fb_init_of(key).is_some()
            || !self.after_init_of(key).is_empty()
            || self.needs_members(key, depth)
    }

    /// Whether `key`'s members (its own or inherited) need initialising.
    fn needs_members(&mut self, key: &str, depth: usize) -> bool {
        if let Some(&known) = self.tree.get(key) {
            return known;
        }
        // Blocks nested deeper than this are refused elsewhere.
        if depth > 64 {
            return false;
        }
        self.tree.insert(key.to_string(), false);
        let mut needed = false;
        let lineage: Vec<(Vec<TypeSpec>, Option<String>)> = self
            .lineage(key)
            .iter()
            .map(|b| (member_types(b.pou), b.parent.clone()))
            .collect();
        'outer: for (types, _) in &lineage {
            for ty in types {
                if let Some((k, _)) = self.block_type(ty)
                    && self.needs_start(&k, depth + 1)
                {
                    needed = true;
                    break 'outer;
                }
            }
        }
        self.tree.insert(key.to_string(), needed);
        needed
    }
}

/// The sections whose instances live as long as their container.
fn lives_with_instance(kind: VarKind) -> bool {
    matches!(kind, VarKind::Local | VarKind::Input | VarKind::Output)
}

/// The declared types of a block's own instance members.
fn member_types(pou: &Pou) -> Vec<TypeSpec> {
    pou.var_blocks
        .iter()
        .filter(|b| lives_with_instance(b.kind))
        .flat_map(|b| b.decls.iter().map(|d| d.ty.clone()))
        .collect()
}

/// A copy of `units` with the hidden methods and function of the module
/// comment; `None` when no instance anywhere has an `FB_init` to run (the
/// units are used as they are). Arguments given to a block without
/// `FB_init` are E931; more positional arguments than it takes, E932.
pub(super) fn with_init_calls(
    units: &[CompilationUnit],
    diags: &mut Diagnostics,
) -> Option<Vec<CompilationUnit>> {
    let mut index = Index::new(units);
    let keys: Vec<String> = index.blocks.keys().cloned().collect();
    for k in &keys {
        index.needs_members(k, 0);
    }
    let derived_inits: Vec<String> = keys
        .iter()
        .filter(|k| {
            let lineage = index.lineage(k);
            lineage.first().is_some_and(|b| b.fb_init.is_some())
                && lineage.iter().skip(1).any(|b| b.fb_init.is_some())
        })
        .cloned()
        .collect();
    let any_start = keys.iter().any(|k| {
        let b = &index.blocks[k];
        b.fb_init.is_some() || !b.after_init.is_empty()
    });
    let any_args = units
        .iter()
        .flat_map(|u| &u.items)
        .any(|i| declarations_of(i).any(|d| d.init_args.is_some()));
    if !any_start && !any_args {
        return None;
    }
    refuse_arguments_elsewhere(units, diags);
    let writer = Writer { index: &index };
    let mut copy = units.to_vec();
    let mut globals: Vec<Stmt> = Vec::new();
    let mut global_loops = 0;
    for (u, unit) in copy.iter_mut().enumerate() {
        for (i, item) in unit.items.iter_mut().enumerate() {
            match item {
                Item::Pou(pou) if pou.kind != PouKind::Function => {
                    let key = pou.name.key();
                    let lineage = index.lineage(&key);
                    // A second POU of the same name is reported elsewhere.
                    if lineage.first().is_none_or(|b| b.at != (u, i)) {
                        continue;
                    }
                    let parent_tree = lineage
                        .get(1)
                        .is_some_and(|p| index.tree.get(&p.pou.name.key()) == Some(&true));
                    let mut stmts = Vec::new();
                    if parent_tree {
                        stmts.push(writer.super_members(pou.name.span));
                    }
                    let mut loops = 0;
                    for block in pou
                        .var_blocks
                        .iter()
                        .filter(|b| lives_with_instance(b.kind))
                    {
                        for d in &block.decls {
                            stmts.extend(writer.start_of(d, &mut loops, diags));
                        }
                    }
                    let derived = derived_inits.contains(&key);
                    let own_members = stmts.len() > usize::from(parent_tree);
                    if !own_members && !derived {
                        continue;
                    }
                    let oop = pou.oop.get_or_insert_with(|| Box::new(PouOop::default()));
                    if derived {
                        let parent_init = lineage.iter().skip(1).find_map(|b| b.fb_init);
                        if let (Some(own), Some(parent)) = (
                            oop.methods.iter_mut().find(|m| m.name.key() == FB_INIT),
                            parent_init,
                        ) {
                            prepend_parent_init(own, parent);
                        }
                    }
                    if own_members {
                        oop.methods
                            .push(members_method(stmts, loops, pou.name.span));
                    }
                }
                Item::Globals(block) => {
                    for d in &block.decls {
                        globals.extend(writer.start_of(d, &mut global_loops, diags));
                    }
                }
                _ => {}
            }
        }
    }
    if !globals.is_empty()
        && let Some(last) = copy.last_mut()
    {
        last.items
            .push(Item::Pou(globals_function(globals, global_loops)));
    }
    Some(copy)
}

/// E931 for FB_init arguments where no instance lives from start to stop:
/// in a FUNCTION, a METHOD, VAR_TEMP and VAR_EXTERNAL.
fn refuse_arguments_elsewhere(units: &[CompilationUnit], diags: &mut Diagnostics) {
    for item in units.iter().flat_map(|u| &u.items) {
        let Item::Pou(pou) = item else { continue };
        let methods = pou.oop.iter().flat_map(|o| &o.methods);
        let in_methods = methods.flat_map(|m| &m.var_blocks);
        let in_pou = pou
            .var_blocks
            .iter()
            .filter(|b| pou.kind == PouKind::Function || !lives_with_instance(b.kind));
        for d in in_pou.chain(in_methods).flat_map(|b| &b.decls) {
            if let Some(args) = &d.init_args {
                diags.error(
                    "E931",
                    args.span,
                    "FB_init arguments are given to the instances of a PROGRAM, a FUNCTION_BLOCK or a global variable list only (VAR, VAR_INPUT, VAR_OUTPUT, VAR_GLOBAL)",
                );
            }
        }
    }
}

/// The declarations of an item's variable sections.
fn declarations_of(item: &Item) -> Box<dyn Iterator<Item = &VarDecl> + '_> {
    match item {
        Item::Pou(p) => Box::new(p.var_blocks.iter().flat_map(|b| &b.decls)),
        Item::Globals(b) => Box::new(b.decls.iter()),
        _ => Box::new(std::iter::empty()),
    }
}

/// Writes the calls.
struct Writer<'i, 'a> {
    index: &'i Index<'a>,
}

impl Writer<'_, '_> {
    /// `SUPER^.FB_init@members(bInitRetains := bInitRetains);`
    fn super_members(&self, span: Span) -> Stmt {
        let callee = member(name(SUPER, span), MEMBERS, span);
        call_stmt(callee, vec![input(RETAINS, name(RETAINS, span))], span)
    }

    /// The start of the instances one declaration declares: for each name
    /// (each element of an array), its members' start then its `FB_init`.
    fn start_of(&self, d: &VarDecl, loops: &mut usize, diags: &mut Diagnostics) -> Vec<Stmt> {
        let Some((key, dims)) = self.index.block_type(&d.ty) else {
            if let Some(args) = &d.init_args
                && self.index.is_known_type(&d.ty)
            {
                diags.error(
                    "E931",
                    args.span,
                    "only a FUNCTION_BLOCK instance takes FB_init arguments in its declaration",
                );
            }
            return Vec::new();
        };
        let fb_init = self.index.fb_init_of(&key);
        let tree = self.index.tree.get(&key).copied().unwrap_or(false);
        let block_name = &self.index.blocks[&key].pou.name.name;
        let given = d.init_args.as_ref();
        if let Some(given) = given
            && fb_init.is_none()
        {
            diags.error(
                "E931",
                given.span,
                format!(
                    "`{block_name}` declares no FB_init method: its instances take no arguments"
                ),
            );
            return Vec::new();
        }
        let after_init = self.index.after_init_of(&key);
        let start = |target: Expr, fb_init: bool, args: &[Arg]| {
            let mut out = Vec::new();
            if tree {
                out.push(members_call(target.clone(), d.span));
            }
            if fb_init {
                out.push(fb_init_call(target.clone(), args, d.span));
            }
            for m in &after_init {
                let callee = member(target.clone(), m, d.span);
                out.push(call_stmt(callee, Vec::new(), d.span));
            }
            out
        };
        let Some(fb_init) = fb_init else {
            if !tree && after_init.is_empty() {
                return Vec::new();
            }
            return self.all_elements(d, &dims, loops, |target| start(target, false, &[]));
        };
        let calls = |target: Expr, args: &[Arg]| start(target, true, args);
        let formal =
            |args: &[Arg], diags: &mut Diagnostics| formal_args(args, fb_init, block_name, diags);
        match given {
            Some(g) if !g.elements.is_empty() => {
                let [(lo, _)] = dims.as_slice() else {
                    diags.error(
                        "E933",
                        g.span,
                        "FB_init arguments for each element are accepted on arrays of one dimension only",
                    );
                    return Vec::new();
                };
                let mut out = Vec::new();
                let mut lists = Vec::new();
                for list in &g.elements {
                    lists.push(formal(list, diags));
                }
                for n in &d.names {
                    for (k, list) in lists.iter().enumerate() {
                        let Some(args) = list else { continue };
                        let at = offset(lo, k as i128, d.span);
                        out.extend(calls(index(named(n, d.span), vec![at], d.span), args));
                    }
                    // The elements the list does not reach: no arguments.
                    let rest = offset(lo, g.elements.len() as i128, d.span);
                    let target = index(named(n, d.span), vec![name(&counter(0), d.span)], d.span);
                    let (_, hi) = dims[0];
                    out.push(for_loop(
                        counter(0),
                        rest,
                        hi.clone(),
                        calls(target, &[]),
                        d.span,
                    ));
                }
                *loops = (*loops).max(1);
                out
            }
            Some(g) => match formal(&g.args, diags) {
                Some(args) => self.all_elements(d, &dims, loops, |t| calls(t, &args)),
                None => Vec::new(),
            },
            None => self.all_elements(d, &dims, loops, |t| calls(t, &[])),
        }
    }

    /// `body` for each instance a declaration declares: each name, and
    /// each element of an array (one loop a dimension, the last innermost).
    fn all_elements(
        &self,
        d: &VarDecl,
        dims: &[&(Expr, Expr)],
        loops: &mut usize,
        body: impl Fn(Expr) -> Vec<Stmt>,
    ) -> Vec<Stmt> {
        let span = d.span;
        let mut out = Vec::new();
        for n in &d.names {
            let counters: Vec<String> = (0..dims.len()).map(counter).collect();
            let mut target = named(n, span);
            if !dims.is_empty() {
                target = index(
                    target,
                    counters.iter().map(|c| name(c, span)).collect(),
                    span,
                );
            }
            let mut stmts = body(target);
            for (k, (lo, hi)) in dims.iter().enumerate().rev() {
                stmts = vec![for_loop(
                    counters[k].clone(),
                    lo.clone(),
                    hi.clone(),
                    stmts,
                    span,
                )];
            }
            out.extend(stmts);
        }
        *loops = (*loops).max(dims.len());
        out
    }
}

/// `target.FB_init@members(bInitRetains := bInitRetains);`
fn members_call(target: Expr, span: Span) -> Stmt {
    let callee = member(target, MEMBERS, span);
    call_stmt(callee, vec![input(RETAINS, name(RETAINS, span))], span)
}

/// `target.FB_init(bInitRetains := bInitRetains, bInCopyCode := FALSE, args)`.
fn fb_init_call(target: Expr, args: &[Arg], span: Span) -> Stmt {
    let mut all = vec![
        input(RETAINS, name(RETAINS, span)),
        input("bInCopyCode", bool_lit(false, span)),
    ];
    all.extend(args.iter().cloned());
    call_stmt(member(target, "FB_init", span), all, span)
}

/// The declaration's arguments as formal ones: a positional argument goes
/// to the `FB_init` input of its rank after `bInitRetains` and
/// `bInCopyCode`.
fn formal_args(
    given: &[Arg],
    fb_init: &Method,
    block_name: &str,
    diags: &mut Diagnostics,
) -> Option<Vec<Arg>> {
    let inputs: Vec<&Ident> = fb_init
        .var_blocks
        .iter()
        .filter(|b| b.kind == VarKind::Input)
        .flat_map(|b| b.decls.iter().flat_map(|d| &d.names))
        .filter(|n| !matches!(n.key().as_str(), "BINITRETAINS" | "BINCOPYCODE"))
        .collect();
    let mut out = Vec::new();
    let mut rank = 0;
    for a in given {
        match a {
            Arg::Positional(e) => {
                let Some(n) = inputs.get(rank) else {
                    diags.error(
                        "E932",
                        e.span,
                        format!(
                            "`{block_name}.FB_init` takes {} argument{} after bInitRetains and bInCopyCode",
                            inputs.len(),
                            if inputs.len() == 1 { "" } else { "s" }
                        ),
                    );
                    return None;
                };
                rank += 1;
                out.push(Arg::Input {
                    name: Ident {
                        name: n.name.clone(),
                        span: e.span,
                    },
                    value: e.clone(),
                });
            }
            other => out.push(other.clone()),
        }
    }
    Some(out)
}

/// Makes a derived block's `FB_init` call its ancestor's first, with the
/// ancestor's inputs taken from its own of the same names.
fn prepend_parent_init(own: &mut Method, parent: &Method) {
    let span = own.name.span;
    let args = parent
        .var_blocks
        .iter()
        .filter(|b| b.kind == VarKind::Input)
        .flat_map(|b| b.decls.iter().flat_map(|d| &d.names))
        .map(|n| input(&n.name, name(&n.name, span)))
        .collect();
    let call = call_stmt(member(name(SUPER, span), "FB_init", span), args, span);
    if let Body::St(stmts) = &mut own.body {
        stmts.insert(0, call);
    }
}

/// The name of the `k`-th loop counter (no identifier can spell it).
fn counter(k: usize) -> String {
    format!("FB_init@i{k}")
}

/// The hidden method [`MEMBERS`]`(bInitRetains : BOOL)` with `loops`
/// counters.
fn members_method(stmts: Vec<Stmt>, loops: usize, span: Span) -> Method {
    Method {
        name: Ident {
            name: MEMBERS.to_string(),
            span,
        },
        mods: Modifiers::default(),
        return_type: None,
        var_blocks: parameters(loops, span),
        body: Body::St(stmts),
        span,
        property: None,
        call_after_init: false,
    }
}

/// `VAR_INPUT bInitRetains : BOOL; END_VAR VAR counters : DINT; END_VAR`.
fn parameters(loops: usize, span: Span) -> Vec<VarBlock> {
    let decl = |n: String, ty: &str| VarDecl {
        names: vec![Ident { name: n, span }],
        location: None,
        ty: TypeSpec::Named(Ident {
            name: ty.to_string(),
            span,
        }),
        init: None,
        span,
        edge: None,
        init_args: None,
    };
    let block = |kind, decls| VarBlock {
        kind,
        constant: false,
        retain: None,
        decls,
        span,
    };
    let mut out = vec![block(
        VarKind::Input,
        vec![decl(RETAINS.to_string(), "BOOL")],
    )];
    if loops > 0 {
        let counters = (0..loops).map(|k| decl(counter(k), "DINT")).collect();
        out.push(block(VarKind::Local, counters));
    }
    out
}

/// The hidden FUNCTION of the global lists.
fn globals_function(stmts: Vec<Stmt>, loops: usize) -> Pou {
    let span = stmts.first().map(|s| s.span).unwrap_or_default();
    Pou {
        kind: PouKind::Function,
        name: Ident {
            name: GLOBALS.to_string(),
            span,
        },
        return_type: None,
        var_blocks: parameters(loops, span),
        body: Body::St(stmts),
        span,
        oop: None,
    }
}

fn named(n: &Ident, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(n.clone()),
        span,
    }
}

fn index(base: Expr, at: Vec<Expr>, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Index(Box::new(base), at),
        span,
    }
}

/// `lo + k`.
fn offset(lo: &Expr, k: i128, span: Span) -> Expr {
    let k = Expr {
        kind: ExprKind::Literal(Literal {
            value: LiteralValue::Int(k),
            type_prefix: None,
        }),
        span,
    };
    Expr {
        kind: ExprKind::Binary(BinaryOp::Add, Box::new(lo.clone()), Box::new(k)),
        span,
    }
}

fn for_loop(var: String, from: Expr, to: Expr, body: Vec<Stmt>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::For {
            var: Ident { name: var, span },
            from,
            to,
            by: None,
            body,
        },
        span,
    }
}

fn name(n: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(Ident {
            name: n.to_string(),
            span,
        }),
        span,
    }
}

fn member(base: Expr, m: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Member(
            Box::new(base),
            Ident {
                name: m.to_string(),
                span,
            },
        ),
        span,
    }
}

fn bool_lit(b: bool, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Literal(Literal {
            value: LiteralValue::Bool(b),
            type_prefix: None,
        }),
        span,
    }
}

fn input(n: &str, value: Expr) -> Arg {
    Arg::Input {
        name: Ident {
            name: n.to_string(),
            span: value.span,
        },
        value,
    }
}

fn call_stmt(callee: Expr, args: Vec<Arg>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::Call(Call {
            callee: Box::new(callee),
            args,
            span,
        }),
        span,
    }
}
