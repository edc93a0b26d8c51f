//! Method calls (`inst.M(...)`, `M(...)`, `THIS^.M(...)`, `SUPER^.M(...)`,
//! `SUPER^()`), calls through interfaces, and interface values: assignment
//! of an instance, `itf = 0` / `itf <> 0`.

use super::model::{BODY, FbOop, ParamSig, Version};
use crate::elementary::ElemType;
use crate::ir::op::{Cmp, CodeIdx, Op, Slot, Target};
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, TypeTable};
use crate::sema::body::BodyBuilder;
use crate::sema::calls::{Bound, Param};
use crate::sema::consts::Const;
use crate::sema::emit::{Place, PlaceRef, Ty, Val};
use crate::sema::model::{ConstInit, Storage};
use crate::source::Span;
use crate::syntax::ast::{Arg, BinaryOp, Call, Expr, ExprKind, Ident, LiteralValue};
use crate::syntax::oop::{Access, SUPER, THIS};

/// Offsets of hidden variables not known while a caller is emitted (the
/// implementing FB may be laid out later): `LoadInd`/`StoreInd` carry
/// `OFFSET_MARK | k`, `k` indexing [`crate::sema::program::Program`]'s
/// `oop_offsets`, and the linker puts the real offset in.
pub(crate) const OFFSET_MARK: u32 = 0x8000_0000;

/// Where the instance a method runs on is.
#[derive(Clone, Copy)]
enum Inst {
    /// At a slot of the current frame (slot 0: `THIS^`).
    Frame(Slot),
    /// At the address held in a slot.
    Ptr(Slot),
}

impl Inst {
    fn member(self, off: u32) -> Place {
        match self {
            Inst::Frame(o) => Place::Frame(o.offset(off)),
            Inst::Ptr(p) => Place::Ind { p, off },
        }
    }
}

/// True for the `THIS^` root.
pub(crate) fn is_this(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Name(id) if id.name == THIS)
}

pub(crate) fn is_super(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Name(id) if id.name == SUPER)
}

/// How a method parameter is passed.
fn param_kind(s: &ParamSig) -> MemberKind {
    match (s.in_out, s.input) {
        (true, _) => MemberKind::InOut,
        (false, true) => MemberKind::Input,
        (false, false) => MemberKind::Output,
    }
}

pub(super) fn place_ref(place: Place, ty: TypeId) -> PlaceRef {
    PlaceRef {
        place,
        ty,
        writable: true,
        readonly_reason: None,
        input_image: false,
    }
}

