//! CODESYS code clears and copies whole structures by bytes:
//! `MEMSET(ADR(st), 0, SIZEOF(st))`, `MEMCPY(ADR(a), ADR(b), SIZEOF(b))`,
//! `MEMCPY(ADR(aDst), ADR(aSrc), N * SIZEOF(ST_Item))`. plcrun's memory is
//! typed slots, and a structure or an array of structures or strings has
//! no byte layout (a byte view of one faults, R037). When such a call
//! covers whole values of one type — a constant count of bytes that is a
//! whole number of them, inside both objects — it is lowered to what it
//! means on typed memory: a clear to zero (numbers 0, strings empty,
//! pointers NULL) or a copy by value, field by field. A structure
//! declared `EXTENDS` another (directly or not) may be copied to or from
//! its base part.
//! Anything else keeps the byte-by-byte library call (and its fault).

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use super::refs::size_bytes;
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::syntax::ast::{Arg, BinaryOp, Call, Expr, ExprKind};

/// Which memory function a call is.
#[derive(Clone, Copy, PartialEq)]
enum MemoryFn {
    /// `MEMSET(destAddr, fillByte, n)`.
    Set,
    /// `MEMCPY(destAddr, srcAddr, n)` or `MEMMOVE`.
    Copy,
}

impl MemoryFn {
    fn of(name: &str) -> Option<Self> {
        match name.to_ascii_uppercase().as_str() {
            "MEMSET" => Some(Self::Set),
            "MEMCPY" | "MEMMOVE" => Some(Self::Copy),
            _ => None,
        }
    }

    /// The parameters, in declaration order.
    fn params(self) -> [&'static str; 3] {
        match self {
            Self::Set => ["DESTADDR", "FILLBYTE", "N"],
            Self::Copy => ["DESTADDR", "SRCADDR", "N"],
        }
    }
}

/// The three arguments of a memory function call, in parameter order.
fn arguments(f: MemoryFn, call: &Call) -> Option<[&Expr; 3]> {
    let mut out: [Option<&Expr>; 3] = [None; 3];
    let mut next = 0;
    for arg in &call.args {
        let (i, e) = match arg {
            Arg::Positional(e) => {
                next += 1;
                (next - 1, e)
            }
            Arg::Input { name, value } => {
                let key = name.key();
                (f.params().iter().position(|p| *p == key)?, value)
            }
            _ => return None,
        };
        if i >= 3 || out[i].is_some() {
            return None;
        }
        out[i] = Some(e);
    }
    Some([out[0]?, out[1]?, out[2]?])
}

/// The variable `ADR(x)` takes the address of.
fn address_operand(e: &Expr) -> Option<&Expr> {
    let ExprKind::Call(call) = &e.kind else {
        return None;
    };
    let ExprKind::Name(f) = &call.callee.kind else {
        return None;
    };
    match call.args.as_slice() {
        [Arg::Positional(x)] if f.name.eq_ignore_ascii_case("ADR") => Some(x),
        _ => None,
    }
}

/// Whether `e` is a literal or a `SIZEOF` call (lowering either emits
/// no code).
fn constant_shape(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Literal(_) => true,
        ExprKind::Call(c) => {
            matches!(&c.callee.kind, ExprKind::Name(f) if f.name.eq_ignore_ascii_case("SIZEOF"))
        }
        _ => false,
    }
}

