//! Reads and writes of properties. `inst.P` (and `itf.P`, `THIS^.P`,
//! `SUPER^.P`, or `P` alone in the FB's own code) read in an expression is
//! a call of the accessor method `P.GET`; assigned (`inst.P := v;`, IL
//! `ST inst.P`) it is a call of `P.SET` with `v`. The calls go through the
//! method call paths (`calls.rs`), so access specifiers, overriding,
//! `SUPER^` and interface dispatch apply as to any method.
//!
//! Diagnostics: E921 (read of a property without GET), E922 (write of one
//! without SET), E924 (a property named like a variable or method of its FB).

use super::calls::{is_super, is_this};
use super::model::OopInfo;
use crate::diagnostics::Diagnostics;
use crate::ir::type_table::{TypeId, TypeKind};
use crate::sema::body::BodyBuilder;
use crate::sema::emit::Val;
use crate::sema::model::{Storage, VarInfo};
use crate::syntax::ast::{Arg, Call, CompilationUnit, Expr, ExprKind, Ident, Item};
use crate::syntax::oop_property::{accessor_name, property_of};

/// Where a property is declared.
enum Owner {
    /// An FB (key).
    Fb(String),
    /// An interface (key).
    Itf(String),
}

/// A property named in the code.
struct PropUse {
    /// What the accessor is called on (`None`: the FB's own instance).
    base: Option<Expr>,
    /// The property's name as written.
    name: Ident,
    /// It has a GET.
    get: bool,
    /// It has a SET.
    set: bool,
    owner: Owner,
}

impl PropUse {
    /// The callee of accessor GET (`get`) or SET.
    fn callee(&self, get: bool) -> Expr {
        let id = Ident {
            name: accessor_name(&self.name.name, get),
            span: self.name.span,
        };
        let kind = match &self.base {
            Some(b) => ExprKind::Member(Box::new(b.clone()), id),
            None => ExprKind::Name(id),
        };
        Expr {
            kind,
            span: self.name.span,
        }
    }
}

/// E924: a property with the name of a variable or a method of its FB
/// (its own or inherited).
pub(crate) fn check_names(units: &[CompilationUnit], info: &OopInfo, diags: &mut Diagnostics) {
    let pous: std::collections::HashMap<String, &crate::syntax::ast::Pou> = units
        .iter()
        .flat_map(|u| &u.items)
        .filter_map(|i| match i {
            Item::Pou(p) => Some((p.name.key(), p)),
            _ => None,
        })
        .collect();
    for (key, fb) in &info.fbs {
        let mut vars = Vec::new();
        let mut at = Some(key.clone());
        let mut steps = 0;
        while let Some(a) = at {
            if let Some(p) = pous.get(&a) {
                vars.extend(
                    p.var_blocks
                        .iter()
                        .flat_map(|b| &b.decls)
                        .flat_map(|d| &d.names),
                );
            }
            steps += 1;
            if steps > info.fbs.len() {
                break;
            }
            at = info.fbs.get(&a).and_then(|f| f.parent.clone());
        }
        for v in fb.versions.iter().filter(|v| v.origin == *key) {
            let Some((prop, _)) = property_of(&v.name.name) else {
                continue;
            };
            let pk = prop.to_ascii_uppercase();
            let clash = if vars.iter().any(|n| n.key() == pk) {
                "a variable"
            } else if fb.dispatch.contains_key(&pk) {
                "a method"
            } else {
                continue;
            };
            // Once per property (GET and SET share the name).
            if fb
                .versions
                .iter()
                .filter(|w| w.origin == *key)
                .find(|w| {
                    property_of(&w.name.name).is_some_and(|(p, _)| p.eq_ignore_ascii_case(prop))
                })
                .is_some_and(|w| !std::ptr::eq(w, v))
            {
                continue;
            }
            diags.error(
                "E924",
                v.name.span,
                format!(
                    "property `{prop}` of `{}` has the name of {clash} of it",
                    fb.name
                ),
            );
        }
    }
}

