//! Instruction List lowering. The current result (CR) lives in a frame
//! slot whose type the checker tracks instruction by instruction; deferred
//! operations `OP(` save CR in their own slot; jumps and labels become IR
//! jumps. IL therefore runs on the same executor as ST.

use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use super::model::{Storage, VarInfo};
use crate::elementary::ElemType;
use crate::ir::op::{Op, Slot, Target};
use crate::ir::type_table::{MemberKind, TypeId, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{
    Arg, BinaryOp, Call, Expr, ExprKind, Ident, IlInstr, IlInstrKind, IlLine, IlOperator,
    IlOutputCopy,
};
use std::collections::HashMap;

/// Name under which the CR slot is visible to the expression checker.
pub(super) const CR_KEY: &str = "\u{0}CR";

/// A pending deferred operation.
struct Deferred {
    op: IlOperator,
    negate: bool,
    saved: Slot,
    saved_ty: Option<TypeId>,
    /// The saved CR when it was an untyped literal.
    saved_lit: Option<Val>,
    span: Span,
}

fn binary_of(op: IlOperator) -> Option<BinaryOp> {
    Some(match op {
        IlOperator::And => BinaryOp::And,
        IlOperator::Or => BinaryOp::Or,
        IlOperator::Xor => BinaryOp::Xor,
        IlOperator::Add => BinaryOp::Add,
        IlOperator::Sub => BinaryOp::Sub,
        IlOperator::Mul => BinaryOp::Mul,
        IlOperator::Div => BinaryOp::Div,
        IlOperator::Mod => BinaryOp::Mod,
        IlOperator::Gt => BinaryOp::Gt,
        IlOperator::Ge => BinaryOp::Ge,
        IlOperator::Eq => BinaryOp::Eq,
        IlOperator::Ne => BinaryOp::Ne,
        IlOperator::Le => BinaryOp::Le,
        IlOperator::Lt => BinaryOp::Lt,
        _ => return None,
    })
}

fn op_name(op: IlOperator) -> &'static str {
    match op {
        IlOperator::Ld => "LD",
        IlOperator::St => "ST",
        IlOperator::S => "S",
        IlOperator::R => "R",
        IlOperator::And => "AND",
        IlOperator::Or => "OR",
        IlOperator::Xor => "XOR",
        IlOperator::Not => "NOT",
        IlOperator::Add => "ADD",
        IlOperator::Sub => "SUB",
        IlOperator::Mul => "MUL",
        IlOperator::Div => "DIV",
        IlOperator::Mod => "MOD",
        IlOperator::Gt => "GT",
        IlOperator::Ge => "GE",
        IlOperator::Eq => "EQ",
        IlOperator::Ne => "NE",
        IlOperator::Le => "LE",
        IlOperator::Lt => "LT",
    }
}

/// IL lowering state of one body.
struct IlState {
    cr: Slot,
    cr_ty: Option<TypeId>,
    /// The CR as an untyped literal (`LD 1`), so that the next operation
    /// or store gives it its type; the slot holds it in the default type.
    cr_lit: Option<Val>,
    stack: Vec<Deferred>,
    labels: HashMap<String, (Target, Option<TypeId>)>,
    pending: Vec<(usize, Ident, Option<TypeId>)>,
    /// A line of the body had a syntax error: `(` and `)` may not match.
    after_error: bool,
}

