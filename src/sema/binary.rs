//! Binary operators: typing by IEC implicit widening, constant folding,
//! and lowering to typed instructions (with the immediate, NOT-operand and
//! multiply-add forms), plus time and date arithmetic.

use super::body::BodyBuilder;
use super::consts::{Const, slot_to_int, slot_to_real};
use super::emit::{Fcx, Ty, Val};
use super::typeck::shift_of;
use crate::elementary::{ElemType, Family};
use crate::ir::op::{Cmp, Op, Slot};
use crate::ir::type_table::{TypeId, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{BinaryOp, Expr};

impl BodyBuilder<'_> {
    /// Checks and emits `a op b`.
    pub(super) fn binary(
        &mut self,
        op: BinaryOp,
        a: &Expr,
        b: &Expr,
        span: Span,
        expect: Option<TypeId>,
    ) -> Val {
        if matches!(op, BinaryOp::AndThen | BinaryOp::OrElse) {
            return self.short_circuit(op, a, b);
        }
        if let Some(v) = self.oop_compare(op, a, b, span) {
            return v;
        }
        let hint = if op.is_comparison() { None } else { expect };
        let va = self.expr(a, hint);
        let vb = self.expr(b, hint.or(va.ty().id()));
        self.binary_vals(op, va, vb, span)
    }

    /// Applies a binary operator to two checked values.
    pub(super) fn binary_vals(&mut self, op: BinaryOp, va: Val, vb: Val, span: Span) -> Val {
        if va.is_error() || vb.is_error() {
            return Val::error();
        }
        if let Some(v) = self.ref_binary(op, &va, &vb, span) {
            return v;
        }
        let op_name = binary_name(op);
        // An enumeration with an integer first: one of base WORD then
        // computes as a bit string (`(eModule - 1) * 16#800`).
        let (va, vb) = self.enum_operands(op, va, vb, span);
        if let Some(v) = self.bit_string_arith(op, &va, &vb, span) {
            return v;
        }
        // Time and date arithmetic has its own typing rules.
        if let Some(v) = self.time_arith(op, &va, &vb, span) {
            return v;
        }
        let Some(common) = self
            .unify(va.ty(), vb.ty())
            .or_else(|| self.mixed_sign_common(&va, &vb, span))
        else {
            if let Some(v) = self.bit_string_compare(op, &va, &vb, span) {
                return v;
            }
            let (x, y) = (self.ty_name(va.ty()), self.ty_name(vb.ty()));
            self.diags.push(
                crate::diagnostics::Diagnostic::error(
                    "E306",
                    span,
                    format!("operator {op_name} cannot combine {x} and {y}"),
                )
                .with_note("IEC converts implicitly only without loss; use a *_TO_* conversion"),
            );
            return Val::error();
        };
        let is_cmp = op.is_comparison();
        if !self.operands_fit(op, common) {
            self.bad_operand(span, op_name, common);
            return Val::error();
        }
        self.int_bit_operands(op, common, span);
        let common = self.widen_for_literal(&va, &vb, common, span);
        // Constant folding.
        if let (Val::Const(ca, _), Val::Const(cb, _)) = (&va, &vb) {
            match self.fold(op, ca, va.ty(), cb, vb.ty(), common) {
                Ok(Some(v)) => return v,
                Ok(None) => {}
                Err(m) => {
                    self.diags.error("E305", span, m);
                    return Val::error();
                }
            }
        }
        let ct = match common {
            Ty::T(t) => t,
            other => self.default_type(other, None),
        };
        let e = self.scalar(ct).unwrap_or(ElemType::Dint);
        let xa = self.coerce(va, ct, span, "operand");
        let a = self.materialize(&xa);
        if is_cmp {
            return self.compare(op, a, vb, ct, span);
        }
        // Immediate forms for small constants on signed integers.
        if let Some(imm) = self.immediate_operand(&vb, ct, e)
            && e.is_signed_int()
            && let Some(v) = self.immediate_arith(op, a, imm, ct)
        {
            return v;
        }
        let computed_divisor = op == BinaryOp::Div && !matches!(vb, Val::Const(..));
        let xb = self.coerce(vb, ct, span, "operand");
        let mut b = self.materialize(&xb);
        if computed_divisor {
            b = self.checked_divisor(b, e, span);
        }
        if !self.model.unoptimized {
            if let Some(v) = fuse_not_operand(&mut self.block, op, a, b, ct, e) {
                return v;
            }
            if let Some(v) = fuse_mul_add(&mut self.block, op, a, b, ct, e) {
                return v;
            }
        }
        if op == BinaryOp::Pow && e.is_unsigned_int() {
            return self.unsigned_pow(a, b, ct, e);
        }
        let d = self.block.temp();
        let Some(o) = arith_op(op, e, d, a, b) else {
            return Val::error();
        };
        self.block.emit(o);
        Val::Slot(d, ct)
    }

    /// `a ** b` on an unsigned type: the 64-bit wrapping power, then
    /// zero-extended from the type's width (PowS alone sign-extends,
    /// which would leave a USINT holding 16#FF..81).
    fn unsigned_pow(&mut self, a: Slot, b: Slot, ct: TypeId, e: ElemType) -> Val {
        let p = self.block.temp();
        self.block.emit(Op::PowS {
            d: p,
            a,
            b,
            shift: 0,
        });
        let shift = shift_of(e);
        if shift == 0 {
            return Val::Slot(p, ct);
        }
        let d = self.block.temp();
        self.block.emit(Op::Convert {
            d,
            a: p,
            conv: crate::ir::op::Conv::WrapU(shift),
        });
        Val::Slot(d, ct)
    }

    /// Whether operator `op` applies to operands of type `common`.
    fn operands_fit(&self, op: BinaryOp, common: Ty) -> bool {
        let elem = match common {
            Ty::T(t) => self.scalar(t),
            _ => None,
        };
        match op {
            BinaryOp::And | BinaryOp::Or | BinaryOp::Xor => match common {
                Ty::AnyInt => true,
                Ty::AnyReal => false,
                // Integers too, as CODESYS allows (W488, int_bit_ops.rs).
                Ty::T(t) => !self.is_enum(t) && elem.is_some_and(|e| e.is_bit() || e.is_int()),
            },
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div => {
                self.is_numeric(common)
            }
            BinaryOp::Mod => match common {
                Ty::AnyInt => true,
                Ty::T(t) => !self.is_enum(t) && elem.is_some_and(|e| e.is_int()),
                Ty::AnyReal => false,
            },
            BinaryOp::Pow => self.is_numeric(common),
            _ => match common {
                Ty::T(t) => self.scalar(t).is_some(),
                _ => true,
            },
        }
    }

    /// The right operand as an immediate, when it is a small constant of a
    /// signed (or short unsigned) integer type.
    fn immediate_operand(&self, vb: &Val, ct: TypeId, e: ElemType) -> Option<i32> {
        match vb {
            Val::Const(c, t) => match self.const_as(c, *t, ct) {
                Ok(Const::Bits(bits)) if e.is_signed_int() || (e.is_int() && e.bits() <= 32) => {
                    i32::try_from(bits as i64).ok()
                }
                _ => None,
            },
            _ => None,
        }
    }

    /// A comparison of `a` (already in a slot) with `vb`.
    fn compare(&mut self, op: BinaryOp, a: Slot, vb: Val, ct: TypeId, span: Span) -> Val {
        let e = self.scalar(ct).unwrap_or(ElemType::Dint);
        let cmp = cmp_of(op);
        if let Some(imm) = self.immediate_operand(&vb, ct, e)
            && super::typeck::compares_signed(e)
        {
            let d = self.block.temp();
            self.block.emit(Op::CmpSI { d, a, imm, cmp });
            return Val::Slot(d, TypeTable::elem(ElemType::Bool));
        }
        let xb = self.coerce(vb, ct, span, "operand");
        let b = self.materialize(&xb);
        let d = self.emit_cmp(e, a, b, cmp);
        Val::Slot(d, TypeTable::elem(ElemType::Bool))
    }

    /// `a + imm`, `a - imm`, `a MOD imm` on signed integers with the
    /// immediate forms; `None` for the other operators.
    fn immediate_arith(&mut self, op: BinaryOp, a: Slot, imm: i32, ct: TypeId) -> Option<Val> {
        let e = self.scalar(ct).unwrap_or(ElemType::Dint);
        match op {
            // x + 0 and x - 0 are x (already of the common type).
            BinaryOp::Add | BinaryOp::Sub if imm == 0 => Some(Val::Slot(a, ct)),
            BinaryOp::Add => {
                let d = self.block.temp();
                self.block.emit(Op::AddSI {
                    d,
                    a,
                    imm,
                    shift: shift_of(e),
                });
                Some(Val::Slot(d, ct))
            }
            BinaryOp::Sub if imm != i32::MIN => {
                let d = self.block.temp();
                self.block.emit(Op::AddSI {
                    d,
                    a,
                    imm: -imm,
                    shift: shift_of(e),
                });
                Some(Val::Slot(d, ct))
            }
            BinaryOp::Mod if imm != 0 => {
                let d = self.block.temp();
                self.block.emit(Op::ModSI {
                    d,
                    a,
                    imm,
                    shift: shift_of(e),
                });
                Some(Val::Slot(d, ct))
            }
            _ => None,
        }
    }

    /// TIME/DATE arithmetic: `TIME ± TIME`, `TOD ± TIME`, `DT ± TIME`,
    /// `DATE - DATE`, `TOD - TOD`, `DT - DT`, `TIME * num`, `TIME / num`.
    fn time_arith(&mut self, op: BinaryOp, va: &Val, vb: &Val, span: Span) -> Option<Val> {
        let fam = |c: &BodyBuilder, v: &Val| v.ty().id().and_then(|t| c.scalar(t));
        let (ea, eb) = (fam(self, va), fam(self, vb));
        let is_dur = |e: Option<ElemType>| e.is_some_and(|e| e.family() == Family::Duration);
        let is_date = |e: Option<ElemType>| e.is_some_and(|e| e.family() == Family::DateTime);
        if !(is_dur(ea) || is_date(ea) || is_dur(eb) || is_date(eb)) {
            return None;
        }
        if !matches!(
            op,
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div
        ) {
            return None;
        }
        let time = TypeTable::elem(
            if ea == Some(ElemType::Ltime) || eb == Some(ElemType::Ltime) {
                ElemType::Ltime
            } else {
                ElemType::Time
            },
        );
        let result = match (op, ea, eb) {
            (BinaryOp::Add | BinaryOp::Sub, a, b) if is_dur(a) && is_dur(b) => time,
            (BinaryOp::Add | BinaryOp::Sub, Some(a), b)
                if is_date(Some(a)) && is_dur(b) && a != ElemType::Date && a != ElemType::Ldate =>
            {
                TypeTable::elem(a)
            }
            (BinaryOp::Add, a, Some(b))
                if is_dur(a) && is_date(Some(b)) && b != ElemType::Date && b != ElemType::Ldate =>
            {
                TypeTable::elem(b)
            }
            (BinaryOp::Sub, Some(a), Some(b)) if is_date(Some(a)) && a == b => time,
            (BinaryOp::Mul | BinaryOp::Div, a, _) if is_dur(a) && self.is_numeric(vb.ty()) => {
                return Some(self.time_scale(op, va, vb, time, span));
            }
            (BinaryOp::Mul, _, b) if is_dur(b) && self.is_numeric(va.ty()) => {
                return Some(self.time_scale(op, vb, va, time, span));
            }
            _ => {
                let (x, y) = (self.ty_name(va.ty()), self.ty_name(vb.ty()));
                self.diags.error(
                    "E306",
                    span,
                    format!("operator {} cannot combine {x} and {y}", binary_name(op)),
                );
                return Some(Val::error());
            }
        };
        let result_elem = self.scalar(result);
        if let (Val::Const(Const::Bits(x), _), Val::Const(Const::Bits(y), _)) = (va, vb) {
            let r = if op == BinaryOp::Add {
                (*x as i64).checked_add(*y as i64)
            } else {
                (*x as i64).checked_sub(*y as i64)
            };
            let r = r.map(|v| {
                if is_tod(result_elem) {
                    v.rem_euclid(DAY_NS)
                } else {
                    v
                }
            });
            return Some(match r {
                Some(v) => Val::Const(Const::Bits(v as u64), Ty::T(result)),
                None => {
                    self.diags
                        .error("E305", span, "constant time arithmetic overflows");
                    Val::error()
                }
            });
        }
        let a = self.materialize(va);
        let b = self.materialize(vb);
        let d = self.block.temp();
        self.block.emit(if op == BinaryOp::Add {
            Op::AddS { d, a, b, shift: 0 }
        } else {
            Op::SubS { d, a, b, shift: 0 }
        });
        if is_tod(result_elem) {
            // A time of day stays within the day: it wraps around midnight.
            let w = self.block.temp();
            self.block.emit(Op::Convert {
                d: w,
                a: d,
                conv: crate::ir::op::Conv::DtToTod,
            });
            return Some(Val::Slot(w, result));
        }
        Some(Val::Slot(d, result))
    }

    fn time_scale(&mut self, op: BinaryOp, t: &Val, n: &Val, time: TypeId, span: Span) -> Val {
        let a = self.materialize(t);
        let ne = match n.ty() {
            Ty::AnyInt => ElemType::Lint,
            Ty::AnyReal => ElemType::Lreal,
            Ty::T(x) => self.scalar(x).unwrap_or(ElemType::Lint),
        };
        let nv = self.coerce(n.clone(), TypeTable::elem(ne), span, "time factor");
        let mut b = self.materialize(&nv);
        if ne == ElemType::Ulint && op == BinaryOp::Div {
            // The division is signed: a ULINT divisor of 2^63 or more
            // would read as negative, so it faults (R004) instead.
            let c = self.block.temp();
            self.block.emit(Op::Convert {
                d: c,
                a: b,
                conv: crate::ir::op::Conv::CheckU(1),
            });
            b = c;
        }
        let d = self.block.temp();
        if ne.is_real() {
            let b = if ne == ElemType::Real {
                let x = self.block.temp();
                self.block.emit(Op::Convert {
                    d: x,
                    a: b,
                    conv: crate::ir::op::Conv::F32ToF64,
                });
                x
            } else {
                b
            };
            self.block.emit(if op == BinaryOp::Mul {
                Op::MulTimeF64 { d, a, b }
            } else {
                Op::DivTimeF64 { d, a, b }
            });
        } else {
            self.block.emit(if op == BinaryOp::Mul {
                Op::MulS { d, a, b, shift: 0 }
            } else {
                Op::DivS { d, a, b, shift: 0 }
            });
        }
        Val::Slot(d, time)
    }

    /// Folds a binary operator over two constants. `Ok(None)` when the
    /// combination is not folded (left to run time).
    fn fold(
        &mut self,
        op: BinaryOp,
        ca: &Const,
        ta: Ty,
        cb: &Const,
        tb: Ty,
        common: Ty,
    ) -> Result<Option<Val>, String> {
        let bool_t = Ty::T(TypeTable::elem(ElemType::Bool));
        let is_cmp = op.is_comparison();
        // Bring both to the common representation.
        enum N {
            I(i128),
            R(f64),
            S(String),
        }
        let to_n = |c: &Const, t: Ty, s: &BodyBuilder| -> Option<N> {
            Some(match (c, t) {
                (Const::Int(i), _) => N::I(*i),
                (Const::Real(r), _) => N::R(*r),
                (Const::Str(x), _) => N::S(x.clone()),
                (Const::Bits(b), Ty::T(t)) => {
                    let e = s.scalar(t)?;
                    if e.is_real() {
                        N::R(slot_to_real(*b, e))
                    } else {
                        N::I(slot_to_int(*b, e))
                    }
                }
                _ => return None,
            })
        };
        let (Some(x), Some(y)) = (to_n(ca, ta, self), to_n(cb, tb, self)) else {
            return Ok(None);
        };
        let result_ty = if is_cmp { bool_t } else { common };
        let target_elem = match common {
            Ty::T(t) => self.scalar(t),
            _ => None,
        };
        let wants_real = matches!(common, Ty::AnyReal) || target_elem.is_some_and(|e| e.is_real());
        let as_real = |n: &N| match n {
            N::I(i) => *i as f64,
            N::R(r) => *r,
            N::S(_) => 0.0,
        };
        if let (N::S(a), N::S(b)) = (&x, &y) {
            if !is_cmp {
                return Ok(None);
            }
            let r = cmp_of(op).test(a.cmp(b));
            return Ok(Some(Val::Const(Const::Bits(r as u64), bool_t)));
        }
        if wants_real {
            let (a, b) = (as_real(&x), as_real(&y));
            let value = match op {
                BinaryOp::Add => a + b,
                BinaryOp::Sub => a - b,
                BinaryOp::Mul => a * b,
                BinaryOp::Div => a / b,
                BinaryOp::Pow => a.powf(b),
                _ if is_cmp => {
                    let r = match op {
                        BinaryOp::Eq => a == b,
                        BinaryOp::Ne => a != b,
                        BinaryOp::Lt => a < b,
                        BinaryOp::Le => a <= b,
                        BinaryOp::Gt => a > b,
                        _ => a >= b,
                    };
                    return Ok(Some(Val::Const(Const::Bits(r as u64), bool_t)));
                }
                _ => return Ok(None),
            };
            return Ok(Some(match (result_ty, target_elem) {
                (Ty::T(t), Some(e)) => match super::consts::real_to_slot(value, e) {
                    Some(b) => Val::Const(Const::Bits(b), Ty::T(t)),
                    None => return Err(format!("constant overflows {e}")),
                },
                _ => Val::Const(Const::Real(value), Ty::AnyReal),
            }));
        }
        let (N::I(a), N::I(b)) = (x, y) else {
            return Ok(None);
        };
        let value = match op {
            BinaryOp::Add => a.checked_add(b),
            BinaryOp::Sub => a.checked_sub(b),
            BinaryOp::Mul => a.checked_mul(b),
            BinaryOp::Div | BinaryOp::Mod if b == 0 => {
                return Err("division by zero in a constant expression".into());
            }
            BinaryOp::Div => a.checked_div(b),
            BinaryOp::Mod => a.checked_rem(b),
            BinaryOp::Pow => {
                if b < 0 {
                    return Ok(None);
                }
                u32::try_from(b).ok().and_then(|e| a.checked_pow(e))
            }
            BinaryOp::And => Some(a & b),
            BinaryOp::Or => Some(a | b),
            BinaryOp::Xor => Some(a ^ b),
            _ => {
                let r = cmp_of(op).test(a.cmp(&b));
                return Ok(Some(Val::Const(Const::Bits(r as u64), bool_t)));
            }
        };
        let Some(value) = value else {
            return Err("constant expression overflows".into());
        };
        Ok(Some(match (result_ty, target_elem) {
            (Ty::T(t), Some(e)) => match super::consts::int_to_slot(value, e) {
                Some(bits) => Val::Const(Const::Bits(bits), Ty::T(t)),
                None => return Err(format!("constant {value} overflows {e}")),
            },
            _ => Val::Const(Const::Int(value), Ty::AnyInt),
        }))
    }
}

