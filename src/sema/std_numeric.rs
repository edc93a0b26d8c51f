//! The numeric, selection, comparison and bit-string standard functions
//! (ABS, SQRT, TRUNC, SEL, MIN/MAX, LIMIT, MUX, GT..., SHL..., NOT, ...).

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use crate::elementary::{ElemType, Family};
use crate::ir::op::{Conv, MathFn, Op, ShiftKind, Slot};
use crate::ir::type_table::TypeTable;
use crate::source::Span;
use crate::syntax::ast::BinaryOp;

impl BodyBuilder<'_> {
    /// ADD, MUL, ... and the time functions: the operator folded over the inputs.
    pub(super) fn std_fold_binary(
        &mut self,
        op: BinaryOp,
        vals: Vec<(Val, Span)>,
        span: Span,
    ) -> Val {
        let mut it = vals.into_iter();
        let Some((mut acc, _)) = it.next() else {
            return Val::error();
        };
        for (v, _) in it {
            acc = self.binary_vals(op, acc, v, span);
        }
        acc
    }

    /// NOT of a BOOL or bit string.
    pub(super) fn std_not(&mut self, mut vals: Vec<(Val, Span)>) -> Val {
        let bool_t = TypeTable::elem(ElemType::Bool);
        let (v, s) = vals.remove(0);
        let expr_ty = v.ty();
        match v {
            Val::Const(Const::Bits(b), Ty::T(t)) if t == bool_t => {
                Val::Const(Const::Bits(b ^ 1), Ty::T(t))
            }
            _ => {
                let Some(t) = expr_ty
                    .id()
                    .filter(|t| self.scalar(*t).is_some_and(|e| e.is_bit()))
                else {
                    self.diags
                        .error("E302", s, "NOT needs a BOOL or bit string");
                    return Val::error();
                };
                let e = self.scalar(t).unwrap_or(ElemType::Bool);
                let a = self.materialize(&v);
                let d = self.block.temp();
                self.block.emit(if e == ElemType::Bool {
                    Op::NotB { d, a }
                } else {
                    Op::NotW {
                        d,
                        a,
                        shift: super::typeck::shift_of(e),
                    }
                });
                Val::Slot(d, t)
            }
        }
    }

    /// ABS of a number (unsigned integers are their own absolute value).
    pub(super) fn std_abs(&mut self, mut vals: Vec<(Val, Span)>) -> Val {
        let (v, s) = vals.remove(0);
        match v {
            Val::Const(Const::Int(i), t) => Val::Const(Const::Int(i.abs()), t),
            Val::Const(Const::Real(r), t) => Val::Const(Const::Real(r.abs()), t),
            _ => {
                let Some(t) = v.ty().id() else {
                    return Val::error();
                };
                let Some(e) = self.scalar(t).filter(|e| e.is_num()) else {
                    self.diags.error("E302", s, "ABS needs a number");
                    return Val::error();
                };
                let a = self.materialize(&v);
                let d = self.block.temp();
                self.block.emit(match e {
                    ElemType::Real => Op::MathF32 {
                        d,
                        a,
                        f: MathFn::Abs,
                    },
                    ElemType::Lreal => Op::MathF64 {
                        d,
                        a,
                        f: MathFn::Abs,
                    },
                    _ if e.is_unsigned_int() => Op::Mov { d, s: a },
                    _ => Op::AbsS {
                        d,
                        a,
                        shift: super::typeck::shift_of(e),
                    },
                });
                Val::Slot(d, t)
            }
        }
    }

    /// SQRT, SIN, EXP, ...: REAL or LREAL (integers widen to the smallest that holds them).
    pub(super) fn std_math(&mut self, m: MathFn, mut vals: Vec<(Val, Span)>, fname: &str) -> Val {
        let (v, s) = vals.remove(0);
        if let Val::Const(c, Ty::AnyInt | Ty::AnyReal) = &v {
            let x = match c {
                Const::Int(i) => *i as f64,
                Const::Real(r) => *r,
                _ => 0.0,
            };
            return Val::Const(Const::Real(m.apply_f64(x)), Ty::AnyReal);
        }
        let t = v.ty().id().unwrap_or(TypeTable::error());
        let e = self.scalar(t);
        let target = match e {
            Some(ElemType::Real) => ElemType::Real,
            Some(ElemType::Lreal) => ElemType::Lreal,
            Some(x) if x.widens_to(ElemType::Real) => ElemType::Real,
            Some(x) if x.widens_to(ElemType::Lreal) => ElemType::Lreal,
            _ => {
                let n = self.types.name(t).to_string();
                self.diags.error(
                    "E302",
                    s,
                    format!("{fname} needs a REAL or LREAL, found {n}"),
                );
                return Val::error();
            }
        };
        let rt = TypeTable::elem(target);
        let v = self.coerce(v, rt, s, fname);
        let a = self.materialize(&v);
        let d = self.block.temp();
        self.block.emit(if target == ElemType::Real {
            Op::MathF32 { d, a, f: m }
        } else {
            Op::MathF64 { d, a, f: m }
        });
        Val::Slot(d, rt)
    }

    /// TRUNC (and `*_TRUNC_*`): a real to an integer, toward zero.
    pub(super) fn std_trunc(
        &mut self,
        to: Option<ElemType>,
        mut vals: Vec<(Val, Span)>,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Val {
        let (v, s) = vals.remove(0);
        let to = to
            .or_else(|| expect.and_then(|t| self.scalar(t)).filter(|e| e.is_int()))
            .unwrap_or(ElemType::Dint);
        let from = match v.ty() {
            Ty::AnyReal | Ty::AnyInt => ElemType::Lreal,
            Ty::T(t) => self.scalar(t).unwrap_or(ElemType::Lreal),
        };
        if !from.is_real() {
            self.diags.error("E302", s, "TRUNC needs a REAL or LREAL");
            return Val::error();
        }
        let v = self.coerce(v, TypeTable::elem(from), s, "TRUNC");
        let conv = match (from, to.is_signed_int()) {
            (ElemType::Real, true) => Conv::TruncF32ToS(super::typeck::shift_of(to)),
            (ElemType::Real, false) => Conv::TruncF32ToU(super::typeck::shift_of(to)),
            (_, true) => Conv::TruncF64ToS(super::typeck::shift_of(to)),
            (_, false) => Conv::TruncF64ToU(super::typeck::shift_of(to)),
        };
        self.apply_conv(v, conv, to, s)
    }

    /// SEL(G, IN0, IN1): a conditional move (folded when G is constant).
    pub(super) fn std_sel(
        &mut self,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
        span: Span,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Val {
        let bool_t = TypeTable::elem(ElemType::Bool);
        let (b, _) = vals.pop().unwrap_or((Val::error(), span));
        let (a, _) = vals.pop().unwrap_or((Val::error(), span));
        let (g, gs) = vals.pop().unwrap_or((Val::error(), span));
        let g = self.sel_selector(g, gs);
        if g.ty() != Ty::T(bool_t) {
            self.diags.error("E301", gs, "SEL: G must be BOOL");
            return Val::error();
        }
        let Some(t) = self.unify_all(&[a.ty(), b.ty()], span, fname, expect) else {
            return Val::error();
        };
        if let Val::Const(Const::Bits(c), _) = g {
            let pick = if c != 0 { b } else { a };
            return self.coerce(pick, t, span, fname);
        }
        let gs_slot = self.materialize(&g);
        let a = self.coerce(a, t, span, fname);
        let b = self.coerce(b, t, span, fname);
        let (sa, sb) = (self.materialize(&a), self.materialize(&b));
        let d = self.block.temp();
        self.block.emit(Op::Mov { d, s: sa });
        self.block.emit(Op::CMov {
            d,
            c: gs_slot,
            s: sb,
        });
        self.block.last_def = None;
        Val::Slot(d, t)
    }

    /// MIN or MAX over two or more inputs of one type.
    pub(super) fn std_min_max(
        &mut self,
        max: bool,
        vals: Vec<(Val, Span)>,
        fname: &str,
        span: Span,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Val {
        let vals = self.enum_args_as_ints(vals);
        let tys: Vec<Ty> = vals.iter().map(|(v, _)| v.ty()).collect();
        let Some(t) = self.unify_all(&tys, span, fname, expect) else {
            return Val::error();
        };
        let mut acc: Option<Slot> = None;
        for (v, s) in vals {
            let v = self.coerce(v, t, s, fname);
            let x = self.materialize(&v);
            acc = Some(match acc {
                None => x,
                Some(a) => self.minmax(t, a, x, max),
            });
        }
        Val::Slot(acc.unwrap_or(Slot::new(0)), t)
    }

    /// LIMIT(MN, IN, MX) as MIN(MAX(IN, MN), MX).
    pub(super) fn std_limit(
        &mut self,
        vals: Vec<(Val, Span)>,
        fname: &str,
        span: Span,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Val {
        let vals = self.enum_args_as_ints(vals);
        let tys: Vec<Ty> = vals.iter().map(|(v, _)| v.ty()).collect();
        let Some(t) = self.unify_all(&tys, span, fname, expect) else {
            return Val::error();
        };
        let mut slots = Vec::new();
        for (v, s) in vals {
            let v = self.coerce(v, t, s, fname);
            slots.push(self.materialize(&v));
        }
        let lo = self.minmax(t, slots[1], slots[0], true);
        let r = self.minmax(t, lo, slots[2], false);
        Val::Slot(r, t)
    }

    /// MUX(K, IN0, ...): the inputs copied to consecutive slots, K selects.
    pub(super) fn std_mux(
        &mut self,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
        span: Span,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Val {
        let (k, ks) = vals.remove(0);
        let k_ok = match k.ty() {
            Ty::AnyInt => true,
            Ty::T(t) => self.scalar(t).is_some_and(|e| e.is_int()),
            _ => false,
        };
        if !k_ok {
            self.diags.error("E301", ks, "MUX: K must be an integer");
            return Val::error();
        }
        let tys: Vec<Ty> = vals.iter().map(|(v, _)| v.ty()).collect();
        let Some(t) = self.unify_all(&tys, span, fname, expect) else {
            return Val::error();
        };
        let ksl = self.materialize(&k);
        let Ok(n) = u16::try_from(vals.len()) else {
            self.diags
                .error("E404", span, "MUX takes at most 65535 inputs");
            return Val::error();
        };
        let mut slots = Vec::new();
        for (v, s) in vals {
            let v = self.coerce(v, t, s, fname);
            slots.push(self.materialize(&v));
        }
        let first = self.block.temps(n as u32);
        for (i, s) in slots.into_iter().enumerate() {
            self.block.emit(Op::Mov {
                d: first.offset(i as u32),
                s,
            });
        }
        let d = self.block.temp();
        self.block.emit(Op::Mux {
            d,
            k: ksl,
            first,
            n,
        });
        Val::Slot(d, t)
    }

    /// GT, EQ, ... over a chain of inputs: the pairwise comparisons ANDed.
    pub(super) fn std_compare(&mut self, op: BinaryOp, vals: Vec<(Val, Span)>, span: Span) -> Val {
        let mut result: Option<Val> = None;
        for w in vals.windows(2) {
            let c = self.binary_vals(op, w[0].0.clone(), w[1].0.clone(), span);
            result = Some(match result {
                None => c,
                Some(r) => self.binary_vals(BinaryOp::And, r, c, span),
            });
        }
        result.unwrap_or_else(Val::error)
    }

    /// SHL, SHR, ROL, ROR of a bit string by N.
    pub(super) fn std_shift(
        &mut self,
        kind: ShiftKind,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
        span: Span,
    ) -> Val {
        let (n, ns) = vals.pop().unwrap_or((Val::error(), span));
        let (mut v, vs) = vals.pop().unwrap_or((Val::error(), span));
        // TwinCAT 3 and CODESYS shift an untyped constant in a register's
        // width (`SHL(1, nBit)` for a 32-bit mask): a DWORD, or an LWORD
        // for a constant beyond 32 bits.
        if let Val::Const(Const::Int(i), Ty::AnyInt) = v
            && self.model.codesys_files.contains(&vs.file)
            && i >= 0
        {
            let e = if i > u32::MAX as i128 {
                ElemType::Lword
            } else {
                ElemType::Dword
            };
            v = self.coerce(v, TypeTable::elem(e), vs, fname);
        }
        let Some(t) = v.ty().id() else {
            self.diags.error(
                "E301",
                vs,
                format!("{fname}: IN needs a typed bit string (e.g. WORD#16#00FF)"),
            );
            return Val::error();
        };
        let Some(e) = self
            .scalar(t)
            .filter(|e| e.family() == Family::Bits || e.is_int())
        else {
            self.diags
                .error("E302", vs, format!("{fname}: IN must be a bit string"));
            return Val::error();
        };
        let n_ok = match n.ty() {
            Ty::AnyInt => true,
            Ty::T(t) => self.scalar(t).is_some_and(|e| e.is_int()),
            _ => false,
        };
        // CODESYS also counts with a bit string (BYTE..LWORD).
        let n_bits = match n.ty() {
            Ty::T(t) => {
                !self.is_enum(t) && self.scalar(t).is_some_and(|e| e.family() == Family::Bits)
            }
            _ => false,
        };
        if n_bits {
            self.diags.warning(
                "W352",
                ns,
                format!("{fname}: a bit string as the shift count N is a CODESYS extension"),
            );
        }
        if !n_ok && !n_bits {
            self.diags
                .error("E301", ns, format!("{fname}: N must be an integer"));
            return Val::error();
        }
        let a = self.materialize(&v);
        let b = self.materialize(&n);
        let d = self.block.temp();
        self.block.emit(Op::Shift {
            d,
            a,
            b,
            kind,
            bits: e.bits() as u8,
        });
        if e.is_signed_int() {
            let w = self.block.temp();
            self.block.emit(Op::Convert {
                d: w,
                a: d,
                conv: Conv::WrapS(super::typeck::shift_of(e)),
            });
            return Val::Slot(w, t);
        }
        Val::Slot(d, t)
    }

    /// CONCAT_DATE_TOD: a DATE and a TIME_OF_DAY added into a DT.
    pub(super) fn std_concat_date_tod(
        &mut self,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
        span: Span,
    ) -> Val {
        let (t, _) = vals.pop().unwrap_or((Val::error(), span));
        let (d, ds) = vals.pop().unwrap_or((Val::error(), span));
        // CONCAT_LDATE_LTOD works on the long types and gives an LDT.
        let long = fname.to_ascii_uppercase().contains("LDATE");
        let (de, te, re) = if long {
            (ElemType::Ldate, ElemType::Ltod, ElemType::Ldt)
        } else {
            (ElemType::Date, ElemType::Tod, ElemType::Dt)
        };
        let dt = TypeTable::elem(de);
        let tt = TypeTable::elem(te);
        let d = self.coerce(d, dt, ds, fname);
        let t = self.coerce(t, tt, ds, fname);
        let (a, b) = (self.materialize(&d), self.materialize(&t));
        let r = self.block.temp();
        self.block.emit(Op::AddS {
            d: r,
            a,
            b,
            shift: 0,
        });
        Val::Slot(r, TypeTable::elem(re))
    }

    /// The common type of the arguments; untyped literals alone take the
    /// type the context expects (`i := MAX(1, 2)` with `i : INT` is INT).
    fn unify_all(
        &mut self,
        tys: &[Ty],
        span: Span,
        fname: &str,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Option<crate::ir::type_table::TypeId> {
        let mut acc = *tys.first()?;
        for t in &tys[1..] {
            match self.unify(acc, *t) {
                Some(u) => acc = u,
                None => {
                    let (a, b) = (self.ty_name(acc), self.ty_name(*t));
                    self.diags
                        .error("E306", span, format!("{fname} cannot mix {a} and {b}"));
                    return None;
                }
            }
        }
        if let (Ty::AnyInt | Ty::AnyReal, Some(e)) = (acc, expect)
            && let Some(Ty::T(t)) = self.unify(acc, Ty::T(e))
        {
            return Some(t);
        }
        Some(self.default_type(acc, None))
    }

    fn minmax(&mut self, t: crate::ir::type_table::TypeId, a: Slot, b: Slot, max: bool) -> Slot {
        let e = self.scalar(t).unwrap_or(ElemType::Dint);
        let d = self.block.temp();
        self.block.emit(match e {
            ElemType::Real => Op::MinMaxF32 { d, a, b, max },
            ElemType::Lreal => Op::MinMaxF64 { d, a, b, max },
            _ if super::typeck::compares_signed(e) => Op::MinMaxS { d, a, b, max },
            _ => Op::MinMaxU { d, a, b, max },
        });
        d
    }
}
