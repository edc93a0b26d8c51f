//! Statements: assignment, calls, IF, CASE, FOR, WHILE, REPEAT, EXIT,
//! CONTINUE, RETURN — lowered to typed instructions and jumps.

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Fcx, LoopCtx, Ty, Val};
use crate::elementary::ElemType;
use crate::ir::op::{Cmp, Op, ShortTarget, Slot, Target};
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{CaseLabel, Expr, ExprKind, Stmt, StmtKind};

/// The predicate that is TRUE exactly when `c` is FALSE.
pub fn negate(c: Cmp) -> Cmp {
    match c {
        Cmp::Eq => Cmp::Ne,
        Cmp::Ne => Cmp::Eq,
        Cmp::Lt => Cmp::Ge,
        Cmp::Ge => Cmp::Lt,
        Cmp::Le => Cmp::Gt,
        Cmp::Gt => Cmp::Le,
    }
}

/// A condition `NOT c` branches on `c` the other way round (so that
/// `IF NOT f[i]` and `IF NOT (a < b)` keep their fused branches).
fn strip_not(cond: &Expr, when: bool) -> (&Expr, bool) {
    match &cond.kind {
        ExprKind::Unary(crate::syntax::ast::UnaryOp::Not, inner) => strip_not(inner, !when),
        _ => (cond, when),
    }
}

/// `v := v + x` (or `v + 3`) right before a WHILE test `v cmp K` becomes one `AddBr`
/// that steps and branches back; the test stays in place for the loop
/// entry and for CONTINUE, and runs once more only when the loop ends.
fn fuse_step_and_test(f: &mut Fcx, cond_at: usize, top: Target) {
    if cond_at == 0 || cond_at + 1 != f.ops.len() {
        return;
    }
    let Op::JnCmpSI {
        a: tested,
        imm,
        cmp,
        t,
    } = f.ops[cond_at]
    else {
        return;
    };
    let (d, a, b, shift) = match f.ops[cond_at - 1] {
        Op::AddS { d, a, b, shift } => (d, a, b, shift),
        // A constant step is read from a constant slot.
        Op::AddSI { d, a, imm, shift } => (d, a, f.const_slot(imm as i64 as u64), shift),
        _ => return,
    };
    let (Ok(imm), Ok(target)) = (i16::try_from(imm), u16::try_from(top.get())) else {
        return;
    };
    if a != d || tested != d || t != top || b == d {
        return;
    }
    f.ops[cond_at - 1] = Op::AddBr {
        d,
        b,
        imm,
        t: ShortTarget::new(target),
        cmp: negate(cmp),
        shift,
    };
}

