//! Calls: FB invocations (native and user), user function calls, EN/ENO,
//! formal and non-formal arguments, `=>` outputs.

use super::body::BodyBuilder;
use super::emit::{Place, PlaceRef, Ty, Val};
use super::model::ConstInit;
use super::refs::RefArg;
use crate::elementary::ElemType;
use crate::ir::op::{Op, Slot, Target};
use crate::ir::type_table::{MemberKind, TypeDef, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::stdlib::{self, ParamDir};
use crate::syntax::ast::{Arg, Call, Expr, ExprKind, PouKind};

/// One formal parameter of a callee.
#[derive(Debug, Clone)]
pub(super) struct Param {
    pub(super) name: String,
    pub(super) aliases: &'static [&'static str],
    pub(super) kind: MemberKind,
    pub(super) ty: TypeId,
    pub(super) offset: u32,
    pub(super) default: Option<ConstInit>,
    /// Declared CONSTANT: a `VAR_IN_OUT CONSTANT` (CODESYS) may be given
    /// a variable the caller cannot write (in_out_constant.rs).
    pub(super) constant: bool,
}

impl Param {
    /// True if `name` is this parameter (or one of its aliases).
    pub(super) fn matches(&self, name: &str) -> bool {
        self.name.eq_ignore_ascii_case(name)
            || self.aliases.iter().any(|a| a.eq_ignore_ascii_case(name))
    }
}