impl BodyBuilder<'_> {
    /// The FB being emitted, if it has methods.
    pub(super) fn this_fb(&self) -> Option<&FbOop> {
        self.model.oop.fbs.get(&self.oop.as_ref()?.fb)
    }

    /// The code block being emitted (for the call graph).
    pub(in crate::sema) fn current_code(&self) -> CodeIdx {
        match &self.oop {
            Some(s) => s.code,
            None => self.model.pous[self.block.pou].code,
        }
    }

    /// The static type of a variable path, found without emitting code.
    pub(in crate::sema) fn static_type(&self, e: &Expr) -> Option<TypeId> {
        match &e.kind {
            ExprKind::Name(id) => self.lookup_var(&id.key()).map(|v| v.ty),
            ExprKind::Paren(x) => self.static_type(x),
            ExprKind::Deref(x) => match self.types.get(self.static_type(x)?).kind {
                TypeKind::Ref { target, .. } => Some(target),
                _ => None,
            },
            ExprKind::Member(b, n) => {
                if is_this(b) || self.is_list_qualifier(b, n) {
                    // `THIS^.x`, or `GVL.x`: a global named with its list.
                    return self.lookup_var(&n.key()).map(|v| v.ty);
                }
                let t = self.designated(self.static_type(b)?);
                match &self.types.get(t).kind {
                    TypeKind::Pou { members, .. } => members
                        .iter()
                        .find(|m| m.name.eq_ignore_ascii_case(&n.name))
                        .map(|m| m.ty),
                    TypeKind::Struct { fields } => fields
                        .iter()
                        .find(|m| m.name.eq_ignore_ascii_case(&n.name))
                        .map(|m| m.ty),
                    _ => None,
                }
                .or_else(|| self.call_type(&self.property_get_call(e)?))
            }
            ExprKind::Index(b, _) => {
                match &self.types.get(self.designated(self.static_type(b)?)).kind {
                    TypeKind::Array { elem, .. } => Some(*elem),
                    _ => None,
                }
            }
            ExprKind::Call(c) => self.call_type(c),
            _ => None,
        }
    }

    /// The interface (key) a type is, if it is an interface's value type.
    pub(in crate::sema) fn interface_of(&self, ty: TypeId) -> Option<String> {
        if self.model.oop.interfaces.is_empty() {
            return None;
        }
        let key = self.types.get(ty).name.to_ascii_uppercase();
        (self.model.oop.interfaces.contains_key(&key) && self.model.type_ids.get(&key) == Some(&ty))
            .then_some(key)
    }

    /// The OOP FB (key) a type is an instance of.
    pub(super) fn oop_fb_of(&self, ty: TypeId) -> Option<String> {
        if !matches!(
            self.types.get(ty).kind,
            TypeKind::Pou { program: false, .. }
        ) {
            return None;
        }
        let key = self.types.get(ty).name.to_ascii_uppercase();
        self.model.oop.fbs.contains_key(&key).then_some(key)
    }

    /// A method call or a call through an interface; `None` when `call` is
    /// neither (the ordinary call paths take it).
    pub(in crate::sema) fn oop_call(&mut self, call: &Call, want: bool) -> Option<Val> {
        if self.model.oop.is_empty() {
            return None;
        }
        match &call.callee.kind {
            ExprKind::Name(id) if id.name == SUPER => Some(self.super_call(None, call, want)),
            ExprKind::Name(id) => {
                let vi = *self.this_fb()?.dispatch.get(&id.key())?;
                let fb = self.oop.as_ref()?.fb.clone();
                Some(self.method_call(&fb, vi, Inst::Frame(Slot::new(0)), true, call, want))
            }
            ExprKind::Member(base, m) if is_super(base) => {
                Some(self.super_call(Some(m), call, want))
            }
            ExprKind::Member(base, m) if is_this(base) => {
                let Some(fb) = self.oop.as_ref().map(|s| s.fb.clone()) else {
                    self.diags.error(
                        "E918",
                        base.span,
                        "`THIS^` can only be used in a FUNCTION_BLOCK",
                    );
                    return Some(Val::error());
                };
                let Some(&vi) = self.model.oop.fbs[&fb].dispatch.get(&m.key()) else {
                    // `THIS^.tmr(...)`: an FB instance of the block, which
                    // the ordinary call path calls.
                    let own = self
                        .model
                        .pou_index
                        .get(&fb)
                        .map(|&p| self.model.pous[p].ty);
                    if own.is_some_and(|ty| self.has_member(ty, m)) {
                        return None;
                    }
                    self.unknown_method(&fb, m);
                    return Some(Val::error());
                };
                Some(self.method_call(&fb, vi, Inst::Frame(Slot::new(0)), true, call, want))
            }
            ExprKind::Member(base, m) => {
                // Through a `REFERENCE TO` (or `r^`), on the instance it designates.
                let ty = self.designated(self.static_type(base)?);
                if let Some(itf) = self.interface_of(ty) {
                    return Some(self.itf_call(&itf, base, m, call, want));
                }
                let fb = self.oop_fb_of(ty)?;
                let Some(&vi) = self.model.oop.fbs[&fb].dispatch.get(&m.key()) else {
                    if self.has_member(ty, m) {
                        return None;
                    }
                    self.unknown_method(&fb, m);
                    return Some(Val::error());
                };
                let inst = self.place(base)?;
                let at = match inst.place {
                    Place::Frame(o) => Inst::Frame(o),
                    _ => Inst::Ptr(self.address_of(&inst)),
                };
                Some(self.method_call(&fb, vi, at, false, call, want))
            }
            _ => None,
        }
    }

    /// Whether the POU type `ty` has a variable named `m`.
    fn has_member(&self, ty: TypeId, m: &Ident) -> bool {
        matches!(&self.types.get(ty).kind,
            TypeKind::Pou { members, .. } if members.iter().any(|x| x.name.eq_ignore_ascii_case(&m.name)))
    }

    fn unknown_method(&mut self, fb: &str, m: &Ident) {
        let name = self.model.oop.fbs[fb].name.clone();
        self.diags.error(
            "E900",
            m.span,
            format!("`{name}` has no method `{}`", m.name),
        );
    }

    /// `SUPER^.M(...)` (`m` given) or `SUPER^()`: the version of the nearest
    /// ancestor of the code's origin.
    fn super_call(&mut self, m: Option<&Ident>, call: &Call, want: bool) -> Val {
        let Some(scope) = self.oop.clone() else {
            self.diags.error(
                "E918",
                call.callee.span,
                "`SUPER^` can only be used in a FUNCTION_BLOCK that EXTENDS another",
            );
            return Val::error();
        };
        let model = self.model;
        let fbs = &model.oop.fbs;
        let key = m.map_or(BODY.to_string(), |m| m.key());
        let mut at = fbs.get(&scope.origin).and_then(|f| f.parent.clone());
        let mut found = None;
        let mut steps = 0;
        while let Some(a) = at {
            if let Some(vi) = fbs[&scope.fb].version_of(&a, &key) {
                found = Some(vi);
                break;
            }
            steps += 1;
            if steps > fbs.len() {
                break;
            }
            at = fbs.get(&a).and_then(|f| f.parent.clone());
        }
        let Some(vi) = found else {
            let what = match m {
                Some(m) => format!("no parent of this FB has a method `{}`", m.name),
                None => "no parent of this FB has a body to call".to_string(),
            };
            self.diags
                .error("E912", call.callee.span, format!("`SUPER^`: {what}"));
            return Val::error();
        };
        if fbs[&scope.fb].versions[vi].mods.is_abstract {
            self.diags.error(
                "E907",
                call.callee.span,
                "this method is ABSTRACT in the parent: it has no implementation to call",
            );
            return Val::error();
        }
        self.method_call(&scope.fb, vi, Inst::Frame(Slot::new(0)), true, call, want)
    }

    /// E913: a PRIVATE or PROTECTED method called from where it is hidden.
    fn check_access(&mut self, v: &Version, on_this: bool, span: Span) {
        let origin = self.oop.as_ref().map(|s| s.origin.clone());
        let allowed = match v.mods.access() {
            Access::Public | Access::Internal => true,
            Access::Private => on_this && origin.as_deref() == Some(v.origin.as_str()),
            // Code of the FB's hierarchy calling on its own instance.
            Access::Protected => on_this,
        };
        if !allowed {
            let which = match v.mods.access() {
                Access::Private => "PRIVATE: only its own FB's code may call it",
                _ => "PROTECTED: only its FB and the FBs that extend it may call it, on THIS^",
            };
            self.diags
                .error("E913", span, format!("method `{}` is {which}", v.name.name));
        }
    }

    /// The parameters of version `v` of FB `fb` (pou `p`) as call parameters.
    fn version_params(&self, p: usize, params: &[ParamSig]) -> Vec<Param> {
        let vars = &self.model.pous[p].vars;
        params
            .iter()
            .filter_map(|s| {
                let var = vars.get(&s.hidden)?;
                let (Storage::Frame(o) | Storage::Ref(o)) = var.storage else {
                    return None;
                };
                Some(Param {
                    name: s.name.clone(),
                    aliases: &[],
                    kind: param_kind(s),
                    ty: var.ty,
                    offset: o,
                    default: var.init.clone(),
                    constant: var.constant,
                })
            })
            .collect()
    }

    /// A call of version `vi` of FB `fb` on the instance at `at`.
    fn method_call(
        &mut self,
        fb: &str,
        vi: usize,
        at: Inst,
        on_this: bool,
        call: &Call,
        want: bool,
    ) -> Val {
        let model = self.model;
        let f = &model.oop.fbs[fb];
        let v = &f.versions[vi];
        let code = f.codes[vi];
        self.check_access(v, on_this, call.callee.span);
        let Some(&p) = model.pou_index.get(fb) else {
            return Val::error();
        };
        let mut params = self.version_params(p, &v.params);
        // An action or `SUPER^()` has no parameters of its own: CODESYS
        // binds the arguments of such a call to the FB's own inputs and
        // outputs (`fb.A_Add(key := k, bOk => ok)`), the others keeping
        // their values as in a call of the instance.
        let fb_own = params.is_empty() && !call.args.is_empty();
        if fb_own {
            let def = self.types.get(model.pous[p].ty).clone();
            params = self.fb_params(&def, call.span).unwrap_or_default();
        }
        let Some(b) = self.bind(&params, &call.args, &v.name.name, call.span) else {
            return Val::error();
        };
        self.no_en(&b, call.span);
        for (i, prm) in params.iter().enumerate() {
            if prm.kind == MemberKind::Output {
                continue;
            }
            let dst = place_ref(at.member(prm.offset), prm.ty);
            match b.inputs.iter().find(|(j, _)| *j == i) {
                Some((_, e)) if prm.kind == MemberKind::InOut => self.connect_in_out(prm, &dst, e),
                Some((_, e)) => self.store_arg(&dst, e, &prm.name),
                None if fb_own => {}
                None if prm.kind == MemberKind::InOut => self.unconnected(prm, &v.name, call.span),
                None if self.any_class(prm.ty).is_some() => {
                    self.any_missing(&prm.name, &v.name.name, call.span)
                }
                None => self.store_default(&dst, prm.default.as_ref()),
            }
        }
        match at {
            Inst::Frame(o) => self.block.emit(Op::CallFb { code, inst: o }),
            Inst::Ptr(ptr) => self.block.emit(Op::CallFbInd { code, p: ptr }),
        };
        let caller = self.current_code();
        self.out.calls.push((caller, code, call.span));
        if matches!(at, Inst::Frame(o) if o.index() == 0) {
            self.out.own_instance_calls.insert((caller, code));
        }
        self.block.last_def = None;
        for &(i, negated, target) in &b.outputs {
            let src = place_ref(at.member(params[i].offset), params[i].ty);
            self.store_output(&src, negated, target, &params[i].name);
        }
        let ret = v.ret.as_ref().and_then(|k| model.pous[p].vars.get(k));
        self.method_result(ret.map(|r| (r.storage, r.ty)), at, want, &v.name, call.span)
    }

    /// EN/ENO are not parameters of methods.
    fn no_en(&mut self, b: &Bound, span: Span) {
        if b.en.is_some() || b.eno.is_some() {
            self.diags
                .error("E403", span, "methods have no EN/ENO parameters");
        }
    }

    /// A method's result copied out of the instance (a later call of the
    /// same method must not change a value already computed).
    fn method_result(
        &mut self,
        ret: Option<(Storage, TypeId)>,
        at: Inst,
        want: bool,
        name: &Ident,
        span: Span,
    ) -> Val {
        if !want {
            return Val::None(TypeTable::void());
        }
        let Some((Storage::Frame(o), ty)) = ret else {
            self.diags.error(
                "E919",
                span,
                format!(
                    "method `{}` has no result: call it as a statement",
                    name.name
                ),
            );
            return Val::error();
        };
        self.copy_result(&place_ref(at.member(o), ty))
    }

    fn copy_result(&mut self, src: &PlaceRef) -> Val {
        if self.is_aggregate_type(src.ty) {
            // Like a function's: the address, copied out by `call_place`.
            return Val::Slot(self.address_of(src), src.ty);
        }
        let Val::Slot(s, ty) = self.read_place(src) else {
            return Val::error();
        };
        match self.types.get(ty).kind.clone() {
            TypeKind::Str { max, wide } => {
                let t = self.string_temp(max, wide);
                self.block.emit(Op::StrMov { d: t, s });
                Val::Slot(t, ty)
            }
            _ => {
                let t = self.block.temp();
                self.block.mov(t, s);
                Val::Slot(t, ty)
            }
        }
    }

    /// Stores an input's declared initial value (an input not given).
    fn store_default(&mut self, dst: &PlaceRef, init: Option<&ConstInit>) {
        let init = match init {
            Some(i) => i.clone(),
            None => self.model.default_init(self.types, dst.ty),
        };
        let v = match init {
            ConstInit::Scalar(bits) => Val::Const(Const::Bits(bits), Ty::T(dst.ty)),
            ConstInit::Str(s) => Val::Const(Const::Str(s), Ty::T(dst.ty)),
            // Structured inputs not given keep their last value.
            _ => return,
        };
        let s = self.materialize(&v);
        self.write_place(dst, s);
    }

    /// The place of hidden variable `key` of pou `p` at an instance reached
    /// through a pointer, its offset filled in at link time.
    fn late_member(&mut self, ptr: Slot, p: usize, key: &str, ty: TypeId) -> PlaceRef {
        let k = self.out.oop_offsets.len() as u32;
        self.out.oop_offsets.push((p, key.to_string()));
        place_ref(
            Place::Ind {
                p: ptr,
                off: OFFSET_MARK | k,
            },
            ty,
        )
    }

    /// `itf.M(...)`: compares the value's type id with each implementing
    /// FB's and calls that FB's version; fault R080 when none matches.
    fn itf_call(&mut self, itf: &str, base: &Expr, m: &Ident, call: &Call, want: bool) -> Val {
        let model = self.model;
        let info = &model.oop.interfaces[itf];
        let Some(im) = info.methods.get(&m.key()) else {
            self.diags.error(
                "E900",
                m.span,
                format!("interface `{}` has no method `{}`", info.name, m.name),
            );
            return Val::error();
        };
        let (params, ret_ty) = self.itf_params(im, &info.sig_type);
        let Some(b) = self.bind(&params, &call.args, &m.name, call.span) else {
            return Val::error();
        };
        self.no_en(&b, call.span);
        // Arguments first, once, in order.
        let mut args: Vec<Option<Slot>> = vec![None; params.len()];
        for (i, prm) in params.iter().enumerate() {
            if b.inputs.iter().any(|(j, _)| *j == i) {
                continue;
            }
            if prm.kind == MemberKind::InOut {
                self.unconnected(prm, m, call.span);
                return Val::error();
            }
            if self.any_class(prm.ty).is_some() {
                self.any_missing(&prm.name, &m.name, call.span);
                return Val::error();
            }
        }
        for &(i, e) in &b.inputs {
            let ty = params[i].ty;
            if let Some(class) = self.any_class(ty) {
                let Some(a) = self.any_block(class, ty, &params[i].name, e) else {
                    return Val::error();
                };
                args[i] = Some(a);
                continue;
            }
            if params[i].kind == MemberKind::InOut {
                let Some(a) = self.in_out_address(&params[i], e) else {
                    return Val::error();
                };
                args[i] = Some(a);
                continue;
            }
            if self.is_aggregate_type(ty) {
                let Some(a) = self.aggregate_arg(ty, e, &params[i].name) else {
                    return Val::error();
                };
                args[i] = Some(a);
                continue;
            }
            let v = self.expr(e, Some(ty));
            let v = self.coerce(v, ty, e.span, &format!("argument `{}`", params[i].name));
            if v.is_error() {
                return Val::error();
            }
            args[i] = Some(self.materialize(&v));
        }
        let Some(value) = self.place(base) else {
            return Val::error();
        };
        let udint = TypeTable::elem(ElemType::Udint);
        let ulint = TypeTable::elem(ElemType::Ulint);
        let member = |off: u32| match value.place {
            Place::Frame(o) => Some(Place::Frame(o.offset(off))),
            Place::Abs(a) => Some(Place::Abs(a + off)),
            Place::Ind { p, off: o } => Some(Place::Ind { p, off: o + off }),
            Place::Elem { .. } | Place::View { .. } => None,
        };
        let (Some(addr_at), Some(tid_at)) = (member(0), member(1)) else {
            self.diags.error(
                "E915",
                base.span,
                "calling a method through an element of an array of interfaces is not supported by plcrun: copy the element to an interface variable first",
            );
            return Val::error();
        };
        let Val::Slot(addr, _) = self.read_place(&place_ref(addr_at, ulint)) else {
            return Val::error();
        };
        let addr = self.keep(addr);
        let Val::Slot(tid, _) = self.read_place(&place_ref(tid_at, udint)) else {
            return Val::error();
        };
        let tid = self.keep(tid);
        let result = match (want, ret_ty) {
            (false, _) => None,
            (true, None) => {
                self.diags.error(
                    "E919",
                    call.span,
                    format!("method `{}` has no result: call it as a statement", m.name),
                );
                return Val::error();
            }
            (true, Some(t)) => Some((self.result_slot(t), t)),
        };
        let mut impls: Vec<(&String, &FbOop)> = model
            .oop
            .fbs
            .iter()
            .filter(|(_, f)| !f.is_abstract && f.interfaces.iter().any(|i| i == itf))
            .collect();
        impls.sort_by_key(|(_, f)| f.tid);
        let mut ends = Vec::new();
        for (key, f) in impls {
            let Some(&vi) = f.dispatch.get(&m.key()) else {
                continue;
            };
            let Some(&p) = model.pou_index.get(key) else {
                continue;
            };
            let v = &f.versions[vi];
            let next = self.block.emit(Op::JnCmpSI {
                a: tid,
                imm: f.tid as i32,
                cmp: Cmp::Eq,
                t: Target::UNPATCHED,
            });
            let code = f.codes[vi];
            if !self.itf_branch(p, v, code, (&params, &args, &b), addr, result, call.span) {
                return Val::error();
            }
            ends.push(self.block.emit(Op::Jmp {
                t: Target::UNPATCHED,
            }));
            let here = self.block.here();
            self.block.patch(next, here);
        }
        self.block.emit(Op::FaultNullItf);
        let end = self.block.here();
        for j in ends {
            self.block.patch(j, end);
        }
        self.block.last_def = None;
        match result {
            Some((r, ty)) => Val::Slot(r, ty),
            None => Val::None(TypeTable::void()),
        }
    }

    /// A slot that a later instruction cannot retarget (a frame slot of a
    /// variable is copied: the call may change it).
    fn keep(&mut self, s: Slot) -> Slot {
        if self.block.is_temp(s) {
            return s;
        }
        let t = self.block.temp();
        self.block.mov(t, s);
        t
    }

    fn result_slot(&mut self, ty: TypeId) -> Slot {
        match self.types.get(ty).kind.clone() {
            TypeKind::Str { max, wide } => self.string_temp(max, wide),
            _ => self.block.temp(),
        }
    }

    fn set_result(&mut self, r: Slot, s: Slot, ty: TypeId) {
        if matches!(self.types.get(ty).kind, TypeKind::Str { .. }) {
            self.block.emit(Op::StrMov { d: r, s });
        } else {
            self.block.mov(r, s);
        }
    }

    /// The type id of FB `fb` stored with it in interface `itf`; E914 at
    /// `span` when `fb` does not implement `itf`.
    pub(super) fn implementing_tid(&mut self, span: Span, fb: &str, itf: &str) -> Option<u32> {
        let f = &self.model.oop.fbs[fb];
        if f.interfaces.iter().any(|i| i == itf) {
            return Some(f.tid);
        }
        let (fb_name, name) = (f.name.clone(), self.model.oop.interfaces[itf].name.clone());
        self.diags.error(
            "E914",
            span,
            format!("`{fb_name}` does not implement `{name}`: it cannot be assigned to it"),
        );
        None
    }

    /// `itf = 0`, `itf <> 0`, `itf1 = itf2` (the same instance).
    pub(in crate::sema) fn oop_compare(
        &mut self,
        op: BinaryOp,
        a: &Expr,
        b: &Expr,
        span: Span,
    ) -> Option<Val> {
        if self.model.oop.interfaces.is_empty() || !matches!(op, BinaryOp::Eq | BinaryOp::Ne) {
            return None;
        }
        let ia = self.static_type(a).and_then(|t| self.interface_of(t));
        let ib = self.static_type(b).and_then(|t| self.interface_of(t));
        if ia.is_none() && ib.is_none() {
            return None;
        }
        // Against 0 the type id tells (an instance may sit at address 0);
        // two interfaces are the same instance when their addresses are.
        let both = ia.is_some() && ib.is_some();
        let (field, ty) = if both {
            (0, TypeTable::elem(ElemType::Ulint))
        } else {
            (1, TypeTable::elem(ElemType::Udint))
        };
        let mut side = |e: &Expr, is_itf: bool| -> Option<Val> {
            if is_itf {
                let p = self.place(e)?;
                let at = match p.place {
                    Place::Frame(o) => Place::Frame(o.offset(field)),
                    Place::Abs(x) => Place::Abs(x + field),
                    Place::Ind { p, off } => Place::Ind {
                        p,
                        off: off + field,
                    },
                    Place::Elem { .. } | Place::View { .. } => return None,
                };
                return Some(self.read_place(&place_ref(at, ty)));
            }
            match &e.kind {
                ExprKind::Literal(l) if matches!(l.value, LiteralValue::Int(0)) => {
                    Some(Val::Const(Const::Bits(0), Ty::T(ty)))
                }
                _ => {
                    self.diags.error(
                        "E920",
                        e.span,
                        "an interface compares only with `0` (no instance) or with another interface",
                    );
                    None
                }
            }
        };
        let va = side(a, ia.is_some());
        let vb = side(b, ib.is_some());
        match (va, vb) {
            (Some(x), Some(y)) => Some(self.binary_vals(op, x, y, span)),
            _ => Some(Val::error()),
        }
    }
}

