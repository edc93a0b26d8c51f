//! Enumeration values written with their type's name, `E_Mode.Run`
//! (CODESYS / TwinCAT, as well as IEC's `E_Mode#Run`), and the types
//! declared after `{attribute 'qualified_only'}`, whose values may only
//! be written that way (E433 otherwise). The type may carry its library's
//! namespace (`IBaseLibrary.TypeClass.TYPE_INT`), as in declarations.

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use super::model::Model;
use crate::diagnostics::Diagnostics;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::syntax::ast::{Expr, ExprKind, Ident};

/// What `Type.Value` names, when `Type` is an enumeration type.
pub(super) enum Qualified {
    /// The value of enumeration type `.0`.
    Value(TypeId, i64),
    /// `Type` is an enumeration without a value of that name (E201
    /// reported).
    Unknown,
}

/// `e` as `Type.Value` for an enumeration type `Type`, if it has that
/// shape. The caller makes sure `Type` is not a variable's name.
pub(super) fn qualified(
    types: &TypeTable,
    model: &Model,
    diags: &mut Diagnostics,
    e: &Expr,
) -> Option<Qualified> {
    let ExprKind::Member(base, value) = &e.kind else {
        return None;
    };
    let ty_name = match &base.kind {
        ExprKind::Name(n) => n,
        // `__SYSTEM.TYPE_CLASS.TYPE_INT`, `IBaseLibrary.TypeClass.TYPE_INT`:
        // the type named with its library's namespace, as in declarations.
        ExprKind::Member(ns, n) if is_namespace(model, ns) => n,
        _ => return None,
    };
    let t = *model.type_ids.get(&ty_name.key())?;
    let TypeKind::Enum { values, .. } = &types.get(t).kind else {
        return None;
    };
    match values
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(&value.name))
    {
        Some((_, v)) => Some(Qualified::Value(t, *v)),
        None => {
            let names = values.iter().map(|(n, _)| n.as_str());
            let message = super::suggest::with_suggestion(
                format!("enumeration {} has no value `{}`", ty_name.name, value.name),
                &value.name,
                names,
            );
            diags.error("E201", value.span, message);
            Some(Qualified::Unknown)
        }
    }
}

/// The name `Ns.Type` or `Type` starts with.
fn root_name(e: &Expr) -> Option<&Ident> {
    match &e.kind {
        ExprKind::Name(n) => Some(n),
        ExprKind::Member(b, _) => match &b.kind {
            ExprKind::Name(n) => Some(n),
            _ => None,
        },
        _ => None,
    }
}

/// True when `e` is a bare name that no POU, type or global list of the
/// program has: a library's namespace (variables are the caller's check).
fn is_namespace(model: &Model, e: &Expr) -> bool {
    let ExprKind::Name(q) = &e.kind else {
        return false;
    };
    let k = q.key();
    !model.pou_index.contains_key(&k)
        && !model.type_ids.contains_key(&k)
        && !model.globals.contains_key(&k)
}

/// Reports E433 when `id`, written alone, is a value of a
/// `qualified_only` enumeration (of type `ty` when given); true then.
pub(super) fn unqualified_use(
    types: &TypeTable,
    model: &Model,
    diags: &mut Diagnostics,
    id: &Ident,
    ty: Option<TypeId>,
) -> bool {
    let Some(owners) = model.qualified_enum_values.get(&id.key()) else {
        return false;
    };
    let owner = match ty {
        Some(t) if owners.contains(&t) => t,
        Some(_) => return false,
        None => owners[0],
    };
    let ty_name = types.name(owner);
    diags.push(
        crate::diagnostics::Diagnostic::error(
            "E433",
            id.span,
            format!(
                "enumeration value `{}` must be written with its type: `{ty_name}.{}`",
                id.name, id.name
            ),
        )
        .with_note(format!(
            "{ty_name} is declared after {{attribute 'qualified_only'}}"
        )),
    );
    true
}

impl BodyBuilder<'_> {
    /// `Type.Value` in an expression, when `Type` is an enumeration type
    /// and no variable of that name is visible.
    pub(super) fn qualified_enum(&mut self, e: &Expr) -> Option<Val> {
        if let ExprKind::Member(base, _) = &e.kind
            && let Some(b) = root_name(base)
            && self.lookup_var(&b.key()).is_some()
        {
            return None;
        }
        Some(match qualified(self.types, self.model, self.diags, e)? {
            Qualified::Value(t, v) => Val::Const(Const::Bits(v as u64), Ty::T(t)),
            Qualified::Unknown => Val::error(),
        })
    }

    /// E433 for a value of a `qualified_only` enumeration written alone
    /// (true when reported).
    pub(super) fn unqualified_enum(&mut self, id: &Ident) -> bool {
        unqualified_use(self.types, self.model, self.diags, id, None)
    }
}