/// Arguments sorted by parameter after matching.
pub(super) struct Bound<'e> {
    pub(super) inputs: Vec<(usize, &'e Expr)>,
    pub(super) outputs: Vec<(usize, bool, &'e Expr)>,
    pub(super) en: Option<&'e Expr>,
    pub(super) eno: Option<&'e Expr>,
}

/// Where an FB instance being called is.
#[derive(Clone, Copy)]
enum InstanceAt {
    /// At a slot of the current frame.
    Frame(Slot),
    /// At the address held in a slot.
    Ptr(Slot),
}

impl InstanceAt {
    /// The place of the instance's member at `off`.
    fn member(self, off: u32) -> Place {
        match self {
            InstanceAt::Frame(o) => Place::Frame(o.offset(off)),
            InstanceAt::Ptr(p) => Place::Ind { p, off },
        }
    }
}

impl BodyBuilder<'_> {
    /// True when the callee is a name that is not an FB instance variable:
    /// then it names a function (a variable called `sel` does not hide the
    /// function `SEL`; a call is not a variable).
    pub(super) fn calls_a_function(&self, call: &Call) -> bool {
        let ExprKind::Name(id) = &call.callee.kind else {
            return false;
        };
        // A REFERENCE TO an FB stands for the instance it is bound to.
        self.lookup_var(&id.key()).is_none_or(|v| {
            !matches!(
                self.types.get(self.designated(v.ty)).kind,
                TypeKind::Pou { .. } | TypeKind::NativeFb(_) | TypeKind::Error
            )
        })
    }

    /// A call used as a statement.
    pub(super) fn call_stmt(&mut self, call: &Call) {
        if self.raise_exception_call(call) {
            return;
        }
        if self.oop_call(call, false).is_some() || self.this_body_call(call) {
            return;
        }
        if let Some(plain) = self.without_namespace(call) {
            return self.call_stmt(&plain);
        }
        if self.calls_a_function(call) {
            self.call_function(call, None, false);
            return;
        }
        let Some(inst) = self.place(&call.callee) else {
            return;
        };
        self.fb_call(&inst, &call.args, call.span);
    }

    /// A call used in an expression: must be a function.
    pub(super) fn call_expr(&mut self, call: &Call, expect: Option<TypeId>) -> Val {
        if let Some(v) = self
            .ref_call(call)
            .or_else(|| self.pou_name_call(call))
            .or_else(|| self.raise_exception_value(call))
            .or_else(|| self.bound_call(call))
        {
            return v;
        }
        if let Some(v) = self.oop_call(call, true) {
            return v;
        }
        if let Some(plain) = self.without_namespace(call) {
            return self.call_expr(&plain, expect);
        }
        if self.calls_a_function(call) {
            return self.call_function(call, expect, true);
        }
        if self.unknown_library_call(call) || self.through_unknown_type(&call.callee) {
            return Val::error();
        }
        self.diags.error(
            "E406",
            call.callee.span,
            "a function block instance cannot be called inside an expression; call it as a statement and read its outputs",
        );
        Val::error()
    }

    /// True when `callee` goes through a variable whose type is unknown
    /// (`fbJson.HasMember(...)` with `fbJson : FB_JsonDomParser` from a
    /// library plcrun does not have): its declaration already has E203, a
    /// second error here would only mislead.
    fn through_unknown_type(&self, callee: &Expr) -> bool {
        match &callee.kind {
            ExprKind::Member(base, _) | ExprKind::Index(base, _) | ExprKind::Deref(base) => {
                self.through_unknown_type(base)
            }
            ExprKind::Name(id) => self
                .lookup_var(&id.key())
                .is_some_and(|v| v.ty == TypeTable::error()),
            _ => false,
        }
    }

    pub(super) fn call_function(&mut self, call: &Call, expect: Option<TypeId>, want: bool) -> Val {
        let ExprKind::Name(id) = &call.callee.kind else {
            return Val::error();
        };
        let key = id.key();
        if let Some(&p) = self.model.pou_index.get(&key) {
            if self.model.pous[p].kind != PouKind::Function {
                self.diags.error(
                    "E406",
                    id.span,
                    format!(
                        "`{}` is a {}: declare an instance and call the instance",
                        id.name,
                        if self.model.pous[p].kind == PouKind::Program {
                            "PROGRAM"
                        } else {
                            "FUNCTION_BLOCK"
                        }
                    ),
                );
                return Val::error();
            }
            return self.user_function_call(p, call, want);
        }
        if let Some(v) = self.assert_call(id, call, want) {
            return v;
        }
        if let Some(v) = self.std_call(id, &call.args, call.span, expect) {
            return v;
        }
        if stdlib::lookup_native(&id.name).is_some() {
            self.diags.error(
                "E406",
                id.span,
                format!(
                    "`{}` is a function block type: declare an instance and call it",
                    id.name
                ),
            );
        } else if let Some(v) = self.lookup_var(&key) {
            let ty = self.types.name(v.ty).to_string();
            self.diags.error(
                "E406",
                id.span,
                format!(
                    "`{}` is a variable of type {ty}, not a function or a function block instance",
                    id.name
                ),
            );
        } else if matches!(key.as_str(), "__NEW" | "__DELETE") {
            self.diags.push(
                crate::diagnostics::Diagnostic::error(
                    "E435",
                    id.span,
                    format!(
                        "`{}` (CODESYS dynamic memory) is not supported: plcrun allocates every variable when the program is loaded",
                        id.name
                    ),
                )
                .with_note("declare the object as a variable (or an ARRAY of them) and use a POINTER TO or REFERENCE TO it"),
            );
        } else {
            let message = format!("unknown function `{}`", id.name);
            let names = self.model.pous.iter().map(|p| p.name.as_str());
            let names = names.chain(super::suggest::STANDARD_FUNCTIONS.iter().copied());
            let message = super::suggest::with_suggestion(message, &id.name, names);
            self.diags.error("E201", id.span, message);
        }
        Val::error()
    }

    /// Matches arguments to parameters (formal by name, or non-formal in order).
    pub(super) fn bind<'e>(
        &mut self,
        params: &[Param],
        args: &'e [Arg],
        callee: &str,
        span: Span,
    ) -> Option<Bound<'e>> {
        let mut b = Bound {
            inputs: Vec::new(),
            outputs: Vec::new(),
            en: None,
            eno: None,
        };
        let formal = args.iter().any(|a| !matches!(a, Arg::Positional(_)));
        let positional = args.iter().any(|a| matches!(a, Arg::Positional(_)));
        if formal && positional {
            let leading = self.mixed_arguments(params, args, callee, span)?;
            b.inputs = leading;
        }
        let mut ok = true;
        if positional && !formal {
            let order: Vec<usize> = params
                .iter()
                .enumerate()
                .filter(|(_, p)| matches!(p.kind, MemberKind::Input | MemberKind::InOut))
                .map(|(i, _)| i)
                .collect();
            if args.len() != order.len() {
                self.diags.error(
                    "E404",
                    span,
                    format!(
                        "`{callee}` takes {} argument(s), {} given",
                        order.len(),
                        args.len()
                    ),
                );
                return None;
            }
            for (a, &i) in args.iter().zip(&order) {
                if let Arg::Positional(e) = a {
                    b.inputs.push((i, e));
                }
            }
            return Some(b);
        }
        // The inputs given by name so far (W493 when one is named again).
        let mut by_name: Vec<usize> = Vec::new();
        for a in args {
            match a {
                Arg::Input { name, value } => {
                    // A declared `EN` parameter takes the argument
                    // (CODESYS's reading, W432); else it is the enable.
                    if name.name.eq_ignore_ascii_case("EN")
                        && !params.iter().any(|p| p.matches("EN"))
                    {
                        b.en = Some(value);
                        continue;
                    }
                    match params.iter().position(|p| p.matches(&name.name)) {
                        Some(i)
                            if matches!(params[i].kind, MemberKind::Input | MemberKind::InOut) =>
                        {
                            if b.inputs.iter().any(|(j, _)| *j == i) {
                                // Named twice (not named and by position).
                                if by_name.contains(&i)
                                    && self.model.codesys_files.contains(&name.span.file)
                                {
                                    // CODESYS takes the last value (W493).
                                    self.diags.warning(
                                        "W493",
                                        name.span,
                                        format!(
                                            "`{}` is given twice: the last value is used (a CODESYS extension)",
                                            name.name
                                        ),
                                    );
                                    b.inputs.retain(|(j, _)| *j != i);
                                } else {
                                    self.diags.error(
                                        "E404",
                                        name.span,
                                        format!("`{}` is given twice", name.name),
                                    );
                                    ok = false;
                                }
                            }
                            b.inputs.push((i, value));
                            by_name.push(i);
                        }
                        Some(_) => {
                            self.diags.error(
                                "E403",
                                name.span,
                                format!(
                                    "`{}` is an output of `{callee}`: use `{} => variable`",
                                    name.name, name.name
                                ),
                            );
                            ok = false;
                        }
                        None => {
                            if !self.pou_broken(callee) {
                                let message = format!("`{callee}` has no input `{}`", name.name);
                                let inputs = params.iter().filter(|p| p.kind != MemberKind::Output);
                                let names = inputs.map(|p| p.name.as_str());
                                let message =
                                    super::suggest::with_suggestion(message, &name.name, names);
                                self.diags.error("E403", name.span, message);
                            }
                            ok = false;
                        }
                    }
                }
                Arg::Output {
                    name,
                    negated,
                    target,
                } => {
                    if name.name.eq_ignore_ascii_case("ENO") {
                        b.eno = Some(target);
                        continue;
                    }
                    match params.iter().position(|p| p.matches(&name.name)) {
                        Some(i) if params[i].kind == MemberKind::Output => {
                            b.outputs.push((i, *negated, target));
                        }
                        _ => {
                            if !self.pou_broken(callee) {
                                let message = format!("`{callee}` has no output `{}`", name.name);
                                let outputs =
                                    params.iter().filter(|p| p.kind == MemberKind::Output);
                                let names = outputs.map(|p| p.name.as_str());
                                let message =
                                    super::suggest::with_suggestion(message, &name.name, names);
                                self.diags.error("E403", name.span, message);
                            }
                            ok = false;
                        }
                    }
                }
                Arg::Positional(_) => {}
            }
        }
        ok.then_some(b)
    }

    /// Checks and emits a call of the FB instance at `inst`.
    pub(super) fn fb_call(&mut self, inst: &PlaceRef, args: &[Arg], span: Span) {
        if self.class_instance_called(inst.ty, span) {
            return;
        }
        let def = self.types.get(inst.ty).clone();
        let Some(params) = self.fb_params(&def, span) else {
            return;
        };
        let callee = def.name.clone();
        let Some(b) = self.bind(&params, args, &callee, span) else {
            return;
        };
        for (i, p) in params.iter().enumerate() {
            if p.kind == MemberKind::InOut && !b.inputs.iter().any(|(j, _)| *j == i) {
                self.diags.error(
                    "E404",
                    span,
                    format!("VAR_IN_OUT `{}` of `{callee}` must be connected", p.name),
                );
            }
        }
        let skip = match b.en {
            Some(en) => self.cond_jump(en, false),
            None => None,
        };
        // Where the instance is: a frame slot, or an address in a slot.
        let at = match inst.place {
            Place::Frame(o) => InstanceAt::Frame(o),
            _ => InstanceAt::Ptr(self.address_of(inst)),
        };
        for &(i, e) in &b.inputs {
            let p = &params[i];
            let slot_place = PlaceRef {
                place: at.member(p.offset),
                ty: p.ty,
                writable: true,
                readonly_reason: None,
                input_image: false,
            };
            if p.kind == MemberKind::InOut {
                self.connect_in_out(p, &slot_place, e);
                continue;
            }
            self.store_arg(&slot_place, e, &p.name);
        }
        self.invoke_fb(&def.kind, at, span);
        self.block.last_def = None;
        for &(i, negated, target) in &b.outputs {
            let p = &params[i];
            let src = PlaceRef {
                place: at.member(p.offset),
                ty: p.ty,
                writable: false,
                readonly_reason: None,
                input_image: false,
            };
            self.store_output(&src, negated, target, &p.name);
        }
        let callee_eno = match &def.kind {
            TypeKind::Pou { members, .. } if skip.is_some() || b.eno.is_some() => {
                self.fb_eno(members, |off| at.member(off))
            }
            _ => None,
        };
        // An instance reached through an address (array element, VAR_IN_OUT)
        // has its address computed only on the called path: a skipped call
        // cannot reset its ENO there.
        let callee_eno = callee_eno.map(|c| PlaceRef {
            writable: c.writable && matches!(at, InstanceAt::Frame(_)),
            ..c
        });
        self.finish_en(skip, b.eno, callee_eno);
    }

    /// The call interface of an FB type (`None` for what cannot be called).
    pub(super) fn fb_params(&mut self, def: &TypeDef, span: Span) -> Option<Vec<Param>> {
        match &def.kind {
            TypeKind::NativeFb(fb) => Some(
                stdlib::interface(*fb)
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| p.dir != ParamDir::Hidden)
                    .map(|(i, p)| Param {
                        name: p.name.to_string(),
                        aliases: p.aliases,
                        kind: if p.dir == ParamDir::Input {
                            MemberKind::Input
                        } else {
                            MemberKind::Output
                        },
                        ty: TypeTable::elem(p.ty),
                        offset: i as u32,
                        default: None,
                        constant: false,
                    })
                    .collect(),
            ),
            TypeKind::Pou {
                members,
                program: false,
                ..
            } => Some(
                members
                    .iter()
                    .filter(|m| {
                        matches!(
                            m.kind,
                            MemberKind::Input | MemberKind::Output | MemberKind::InOut
                        ) && !self.is_method_in_out(&def.name, &m.name)
                    })
                    .map(|m| Param {
                        name: m.name.clone(),
                        aliases: &[],
                        kind: m.kind,
                        ty: m.ty,
                        offset: m.offset,
                        default: None,
                        constant: m.constant,
                    })
                    .collect(),
            ),
            TypeKind::Error => None,
            _ => {
                self.diags
                    .error("E406", span, format!("a {} cannot be called", def.name));
                None
            }
        }
    }

    /// Connects VAR_IN_OUT `p` of an FB instance to the variable `e`: the
    /// variable's address goes into the pointer slot `slot_place`.
    pub(super) fn connect_in_out(&mut self, p: &Param, slot_place: &PlaceRef, e: &Expr) {
        if self.is_open_array(p.ty) {
            return self.connect_open_array(p, slot_place, e);
        }
        let Some(arg) = self.in_out_place(p, e) else {
            return;
        };
        if arg.ty != p.ty && arg.ty != TypeTable::error() && !self.enum_in_out(arg.ty, p.ty, e.span)
        {
            self.mismatch(
                e.span,
                Ty::T(arg.ty),
                p.ty,
                &format!("VAR_IN_OUT `{}`", p.name),
            );
            return;
        }
        if !self.in_out_bindable(p, &arg, e.span) {
            return;
        }
        let a = self.address_of(&arg);
        let ptr_place = PlaceRef {
            ty: TypeTable::elem(ElemType::Ulint),
            ..*slot_place
        };
        self.write_place(&ptr_place, a);
    }

    /// The call instruction of an FB instance.
    fn invoke_fb(&mut self, kind: &TypeKind, at: InstanceAt, span: Span) {
        match (kind, at) {
            (TypeKind::NativeFb(fb), InstanceAt::Frame(o)) => {
                self.block.emit(Op::CallNative { fb: *fb, inst: o });
            }
            (TypeKind::NativeFb(fb), InstanceAt::Ptr(p)) => {
                self.block.emit(Op::CallNativeInd { fb: *fb, p });
            }
            (TypeKind::Pou { code, .. }, InstanceAt::Frame(o)) => {
                // A method's own block: `THIS^()` in a method is no recursion.
                let caller = self.current_code();
                self.out.calls.push((caller, *code, span));
                self.block.emit(Op::CallFb {
                    code: *code,
                    inst: o,
                });
            }
            (TypeKind::Pou { code, .. }, InstanceAt::Ptr(p)) => {
                // A method's own block: `THIS^()` in a method is no recursion.
                let caller = self.current_code();
                self.out.calls.push((caller, *code, span));
                self.block.emit(Op::CallFbInd { code: *code, p });
            }
            _ => {}
        }
    }

    /// Evaluates an input argument into a parameter place.
    pub(super) fn store_arg(&mut self, dst: &PlaceRef, e: &Expr, name: &str) {
        if let Some(class) = self.any_class(dst.ty) {
            return self.connect_any(class, dst, e, name);
        }
        if self.oop_store(dst, e) {
            return;
        }
        let what = format!("argument `{name}`");
        match self.reference_argument(dst.ty, e, &what) {
            RefArg::Value => {}
            RefArg::Bound(r) => return self.write_place(dst, r),
            RefArg::Error => return,
        }
        match self.types.get(dst.ty).kind {
            TypeKind::Array { .. } | TypeKind::Struct { .. } => {
                let Some(src) = self.place(e) else { return };
                self.copy_if_assignable(dst, &src, e.span, e.span, &what);
            }
            // An FB instance passed by value (a METHOD's `VAR_INPUT v :
            // FB_Vec3`, CODESYS): copied as by assignment.
            TypeKind::Pou { program: false, .. } => self.copy_fb(dst, e, e.span),
            _ => {
                let v = self.expr(e, Some(dst.ty));
                let v = self.coerce(v, dst.ty, e.span, &what);
                if v.is_error() {
                    return;
                }
                let s = self.materialize(&v);
                self.write_place(dst, s);
            }
        }
    }

    /// Copies an output parameter to the `=>` target.
    pub(super) fn store_output(
        &mut self,
        src: &PlaceRef,
        negated: bool,
        target: &Expr,
        name: &str,
    ) {
        let Some(t) = self.place(target) else {
            return;
        };
        if !t.writable {
            let why = t.readonly_reason.unwrap_or("it is read-only");
            self.diags.error(
                "E412",
                target.span,
                format!("output `{name}` cannot be stored here: {why}"),
            );
            return;
        }
        self.note_input_write(&t, target.span);
        // An array or structure output is copied whole, as an assignment.
        if !negated
            && matches!(
                self.types.get(src.ty).kind,
                TypeKind::Array { .. } | TypeKind::Struct { .. }
            )
        {
            let what = format!("output `{name}`");
            self.copy_if_assignable(&t, src, target.span, target.span, &what);
            return;
        }
        // An FB instance output (a METHOD's `o : FB_Vec3`) is copied
        // whole, as an instance assignment is (without its W489).
        if !negated && matches!(self.types.get(src.ty).kind, TypeKind::Pou { .. }) {
            if t.ty != src.ty {
                let what = format!("output `{name}`");
                self.mismatch(target.span, Ty::T(src.ty), t.ty, &what);
                return;
            }
            self.copy_aggregate(&t, src, target.span);
            return;
        }
        let v = self.read_place(src);
        let v = if negated {
            if src.ty != TypeTable::elem(ElemType::Bool) {
                self.diags
                    .error("E302", target.span, "`NOT ... =>` needs a BOOL output");
                return;
            }
            let s = self.materialize(&v);
            let d = self.block.temp();
            self.block.emit(Op::NotB { d, a: s });
            Val::Slot(d, src.ty)
        } else {
            v
        };
        let v = self.coerce(v, t.ty, target.span, &format!("output `{name}`"));
        if v.is_error() {
            return;
        }
        let s = self.materialize(&v);
        self.write_place(&t, s);
    }

    /// Closes an EN-guarded call: `ENO =>` gets the callee's ENO output
    /// (`callee_eno`, TRUE when it has none) on the called path and FALSE
    /// when the call was skipped; a skipped instance's own ENO (a writable
    /// `callee_eno`) is reset too.
    pub(super) fn finish_en(
        &mut self,
        skip: Option<usize>,
        eno: Option<&Expr>,
        callee_eno: Option<PlaceRef>,
    ) {
        let target = eno.and_then(|e| self.eno_target(e));
        let instance_eno = callee_eno.filter(|c| c.writable);
        if let Some(t) = &target {
            let v = match &callee_eno {
                Some(c) => {
                    let v = self.read_place(c);
                    self.materialize(&v)
                }
                None => {
                    let one = self.block.temp();
                    self.block.emit(Op::LoadI { d: one, imm: 1 });
                    one
                }
            };
            self.write_place(t, v);
        }
        let Some(j) = skip else { return };
        if target.is_none() && instance_eno.is_none() {
            let end = self.block.here();
            self.block.patch(j, end);
            return;
        }
        let over = self.block.emit(Op::Jmp {
            t: Target::UNPATCHED,
        });
        let at = self.block.here();
        self.block.patch(j, at);
        let zero = self.block.temp();
        self.block.emit(Op::LoadI { d: zero, imm: 0 });
        if let Some(c) = &instance_eno {
            self.write_place(c, zero);
        }
        if let Some(t) = &target {
            self.write_place(t, zero);
        }
        let end = self.block.here();
        self.block.patch(over, end);
    }

    /// The BOOL variable an `ENO =>` stores into (`None` after an error).
    fn eno_target(&mut self, eno: &Expr) -> Option<PlaceRef> {
        let t = self.place(eno)?;
        if t.ty != TypeTable::elem(ElemType::Bool) {
            self.mismatch(
                eno.span,
                Ty::T(t.ty),
                TypeTable::elem(ElemType::Bool),
                "ENO",
            );
            return None;
        }
        Some(t)
    }
}
