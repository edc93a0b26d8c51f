//! Constant expressions of declarations: array bounds, string lengths and
//! initial values, folded against the declarations known so far. Reads the
//! model; writes only diagnostics.

use super::consts::{
    Const, int_to_slot, literal_to_slot, real_to_slot, slot_to_int, typed_literal,
};
use super::enum_qualified::Qualified;
use super::model::{ConstInit, Model, VarInfo};
use crate::diagnostics::Diagnostics;
use crate::elementary::ElemType;
use crate::ir::type_table::{RefFlavor, TypeId, TypeKind, TypeTable, linear_index};
use crate::syntax::ast::{Arg, BinaryOp, Expr, ExprKind, Initializer, LiteralValue, UnaryOp};
use indexmap::IndexMap;

/// Folds the constant expressions of declarations.
pub(super) struct DeclConsts<'a> {
    /// Types declared so far.
    pub(super) types: &'a TypeTable,
    /// Globals and type defaults declared so far.
    pub(super) model: &'a Model,
    /// Where errors go.
    pub(super) diags: &'a mut Diagnostics,
    /// The variables declared earlier in the VAR block whose initial value
    /// is being folded: their initial values may be read (CODESYS
    /// initialises a block's variables in order, so `b : INT := a;` sees
    /// `a`'s initial value, at start for static variables and at each call
    /// for temporaries), and for an FB's or PROGRAM's static variables
    /// also those of its earlier input, output and VAR blocks (layout.rs).
    /// Empty elsewhere, and for inputs (set by callers).
    pub(super) same_block: &'a [String],
    /// The global variables hold their initial values when this initial
    /// value is computed: true for a static variable (initialised at
    /// start, after the global lists); false for one set afresh at each
    /// call, which reads the globals as they are then (`computed_inits`).
    pub(super) globals_at_start: bool,
}

