//! Access specifiers on variables (`VAR PUBLIC`, `VAR PRIVATE`,
//! `VAR PROTECTED`, `VAR INTERNAL` in an FB or class), checked at compile
//! time:
//!
//! * PUBLIC and INTERNAL (plcrun has no namespaces, so INTERNAL reaches the
//!   whole program): `inst.x` is read and written from anywhere, without
//!   the W320 that an unqualified `VAR` gets.
//! * PRIVATE: only the code written in the declaring FB (its body and its
//!   methods, on any instance of it) sees the variable; code inherited from
//!   or added by a child does not (E929).
//! * PROTECTED: the declaring FB and the FBs that extend it, on their own
//!   instance by name or on an instance of the hierarchy (E930 elsewhere).

use super::model::OopInfo;
use crate::ir::type_table::{Member, MemberKind, TypeDef, TypeId};
use crate::sema::body::BodyBuilder;
use crate::syntax::ast::{CompilationUnit, Ident, Item};
use crate::syntax::oop::Access;
use std::collections::HashMap;

/// Fills `info.var_access`: for each FB of the program, its variables with
/// an access specifier, the inherited ones with the FB that declares them.
pub(crate) fn collect(units: &[CompilationUnit], info: &mut OopInfo) {
    let mut declared: HashMap<String, Vec<(String, Access)>> = HashMap::new();
    for p in units.iter().flat_map(|u| &u.items).filter_map(|i| match i {
        Item::Pou(p) => Some(p),
        _ => None,
    }) {
        let Some(oop) = p.oop.as_ref().filter(|o| !o.var_access.is_empty()) else {
            continue;
        };
        let mut vars = Vec::new();
        for (span, access) in &oop.var_access {
            for b in p.var_blocks.iter().filter(|b| b.span == *span) {
                for n in b.decls.iter().flat_map(|d| &d.names) {
                    vars.push((n.key(), *access));
                }
            }
        }
        declared.entry(p.name.key()).or_insert(vars);
    }
    if declared.is_empty() {
        return;
    }
    for key in info.fbs.keys() {
        let mut table = HashMap::new();
        let mut at = Some(key.clone());
        let mut steps = 0;
        while let Some(a) = at {
            for (var, access) in declared.get(&a).into_iter().flatten() {
                table.entry(var.clone()).or_insert((a.clone(), *access));
            }
            steps += 1;
            if steps > info.fbs.len() {
                break;
            }
            at = info.fbs.get(&a).and_then(|f| f.parent.clone());
        }
        if !table.is_empty() {
            info.var_access.insert(key.clone(), table);
        }
    }
}

impl BodyBuilder<'_> {
    /// The access specifier of variable `var` of FB `fb`, with the FB that
    /// declares it.
    fn declared_access(&self, fb: &str, var: &str) -> Option<(String, Access)> {
        self.model.oop.var_access.get(fb)?.get(var).cloned()
    }

    /// True when the code being emitted was written in `fb` or in an FB
    /// that extends it (`exact`: in `fb` itself).
    fn code_written_in(&self, fb: &str, exact: bool) -> bool {
        let Some(scope) = self.oop.as_ref() else {
            return false;
        };
        if exact {
            return scope.origin == fb;
        }
        let fbs = &self.model.oop.fbs;
        let mut at = Some(scope.origin.clone());
        let mut steps = 0;
        while let Some(a) = at {
            if a == fb {
                return true;
            }
            steps += 1;
            if steps > fbs.len() {
                return false;
            }
            at = fbs.get(&a).and_then(|f| f.parent.clone());
        }
        false
    }

    /// `inst.x` where `x` has an access specifier: `Some` with what the
    /// place is (PUBLIC/INTERNAL: read and write; PRIVATE/PROTECTED from
    /// where they are hidden: E929/E930), `None` when `x` has none.
    #[allow(clippy::type_complexity)]
    pub(in crate::sema) fn var_access_outside(
        &mut self,
        def: &TypeDef,
        m: &Member,
        name: &Ident,
    ) -> Option<Option<(u32, TypeId, bool, Option<&'static str>)>> {
        if self.model.oop.var_access.is_empty() || m.kind != MemberKind::Local {
            return None;
        }
        let (origin, access) = self.declared_access(&def.name.to_ascii_uppercase(), &name.key())?;
        let allowed = match access {
            Access::Public | Access::Internal => true,
            Access::Private => self.code_written_in(&origin, true),
            Access::Protected => self.code_written_in(&origin, false),
        };
        if allowed {
            return Some(Some((m.offset, m.ty, true, None)));
        }
        self.hidden_var(&origin, access, name);
        Some(None)
    }

    /// A variable named in the code of an FB: E929 when it is PRIVATE to
    /// an ancestor that did not write this code.
    pub(in crate::sema) fn check_inherited_private(&mut self, id: &Ident) {
        if self.model.oop.var_access.is_empty() {
            return;
        }
        let Some(fb) = self.oop.as_ref().map(|s| s.fb.clone()) else {
            return;
        };
        let key = id.key();
        if self.oop_local(&key).is_some() {
            return;
        }
        if let Some((origin, Access::Private)) = self.declared_access(&fb, &key)
            && !self.code_written_in(&origin, true)
        {
            self.hidden_var(&origin, Access::Private, id);
        }
    }

    fn hidden_var(&mut self, origin: &str, access: Access, name: &Ident) {
        let owner = self
            .model
            .oop
            .fbs
            .get(origin)
            .map_or(origin.to_string(), |f| f.name.clone());
        let (code, which) = match access {
            Access::Private => (
                "E929",
                format!("PRIVATE to `{owner}`: only code written in `{owner}` can use it"),
            ),
            _ => (
                "E930",
                format!(
                    "PROTECTED in `{owner}`: only code of `{owner}` and of the FBs that extend it can use it"
                ),
            ),
        };
        self.diags.error(
            code,
            name.span,
            format!("variable `{}` is {which}", name.name),
        );
    }
}
