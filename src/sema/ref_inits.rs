//! Reference and pointer initial values in declarations:
//! `r : REF_TO INT := REF(x);` (edition 3) and `p : POINTER TO INT :=
//! ADR(x);` (CODESYS).
//!
//! A reference is a runtime value (the number the machine gives the
//! object it designates, `crate::ir::refs`), so it cannot be part of the
//! initial memory image: the initial value is evaluated by code, at the
//! start of the POU's body, before its first statement.
//! - In a FUNCTION, and for a VAR_TEMP, at every call (their variables
//!   are fresh at every call).
//! - In a FUNCTION_BLOCK or PROGRAM, once per initialisation: a hidden
//!   slot of the instance remembers that the instance's references were
//!   set. The slot is not a member of the instance, so it starts again at
//!   0 exactly when the references start again from NULL: a cold start,
//!   a warm start (references are never retained) and an online change
//!   (which resets references, semantics §16). The evaluation happens at
//!   the instance's first call after that, before its body: until then a
//!   reference read from outside the instance is still NULL.
//!
//! An initial value on a VAR_INPUT, VAR_IN_OUT or VAR_EXTERNAL (set by
//! the caller or elsewhere) is refused, E429. `:= NULL` is every
//! reference's initial value already: accepted anywhere, nothing to run.

use super::body::BodyBuilder;
use super::declare::Declarer;
use crate::ir::op::{Op, Slot, Target};
use crate::ir::type_table::{TypeId, TypeKind};
use crate::syntax::ast::{
    Expr, ExprKind, Ident, Initializer, Pou, PouKind, Stmt, StmtKind, VarBlock, VarDecl, VarKind,
};

/// The `REF(x)` / `ADR(x)` initial value of `decl`, if it has one.
pub(super) fn reference_init(decl: &VarDecl) -> Option<&Expr> {
    let Some(Initializer::Expr(e)) = &decl.init else {
        return None;
    };
    let ExprKind::Call(call) = &e.kind else {
        return None;
    };
    let ExprKind::Name(f) = &call.callee.kind else {
        return None;
    };
    matches!(f.key().as_str(), "REF" | "ADR").then_some(e)
}

/// `name := value`, the assignment the body makes of `decl`'s initial
/// value (at `decl`'s place).
pub(super) fn init_assignment(name: &Ident, value: &Expr, decl: &VarDecl) -> Stmt {
    Stmt {
        kind: StmtKind::Assign {
            target: Expr {
                kind: ExprKind::Name(name.clone()),
                span: name.span,
            },
            value: value.clone(),
        },
        span: decl.span,
    }
}

/// Whether `decl`'s initial value is `NULL` (every reference's initial
/// value already: nothing to evaluate).
fn null_init(decl: &VarDecl) -> bool {
    matches!(&decl.init, Some(Initializer::Expr(Expr { kind: ExprKind::Name(n), .. })) if n.key() == "NULL")
}

/// Whether the initial value of a declaration in `block` of `pou` is
/// evaluated at every call (no once-only guard).
pub(super) fn every_call(pou: &Pou, block: &VarBlock) -> bool {
    pou.kind == PouKind::Function || block.kind == VarKind::Temp
}

impl Declarer<'_> {
    /// For a declaration of reference type `ty` initialised with `REF(x)`
    /// or `ADR(x)`: true (the value is evaluated by the body, not put in
    /// the memory image), with the POU's guard slot taken from `offset`
    /// when it needs one. E429 where the body cannot set it.
    pub(super) fn defer_reference_init(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        decl: &VarDecl,
        ty: TypeId,
        offset: &mut u32,
    ) -> bool {
        if !matches!(self.types.get(ty).kind, TypeKind::Ref { .. }) {
            return false;
        }
        if null_init(decl) {
            return true;
        }
        let Some(e) = reference_init(decl) else {
            return false;
        };
        if !matches!(block.kind, VarKind::Local | VarKind::Output | VarKind::Temp) {
            self.diags.error(
                "E429",
                e.span,
                "a reference initial value (`REF(x)`, `ADR(x)`) is evaluated by the POU's body: \
                 it is allowed on VAR, VAR_OUTPUT and VAR_TEMP, not on inputs, in-outs or \
                 externals",
            );
            return true;
        }
        let key = pou.name.key();
        if !every_call(pou, block) && !self.model.ref_init_guards.contains_key(&key) {
            let slot = *offset;
            *offset = self.grow(*offset, 1, decl.span);
            self.model.ref_init_guards.insert(key, (slot, ty));
        }
        true
    }
}

