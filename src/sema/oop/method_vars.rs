//! VAR_IN_OUT of methods: each is a hidden pointer slot of the FB (like an
//! FB's own VAR_IN_OUT) that a method call connects to the caller's
//! variable; calling the FB itself does not ask for it. (A method's
//! VAR_EXTERNAL is declared on its FB under the global's own name.)

use crate::ir::op::Slot;
use crate::ir::type_table::TypeTable;
use crate::sema::body::BodyBuilder;
use crate::sema::calls::Param;
use crate::sema::emit::Ty;
use crate::source::Span;
use crate::syntax::ast::{Expr, Ident};

impl BodyBuilder<'_> {
    /// True when member `member` of FB type `fb` is the hidden VAR_IN_OUT
    /// of one of its methods.
    pub(in crate::sema) fn is_method_in_out(&self, fb: &str, member: &str) -> bool {
        if self.model.oop.fbs.is_empty() {
            return false;
        }
        let Some(f) = self.model.oop.fbs.get(&fb.to_ascii_uppercase()) else {
            return false;
        };
        let key = member.to_ascii_uppercase();
        f.versions
            .iter()
            .flat_map(|v| &v.params)
            .any(|p| p.in_out && p.hidden == key)
    }

    /// E404: a method's VAR_IN_OUT left unconnected.
    pub(super) fn unconnected(&mut self, p: &Param, method: &Ident, span: Span) {
        self.diags.error(
            "E404",
            span,
            format!(
                "VAR_IN_OUT `{}` of method `{}` must be connected",
                p.name, method.name
            ),
        );
    }

    /// The address of the variable connected to VAR_IN_OUT `p` of a method
    /// called through an interface, in a temporary (checked as an FB's).
    pub(super) fn in_out_address(&mut self, p: &Param, e: &Expr) -> Option<Slot> {
        if self.is_open_array(p.ty) {
            // The call keeps one slot per argument: no room for the bounds.
            self.diags.error(
                "E307",
                e.span,
                "an ARRAY[*] parameter cannot be given in a call through an interface or a pointer; call the method on the instance",
            );
            return None;
        }
        let arg = self.in_out_place(p, e)?;
        if arg.ty != p.ty && arg.ty != TypeTable::error() {
            self.mismatch(
                e.span,
                Ty::T(arg.ty),
                p.ty,
                &format!("VAR_IN_OUT `{}`", p.name),
            );
            return None;
        }
        if !arg.writable && !p.constant {
            self.in_out_not_writable(p, e.span);
            return None;
        }
        let a = self.address_of(&arg);
        if self.block.is_temp(a) {
            return Some(a);
        }
        let t = self.block.temp();
        self.block.mov(t, a);
        self.block.last_def = None;
        Some(t)
    }
}
