//! Interface values wherever a value goes: assigned, passed to a FUNCTION,
//! a method or an FB input, returned by a FUNCTION or a METHOD, held in
//! array elements. An interface value is two slots (instance address, type
//! id); whatever denotes one (a variable, an element, a call's result) is
//! copied as it is, an FB instance or `THIS^` is made into one, `0` is
//! the empty one. An interface may receive a value of an interface that
//! extends it (the upcast keeps the instance and its type id, which
//! dispatch through the wider interface knows); the other way is refused
//! (E940), `?=` tries it at run time (`assign_attempt.rs`).

use super::calls::{is_this, place_ref};
use crate::elementary::ElemType;
use crate::ir::op::Slot;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::sema::body::BodyBuilder;
use crate::sema::consts::Const;
use crate::sema::emit::{Place, PlaceRef, Ty, Val};
use crate::syntax::ast::{Call, Expr, ExprKind, LiteralValue, PouKind};

/// What gives an interface its value.
enum ItfSrc {
    /// An instance's address (in a slot) and its FB's type id.
    Pair(Slot, u32),
    /// An interface value stored somewhere.
    Place(PlaceRef),
}

/// The place of field `off` (0: address, 1: type id) of the interface
/// value at `p`.
pub(super) fn field(p: &PlaceRef, off: u32, ty: TypeId) -> Option<PlaceRef> {
    let at = match p.place {
        Place::Frame(o) => Place::Frame(o.offset(off)),
        Place::Abs(a) => Place::Abs(a + off),
        Place::Ind { p, off: o } => Place::Ind { p, off: o + off },
        Place::Elem { .. } | Place::View { .. } => return None,
    };
    Some(place_ref(at, ty))
}