impl Declarer<'_> {
    /// For a global variable or a structure field (`what`) of reference
    /// type `ty`: true when its initial value needs no image value —
    /// `NULL`, or `REF(x)`/`ADR(x)`, which no body evaluates there and is
    /// refused by name (E430).
    pub(super) fn static_reference_init(&mut self, decl: &VarDecl, ty: TypeId, what: &str) -> bool {
        if !matches!(self.types.get(ty).kind, TypeKind::Ref { .. }) {
            return false;
        }
        if null_init(decl) {
            return true;
        }
        let Some(e) = reference_init(decl) else {
            return false;
        };
        self.diags.error(
            "E430",
            e.span,
            format!(
                "a reference initial value (`REF(x)`, `ADR(x)`) on {what} is not supported: no POU \
                 body evaluates it; assign it in a PROGRAM (or declare the reference in the \
                 POU that uses it)"
            ),
        );
        true
    }
}

impl BodyBuilder<'_> {
    /// Evaluates the reference initial values of `pou` before its body:
    /// those of every call first, then, under the instance's guard, the
    /// once-per-initialisation ones.
    pub(super) fn emit_reference_inits(&mut self, pou: &Pou) {
        let inits: Vec<(bool, Stmt)> = pou
            .var_blocks
            .iter()
            .filter(|b| matches!(b.kind, VarKind::Local | VarKind::Output | VarKind::Temp))
            .flat_map(|b| b.decls.iter().map(move |d| (b, d)))
            .filter_map(|(b, d)| reference_init(d).map(|e| (b, d, e)))
            .flat_map(|(b, d, e)| {
                d.names
                    .iter()
                    .map(move |n| (every_call(pou, b), init_assignment(n, e, d)))
            })
            .filter(|(_, s)| self.assigns_a_reference(s))
            .collect();
        if inits.is_empty() {
            return;
        }
        let (each, once): (Vec<_>, Vec<_>) = inits.into_iter().partition(|(e, _)| *e);
        let each: Vec<Stmt> = each.into_iter().map(|(_, s)| s).collect();
        self.stmts(&each);
        let Some(&(guard, _)) = self.model.ref_init_guards.get(&pou.name.key()) else {
            return;
        };
        let once: Vec<Stmt> = once.into_iter().map(|(_, s)| s).collect();
        let Some(first) = once.first().and_then(|s| match &s.kind {
            StmtKind::Assign { target, .. } => Some(target.clone()),
            _ => None,
        }) else {
            return;
        };
        let guard = Slot::new(guard);
        let done = self.block.emit(Op::Jnz {
            c: guard,
            t: Target::UNPATCHED,
        });
        self.stmts(&once);
        // REF(x) and ADR(x) are never NULL: the first one marks the
        // instance as initialised.
        if let Some(v) = self.place(&first) {
            let value = self.read_place(&v);
            let s = self.materialize(&value);
            self.block.emit(Op::Mov { d: guard, s });
        }
        let here = self.block.here();
        self.block.patch(done, here);
    }

    /// Whether `s` assigns a variable of reference type (a `REF(x)`
    /// initial value of anything else was refused when it was declared).
    fn assigns_a_reference(&self, s: &Stmt) -> bool {
        let StmtKind::Assign { target, .. } = &s.kind else {
            return false;
        };
        let ExprKind::Name(n) = &target.kind else {
            return false;
        };
        self.lookup_var(&n.key())
            .is_some_and(|v| matches!(self.types.get(v.ty).kind, TypeKind::Ref { .. }))
    }
}