impl DeclConsts<'_> {
    /// Evaluates a constant integer expression (array bounds, lengths...).
    pub(super) fn const_int(
        &mut self,
        e: &Expr,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<i128> {
        let r = self.const_int_inner(e, local);
        if r.is_none() {
            match self.undeclared(e, local) {
                Some(name) => self.diags.error(
                    "E201",
                    e.span,
                    format!("undeclared constant `{name}` (a constant integer expression is expected here)"),
                ),
                None => self
                    .diags
                    .error("E205", e.span, "expected a constant integer expression"),
            }
        }
        r
    }

    fn const_int_inner(&self, e: &Expr, local: Option<&IndexMap<String, VarInfo>>) -> Option<i128> {
        if let Some(global) = self.list_qualified(e, local) {
            return self.const_int_inner(&global, local);
        }
        match &e.kind {
            ExprKind::Literal(l) => match l.value {
                LiteralValue::Int(v) => Some(v),
                _ => None,
            },
            ExprKind::Paren(x) => self.const_int_inner(x, local),
            ExprKind::Unary(UnaryOp::Neg, x) => self.const_int_inner(x, local).map(|v| -v),
            ExprKind::Unary(UnaryOp::Plus, x) => self.const_int_inner(x, local),
            ExprKind::Binary(op, a, b) => {
                let (a, b) = (
                    self.const_int_inner(a, local)?,
                    self.const_int_inner(b, local)?,
                );
                match op {
                    BinaryOp::Add => a.checked_add(b),
                    BinaryOp::Sub => a.checked_sub(b),
                    BinaryOp::Mul => a.checked_mul(b),
                    BinaryOp::Div => a.checked_div(b),
                    BinaryOp::Mod => a.checked_rem(b),
                    _ => None,
                }
            }
            ExprKind::Call(_) => self.const_sizeof(e, local),
            ExprKind::Name(id) => {
                let key = id.key();
                let var = local
                    .and_then(|l| l.get(&key))
                    .or_else(|| self.model.globals.get(&key))?;
                if !var.constant {
                    return None;
                }
                let e = self.types.scalar(var.ty)?;
                // A bit string constant counts as its unsigned value
                // (CODESYS: `ARRAY [1..MAX_LINES]` with `MAX_LINES : BYTE`).
                let counts = e.is_int() || e.family() == crate::elementary::Family::Bits;
                match var.value.as_ref()? {
                    Const::Bits(b) if counts => Some(slot_to_int(*b, e)),
                    Const::Int(v) => Some(*v),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// `GVL.x` or `Library.GVL.x` (a global named with its list or
    /// library, CODESYS and TwinCAT; see `place.rs`, `is_list_qualifier`)
    /// as the name `x`, when the qualifiers name no variable, POU or type
    /// and `x` is a global.
    fn list_qualified(&self, e: &Expr, local: Option<&IndexMap<String, VarInfo>>) -> Option<Expr> {
        let ExprKind::Member(base, name) = &e.kind else {
            return None;
        };
        let visible = |qk: &str| {
            local.is_some_and(|l| l.contains_key(qk))
                || self.model.globals.contains_key(qk)
                || self.model.pou_index.contains_key(qk)
                || self.model.type_ids.contains_key(qk)
        };
        let qualified = super::place::names_a_list(base, |key| !visible(key));
        (qualified && self.model.globals.contains_key(&name.key())).then(|| Expr {
            kind: ExprKind::Name(name.clone()),
            span: e.span,
        })
    }

    /// The value of `v` (named `key`) an initial value may read: a
    /// CONSTANT's, or the initial value of a scalar variable declared
    /// earlier in the same block (its type's default without one).
    fn readable_value(&self, key: &str, v: &VarInfo) -> Option<Const> {
        if v.constant {
            return v.value.clone();
        }
        if !self.same_block.iter().any(|k| k == key) || v.location.is_some() {
            return None;
        }
        match self.initial(v) {
            ConstInit::Scalar(b) => Some(Const::Bits(b)),
            ConstInit::Str(s) => Some(Const::Str(s)),
            _ => None,
        }
    }

    /// The initial value of a structure or array named by `e`, of the same
    /// type `ty`: a CONSTANT, a variable declared earlier in the same
    /// block, or a global variable (CODESYS initialises the global lists
    /// first: `PG : ST_VG := g_DummyVG;`, `st : ST_X := GVL.cstDefault;`).
    fn whole_value(
        &self,
        e: &Expr,
        ty: TypeId,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<ConstInit> {
        if let Some(global) = self.list_qualified(e, local) {
            return self.whole_value(&global, ty, local);
        }
        let e = match &e.kind {
            ExprKind::Paren(x) => return self.whole_value(x, ty, local),
            ExprKind::Name(id) => id,
            _ => return None,
        };
        let key = e.key();
        let (v, global) = self.variable(&key, local)?;
        let readable =
            v.constant || (global && self.globals_at_start) || self.same_block.contains(&key);
        (v.ty == ty && readable && v.location.is_none()).then(|| self.initial(v))
    }

    /// The variable `key` names: the POU's own (`local`), or else a global
    /// (then `true`).
    fn variable<'v>(
        &'v self,
        key: &str,
        local: Option<&'v IndexMap<String, VarInfo>>,
    ) -> Option<(&'v VarInfo, bool)> {
        match local.and_then(|l| l.get(key)) {
            Some(v) => Some((v, false)),
            None => Some((self.model.globals.get(key)?, true)),
        }
    }

    /// Resolves an initializer against type `ty`.
    pub(super) fn resolve_init(
        &mut self,
        init: &Initializer,
        ty: TypeId,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<ConstInit> {
        let def = self.types.get(ty).clone();
        match (init, &def.kind) {
            (_, TypeKind::Error) => None,
            (Initializer::Array(elems, span), TypeKind::Array { dims, elem }) => {
                let count: u64 = dims.iter().map(|d| d.len()).product();
                let mut out = Vec::new();
                for el in elems {
                    // `N(x)` with a named count reads as a call: a count
                    // that is an integer constant makes it a repetition
                    // (`[GVL.N_MAX(stDefault)]`).
                    let named = match (&el.repeat, &el.value) {
                        (None, Some(Initializer::Expr(e))) => self.named_repetition(e, local),
                        _ => None,
                    };
                    let n = match (&el.repeat, &named) {
                        (_, Some((n, _))) => *n,
                        (Some(r), None) => match self.const_int(r, local) {
                            Some(n) if n >= 0 => n as u64,
                            _ => return None,
                        },
                        (None, None) => 1,
                    };
                    let v = match (&named, &el.value) {
                        (Some((_, x)), _) => Some(self.resolve_init(
                            &Initializer::Expr((*x).clone()),
                            *elem,
                            local,
                        )?),
                        (None, Some(v)) => Some(self.resolve_init(v, *elem, local)?),
                        (None, None) => None,
                    };
                    for _ in 0..n.min(count + 1) {
                        out.push(
                            v.clone()
                                .unwrap_or_else(|| self.model.default_init(self.types, *elem)),
                        );
                    }
                }
                if out.len() as u64 > count {
                    self.diags.error(
                        "E301",
                        *span,
                        format!(
                            "{} initial values for an array of {count} elements",
                            out.len()
                        ),
                    );
                    return None;
                }
                Some(ConstInit::Array(out))
            }
            (Initializer::Struct(fields, _), TypeKind::Struct { fields: members }) => {
                let mut out = Vec::new();
                for (name, v) in fields {
                    match members
                        .iter()
                        .position(|m| m.name.eq_ignore_ascii_case(&name.name))
                    {
                        Some(i) => {
                            if let Some(ci) = self.resolve_init(v, members[i].ty, local) {
                                out.push((i, ci));
                            }
                        }
                        None => self.diags.error(
                            "E201",
                            name.span,
                            format!("`{}` has no field `{}`", def.name, name.name),
                        ),
                    }
                }
                Some(ConstInit::Struct(out))
            }
            (Initializer::Expr(e), _) => {
                if matches!(def.kind, TypeKind::Struct { .. } | TypeKind::Array { .. }) {
                    if let Some(whole) = self.whole_value(e, ty, local) {
                        return Some(whole);
                    }
                    if let Some(name) = self.undeclared(e, local) {
                        self.diags.error(
                            "E201",
                            e.span,
                            format!("undeclared variable `{name}`: a {} is initialised from a declared variable or constant of its type", def.name),
                        );
                        return None;
                    }
                }
                let c = self.const_value(e, ty, local)?;
                Some(match c {
                    Const::Str(s) => ConstInit::Str(s),
                    Const::Bits(b) => ConstInit::Scalar(b),
                    Const::Int(_) | Const::Real(_) => return None,
                })
            }
            (
                Initializer::Struct(fields, _),
                TypeKind::Pou { program: false, .. } | TypeKind::NativeFb(_),
            ) => Some(self.fb_instance_init(fields, &def, local)),
            (Initializer::Array(_, span), _) | (Initializer::Struct(_, span), _) => {
                self.diags.error(
                    "E301",
                    *span,
                    format!("this initializer does not fit type {}", def.name),
                );
                None
            }
        }
    }

    /// The name `e` gives when it declares nothing in scope: `x` that is
    /// no variable, `GVL.x` whose qualifier is none and `x` no global.
    fn undeclared(&self, e: &Expr, local: Option<&IndexMap<String, VarInfo>>) -> Option<String> {
        let known = |key: &str| {
            local.is_some_and(|l| l.contains_key(key))
                || self.model.globals.contains_key(key)
                || self.model.pou_index.contains_key(key)
                || self.model.type_ids.contains_key(key)
        };
        match &e.kind {
            ExprKind::Name(id) if !known(&id.key()) => Some(id.name.clone()),
            ExprKind::Member(base, name) => match &base.kind {
                ExprKind::Name(q) if !known(&q.key()) && !known(&name.key()) => {
                    Some(format!("{}.{}", q.name, name.name))
                }
                _ => None,
            },
            _ => None,
        }
    }

    /// `N(x)` where `N` (plain or list-qualified) is a non-negative integer
    /// constant and `x` the one argument: the count and the value.
    fn named_repetition<'e>(
        &self,
        e: &'e Expr,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<(u64, &'e Expr)> {
        let ExprKind::Call(call) = &e.kind else {
            return None;
        };
        let [Arg::Positional(value)] = call.args.as_slice() else {
            return None;
        };
        if !matches!(call.callee.kind, ExprKind::Name(_) | ExprKind::Member(..)) {
            return None;
        }
        let n = self.const_int_inner(&call.callee, local)?;
        Some((u64::try_from(n).ok()?, value))
    }

    /// Evaluates a constant scalar expression as a value of `ty`.
    pub(super) fn const_value(
        &mut self,
        e: &Expr,
        ty: TypeId,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<Const> {
        let def = self.types.get(ty).clone();
        // Enumerations: a value name, optionally qualified.
        if let TypeKind::Enum { values, .. } = &def.kind {
            if let Some(q) = super::enum_qualified::qualified(self.types, self.model, self.diags, e)
            {
                return match q {
                    Qualified::Value(t, v) if t == ty => Some(Const::Bits(v as u64)),
                    Qualified::Value(..) => {
                        self.diags.error(
                            "E301",
                            e.span,
                            format!("expected a value of enumeration {}", def.name),
                        );
                        None
                    }
                    Qualified::Unknown => None,
                };
            }
            if let ExprKind::Name(id) = &e.kind
                && super::enum_qualified::unqualified_use(
                    self.types,
                    self.model,
                    self.diags,
                    id,
                    Some(ty),
                )
            {
                return None;
            }
            let name = match &e.kind {
                ExprKind::Name(id) => Some(id.clone()),
                ExprKind::Literal(l) => match &l.value {
                    LiteralValue::EnumValue(v) => Some(v.clone()),
                    _ => None,
                },
                _ => None,
            };
            if let Some(id) = name
                && let Some((_, v)) = values
                    .iter()
                    .find(|(n, _)| n.eq_ignore_ascii_case(&id.name))
            {
                return Some(Const::Bits(*v as u64));
            }
            // A constant or an earlier variable of the same enumeration.
            if let ExprKind::Name(id) = &e.kind {
                let key = id.key();
                let var = local
                    .and_then(|l| l.get(&key))
                    .or_else(|| self.model.globals.get(&key));
                if let Some(v) = var.filter(|v| v.ty == ty)
                    && let Some(c @ Const::Bits(_)) = self.readable_value(&key, v)
                {
                    return Some(c);
                }
            }
            self.diags.error(
                "E301",
                e.span,
                format!("expected a value of enumeration {}", def.name),
            );
            return None;
        }
        // `p : POINTER TO T := 0;`: CODESYS's null pointer, spelled as the
        // address 0.
        if let TypeKind::Ref {
            flavor: RefFlavor::Pointer,
            ..
        } = def.kind
            && is_zero_literal(e)
        {
            return Some(Const::Bits(0));
        }
        if let Some(c) = self.enum_value_as_integer(e, ty, local) {
            return Some(c);
        }
        let Some(elem) = self.types.scalar(ty) else {
            self.diags.error(
                "E301",
                e.span,
                format!("a {} cannot be initialised with a single value", def.name),
            );
            return None;
        };
        let result = self.const_scalar(e, elem, local);
        match result {
            Ok(c) => {
                if let (TypeKind::Subrange { lo, hi, .. }, Const::Bits(b)) = (&def.kind, &c) {
                    let v = slot_to_int(*b, elem);
                    if v < *lo as i128 || v > *hi as i128 {
                        self.diags.error(
                            "E304",
                            e.span,
                            format!("{v} is outside the subrange {}", def.name),
                        );
                        return None;
                    }
                }
                Some(c)
            }
            Err((code, msg)) => {
                self.diags.error(code, e.span, msg);
                None
            }
        }
    }

    /// A value of an enumeration (`E_Kind.Move`, or a value name that is
    /// no variable and means one integer, not `qualified_only`) where an integer or bit
    /// string of type `ty` is expected: its integer, with W485 as in an
    /// assignment (CODESYS converts it implicitly). `None` for anything
    /// else, or a value `ty` does not hold.
    fn enum_value_as_integer(
        &mut self,
        e: &Expr,
        ty: TypeId,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<Const> {
        if !matches!(self.types.get(ty).kind, TypeKind::Elem(_)) {
            return None;
        }
        let elem = self.types.scalar(ty).filter(|t| t.is_int() || t.is_bit())?;
        let (from, v) = match &e.kind {
            ExprKind::Member(..) => {
                match super::enum_qualified::qualified(self.types, self.model, self.diags, e)? {
                    Qualified::Value(t, v) => (t, v),
                    Qualified::Unknown => return None,
                }
            }
            ExprKind::Name(id)
                if self.variable(&id.key(), local).is_none()
                    && !self.model.qualified_enum_values.contains_key(&id.key()) =>
            {
                // A named enumeration's values are registered for it and
                // for the anonymous type it is declared as: one value.
                let owners = self.model.enum_values.get(&id.key())?;
                let &(t, v) = owners.last()?;
                if owners.iter().any(|(_, w)| *w != v) {
                    return None;
                }
                (t, v)
            }
            _ => return None,
        };
        let bits = int_to_slot(v as i128, elem)?;
        let name = self.types.name(from).to_string();
        self.diags.warning(
            "W485",
            e.span,
            format!(
                "enumeration {name} used as an integer of type {} (a CODESYS extension)",
                elem.name()
            ),
        );
        Some(Const::Bits(bits))
    }

    fn const_scalar(
        &self,
        e: &Expr,
        elem: ElemType,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Result<Const, (&'static str, String)> {
        if let Some(global) = self.list_qualified(e, local) {
            return self.const_scalar(&global, elem, local);
        }
        match &e.kind {
            ExprKind::Paren(x) => self.const_scalar(x, elem, local),
            ExprKind::Literal(l) => {
                if let Some(prefix) = typed_literal(l)
                    && prefix != elem
                    && !prefix.widens_to(elem)
                {
                    return Err((
                        "E301",
                        format!("a {prefix} value cannot initialise a {elem}"),
                    ));
                }
                literal_to_slot(&l.value, elem).map_err(|m| ("E304", m))
            }
            ExprKind::Unary(UnaryOp::Neg, x) => {
                if let ExprKind::Literal(l) = &x.kind {
                    let neg = match &l.value {
                        LiteralValue::Int(v) => LiteralValue::Int(-v),
                        LiteralValue::Real(v) => LiteralValue::Real(-v),
                        LiteralValue::Duration { nanos, long } => LiteralValue::Duration {
                            nanos: -nanos,
                            long: *long,
                        },
                        other => other.clone(),
                    };
                    return literal_to_slot(&neg, elem).map_err(|m| ("E304", m));
                }
                match self.const_scalar(x, elem, local)? {
                    Const::Bits(b) if elem.is_real() => {
                        Ok(Const::Bits(if elem == ElemType::Real {
                            (-(f32::from_bits(b as u32))).to_bits() as u64
                        } else {
                            (-f64::from_bits(b)).to_bits()
                        }))
                    }
                    Const::Bits(b) => int_to_slot(-slot_to_int(b, elem), elem)
                        .map(Const::Bits)
                        .ok_or(("E305", format!("constant overflows {elem}"))),
                    other => Ok(other),
                }
            }
            ExprKind::Name(_) | ExprKind::Index(..) => {
                let Some(id) = root_name(e) else {
                    return Err(("E205", "initial values must be constant expressions".into()));
                };
                let read = self.read_variable(e, local);
                match read {
                    Some((value, ty)) => match (&Some(value), self.types.scalar(ty)) {
                        (Some(Const::Bits(b)), Some(t)) if t == elem => Ok(Const::Bits(*b)),
                        (Some(Const::Bits(b)), Some(t)) if t.widens_to(elem) => {
                            if t.is_int() && elem.is_real() {
                                let v = slot_to_int(*b, t);
                                Ok(Const::Bits(
                                    real_to_slot(v as f64, elem).unwrap_or_default(),
                                ))
                            } else if t == ElemType::Real && elem == ElemType::Lreal {
                                Ok(Const::Bits((f32::from_bits(*b as u32) as f64).to_bits()))
                            } else {
                                Ok(Const::Bits(*b))
                            }
                        }
                        (Some(Const::Str(s)), _) if elem.is_string() => Ok(Const::Str(s.clone())),
                        // CODESYS converts between integers and bit strings
                        // implicitly (`nID : DWORD := GVL.ID_UDINT`), keeping
                        // the low bits as in an assignment (W490 there).
                        (Some(Const::Bits(b)), Some(t))
                            if self.model.codesys_files.contains(&id.span.file)
                                && (super::bits_arith::codesys_widens(t, elem)
                                    || super::implicit_int::may_change(t, elem)) =>
                        {
                            Ok(Const::Bits(low_bits(slot_to_int(*b, t), elem)))
                        }
                        _ => Err(("E301", format!("constant `{}` is not a {elem}", id.name))),
                    },
                    None => Err((
                        "E205",
                        format!(
                            "`{}` is not a constant; an initial value may read constants and the variables declared before it (in the same VAR block; in a FUNCTION_BLOCK or PROGRAM, also its earlier VAR_INPUT, VAR_OUTPUT and VAR blocks)",
                            id.name
                        ),
                    )),
                }
            }
            ExprKind::Binary(op, a, b) => self.const_arithmetic(*op, a, b, elem, local),
            _ => Err(("E205", "initial values must be constant expressions".into())),
        }
    }

    /// `a op b` of constants, folded in `elem`: integer and real
    /// arithmetic, and sums and differences of durations.
    fn const_arithmetic(
        &self,
        op: BinaryOp,
        a: &Expr,
        b: &Expr,
        elem: ElemType,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Result<Const, (&'static str, String)> {
        // A duration from durations (`PT := GVL.tBase + T#1S`): summed as
        // the integers of its slots.
        let duration = elem.family() == crate::elementary::Family::Duration
            && matches!(op, BinaryOp::Add | BinaryOp::Sub);
        if !(elem.is_int() || elem.is_real() || duration) {
            return Err(("E205", "initial values must be constant expressions".into()));
        }
        let x = self.const_scalar(a, elem, local)?;
        let y = self.const_scalar(b, elem, local)?;
        let (Const::Bits(x), Const::Bits(y)) = (x, y) else {
            let what = if elem.is_int() {
                "not a constant integer expression"
            } else {
                "not a constant expression"
            };
            return Err(("E205", what.into()));
        };
        if elem.is_real() {
            let (x, y) = (
                super::consts::slot_to_real(x, elem),
                super::consts::slot_to_real(y, elem),
            );
            let r = match op {
                BinaryOp::Add => x + y,
                BinaryOp::Sub => x - y,
                BinaryOp::Mul => x * y,
                BinaryOp::Div => x / y,
                _ => return Err(("E205", "not a constant expression".into())),
            };
            return real_to_slot(r, elem)
                .map(Const::Bits)
                .ok_or(("E305", format!("constant overflows {elem}")));
        }
        let (x, y) = (slot_to_int(x, elem), slot_to_int(y, elem));
        let r = match op {
            BinaryOp::Add => x.checked_add(y),
            BinaryOp::Sub => x.checked_sub(y),
            BinaryOp::Mul => x.checked_mul(y),
            BinaryOp::Div if y != 0 => x.checked_div(y),
            BinaryOp::Mod if y != 0 => x.checked_rem(y),
            BinaryOp::Div | BinaryOp::Mod => {
                return Err(("E305", "division by zero in a constant".into()));
            }
            _ => return Err(("E205", "not a constant integer expression".into())),
        };
        r.and_then(|v| int_to_slot(v, elem))
            .map(Const::Bits)
            .ok_or(("E305", format!("constant overflows {elem}")))
    }
}

impl DeclConsts<'_> {
    /// The value and type an initial value reads from variable `e` (a
    /// name, or an element of an array at constant indexes): a constant's,
    /// an earlier variable's of the same block ([`Self::readable_value`]),
    /// or a global variable's initial value, CODESYS initialising the global
    /// lists before the POUs (`MaxEv : REAL := GVL.aBounds[GVL.N];`).
    fn read_variable(
        &self,
        e: &Expr,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<(Const, TypeId)> {
        if let Some(global) = self.list_qualified(e, local) {
            return self.read_variable(&global, local);
        }
        match &e.kind {
            ExprKind::Name(id) => {
                let key = id.key();
                let (var, global) = self.variable(&key, local)?;
                let value = self.readable_value(&key, var).or_else(|| {
                    let global = global && var.location.is_none() && self.globals_at_start;
                    global.then(|| init_const(&self.initial(var))).flatten()
                })?;
                Some((value, var.ty))
            }
            ExprKind::Index(base, index) => {
                let ExprKind::Name(id) = &self
                    .list_qualified(base, local)
                    .unwrap_or(*base.clone())
                    .kind
                else {
                    return None;
                };
                let key = id.key();
                let (var, global) = self.variable(&key, local)?;
                let readable = var.constant
                    || (global && var.location.is_none() && self.globals_at_start)
                    || self.same_block.contains(&key);
                let TypeKind::Array { dims, elem } = &self.types.get(var.ty).kind else {
                    return None;
                };
                if !readable || dims.len() != index.len() {
                    return None;
                }
                let values: Vec<i128> = index
                    .iter()
                    .map(|i| self.const_int_inner(i, local))
                    .collect::<Option<_>>()?;
                let linear = linear_index(dims, &values)?;
                // An array without initial values holds its element's default.
                let values = match self.initial(var) {
                    ConstInit::Array(values) => values,
                    _ => Vec::new(),
                };
                let value = match values.get(usize::try_from(linear).ok()?) {
                    Some(ci) => init_const(ci)?,
                    // Past the values given: the element type's default.
                    None => init_const(&self.model.default_init(self.types, *elem))?,
                };
                Some((value, *elem))
            }
            _ => None,
        }
    }

    /// A variable's initial value (its type's default without one).
    fn initial(&self, v: &VarInfo) -> ConstInit {
        v.init
            .clone()
            .unwrap_or_else(|| self.model.default_init(self.types, v.ty))
    }
}

/// The variable an expression reads: `x`, `x[i]`, `GVL.x[i]` name `x`
/// (the list qualifier aside).
fn root_name(e: &Expr) -> Option<&crate::syntax::ast::Ident> {
    match &e.kind {
        ExprKind::Name(id) => Some(id),
        ExprKind::Index(base, _) => root_name(base),
        ExprKind::Member(_, id) => Some(id),
        _ => None,
    }
}

/// The folded value of a scalar initializer, for CONSTANT variables.
pub(super) fn init_const(ci: &ConstInit) -> Option<Const> {
    match ci {
        ConstInit::Scalar(b) => Some(Const::Bits(*b)),
        ConstInit::Str(s) => Some(Const::Str(s.clone())),
        _ => None,
    }
}

/// True for the integer literal `0` (in parentheses or not).
fn is_zero_literal(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Paren(x) => is_zero_literal(x),
        ExprKind::Literal(l) => matches!(l.value, LiteralValue::Int(0)),
        _ => false,
    }
}

/// The slot of a `to` holding the low bits of `v` (two's complement),
/// sign-extended when `to` is signed.
fn low_bits(v: i128, to: ElemType) -> u64 {
    let width = to.bits();
    let low = (v as u128 & ((1u128 << width) - 1)) as u64;
    if to.is_signed_int() && width < 64 && low >> (width - 1) & 1 == 1 {
        low | !((1u64 << width) - 1)
    } else {
        low
    }
}