impl BodyBuilder<'_> {
    /// `MEMSET`, `MEMCPY` or `MEMMOVE` (plcrun's TwinCAT library, or a
    /// CODESYS-dialect file's own) over whole typed values, lowered as the
    /// module says; `None` when the call is not one (it is then called).
    pub(super) fn memory_idiom(&mut self, p: usize, call: &Call, want: bool) -> Option<Val> {
        let callee = &self.model.pous[p];
        let f = MemoryFn::of(&callee.name)?;
        let params: Vec<String> = callee
            .params
            .iter()
            .map(|n| n.to_ascii_uppercase())
            .collect();
        if !self.model.codesys_files.contains(&callee.span.file) || params != f.params() {
            return None;
        }
        let [dest, second, count] = arguments(f, call)?;
        let x = address_operand(dest)?;
        let dest_ty = self.static_type(x)?;
        // The source of a copy, with its type.
        let src = match f {
            MemoryFn::Set => None,
            MemoryFn::Copy => {
                let y = address_operand(second)?;
                Some((y, self.static_type(y)?))
            }
        };
        if byte_layout(self.types, dest_ty) && src.is_none_or(|(_, t)| byte_layout(self.types, t)) {
            return None;
        }
        let n = self.constant_count(count)?;
        match src {
            None => {
                if self.constant_count(second)? != 0 {
                    return None;
                }
                let (elem, count) = self.zero_plan(dest_ty, n)?;
                let d = self.place(x)?;
                let d = self.address_of(&d);
                self.zero_elems(d, elem, 0, count);
            }
            Some((y, src_ty)) => {
                let (elem, count) = self.copy_plan(dest_ty, src_ty, n)?;
                let d = self.place(x)?;
                let d = self.address_of(&d);
                let s = self.place(y)?;
                let s = self.address_of(&s);
                self.copy_elems(d, s, elem, 0, count);
            }
        }
        Some(if want {
            Val::Const(
                Const::Int(n as i128),
                Ty::T(TypeTable::elem(ElemType::Udint)),
            )
        } else {
            Val::None(TypeTable::void())
        })
    }

    /// The value of `e` when it is a non-negative integer constant.
    fn constant_count(&mut self, e: &Expr) -> Option<u64> {
        u64::try_from(self.constant_int(e)?).ok()
    }

    /// The value of integer constant expression `e`: literals, named
    /// constants (also qualified by their list, `GVL.N`), `SIZEOF` and
    /// `+ - *` on them. Only `SIZEOF` and literals are lowered (they
    /// emit no code); anything else is `None` before emitting.
    fn constant_int(&mut self, e: &Expr) -> Option<i128> {
        let named = |b: &Self, key: String| match b.lookup_var(&key)?.value.clone()? {
            Const::Int(v) => Some(v),
            Const::Bits(v) => Some(i128::from(v)),
            _ => None,
        };
        match &e.kind {
            ExprKind::Paren(x) => self.constant_int(x),
            ExprKind::Name(id) => named(self, id.key()),
            ExprKind::Member(base, n) if self.is_list_qualifier(base, n) => named(self, n.key()),
            ExprKind::Binary(op, a, b) => {
                let (a, b) = (self.constant_int(a)?, self.constant_int(b)?);
                match op {
                    BinaryOp::Add => a.checked_add(b),
                    BinaryOp::Sub => a.checked_sub(b),
                    BinaryOp::Mul => a.checked_mul(b),
                    _ => None,
                }
            }
            ExprKind::Literal(_) | ExprKind::Call(_) if constant_shape(e) => {
                match self.expr(e, None) {
                    Val::Const(Const::Int(v), _) => Some(v),
                    Val::Const(Const::Bits(v), _) => Some(i128::from(v)),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// Clearing `n` bytes from the start of a `ty`: how many values of
    /// which type.
    fn zero_plan(&self, ty: TypeId, n: u64) -> Option<(TypeId, u64)> {
        let (elem, len) = units(self.types, ty);
        let count = whole_units(self.types, elem, n)?;
        (count <= len && self.can_zero(elem)).then_some((elem, count))
    }

    /// Copying `n` bytes from the start of a `src` to that of a `dest`:
    /// how many values of which type.
    fn copy_plan(&self, dest: TypeId, src: TypeId, n: u64) -> Option<(TypeId, u64)> {
        let (de, dl) = units(self.types, dest);
        let (se, sl) = units(self.types, src);
        if de == se {
            let count = whole_units(self.types, de, n)?;
            return (count <= dl.min(sl)).then_some((de, count));
        }
        // A structure and its base (`EXTENDS`): the base's part.
        let base = if self.extends_structure(dest, src) {
            src
        } else if self.extends_structure(src, dest) {
            dest
        } else {
            return None;
        };
        (size_bytes(self.types, base)? == n).then_some((base, 1))
    }
}

/// Whether a byte view of a `ty` works (docs/semantics.md, byte views):
/// an elementary value, a STRING, or an array of elementary values.
fn byte_layout(types: &TypeTable, ty: TypeId) -> bool {
    let scalar = |t: TypeId| {
        matches!(
            types.get(t).kind,
            TypeKind::Elem(_)
                | TypeKind::Enum { .. }
                | TypeKind::Subrange { .. }
                | TypeKind::Ref { .. }
        )
    };
    match &types.get(ty).kind {
        TypeKind::Str { .. } => true,
        TypeKind::Array { elem, .. } => scalar(*elem),
        _ => scalar(ty),
    }
}

/// A `ty` seen as consecutive values: an array's elements, or itself.
fn units(types: &TypeTable, ty: TypeId) -> (TypeId, u64) {
    match &types.get(ty).kind {
        TypeKind::Array { dims, elem } => (*elem, dims.iter().map(|d| d.len()).product()),
        _ => (ty, 1),
    }
}

/// How many `elem`s `n` bytes are, when they are a whole number of them.
fn whole_units(types: &TypeTable, elem: TypeId, n: u64) -> Option<u64> {
    let b = size_bytes(types, elem)?;
    (b > 0 && n.is_multiple_of(b)).then_some(n / b)
}
