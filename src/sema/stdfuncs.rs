//! The IEC standard functions: arithmetic, selection, comparison, bit
//! strings, type conversions, time arithmetic and strings. They lower to
//! typed instructions directly (no call overhead).

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Fcx, Ty, Val};
use crate::ir::op::{Conv, MathFn, Op, ShiftKind, StrFn};
use crate::ir::types::{TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Arg, BinaryOp, Ident};
use crate::types::{ElemType, Family};

/// The kinds of standard function.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Std {
    Binary(BinaryOp, bool),
    Move,
    Abs,
    Math(MathFn),
    Trunc(Option<ElemType>),
    Sel,
    MinMax(bool),
    Limit,
    Mux,
    Compare(BinaryOp),
    Shift(ShiftKind),
    Not,
    Convert(Option<ElemType>, ElemType),
    BcdTo(ElemType),
    ToBcd(Option<ElemType>),
    Time(BinaryOp),
    ConcatDateTod,
    Str(StrFn),
    Concat,
    Clock,
}

fn elem(name: &str) -> Option<ElemType> {
    ElemType::from_name(name)
}

fn classify(name: &str) -> Option<Std> {
    let n = name.to_ascii_uppercase();
    use BinaryOp as B;
    let direct = match n.as_str() {
        "ADD" => Some(Std::Binary(B::Add, true)),
        "MUL" => Some(Std::Binary(B::Mul, true)),
        "SUB" => Some(Std::Binary(B::Sub, false)),
        "DIV" => Some(Std::Binary(B::Div, false)),
        "MOD" => Some(Std::Binary(B::Mod, false)),
        "EXPT" => Some(Std::Binary(B::Pow, false)),
        "AND" => Some(Std::Binary(B::And, true)),
        "OR" => Some(Std::Binary(B::Or, true)),
        "XOR" => Some(Std::Binary(B::Xor, true)),
        "NOT" => Some(Std::Not),
        "MOVE" => Some(Std::Move),
        "ABS" => Some(Std::Abs),
        "SQRT" => Some(Std::Math(MathFn::Sqrt)),
        "LN" => Some(Std::Math(MathFn::Ln)),
        "LOG" => Some(Std::Math(MathFn::Log)),
        "EXP" => Some(Std::Math(MathFn::Exp)),
        "SIN" => Some(Std::Math(MathFn::Sin)),
        "COS" => Some(Std::Math(MathFn::Cos)),
        "TAN" => Some(Std::Math(MathFn::Tan)),
        "ASIN" => Some(Std::Math(MathFn::Asin)),
        "ACOS" => Some(Std::Math(MathFn::Acos)),
        "ATAN" => Some(Std::Math(MathFn::Atan)),
        "TRUNC" => Some(Std::Trunc(None)),
        "SEL" => Some(Std::Sel),
        "MAX" => Some(Std::MinMax(true)),
        "MIN" => Some(Std::MinMax(false)),
        "LIMIT" => Some(Std::Limit),
        "MUX" => Some(Std::Mux),
        "GT" => Some(Std::Compare(B::Gt)),
        "GE" => Some(Std::Compare(B::Ge)),
        "EQ" => Some(Std::Compare(B::Eq)),
        "LE" => Some(Std::Compare(B::Le)),
        "LT" => Some(Std::Compare(B::Lt)),
        "NE" => Some(Std::Compare(B::Ne)),
        "SHL" => Some(Std::Shift(ShiftKind::Shl)),
        "SHR" => Some(Std::Shift(ShiftKind::Shr)),
        "ROL" => Some(Std::Shift(ShiftKind::Rol)),
        "ROR" => Some(Std::Shift(ShiftKind::Ror)),
        "ADD_TIME" | "ADD_LTIME" | "ADD_TOD_TIME" | "ADD_DT_TIME" | "ADD_LTOD_LTIME"
        | "ADD_LDT_LTIME" => Some(Std::Time(B::Add)),
        "SUB_TIME" | "SUB_LTIME" | "SUB_DATE_DATE" | "SUB_TOD_TIME" | "SUB_TOD_TOD"
        | "SUB_DT_TIME" | "SUB_DT_DT" | "SUB_LDATE_LDATE" | "SUB_LTOD_LTIME" | "SUB_LTOD_LTOD"
        | "SUB_LDT_LTIME" | "SUB_LDT_LDT" => Some(Std::Time(B::Sub)),
        "MUL_TIME" | "MUL_LTIME" => Some(Std::Time(B::Mul)),
        "DIV_TIME" | "DIV_LTIME" => Some(Std::Time(B::Div)),
        "CONCAT_DATE_TOD" | "CONCAT_LDATE_LTOD" => Some(Std::ConcatDateTod),
        "LEN" => Some(Std::Str(StrFn::Len)),
        "LEFT" => Some(Std::Str(StrFn::Left)),
        "RIGHT" => Some(Std::Str(StrFn::Right)),
        "MID" => Some(Std::Str(StrFn::Mid)),
        "INSERT" => Some(Std::Str(StrFn::Insert)),
        "DELETE" => Some(Std::Str(StrFn::Delete)),
        "REPLACE" => Some(Std::Str(StrFn::Replace)),
        "FIND" => Some(Std::Str(StrFn::Find)),
        "CONCAT" => Some(Std::Concat),
        "PLC_CLOCK" => Some(Std::Clock),
        _ => None,
    };
    if direct.is_some() {
        return direct;
    }
    if let Some(to) = n.strip_prefix("TRUNC_").and_then(elem) {
        return to.is_int().then_some(Std::Trunc(Some(to)));
    }
    if let Some((from, to)) = n.split_once("_TRUNC_") {
        let (f, t) = (elem(from)?, elem(to)?);
        return (f.is_real() && t.is_int()).then_some(Std::Trunc(Some(t)));
    }
    if let Some(to) = n.strip_prefix("BCD_TO_").and_then(elem) {
        return to.is_int().then_some(Std::BcdTo(to));
    }
    if let Some((from, to)) = n.split_once("_BCD_TO_") {
        let (f, t) = (elem(from)?, elem(to)?);
        return (f.family() == Family::Bits && t.is_int()).then_some(Std::BcdTo(t));
    }
    if let Some(from) = n.strip_suffix("_TO_BCD") {
        return elem(from).filter(|e| e.is_int()).map(|_| Std::ToBcd(None));
    }
    if let Some((from, to)) = n.split_once("_TO_BCD_") {
        let (f, t) = (elem(from)?, elem(to)?);
        return (f.is_int() && t.family() == Family::Bits).then_some(Std::ToBcd(Some(t)));
    }
    if let Some(to) = n.strip_prefix("TO_").and_then(elem) {
        return Some(Std::Convert(None, to));
    }
    if let Some((from, to)) = n.split_once("_TO_") {
        return Some(Std::Convert(Some(elem(from)?), elem(to)?));
    }
    None
}

