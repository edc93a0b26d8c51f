//! Copy assignment of FB instances, `fb1 := fb2;` (CODESYS / TwinCAT):
//! every variable of `fb2` (inputs, outputs, locals, the state of nested
//! instances, the addresses its in-outs were last connected to) is copied
//! into `fb1`, both of the same FB type. IEC 61131-3 does not allow it:
//! a compatibility warning (W489). Strings are copied by text, as in a
//! structure copy (aggregate_copy.rs).

use super::body::BodyBuilder;
use crate::ir::op::Slot;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind};
use crate::source::Span;
use crate::syntax::ast::Expr;

/// Whether a member of kind `k` holds its value inside the instance (an
/// in-out holds an address there, an external lives outside).
fn held_by_value(k: MemberKind) -> bool {
    !matches!(k, MemberKind::InOut | MemberKind::External)
}

impl BodyBuilder<'_> {
    /// `target := value` for an FB instance `target`.
    pub(super) fn copy_fb(&mut self, target: &super::emit::PlaceRef, value: &Expr, span: Span) {
        let Some(src) = self.place(value) else {
            return;
        };
        if src.ty != target.ty {
            self.mismatch(
                value.span,
                super::emit::Ty::T(src.ty),
                target.ty,
                "assignment",
            );
            return;
        }
        self.diags.warning(
            "W489",
            span,
            format!(
                "a {} instance copied by assignment (a CODESYS extension): every variable of the instance is copied",
                self.types.name(target.ty)
            ),
        );
        self.copy_aggregate(target, &src, span);
    }

    /// The string-holding members of FB type `ty` held in the instance:
    /// (offset, type), by offset.
    pub(super) fn fb_string_members(&self, ty: TypeId) -> Vec<(u32, TypeId)> {
        let TypeKind::Pou { members, .. } = &self.types.get(ty).kind else {
            return Vec::new();
        };
        let mut out: Vec<(u32, TypeId)> = members
            .iter()
            .filter(|m| held_by_value(m.kind) && self.contains_strings(m.ty))
            .map(|m| (m.offset, m.ty))
            .collect();
        out.sort_by_key(|m| m.0);
        out
    }

    /// Copies an instance of FB type `ty` holding strings, at offset
    /// `off` from the addresses in `d` and `s`: the slots between its
    /// strings in runs, the strings by text.
    pub(super) fn copy_fb_at(&mut self, d: Slot, s: Slot, ty: TypeId, off: u32) {
        let size = self.types.size(ty);
        let mut at = 0;
        for (o, t) in self.fb_string_members(ty) {
            self.copy_plain(d, s, off + at, o.saturating_sub(at));
            self.copy_at(d, s, t, off + o);
            at = o + self.types.size(t);
        }
        self.copy_plain(d, s, off + at, size.saturating_sub(at));
    }
}