impl BodyBuilder<'_> {
    /// Emits a statement list.
    pub(super) fn stmts(&mut self, list: &[Stmt]) {
        for s in list {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        let mark = self.block.temp_next;
        self.block.span = s.span;
        match &s.kind {
            StmtKind::Assign { target, value } => self.assign(target, value, s.span),
            StmtKind::RefAssign { target, value } => self.ref_bind(target, value),
            StmtKind::Call(call) => self.call_stmt(call),
            StmtKind::If {
                branches,
                else_branch,
            } => {
                let mut ends = Vec::new();
                for (k, (cond, body)) in branches.iter().enumerate() {
                    let skip = self.cond_jump(cond, false);
                    self.block.temp_next = mark;
                    self.stmts(body);
                    let last = k + 1 == branches.len() && else_branch.is_none();
                    if !last {
                        ends.push(self.block.emit(Op::Jmp {
                            t: Target::UNPATCHED,
                        }));
                    }
                    let next = self.block.here();
                    if let Some(j) = skip {
                        self.block.patch(j, next);
                    }
                }
                if let Some(body) = else_branch {
                    self.stmts(body);
                }
                let end = self.block.here();
                for j in ends {
                    self.block.patch(j, end);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_branch,
            } => self.case(selector, arms, else_branch.as_deref()),
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => self.for_loop(var, from, to, by.as_ref(), body, s.span),
            StmtKind::While { cond, body } => {
                let to_cond = self.block.emit(Op::Jmp {
                    t: Target::UNPATCHED,
                });
                let top = self.block.here();
                self.block.loops.push(LoopCtx::default());
                self.stmts(body);
                let cont = self.block.here();
                self.block.patch(to_cond, cont);
                self.block.span = cond.span;
                self.cond_branch_to(cond, true, top);
                if !self.model.unoptimized {
                    fuse_step_and_test(&mut self.block, cont.index(), top);
                }
                self.block.end_loop(cont, Vec::new());
            }
            StmtKind::Repeat { body, until } => {
                let top = self.block.here();
                self.block.loops.push(LoopCtx::default());
                self.stmts(body);
                let cont = self.block.here();
                self.block.span = until.span;
                self.cond_branch_to(until, false, top);
                self.block.end_loop(cont, Vec::new());
            }
            StmtKind::Try {
                body,
                catch,
                finally,
            } => self.try_stmt(body, catch.as_ref(), finally.as_deref()),
            StmtKind::Exit => self.loop_jump(true, s.span),
            StmtKind::Continue => self.loop_jump(false, s.span),
            StmtKind::Return => {
                if !self.block.finally.is_empty() {
                    self.run_finally_parts(None);
                }
                let j = self.block.emit(Op::Jmp {
                    t: Target::UNPATCHED,
                });
                self.block.returns.push(j);
            }
            StmtKind::Empty => {}
        }
        self.block.temp_next = mark;
    }

    /// EXIT (`exit`) or CONTINUE: a jump patched when the innermost loop ends.
    fn loop_jump(&mut self, exit: bool, span: Span) {
        if self.block.loops.is_empty() {
            let word = if exit { "EXIT" } else { "CONTINUE" };
            self.diags.error(
                "E405",
                span,
                format!("{word} outside of a FOR, WHILE or REPEAT loop"),
            );
            return;
        }
        if !self.block.finally.is_empty() {
            self.run_finally_parts(Some(self.block.loops.len()));
        }
        let j = self.block.emit(Op::Jmp {
            t: Target::UNPATCHED,
        });
        if let Some(lp) = self.block.loops.last_mut() {
            if exit {
                lp.exits.push(j);
            } else {
                lp.continues.push(j);
            }
        }
    }

    /// Checks a condition and emits a jump taken when it equals `when`;
    /// returns the jump to patch (None if the condition was invalid or is
    /// a constant that never jumps).
    pub(super) fn cond_jump(&mut self, cond: &Expr, when: bool) -> Option<usize> {
        let (test, when) = strip_not(cond, when);
        let v = self.bool_expr(test, cond.span)?;
        if let Val::Const(Const::Bits(b), _) = v {
            if (b != 0) == when {
                return Some(self.block.emit(Op::Jmp {
                    t: Target::UNPATCHED,
                }));
            }
            return None;
        }
        let s = self.materialize(&v);
        Some(self.branch_on_slot(s, when, Target::UNPATCHED))
    }

    /// Emits a jump to `target` taken when `cond` equals `when`.
    fn cond_branch_to(&mut self, cond: &Expr, when: bool, target: Target) {
        let (test, when) = strip_not(cond, when);
        let Some(v) = self.bool_expr(test, cond.span) else {
            return;
        };
        if let Val::Const(Const::Bits(b), _) = v {
            if (b != 0) == when {
                self.block.emit(Op::Jmp { t: target });
            }
            return;
        }
        let s = self.materialize(&v);
        self.branch_on_slot(s, when, target);
    }

    /// Jump on a BOOL slot, fusing a just-computed integer comparison.
    pub(super) fn branch_on_slot(&mut self, s: Slot, when: bool, target: Target) -> usize {
        if let Some((at, d)) = self.block.last_def
            && !self.model.unoptimized
            && d == s
            && self.block.is_temp(s)
            && at + 1 == self.block.ops.len()
        {
            let fused = match self.block.ops[at] {
                Op::LoadElem { idx, desc, .. } => Some(if when {
                    Op::JnzElem {
                        idx,
                        desc,
                        t: target,
                    }
                } else {
                    Op::JzElem {
                        idx,
                        desc,
                        t: target,
                    }
                }),
                Op::CmpSI { a, imm, cmp, .. } => Some(Op::JnCmpSI {
                    a,
                    imm,
                    cmp: if when { negate(cmp) } else { cmp },
                    t: target,
                }),
                Op::CmpS { a, b, cmp, .. } => Some(Op::JnCmpS {
                    a,
                    b,
                    cmp: if when { negate(cmp) } else { cmp },
                    t: target,
                }),
                // Negating a float comparison is wrong for NaN: fuse only
                // "jump when FALSE".
                Op::CmpF32 { a, b, cmp, .. } if !when => Some(Op::JnCmpF32 {
                    a,
                    b,
                    cmp,
                    t: target,
                }),
                Op::CmpF64 { a, b, cmp, .. } if !when => Some(Op::JnCmpF64 {
                    a,
                    b,
                    cmp,
                    t: target,
                }),
                _ => None,
            };
            if let Some(op) = fused {
                self.block.ops[at] = op;
                self.block.last_def = None;
                return at;
            }
        }
        if when {
            self.block.emit(Op::Jnz { c: s, t: target })
        } else {
            self.block.emit(Op::Jz { c: s, t: target })
        }
    }

    /// A condition: must be BOOL (E303, reported at `whole`, the condition
    /// as written, of which `cond` may be the operand of leading NOTs).
    fn bool_expr(&mut self, cond: &Expr, whole: Span) -> Option<Val> {
        let v = self.expr(cond, Some(TypeTable::elem(ElemType::Bool)));
        if v.is_error() {
            return None;
        }
        if v.ty() != Ty::T(TypeTable::elem(ElemType::Bool)) {
            let name = self.ty_name(v.ty());
            self.diags.error(
                "E303",
                whole,
                format!("condition must be BOOL, found {name}"),
            );
            return None;
        }
        Some(v)
    }

    fn assign(&mut self, target: &Expr, value: &Expr, span: Span) {
        if let Some((base, sel)) = self.part_of(target) {
            let v = self.expr(value, Some(TypeTable::elem(sel.size.elem())));
            self.store_part(base, sel, v, value.span);
            return;
        }
        if self.oop_assign(target, value) || self.property_write(target, value) {
            return;
        }
        let Some(p) = self.place(target) else {
            // Still check the right-hand side for its own errors.
            self.expr(value, None);
            return;
        };
        if !self.check_writable(&p, target.span) {
            return;
        }
        let kind = self.types.get(p.ty).kind.clone();
        match kind {
            // A target of unknown type has its error already (E203).
            TypeKind::Error => {}
            TypeKind::Array { .. } | TypeKind::Struct { .. } => {
                let Some(src) = self.place(value) else {
                    return;
                };
                self.copy_if_assignable(&p, &src, value.span, span, "assignment");
            }
            TypeKind::NativeFb(_) | TypeKind::Pou { program: false, .. } => {
                self.copy_fb(&p, value, span);
            }
            TypeKind::Pou { .. } | TypeKind::Step => {
                self.diags.error(
                    "E302",
                    target.span,
                    "program instances and SFC steps cannot be assigned",
                );
            }
            TypeKind::OpenArray { .. } => self.open_array_misused(target.span),
            _ => {
                self.check_ref_escape(target, value);
                let v = self.expr(value, Some(p.ty));
                let v = self.coerce(v, p.ty, value.span, "assignment");
                if v.is_error() {
                    return;
                }
                let s = self.materialize(&v);
                self.write_place(&p, s);
            }
        }
    }

    /// Reports why `p` cannot be written here (E401: read-only, or the
    /// control variable of an enclosing FOR), and warns when a program
    /// writes a `%I` input (W202). Returns whether the write may proceed.
    pub(super) fn check_writable(&mut self, p: &super::emit::PlaceRef, span: Span) -> bool {
        if !p.writable {
            let why = p.readonly_reason.unwrap_or("it is read-only");
            self.diags.error(
                super::fb_member_read::write_refusal_code(p.readonly_reason),
                span,
                format!("cannot assign to this variable: {why}"),
            );
            return false;
        }
        if let super::emit::Place::Frame(s) = p.place
            && self.block.for_vars.contains(&s)
        {
            self.diags.error(
                "E401",
                span,
                "cannot assign to this variable: it is the control variable of an enclosing FOR loop",
            );
            return false;
        }
        self.note_input_write(p, span);
        if p.input_image {
            self.diags.warning(
                "W202",
                span,
                "the program writes a %I input; the next stimulus value will overwrite it",
            );
        }
        true
    }

    /// Copies the array or structure `src` into `dst` when its type may
    /// be assigned there (else a mismatch at `at`, named by `what`); a
    /// fault in the copy is reported at `span`.
    pub(super) fn copy_if_assignable(
        &mut self,
        dst: &super::emit::PlaceRef,
        src: &super::emit::PlaceRef,
        at: Span,
        span: Span,
        what: &str,
    ) {
        if !self.assignable(src.ty, dst.ty) && !self.extends_structure(src.ty, dst.ty) {
            self.mismatch(at, Ty::T(src.ty), dst.ty, what);
            return;
        }
        self.copy_aggregate(dst, src, span);
    }

    /// True when structure `derived` extends `base`, directly or not: its
    /// value starts with a `base` (CODESYS copies that part, `stBase :=
    /// stDerived;`, as `copy_aggregate` does with `base`'s size).
    pub(super) fn extends_structure(&self, derived: TypeId, base: TypeId) -> bool {
        let mut at = derived;
        // A chain of bases is as long as the structures declared.
        for _ in 0..=self.model.struct_bases.len() {
            match self.model.struct_bases.get(&at) {
                Some(&b) if b == base => return true,
                Some(&b) => at = b,
                None => return false,
            }
        }
        false
    }

    /// Copies an array or structure by value.
    pub(super) fn copy_aggregate(
        &mut self,
        dst: &super::emit::PlaceRef,
        src: &super::emit::PlaceRef,
        span: Span,
    ) {
        // A fault in the copy is reported at the assignment.
        let saved = std::mem::replace(&mut self.block.span, span);
        let d = self.address_of(dst);
        let s = self.address_of(src);
        self.copy_value(d, s, dst.ty);
        self.block.span = saved;
    }

    /// True if a value of `t` holds string slots.
    pub(super) fn contains_strings(&self, t: crate::ir::type_table::TypeId) -> bool {
        match &self.types.get(t).kind {
            TypeKind::Str { .. } => true,
            TypeKind::Array { elem, .. } => self.contains_strings(*elem),
            TypeKind::Struct { fields } => fields.iter().any(|m| self.contains_strings(m.ty)),
            TypeKind::Pou { .. } => !self.fb_string_members(t).is_empty(),
            _ => false,
        }
    }

    fn case(
        &mut self,
        selector: &Expr,
        arms: &[crate::syntax::ast::CaseArm],
        else_branch: Option<&[Stmt]>,
    ) {
        let sv = self.expr(selector, None);
        if sv.is_error() {
            return;
        }
        let st = match sv.ty() {
            Ty::T(t) => t,
            other => self.default_type(other, None),
        };
        let Some(e) = self
            .scalar(st)
            .filter(|e| e.is_int() || e.is_bit() && *e != ElemType::Bool)
        else {
            let name = self.types.name(st).to_string();
            self.diags.error(
                "E301",
                selector.span,
                format!("CASE selector must be an integer or enumeration, found {name}"),
            );
            return;
        };
        let sv = self.coerce(sv, st, selector.span, "CASE selector");
        let sel = self.materialize(&sv);
        let mut seen: Vec<(i128, i128)> = Vec::new();
        let mut to_body: Vec<Vec<usize>> = Vec::new();
        for arm in arms {
            let mut jumps = Vec::new();
            for label in &arm.labels {
                let Some((lo, hi, lspan)) = self.case_label_range(label, st) else {
                    continue;
                };
                if seen.iter().any(|&(a, b)| lo <= b && a <= hi) {
                    self.diags
                        .error("E408", lspan, "this CASE label overlaps an earlier one");
                    continue;
                }
                seen.push((lo, hi));
                let signed = super::typeck::compares_signed(e);
                jumps.push(self.case_test(sel, lo, hi, signed));
            }
            to_body.push(jumps);
        }
        let to_else = self.block.emit(Op::Jmp {
            t: Target::UNPATCHED,
        });
        let mut ends = Vec::new();
        for (arm, jumps) in arms.iter().zip(to_body) {
            let start = self.block.here();
            for j in jumps {
                self.block.patch(j, start);
            }
            self.stmts(&arm.body);
            ends.push(self.block.emit(Op::Jmp {
                t: Target::UNPATCHED,
            }));
        }
        let else_at = self.block.here();
        self.block.patch(to_else, else_at);
        if let Some(body) = else_branch {
            self.stmts(body);
        }
        let end = self.block.here();
        for j in ends {
            self.block.patch(j, end);
        }
    }

    /// The values of one CASE label (a value or a range), checked.
    fn case_label_range(&mut self, label: &CaseLabel, st: TypeId) -> Option<(i128, i128, Span)> {
        Some(match label {
            CaseLabel::Value(x) => {
                let v = self.case_label(x, st)?;
                (v, v, x.span)
            }
            CaseLabel::Range(a, b) => {
                let (Some(x), Some(y)) = (self.case_label(a, st), self.case_label(b, st)) else {
                    return None;
                };
                if y < x {
                    self.diags
                        .error("E408", a.span.to(b.span), "empty CASE range");
                    return None;
                }
                (x, y, a.span.to(b.span))
            }
        })
    }

    /// A jump taken when the selector in `sel` lies in `lo..=hi`.
    fn case_test(&mut self, sel: Slot, lo: i128, hi: i128, signed: bool) -> usize {
        if lo == hi {
            let c = self.block.const_slot(lo as u64);
            let d = self.block.temp();
            self.block.emit(if signed {
                Op::CmpS {
                    d,
                    a: sel,
                    b: c,
                    cmp: Cmp::Eq,
                }
            } else {
                Op::CmpU {
                    d,
                    a: sel,
                    b: c,
                    cmp: Cmp::Eq,
                }
            });
            self.branch_on_slot(d, true, Target::UNPATCHED)
        } else {
            let (cl, ch) = (
                self.block.const_slot(lo as u64),
                self.block.const_slot(hi as u64),
            );
            let (d1, d2, d) = (self.block.temp(), self.block.temp(), self.block.temp());
            if signed {
                self.block.emit(Op::CmpS {
                    d: d1,
                    a: sel,
                    b: cl,
                    cmp: Cmp::Ge,
                });
                self.block.emit(Op::CmpS {
                    d: d2,
                    a: sel,
                    b: ch,
                    cmp: Cmp::Le,
                });
            } else {
                self.block.emit(Op::CmpU {
                    d: d1,
                    a: sel,
                    b: cl,
                    cmp: Cmp::Ge,
                });
                self.block.emit(Op::CmpU {
                    d: d2,
                    a: sel,
                    b: ch,
                    cmp: Cmp::Le,
                });
            }
            self.block.emit(Op::And { d, a: d1, b: d2 });
            self.block.emit(Op::Jnz {
                c: d,
                t: Target::UNPATCHED,
            })
        }
    }

    /// A CASE label's constant value in the selector's type.
    fn case_label(&mut self, x: &Expr, st: crate::ir::type_table::TypeId) -> Option<i128> {
        let v = self.expr(x, Some(st));
        let Val::Const(c, t) = &v else {
            if !v.is_error() {
                self.diags
                    .error("E408", x.span, "CASE labels must be constants");
            }
            return None;
        };
        match self.const_as(c, *t, st) {
            Ok(Const::Bits(b)) => Some(super::consts::slot_to_int(
                b,
                self.scalar(st).unwrap_or(ElemType::Dint),
            )),
            _ => {
                self.mismatch(x.span, *t, st, "CASE label");
                None
            }
        }
    }
}