/// True if `name` is a standard function (or a plcrun extension function).
pub fn is_standard_function(name: &str) -> bool {
    classify(name).is_some()
}

/// Formal parameter names of a standard function, in positional order.
fn param_names(std: Std, n: usize) -> Vec<String> {
    let ins = |n: usize| (1..=n).map(|i| format!("IN{i}")).collect::<Vec<_>>();
    let v = |x: &[&str]| x.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    match std {
        Std::Binary(_, true) | Std::MinMax(_) | Std::Compare(_) | Std::Concat => ins(n.max(2)),
        Std::Binary(_, false) | Std::Time(_) | Std::ConcatDateTod => ins(2),
        Std::Sel => v(&["G", "IN0", "IN1"]),
        Std::Limit => v(&["MN", "IN", "MX"]),
        Std::Mux => {
            let mut p = v(&["K"]);
            p.extend((0..n.saturating_sub(1)).map(|i| format!("IN{i}")));
            p
        }
        Std::Shift(_) => v(&["IN", "N"]),
        Std::Str(StrFn::Len) => v(&["IN"]),
        Std::Str(StrFn::Left | StrFn::Right) => v(&["IN", "L"]),
        Std::Str(StrFn::Mid | StrFn::Delete) => v(&["IN", "L", "P"]),
        Std::Str(StrFn::Insert) => v(&["IN1", "IN2", "P"]),
        Std::Str(StrFn::Replace) => v(&["IN1", "IN2", "L", "P"]),
        Std::Str(StrFn::Find) => v(&["IN1", "IN2"]),
        Std::Str(StrFn::Concat) => ins(2),
        Std::Clock => Vec::new(),
        _ => v(&["IN"]),
    }
}

