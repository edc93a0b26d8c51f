//! Expressions: name resolution, places (lvalues), operators with constant
//! folding, and emission of typed instructions.

use super::body::BodyBuilder;
use super::consts::{Const, literal_to_slot, literal_type, slot_to_int, slot_to_real};
use super::emit::{Ty, Val};
use super::typeck::shift_of;
use crate::elementary::{ElemType, Family};
use crate::ir::op::Op;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind, Literal, LiteralValue, UnaryOp};

impl BodyBuilder<'_> {
    /// Checks and emits an expression used as a value.
    pub(super) fn expr(&mut self, e: &Expr, expect: Option<TypeId>) -> Val {
        let saved = self.block.span;
        self.block.span = e.span;
        let v = self.expr_inner(e, expect);
        self.block.span = saved;
        v
    }

    fn expr_inner(&mut self, e: &Expr, expect: Option<TypeId>) -> Val {
        if let Some(v) = self.property_read(e) {
            return v;
        }
        if matches!(e.kind, ExprKind::Member(..))
            && let Some(v) = self.qualified_enum(e)
        {
            return v;
        }
        match &e.kind {
            ExprKind::Literal(l) => self.literal(l, e.span, expect),
            ExprKind::Paren(x) => self.expr(x, expect),
            ExprKind::Name(id) => {
                // Enumeration value names come after variables.
                let key = id.key();
                if let Some(v) = self.en_in_body(&key) {
                    return v;
                }
                if self.lookup_var(&key).is_none()
                    && let Some(v) = self.enum_value(&key, expect)
                {
                    return v;
                }
                if key == "NULL" && self.lookup_var(&key).is_none() {
                    return self.null_value();
                }
                if key == "THIS" && self.lookup_var(&key).is_none() {
                    return self.this_pointer(e.span);
                }
                if self.lookup_var(&key).is_none() && self.unqualified_enum(id) {
                    return Val::error();
                }
                if let Some(var) = self.lookup_var(&key)
                    && var.constant
                    && let Some(c) = var.value.clone()
                {
                    return Val::Const(c, Ty::T(var.ty));
                }
                self.place_value(e)
            }
            ExprKind::BitAccess(..)
            | ExprKind::Member(..)
            | ExprKind::Index(..)
            | ExprKind::Direct(_) => match self.part_of(e) {
                Some((base, sel)) => self.read_part(base, sel),
                None => self.place_value(e),
            },
            ExprKind::Deref(_) => self.place_value(e),
            ExprKind::Unary(op, x) => self.unary(*op, x, e.span, expect),
            ExprKind::Binary(op, a, b) => self.binary(*op, a, b, e.span, expect),
            ExprKind::Call(call) => self.call_expr(call, expect),
            ExprKind::Assign(target, value) => self.assign_expr(target, value, e.span),
        }
    }

    /// A literal's value.
    pub(super) fn literal(&mut self, l: &Literal, span: Span, expect: Option<TypeId>) -> Val {
        if let Some(prefix) = &l.type_prefix {
            if let Some(e) = ElemType::from_name(&prefix.name) {
                return match literal_to_slot(&l.value, e) {
                    Ok(c) => Val::Const(c, Ty::T(TypeTable::elem(e))),
                    Err(m) => {
                        self.diags.error("E304", span, m);
                        Val::error()
                    }
                };
            }
            // `Color#Red`
            let key = prefix.key();
            if let Some(t) = self.model.type_ids.get(&key).copied()
                && let TypeKind::Enum { values, .. } = &self.types.get(t).kind
            {
                let name = match &l.value {
                    LiteralValue::EnumValue(v) => v.name.clone(),
                    _ => String::new(),
                };
                if let Some((_, v)) = values.iter().find(|(n, _)| n.eq_ignore_ascii_case(&name)) {
                    return Val::Const(Const::Bits(*v as u64), Ty::T(t));
                }
                self.diags.error(
                    "E201",
                    span,
                    format!("enumeration {} has no value `{name}`", prefix.name),
                );
                return Val::error();
            }
            self.diags.error(
                "E203",
                prefix.span,
                format!("unknown type `{}` in typed literal", prefix.name),
            );
            return Val::error();
        }
        match &l.value {
            LiteralValue::Int(v) => Val::Const(Const::Int(*v), Ty::AnyInt),
            LiteralValue::Real(v) => Val::Const(Const::Real(*v), Ty::AnyReal),
            LiteralValue::EnumValue(id) => match self.enum_value(&id.key(), expect) {
                Some(v) => v,
                None if self.unqualified_enum(id) => Val::error(),
                None => {
                    let message = format!("unknown enumeration value `{}`", id.name);
                    let names = self.model.enum_values.keys().map(String::as_str);
                    let message = super::suggest::with_suggestion(message, &id.name, names);
                    self.diags.error("E201", span, message);
                    Val::error()
                }
            },
            other => {
                let Some(e) = literal_type(other) else {
                    return Val::error();
                };
                match literal_to_slot(other, e) {
                    Ok(c) => Val::Const(c, Ty::T(TypeTable::elem(e))),
                    Err(m) => {
                        self.diags.error("E304", span, m);
                        Val::error()
                    }
                }
            }
        }
    }

    /// An unqualified enumeration value, disambiguated by the expected type.
    fn enum_value(&self, key: &str, expect: Option<TypeId>) -> Option<Val> {
        let candidates = self.model.enum_values.get(key)?;
        let pick = expect
            .and_then(|t| candidates.iter().find(|(id, _)| *id == t))
            .or_else(|| candidates.first())?;
        Some(Val::Const(Const::Bits(pick.1 as u64), Ty::T(pick.0)))
    }

    /// Finds a variable visible in the current body.
    pub(super) fn lookup_var(&self, key: &str) -> Option<&super::model::VarInfo> {
        if let Some(cr) = &self.block.il_cr
            && key == super::il::CR_KEY
        {
            return Some(cr);
        }
        if let Some(v) = self.oop_local(key) {
            return Some(v);
        }
        self.model
            .pous
            .get(self.block.pou)
            .and_then(|p| p.vars.get(key))
            .or_else(|| self.model.globals.get(key))
    }

    fn unary(&mut self, op: UnaryOp, x: &Expr, span: Span, expect: Option<TypeId>) -> Val {
        let v = self.expr(x, expect);
        if v.is_error() {
            return v;
        }
        match op {
            UnaryOp::Plus => {
                if !self.is_numeric(v.ty()) {
                    self.bad_operand(span, "unary `+`", v.ty());
                    return Val::error();
                }
                v
            }
            UnaryOp::Neg => {
                if let Some(r) = self.bit_string_neg(&v, span) {
                    return r;
                }
                let ty = v.ty();
                let ok = self.is_numeric(ty)
                    || ty
                        .id()
                        .and_then(|t| self.scalar(t))
                        .is_some_and(|e| e.family() == Family::Duration);
                if !ok
                    || ty
                        .id()
                        .and_then(|t| self.scalar(t))
                        .is_some_and(|e| e.is_unsigned_int())
                {
                    self.bad_operand(span, "unary `-`", ty);
                    return Val::error();
                }
                match v {
                    Val::Const(Const::Int(i), t) => Val::Const(Const::Int(-i), t),
                    Val::Const(Const::Real(r), t) => Val::Const(Const::Real(-r), t),
                    Val::Const(Const::Bits(b), Ty::T(t)) => {
                        let e = self.scalar(t).unwrap_or(ElemType::Lint);
                        let r = if e.is_real() {
                            super::consts::real_to_slot(-slot_to_real(b, e), e)
                        } else {
                            super::consts::int_to_slot(-slot_to_int(b, e), e)
                        };
                        match r {
                            Some(b) => Val::Const(Const::Bits(b), Ty::T(t)),
                            None => {
                                self.diags
                                    .error("E305", span, "constant overflow in negation");
                                Val::error()
                            }
                        }
                    }
                    Val::Slot(s, t) => {
                        let e = self.scalar(t).unwrap_or(ElemType::Lint);
                        let d = self.block.temp();
                        self.block.emit(match e {
                            ElemType::Real => Op::NegF32 { d, a: s },
                            ElemType::Lreal => Op::NegF64 { d, a: s },
                            _ => Op::NegS {
                                d,
                                a: s,
                                shift: shift_of(e),
                            },
                        });
                        Val::Slot(d, self.plain(t))
                    }
                    other => other,
                }
            }
            UnaryOp::Not => {
                let ty = v.ty();
                match v {
                    Val::Const(Const::Int(i), t) => Val::Const(Const::Int(!i), t),
                    Val::Const(Const::Bits(b), Ty::T(t))
                        if self.scalar(t).is_some_and(|e| e.is_bit()) =>
                    {
                        let e = self.scalar(t).unwrap_or(ElemType::Bool);
                        let r = if e == ElemType::Bool {
                            b ^ 1
                        } else {
                            crate::ir::op::wrap_u(!b, shift_of(e))
                        };
                        Val::Const(Const::Bits(r), Ty::T(t))
                    }
                    Val::Slot(s, t) if self.scalar(t).is_some_and(|e| e.is_bit()) => {
                        let e = self.scalar(t).unwrap_or(ElemType::Bool);
                        let d = self.block.temp();
                        self.block.emit(if e == ElemType::Bool {
                            Op::NotB { d, a: s }
                        } else {
                            Op::NotW {
                                d,
                                a: s,
                                shift: shift_of(e),
                            }
                        });
                        Val::Slot(d, TypeTable::elem(e))
                    }
                    _ => match self.int_not(&v, span) {
                        Some(r) => r,
                        None => {
                            self.bad_operand(span, "NOT", ty);
                            Val::error()
                        }
                    },
                }
            }
        }
    }

    /// True for integer and real types (not enumerations).
    pub(super) fn is_numeric(&self, t: Ty) -> bool {
        match t {
            Ty::AnyInt | Ty::AnyReal => true,
            Ty::T(t) => !self.is_enum(t) && self.scalar(t).is_some_and(|e| e.is_num()),
        }
    }

    /// Reports an operand type an operator does not accept.
    pub(super) fn bad_operand(&mut self, span: Span, op: &str, t: Ty) {
        let name = self.ty_name(t);
        self.diags.error(
            "E302",
            span,
            format!("operator {op} cannot be applied to {name}"),
        );
    }
}
