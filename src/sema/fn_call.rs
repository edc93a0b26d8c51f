//! Calls of user FUNCTIONs: every argument is evaluated before the
//! callee's static frame is written (nested calls of the same function
//! cannot clobber it), then the inputs are stored, the function called,
//! and its result and outputs read back. Frame addresses are relative to
//! the callee's frame until the linker places it.

use super::body::BodyBuilder;
use super::calls::{Bound, Param};
use super::consts::Const;
use super::emit::{Place, PlaceRef, Ty, Val};
use super::model::{ConstInit, PouInfo, Storage};
use super::refs::RefArg;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{MemberKind, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Call, Expr, ExprKind};

/// An argument evaluated and ready to be stored in the callee's frame.
enum Ready {
    /// A scalar (or string id) in a temporary.
    Scalar(Slot),
    /// The address of a VAR_IN_OUT variable.
    Pointer(Slot),
    /// The address and type of an array or structure passed by value.
    Aggregate(Slot, crate::ir::type_table::TypeId),
    /// An `ARRAY[*]` VAR_IN_OUT's slots: the address, then the bounds;
    /// or a generic input's: type class, pointer, size (any_args.rs).
    Slots(Vec<Slot>),
}

/// The parameters of function `callee`, in interface order.
fn function_params(callee: &PouInfo) -> Vec<Param> {
    callee
        .params
        .iter()
        .filter_map(|k| callee.vars.get(k))
        .map(|v| Param {
            name: v.name.clone(),
            aliases: &[],
            kind: v.kind,
            ty: v.ty,
            offset: match v.storage {
                Storage::Frame(o) | Storage::Ref(o) => o,
                Storage::Abs(a) => a,
            },
            default: v.init.clone(),
            constant: v.constant,
        })
        .collect()
}