impl BodyBuilder<'_> {
    /// Checks and emits a call of a standard function; `None` if `id` is not one.
    pub(super) fn std_call(
        &mut self,
        f: &mut Fcx,
        id: &Ident,
        args: &[Arg],
        span: Span,
        expect: Option<crate::ir::types::TypeId>,
    ) -> Option<Val> {
        let std = classify(&id.name)?;
        let fname = id.name.to_ascii_uppercase();
        // Order the argument expressions by parameter.
        let names = param_names(std, args.len());
        let mut exprs: Vec<Option<&crate::syntax::ast::Expr>> = vec![None; names.len()];
        let formal = args.iter().any(|a| !matches!(a, Arg::Positional(_)));
        for (i, a) in args.iter().enumerate() {
            match a {
                Arg::Positional(e) => {
                    if formal {
                        self.diags.error(
                            "E411",
                            e.span,
                            "a call must use either formal or non-formal arguments, not both",
                        );
                        return Some(Val::error());
                    }
                    if i < exprs.len() {
                        exprs[i] = Some(e);
                    } else {
                        exprs.push(Some(e));
                    }
                }
                Arg::Input { name, value } => {
                    match names
                        .iter()
                        .position(|n| n.eq_ignore_ascii_case(&name.name))
                    {
                        Some(k) => exprs[k] = Some(value),
                        None => {
                            self.diags.error(
                                "E403",
                                name.span,
                                format!("{fname} has no input `{}`", name.name),
                            );
                            return Some(Val::error());
                        }
                    }
                }
                Arg::Output { name, .. } => {
                    self.diags.error(
                        "E403",
                        name.span,
                        format!("{fname} has no output `{}`", name.name),
                    );
                    return Some(Val::error());
                }
            }
        }
        let extensible = matches!(
            std,
            Std::Binary(_, true) | Std::MinMax(_) | Std::Compare(_) | Std::Concat | Std::Mux
        );
        let min = match std {
            Std::Clock => 0,
            Std::Mux => 2,
            _ if extensible => 2,
            _ => names.len(),
        };
        let given: Vec<&crate::syntax::ast::Expr> = exprs.iter().flatten().copied().collect();
        if given.len() < min
            || (!extensible && given.len() != names.len())
            || given.len() != exprs.len()
        {
            let expected = if extensible {
                format!("at least {min}")
            } else {
                names.len().to_string()
            };
            self.diags.error(
                "E404",
                span,
                format!(
                    "{fname} takes {expected} argument(s), {} given",
                    given.len()
                ),
            );
            return Some(Val::error());
        }
        // Evaluate in order.
        let mut vals: Vec<(Val, Span)> = Vec::new();
        for e in &given {
            let hint = match std {
                Std::Binary(..) | Std::MinMax(_) | Std::Move | Std::Sel | Std::Limit | Std::Mux => {
                    expect
                }
                _ => None,
            };
            let v = self.expr(f, e, hint);
            if v.is_error() {
                return Some(Val::error());
            }
            vals.push((v, e.span));
        }
        Some(self.std_emit(f, std, &fname, vals, span, expect))
    }

    fn std_emit(
        &mut self,
        f: &mut Fcx,
        std: Std,
        fname: &str,
        mut vals: Vec<(Val, Span)>,
        span: Span,
        expect: Option<crate::ir::types::TypeId>,
    ) -> Val {
        let bool_t = TypeTable::elem(ElemType::Bool);
        match std {
            Std::Binary(op, _) | Std::Time(op) => {
                let mut it = vals.into_iter();
                let Some((mut acc, _)) = it.next() else {
                    return Val::error();
                };
                for (v, _) in it {
                    acc = self.binary_vals(f, op, acc, v, span);
                }
                acc
            }
            Std::Move => vals.remove(0).0,
            Std::Not => {
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
                        let a = self.materialize(f, &v);
                        let d = f.temp();
                        f.emit(if e == ElemType::Bool {
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
            Std::Abs => {
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
                        let a = self.materialize(f, &v);
                        let d = f.temp();
                        f.emit(match e {
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
            Std::Math(m) => {
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
                let v = self.coerce(f, v, rt, s, fname);
                let a = self.materialize(f, &v);
                let d = f.temp();
                f.emit(if target == ElemType::Real {
                    Op::MathF32 { d, a, f: m }
                } else {
                    Op::MathF64 { d, a, f: m }
                });
                Val::Slot(d, rt)
            }
            Std::Trunc(to) => {
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
                let v = self.coerce(f, v, TypeTable::elem(from), s, "TRUNC");
                let conv = match (from, to.is_signed_int()) {
                    (ElemType::Real, true) => Conv::TruncF32ToS(super::typeck::shift_of(to)),
                    (ElemType::Real, false) => Conv::TruncF32ToU(super::typeck::shift_of(to)),
                    (_, true) => Conv::TruncF64ToS(super::typeck::shift_of(to)),
                    (_, false) => Conv::TruncF64ToU(super::typeck::shift_of(to)),
                };
                self.apply_conv(f, v, conv, to, s)
            }
            Std::Sel => {
                let (b, _) = vals.pop().unwrap_or((Val::error(), span));
                let (a, _) = vals.pop().unwrap_or((Val::error(), span));
                let (g, gs) = vals.pop().unwrap_or((Val::error(), span));
                if g.ty() != Ty::T(bool_t) {
                    self.diags.error("E301", gs, "SEL: G must be BOOL");
                    return Val::error();
                }
                let Some(t) = self.unify_all(&[a.ty(), b.ty()], span, fname, expect) else {
                    return Val::error();
                };
                if let Val::Const(Const::Bits(c), _) = g {
                    let pick = if c != 0 { b } else { a };
                    return self.coerce(f, pick, t, span, fname);
                }
                let gs_slot = self.materialize(f, &g);
                let a = self.coerce(f, a, t, span, fname);
                let b = self.coerce(f, b, t, span, fname);
                let (sa, sb) = (self.materialize(f, &a), self.materialize(f, &b));
                let d = f.temp();
                f.emit(Op::Mov { d, s: sa });
                f.emit(Op::CMov {
                    d,
                    c: gs_slot,
                    s: sb,
                });
                f.last_def = None;
                Val::Slot(d, t)
            }
            Std::MinMax(max) => {
                let tys: Vec<Ty> = vals.iter().map(|(v, _)| v.ty()).collect();
                let Some(t) = self.unify_all(&tys, span, fname, expect) else {
                    return Val::error();
                };
                let mut acc: Option<u32> = None;
                for (v, s) in vals {
                    let v = self.coerce(f, v, t, s, fname);
                    let x = self.materialize(f, &v);
                    acc = Some(match acc {
                        None => x,
                        Some(a) => self.minmax(f, t, a, x, max),
                    });
                }
                Val::Slot(acc.unwrap_or(0), t)
            }
            Std::Limit => {
                let tys: Vec<Ty> = vals.iter().map(|(v, _)| v.ty()).collect();
                let Some(t) = self.unify_all(&tys, span, fname, expect) else {
                    return Val::error();
                };
                let mut slots = Vec::new();
                for (v, s) in vals {
                    let v = self.coerce(f, v, t, s, fname);
                    slots.push(self.materialize(f, &v));
                }
                let lo = self.minmax(f, t, slots[1], slots[0], true);
                let r = self.minmax(f, t, lo, slots[2], false);
                Val::Slot(r, t)
            }
            Std::Mux => {
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
                let ksl = self.materialize(f, &k);
                let Ok(n) = u16::try_from(vals.len()) else {
                    self.diags
                        .error("E404", span, "MUX takes at most 65535 inputs");
                    return Val::error();
                };
                let mut slots = Vec::new();
                for (v, s) in vals {
                    let v = self.coerce(f, v, t, s, fname);
                    slots.push(self.materialize(f, &v));
                }
                let first = f.temps(n as u32);
                for (i, s) in slots.into_iter().enumerate() {
                    f.emit(Op::Mov {
                        d: first + i as u32,
                        s,
                    });
                }
                let d = f.temp();
                f.emit(Op::Mux {
                    d,
                    k: ksl,
                    first,
                    n,
                });
                Val::Slot(d, t)
            }
            Std::Compare(op) => {
                let mut result: Option<Val> = None;
                for w in vals.windows(2) {
                    let c = self.binary_vals(f, op, w[0].0.clone(), w[1].0.clone(), span);
                    result = Some(match result {
                        None => c,
                        Some(r) => self.binary_vals(f, BinaryOp::And, r, c, span),
                    });
                }
                result.unwrap_or_else(Val::error)
            }
            Std::Shift(kind) => {
                let (n, ns) = vals.pop().unwrap_or((Val::error(), span));
                let (v, vs) = vals.pop().unwrap_or((Val::error(), span));
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
                if !n_ok {
                    self.diags
                        .error("E301", ns, format!("{fname}: N must be an integer"));
                    return Val::error();
                }
                let a = self.materialize(f, &v);
                let b = self.materialize(f, &n);
                let d = f.temp();
                f.emit(Op::Shift {
                    d,
                    a,
                    b,
                    kind,
                    bits: e.bits() as u8,
                });
                if e.is_signed_int() {
                    let w = f.temp();
                    f.emit(Op::Convert {
                        d: w,
                        a: d,
                        conv: Conv::WrapS(super::typeck::shift_of(e)),
                    });
                    return Val::Slot(w, t);
                }
                Val::Slot(d, t)
            }
            Std::Convert(from, to) => {
                let (v, s) = vals.remove(0);
                let actual = match v.ty() {
                    Ty::T(t) => self.scalar(t),
                    Ty::AnyInt => from.or(Some(ElemType::Lint)),
                    Ty::AnyReal => from.or(Some(ElemType::Lreal)),
                };
                let Some(actual) = actual else {
                    self.diags
                        .error("E302", s, format!("{fname} cannot convert this value"));
                    return Val::error();
                };
                let from = from.unwrap_or(actual);
                let v = self.coerce(f, v, TypeTable::elem(from), s, fname);
                if v.is_error() {
                    return v;
                }
                self.convert(f, v, from, to, s, fname)
            }
            Std::BcdTo(to) => {
                let (v, s) = vals.remove(0);
                let is_bits = v
                    .ty()
                    .id()
                    .and_then(|t| self.scalar(t))
                    .is_some_and(|e| e.family() == Family::Bits);
                if !is_bits {
                    self.diags.error(
                        "E302",
                        s,
                        format!("{fname} needs a bit string (BYTE, WORD, ...)"),
                    );
                    return Val::error();
                }
                let x = self.apply_conv(f, v, Conv::FromBcd, ElemType::Ulint, s);
                self.convert(f, x, ElemType::Ulint, to, s, fname)
            }
            Std::ToBcd(to) => {
                let (v, s) = vals.remove(0);
                let Some(from) = v
                    .ty()
                    .id()
                    .and_then(|t| self.scalar(t))
                    .filter(|e| e.is_int())
                    .or(if v.ty() == Ty::AnyInt {
                        Some(ElemType::Lint)
                    } else {
                        None
                    })
                else {
                    self.diags
                        .error("E302", s, format!("{fname} needs an integer"));
                    return Val::error();
                };
                let to = to.unwrap_or(match from.bits() {
                    8 => ElemType::Byte,
                    16 => ElemType::Word,
                    32 => ElemType::Dword,
                    _ => ElemType::Lword,
                });
                let v = self.coerce(f, v, TypeTable::elem(from), s, fname);
                self.apply_conv(f, v, Conv::ToBcd(to.bits() as u8), to, s)
            }
            Std::ConcatDateTod => {
                let (t, _) = vals.pop().unwrap_or((Val::error(), span));
                let (d, ds) = vals.pop().unwrap_or((Val::error(), span));
                let dt = TypeTable::elem(ElemType::Date);
                let tt = TypeTable::elem(ElemType::Tod);
                let d = self.coerce(f, d, dt, ds, fname);
                let t = self.coerce(f, t, tt, ds, fname);
                let (a, b) = (self.materialize(f, &d), self.materialize(f, &t));
                let r = f.temp();
                f.emit(Op::AddS {
                    d: r,
                    a,
                    b,
                    shift: 0,
                });
                Val::Slot(r, TypeTable::elem(ElemType::Dt))
            }
            Std::Clock => {
                let d = f.temp();
                f.emit(Op::Clock { d });
                Val::Slot(d, TypeTable::elem(ElemType::Time))
            }
            Std::Concat => {
                let mut acc: Option<(Val, Span)> = None;
                for (v, s) in vals {
                    acc = Some(match acc {
                        None => (v, s),
                        Some((a, _)) => (
                            self.string_fn(f, StrFn::Concat, vec![(a, s), (v, s)], fname),
                            s,
                        ),
                    });
                }
                acc.map(|a| a.0).unwrap_or_else(Val::error)
            }
            Std::Str(func) => self.string_fn(f, func, vals, fname),
        }
    }

    /// The common type of the arguments; untyped literals alone take the
    /// type the context expects (`i := MAX(1, 2)` with `i : INT` is INT).
    fn unify_all(
        &mut self,
        tys: &[Ty],
        span: Span,
        fname: &str,
        expect: Option<crate::ir::types::TypeId>,
    ) -> Option<crate::ir::types::TypeId> {
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

    fn minmax(
        &mut self,
        f: &mut Fcx,
        t: crate::ir::types::TypeId,
        a: u32,
        b: u32,
        max: bool,
    ) -> u32 {
        let e = self.scalar(t).unwrap_or(ElemType::Dint);
        let d = f.temp();
        f.emit(match e {
            ElemType::Real => Op::MinMaxF32 { d, a, b, max },
            ElemType::Lreal => Op::MinMaxF64 { d, a, b, max },
            _ if super::typeck::compares_signed(e) => Op::MinMaxS { d, a, b, max },
            _ => Op::MinMaxU { d, a, b, max },
        });
        d
    }

    /// A string function with arguments in consecutive slots.
    fn string_fn(&mut self, f: &mut Fcx, func: StrFn, vals: Vec<(Val, Span)>, fname: &str) -> Val {
        let is_str = |c: &BodyBuilder, v: &Val| {
            v.ty()
                .id()
                .and_then(|t| c.scalar(t))
                .is_some_and(|e| e.is_string())
        };
        // Which positions are strings.
        let string_pos: &[usize] = match func {
            StrFn::Len | StrFn::Left | StrFn::Right | StrFn::Mid | StrFn::Delete => &[0],
            StrFn::Concat | StrFn::Insert | StrFn::Replace | StrFn::Find => &[0, 1],
        };
        let mut wide = false;
        let mut max = 0u32;
        let mut slots = Vec::new();
        for (i, (v, s)) in vals.into_iter().enumerate() {
            if string_pos.contains(&i) {
                if !is_str(self, &v) {
                    let n = self.ty_name(v.ty());
                    self.diags
                        .error("E301", s, format!("{fname}: expected a string, found {n}"));
                    return Val::error();
                }
                if let Some(TypeKind::Str { max: m, wide: w }) =
                    v.ty().id().map(|t| self.types.get(t).kind.clone())
                {
                    max = max.saturating_add(m);
                    wide |= w;
                }
                slots.push(self.materialize(f, &v));
            } else {
                let v = self.coerce(f, v, TypeTable::elem(ElemType::Dint), s, fname);
                if v.is_error() {
                    return v;
                }
                slots.push(self.materialize(f, &v));
            }
        }
        let a = f.temps(4);
        for (i, s) in slots.into_iter().enumerate() {
            f.emit(Op::Mov { d: a + i as u32, s });
        }
        if matches!(func, StrFn::Len | StrFn::Find) {
            let d = f.temp();
            f.emit(Op::StrCall { d, a, f: func });
            return Val::Slot(d, TypeTable::elem(ElemType::Int));
        }
        let max = max.clamp(1, 65535);
        let d = self.string_temp(f, max, wide);
        f.emit(Op::StrCall { d, a, f: func });
        let t = self.types.intern(crate::ir::types::TypeDef {
            name: format!("{}[{max}]", if wide { "WSTRING" } else { "STRING" }),
            kind: TypeKind::Str { wide, max },
            size: 1,
        });
        Val::Slot(d, t)
    }

    /// Applies a conversion instruction (folding constants at compile time).
    fn apply_conv(&mut self, f: &mut Fcx, v: Val, conv: Conv, to: ElemType, span: Span) -> Val {
        let rt = TypeTable::elem(to);
        if let Val::Const(Const::Bits(b), _) = v {
            return match crate::vm::convert_value(conv, b) {
                Ok(r) => Val::Const(Const::Bits(r), Ty::T(rt)),
                Err(k) => {
                    self.diags
                        .error("E305", span, format!("constant conversion fails: {k}"));
                    Val::error()
                }
            };
        }
        let a = self.materialize(f, &v);
        let d = f.temp();
        f.emit(Op::Convert { d, a, conv });
        Val::Slot(d, rt)
    }

    /// `FROM_TO_TO` conversion of a value already of type `from`.
    fn convert(
        &mut self,
        f: &mut Fcx,
        v: Val,
        from: ElemType,
        to: ElemType,
        span: Span,
        fname: &str,
    ) -> Val {
        use ElemType as E;
        let rt = TypeTable::elem(to);
        let shift = super::typeck::shift_of(to);
        let (ff, tf) = (from.family(), to.family());
        let int_like = |fam: Family| {
            matches!(
                fam,
                Family::Signed | Family::Unsigned | Family::Bits | Family::Bool | Family::Char
            )
        };
        if from == to {
            return match v {
                Val::Const(c, _) => Val::Const(c, Ty::T(rt)),
                Val::Slot(s, _) => Val::Slot(s, rt),
                other => other,
            };
        }
        if to.is_string() {
            if from.is_string() {
                let s = self.materialize(f, &v);
                let d = self.string_temp(f, 254, to == E::WString);
                f.emit(Op::StrMov { d, s });
                return Val::Slot(d, rt);
            }
            let a = self.materialize(f, &v);
            let idx = self.out.scalar_index(from);
            let d = self.string_temp(f, 254, to == E::WString);
            f.emit(Op::ToStr { d, a, ty: idx });
            return Val::Slot(d, rt);
        }
        if from.is_string() {
            let a = self.materialize(f, &v);
            let idx = self.out.scalar_index(to);
            let d = f.temp();
            f.emit(Op::FromStr { d, a, ty: idx });
            return Val::Slot(d, rt);
        }
        let conv = match (ff, tf) {
            _ if to == E::Bool && int_like(ff) => Some(Conv::ToBool),
            (a, b) if int_like(a) && int_like(b) => {
                let binary = a == Family::Bits || b == Family::Bits;
                if from.widens_to(to) || (from == E::Bool) {
                    None
                } else if binary {
                    // Bit strings convert as bit patterns (IEC: binary transfer).
                    if to.is_signed_int() {
                        Some(Conv::WrapS(shift))
                    } else {
                        Some(Conv::WrapU(shift))
                    }
                } else if to.is_signed_int() {
                    // Between integers the value must fit (semantics §3).
                    Some(Conv::CheckS(shift))
                } else if from.is_signed_int() {
                    Some(Conv::CheckSToU(shift))
                } else {
                    Some(Conv::CheckU(shift))
                }
            }
            (a, Family::Real) if int_like(a) => Some(match (from.is_signed_int(), to) {
                (true, E::Real) => Conv::SToF32,
                (true, _) => Conv::SToF64,
                (false, E::Real) => Conv::UToF32,
                (false, _) => Conv::UToF64,
            }),
            (Family::Real, b) if int_like(b) && to != E::Bool => {
                Some(match (from, to.is_signed_int()) {
                    (E::Real, true) => Conv::F32ToS(shift),
                    (E::Real, false) => Conv::F32ToU(shift),
                    (_, true) => Conv::F64ToS(shift),
                    (_, false) => Conv::F64ToU(shift),
                })
            }
            (Family::Real, Family::Real) => Some(if from == E::Real {
                Conv::F32ToF64
            } else {
                Conv::F64ToF32
            }),
            (Family::Duration, Family::Duration) => None,
            (Family::Duration, b) if int_like(b) && to != E::Bool => Some(if to.is_signed_int() {
                Conv::NsToMsS(shift)
            } else {
                Conv::NsToMsU(shift)
            }),
            (a, Family::Duration) if int_like(a) => Some(if from.is_signed_int() {
                Conv::MsToNsS
            } else {
                Conv::MsToNsU
            }),
            (Family::Duration, Family::Real) => Some(if to == E::Real {
                Conv::NsToMsF32
            } else {
                Conv::NsToMsF64
            }),
            (Family::Real, Family::Duration) => Some(if from == E::Real {
                Conv::MsF32ToNs
            } else {
                Conv::MsF64ToNs
            }),
            (Family::DateTime, Family::DateTime) => match (from, to) {
                (E::Dt | E::Ldt, E::Date | E::Ldate) => Some(Conv::DtToDate),
                (E::Dt | E::Ldt, E::Tod | E::Ltod) => Some(Conv::DtToTod),
                (E::Date, E::Ldate)
                | (E::Ldate, E::Date)
                | (E::Tod, E::Ltod)
                | (E::Ltod, E::Tod)
                | (E::Dt, E::Ldt)
                | (E::Ldt, E::Dt)
                | (E::Date | E::Ldate, E::Dt | E::Ldt) => None,
                _ => {
                    self.diags
                        .error("E302", span, format!("{fname}: no such conversion"));
                    return Val::error();
                }
            },
            _ => {
                self.diags
                    .error("E302", span, format!("{fname}: no such conversion"));
                return Val::error();
            }
        };
        match conv {
            None => match v {
                Val::Const(c, _) => Val::Const(c, Ty::T(rt)),
                Val::Slot(s, _) => Val::Slot(s, rt),
                other => other,
            },
            Some(c) => self.apply_conv(f, v, c, to, span),
        }
    }
}
