//! `EN` and `ENO` inside FUNCTION and FUNCTION_BLOCK bodies (edition 3).
//!
//! A FUNCTION or FUNCTION_BLOCK whose body mentions `ENO` gets an implicit
//! `VAR_OUTPUT ENO : BOOL` (appended after its own declarations, so the
//! other variables keep their places); a POU may also declare that output
//! itself, and then it is the same slot. Every call of such a POU sets
//! `ENO := TRUE` before its body runs; the body may reset (or read) it, and
//! the caller's `ENO => x` reads it. A call skipped by `EN := FALSE` runs no
//! body and gives `ENO` FALSE (also in the instance of a block). POUs that
//! do not mention `ENO` get no slot and no code. `EN` reads TRUE in a body:
//! the body runs only when its caller's EN was TRUE.

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Place, PlaceRef, Ty, Val};
use super::eno_uses::body_mentions_eno;
use crate::diagnostics::Diagnostics;
use crate::elementary::ElemType;
use crate::ir::op::Op;
use crate::ir::type_table::{MemberKind, TypeTable};
use crate::syntax::ast::{
    CompilationUnit, Expr, ExprKind, Ident, Item, Pou, PouKind, TypeSpec, VarBlock, VarKind,
};

/// The key of the output.
const ENO: &str = "ENO";

/// A copy of `units` in which each FUNCTION and FUNCTION_BLOCK whose body
/// mentions an undeclared `ENO` declares it as a BOOL output; `None` when
/// no POU needs one (the units are used as they are). An own declaration
/// of `ENO` other than a BOOL VAR_OUTPUT is E428.
pub(super) fn with_implicit_eno(
    units: &[CompilationUnit],
    diags: &mut Diagnostics,
) -> Option<Vec<CompilationUnit>> {
    let mut needed = Vec::new();
    for (u, unit) in units.iter().enumerate() {
        for (i, item) in unit.items.iter().enumerate() {
            let Item::Pou(pou) = item else { continue };
            if pou.kind == PouKind::Program {
                continue;
            }
            if !declares_eno(pou, diags) && body_mentions_eno(&pou.body) {
                needed.push((u, i));
            }
        }
    }
    if needed.is_empty() {
        return None;
    }
    let mut copy = units.to_vec();
    for (u, i) in needed {
        if let Item::Pou(pou) = &mut copy[u].items[i] {
            pou.var_blocks.push(implicit_block(pou));
        }
    }
    Some(copy)
}

/// Whether the POU declares `ENO` itself (E428 unless as a BOOL output).
fn declares_eno(pou: &Pou, diags: &mut Diagnostics) -> bool {
    let mut declared = false;
    for block in &pou.var_blocks {
        for decl in &block.decls {
            if !decl.names.iter().any(|n| n.key() == ENO) {
                continue;
            }
            declared = true;
            let is_bool = matches!(&decl.ty, TypeSpec::Named(t) if t.key() == "BOOL");
            if block.kind != VarKind::Output || !is_bool {
                diags.error(
                    "E428",
                    decl.span,
                    "`ENO` is the BOOL output that tells the caller whether the call succeeded: \
                     declare it as `VAR_OUTPUT ENO : BOOL;` or leave it undeclared",
                );
            }
        }
    }
    declared
}

/// `VAR_OUTPUT ENO : BOOL; END_VAR`, placed at the POU's name.
fn implicit_block(pou: &Pou) -> VarBlock {
    let span = pou.name.span;
    let ident = |name: &str| Ident {
        name: name.to_string(),
        span,
    };
    VarBlock {
        kind: VarKind::Output,
        constant: false,
        retain: None,
        decls: vec![crate::syntax::ast::VarDecl {
            names: vec![ident(ENO)],
            location: None,
            ty: TypeSpec::Named(ident("BOOL")),
            init: None,
            span,
            edge: None,
            init_args: None,
        }],
        span,
    }
}

impl BodyBuilder<'_> {
    /// At the start of a FUNCTION's or FUNCTION_BLOCK's body with an ENO
    /// output: `ENO := TRUE`.
    pub(super) fn emit_eno_start(&mut self, pou: &Pou) {
        if pou.kind == PouKind::Program || !self.own_eno_is_output() {
            return;
        }
        let name = Expr {
            kind: ExprKind::Name(Ident {
                name: ENO.to_string(),
                span: pou.name.span,
            }),
            span: pou.name.span,
        };
        let Some(place) = self.place(&name) else {
            return;
        };
        let one = self.block.temp();
        self.block.emit(Op::LoadI { d: one, imm: 1 });
        self.write_place(&place, one);
        self.block.last_def = None;
    }

    /// True when the POU being built has a BOOL output `ENO`.
    fn own_eno_is_output(&self) -> bool {
        self.model
            .pous
            .get(self.block.pou)
            .and_then(|p| p.vars.get(ENO))
            .is_some_and(|v| v.kind == MemberKind::Output && v.ty == bool_ty())
    }

    /// `EN` read in a FUNCTION's or FUNCTION_BLOCK's body that does not
    /// declare it: TRUE (the body runs only when EN is TRUE).
    pub(super) fn en_in_body(&self, key: &str) -> Option<Val> {
        if key != "EN" || self.lookup_var(key).is_some() {
            return None;
        }
        let pou = self.model.pous.get(self.block.pou)?;
        (pou.kind != PouKind::Program).then(|| Val::Const(Const::Bits(1), Ty::T(bool_ty())))
    }

    /// The ENO output of the FB instance whose member at offset `off` is
    /// at `member(off)`, if its type has one.
    pub(super) fn fb_eno(
        &self,
        members: &[crate::ir::type_table::Member],
        member: impl Fn(u32) -> Place,
    ) -> Option<PlaceRef> {
        let m = members
            .iter()
            .find(|m| m.kind == MemberKind::Output && m.name.eq_ignore_ascii_case(ENO))?;
        (m.ty == bool_ty()).then(|| PlaceRef {
            place: member(m.offset),
            ty: m.ty,
            writable: true,
            readonly_reason: None,
            input_image: false,
        })
    }

    /// Reads function `p`'s ENO output right after its call, if it has one.
    pub(super) fn function_eno(&mut self, p: usize) -> Option<PlaceRef> {
        let var = self.model.pous[p].vars.get(ENO)?;
        if var.kind != MemberKind::Output || var.ty != bool_ty() {
            return None;
        }
        let super::model::Storage::Frame(abs) = var.storage else {
            return None;
        };
        let t = self.block.temp();
        let at = self.block.emit(Op::LoadAbs { d: t, abs });
        self.block.fixups.push((at, p));
        self.block.last_def = None;
        Some(PlaceRef {
            place: Place::Frame(t),
            ty: bool_ty(),
            writable: false,
            readonly_reason: None,
            input_image: false,
        })
    }
}

fn bool_ty() -> crate::ir::type_table::TypeId {
    TypeTable::elem(ElemType::Bool)
}
