//! `REF`, `ADR`, `SIZEOF`, `__ISVALIDREF` / `ISVALIDREF`, and the rule
//! that a reference to a temporary may not be stored where it outlives it.

use super::{intern_ref, ref_parts, size_bytes};
use crate::elementary::ElemType;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{MemberKind, RefFlavor, TypeId, TypeKind, TypeTable};
use crate::sema::body::BodyBuilder;
use crate::sema::consts::Const;
use crate::sema::emit::{Place, Ty, Val};
use crate::sema::model::Storage;
use crate::syntax::ast::{Arg, Call, Expr, ExprKind, PouKind};

/// The built-in a call names, if it is one of ours.
#[derive(Clone, Copy, PartialEq, Eq)]
enum RefBuiltin {
    Ref,
    Adr,
    SizeOf,
    IsValidRef,
}

impl BodyBuilder<'_> {
    /// `REF(x)`, `ADR(x)`, `SIZEOF(x)`, `__ISVALIDREF(r)`; `None` when the
    /// call is something else (a user POU of that name wins).
    pub(in crate::sema) fn ref_call(&mut self, call: &Call) -> Option<Val> {
        let ExprKind::Name(id) = &call.callee.kind else {
            return None;
        };
        let key = id.key();
        let which = match key.as_str() {
            "REF" => RefBuiltin::Ref,
            "ADR" => RefBuiltin::Adr,
            "SIZEOF" => RefBuiltin::SizeOf,
            "__ISVALIDREF" | "ISVALIDREF" => RefBuiltin::IsValidRef,
            _ => return None,
        };
        if self.model.pou_index.contains_key(&key) || self.lookup_var(&key).is_some() {
            return None;
        }
        let arg = match call.args.as_slice() {
            [Arg::Positional(e)] => e,
            _ => {
                self.diags.error(
                    "E251",
                    call.span,
                    format!("{} takes exactly one argument", id.name),
                );
                return Some(Val::error());
            }
        };
        Some(match which {
            RefBuiltin::Ref => self.reference_to(arg, RefFlavor::RefTo),
            RefBuiltin::Adr => {
                self.diags.warning(
                    "W301",
                    call.callee.span,
                    "`ADR` is a CODESYS extension (IEC 61131-3 edition 3 has `REF`)",
                );
                self.reference_to(arg, RefFlavor::Pointer)
            }
            RefBuiltin::SizeOf => {
                self.diags
                    .warning("W302", call.callee.span, "`SIZEOF` is a CODESYS extension");
                self.size_of(arg)
            }
            RefBuiltin::IsValidRef => {
                self.diags.warning(
                    "W305",
                    call.callee.span,
                    format!("`{}` is a CODESYS extension", id.name),
                );
                self.is_valid_ref(arg)
            }
        })
    }

    /// A reference of `flavor` to the variable `x`.
    fn reference_to(&mut self, x: &Expr, flavor: RefFlavor) -> Val {
        if let Some(var) = root_name(x).and_then(|n| self.lookup_var(&n.key()))
            && var.constant
        {
            self.diags.error(
                "E254",
                x.span,
                format!(
                    "`{}` is a CONSTANT: no reference to it may be taken",
                    var.name
                ),
            );
            return Val::error();
        }
        if flavor == RefFlavor::Pointer
            && let Some(v) = self.address_in_array(x)
        {
            return v;
        }
        let Some(p) = self.place(x) else {
            return Val::error();
        };
        if p.ty == TypeTable::error() {
            return Val::error();
        }
        if self.is_open_array(p.ty) {
            self.open_array_misused(x.span);
            return Val::error();
        }
        if let Place::View { r, .. } = p.place {
            // A byte view (a UNION member, `p^` of one) is its own address.
            return Val::Slot(r, intern_ref(self.types, p.ty, flavor));
        }
        let d = self.reference_value(&p);
        let ty = intern_ref(self.types, p.ty, flavor);
        Val::Slot(d, ty)
    }

    /// `ADR(a[i])` of an element of an array variable: a pointer into the
    /// whole array's object, so it may move along the array as CODESYS
    /// code does (`MEMCPY(ADR(buf[0]), src, SIZEOF(buf))`) and still never
    /// leaves it. `None` when `x` is no such element (the element alone is
    /// then the object).
    fn address_in_array(&mut self, x: &Expr) -> Option<Val> {
        let ExprKind::Index(base, indexes) = &x.kind else {
            return None;
        };
        let array = self.static_type(base)?;
        if !matches!(self.types.get(array).kind, TypeKind::Array { .. }) {
            return None;
        }
        let Some(q) = self.place(base) else {
            return Some(Val::error());
        };
        if matches!(q.place, Place::View { .. }) || q.ty != array {
            return None;
        }
        let whole = self.reference_value(&q);
        let Some((d, elem, _)) = self.element_reference(x, whole, array, indexes) else {
            return Some(Val::error());
        };
        Some(Val::Slot(
            d,
            intern_ref(self.types, elem, RefFlavor::Pointer),
        ))
    }

    /// `SIZEOF(x)` or `SIZEOF(T)`: bytes, an untyped integer constant.
    fn size_of(&mut self, x: &Expr) -> Val {
        let ty = match &x.kind {
            ExprKind::Name(n) if self.lookup_var(&n.key()).is_none() => self.type_named(&n.name),
            _ => self.place(x).map(|p| p.ty),
        };
        let Some(ty) = ty else {
            if let ExprKind::Name(n) = &x.kind
                && self.lookup_var(&n.key()).is_none()
            {
                self.diags.error(
                    "E201",
                    n.span,
                    format!("`{}` is neither a variable nor a type", n.name),
                );
            }
            return Val::error();
        };
        if self.is_open_array(ty) {
            self.open_array_misused(x.span);
            return Val::error();
        }
        match self.union_bytes(ty).or_else(|| size_bytes(self.types, ty)) {
            Some(b) => Val::Const(Const::Int(b as i128), Ty::AnyInt),
            None => Val::error(),
        }
    }

    /// The type a name denotes in an expression (`SIZEOF(INT)`).
    fn type_named(&self, name: &str) -> Option<TypeId> {
        if let Some(e) = ElemType::from_name(name) {
            return Some(TypeTable::elem(e));
        }
        let key = name.to_ascii_uppercase();
        if let Some(t) = self.model.type_ids.get(&key) {
            return Some(*t);
        }
        let p = *self.model.pou_index.get(&key)?;
        (self.model.pous[p].kind != PouKind::Function).then(|| self.model.pous[p].ty)
    }

    /// `__ISVALIDREF(r)`: TRUE if `r^` would not fault.
    fn is_valid_ref(&mut self, r: &Expr) -> Val {
        // A VAR_IN_OUT (CODESYS: checked before a METHOD uses it): TRUE
        // once a call connected it, its slot holding the variable's address
        // instead of NOT_CONNECTED.
        if let ExprKind::Name(id) = &r.kind
            && let Some(Storage::Ref(o)) = self.lookup_var(&id.key()).map(|v| v.storage)
        {
            let d = self.in_out_connected(Slot::new(o));
            return Val::Slot(d, TypeTable::elem(ElemType::Bool));
        }
        // A REFERENCE TO variable is asked about itself, not its target
        // (also a member: `THIS^.stFilter`, `fb.refIn`).
        let v = if let ExprKind::Name(_) | ExprKind::Member(..) = &r.kind {
            let Some(p) = self.place_raw(r) else {
                return Val::error();
            };
            match ref_parts(self.types, p.ty) {
                Some(_) => self.read_place(&p),
                None => Val::None(p.ty),
            }
        } else {
            self.expr(r, None)
        };
        if v.is_error() {
            return v;
        }
        let parts = v.ty().id().and_then(|t| ref_parts(self.types, t));
        let Some((target, _)) = parts else {
            let name = self.ty_name(v.ty());
            self.diags.error(
                "E250",
                r.span,
                format!("__ISVALIDREF needs a reference or pointer, found {name}"),
            );
            return Val::error();
        };
        let width = self.types.size(target).max(1);
        let s = self.materialize(&v);
        let d = self.block.temp();
        self.block.emit(Op::RefValid { d, r: s, width });
        Val::Slot(d, TypeTable::elem(ElemType::Bool))
    }

    /// E253 for `target := REF(t)` (or `ADR`) where `t` lives only during
    /// the call (a FUNCTION's variable, or a VAR_TEMP) and `target` does
    /// not: the reference would outlive what it designates.
    pub(in crate::sema) fn check_ref_escape(&mut self, target: &Expr, value: &Expr) {
        let ExprKind::Call(call) = &value.kind else {
            return;
        };
        let ExprKind::Name(f) = &call.callee.kind else {
            return;
        };
        if !matches!(f.key().as_str(), "REF" | "ADR") {
            return;
        }
        let Some(Arg::Positional(x)) = call.args.first() else {
            return;
        };
        self.check_escape_of(target, x, value.span);
    }

    /// E253 when `target` would keep a reference to `x` past its life.
    pub(in crate::sema) fn check_escape_of(
        &mut self,
        target: &Expr,
        x: &Expr,
        span: crate::source::Span,
    ) {
        let (Some(src), Some(dst)) = (root_name(x), root_name(target)) else {
            return;
        };
        if self.is_temporary(&src.key()) && !self.is_temporary(&dst.key()) {
            self.diags.error(
                "E253",
                span,
                format!(
                    "`{}` lives only during this call: a reference to it cannot be stored in `{}`",
                    src.name, dst.name
                ),
            );
        }
    }

    /// A variable that lives only during one call of the current POU: any
    /// variable of a FUNCTION but its result, or a VAR_TEMP.
    fn is_temporary(&self, key: &str) -> bool {
        let Some(pou) = self.model.pous.get(self.block.pou) else {
            return false;
        };
        let Some(var) = pou.vars.get(key) else {
            return false;
        };
        let is_result = pou.kind == PouKind::Function && key == pou.name.to_ascii_uppercase();
        var.kind == MemberKind::Temp
            || (pou.kind == PouKind::Function
                && !is_result
                && !matches!(
                    var.kind,
                    MemberKind::InOut | MemberKind::Output | MemberKind::External
                ))
    }
}

/// The variable name an access path starts from (`a` of `a.b[i]^.c`).
fn root_name(e: &Expr) -> Option<&crate::syntax::ast::Ident> {
    match &e.kind {
        ExprKind::Name(n) => Some(n),
        ExprKind::Member(b, _)
        | ExprKind::Index(b, _)
        | ExprKind::Paren(b)
        | ExprKind::BitAccess(b, _) => root_name(b),
        _ => None,
    }
}