impl BodyBuilder<'_> {
    /// `CAL inst.M(...)` in IL (handled here: `true`).
    pub(in crate::sema) fn oop_il_call(
        &mut self,
        instance: &Expr,
        args: &[Arg],
        span: Span,
    ) -> bool {
        if self.model.oop.is_empty() {
            return false;
        }
        let call = Call {
            callee: Box::new(instance.clone()),
            args: args.to_vec(),
            span,
        };
        self.oop_call(&call, false).is_some()
    }
}

impl BodyBuilder<'_> {
    /// `THIS^` is allowed in the code of a FUNCTION_BLOCK only (E918).
    pub(in crate::sema) fn this_allowed(&mut self, span: Span) -> bool {
        let in_fb = self
            .model
            .pous
            .get(self.block.pou)
            .is_some_and(|p| p.kind == crate::syntax::ast::PouKind::FunctionBlock);
        if !in_fb {
            self.diags
                .error("E918", span, "`THIS^` can only be used in a FUNCTION_BLOCK");
        }
        in_fb
    }

    /// E918 unless the code is a FUNCTION_BLOCK's that EXTENDS another
    /// (where `SUPER^.x` names the instance's inherited `x`).
    pub(in crate::sema) fn super_allowed(&mut self, span: Span) -> bool {
        let derived = self.oop.as_ref().is_some_and(|scope| {
            (self.model.oop.fbs.get(&scope.origin)).is_some_and(|f| f.parent.is_some())
        });
        if !derived {
            self.diags.error(
                "E918",
                span,
                "`SUPER^` can only be used in a FUNCTION_BLOCK that EXTENDS another",
            );
        }
        derived
    }
}

