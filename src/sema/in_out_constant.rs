//! `VAR_IN_OUT CONSTANT` (CODESYS / TwinCAT): an in-out the body may not
//! write (E401), passed by reference as any in-out, so its argument may be
//! a variable the caller cannot write either (a CONSTANT, an input). Its
//! declaration is a compatibility warning (W353, layout.rs); an in-out
//! without CONSTANT still needs a writable variable (E412).

use super::body::BodyBuilder;
use super::calls::Param;
use super::consts::Const;
use super::emit::{Place, PlaceRef, Val};
use crate::ir::type_table::{TypeId, TypeKind};
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind};

/// Why an output of a function block instance is read-only from outside.
pub(super) const FB_OUTPUT: &str = "outputs of a function block are written only by the block";

impl BodyBuilder<'_> {
    /// Whether `arg` may be bound to in-out `p`: a variable the caller may
    /// write, or any variable for a CONSTANT in-out (E412 otherwise). The
    /// binding counts as a write of `arg` unless `p` is CONSTANT (the
    /// callee does not write it).
    pub(super) fn in_out_bindable(&mut self, p: &Param, arg: &PlaceRef, at: Span) -> bool {
        // CODESYS connects another instance's output to an in-out, which
        // the callee then may write (`bEnable := fbAxis.bEnabled`).
        if !arg.writable
            && !p.constant
            && arg.readonly_reason == Some(FB_OUTPUT)
            && self.model.codesys_files.contains(&at.file)
        {
            self.diags.warning(
                "W492",
                at,
                format!(
                    "VAR_IN_OUT `{}` connected to an output of another instance (CODESYS): the called block may write that output",
                    p.name
                ),
            );
            return true;
        }
        if !arg.writable && !p.constant {
            self.in_out_not_writable(p, at);
            return false;
        }
        if !p.constant {
            self.note_input_write(arg, at);
        }
        true
    }

    /// E412: the variable given to in-out `p` cannot be written.
    pub(super) fn in_out_not_writable(&mut self, p: &Param, at: Span) {
        self.diags.push(
            crate::diagnostics::Diagnostic::error(
                "E412",
                at,
                format!("VAR_IN_OUT `{}` needs a writable variable", p.name),
            )
            .with_note(
                "a VAR_IN_OUT CONSTANT (CODESYS) takes any variable: the callee only reads it",
            ),
        );
    }
}

impl BodyBuilder<'_> {
    /// The variable connected to in-out `p` by argument `e`. A `VAR_IN_OUT
    /// CONSTANT` also takes a value (a literal, an expression, a call's
    /// scalar result: `fbJson.AddObjectMember(v, 'name')`, as TwinCAT's own
    /// libraries are called), kept in a temporary of the parameter's type
    /// for the call, and a STRING of another length, passed whole (the
    /// callee reads it only).
    pub(super) fn in_out_place(&mut self, p: &Param, e: &Expr) -> Option<PlaceRef> {
        if !p.constant {
            return self.place(e);
        }
        if !self.denotes_storage(e) {
            return self.constant_in_out_value(p, e);
        }
        let arg = self.place(e)?;
        let strings = |s: &Self, t: TypeId| match s.types.get(t).kind {
            TypeKind::Str { wide, .. } => Some(wide),
            _ => None,
        };
        match (strings(self, arg.ty), strings(self, p.ty)) {
            (Some(a), Some(b)) if a == b => Some(PlaceRef { ty: p.ty, ..arg }),
            _ => Some(arg),
        }
    }

    /// Whether `e` names storage (a variable, an element, a member, a
    /// dereference, a call of a function returning an array or a
    /// structure) rather than a value.
    fn denotes_storage(&mut self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Paren(x) => self.denotes_storage(x),
            ExprKind::Name(_)
            | ExprKind::Direct(_)
            | ExprKind::Member(..)
            | ExprKind::Index(..)
            | ExprKind::Deref(_) => true,
            ExprKind::Call(_) => {
                let t = self.probe_in(e, false, None);
                t.id().is_some_and(|t| {
                    matches!(
                        self.types.get(t).kind,
                        TypeKind::Array { .. } | TypeKind::Struct { .. } | TypeKind::Pou { .. }
                    )
                })
            }
            _ => false,
        }
    }

    /// A value given to `VAR_IN_OUT CONSTANT` `p`: evaluated into a
    /// temporary of `p`'s type (a string one as long as the value, so
    /// that it is passed whole), read-only.
    fn constant_in_out_value(&mut self, p: &Param, e: &Expr) -> Option<PlaceRef> {
        let v = self.expr(e, Some(p.ty));
        if v.is_error() {
            return None;
        }
        let what = format!("VAR_IN_OUT CONSTANT `{}`", p.name);
        let region = self.block.temps(1);
        let place = PlaceRef {
            place: Place::Frame(region),
            ty: p.ty,
            writable: false,
            readonly_reason: Some("it is a value given to a VAR_IN_OUT CONSTANT"),
            input_image: false,
        };
        let kind = self.types.get(p.ty).kind.clone();
        match kind {
            TypeKind::Str { max, wide } => {
                let given = v.ty().id().and_then(|t| match self.types.get(t).kind {
                    TypeKind::Str { max, .. } => Some(max),
                    _ => None,
                });
                let literal = match &v {
                    Val::Const(Const::Str(s), _) => u32::try_from(s.chars().count()).ok(),
                    _ => None,
                };
                let room = max.max(given.unwrap_or(0)).max(literal.unwrap_or(0));
                let id = self.string_temp(room, wide);
                self.block.mov(region, id);
                self.block.last_def = None;
            }
            TypeKind::Elem(_) | TypeKind::Enum { .. } | TypeKind::Subrange { .. } => {}
            _ => {
                self.diags
                    .error("E402", e.span, "this expression is not a variable");
                return None;
            }
        }
        let x = self.coerce(v, p.ty, e.span, &what);
        if x.is_error() {
            return None;
        }
        let s = self.materialize(&x);
        self.write_place(&place, s);
        Some(place)
    }
}
