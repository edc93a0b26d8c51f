//! Places: the storage an expression denotes (a variable, a direct
//! address, a member of a structure or an instance, an array element),
//! with its type and whether the current body may write it.

use super::body::BodyBuilder;
use super::consts::{Const, slot_to_int};
use super::declare::{address_type, normalize_address};
use super::emit::{Place, PlaceRef, Ty, Val};
use super::model::{Storage, VarInfo};
use crate::elementary::ElemType;
use crate::ir::image::ArrayDesc;
use crate::ir::op::NativeFb;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{
    Dim, Member, MemberKind, RefFlavor, TypeDef, TypeId, TypeKind, TypeTable, step_layout,
};
use crate::source::Span;
use crate::syntax::ast::{DirectAddress, Expr, ExprKind, Ident, PouKind};

/// The shape of an indexed array for element access.
#[derive(Clone, Copy)]
struct ElemShape {
    /// Lower bound of the element number (0 after linearisation).
    lo: i64,
    /// Number of elements.
    total: u64,
    /// Element size in slots.
    stride: u32,
    /// One dimension (the index variable is the element number).
    one_dim: bool,
}

/// True when `base` is the qualifier of a global named with its list,
/// `GVL` in `GVL.x`, or with its library and list, `Library.GVL` in
/// `Library.GVL.x` (`lcls_twincat_math.GVL_Constants.PI`): names for which
/// `unbound` is true (they name nothing in scope).
pub(super) fn names_a_list(base: &Expr, unbound: impl Fn(&str) -> bool) -> bool {
    match &base.kind {
        ExprKind::Name(q) => unbound(&q.key()),
        ExprKind::Member(library, list) => {
            matches!(&library.kind, ExprKind::Name(l) if unbound(&l.key())) && unbound(&list.key())
        }
        _ => false,
    }
}