/// `a AND NOT x` / `a OR NOT x` on BOOL: the NOT just computed into `b`
/// folded into an `AndN`/`OrN`.
fn fuse_not_operand(
    f: &mut Fcx,
    op: BinaryOp,
    a: Slot,
    b: Slot,
    ct: TypeId,
    e: ElemType,
) -> Option<Val> {
    if e == ElemType::Bool
        && matches!(op, BinaryOp::And | BinaryOp::Or)
        && let Some((at, def)) = f.last_def
        && def == b
        && f.is_temp(b)
        && at + 1 == f.ops.len()
        && let Op::NotB { a: x, .. } = f.ops[at]
    {
        f.ops.pop();
        f.spans.pop();
        let d = f.temp();
        f.emit(if op == BinaryOp::And {
            Op::AndN { d, a, b: x }
        } else {
            Op::OrN { d, a, b: x }
        });
        return Some(Val::Slot(d, ct));
    }
    None
}

/// `x * y + c` (or `c + x * y`) on REAL/LREAL right after the product:
/// one multiply-add with `c` in the operand word that follows.
fn fuse_mul_add(
    f: &mut Fcx,
    op: BinaryOp,
    a: Slot,
    b: Slot,
    ct: TypeId,
    e: ElemType,
) -> Option<Val> {
    if op == BinaryOp::Add
        && e.is_real()
        && let Some((at, def)) = f.last_def
        && at + 1 == f.ops.len()
        && f.is_temp(def)
        && (def == a || def == b)
        && a != b
        && let Op::MulF32 { a: x, b: y, .. } | Op::MulF64 { a: x, b: y, .. } = f.ops[at]
    {
        let other = if def == a { b } else { a };
        f.ops.pop();
        f.spans.pop();
        let d = f.temp();
        let at = f.emit(if e == ElemType::Real {
            Op::MulAddF32 { d, a: x, b: y }
        } else {
            Op::MulAddF64 { d, a: x, b: y }
        });
        f.emit(Op::Operand { s: other });
        f.last_def = Some((at, d));
        return Some(Val::Slot(d, ct));
    }
    None
}

