//! `SIZEOF(T)` and `SIZEOF(c)` in constant expressions — array bounds and
//! constants such as TcUnit's `ARRAY[0..(N * SIZEOF(ST_Message)) - 1] OF
//! BYTE` — with the byte counts `SIZEOF` gives in code
//! (docs/semantics.md §23): a type's or a variable's declared type.

use super::decl_consts::DeclConsts;
use super::declare::Declarer;
use super::model::VarInfo;
use super::refs::size_bytes;
use crate::elementary::ElemType;
use crate::ir::type_table::TypeId;
use crate::syntax::ast::{Arg, Expr, ExprKind, Ident};
use indexmap::IndexMap;

/// The name `e` takes the size of, when `e` is `SIZEOF(name)`.
fn sizeof_operand(e: &Expr) -> Option<&Ident> {
    let ExprKind::Call(call) = &e.kind else {
        return None;
    };
    let ExprKind::Name(f) = &call.callee.kind else {
        return None;
    };
    if !f.name.eq_ignore_ascii_case("SIZEOF") {
        return None;
    }
    match call.args.as_slice() {
        [Arg::Positional(x)] => match &x.kind {
            ExprKind::Name(id) => Some(id),
            _ => None,
        },
        _ => None,
    }
}

/// Every `SIZEOF(name)` inside `e`.
fn sizeof_operands<'e>(e: &'e Expr, out: &mut Vec<&'e Ident>) {
    if let Some(id) = sizeof_operand(e) {
        out.push(id);
        return;
    }
    match &e.kind {
        ExprKind::Paren(x) | ExprKind::Unary(_, x) => sizeof_operands(x, out),
        ExprKind::Binary(_, a, b) => {
            sizeof_operands(a, out);
            sizeof_operands(b, out);
        }
        _ => {}
    }
}

impl Declarer<'_> {
    /// Resolves the user types `e`'s `SIZEOF`s name, so that folding `e`
    /// (which only reads the declarations) finds their layout.
    pub(super) fn resolve_sizeof_types(&mut self, e: &Expr) {
        let mut names = Vec::new();
        sizeof_operands(e, &mut names);
        for id in names {
            let key = id.key();
            if self.type_decls.contains_key(&key) {
                self.user_type(&key, id.span);
            }
        }
    }
}

impl DeclConsts<'_> {
    /// The bytes of `SIZEOF(name)` when `e` is one and `name` is a type
    /// already laid out or a variable of the declarations.
    pub(super) fn const_sizeof(
        &self,
        e: &Expr,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<i128> {
        let id = sizeof_operand(e)?;
        let key = id.key();
        let var = local
            .and_then(|l| l.get(&key))
            .or_else(|| self.model.globals.get(&key));
        let ty: TypeId = match var {
            Some(v) => v.ty,
            None => match ElemType::from_name(&id.name) {
                Some(e) => crate::ir::type_table::TypeTable::elem(e),
                None => *self.model.type_ids.get(&key)?,
            },
        };
        size_bytes(self.types, ty).map(i128::from)
    }
}