impl BodyBuilder<'_> {
    /// The parameters of an interface method, typed by the interface's
    /// signature structure, and its result type.
    pub(super) fn itf_params(
        &self,
        im: &super::model::ItfMethod,
        sig_type: &str,
    ) -> (Vec<Param>, Option<TypeId>) {
        let model = self.model;
        let info_sig_type = sig_type;
        let sig_ty = model.type_ids.get(info_sig_type).copied();
        let field_ty = |types: &TypeTable, key: &str| -> Option<(TypeId, u32)> {
            match &types.get(sig_ty?).kind {
                TypeKind::Struct { fields } => fields
                    .iter()
                    .find(|f| f.name.eq_ignore_ascii_case(key))
                    .map(|f| (f.ty, f.offset)),
                _ => None,
            }
        };
        let params: Vec<Param> = im
            .params
            .iter()
            .filter_map(|s| {
                let (ty, _) = field_ty(self.types, &s.hidden)?;
                Some(Param {
                    name: s.name.clone(),
                    aliases: &[],
                    kind: param_kind(s),
                    ty,
                    offset: 0,
                    default: None,
                    constant: false,
                })
            })
            .collect();
        let ret_ty = im
            .ret
            .as_ref()
            .and_then(|r| field_ty(self.types, r))
            .map(|x| x.0);
        (params, ret_ty)
    }

    /// One implementing FB's branch of an interface call: the arguments
    /// stored into its version's inputs, the call, the outputs and the
    /// result copied out (`false` after an error).
    #[allow(clippy::too_many_arguments)]
    fn itf_branch(
        &mut self,
        p: usize,
        v: &Version,
        code: CodeIdx,
        (params, args, b): (&[Param], &[Option<Slot>], &Bound),
        addr: Slot,
        result: Option<(Slot, TypeId)>,
        span: Span,
    ) -> bool {
        let model = self.model;
        let caller = self.current_code();
        for (i, prm) in params.iter().enumerate() {
            let Some(hidden) = v
                .params
                .iter()
                .find(|s| s.name.eq_ignore_ascii_case(&prm.name))
            else {
                continue;
            };
            if !hidden.input {
                continue;
            }
            let dst = self.late_member(addr, p, &hidden.hidden, prm.ty);
            match args[i] {
                Some(s) if prm.kind == MemberKind::InOut => {
                    let ptr = PlaceRef {
                        ty: TypeTable::elem(ElemType::Ulint),
                        ..dst
                    };
                    self.write_place(&ptr, s);
                }
                Some(s) if self.is_aggregate_type(prm.ty) => {
                    let d = self.address_of(&dst);
                    self.copy_value(d, s, prm.ty);
                }
                Some(s) => self.write_place(&dst, s),
                None => {
                    let init = model.pous[p]
                        .vars
                        .get(&hidden.hidden)
                        .and_then(|x| x.init.clone());
                    self.store_default(&dst, init.as_ref());
                }
            }
        }
        self.block.emit(Op::CallFbInd { code, p: addr });
        self.out.calls.push((caller, code, span));
        self.block.last_def = None;
        for &(i, negated, target) in &b.outputs {
            let Some(hidden) = v
                .params
                .iter()
                .find(|s| s.name.eq_ignore_ascii_case(&params[i].name))
            else {
                continue;
            };
            let src = self.late_member(addr, p, &hidden.hidden, params[i].ty);
            self.store_output(&src, negated, target, &params[i].name);
        }
        if let (Some((r, ty)), Some(rk)) = (result, &v.ret) {
            let src = self.late_member(addr, p, rk, ty);
            if self.is_aggregate_type(ty) {
                // The result's address, copied out by `call_place`.
                let a = self.address_of(&src);
                self.block.mov(r, a);
                return true;
            }
            let Val::Slot(s, _) = self.read_place(&src) else {
                return false;
            };
            self.set_result(r, s, ty);
        }
        true
    }
}