impl BodyBuilder<'_> {
    /// The property `e` names, if it names one.
    fn property_use(&self, e: &Expr) -> Option<PropUse> {
        let has = |d: &dyn Fn(&str) -> bool, name: &Ident| {
            (
                d(&accessor_name(&name.key(), true)),
                d(&accessor_name(&name.key(), false)),
            )
        };
        let (base, name, owner) = match &e.kind {
            ExprKind::Name(id) => {
                if self.lookup_var(&id.key()).is_some() {
                    return None;
                }
                (None, id, Owner::Fb(self.oop.as_ref()?.fb.clone()))
            }
            ExprKind::Member(b, n) if is_this(b) || is_super(b) => (
                Some((**b).clone()),
                n,
                Owner::Fb(self.oop.as_ref()?.fb.clone()),
            ),
            ExprKind::Member(b, n) => {
                // Through a `REFERENCE TO` (or `r^`), on the instance it designates.
                let ty = self.designated(self.static_type(b)?);
                let owner = match self.interface_of(ty) {
                    Some(i) => Owner::Itf(i),
                    None => {
                        let fb = self.oop_fb_of(ty)?;
                        if let TypeKind::Pou { members, .. } = &self.types.get(ty).kind
                            && members.iter().any(|m| m.name.eq_ignore_ascii_case(&n.name))
                        {
                            return None;
                        }
                        Owner::Fb(fb)
                    }
                };
                (Some((**b).clone()), n, owner)
            }
            _ => return None,
        };
        let (get, set) = match &owner {
            Owner::Fb(fb) => {
                let d = &self.model.oop.fbs.get(fb)?.dispatch;
                has(&|k| d.contains_key(k), name)
            }
            Owner::Itf(i) => {
                let m = &self.model.oop.interfaces.get(i)?.methods;
                has(&|k| m.contains_key(k), name)
            }
        };
        (get || set).then(|| PropUse {
            base,
            name: name.clone(),
            get,
            set,
            owner,
        })
    }

    /// The call of the GET accessor of the property `e` names, if it names
    /// one that has a GET: so that a property read where storage is needed
    /// (a structure's field `itf.P.a`, a structure copied `s := itf.P;`,
    /// a method of the interface it returns `fb.ipArgs.Clear()`) goes
    /// through the paths of a method's result.
    pub(in crate::sema) fn property_get_call(&self, e: &Expr) -> Option<Call> {
        if self.model.oop.is_empty() || !matches!(e.kind, ExprKind::Name(_) | ExprKind::Member(..))
        {
            return None;
        }
        let p = self.property_use(e).filter(|p| p.get)?;
        Some(Call {
            callee: Box::new(p.callee(true)),
            args: Vec::new(),
            span: e.span,
        })
    }

    /// A property read in an expression (`None`: `e` is no property).
    pub(in crate::sema) fn property_read(&mut self, e: &Expr) -> Option<Val> {
        if self.model.oop.is_empty() || !matches!(e.kind, ExprKind::Name(_) | ExprKind::Member(..))
        {
            return None;
        }
        let p = self.property_use(e)?;
        if !p.get {
            self.diags.error(
                "E921",
                p.name.span,
                format!(
                    "property `{}` has no GET: it can be written, not read",
                    p.name.name
                ),
            );
            return Some(Val::error());
        }
        let call = Call {
            callee: Box::new(p.callee(true)),
            args: Vec::new(),
            span: e.span,
        };
        Some(self.oop_call(&call, true).unwrap_or_else(Val::error))
    }

    /// `P := value;` for a property `P` (handled here: `true`).
    pub(in crate::sema) fn property_write(&mut self, target: &Expr, value: &Expr) -> bool {
        let Some(p) = self.writable_property(target) else {
            return false;
        };
        if let Some(p) = p {
            self.call_setter(&p, value.clone(), target);
        }
        true
    }

    /// IL `ST P` for a property `P` with the current result `v` (handled
    /// here: `true`).
    pub(in crate::sema) fn property_write_val(&mut self, target: &Expr, v: &Val) -> bool {
        let Some(p) = self.writable_property(target) else {
            return false;
        };
        let Some(p) = p else { return true };
        let Some(ty) = self.setter_type(&p) else {
            return true;
        };
        let v = self.coerce(v.clone(), ty, target.span, "ST");
        if v.is_error() {
            return true;
        }
        let s = self.materialize(&v);
        // The value reaches the setter as the hidden IL current-result name.
        let saved = self.block.il_cr.replace(VarInfo {
            name: "current result".into(),
            ty,
            kind: crate::ir::type_table::MemberKind::Temp,
            storage: Storage::Frame(s.get()),
            constant: false,
            value: None,
            init: None,
            location: None,
        });
        let arg = Expr {
            kind: ExprKind::Name(Ident {
                name: crate::sema::il::CR_KEY.to_string(),
                span: target.span,
            }),
            span: target.span,
        };
        self.call_setter(&p, arg, target);
        self.block.il_cr = saved;
        true
    }

    /// `Some(Some(p))`: a property with SET; `Some(None)`: a property
    /// without (E922 given); `None`: not a property.
    fn writable_property(&mut self, target: &Expr) -> Option<Option<PropUse>> {
        if self.model.oop.is_empty()
            || !matches!(target.kind, ExprKind::Name(_) | ExprKind::Member(..))
        {
            return None;
        }
        let p = self.property_use(target)?;
        if !p.set {
            self.diags.error(
                "E922",
                p.name.span,
                format!("property `{}` has no SET: it is read-only", p.name.name),
            );
            return Some(None);
        }
        Some(Some(p))
    }

    fn call_setter(&mut self, p: &PropUse, value: Expr, target: &Expr) {
        let call = Call {
            callee: Box::new(p.callee(false)),
            args: vec![Arg::Positional(value)],
            span: target.span,
        };
        self.oop_call(&call, false);
    }

    /// The type of the value a property's SET takes.
    fn setter_type(&self, p: &PropUse) -> Option<TypeId> {
        let key = accessor_name(&p.name.key(), false);
        let model = self.model;
        match &p.owner {
            Owner::Fb(fb) => {
                let f = model.oop.fbs.get(fb)?;
                let v = &f.versions[*f.dispatch.get(&key)?];
                let hidden = &v.params.first()?.hidden;
                Some(model.pous[*model.pou_index.get(fb)?].vars.get(hidden)?.ty)
            }
            Owner::Itf(i) => {
                let itf = model.oop.interfaces.get(i)?;
                let hidden = &itf.methods.get(&key)?.params.first()?.hidden;
                let sig = *model.type_ids.get(&itf.sig_type)?;
                match &self.types.get(sig).kind {
                    TypeKind::Struct { fields } => fields
                        .iter()
                        .find(|f| f.name.eq_ignore_ascii_case(hidden))
                        .map(|f| f.ty),
                    _ => None,
                }
            }
        }
    }
}
