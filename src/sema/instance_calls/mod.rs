//! The implicit `FB_init` and `FB_exit` calls of CODESYS V3 and TwinCAT 3.
//!
//! A FUNCTION_BLOCK may declare a method `FB_init` (inputs `bInitRetains`,
//! `bInCopyCode`, then its own) and a method `FB_exit` (input
//! `bInCopyCode`). Each instance that lives from start to stop has its
//! `FB_init` called before the first cycle and again at every reset, with
//! the arguments of its declaration (`fb : FB_X(a := 1);`), and its
//! `FB_exit` when the program is unloaded. This pass writes those calls
//! as ST, in hidden methods the rest of the compiler builds like any
//! other, one family per [`Phase`]:
//!
//! - every FUNCTION_BLOCK and PROGRAM whose instances hold instances that
//!   need calls (directly, in arrays, or deeper down) gets a method
//!   (`FB_init@members(bInitRetains)`, `FB_exit@members(bInCopyCode)`).
//!   At start it runs, for each of its members in declaration order, the
//!   member's own members' start (the innermost instances first), the
//!   member's `FB_init` and its `call_after_init` methods, after its
//!   parent's members (`SUPER^`). At exit the reverse: members in reverse
//!   order, each member's `FB_exit` before its members', the parent's
//!   members last;
//! - an explicit `FB_init` of a block whose ancestor has one starts by
//!   calling the ancestor's with the same arguments; an explicit `FB_exit`
//!   ends by calling the ancestor's (TwinCAT's order);
//! - the global variable lists get a FUNCTION per phase
//!   (`FB_init@globals`, `FB_exit@globals`).
//!
//! The linker lists these entry points ([`crate::ir::image::InstanceCall`]);
//! the runtime runs them (docs/semantics.md §24).

mod build;
mod exit;
mod index;
mod init;
mod per_call;

use crate::diagnostics::Diagnostics;
use crate::syntax::ast::{CompilationUnit, Item, Pou, PouKind, Stmt, VarDecl};
use crate::syntax::oop::PouOop;
use index::{Index, lives_with_instance};

/// One family of implicit calls.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Phase {
    /// The key of the method a block declares.
    pub key: &'static str,
    /// Its name as written in the calls.
    pub method: &'static str,
    /// The hidden method that calls it on an instance's members (a name no
    /// identifier can spell).
    pub members: &'static str,
    /// The hidden FUNCTION that calls it on the global lists' instances.
    pub globals: &'static str,
    /// The BOOL input of both, which the runtime sets before the call.
    pub flag: &'static str,
}

/// Before the first cycle and at every reset.
pub(crate) const INIT: Phase = Phase {
    key: "FB_INIT",
    method: "FB_init",
    members: "FB_init@members",
    globals: "FB_init@globals",
    flag: "bInitRetains",
};

/// When the program is unloaded.
pub(crate) const EXIT: Phase = Phase {
    key: "FB_EXIT",
    method: "FB_exit",
    members: "FB_exit@members",
    globals: "FB_exit@globals",
    flag: "bInCopyCode",
};

/// A copy of `units` with the hidden methods and functions of the module
/// comment; `None` when no block declares `FB_init`, `FB_exit` or a
/// `call_after_init` method and no declaration gives FB_init arguments
/// (the units are used as they are). Arguments an instance cannot take
/// are E931-E933.
pub(super) fn with_instance_calls(
    units: &[CompilationUnit],
    diags: &mut Diagnostics,
) -> Option<Vec<CompilationUnit>> {
    let index = Index::new(units);
    let any_binding = units
        .iter()
        .flat_map(|u| &u.items)
        .any(|i| declarations_of(i).any(|d| index.binds_interface(d)));
    let any_method = any_binding
        || index.blocks.values().any(|b| {
            b.method(INIT.key).is_some()
                || b.method(EXIT.key).is_some()
                || b.methods.iter().any(|m| m.call_after_init)
        });
    let any_args = units
        .iter()
        .flat_map(|u| &u.items)
        .any(|i| declarations_of(i).any(|d| d.init_args.is_some()));
    if !any_method && !any_args {
        return None;
    }
    init::refuse_arguments_elsewhere(units, diags);
    let mut copy = units.to_vec();
    for phase in [INIT, EXIT] {
        add_phase(units, &mut copy, &index, phase, diags);
    }
    Some(copy)
}

