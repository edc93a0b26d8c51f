//! The instances a METHOD or a FUNCTION declares in its `VAR` or
//! `VAR_TEMP`: CODESYS and TwinCAT create them at every call, so their
//! `FB_init` (with the declaration's arguments, `Arb : FB_Arbiter(20);`)
//! and `call_after_init` methods run at the start of every call, with
//! `bInitRetains` FALSE. The calls are put in front of the body, with the
//! variables they use (the flag, the loop counters over arrays) declared
//! beside the POU's own.

use super::build::counters;
use super::{INIT, Index, phase_calls};
use crate::diagnostics::Diagnostics;
use crate::syntax::ast::{Body, VarBlock, VarDecl, VarKind};

/// The methods that start or end an instance: their own locals are left
/// as they are (`FB_init` has `bInitRetains` as an input).
const LIFE_CYCLE: [&str; 3] = ["FB_INIT", "FB_EXIT", "FB_REINIT"];

/// True for a method whose locals get started at each call.
pub(super) fn starts_locals(method: &str) -> bool {
    !LIFE_CYCLE.contains(&method.to_ascii_uppercase().as_str())
}

/// True for the variable sections whose instances live for one call.
pub(super) fn per_call_section(kind: VarKind) -> bool {
    matches!(kind, VarKind::Local | VarKind::Temp)
}

/// Puts the start of the per-call instances `blocks` declares in front of
/// `body` (an ST body; IL and SFC bodies are left as they are).
pub(super) fn start_locals(
    index: &Index,
    blocks: &mut Vec<VarBlock>,
    body: &mut Body,
    diags: &mut Diagnostics,
) {
    let Body::St(stmts) = body else {
        return;
    };
    let decls: Vec<&VarDecl> = blocks
        .iter()
        .filter(|b| per_call_section(b.kind))
        .flat_map(|b| &b.decls)
        .collect();
    if decls.is_empty() {
        return;
    }
    let (calls, loops) = phase_calls(index, INIT, decls, diags);
    let Some(span) = calls.first().map(|s| s.span) else {
        return;
    };
    let declared = |name: &str| {
        blocks
            .iter()
            .flat_map(|b| &b.decls)
            .flat_map(|d| &d.names)
            .any(|n| n.name.eq_ignore_ascii_case(name))
    };
    let mut locals = Vec::new();
    if !declared(INIT.flag) {
        locals.push(VarDecl::simple(INIT.flag, "BOOL", span));
    }
    locals.extend(counters(loops, span));
    if !locals.is_empty() {
        blocks.push(VarBlock {
            kind: VarKind::Local,
            constant: false,
            retain: None,
            decls: locals,
            span,
        });
    }
    stmts.splice(0..0, calls);
}