/// Nanoseconds in a day (a TOD wraps around midnight).
const DAY_NS: i64 = 86_400_000_000_000;

/// Whether `e` is TOD or LTOD.
fn is_tod(e: Option<ElemType>) -> bool {
    matches!(e, Some(ElemType::Tod | ElemType::Ltod))
}

/// The instruction computing `a op b` into `d` for elementary type `e`.
fn arith_op(op: BinaryOp, e: ElemType, d: Slot, a: Slot, b: Slot) -> Option<Op> {
    let s = shift_of(e);
    let signed = e.is_signed_int();
    Some(match (op, e) {
        (BinaryOp::And, _) => Op::And { d, a, b },
        (BinaryOp::Or, _) => Op::Or { d, a, b },
        (BinaryOp::Xor, _) => Op::Xor { d, a, b },
        (BinaryOp::Add, ElemType::Real) => Op::AddF32 { d, a, b },
        (BinaryOp::Sub, ElemType::Real) => Op::SubF32 { d, a, b },
        (BinaryOp::Mul, ElemType::Real) => Op::MulF32 { d, a, b },
        (BinaryOp::Div, ElemType::Real) => Op::DivF32 { d, a, b },
        (BinaryOp::Pow, ElemType::Real) => Op::PowF32 { d, a, b },
        (BinaryOp::Add, ElemType::Lreal) => Op::AddF64 { d, a, b },
        (BinaryOp::Sub, ElemType::Lreal) => Op::SubF64 { d, a, b },
        (BinaryOp::Mul, ElemType::Lreal) => Op::MulF64 { d, a, b },
        (BinaryOp::Div, ElemType::Lreal) => Op::DivF64 { d, a, b },
        (BinaryOp::Pow, ElemType::Lreal) => Op::PowF64 { d, a, b },
        (BinaryOp::Add, _) if signed => Op::AddS { d, a, b, shift: s },
        (BinaryOp::Add, _) => Op::AddU { d, a, b, shift: s },
        (BinaryOp::Sub, _) if signed => Op::SubS { d, a, b, shift: s },
        (BinaryOp::Sub, _) => Op::SubU { d, a, b, shift: s },
        (BinaryOp::Mul, _) if signed => Op::MulS { d, a, b, shift: s },
        (BinaryOp::Mul, _) => Op::MulU { d, a, b, shift: s },
        (BinaryOp::Div, _) if signed => Op::DivS { d, a, b, shift: s },
        (BinaryOp::Div, _) => Op::DivU { d, a, b, shift: s },
        (BinaryOp::Mod, _) if signed => Op::ModS { d, a, b, shift: s },
        (BinaryOp::Mod, _) => Op::ModU { d, a, b, shift: s },
        (BinaryOp::Pow, _) => Op::PowS { d, a, b, shift: s },
        _ => return None,
    })
}

