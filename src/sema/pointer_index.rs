//! `p[i]` on a `POINTER TO T` (CODESYS / TwinCAT): the `T` `i` elements
//! after the one `p` points to, `(p + i * SIZEOF(p^))^`. It is spelt as
//! that expression and resolved as one, so it is checked as pointer
//! arithmetic and dereference are (W303; outside the object R031).

use super::body::BodyBuilder;
use super::emit::PlaceRef;
use crate::ir::type_table::{RefFlavor, TypeKind};
use crate::syntax::ast::{Arg, BinaryOp, Call, Expr, ExprKind, Ident};

impl BodyBuilder<'_> {
    /// Whether `base` is a variable path of a `POINTER TO` type.
    pub(super) fn is_pointer_path(&self, base: &Expr) -> bool {
        self.static_type(base).is_some_and(|t| {
            matches!(
                self.types.get(t).kind,
                TypeKind::Ref {
                    flavor: RefFlavor::Pointer,
                    ..
                }
            )
        })
    }

    /// The place `base[indexes]` for a pointer `base` (E404 unless one
    /// index is given).
    pub(super) fn pointer_index(
        &mut self,
        e: &Expr,
        base: &Expr,
        indexes: &[Expr],
    ) -> Option<PlaceRef> {
        let [index] = indexes else {
            self.diags.error(
                "E404",
                e.span,
                format!(
                    "a pointer takes one index (`p[i]`), {} given",
                    indexes.len()
                ),
            );
            return None;
        };
        let span = e.span;
        let node = |kind| Expr { kind, span };
        let sizeof = node(ExprKind::Call(Call {
            callee: Box::new(node(ExprKind::Name(Ident {
                name: "SIZEOF".to_string(),
                span,
            }))),
            args: vec![Arg::Positional(node(ExprKind::Deref(Box::new(
                base.clone(),
            ))))],
            span,
        }));
        let offset = node(ExprKind::Binary(
            BinaryOp::Mul,
            Box::new(index.clone()),
            Box::new(sizeof),
        ));
        let moved = node(ExprKind::Binary(
            BinaryOp::Add,
            Box::new(base.clone()),
            Box::new(offset),
        ));
        self.place(&node(ExprKind::Deref(Box::new(moved))))
    }
}
