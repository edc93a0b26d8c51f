//! User types and type specifications of the declaration phase: TYPE
//! declarations resolved on first use (cycles reported), and every
//! `TypeSpec` turned into an interned [`TypeId`].

use super::consts::int_to_slot;
use super::declare::Declarer;
use super::model::{ConstInit, LayoutState, VarInfo};
use crate::elementary::ElemType;
use crate::ir::type_table::{Dim, Member, TypeDef, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::stdlib;
use crate::syntax::ast::{Expr, ExprKind, Ident, Initializer, Item, PouKind, TypeSpec, VarDecl};
use indexmap::IndexMap;

/// The length of a STRING declared without one in CODESYS V3 and
/// TwinCAT 3 files.
const CODESYS_STRING_LENGTH: u32 = 80;

/// What a structure declared `EXTENDS base` starts with: `base`'s fields,
/// their initial values (by field index), the slots they take, and `base`
/// itself (`None` after an error).
type Inherited = (Vec<Member>, Vec<(usize, ConstInit)>, u32, Option<TypeId>);

impl Declarer<'_> {
    /// Resolves a user TYPE by key, computing it on first use.
    pub(super) fn user_type(&mut self, key: &str, span: Span) -> Option<TypeId> {
        if let Some(&t) = self.model.type_ids.get(key) {
            return Some(t);
        }
        let &(u, i, d) = self.type_decls.get(key)?;
        if self.type_state.get(key) == Some(&LayoutState::InProgress) {
            self.diags.error(
                "E204",
                span,
                format!("type `{key}` is defined in terms of itself"),
            );
            return Some(TypeTable::error());
        }
        self.type_state
            .insert(key.to_string(), LayoutState::InProgress);
        let Item::Types(decls) = &self.units[u].items[i] else {
            return None;
        };
        let decl = &decls[d];
        self.reserve_struct_id(key, &decl.name.name, &decl.ty);
        let base = self.resolve_type(&decl.ty, None);
        // A named type gets its own identity for enums and structs; aliases share.
        let ty = match &decl.ty {
            TypeSpec::Enum { .. } | TypeSpec::Struct { .. } => {
                let mut def = self.types.get(base).clone();
                def.name = decl.name.name.clone();
                let id = self.place_named_type(key, def);
                if let Some(u) = self.model.unions.get(&base).cloned() {
                    self.model.unions.insert(id, u);
                }
                // Field defaults belong to the named type too, and so
                // does the structure it extends.
                if let Some(ci) = self.model.type_inits.get(&base).cloned() {
                    self.model.type_inits.insert(id, ci);
                }
                if let Some(&b) = self.model.struct_bases.get(&base) {
                    self.model.struct_bases.insert(id, b);
                }
                if let TypeKind::Enum { values, .. } = &self.types.get(id).kind {
                    let values = values.clone();
                    self.register_enum_values(&values, base, id, decl.qualified_only);
                    if decl.strict {
                        self.model.strict_enums.insert(id);
                    }
                }
                id
            }
            _ => base,
        };
        if let Some(init) = &decl.init {
            let ci = own_enum_value(self.types.get(ty), init)
                .or_else(|| self.consts().resolve_init(init, ty, None));
            if let Some(ci) = ci {
                self.model.type_inits.insert(ty, ci);
            }
        }
        self.model.type_ids.insert(key.to_string(), ty);
        self.type_state.insert(key.to_string(), LayoutState::Done);
        Some(ty)
    }

    /// Resolves a type specification. `local` holds the constants of the
    /// POU being declared (for array bounds).
    pub(super) fn resolve_type(
        &mut self,
        spec: &TypeSpec,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        match spec {
            TypeSpec::Named(id) => self.named_type(id),
            TypeSpec::String { wide, len, span } => self.string_type(*wide, len, *span, local),
            TypeSpec::Array { ranges, elem, span } => self.array_type(ranges, elem, *span, local),
            TypeSpec::OpenArray { span, .. } => self.open_array_refused(*span),
            TypeSpec::Subrange { base, lo, hi, span } => {
                self.subrange_type(base, lo, hi, *span, local)
            }
            TypeSpec::Enum { base, values, span } => self.enum_type(base, values, *span, local),
            TypeSpec::Struct {
                fields,
                union: true,
                extends,
                ..
            } => {
                if let Some(base) = extends {
                    self.diags
                        .error("E219", base.span, "a UNION cannot extend another type");
                }
                self.union_type(fields, local)
            }
            TypeSpec::Struct {
                extends, fields, ..
            } => self.struct_type(extends.as_ref(), fields, local),
            TypeSpec::Ref { kind, target, span } => self.ref_type(*kind, target, *span, local),
        }
    }

    /// A named type: elementary, user TYPE, standard FB or user FB/PROGRAM
    /// (whose layout, and for an FB its body, comes first).
    fn named_type(&mut self, id: &Ident) -> TypeId {
        if id.name == crate::syntax::recovery::UNKNOWN_TYPE {
            // A declaration salvaged after a syntax error (already reported).
            return TypeTable::error();
        }
        if let Some(e) = ElemType::from_name(&id.name) {
            return TypeTable::elem(e);
        }
        let key = id.key();
        if let Some(t) = self.user_type(&key, id.span) {
            return t;
        }
        if key == "BIT" {
            // CODESYS's BIT: a BOOL that a structure packs into a bit. The
            // value is the same; plcrun keeps it in a slot of its own.
            self.diags.warning(
                "W309",
                id.span,
                "`BIT` is a CODESYS extension: read as BOOL (not packed into a bit of the structure)",
            );
            return TypeTable::elem(ElemType::Bool);
        }
        if super::any_params::GenericClass::from_name(&id.name).is_some() {
            return self.generic_refused(id);
        }
        if let Some(fb) = stdlib::lookup_native(&id.name) {
            let params = stdlib::interface(fb);
            return self.types.intern(TypeDef {
                name: stdlib::native_name(fb),
                kind: TypeKind::NativeFb(fb),
                size: params.len() as u32,
            });
        }
        if let Some(&p) = self.model.pou_index.get(&key) {
            return match self.model.pous[p].kind {
                PouKind::FunctionBlock => {
                    self.ensure_emitted(p);
                    self.model.pous[p].ty
                }
                PouKind::Program => {
                    self.layout_pou(p);
                    self.model.pous[p].ty
                }
                PouKind::Function => {
                    self.diags.error(
                        "E209",
                        id.span,
                        format!("`{}` is a FUNCTION, not a type", id.name),
                    );
                    TypeTable::error()
                }
            };
        }
        let message = format!("unknown type `{}`", id.name);
        let elementary = ElemType::ALL.iter().map(|e| e.name());
        let user = self
            .model
            .pous
            .iter()
            .filter(|p| p.kind == PouKind::FunctionBlock);
        let names = elementary
            .chain(user.map(|p| p.name.as_str()))
            .chain(self.model.type_ids.keys().map(String::as_str))
            .chain(super::suggest::STANDARD_FBS.iter().copied());
        let message = super::suggest::with_suggestion(message, &id.name, names);
        self.diags.error("E203", id.span, message);
        TypeTable::error()
    }

    /// `STRING[n]` / `WSTRING[n]`; without a length 254 characters, 80 in
    /// a CODESYS V3 / TwinCAT 3 file (as those tools allocate).
    fn string_type(
        &mut self,
        wide: bool,
        len: &Option<Box<Expr>>,
        span: Span,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let max = match len {
            Some(e) => match self.consts().const_int(e, local) {
                Some(n) if (1..=65535).contains(&n) => n as u32,
                Some(_) => {
                    self.diags
                        .error("E206", span, "string length must be between 1 and 65535");
                    254
                }
                None => 254,
            },
            None if self.model.checked_files.contains(&span.file) => CODESYS_STRING_LENGTH,
            None => 254,
        };
        let kw = if wide { "WSTRING" } else { "STRING" };
        self.types.intern(TypeDef {
            name: format!("{kw}[{max}]"),
            kind: TypeKind::Str { wide, max },
            size: 1,
        })
    }

    /// `ARRAY[l..h, ...] OF elem`, with its bounds checked.
    fn array_type(
        &mut self,
        ranges: &[(Expr, Expr)],
        elem: &TypeSpec,
        span: Span,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let elem_ty = self.resolve_type(elem, local);
        let mut dims = Vec::new();
        for (lo, hi) in ranges {
            self.resolve_sizeof_types(lo);
            self.resolve_sizeof_types(hi);
            let (Some(l), Some(h)) = (
                self.consts().const_int(lo, local),
                self.consts().const_int(hi, local),
            ) else {
                return TypeTable::error();
            };
            if h < l {
                self.diags.error(
                    "E206",
                    lo.span.to(hi.span),
                    format!("array bounds [{l}..{h}] are empty"),
                );
                return TypeTable::error();
            }
            let too_large = h - l + 1 > super::MAX_FRAME_SLOTS as i128
                || i64::try_from(l).is_err()
                || i64::try_from(h).is_err();
            if too_large {
                self.diags.error(
                    "E206",
                    lo.span.to(hi.span),
                    format!("array bounds [{l}..{h}] give too many elements"),
                );
                return TypeTable::error();
            }
            let limit = self.out.data_limit();
            if h.saturating_sub(l).saturating_add(1) > limit as i128 {
                self.diags.error(
                    "E120",
                    lo.span.to(hi.span),
                    format!(
                        "array bounds [{l}..{h}] give more elements than the memory limit of {} holds",
                        super::program::format_bytes(limit * 8)
                    ),
                );
                return TypeTable::error();
            }
            dims.push(Dim {
                lo: l as i64,
                hi: h as i64,
            });
        }
        let count = dims
            .iter()
            .try_fold(1u64, |acc, d| acc.checked_mul(d.len()))
            .unwrap_or(u64::MAX);
        let size = count.saturating_mul(self.types.size(elem_ty) as u64);
        if size > super::MAX_FRAME_SLOTS as u64 {
            self.diags
                .error("E206", span, "array too large (more than 64 Mi slots)");
            return TypeTable::error();
        }
        let limit = self.out.data_limit();
        if size > limit as u64 {
            self.diags.error(
                "E120",
                span,
                format!(
                    "this array needs {} of data, over the memory limit of {}",
                    super::program::format_bytes_u64(size.saturating_mul(8)),
                    super::program::format_bytes(limit * 8)
                ),
            );
            return TypeTable::error();
        }
        let dims_text: Vec<String> = dims.iter().map(|d| format!("{}..{}", d.lo, d.hi)).collect();
        self.types.intern(TypeDef {
            name: format!(
                "ARRAY[{}] OF {}",
                dims_text.join(","),
                self.types.name(elem_ty)
            ),
            kind: TypeKind::Array {
                dims,
                elem: elem_ty,
            },
            size: size as u32,
        })
    }

    /// `INT(l..h)`.
    fn subrange_type(
        &mut self,
        base: &Ident,
        lo: &Expr,
        hi: &Expr,
        span: Span,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let Some(b) = ElemType::from_name(&base.name).filter(|e| e.is_int()) else {
            self.diags.error(
                "E203",
                base.span,
                format!("a subrange needs an integer base type, not `{}`", base.name),
            );
            return TypeTable::error();
        };
        let (Some(l), Some(h)) = (
            self.consts().const_int(lo, local),
            self.consts().const_int(hi, local),
        ) else {
            return TypeTable::error();
        };
        if h < l || int_to_slot(l, b).is_none() || int_to_slot(h, b).is_none() {
            self.diags
                .error("E206", span, format!("invalid subrange {l}..{h} of {b}"));
            return TypeTable::error();
        }
        self.types.intern(TypeDef {
            name: format!("{b}({l}..{h})"),
            kind: TypeKind::Subrange {
                base: b,
                lo: l as i64,
                hi: h as i64,
            },
            size: 1,
        })
    }

    /// `(A, B := 5, C)`: values numbered from 0 or from an explicit value;
    /// the names become known enumeration values.
    fn enum_type(
        &mut self,
        base: &Option<Ident>,
        values: &[(Ident, Option<Expr>)],
        span: Span,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let b = match base {
            Some(b) => match ElemType::from_name(&b.name).filter(|e| e.is_int() || e.is_bit()) {
                Some(e) => e,
                None => {
                    self.diags.error(
                        "E203",
                        b.span,
                        format!("`{}` cannot be the base type of an enumeration", b.name),
                    );
                    ElemType::Dint
                }
            },
            None => ElemType::Dint,
        };
        let mut out: Vec<(String, i64)> = Vec::new();
        let mut next: i128 = 0;
        for (name, v) in values {
            if let Some(e) = v
                && let Some(n) = self.consts().const_int(e, local)
            {
                next = n;
            }
            if out.iter().any(|(n, _)| n.eq_ignore_ascii_case(&name.name)) {
                self.diags.error(
                    "E202",
                    name.span,
                    format!("enumeration value `{}` is declared twice", name.name),
                );
            }
            out.push((name.name.clone(), next as i64));
            next += 1;
        }
        if out.is_empty() {
            self.diags
                .error("E206", span, "an enumeration needs at least one value");
        }
        let names: Vec<&str> = out.iter().map(|(n, _)| n.as_str()).collect();
        let id = self.types.add(TypeDef {
            name: format!("({})", names.join(", ")),
            kind: TypeKind::Enum {
                base: b,
                values: out.clone(),
            },
            size: 1,
        });
        for (name, v) in out {
            self.model
                .enum_values
                .entry(name.to_ascii_uppercase())
                .or_default()
                .push((id, v));
        }
        id
    }

    /// Makes the values of the named enumeration `id` (declared as the
    /// anonymous `base`) known by their names alone, or, for a
    /// `qualified_only` type, only as `Type.Value` (`enum_qualified.rs`).
    fn register_enum_values(
        &mut self,
        values: &[(String, i64)],
        base: TypeId,
        id: TypeId,
        qualified_only: bool,
    ) {
        for (name, v) in values {
            let key = name.to_ascii_uppercase();
            if !qualified_only {
                self.model
                    .enum_values
                    .entry(key)
                    .or_default()
                    .push((id, *v));
                continue;
            }
            if let Some(list) = self.model.enum_values.get_mut(&key) {
                list.retain(|(t, _)| *t != base);
                if list.is_empty() {
                    self.model.enum_values.remove(&key);
                }
            }
            self.model
                .qualified_enum_values
                .entry(key)
                .or_default()
                .push(id);
        }
    }

    /// The fields (with their initial values and the size they take) a
    /// structure declared `EXTENDS base` starts with: `base`'s own, and
    /// `base`'s type. A base that is not a structure is E438.
    fn inherited_fields(&mut self, base: &Ident) -> Inherited {
        let ty = self.named_type(base);
        let TypeKind::Struct { fields } = &self.types.get(ty).kind else {
            if ty != TypeTable::error() {
                self.diags.error(
                    "E438",
                    base.span,
                    format!(
                        "a structure can extend only a structure; `{}` is not one",
                        base.name
                    ),
                );
            }
            return (Vec::new(), Vec::new(), 0, None);
        };
        let inits = match self.model.type_inits.get(&ty) {
            Some(ConstInit::Struct(v)) => v.clone(),
            _ => Vec::new(),
        };
        (fields.clone(), inits, self.types.size(ty), Some(ty))
    }

    /// `STRUCT ... END_STRUCT`: fields laid out in order, with their defaults.
    fn struct_type(
        &mut self,
        extends: Option<&Ident>,
        fields: &[VarDecl],
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let (mut members, mut inits, mut offset, base) = match extends {
            Some(base) => self.inherited_fields(base),
            None => (Vec::new(), Vec::new(), 0u32, None),
        };
        for decl in fields {
            let fty = self
                .any_signature_field(decl)
                .unwrap_or_else(|| self.resolve_type(&decl.ty, local));
            let no_value = self.static_reference_init(decl, fty, "a structure field");
            let init = decl
                .init
                .as_ref()
                .filter(|_| !no_value)
                .and_then(|i| self.consts().resolve_init(i, fty, local));
            for name in &decl.names {
                if members
                    .iter()
                    .any(|m| m.name.eq_ignore_ascii_case(&name.name))
                {
                    self.diags.error(
                        "E202",
                        name.span,
                        format!("field `{}` is declared twice", name.name),
                    );
                    continue;
                }
                if let Some(ci) = &init {
                    inits.push((members.len(), ci.clone()));
                }
                members.push(Member::field(&name.name, fty, offset));
                offset = self.grow(offset, self.types.size(fty), name.span);
            }
        }
        let id = self.types.add(TypeDef {
            name: "STRUCT".into(),
            kind: TypeKind::Struct { fields: members },
            size: offset,
        });
        if !inits.is_empty() {
            self.model.type_inits.insert(id, ConstInit::Struct(inits));
        }
        if let Some(base) = base {
            self.model.struct_bases.insert(id, base);
        }
        id
    }
}

/// The initial value of an enumeration type named by one of its own values
/// written alone (`(LOCAL, REMOTE) USINT := REMOTE;`), which CODESYS takes
/// even under `qualified_only`: the declaration is the value's scope.
fn own_enum_value(def: &TypeDef, init: &Initializer) -> Option<ConstInit> {
    let (TypeKind::Enum { values, .. }, Initializer::Expr(e)) = (&def.kind, init) else {
        return None;
    };
    let ExprKind::Name(id) = &e.kind else {
        return None;
    };
    values
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(&id.name))
        .map(|(_, v)| ConstInit::Scalar(*v as u64))
}
