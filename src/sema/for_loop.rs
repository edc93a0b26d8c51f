//! FOR loops: the control variable, the limit and step evaluated once, the
//! exit test, the back edge (a fused `ForNext` for small constant steps),
//! the array-fill idiom, and bounds checks proven by the loop range.

use super::body::BodyBuilder;
use super::consts::Const;
use super::consts::slot_to_int;
use super::emit::{LoopCtx, Ty, Val};
use super::stmt::negate;
use super::typeck::shift_of;
use crate::elementary::ElemType;
use crate::ir::op::{Cmp, Op, ShortArrayIdx, Slot, Target};
use crate::ir::type_table::TypeId;
use crate::ir::type_table::TypeKind;
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind, Stmt, StmtKind};

/// A FOR loop's control variable, limit and step.
struct ForLoop {
    /// Control variable slot.
    i: Slot,
    /// Its elementary type.
    e: ElemType,
    /// Constant limit as an immediate.
    lim_imm: Option<i32>,
    /// Otherwise the slot holding the limit.
    lim: Option<Slot>,
    /// Constant step.
    step_const: Option<i128>,
    /// Otherwise the slot holding the step.
    step_slot: Option<Slot>,
    /// Compare signed.
    signed: bool,
}

impl BodyBuilder<'_> {
    /// `FOR i := from TO to BY by DO body END_FOR`: the control variable is
    /// a local integer; constant steps give a rotated loop (a fused
    /// `ForNext` back edge when the limit fits), a runtime step tests its
    /// sign at the top.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn for_loop(
        &mut self,
        var: &Expr,
        from: &Expr,
        to: &Expr,
        by: Option<&Expr>,
        body: &[Stmt],
        span: Span,
    ) {
        let Some((i, e, vt)) = self.for_control(var) else {
            return;
        };
        let v0 = self.expr(from, Some(vt));
        let v0 = self.coerce(v0, vt, from.span, "FOR start");
        let vlim = self.expr(to, Some(vt));
        let vlim = self.coerce(vlim, vt, to.span, "FOR end");
        let vstep = match by {
            Some(b) => {
                let v = self.expr(b, Some(vt));
                self.coerce(v, vt, b.span, "FOR step")
            }
            None => Val::Const(Const::Bits(1), Ty::T(vt)),
        };
        if v0.is_error() || vlim.is_error() || vstep.is_error() {
            return;
        }
        let start = self.materialize(&v0);
        self.block.mov(i, start);
        let step_const = match &vstep {
            Val::Const(Const::Bits(b), _) => Some(slot_to_int(*b, e)),
            _ => None,
        };
        if step_const == Some(0) {
            self.diags.error("E407", span, "FOR step must not be zero");
            return;
        }
        let fl = self.for_bounds(i, e, &vlim, &vstep, step_const);
        if step_const == Some(1)
            && !self.model.unoptimized
            && e.is_signed_int()
            && let Some(lim) = fl.lim_imm
            && let ExprKind::Name(var) = &var.kind
        {
            self.fill_idiom(var, body, i, lim, shift_of(e));
        }
        // Test at the top: continue while i <= lim (step > 0) or i >= lim (step < 0).
        let test_at = self.block.here();
        let exit_jumps = self.for_entry_test(&fl);
        let body_at = self.block.here();
        self.block.loops.push(LoopCtx::default());
        self.block.for_vars.push(i);
        self.stmts(body);
        self.block.for_vars.pop();
        let cont = self.block.here();
        // With a constant start, limit and step the back edge is a ForNext
        // (below): the body sees only start..=limit.
        if let (Some(st), Some(l), Val::Const(Const::Bits(b0), _)) = (step_const, fl.lim_imm, &v0)
            && e.is_signed_int()
            && !self.model.unoptimized
            && i16::try_from(st).is_ok()
            && let Ok(s0) = i64::try_from(slot_to_int(*b0, e))
        {
            super::bounds::drop_proven_checks(
                &mut self.block.ops[body_at.index()..cont.index()],
                &self.out.arrays,
                i,
                s0.min(l as i64),
                s0.max(l as i64),
            );
        }
        self.block.span = span;
        self.for_back_edge(&fl, body_at, test_at);
        self.block.end_loop(cont, exit_jumps);
    }

    /// The FOR control variable: a writable local integer of this POU.
    /// Returns its slot, elementary type and type.
    fn for_control(&mut self, var: &Expr) -> Option<(Slot, ElemType, TypeId)> {
        let p = self.place(var)?;
        let super::emit::Place::Frame(i) = p.place else {
            self.diags.error(
                "E407",
                var.span,
                "the FOR control variable must be a local variable of this POU (or an element or field of one at a constant position)",
            );
            return None;
        };
        // A bit string counts as the unsigned integer of its width (CODESYS
        // arithmetic on bit strings, W350): `FOR nByte := 1 TO 8`.
        let counted = self.scalar(p.ty).map(|e| match super::bits_arith::unsigned_of(e) {
            Some(u) if !self.is_enum(p.ty) => {
                self.diags.warning(
                    "W350",
                    var.span,
                    "a bit string (BYTE..LWORD) as the FOR control variable is a CODESYS extension: \
                     it counts as the unsigned integer of the same width",
                );
                u
            }
            _ => e,
        });
        let Some(e) = counted.filter(|e| e.is_int()) else {
            let name = self.types.name(p.ty).to_string();
            self.diags.error(
                "E407",
                var.span,
                format!("the FOR control variable must be an integer, found {name}"),
            );
            return None;
        };
        if !p.writable {
            self.diags
                .error("E401", var.span, "the FOR control variable is read-only");
            return None;
        }
        self.note_input_write(&p, var.span);
        Some((i, e, p.ty))
    }

    /// The limit and step of the loop: immediates when constant, else
    /// copied into temporaries (evaluated once, before the loop).
    fn for_bounds(
        &mut self,
        i: Slot,
        e: ElemType,
        vlim: &Val,
        vstep: &Val,
        step_const: Option<i128>,
    ) -> ForLoop {
        let lim_imm = match vlim {
            Val::Const(Const::Bits(b), _) if e.is_signed_int() || e.bits() <= 32 => {
                i32::try_from(slot_to_int(*b, e)).ok()
            }
            _ => None,
        };
        let lim = if lim_imm.is_none() {
            let t = self.block.temp();
            let s = self.materialize(vlim);
            self.block.emit(Op::Mov { d: t, s });
            Some(t)
        } else {
            None
        };
        let step_slot = if step_const.is_none() {
            let t = self.block.temp();
            let s = self.materialize(vstep);
            self.block.emit(Op::Mov { d: t, s });
            Some(t)
        } else {
            None
        };
        ForLoop {
            i,
            e,
            lim_imm,
            lim,
            step_const,
            step_slot,
            signed: super::typeck::compares_signed(e),
        }
    }

    /// The exit test at the top of the loop; returns the exit jumps.
    fn for_entry_test(&mut self, fl: &ForLoop) -> Vec<usize> {
        match fl.step_const {
            Some(st) => {
                let cmp = if st > 0 { Cmp::Le } else { Cmp::Ge };
                vec![self.loop_test(fl, cmp, false)]
            }
            None => {
                // Runtime sign: positive steps test `<=`, negative `>=`.
                let sp = fl.step_slot.unwrap_or(fl.i);
                let neg = self.block.temp();
                self.block.emit(Op::CmpSI {
                    d: neg,
                    a: sp,
                    imm: 0,
                    cmp: Cmp::Lt,
                });
                let to_neg = self.block.emit(Op::Jnz {
                    c: neg,
                    t: Target::UNPATCHED,
                });
                let up = self.loop_test(fl, Cmp::Le, false);
                let to_body = self.block.emit(Op::Jmp {
                    t: Target::UNPATCHED,
                });
                let neg_at = self.block.here();
                self.block.patch(to_neg, neg_at);
                let down = self.loop_test(fl, Cmp::Ge, false);
                let body_at = self.block.here();
                self.block.patch(to_body, body_at);
                vec![up, down]
            }
        }
    }

    /// The back edge: a fused `ForNext` when the step is a small constant,
    /// else the increment and the test again (rotated) or a jump to the test.
    fn for_back_edge(&mut self, fl: &ForLoop, body_at: Target, test_at: Target) {
        let (i, e) = (fl.i, fl.e);
        let shift = shift_of(e);
        if let Some(st) = fl.step_const
            && e.is_signed_int()
            && let Ok(step) = i16::try_from(st)
            && (fl.lim_imm.is_some() || fl.lim.is_some())
        {
            self.block.emit(match (fl.lim_imm, fl.lim) {
                (Some(lim), _) => Op::ForNext {
                    i,
                    lim,
                    t: body_at,
                    step,
                    shift,
                },
                (None, Some(l)) => Op::ForNextS {
                    i,
                    lim: l,
                    t: body_at,
                    step,
                    shift,
                },
                (None, None) => Op::Nop,
            });
            return;
        }
        self.for_increment(fl);
        match fl.step_const {
            // Rotated loop: test again at the bottom and jump back to the body.
            Some(st) => {
                let cmp = if st > 0 { Cmp::Le } else { Cmp::Ge };
                let back = self.loop_test(fl, cmp, true);
                self.block.patch(back, body_at);
            }
            None => {
                self.block.emit(Op::Jmp { t: test_at });
            }
        }
    }

    /// `i := i + step`.
    fn for_increment(&mut self, fl: &ForLoop) {
        let (i, e) = (fl.i, fl.e);
        let shift = shift_of(e);
        let add = |b: Slot| {
            if e.is_signed_int() {
                Op::AddS {
                    d: i,
                    a: i,
                    b,
                    shift,
                }
            } else {
                Op::AddU {
                    d: i,
                    a: i,
                    b,
                    shift,
                }
            }
        };
        match (fl.step_const, fl.step_slot) {
            (Some(st), _) if i32::try_from(st).is_ok() && e.is_signed_int() => {
                self.block.emit(Op::AddSI {
                    d: i,
                    a: i,
                    imm: st as i32,
                    shift,
                });
            }
            (Some(st), _) => {
                let t = self.block.const_slot(st as u64);
                self.block.emit(add(t));
            }
            (None, Some(sp)) => {
                self.block.emit(add(sp));
            }
            (None, None) => {}
        }
    }

    /// Emits a jump taken when `(i cmp lim) == when`; returns it for patching.
    fn loop_test(&mut self, fl: &ForLoop, cmp: Cmp, when: bool) -> usize {
        let (i, signed) = (fl.i, fl.signed);
        // The fused branches jump when the comparison is FALSE.
        let jcmp = if when { negate(cmp) } else { cmp };
        let branch = |d: Slot| {
            if when {
                Op::Jnz {
                    c: d,
                    t: Target::UNPATCHED,
                }
            } else {
                Op::Jz {
                    c: d,
                    t: Target::UNPATCHED,
                }
            }
        };
        match (fl.lim_imm, fl.lim) {
            (Some(imm), _) if signed => self.block.emit(Op::JnCmpSI {
                a: i,
                imm,
                cmp: jcmp,
                t: Target::UNPATCHED,
            }),
            (Some(imm), _) => {
                let t = self.block.const_slot(imm as i64 as u64);
                let d = self.block.temp();
                self.block.emit(Op::CmpU { d, a: i, b: t, cmp });
                self.block.emit(branch(d))
            }
            (None, Some(l)) if signed => self.block.emit(Op::JnCmpS {
                a: i,
                b: l,
                cmp: jcmp,
                t: Target::UNPATCHED,
            }),
            (None, Some(l)) => {
                let d = self.block.temp();
                self.block.emit(Op::CmpU { d, a: i, b: l, cmp });
                self.block.emit(branch(d))
            }
            (None, None) => self.block.emit(Op::Jmp {
                t: Target::UNPATCHED,
            }),
        }
    }

    /// Loop idiom: a FOR body that only stores one loop-invariant value into
    /// `arr[i]` of a frame array gets a `FillElems` ahead of the loop, which
    /// does the whole loop at once when every index is in range (else the
    /// loop runs as written). The value is a constant or a plain variable,
    /// which the body cannot change.
    fn fill_idiom(
        &mut self,
        var: &crate::syntax::ast::Ident,
        body: &[Stmt],
        i: Slot,
        lim: i32,
        shift: u8,
    ) {
        let [
            Stmt {
                kind: StmtKind::Assign { target, value },
                ..
            },
        ] = body
        else {
            return;
        };
        let ExprKind::Index(base, idx) = &target.kind else {
            return;
        };
        let [
            Expr {
                kind: ExprKind::Name(iv),
                ..
            },
        ] = idx.as_slice()
        else {
            return;
        };
        let (ExprKind::Name(arr), true) = (&base.kind, iv.key() == var.key()) else {
            return;
        };
        let value_ok = match &value.kind {
            ExprKind::Literal(_) => true,
            ExprKind::Name(n) => n.key() != arr.key() && n.key() != var.key(),
            _ => false,
        };
        if !value_ok {
            return;
        }
        // Only for arrays whose element stores are plain slot writes. (A
        // name resolves without emitting code.)
        let mark = self.diags.len();
        let Some(p) = self.place(base) else {
            self.diags.truncate(mark);
            return;
        };
        let (super::emit::Place::Frame(o), TypeKind::Array { dims, elem }) =
            (p.place, self.types.get(p.ty).kind.clone())
        else {
            return;
        };
        let scalar =
            self.scalar(elem).is_some_and(|e| !e.is_string()) && !self.contains_strings(elem);
        if dims.len() != 1 || !scalar || self.types.size(elem) != 1 || !p.writable || p.input_image
        {
            return;
        }
        let v = self.expr(value, Some(elem));
        let v = self.coerce(v, elem, value.span, "assignment");
        if v.is_error() || self.diags.len() != mark {
            // The loop body reports the problem itself.
            self.diags.truncate(mark);
            return;
        }
        let v = self.materialize(&v);
        let desc = self.out.arrays.len();
        let Ok(desc) = u16::try_from(desc).map(ShortArrayIdx::new) else {
            return;
        };
        self.out.arrays.push(crate::ir::image::ArrayDesc {
            offset: o.get(),
            lo: dims[0].lo,
            len: dims[0].len(),
            stride: 1,
            span: target.span,
        });
        self.block.emit(Op::FillElems {
            i,
            v,
            lim,
            desc,
            shift,
        });
    }
}