impl BodyBuilder<'_> {
    /// True for `Q.x` where `Q` names nothing visible (no variable, POU or
    /// type) and `x` is a global variable: CODESYS and TwinCAT name a
    /// global with its global variable list or library (`GVL_Io.bStart`,
    /// `GVL_Constants.PI`). plcrun has one namespace for globals, so the
    /// qualifier itself is not checked.
    pub(super) fn is_list_qualifier(&self, base: &Expr, name: &Ident) -> bool {
        names_a_list(base, |key| self.unbound_key(key))
            && self.model.globals.contains_key(&name.key())
    }

    /// True when `base` is a bare name that is no variable, POU, type or
    /// enumeration value in scope.
    fn names_nothing(&self, base: &Expr) -> bool {
        self.unbound_name(base)
            .is_some_and(|k| !self.model.enum_values.contains_key(&k))
    }

    /// The key of `base` when it is a bare name that is no variable, POU
    /// or type in scope.
    fn unbound_name(&self, base: &Expr) -> Option<String> {
        let ExprKind::Name(q) = &base.kind else {
            return None;
        };
        let qk = q.key();
        self.unbound_key(&qk).then_some(qk)
    }

    /// True when `key` names no variable, POU or type in scope.
    fn unbound_key(&self, key: &str) -> bool {
        self.lookup_var(key).is_none()
            && !self.model.pou_index.contains_key(key)
            && !self.model.type_ids.contains_key(key)
    }

    /// Reads the place `e` denotes as a scalar value.
    pub(super) fn place_value(&mut self, e: &Expr) -> Val {
        let Some(p) = self.place(e) else {
            return Val::error();
        };
        let is_ref = matches!(self.types.get(p.ty).kind, TypeKind::Ref { .. });
        if !is_ref
            && (!self.types.get(p.ty).kind.is_value_type() || self.types.scalar(p.ty).is_none())
        {
            if p.ty != TypeTable::error() {
                self.diags.error(
                    "E302",
                    e.span,
                    format!("a {} cannot be used as a value here", self.types.name(p.ty)),
                );
            }
            return Val::error();
        }
        self.read_place(&p)
    }

    /// Resolves an expression that denotes a storage location (a
    /// `REFERENCE TO` variable denotes the variable it is bound to).
    pub(super) fn place(&mut self, e: &Expr) -> Option<PlaceRef> {
        let p = self.place_raw(e)?;
        Some(self.implicit_deref(p))
    }

    /// As [`Self::place`], but a `REFERENCE TO` variable is itself.
    pub(super) fn place_raw(&mut self, e: &Expr) -> Option<PlaceRef> {
        match &e.kind {
            ExprKind::Paren(x) => self.place(x),
            ExprKind::Name(id) => self.place_name(id),
            ExprKind::Direct(a) => self.place_direct(a),
            ExprKind::Member(base, name) => match self.property_get_call(e) {
                Some(get) => self.call_place(&get),
                None => self.place_member(base, name),
            },
            ExprKind::Index(base, indexes) => self.place_index(e, base, indexes),
            ExprKind::Call(call) => self.call_place(call),
            ExprKind::Deref(r) => self.place_deref(r),
            _ => {
                self.diags
                    .error("E402", e.span, "this expression is not a variable");
                None
            }
        }
    }

    /// A declared variable (or the IL current result).
    fn place_name(&mut self, id: &Ident) -> Option<PlaceRef> {
        let key = id.key();
        let Some(var) = self.lookup_var(&key).cloned() else {
            if self.model.pou_index.contains_key(&key) {
                let what = format!("`{}` is a POU, not a variable", id.name);
                self.diags.error("E201", id.span, what);
            } else {
                self.undeclared_variable(id);
            }
            return None;
        };
        self.place_of(id, var)
    }

    /// `THIS^.name`: the instance's own variable, also in a METHOD that
    /// declares one of the same name (`THIS^.AxisRef REF= AxisRef;` in an
    /// `FB_init` whose input is `AxisRef`), where `name` alone is the
    /// method's.
    fn place_this_member(&mut self, id: &Ident) -> Option<PlaceRef> {
        let key = id.key();
        if self.oop_local(&key).is_some() {
            let member = self.model.pous.get(self.block.pou);
            if let Some(var) = member.and_then(|p| p.vars.get(&key)).cloned() {
                return self.place_of(id, var);
            }
        }
        self.place_name(id)
    }

    /// The place of variable `var`, named `id`.
    fn place_of(&mut self, id: &Ident, var: VarInfo) -> Option<PlaceRef> {
        self.check_inherited_private(id);
        let place = match var.storage {
            Storage::Frame(o) => Place::Frame(Slot::new(o)),
            Storage::Abs(a) => Place::Abs(a),
            Storage::Ref(o) => Place::Ind {
                p: Slot::new(o),
                off: 0,
            },
        };
        let own_input = var.kind == MemberKind::Input
            && self
                .model
                .pous
                .get(self.block.pou)
                .is_some_and(|p| matches!(p.kind, PouKind::Function | PouKind::FunctionBlock));
        let reason = if var.constant {
            Some("it is a CONSTANT")
        } else if var.kind == MemberKind::Step {
            Some("step flags are read-only")
        } else if var.kind == MemberKind::Action {
            Some("action flags are read-only")
        } else {
            None
        };
        Some(PlaceRef {
            place,
            ty: var.ty,
            writable: reason.is_none(),
            readonly_reason: reason.or(own_input.then_some(super::input_write::OWN_INPUT)),
            input_image: var.location.as_deref().is_some_and(|l| l.starts_with("%I")),
        })
    }

    /// A direct address (`%IX0.1`), declared or not.
    fn place_direct(&mut self, a: &DirectAddress) -> Option<PlaceRef> {
        let key = normalize_address(a);
        let (addr, ty) = match self.out.located.get(&key) {
            Some(&(addr, ty)) => (addr, ty),
            None => {
                let ty = TypeTable::elem(address_type(a));
                (self.out.located_slot(self.types, self.diags, a, ty)?, ty)
            }
        };
        Some(PlaceRef {
            place: Place::Abs(addr),
            ty,
            writable: true,
            readonly_reason: None,
            input_image: key.starts_with("%I"),
        })
    }

    /// A member of a structure or an instance: `base.name`.
    fn place_member(&mut self, base: &Expr, name: &Ident) -> Option<PlaceRef> {
        if self.is_list_qualifier(base, name) {
            // `GVL.x`: a global variable named with its list (or library).
            return self.place_name(name);
        }
        // `SUPER^.x`: the parent's variables are the instance's own (an
        // FB may not declare a name its parent declares).
        if super::oop::calls::is_this(base) {
            return self
                .this_allowed(base.span)
                .then(|| self.place_this_member(name))?;
        }
        if super::oop::calls::is_super(base) {
            return self
                .super_allowed(base.span)
                .then(|| self.place_name(name))?;
        }
        if self.names_nothing(base) {
            if let ExprKind::Name(q) = &base.kind {
                self.undeclared_qualifier(q, Some(name));
            }
            return None;
        }
        let b = self.place(base)?;
        if let Some(p) = self.union_member(&b, name) {
            return Some(p);
        }
        let def = self.types.get(b.ty).clone();
        let (offset, ty, writable, reason) = match &def.kind {
            TypeKind::Struct { fields } => self.struct_field(&def, fields, name, &b)?,
            TypeKind::NativeFb(fb) => self.native_pin(&def, *fb, name, &b)?,
            TypeKind::Pou { members, .. } => {
                if let Some(p) = self.in_out_from_outside(&def, members, name, &b) {
                    return Some(p);
                }
                self.pou_member(&def, members, name, &b)?
            }
            TypeKind::Step => {
                let (off, ty) = match name.key().as_str() {
                    "X" => (step_layout::X, TypeTable::elem(ElemType::Bool)),
                    "T" => (step_layout::T, TypeTable::elem(ElemType::Time)),
                    _ => {
                        self.diags.error(
                            "E201",
                            name.span,
                            format!("a step has only `.X` and `.T`, not `.{}`", name.name),
                        );
                        return None;
                    }
                };
                (off, ty, false, Some("step flags are read-only"))
            }
            TypeKind::Error => return None,
            _ => {
                self.diags
                    .error("E302", name.span, format!("a {} has no members", def.name));
                return None;
            }
        };
        let place = self.offset_place(b.place, offset);
        Some(PlaceRef {
            place,
            ty,
            writable,
            readonly_reason: reason,
            input_image: b.input_image,
        })
    }

    /// A field of a structure.
    fn struct_field(
        &mut self,
        def: &TypeDef,
        fields: &[Member],
        name: &Ident,
        b: &PlaceRef,
    ) -> Option<(u32, TypeId, bool, Option<&'static str>)> {
        let m = fields
            .iter()
            .find(|m| m.name.eq_ignore_ascii_case(&name.name));
        match m {
            Some(m) => Some((m.offset, m.ty, b.writable, b.readonly_reason)),
            None => {
                let message = format!("`{}` has no field `{}`", def.name, name.name);
                let names = fields.iter().map(|m| m.name.as_str());
                let message = super::suggest::with_suggestion(message, &name.name, names);
                self.diags.error("E201", name.span, message);
                None
            }
        }
    }

    /// An input or output of a standard function block instance.
    fn native_pin(
        &mut self,
        def: &TypeDef,
        fb: NativeFb,
        name: &Ident,
        b: &PlaceRef,
    ) -> Option<(u32, TypeId, bool, Option<&'static str>)> {
        let params = crate::stdlib::interface(fb);
        let found = params.iter().enumerate().find(|(_, p)| {
            p.name.eq_ignore_ascii_case(&name.name)
                || p.aliases.iter().any(|a| a.eq_ignore_ascii_case(&name.name))
        });
        match found {
            Some((i, p)) if p.dir != crate::stdlib::ParamDir::Hidden => {
                let is_out = p.dir == crate::stdlib::ParamDir::Output;
                Some((
                    i as u32,
                    TypeTable::elem(p.ty),
                    !is_out && b.writable,
                    if is_out {
                        Some("outputs of a function block are written only by the block")
                    } else {
                        b.readonly_reason
                    },
                ))
            }
            _ => {
                let message = format!("{} has no input or output `{}`", def.name, name.name);
                let names = params
                    .iter()
                    .filter(|p| p.dir != crate::stdlib::ParamDir::Hidden)
                    .map(|p| p.name);
                let message = super::suggest::with_suggestion(message, &name.name, names);
                self.diags.error("E201", name.span, message);
                None
            }
        }
    }

    /// An input, output, step or action of a POU instance (the rest is
    /// internal).
    fn pou_member(
        &mut self,
        def: &TypeDef,
        members: &[Member],
        name: &Ident,
        b: &PlaceRef,
    ) -> Option<(u32, TypeId, bool, Option<&'static str>)> {
        let m = members
            .iter()
            .find(|m| m.name.eq_ignore_ascii_case(&name.name));
        match m {
            Some(m)
                if matches!(
                    m.kind,
                    MemberKind::Input | MemberKind::Output | MemberKind::Step | MemberKind::Action
                ) =>
            {
                let ro = match m.kind {
                    MemberKind::Output => Some(super::in_out_constant::FB_OUTPUT),
                    MemberKind::Step => Some("step flags are read-only"),
                    MemberKind::Action => Some("action flags are read-only"),
                    _ => b.readonly_reason,
                };
                let own = matches!(
                    m.kind,
                    MemberKind::Output | MemberKind::Step | MemberKind::Action
                );
                Some((m.offset, m.ty, !own && b.writable, ro))
            }
            Some(m) => self.fb_member_outside(def, m, name),
            None => {
                let message = format!("{} has no member `{}`", def.name, name.name);
                let names = members.iter().map(|m| m.name.as_str());
                let message = super::suggest::with_suggestion(message, &name.name, names);
                self.diags.error("E201", name.span, message);
                None
            }
        }
    }

    /// The dimensions and element type of the array type `ty` indexed by
    /// `given` indexes in `e` (E302 when it is not an array, E404 when the
    /// count differs).
    pub(in crate::sema) fn array_shape(
        &mut self,
        e: &Expr,
        ty: TypeId,
        given: usize,
    ) -> Option<(Vec<Dim>, TypeId)> {
        let TypeKind::Array { dims, elem } = self.types.get(ty).kind.clone() else {
            if ty != TypeTable::error() {
                self.diags.error(
                    "E302",
                    e.span,
                    format!("`[...]` needs an array, found {}", self.types.name(ty)),
                );
            }
            return None;
        };
        if given != dims.len() {
            self.diags.error(
                "E404",
                e.span,
                format!(
                    "array has {} dimension(s), {} index(es) given",
                    dims.len(),
                    given
                ),
            );
            return None;
        }
        Some((dims, elem))
    }

    /// An array element: `base[i, j, ...]`.
    fn place_index(&mut self, e: &Expr, base: &Expr, indexes: &[Expr]) -> Option<PlaceRef> {
        if let ExprKind::Deref(r) = &base.kind {
            // Checked element by element against the referenced object.
            return self.place_deref_index(e, r, indexes);
        }
        if self.is_pointer_path(base) {
            return self.pointer_index(e, base, indexes);
        }
        let b = self.place(base)?;
        if let Place::View { r, .. } = b.place {
            // An array member of a UNION: its elements are byte views.
            return self.reference_element(e, r, b.ty, RefFlavor::Pointer, indexes);
        }
        if self.is_open_array(b.ty) {
            return self.open_array_element(e, base, &b, indexes);
        }
        if let Some(byte) = self.string_byte(&b, indexes, e) {
            return byte;
        }
        let (dims, elem) = self.array_shape(e, b.ty, indexes.len())?;
        let elem_size = self.types.size(elem);
        let checked = self.bounds_checked(indexes, &dims);
        let vals = self.index_values(checked.as_deref().unwrap_or(indexes))?;
        // All indexes constant: a static offset, checked now.
        if vals.iter().all(|(v, _)| matches!(v, Val::Const(..))) {
            let linear = self.constant_index(&vals, &dims)?;
            let place = self.offset_place(b.place, (linear * elem_size as u64) as u32);
            return Some(PlaceRef {
                place,
                ty: elem,
                ..b
            });
        }
        // Dynamic: linearise with checked steps.
        let total: u64 = dims.iter().map(|d| d.len()).product();
        let idx = self.dynamic_index(&vals, &dims);
        let lo = if dims.len() == 1 { dims[0].lo } else { 0 };
        let shape = ElemShape {
            lo,
            total,
            stride: elem_size,
            one_dim: dims.len() == 1,
        };
        self.element_place(e, b, idx, elem, shape)
    }

    /// Evaluates array indexes (integers; an enumeration as its base
    /// type's integer, W485, as CODESYS allows it).
    pub(super) fn index_values(&mut self, indexes: &[Expr]) -> Option<Vec<(Val, Span)>> {
        let mut vals = Vec::new();
        for ix in indexes {
            let v = self.expr(ix, None);
            let ok = match v.ty() {
                Ty::AnyInt => true,
                Ty::T(t) => self.scalar(t).is_some_and(|e| e.is_int()) && !self.is_enum(t),
                Ty::AnyReal => false,
            } || self.codesys_bit_string_index(&v, ix.span)
                || self.enum_index(&v, ix.span);
            if !ok {
                if !v.is_error() {
                    self.diags.error(
                        "E301",
                        ix.span,
                        format!(
                            "array index must be an integer, found {}",
                            self.ty_name(v.ty())
                        ),
                    );
                }
                return None;
            }
            vals.push((v, ix.span));
        }
        Some(vals)
    }

    /// The linear position of constant indexes, checked against the bounds.
    fn constant_index(&mut self, vals: &[(Val, Span)], dims: &[Dim]) -> Option<u64> {
        let mut linear: u64 = 0;
        for ((v, span), d) in vals.iter().zip(dims) {
            let i = match v {
                Val::Const(Const::Int(i), _) => *i,
                Val::Const(Const::Bits(b), Ty::T(t)) => {
                    slot_to_int(*b, self.scalar(*t).unwrap_or(ElemType::Dint))
                }
                _ => 0,
            };
            if i < d.lo as i128 || i > d.hi as i128 {
                self.diags.error(
                    "E304",
                    *span,
                    format!("index {i} is outside the array bounds [{}..{}]", d.lo, d.hi),
                );
                return None;
            }
            linear = linear * d.len() + (i - d.lo as i128) as u64;
        }
        Some(linear)
    }

    /// The element number of dynamic indexes in a slot: the index itself for
    /// one dimension, else a linearisation checked per dimension.
    pub(super) fn dynamic_index(&mut self, vals: &[(Val, Span)], dims: &[Dim]) -> Slot {
        if dims.len() == 1 {
            let v = vals[0].0.clone();
            self.materialize(&v)
        } else {
            let acc = self.block.temp();
            self.block.emit(Op::LoadI { d: acc, imm: 0 });
            for ((v, span), d) in vals.iter().zip(dims) {
                let s = self.materialize(v);
                let desc = self.out.array_desc(ArrayDesc {
                    offset: 0,
                    lo: d.lo,
                    len: d.len(),
                    stride: 1,
                    span: *span,
                });
                self.block.emit(Op::IndexStep { acc, idx: s, desc });
            }
            acc
        }
    }

    /// The place of element `idx` of the array at `b`: checked element
    /// access for scalars in the frame, else an element address (cached per
    /// basic block for arrays of the frame).
    fn element_place(
        &mut self,
        e: &Expr,
        b: PlaceRef,
        idx: Slot,
        elem: TypeId,
        shape: ElemShape,
    ) -> Option<PlaceRef> {
        let scalar_elem = self.types.scalar(elem).is_some();
        match b.place {
            Place::Frame(o) if scalar_elem => {
                let desc = self.out.array_desc(ArrayDesc {
                    offset: o.get(),
                    lo: shape.lo,
                    len: shape.total,
                    stride: shape.stride,
                    span: e.span,
                });
                Some(PlaceRef {
                    place: Place::Elem { idx, desc },
                    ty: elem,
                    ..b
                })
            }
            Place::Frame(o) => {
                // Arrays of FBs or structures in this frame: the
                // element address, reused within the basic block.
                let key = (o.get(), shape.lo, shape.total, shape.stride);
                let cacheable = idx.get() < self.block.vars_size && shape.one_dim;
                let cached = self
                    .block
                    .elem_cache
                    .iter()
                    .find(|c| cacheable && c.key == key && c.idx == idx)
                    .map(|c| c.ptr);
                let p = match cached {
                    Some(p) => p,
                    None => {
                        let desc = self.out.array_desc(ArrayDesc {
                            offset: o.get(),
                            lo: shape.lo,
                            len: shape.total,
                            stride: shape.stride,
                            span: e.span,
                        });
                        let p = if cacheable {
                            self.block.pin()
                        } else {
                            self.block.temp()
                        };
                        self.block.emit(Op::ElemRef { d: p, idx, desc });
                        self.block.last_def = None;
                        if cacheable {
                            self.block
                                .elem_cache
                                .push(super::emit::ElemEntry { key, idx, ptr: p });
                        }
                        p
                    }
                };
                Some(PlaceRef {
                    place: Place::Ind { p, off: 0 },
                    ty: elem,
                    ..b
                })
            }
            _ => {
                let base_ptr = self.address_of(&b);
                let fresh = self.block.temp();
                self.block.emit(Op::Mov {
                    d: fresh,
                    s: base_ptr,
                });
                let base_ptr = fresh;
                let desc = self.out.array_desc(ArrayDesc {
                    offset: 0,
                    lo: shape.lo,
                    len: shape.total,
                    stride: shape.stride,
                    span: e.span,
                });
                let p = base_ptr;
                self.block.emit(Op::ElemAddr { d: p, idx, desc });
                self.block.last_def = None;
                Some(PlaceRef {
                    place: Place::Ind { p, off: 0 },
                    ty: elem,
                    ..b
                })
            }
        }
    }

    /// `place + offset`, turning element places into pointers when needed.
    pub(super) fn offset_place(&mut self, place: Place, off: u32) -> Place {
        match place {
            Place::Frame(o) => Place::Frame(o.offset(off)),
            Place::Abs(a) => Place::Abs(a + off),
            Place::Ind { p, off: o } => Place::Ind { p, off: o + off },
            Place::Elem { idx, desc } => {
                let p = self.block.temp();
                self.block.emit(Op::ElemRef { d: p, idx, desc });
                self.block.last_def = None;
                Place::Ind { p, off }
            }
            Place::View { r, .. } => {
                let p = self.block.temp();
                self.block.emit(Op::RefAddr { d: p, r, width: 1 });
                self.block.last_def = None;
                Place::Ind { p, off }
            }
        }
    }
}
