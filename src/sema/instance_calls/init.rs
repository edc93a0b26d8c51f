//! The calls at start: for each instance a declaration declares, its
//! members' start, its `FB_init` with the declaration's arguments, then its
//! `call_after_init` methods; and the checks of those arguments.

use super::INIT;
use super::build::{
    all_elements, bool_lit, call_stmt, input, listed_elements, member, members_call, name, named,
};
use super::index::{Index, lives_with_instance};
use crate::diagnostics::Diagnostics;
use crate::syntax::ast::{
    Arg, Body, CompilationUnit, Expr, Ident, Initializer, Item, PouKind, Stmt, StmtKind, VarDecl,
    VarKind,
};
use crate::syntax::oop::{Method, SUPER};

/// `itf := value;` for the interface variables of `decls` bound by their
/// initial value, which is taken out of the declaration (the start
/// assigns it, before any FB_init runs).
pub(super) fn interface_bindings(index: &Index, decls: &mut [&mut VarDecl]) -> Vec<Stmt> {
    let mut out = Vec::new();
    for d in decls.iter_mut() {
        if !index.binds_interface(d) {
            continue;
        }
        let Some(Initializer::Expr(value)) = d.init.take() else {
            continue;
        };
        for n in &d.names {
            let target = named(n, d.span);
            let kind = StmtKind::Assign {
                target,
                value: value.clone(),
            };
            out.push(Stmt { kind, span: d.span });
        }
    }
    out
}

/// The start of the instances `d` declares (none when their block needs
/// nothing at start); E931-E933 for arguments it cannot take.
pub(super) fn start_of(
    index: &Index,
    d: &VarDecl,
    loops: &mut usize,
    diags: &mut Diagnostics,
) -> Vec<Stmt> {
    let Some((key, dims)) = index.block_type(&d.ty) else {
        if let Some(args) = &d.init_args
            && index.is_known_type(&d.ty)
        {
            diags.error(
                "E931",
                args.span,
                "only a FUNCTION_BLOCK instance takes FB_init arguments in its declaration",
            );
        }
        return Vec::new();
    };
    let fb_init = index.method_of(&key, INIT);
    let tree = index.has_tree(&key, INIT);
    let block_name = &index.blocks[&key].pou.name.name;
    let given = d.init_args.as_ref();
    if let Some(given) = given
        && fb_init.is_none()
    {
        diags.error(
            "E931",
            given.span,
            format!("`{block_name}` declares no FB_init method: its instances take no arguments"),
        );
        return Vec::new();
    }
    let after_init = index.after_init_of(&key);
    if fb_init.is_none() && !tree && after_init.is_empty() {
        return Vec::new();
    }
    let span = d.span;
    let start = |target: Expr, args: &[Arg]| {
        let mut out = Vec::new();
        if tree {
            out.push(members_call(target.clone(), INIT, span));
        }
        if fb_init.is_some() {
            let mut all = vec![
                input(INIT.flag, name(INIT.flag, span)),
                input("bInCopyCode", bool_lit(false, span)),
            ];
            all.extend(args.iter().cloned());
            out.push(call_stmt(
                member(target.clone(), INIT.method, span),
                all,
                span,
            ));
        }
        for m in &after_init {
            out.push(call_stmt(member(target.clone(), m, span), Vec::new(), span));
        }
        out
    };
    let (Some(fb_init), Some(g)) = (fb_init, given) else {
        return all_elements(d, &dims, loops, |t| start(t, &[]));
    };
    if g.elements.is_empty() {
        return match formal_args(&g.args, fb_init, block_name, diags) {
            Some(args) => all_elements(d, &dims, loops, |t| start(t, &args)),
            None => Vec::new(),
        };
    }
    let [range] = dims.as_slice() else {
        diags.error(
            "E933",
            g.span,
            "FB_init arguments for each element are accepted on arrays of one dimension only",
        );
        return Vec::new();
    };
    let lists: Vec<Option<Vec<Arg>>> = g
        .elements
        .iter()
        .map(|list| formal_args(list, fb_init, block_name, diags))
        .collect();
    if lists.iter().any(Option::is_none) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for n in &d.names {
        // Listed elements with their arguments, the others without.
        let body = |t: Expr, k: Option<usize>| match k.and_then(|k| lists[k].as_deref()) {
            Some(args) => start(t, args),
            None => start(t, &[]),
        };
        out.extend(listed_elements(n, range, lists.len(), loops, body, span));
    }
    out
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
pub(super) fn prepend_parent_init(own: &mut Method, parent: &Method) {
    let span = own.name.span;
    let args = parent
        .var_blocks
        .iter()
        .filter(|b| b.kind == VarKind::Input)
        .flat_map(|b| b.decls.iter().flat_map(|d| &d.names))
        .map(|n| input(&n.name, name(&n.name, span)))
        .collect();
    let call = call_stmt(member(name(SUPER, span), INIT.method, span), args, span);
    if let Body::St(stmts) = &mut own.body {
        stmts.insert(0, call);
    }
}

/// E931 for FB_init arguments where no instance lives from start to stop:
/// in a FUNCTION, a METHOD (but its VAR_INST, which lives in the
/// instance), VAR_TEMP and VAR_EXTERNAL.
pub(super) fn refuse_arguments_elsewhere(units: &[CompilationUnit], diags: &mut Diagnostics) {
    for item in units.iter().flat_map(|u| &u.items) {
        let Item::Pou(pou) = item else { continue };
        // A method's VAR_INST lives in the instance; its VAR and VAR_TEMP,
        // and a FUNCTION's, are started at every call (`per_call.rs`).
        let methods = pou.oop.iter().flat_map(|o| &o.methods);
        let in_methods = methods.flat_map(|m| {
            let started = super::per_call::starts_locals(&m.name.name);
            m.var_blocks.iter().filter(move |b| {
                b.kind != crate::syntax::ast::VarKind::Inst
                    && !(started && super::per_call::per_call_section(b.kind))
            })
        });
        let in_pou = pou.var_blocks.iter().filter(|b| match pou.kind {
            PouKind::Function => !super::per_call::per_call_section(b.kind),
            _ => !lives_with_instance(b.kind),
        });
        for d in in_pou.chain(in_methods).flat_map(|b| &b.decls) {
            if let Some(args) = &d.init_args {
                diags.error(
                    "E931",
                    args.span,
                    "FB_init arguments are given to the instances a PROGRAM, a FUNCTION_BLOCK or a global variable list declares (VAR, VAR_INPUT, VAR_OUTPUT, VAR_GLOBAL) and to those a METHOD or FUNCTION declares in VAR, VAR_TEMP or VAR_INST",
                );
            }
        }
    }
}