impl BodyBuilder<'_> {
    /// Lowers an IL body. Returns the CR slot and its final type (used for
    /// IL transition conditions).
    pub(super) fn il_body(&mut self, lines: &[IlLine]) -> (Slot, Option<TypeId>) {
        let cr = self.block.temp();
        // Keep the CR and deferred slots out of statement-level temp reuse.
        self.block.temp_base = self.block.temp_next;
        let mut st = IlState {
            cr,
            cr_ty: None,
            cr_lit: None,
            stack: Vec::new(),
            labels: HashMap::new(),
            pending: Vec::new(),
            after_error: false,
        };
        // After a line with a syntax error the CR is unknown: messages are
        // held back until a label or a load at the outer level.
        let mut poisoned = false;
        // Collect labels first so forward jumps know their targets exist.
        let mut declared: HashMap<String, Span> = HashMap::new();
        for line in lines {
            if let Some(l) = &line.label
                && declared.insert(l.key(), l.span).is_some()
            {
                {
                    self.diags.error(
                        "E503",
                        l.span,
                        format!("label `{}` is defined twice", l.name),
                    );
                }
            }
        }
        for line in lines {
            if line.label.is_none() && line.instr.is_none() {
                (poisoned, st.after_error) = (true, true);
                continue;
            }
            if let Some(l) = &line.label {
                poisoned = false;
                // The CR type at a label: what falls through, else what jumps bring.
                let jumped = st
                    .pending
                    .iter()
                    .find(|(_, id, _)| id.key() == l.key())
                    .and_then(|(_, _, t)| *t);
                self.type_literal_at_join(&mut st, jumped);
                let at = self.block.here();
                if st.cr_ty.is_none() {
                    st.cr_ty = jumped;
                }
                st.cr_lit = None;
                st.labels.entry(l.key()).or_insert((at, st.cr_ty));
                if !st.stack.is_empty() {
                    self.diags
                        .error("E501", l.span, "a label cannot stand inside an open `(`");
                }
            }
            if let Some(instr) = &line.instr {
                let mark = self.block.temp_next;
                self.block.span = instr.span;
                poisoned &= !super::il_recovery::is_load(instr) || !st.stack.is_empty();
                let reported = self.diags.len();
                self.il_instr(&mut st, instr);
                if poisoned {
                    self.diags.truncate(reported);
                }
                // An instruction in error, or a CR of no known type (an
                // undeclared operand), leaves the CR unknown too.
                poisoned |= st.cr_ty == Some(TypeTable::error())
                    || super::il_recovery::has_error_since(self.diags, reported);
                self.block.temp_next = mark.max(self.block.temp_base);
            }
        }
        for d in st.stack.iter().filter(|_| !st.after_error) {
            self.diags.error(
                "E501",
                d.span,
                format!("`{}(` is never closed by `)`", op_name(d.op)),
            );
        }
        for (at, label, _) in std::mem::take(&mut st.pending) {
            match st.labels.get(&label.key()) {
                Some(&(target, _)) => self.block.patch(at, target),
                None => self.diags.error(
                    "E502",
                    label.span,
                    format!("jump to unknown label `{}`", label.name),
                ),
            }
        }
        self.block.il_cr = None;
        (st.cr, st.cr_ty)
    }

    /// An untyped literal falling into a label that a jump reaches with a
    /// typed CR takes the jump's type (`LD 0` before `L: ST out`), converted
    /// before the label so both paths arrive with one type. When it does
    /// not fit that type (`LD 5` falling into a label a `JMPC` reaches with
    /// its BOOL), it keeps its own, as a typed CR falling through does: an
    /// error only where an instruction reads the CR wrongly.
    fn type_literal_at_join(&mut self, st: &mut IlState, jumped: Option<TypeId>) {
        let (Some(lit), Some(t)) = (st.cr_lit.clone(), jumped) else {
            return;
        };
        if st.cr_ty == Some(t) {
            return;
        }
        let reported = self.diags.len();
        let v = self.coerce(lit, t, self.block.span, "current result");
        if v.is_error() || self.diags.len() > reported {
            self.diags.truncate(reported);
            return;
        }
        let s = self.materialize(&v);
        self.block.mov(st.cr, s);
        st.cr_ty = Some(t);
    }

    fn cr_val(&mut self, st: &IlState, span: Span, what: &str) -> Option<Val> {
        if let Some(lit) = &st.cr_lit {
            return Some(lit.clone());
        }
        match st.cr_ty {
            Some(t) => Some(Val::Slot(st.cr, t)),
            None => {
                self.diags.error(
                    "E505",
                    span,
                    format!("{what} needs a current result: load one first (LD)"),
                );
                None
            }
        }
    }

    /// Makes the CR readable as a hidden variable for call arguments.
    fn expose_cr(&mut self, st: &IlState) {
        let ty = st.cr_ty.unwrap_or(TypeTable::error());
        self.block.il_cr = Some(VarInfo {
            name: "current result".into(),
            ty,
            kind: MemberKind::Temp,
            storage: Storage::Frame(st.cr.get()),
            constant: false,
            value: None,
            init: None,
            location: None,
        });
    }

    /// The CR as a call argument: the literal itself while the CR is an
    /// untyped literal (so it takes the parameter's type), else the CR slot.
    fn cr_arg(st: &IlState, span: Span) -> Expr {
        use crate::sema::consts::Const;
        use crate::syntax::ast::{Literal, LiteralValue};
        let value = match &st.cr_lit {
            Some(Val::Const(Const::Int(v), _)) => Some(LiteralValue::Int(*v)),
            Some(Val::Const(Const::Real(v), _)) => Some(LiteralValue::Real(*v)),
            _ => None,
        };
        match value {
            Some(value) => Expr {
                kind: ExprKind::Literal(Literal {
                    value,
                    type_prefix: None,
                }),
                span,
            },
            None => Self::cr_expr(span),
        }
    }

    fn cr_expr(span: Span) -> Expr {
        Expr {
            kind: ExprKind::Name(Ident {
                name: CR_KEY.to_string(),
                span,
            }),
            span,
        }
    }

    /// Sets CR from a value.
    fn set_cr(&mut self, st: &mut IlState, v: Val) {
        if v.is_error() {
            return;
        }
        st.cr_lit = match &v {
            Val::Const(_, Ty::AnyInt | Ty::AnyReal) => Some(v.clone()),
            _ => None,
        };
        let t = match v.ty() {
            Ty::T(t) => t,
            other => self.default_type(other, None),
        };
        let v = self.coerce(v, t, self.block.span, "current result");
        let s = self.materialize(&v);
        if self.types.scalar(t).is_some_and(|e| e.is_string()) {
            // The CR holds the id of a string temporary owned by this body.
            let (max, wide) = match self.types.get(t).kind {
                crate::ir::type_table::TypeKind::Str { max, wide } => (max, wide),
                _ => (254, false),
            };
            let tmp = self.string_temp(max, wide);
            self.block.emit(Op::StrMov { d: tmp, s });
            self.block.emit(Op::Mov { d: st.cr, s: tmp });
        } else {
            self.block.mov(st.cr, s);
        }
        st.cr_ty = Some(t);
    }

    fn operand(&mut self, e: Option<&Expr>, negate: bool, span: Span, what: &str) -> Option<Val> {
        let Some(e) = e else {
            self.diags
                .error("E504", span, format!("{what} needs an operand"));
            return None;
        };
        let v = self.expr(e, None);
        if v.is_error() {
            return None;
        }
        if negate {
            return Some(self.negate_val(v, e.span, what));
        }
        Some(v)
    }

    fn negate_val(&mut self, v: Val, span: Span, what: &str) -> Val {
        let bits = v
            .ty()
            .id()
            .and_then(|t| self.types.scalar(t))
            .filter(|e| e.is_bit());
        match bits {
            Some(ElemType::Bool) => {
                if let Val::Const(crate::sema::consts::Const::Bits(b), t) = v {
                    return Val::Const(crate::sema::consts::Const::Bits(b ^ 1), t);
                }
                let a = self.materialize(&v);
                let d = self.block.temp();
                self.block.emit(Op::NotB { d, a });
                Val::Slot(d, TypeTable::elem(ElemType::Bool))
            }
            Some(e) => {
                let a = self.materialize(&v);
                let d = self.block.temp();
                self.block.emit(Op::NotW {
                    d,
                    a,
                    shift: super::typeck::shift_of(e),
                });
                Val::Slot(d, TypeTable::elem(e))
            }
            None => {
                self.diags.error(
                    "E302",
                    span,
                    format!("the N modifier of {what} needs a BOOL or bit-string operand"),
                );
                Val::error()
            }
        }
    }

    /// Lowers one IL instruction.
    fn il_instr(&mut self, st: &mut IlState, instr: &IlInstr) {
        let span = instr.span;
        match &instr.kind {
            IlInstrKind::Simple {
                op,
                negate,
                operand,
            } => self.il_simple(st, *op, *negate, operand.as_ref(), span),
            IlInstrKind::Deferred {
                op,
                negate,
                operand,
            } => self.il_deferred(st, *op, *negate, operand.as_ref(), span),
            IlInstrKind::Close => self.il_close(st, span),
            IlInstrKind::Jump { cond, label } => self.il_jump(st, *cond, label, span),
            IlInstrKind::Return { cond } => self.il_return(st, *cond, span),
            IlInstrKind::Call {
                cond,
                instance,
                args,
                outputs,
            } => {
                let skip = match cond {
                    None => None,
                    Some(when) => {
                        if !self.cr_is_bool(st, span, "CALC") {
                            return;
                        }
                        Some(if *when {
                            self.block.emit(Op::Jz {
                                c: st.cr,
                                t: Target::UNPATCHED,
                            })
                        } else {
                            self.block.emit(Op::Jnz {
                                c: st.cr,
                                t: Target::UNPATCHED,
                            })
                        })
                    }
                };
                if !(outputs.is_empty() && self.oop_il_call(instance, args, span)) {
                    self.il_fb_call(st, instance, args, outputs, span);
                }
                if let Some(j) = skip {
                    let end = self.block.here();
                    self.block.patch(j, end);
                }
            }
            IlInstrKind::FunctionCall { name, args } => self.il_function_call(st, name, args, span),
            IlInstrKind::FbInput { pin, instance } => self.il_fb_input(st, pin, instance, span),
        }
    }

    /// `OP(`: the CR saved, the operator deferred until `)`.
    fn il_deferred(
        &mut self,
        st: &mut IlState,
        op: IlOperator,
        negate: bool,
        operand: Option<&Expr>,
        span: Span,
    ) {
        if matches!(
            op,
            IlOperator::Ld | IlOperator::St | IlOperator::S | IlOperator::R | IlOperator::Not
        ) {
            self.diags.error(
                "E504",
                span,
                format!("{} cannot be deferred with `(`", op_name(op)),
            );
            return;
        }
        let Some(cur) = self.cr_val(st, span, op_name(op)) else {
            return;
        };
        let saved = self.block.temp();
        self.block.temp_base = self.block.temp_next;
        let s = self.materialize(&cur);
        self.block.emit(Op::Mov { d: saved, s });
        self.block.last_def = None;
        st.stack.push(Deferred {
            op,
            negate,
            saved,
            saved_ty: st.cr_ty,
            saved_lit: st.cr_lit.clone(),
            span,
        });
        st.cr_ty = None;
        st.cr_lit = None;
        if let Some(e) = operand {
            let v = self.expr(e, None);
            self.set_cr(st, v);
        }
    }

    /// `)`: the deferred operator applied to the saved CR and the inner CR.
    fn il_close(&mut self, st: &mut IlState, span: Span) {
        let Some(d) = st.stack.pop() else {
            if !st.after_error {
                self.diags
                    .error("E501", span, "`)` without a matching `OP(`");
            }
            return;
        };
        let Some(inner) = self.cr_val(st, span, "`)`") else {
            return;
        };
        let inner = if d.negate {
            self.negate_val(inner, span, op_name(d.op))
        } else {
            inner
        };
        let Some(bop) = binary_of(d.op) else { return };
        let saved = d
            .saved_lit
            .unwrap_or(Val::Slot(d.saved, d.saved_ty.unwrap_or(TypeTable::error())));
        let r = self.binary_vals(bop, saved, inner, span);
        self.set_cr(st, r);
    }

    /// `JMP`, `JMPC`, `JMPCN`: patched when the labels are known.
    fn il_jump(&mut self, st: &mut IlState, cond: Option<bool>, label: &Ident, span: Span) {
        let Some(at) = self.il_branch(st, cond, span, "JMPC") else {
            return;
        };
        self.block.last_def = None;
        st.pending.push((at, label.clone(), st.cr_ty));
        if cond.is_none() {
            st.cr_ty = None;
            st.cr_lit = None;
        }
    }

    /// `RET`, `RETC`, `RETCN`.
    fn il_return(&mut self, st: &mut IlState, cond: Option<bool>, span: Span) {
        if let Some(at) = self.il_branch(st, cond, span, "RETC") {
            self.block.returns.push(at);
        }
    }

    /// The jump of `JMP`/`RET` (unconditional, `cond` None) or of their
    /// `C`/`CN` forms (taken when the BOOL current result equals `cond`),
    /// with its target left to patch; `None` when the current result is
    /// not a BOOL (reported, naming `what`).
    fn il_branch(
        &mut self,
        st: &mut IlState,
        cond: Option<bool>,
        span: Span,
        what: &str,
    ) -> Option<usize> {
        let t = Target::UNPATCHED;
        Some(match cond {
            None => self.block.emit(Op::Jmp { t }),
            Some(when) => {
                if !self.cr_is_bool(st, span, what) {
                    return None;
                }
                let c = st.cr;
                self.block.emit(if when {
                    Op::Jnz { c, t }
                } else {
                    Op::Jz { c, t }
                })
            }
        })
    }

    /// `CAL inst(...)` and its `=>` output copies (the condition is the caller's).
    fn il_fb_call(
        &mut self,
        st: &mut IlState,
        instance: &Expr,
        args: &[Arg],
        outputs: &[IlOutputCopy],
        span: Span,
    ) {
        self.expose_cr(st);
        if let Some(inst) = self.place(instance) {
            self.fb_call(&inst, args, span);
            for out in outputs {
                let Some(dest) = &out.dest else { continue };
                let member = Expr {
                    kind: ExprKind::Member(Box::new(instance.clone()), out.output.clone()),
                    span: out.span,
                };
                self.block.span = out.span;
                self.assign_il(dest, &member);
            }
        }
    }

    /// A function call in IL: the CR is the first argument of an informal call.
    fn il_function_call(&mut self, st: &mut IlState, name: &Ident, args: &[Arg], span: Span) {
        if self.il_refuses_aggregate_result(name, span) {
            (st.cr_ty, st.cr_lit) = (Some(TypeTable::error()), None);
            return;
        }
        self.expose_cr(st);
        // Formal calls name every input; informal ones take the CR first.
        let formal = args.iter().any(|a| matches!(a, Arg::Input { .. }));
        if st.cr_ty.is_none() && !formal {
            self.diags.error(
                "E505",
                span,
                format!(
                    "{} needs a current result as first argument: load one first",
                    name.name
                ),
            );
            return;
        }
        let mut all = Vec::new();
        if !formal {
            all.push(Arg::Positional(Self::cr_arg(st, span)));
        }
        all.extend(args.iter().cloned());
        let call = Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(name.clone()),
                span: name.span,
            }),
            args: all,
            span,
        };
        let v = self.call_expr(&call, None);
        self.set_cr(st, v);
    }

    /// `S1 inst`, `IN inst`, ...: the CR to one input of an FB instance, and the call.
    fn il_fb_input(&mut self, st: &mut IlState, pin: &Ident, instance: &Expr, span: Span) {
        if st.cr_ty.is_none() {
            self.diags.error(
                "E505",
                span,
                format!("{} needs a current result: load one first", pin.name),
            );
            return;
        }
        self.expose_cr(st);
        if let Some(inst) = self.place(instance) {
            let arg = Arg::Input {
                name: pin.clone(),
                value: Self::cr_arg(st, span),
            };
            self.fb_call(&inst, &[arg], span);
        }
    }

    fn cr_is_bool(&mut self, st: &IlState, span: Span, what: &str) -> bool {
        match st.cr_ty {
            Some(t) if t == TypeTable::elem(ElemType::Bool) => true,
            Some(t) => {
                let n = self.types.name(t).to_string();
                self.diags.error(
                    "E506",
                    span,
                    format!("{what} needs a BOOL current result, found {n}"),
                );
                false
            }
            None => {
                self.diags.error(
                    "E505",
                    span,
                    format!("{what} needs a current result: load one first"),
                );
                false
            }
        }
    }

    /// `dest := source` for the Moeller output list.
    fn assign_il(&mut self, dest: &Expr, source: &Expr) {
        let stmt = crate::syntax::ast::Stmt {
            kind: crate::syntax::ast::StmtKind::Assign {
                target: dest.clone(),
                value: source.clone(),
            },
            span: source.span,
        };
        let mark = self.block.temp_next;
        self.stmts(std::slice::from_ref(&stmt));
        self.block.temp_next = mark;
    }

    fn il_simple(
        &mut self,
        st: &mut IlState,
        op: IlOperator,
        negate: bool,
        operand: Option<&Expr>,
        span: Span,
    ) {
        let name = op_name(op);
        match op {
            IlOperator::Ld => {
                // `LD ctd`: the LD input of a down counter (IEC Table 53).
                if !negate && self.fb_pin_operator(st, operand, "LD", span) {
                    return;
                }
                if let Some(v) = self.operand(operand, negate, span, name) {
                    self.set_cr(st, v);
                }
            }
            IlOperator::St => {
                let Some(target) = operand else {
                    self.diags.error("E504", span, "ST needs an operand");
                    return;
                };
                let Some(cur) = self.cr_val(st, span, name) else {
                    return;
                };
                let cur = if negate {
                    self.negate_val(cur, span, name)
                } else {
                    cur
                };
                self.store_value(target, cur);
            }
            IlOperator::S | IlOperator::R => {
                // `S rs` / `R ctu`: the S or R input of a function block.
                if !negate && self.fb_pin_operator(st, operand, name, span) {
                    return;
                }
                let Some(target) = operand else {
                    self.diags
                        .error("E504", span, format!("{name} needs an operand"));
                    return;
                };
                if !self.cr_is_bool(st, span, name) {
                    return;
                }
                let skip = self.block.emit(Op::Jz {
                    c: st.cr,
                    t: Target::UNPATCHED,
                });
                let v = Val::Const(
                    crate::sema::consts::Const::Bits((op == IlOperator::S) as u64),
                    Ty::T(TypeTable::elem(ElemType::Bool)),
                );
                self.store_value(target, v);
                let end = self.block.here();
                self.block.patch(skip, end);
            }
            IlOperator::Not => {
                if operand.is_some() {
                    self.diags.error(
                        "E504",
                        span,
                        "NOT takes no operand in IL (it negates the current result)",
                    );
                    return;
                }
                let Some(cur) = self.cr_val(st, span, name) else {
                    return;
                };
                let v = self.negate_val(cur, span, name);
                self.set_cr(st, v);
            }
            _ => {
                let Some(bop) = binary_of(op) else { return };
                let Some(cur) = self.cr_val(st, span, name) else {
                    return;
                };
                let Some(v) = self.operand(operand, negate, span, name) else {
                    return;
                };
                let r = self.binary_vals(bop, cur, v, span);
                self.set_cr(st, r);
            }
        }
    }

    /// When `operand` names a function block instance with an input called
    /// `pin`, stores the CR into that input and calls the instance (the FB
    /// input operators of IEC Table 53 that share a name with an IL
    /// operator: `LD`, `S`, `R`). Returns false when it is not such a case.
    fn fb_pin_operator(
        &mut self,
        st: &IlState,
        operand: Option<&Expr>,
        pin: &str,
        span: Span,
    ) -> bool {
        let Some(e) = operand else { return false };
        let key = match &e.kind {
            ExprKind::Name(id) => id.key(),
            _ => return false,
        };
        let Some(var) = self.lookup_var(&key) else {
            return false;
        };
        let has_pin = match &self.types.get(var.ty).kind {
            crate::ir::type_table::TypeKind::NativeFb(fb) => {
                crate::stdlib::interface(*fb).iter().any(|p| {
                    p.dir == crate::stdlib::ParamDir::Input
                        && (p.name.eq_ignore_ascii_case(pin)
                            || p.aliases.iter().any(|a| a.eq_ignore_ascii_case(pin)))
                })
            }
            crate::ir::type_table::TypeKind::Pou { members, .. } => members
                .iter()
                .any(|m| m.kind == MemberKind::Input && m.name.eq_ignore_ascii_case(pin)),
            _ => false,
        };
        if !has_pin {
            return false;
        }
        if st.cr_ty.is_none() {
            self.diags.error(
                "E505",
                span,
                format!("{pin} needs a current result: load one first"),
            );
            return true;
        }
        self.expose_cr(st);
        if let Some(inst) = self.place(e) {
            let arg = Arg::Input {
                name: Ident {
                    name: pin.to_string(),
                    span,
                },
                value: Self::cr_arg(st, span),
            };
            self.fb_call(&inst, &[arg], span);
        }
        true
    }

    /// Stores a value into the place `target` (ST, S, R); `w.3` stores one bit.
    fn store_value(&mut self, target: &Expr, v: Val) {
        if self.property_write_val(target, &v) {
            return;
        }
        if let Some((base, sel)) = self.part_of(target) {
            self.store_part(base, sel, v, target.span);
            return;
        }
        let Some(p) = self.place(target) else {
            return;
        };
        if !self.check_writable(&p, target.span) {
            return;
        }
        let v = self.coerce(v, p.ty, target.span, "ST");
        if v.is_error() {
            return;
        }
        let s = self.materialize(&v);
        self.write_place(&p, s);
    }
}