/// The start of the instances a FUNCTION or the methods of a block
/// create at every call (`per_call.rs`).
fn start_per_call_instances(pou: &mut Pou, index: &Index, diags: &mut Diagnostics) {
    if pou.kind == PouKind::Function {
        per_call::start_locals(index, &mut pou.var_blocks, &mut pou.body, diags);
        return;
    }
    let Some(oop) = pou.oop.as_mut() else {
        return;
    };
    for m in oop
        .methods
        .iter_mut()
        .filter(|m| per_call::starts_locals(&m.name.name))
    {
        per_call::start_locals(index, &mut m.var_blocks, &mut m.body, diags);
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

/// The calls of `phase` for the instances `d` declares.
fn calls_of(
    index: &Index,
    phase: Phase,
    d: &VarDecl,
    loops: &mut usize,
    diags: &mut Diagnostics,
) -> Vec<Stmt> {
    match phase {
        INIT => init::start_of(index, d, loops, diags),
        _ => exit::exit_of(index, d, loops),
    }
}

/// The calls of `phase` for the instances `decls` declare (in source
/// order at start, reversed at exit), and the loop counters they use.
fn phase_calls(
    index: &Index,
    phase: Phase,
    mut decls: Vec<&VarDecl>,
    diags: &mut Diagnostics,
) -> (Vec<Stmt>, usize) {
    if phase == EXIT {
        decls.reverse();
    }
    let mut loops = 0;
    let mut out = Vec::new();
    for d in decls {
        out.extend(calls_of(index, phase, d, &mut loops, diags));
    }
    (out, loops)
}

/// Adds `phase`'s hidden methods to the blocks of `copy` (a copy of
/// `units`) and its hidden function to the last unit.
fn add_phase(
    units: &[CompilationUnit],
    copy: &mut [CompilationUnit],
    index: &Index,
    phase: Phase,
    diags: &mut Diagnostics,
) {
    for (u, unit) in copy.iter_mut().enumerate() {
        for (i, item) in unit.items.iter_mut().enumerate() {
            let Item::Pou(pou) = item else { continue };
            if phase == INIT {
                start_per_call_instances(pou, index, diags);
            }
            if pou.kind == PouKind::Function {
                continue;
            }
            let key = pou.name.key();
            let lineage = index.lineage(&key);
            // A second POU of the same name is reported elsewhere.
            if lineage.first().is_none_or(|b| b.at != (u, i)) {
                continue;
            }
            let mut stmts: Vec<Stmt> = Vec::new();
            if phase == INIT {
                let mut own: Vec<&mut VarDecl> = pou
                    .var_blocks
                    .iter_mut()
                    .filter(|b| lives_with_instance(b.kind))
                    .flat_map(|b| &mut b.decls)
                    .collect();
                stmts = init::interface_bindings(index, &mut own);
            }
            let in_methods = index::method_instance_decls(pou);
            let decls = pou
                .var_blocks
                .iter()
                .filter(|b| lives_with_instance(b.kind))
                .flat_map(|b| &b.decls)
                .chain(&in_methods)
                .collect();
            let (calls, loops) = phase_calls(index, phase, decls, diags);
            stmts.extend(calls);
            let parent = lineage.iter().skip(1).find_map(|b| b.method(phase.key));
            let derived = lineage[0].method(phase.key).is_some() && parent.is_some();
            if stmts.is_empty() && !derived {
                continue;
            }
            let parent_tree = lineage
                .get(1)
                .is_some_and(|p| index.has_tree(&p.pou.name.key(), phase));
            let span = pou.name.span;
            let oop = pou.oop.get_or_insert_with(|| Box::new(PouOop::default()));
            if derived {
                let own = oop.methods.iter_mut().find(|m| m.name.key() == phase.key);
                match (own, parent, phase) {
                    (Some(own), Some(parent), INIT) => init::prepend_parent_init(own, parent),
                    (Some(own), Some(_), _) => exit::append_parent_exit(own),
                    _ => {}
                }
            }
            if !stmts.is_empty() {
                if parent_tree {
                    let call = build::super_members(phase, span);
                    match phase {
                        INIT => stmts.insert(0, call),
                        _ => stmts.push(call),
                    }
                }
                oop.methods
                    .push(build::members_method(phase, stmts, loops, span));
            }
        }
    }
    // The global lists: their interface bindings (taken out of the
    // copy), then the calls, read from the sources.
    let mut globals = Vec::new();
    if phase == INIT {
        let mut own: Vec<&mut VarDecl> = copy
            .iter_mut()
            .flat_map(|u| &mut u.items)
            .filter_map(|i| match i {
                Item::Globals(b) => Some(b),
                _ => None,
            })
            .flat_map(|b| &mut b.decls)
            .collect();
        globals = init::interface_bindings(index, &mut own);
    }
    let decls = units
        .iter()
        .flat_map(|u| &u.items)
        .filter_map(|i| match i {
            Item::Globals(b) => Some(b),
            _ => None,
        })
        .flat_map(|b| &b.decls)
        .collect();
    let (calls, loops) = phase_calls(index, phase, decls, diags);
    globals.extend(calls);
    if !globals.is_empty()
        && let Some(last) = copy.last_mut()
    {
        let function = build::globals_function(phase, globals, loops);
        last.items.push(Item::Pou(function));
    }
}