impl BodyBuilder<'_> {
    /// `itf := value;` (handled here: `true`), and `itf ?= value;`.
    pub(in crate::sema) fn oop_assign(&mut self, target: &Expr, value: &Expr) -> bool {
        if let Some(src) = crate::syntax::assign_attempt::attempted(value) {
            self.assign_attempt(target, src);
            return true;
        }
        if self.model.oop.interfaces.is_empty() {
            return false;
        }
        let Some(itf) = self.static_type(target).and_then(|t| self.interface_of(t)) else {
            return false;
        };
        let Some(dst) = self.place(target) else {
            return true;
        };
        if !self.check_writable(&dst, target.span) {
            return true;
        }
        self.store_itf_value(&dst, &itf, value);
        true
    }

    /// An argument for an interface parameter of a method or an FB
    /// (handled here: `true`).
    pub(in crate::sema) fn oop_store(&mut self, dst: &PlaceRef, e: &Expr) -> bool {
        let Some(itf) = self.interface_of(dst.ty) else {
            return false;
        };
        self.store_itf_value(dst, &itf, e);
        true
    }

    /// The place of a value of interface `itf` denoted by `e` (a fresh
    /// pair of temporaries when `e` is an instance, `THIS^` or `0`).
    pub(in crate::sema) fn itf_place(&mut self, itf: &str, e: &Expr) -> Option<PlaceRef> {
        let ty = *self.model.type_ids.get(itf)?;
        Some(match self.itf_source(itf, e)? {
            ItfSrc::Pair(addr, tid) => self.itf_pair(addr, tid, ty),
            ItfSrc::Place(p) => p,
        })
    }

    /// Stores the value of interface `itf` denoted by `e` into `dst` (an
    /// instance's address and type id are stored straight into its fields).
    fn store_itf_value(&mut self, dst: &PlaceRef, itf: &str, e: &Expr) {
        match self.itf_source(itf, e) {
            Some(ItfSrc::Pair(addr, tid)) => {
                let (Some(a), Some(t)) = (field(dst, 0, ty_ulint()), field(dst, 1, ty_udint()))
                else {
                    return;
                };
                self.write_place(&a, addr);
                let k = self.materialize(&Val::Const(Const::Bits(tid as u64), Ty::T(ty_udint())));
                self.write_place(&t, k);
            }
            Some(ItfSrc::Place(src)) => self.copy_aggregate(dst, &src, e.span),
            None => {}
        }
    }

    /// What `e` gives an interface `itf`.
    fn itf_source(&mut self, itf: &str, e: &Expr) -> Option<ItfSrc> {
        if let ExprKind::Literal(l) = &e.kind
            && matches!(l.value, LiteralValue::Int(0))
        {
            let z = self.materialize(&Val::Const(Const::Bits(0), Ty::T(ty_ulint())));
            return Some(ItfSrc::Pair(z, 0));
        }
        if is_this(e) {
            if !self.this_allowed(e.span) {
                return None;
            }
            let fb = self.oop.as_ref()?.fb.clone();
            let tid = self.implementing_tid(e.span, &fb, itf)?;
            let this = place_ref(Place::Frame(Slot::new(0)), ty_ulint());
            let addr = self.address_of(&this);
            return Some(ItfSrc::Pair(addr, tid));
        }
        let src = self.place(e)?;
        if let Some(from) = self.interface_of(src.ty) {
            let ancestors = &self.model.oop.interfaces[&from].ancestors;
            if from == itf || ancestors.iter().any(|a| a == itf) {
                return Some(ItfSrc::Place(src));
            }
            let (to, from) = (
                self.model.oop.interfaces[itf].name.clone(),
                self.model.oop.interfaces[&from].name.clone(),
            );
            self.diags.error(
                "E940",
                e.span,
                format!(
                    "a `{from}` is not always a `{to}` (`{from}` does not extend `{to}`): use `?=` to try the assignment at run time"
                ),
            );
            return None;
        }
        let Some(fb) = self.oop_fb_of(src.ty) else {
            let found = self.types.name(src.ty).to_string();
            self.diags.error(
                "E914",
                e.span,
                format!(
                    "an interface `{}` holds an instance of an FB that implements it, not a value of type {found}",
                    self.model.oop.interfaces[itf].name
                ),
            );
            return None;
        };
        let tid = self.implementing_tid(e.span, &fb, itf)?;
        let addr = self.address_of(&src);
        Some(ItfSrc::Pair(addr, tid))
    }

    /// An interface value of type `ty` in two fresh temporaries.
    pub(super) fn itf_pair(&mut self, addr: Slot, tid: u32, ty: TypeId) -> PlaceRef {
        let region = self.block.temps(2);
        self.block.mov(region, addr);
        let t = self.materialize(&Val::Const(Const::Bits(tid as u64), Ty::T(ty_udint())));
        self.block.mov(region.offset(1), t);
        self.block.last_def = None;
        PlaceRef {
            writable: false,
            readonly_reason: Some("it is a value computed here"),
            ..place_ref(Place::Frame(region), ty)
        }
    }

    /// The address of a structured argument passed through an interface,
    /// evaluated once before the dispatch (`None` after an error).
    pub(super) fn aggregate_arg(&mut self, ty: TypeId, e: &Expr, name: &str) -> Option<Slot> {
        let src = match self.interface_of(ty) {
            Some(itf) => self.itf_place(&itf, e)?,
            None => {
                let src = self.place(e)?;
                if !self.assignable(src.ty, ty) {
                    self.mismatch(e.span, Ty::T(src.ty), ty, &format!("argument `{name}`"));
                    return None;
                }
                src
            }
        };
        let a = self.address_of(&src);
        if self.block.is_temp(a) {
            return Some(a);
        }
        let t = self.block.temp();
        self.block.mov(t, a);
        Some(t)
    }

    /// True for an array or a structure (interface values included).
    pub(super) fn is_aggregate_type(&self, ty: TypeId) -> bool {
        matches!(
            self.types.get(ty).kind,
            TypeKind::Array { .. } | TypeKind::Struct { .. }
        )
    }

    /// The result type of a call, found without emitting code: a
    /// FUNCTION's, a method's (on an instance, `THIS^` or an interface).
    pub(super) fn call_type(&self, c: &Call) -> Option<TypeId> {
        let model = self.model;
        let (fb, m) = match &c.callee.kind {
            ExprKind::Name(id) => {
                if let Some(&p) = model.pou_index.get(&id.key())
                    && model.pous[p].kind == PouKind::Function
                    && self.calls_a_function(c)
                {
                    return Some(model.pous[p].ret);
                }
                (self.oop.as_ref()?.fb.clone(), id)
            }
            ExprKind::Member(base, m) if is_this(base) => (self.oop.as_ref()?.fb.clone(), m),
            ExprKind::Member(base, m) => {
                let bt = self.designated(self.static_type(base)?);
                if let Some(itf) = self.interface_of(bt) {
                    let info = &model.oop.interfaces[&itf];
                    let im = info.methods.get(&m.key())?;
                    return self.itf_params(im, &info.sig_type).1;
                }
                (self.oop_fb_of(bt)?, m)
            }
            _ => return None,
        };
        let f = model.oop.fbs.get(&fb)?;
        let v = &f.versions[*f.dispatch.get(&m.key())?];
        let p = *model.pou_index.get(&fb)?;
        Some(model.pous[p].vars.get(v.ret.as_ref()?)?.ty)
    }
}

fn ty_ulint() -> TypeId {
    TypeTable::elem(ElemType::Ulint)
}

fn ty_udint() -> TypeId {
    TypeTable::elem(ElemType::Udint)
}