impl BodyBuilder<'_> {
    /// A call of user function `p`; `want` when its value is used.
    pub(super) fn user_function_call(&mut self, p: usize, call: &Call, want: bool) -> Val {
        let callee = &self.model.pous[p];
        if callee.code == crate::ir::op::CodeIdx::new(u32::MAX) {
            // Its layout waits for this very body: the function holds or
            // returns an instance of the block being emitted.
            self.diags.error(
                "E204",
                call.span,
                format!(
                    "`{}` cannot be called here: it holds or returns an instance of a function block whose own code calls it, a cycle plcrun cannot lay out",
                    callee.name
                ),
            );
            return Val::error();
        }
        if let Some(v) = self.memory_idiom(p, call, want) {
            return v;
        }
        let callee = &self.model.pous[p];
        let params = function_params(callee);
        let Some(b) = self.bind(&params, &call.args, &callee.name, call.span) else {
            return Val::error();
        };
        if want && callee.ret == TypeTable::void() {
            self.diags.error(
                "E301",
                call.span,
                format!("`{}` returns no value", callee.name),
            );
            return Val::error();
        }
        let skip = match b.en {
            Some(en) => self.cond_jump(en, false),
            None => None,
        };
        // Evaluate every argument before touching the callee's frame, so
        // nested calls of the same function cannot clobber it.
        let mut ready: Vec<(usize, Ready)> = Vec::new();
        for (i, prm) in params.iter().enumerate() {
            if !matches!(prm.kind, MemberKind::Input | MemberKind::InOut) {
                continue;
            }
            let given = b.inputs.iter().find(|(j, _)| *j == i).map(|(_, e)| *e);
            if let Some(r) = self.ready_argument(p, prm, given, call.span) {
                ready.push((i, r));
            }
        }
        for (i, r) in ready {
            self.store_argument(p, &params[i], r);
        }
        let callee = &self.model.pous[p];
        let caller = self.current_code();
        self.out.calls.push((caller, callee.code, call.span));
        self.block.emit(Op::CallFn { code: callee.code });
        let result = self.function_result(p, call.span);
        self.read_function_outputs(p, &params, &b);
        if skip.is_some() || b.eno.is_some() {
            let callee_eno = match b.eno {
                Some(_) => self.function_eno(p),
                None => None,
            };
            self.finish_en(skip, b.eno, callee_eno);
        }
        if !want {
            return Val::None(TypeTable::void());
        }
        result
    }

    /// Evaluates the argument of input or in-out `prm` of function `p`
    /// (`None` after an error).
    fn ready_argument(
        &mut self,
        p: usize,
        prm: &Param,
        given: Option<&Expr>,
        call_span: Span,
    ) -> Option<Ready> {
        let what = format!("argument `{}`", prm.name);
        match (prm.kind, given) {
            (MemberKind::InOut, Some(e)) if self.is_open_array(prm.ty) => {
                self.open_array_argument(prm, e).map(Ready::Slots)
            }
            (MemberKind::InOut, Some(e)) => {
                let arg = self.in_out_place(prm, e)?;
                if arg.ty != prm.ty {
                    self.mismatch(e.span, Ty::T(arg.ty), prm.ty, &what);
                    return None;
                }
                if !self.in_out_bindable(prm, &arg, e.span) {
                    return None;
                }
                Some(Ready::Pointer(self.address_of(&arg)))
            }
            (MemberKind::InOut, None) => {
                self.diags.error(
                    "E404",
                    call_span,
                    format!(
                        "VAR_IN_OUT `{}` of `{}` must be connected",
                        prm.name, self.model.pous[p].name
                    ),
                );
                None
            }
            (_, Some(e)) if self.any_class(prm.ty).is_some() => {
                let class = self.any_class(prm.ty)?;
                let slots = self.any_argument(class, &prm.name, e)?;
                Some(Ready::Slots(slots.to_vec()))
            }
            (_, Some(e)) if prm.ty == TypeTable::error() => {
                self.refused_parameter_argument(e);
                None
            }
            (_, Some(e)) => match self.types.get(prm.ty).kind {
                TypeKind::Array { .. }
                | TypeKind::Struct { .. }
                | TypeKind::Pou { program: false, .. }
                | TypeKind::NativeFb(_) => self.aggregate_argument(prm, e, &what),
                _ => self.scalar_argument(prm, e, &what),
            },
            (_, None) => self.default_argument(p, prm, call_span),
        }
    }

    /// The argument of a parameter whose type was refused (E203, E209):
    /// checked for its own errors only, as a variable when it names one
    /// (an FB instance is no value), else as a value.
    fn refused_parameter_argument(&mut self, e: &Expr) {
        let is_place = matches!(
            e.kind,
            ExprKind::Name(_) | ExprKind::Member(..) | ExprKind::Index(..) | ExprKind::Deref(_)
        );
        if is_place {
            self.place(e);
        } else {
            self.expr(e, None);
        }
    }

    /// An array or structure passed by value: its address (copied later).
    fn aggregate_argument(&mut self, prm: &Param, e: &Expr, what: &str) -> Option<Ready> {
        if let Some(itf) = self.interface_of(prm.ty) {
            let src = self.itf_place(&itf, e)?;
            return Some(Ready::Aggregate(self.address_of(&src), prm.ty));
        }
        let src = self.place(e)?;
        if !self.assignable(src.ty, prm.ty) {
            self.mismatch(e.span, Ty::T(src.ty), prm.ty, what);
            return None;
        }
        let a = self.address_of(&src);
        Some(Ready::Aggregate(a, prm.ty))
    }

    /// A scalar or string argument, kept in a temporary the next argument
    /// cannot overwrite (strings in a string temporary of their own).
    fn scalar_argument(&mut self, prm: &Param, e: &Expr, what: &str) -> Option<Ready> {
        match self.reference_argument(prm.ty, e, what) {
            RefArg::Value => {}
            RefArg::Bound(r) => return Some(Ready::Scalar(r)),
            RefArg::Error => return None,
        }
        let v = self.expr(e, Some(prm.ty));
        self.ready_value(prm, v, e.span, what)
    }

    /// A value already checked, converted to parameter `prm`'s type and
    /// kept in a temporary (as [`Self::scalar_argument`] keeps it).
    fn ready_value(&mut self, prm: &Param, v: Val, span: Span, what: &str) -> Option<Ready> {
        let v = self.coerce(v, prm.ty, span, what);
        if v.is_error() {
            return None;
        }
        let s = self.materialize(&v);
        let t = self.block.temp();
        if self.types.scalar(prm.ty).is_some_and(|e| e.is_string()) {
            let (max, wide) = match self.types.get(prm.ty).kind {
                TypeKind::Str { max, wide } => (max, wide),
                _ => (254, false),
            };
            let st = self.string_temp(max, wide);
            self.block.emit(Op::StrMov { d: st, s });
            self.block.emit(Op::Mov { d: t, s: st });
        } else {
            self.block.emit(Op::Mov { d: t, s });
        }
        self.block.last_def = None;
        Some(Ready::Scalar(t))
    }

    /// A call of function `p` with values already evaluated, given by
    /// parameter name (`what` names the call in messages); the other
    /// inputs take their initial values. For calls the checker builds
    /// itself (the test assertions), not for calls written in the source.
    pub(super) fn function_call_with_values(
        &mut self,
        p: usize,
        values: Vec<(&str, Val, Span)>,
        span: Span,
        want: bool,
    ) -> Val {
        let params = function_params(&self.model.pous[p]);
        let mut ready: Vec<(usize, Ready)> = Vec::new();
        for (name, v, at) in values {
            let Some(i) = params.iter().position(|prm| prm.matches(name)) else {
                return Val::error();
            };
            let what = format!("argument `{name}`");
            let Some(r) = self.ready_value(&params[i], v, at, &what) else {
                return Val::error();
            };
            ready.push((i, r));
        }
        for (i, prm) in params.iter().enumerate() {
            if prm.kind == MemberKind::Input && !ready.iter().any(|(j, _)| *j == i) {
                let r = self.default_argument(p, prm, span);
                ready.extend(r.map(|r| (i, r)));
            }
        }
        for (i, r) in ready {
            self.store_argument(p, &params[i], r);
        }
        let callee = &self.model.pous[p];
        let caller = self.current_code();
        self.out.calls.push((caller, callee.code, span));
        self.block.emit(Op::CallFn { code: callee.code });
        let result = self.function_result(p, span);
        if !want {
            return Val::None(TypeTable::void());
        }
        result
    }

    /// A missing input: its declared initial value (required for arrays
    /// and structures).
    fn default_argument(&mut self, p: usize, prm: &Param, call_span: Span) -> Option<Ready> {
        if self.any_class(prm.ty).is_some() {
            let callee = self.model.pous[p].name.clone();
            self.any_missing(&prm.name, &callee, call_span);
            return None;
        }
        let init = prm
            .default
            .clone()
            .unwrap_or_else(|| self.model.default_init(self.types, prm.ty));
        let v = match init {
            ConstInit::Scalar(bits) => Val::Const(Const::Bits(bits), Ty::T(prm.ty)),
            ConstInit::Str(s) => Val::Const(Const::Str(s), Ty::T(prm.ty)),
            _ => {
                self.diags.error(
                    "E404",
                    call_span,
                    format!(
                        "input `{}` of `{}` must be given",
                        prm.name, self.model.pous[p].name
                    ),
                );
                return None;
            }
        };
        Some(Ready::Scalar(self.materialize(&v)))
    }

    /// Stores a ready argument into function `p`'s frame (relocated later).
    fn store_argument(&mut self, p: usize, prm: &Param, r: Ready) {
        match r {
            Ready::Scalar(s) => {
                if self.types.scalar(prm.ty).is_some_and(|e| e.is_string()) {
                    let id = self.block.temp();
                    let at = self.block.emit(Op::LoadAbs {
                        d: id,
                        abs: prm.offset,
                    });
                    self.block.fixups.push((at, p));
                    self.block.emit(Op::StrMov { d: id, s });
                } else {
                    let at = self.block.emit(Op::StoreAbs { abs: prm.offset, s });
                    self.block.fixups.push((at, p));
                }
            }
            Ready::Pointer(a) => {
                let at = self.block.emit(Op::StoreAbs {
                    abs: prm.offset,
                    s: a,
                });
                self.block.fixups.push((at, p));
            }
            Ready::Slots(slots) => {
                for (k, s) in slots.into_iter().enumerate() {
                    let abs = prm.offset + k as u32;
                    let at = self.block.emit(Op::StoreAbs { abs, s });
                    self.block.fixups.push((at, p));
                }
            }
            Ready::Aggregate(a, ty) => {
                let d = self.block.temp();
                let at = self.block.emit(Op::LoadI {
                    d,
                    imm: prm.offset as i32,
                });
                self.block.fixups.push((at, p));
                self.copy_value(d, a, ty);
            }
        }
    }

    /// The result of function `p`, read from slot 0 of its frame.
    fn function_result(&mut self, p: usize, span: Span) -> Val {
        let ret = self.model.pous[p].ret;
        if ret == TypeTable::void() {
            return Val::None(TypeTable::void());
        }
        if ret == TypeTable::error() {
            // The result type was refused at the declaration.
            return Val::error();
        }
        if matches!(
            self.types.get(ret).kind,
            TypeKind::Array { .. }
                | TypeKind::Struct { .. }
                | TypeKind::Pou { program: false, .. }
                | TypeKind::NativeFb(_)
        ) {
            // An array, structure or FB instance: the address of the result in the
            // callee's frame (struct_returns.rs copies it out).
            return self.aggregate_result_address(p, ret);
        }
        let t = self.block.temp();
        let at = self.block.emit(Op::LoadAbs { d: t, abs: 0 });
        self.block.fixups.push((at, p));
        if let TypeKind::Str { max, wide } = self.types.get(ret).kind {
            let st = self.string_temp(max, wide);
            self.block.emit(Op::StrMov { d: st, s: t });
            Val::Slot(st, ret)
        } else if self.types.scalar(ret).is_some()
            || matches!(self.types.get(ret).kind, TypeKind::Ref { .. })
        {
            Val::Slot(t, ret)
        } else {
            self.diags.error(
                "E302",
                span,
                format!("a function cannot return a {}", self.types.name(ret)),
            );
            Val::error()
        }
    }

    /// The `=>` outputs of the call, read from function `p`'s frame.
    fn read_function_outputs(&mut self, p: usize, params: &[Param], b: &Bound) {
        for &(i, negated, target) in &b.outputs {
            let prm = &params[i];
            // An array or structure is read where it lies in the callee's
            // frame (its address); a scalar is loaded.
            let aggregate = matches!(
                self.types.get(prm.ty).kind,
                TypeKind::Array { .. } | TypeKind::Struct { .. }
            );
            let place = if aggregate {
                let p = self.callee_frame_address(p, prm.offset);
                Place::Ind { p, off: 0 }
            } else {
                let t = self.block.temp();
                let at = self.block.emit(Op::LoadAbs {
                    d: t,
                    abs: prm.offset,
                });
                self.block.fixups.push((at, p));
                Place::Frame(t)
            };
            let src = PlaceRef {
                place,
                ty: prm.ty,
                writable: false,
                readonly_reason: None,
                input_image: false,
            };
            self.store_output(&src, negated, target, &prm.name);
        }
    }
}