/// The comparison an operator denotes.
pub fn cmp_of(op: BinaryOp) -> Cmp {
    match op {
        BinaryOp::Eq => Cmp::Eq,
        BinaryOp::Ne => Cmp::Ne,
        BinaryOp::Lt => Cmp::Lt,
        BinaryOp::Le => Cmp::Le,
        BinaryOp::Gt => Cmp::Gt,
        _ => Cmp::Ge,
    }
}

/// The operator as written, for messages.
pub fn binary_name(op: BinaryOp) -> &'static str {
    match op {
        BinaryOp::Pow => "`**`",
        BinaryOp::Mul => "`*`",
        BinaryOp::Div => "`/`",
        BinaryOp::Mod => "MOD",
        BinaryOp::Add => "`+`",
        BinaryOp::Sub => "`-`",
        BinaryOp::Lt => "`<`",
        BinaryOp::Gt => "`>`",
        BinaryOp::Le => "`<=`",
        BinaryOp::Ge => "`>=`",
        BinaryOp::Eq => "`=`",
        BinaryOp::Ne => "`<>`",
        BinaryOp::And => "AND",
        BinaryOp::Xor => "XOR",
        BinaryOp::Or => "OR",
        BinaryOp::AndThen => "AND_THEN",
        BinaryOp::OrElse => "OR_ELSE",
    }
}
