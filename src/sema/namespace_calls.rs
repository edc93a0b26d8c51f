//! A function called with its library's namespace, `Tc2_Standard.CONCAT(a,
//! b)`, `Tc2_Utilities.F_LTrim(s)` (CODESYS / TwinCAT): plcrun has one
//! namespace, so the call is that of the function of that name. The
//! qualifier is taken for a namespace only when it names nothing else
//! visible (a variable, a POU, a type), so `inst.M()` stays a method call,
//! and only before a FUNCTION or standard function, so a misspelt
//! instance (`fbTmer.Start()`) is still reported as undeclared.

use super::body::BodyBuilder;
use super::oop::calls::is_this;
use crate::syntax::ast::{Call, Expr, ExprKind};

impl BodyBuilder<'_> {
    /// `call` without its namespace, when its callee is `Ns.F`.
    pub(super) fn without_namespace(&self, call: &Call) -> Option<Call> {
        let ExprKind::Member(base, f) = &call.callee.kind else {
            return None;
        };
        let ExprKind::Name(ns) = &base.kind else {
            return None;
        };
        let key = ns.key();
        let named = self.lookup_var(&key).is_some()
            || self.model.pou_index.contains_key(&key)
            || self.model.type_ids.contains_key(&key)
            || is_this(base)
            || super::oop::calls::is_super(base);
        let fkey = f.key();
        let function = self
            .model
            .pou_index
            .get(&fkey)
            .is_some_and(|&p| self.model.pous[p].kind == crate::syntax::ast::PouKind::Function)
            || super::stdfuncs::is_standard_function(&f.name);
        if named || !function {
            return None;
        }
        Some(Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(f.clone()),
                span: f.span,
            }),
            args: call.args.clone(),
            span: call.span,
        })
    }

    /// E201 for `ns.f(...)` where `ns` names nothing here (a library that
    /// is not loaded, `SysFile.SysFileClose(...)`) and `f` is no function:
    /// one named error instead of a misleading one about instances.
    pub(super) fn unknown_library_call(&mut self, call: &Call) -> bool {
        let ExprKind::Member(base, f) = &call.callee.kind else {
            return false;
        };
        let ExprKind::Name(ns) = &base.kind else {
            return false;
        };
        let key = ns.key();
        let named = self.lookup_var(&key).is_some()
            || self.model.pou_index.contains_key(&key)
            || self.model.type_ids.contains_key(&key)
            || self.model.globals.contains_key(&key)
            || is_this(base)
            || super::oop::calls::is_super(base);
        // `GVL.inst(...)`: a global read through its list's name.
        if named || self.model.globals.contains_key(&f.key()) {
            return false;
        }
        self.diags.error(
            "E201",
            call.callee.span,
            format!(
                "unknown function `{}.{}`: nothing here is named `{}` (no variable, POU or global list; a library plcrun does not have?)",
                ns.name, f.name, ns.name
            ),
        );
        true
    }
}
