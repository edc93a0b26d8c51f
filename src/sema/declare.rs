//! Declarations: collects POUs, types and globals, resolves type
//! specifications and lays out instance memory.

use super::Compiler;
use super::consts::{
    Const, int_to_slot, literal_to_slot, real_to_slot, slot_to_int, typed_literal,
};
use super::model::{ConstInit, LayoutState, PouInfo, Storage, VarInfo};
use crate::ir::types::{Dim, Member, MemberKind, TypeDef, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::stdlib;
use crate::syntax::ast::{
    AddrSize, Area, BinaryOp, DirectAddress, Expr, ExprKind, Initializer, Item, LiteralValue,
    PouKind, TypeSpec, UnaryOp, VarBlock, VarKind,
};
use crate::types::ElemType;
use indexmap::IndexMap;

/// Normalised text of a direct address: `%` area, size letter, fields.
pub fn normalize_address(a: &DirectAddress) -> String {
    let area = match a.area {
        Area::Input => 'I',
        Area::Output => 'Q',
        Area::Memory => 'M',
    };
    let size = match a.size {
        AddrSize::Bit => 'X',
        AddrSize::Byte => 'B',
        AddrSize::Word => 'W',
        AddrSize::Dword => 'D',
        AddrSize::Lword => 'L',
    };
    let fields: Vec<String> = a.fields.iter().map(|f| f.to_string()).collect();
    format!("%{area}{size}{}", fields.join("."))
}

/// The elementary type a direct address denotes when used undeclared.
pub fn address_type(a: &DirectAddress) -> ElemType {
    match a.size {
        AddrSize::Bit => ElemType::Bool,
        AddrSize::Byte => ElemType::Byte,
        AddrSize::Word => ElemType::Word,
        AddrSize::Dword => ElemType::Dword,
        AddrSize::Lword => ElemType::Lword,
    }
}

fn member_kind(k: VarKind) -> MemberKind {
    match k {
        VarKind::Local | VarKind::Global => MemberKind::Local,
        VarKind::Input => MemberKind::Input,
        VarKind::Output => MemberKind::Output,
        VarKind::InOut => MemberKind::InOut,
        VarKind::External => MemberKind::External,
        VarKind::Temp => MemberKind::Temp,
    }
}

impl Compiler<'_> {
    /// Collects every declaration and lays out all POUs.
    pub(super) fn declare_all(&mut self) {
        let units = self.units;
        for (u, unit) in units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                match item {
                    Item::Pou(p) => {
                        let key = p.name.key();
                        if let Some(&prev) = self.pou_index.get(&key) {
                            let prev_span = self.pous[prev].span;
                            let loc = prev_span;
                            self.diags.push(
                                crate::diagnostics::Diagnostic::error(
                                    "E202",
                                    p.name.span,
                                    format!("`{}` is declared twice", p.name.name),
                                )
                                .with_note(format!(
                                    "the first declaration is at byte {} of the same or another file",
                                    loc.start
                                )),
                            );
                            continue;
                        }
                        if stdlib::lookup_native(&p.name.name).is_some()
                            || super::stdfuncs::is_standard_function(&p.name.name)
                        {
                            self.diags.error(
                                "E202",
                                p.name.span,
                                format!(
                                    "`{}` is the name of a standard function or function block",
                                    p.name.name
                                ),
                            );
                            continue;
                        }
                        self.pou_index.insert(key, self.pous.len());
                        self.pous.push(PouInfo {
                            name: p.name.name.clone(),
                            kind: p.kind,
                            ast: (u, i),
                            ty: TypeTable::error(),
                            ret: TypeTable::void(),
                            vars: IndexMap::new(),
                            params: Vec::new(),
                            code: u32::MAX,
                            vars_size: 0,
                            frame_abs: 0,
                            consts: Vec::new(),
                            span: p.name.span,
                        });
                        self.pou_state.push(LayoutState::Pending);
                        self.emit_state.push(LayoutState::Pending);
                    }
                    Item::Types(decls) => {
                        for (d, decl) in decls.iter().enumerate() {
                            let key = decl.name.key();
                            if self.type_decls.contains_key(&key)
                                || ElemType::from_name(&key).is_some()
                            {
                                self.diags.error(
                                    "E202",
                                    decl.name.span,
                                    format!("type `{}` is declared twice", decl.name.name),
                                );
                                continue;
                            }
                            self.type_decls.insert(key, (u, i, d));
                        }
                    }
                    Item::Configuration(_) | Item::Globals(_) => {}
                }
            }
        }
        // Types that clash with POU names.
        let mut clashes: Vec<(String, Span)> = Vec::new();
        for (k, &(u, i, d)) in &self.type_decls {
            if let (true, Item::Types(decls)) = (self.pou_index.contains_key(k), &units[u].items[i])
            {
                clashes.push((k.clone(), decls[d].name.span));
            }
        }
        clashes.sort_by_key(|(_, span)| (span.file, span.start));
        for (k, span) in clashes {
            self.diags.error(
                "E202",
                span,
                format!("`{k}` is declared both as a type and as a POU"),
            );
        }
        let mut keys: Vec<(usize, usize, usize, String)> = self
            .type_decls
            .iter()
            .map(|(k, &(u, i, d))| (u, i, d, k.clone()))
            .collect();
        keys.sort();
        for (_, _, _, k) in keys {
            let span = self.type_decl_span(&k);
            self.user_type(&k, span);
        }
        // Globals: top-level lists, then configurations and resources.
        for unit in units {
            for item in &unit.items {
                match item {
                    Item::Globals(block) => self.declare_globals(block),
                    Item::Configuration(cfg) => {
                        for b in &cfg.globals {
                            self.declare_globals(b);
                        }
                        for r in &cfg.resources {
                            for b in &r.globals {
                                self.declare_globals(b);
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        for p in 0..self.pous.len() {
            self.layout_pou(p);
        }
    }

    fn type_decl_span(&self, key: &str) -> Span {
        let Some(&(u, i, d)) = self.type_decls.get(key) else {
            return Span::default();
        };
        match &self.units[u].items[i] {
            Item::Types(decls) => decls[d].name.span,
            _ => Span::default(),
        }
    }

    fn declare_globals(&mut self, block: &VarBlock) {
        for decl in &block.decls {
            let ty = self.resolve_type(&decl.ty, None);
            if matches!(self.types.get(ty).kind, TypeKind::Pou { program: true, .. }) {
                self.diags.error(
                    "E209",
                    decl.ty.span(),
                    "a PROGRAM cannot be used as a variable type",
                );
                continue;
            }
            let init = decl
                .init
                .as_ref()
                .and_then(|i| self.resolve_init(i, ty, None));
            for name in &decl.names {
                let key = name.key();
                if self.globals.contains_key(&key) {
                    self.diags.error(
                        "E202",
                        name.span,
                        format!("global `{}` is declared twice", name.name),
                    );
                    continue;
                }
                let (addr, location) = match &decl.location {
                    Some(a) => match self.located_slot(a, ty) {
                        Some(addr) => (addr, Some(normalize_address(a))),
                        None => continue,
                    },
                    None => (self.alloc_abs(self.types.size(ty)), None),
                };
                let value = if block.constant {
                    init.as_ref().and_then(init_const)
                } else {
                    None
                };
                if block.constant && value.is_none() && !self.is_aggregate(ty) {
                    self.diags.error(
                        "E205",
                        name.span,
                        format!("constant `{}` needs a constant initial value", name.name),
                    );
                }
                self.globals.insert(
                    key,
                    VarInfo {
                        name: name.name.clone(),
                        ty,
                        kind: MemberKind::Local,
                        storage: Storage::Abs(addr),
                        constant: block.constant,
                        value,
                        init: init.clone(),
                        location,
                        span: name.span,
                    },
                );
            }
        }
    }

    /// Absolute slot of a located variable (shared by every declaration of
    /// the same address).
    pub(super) fn located_slot(&mut self, a: &DirectAddress, ty: TypeId) -> Option<u32> {
        let key = normalize_address(a);
        let elem = self.types.scalar(ty);
        let ok = match (a.size, elem) {
            (AddrSize::Bit, Some(ElemType::Bool)) => true,
            (AddrSize::Bit, _) => false,
            (size, Some(e)) => {
                let bits = match size {
                    AddrSize::Byte => 8,
                    AddrSize::Word => 16,
                    AddrSize::Dword => 32,
                    _ => 64,
                };
                e.bits() == bits || (bits == 32 && matches!(e, ElemType::Time))
            }
            _ => false,
        };
        if !ok {
            self.diags.error(
                "E207",
                a.span,
                format!(
                    "`{}` cannot hold a {}: the address size does not match the type",
                    a.text,
                    self.types.name(ty)
                ),
            );
            return None;
        }
        if let Some(&(addr, prev)) = self.located.get(&key) {
            if prev != ty {
                self.diags.error(
                    "E207",
                    a.span,
                    format!(
                        "`{}` is already declared as {}, not {}",
                        a.text,
                        self.types.name(prev),
                        self.types.name(ty)
                    ),
                );
                return None;
            }
            return Some(addr);
        }
        let addr = self.alloc_abs(1);
        self.located.insert(key, (addr, ty));
        Some(addr)
    }

    fn is_aggregate(&self, ty: TypeId) -> bool {
        matches!(
            self.types.get(ty).kind,
            TypeKind::Array { .. } | TypeKind::Struct { .. }
        )
    }

    /// Resolves a user TYPE by key, computing it on first use.
    pub(super) fn user_type(&mut self, key: &str, span: Span) -> Option<TypeId> {
        if let Some(&t) = self.type_ids.get(key) {
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
        let base = self.resolve_type(&decl.ty, None);
        // A named type gets its own identity for enums and structs; aliases share.
        let ty = match &decl.ty {
            TypeSpec::Enum { .. } | TypeSpec::Struct { .. } => {
                let mut def = self.types.get(base).clone();
                def.name = decl.name.name.clone();
                let id = self.types.add(def);
                // Field defaults belong to the named type too.
                if let Some(ci) = self.type_inits.get(&base).cloned() {
                    self.type_inits.insert(id, ci);
                }
                if let TypeKind::Enum { values, .. } = &self.types.get(id).kind {
                    for (name, v) in values.clone() {
                        self.enum_values
                            .entry(name.to_ascii_uppercase())
                            .or_default()
                            .push((id, v));
                    }
                }
                id
            }
            _ => base,
        };
        if let Some(init) = &decl.init
            && let Some(ci) = self.resolve_init(init, ty, None)
        {
            self.type_inits.insert(ty, ci);
        }
        self.type_ids.insert(key.to_string(), ty);
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
            TypeSpec::Named(id) => {
                if let Some(e) = ElemType::from_name(&id.name) {
                    return TypeTable::elem(e);
                }
                let key = id.key();
                if let Some(t) = self.user_type(&key, id.span) {
                    return t;
                }
                if let Some(fb) = stdlib::lookup_native(&id.name) {
                    let params = stdlib::interface(fb);
                    return self.types.intern(TypeDef {
                        name: stdlib::native_name(fb),
                        kind: TypeKind::NativeFb(fb),
                        size: params.len() as u32,
                    });
                }
                if let Some(&p) = self.pou_index.get(&key) {
                    return match self.pous[p].kind {
                        PouKind::FunctionBlock => {
                            self.ensure_emitted(p);
                            self.pous[p].ty
                        }
                        PouKind::Program => {
                            self.layout_pou(p);
                            self.pous[p].ty
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
                self.diags
                    .error("E203", id.span, format!("unknown type `{}`", id.name));
                TypeTable::error()
            }
            TypeSpec::String { wide, len, span } => {
                let max = match len {
                    Some(e) => match self.const_int(e, local) {
                        Some(n) if (1..=65535).contains(&n) => n as u32,
                        Some(_) => {
                            self.diags.error(
                                "E206",
                                *span,
                                "string length must be between 1 and 65535",
                            );
                            254
                        }
                        None => 254,
                    },
                    None => 254,
                };
                let kw = if *wide { "WSTRING" } else { "STRING" };
                self.types.intern(TypeDef {
                    name: format!("{kw}[{max}]"),
                    kind: TypeKind::Str { wide: *wide, max },
                    size: 1,
                })
            }
            TypeSpec::Array { ranges, elem, span } => {
                let elem_ty = self.resolve_type(elem, local);
                let mut dims = Vec::new();
                for (lo, hi) in ranges {
                    let (Some(l), Some(h)) = (self.const_int(lo, local), self.const_int(hi, local))
                    else {
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
                        .error("E206", *span, "array too large (more than 64 Mi slots)");
                    return TypeTable::error();
                }
                let dims_text: Vec<String> =
                    dims.iter().map(|d| format!("{}..{}", d.lo, d.hi)).collect();
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
            TypeSpec::Subrange { base, lo, hi, span } => {
                let Some(b) = ElemType::from_name(&base.name).filter(|e| e.is_int()) else {
                    self.diags.error(
                        "E203",
                        base.span,
                        format!("a subrange needs an integer base type, not `{}`", base.name),
                    );
                    return TypeTable::error();
                };
                let (Some(l), Some(h)) = (self.const_int(lo, local), self.const_int(hi, local))
                else {
                    return TypeTable::error();
                };
                if h < l || int_to_slot(l, b).is_none() || int_to_slot(h, b).is_none() {
                    self.diags
                        .error("E206", *span, format!("invalid subrange {l}..{h} of {b}"));
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
            TypeSpec::Enum { base, values, span } => {
                let b = match base {
                    Some(b) => match ElemType::from_name(&b.name)
                        .filter(|e| e.is_int() || e.is_bit())
                    {
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
                        && let Some(n) = self.const_int(e, local)
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
                        .error("E206", *span, "an enumeration needs at least one value");
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
                if !matches!(spec, TypeSpec::Enum { .. }) {
                    return id;
                }
                for (name, v) in out {
                    self.enum_values
                        .entry(name.to_ascii_uppercase())
                        .or_default()
                        .push((id, v));
                }
                id
            }
            TypeSpec::Struct { fields, span: _ } => {
                let mut members: Vec<Member> = Vec::new();
                let mut inits = Vec::new();
                let mut offset = 0u32;
                for decl in fields {
                    let fty = self.resolve_type(&decl.ty, local);
                    let init = decl
                        .init
                        .as_ref()
                        .and_then(|i| self.resolve_init(i, fty, local));
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
                        members.push(Member {
                            name: name.name.clone(),
                            ty: fty,
                            offset,
                            kind: MemberKind::Field,
                            constant: false,
                        });
                        offset = self.grow(offset, self.types.size(fty), name.span);
                    }
                }
                let id = self.types.add(TypeDef {
                    name: "STRUCT".into(),
                    kind: TypeKind::Struct { fields: members },
                    size: offset,
                });
                if !inits.is_empty() {
                    self.type_inits.insert(id, ConstInit::Struct(inits));
                }
                id
            }
        }
    }

    /// Evaluates a constant integer expression (array bounds, lengths...).
    pub(super) fn const_int(
        &mut self,
        e: &Expr,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<i128> {
        let r = self.const_int_inner(e, local);
        if r.is_none() {
            self.diags
                .error("E205", e.span, "expected a constant integer expression");
        }
        r
    }

    fn const_int_inner(&self, e: &Expr, local: Option<&IndexMap<String, VarInfo>>) -> Option<i128> {
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
            ExprKind::Name(id) => {
                let key = id.key();
                let var = local
                    .and_then(|l| l.get(&key))
                    .or_else(|| self.globals.get(&key))?;
                if !var.constant {
                    return None;
                }
                let e = self.types.scalar(var.ty)?;
                match var.value.as_ref()? {
                    Const::Bits(b) if e.is_int() => Some(slot_to_int(*b, e)),
                    Const::Int(v) => Some(*v),
                    _ => None,
                }
            }
            _ => None,
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
                    let n = match &el.repeat {
                        Some(r) => match self.const_int(r, local) {
                            Some(n) if n >= 0 => n as u64,
                            _ => return None,
                        },
                        None => 1,
                    };
                    let v = match &el.value {
                        Some(v) => Some(self.resolve_init(v, *elem, local)?),
                        None => None,
                    };
                    for _ in 0..n.min(count + 1) {
                        out.push(v.clone().unwrap_or_else(|| self.default_init(*elem)));
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
                let c = self.const_value(e, ty, local)?;
                Some(match c {
                    Const::Str(s) => ConstInit::Str(s),
                    Const::Bits(b) => ConstInit::Scalar(b),
                    Const::Int(_) | Const::Real(_) => return None,
                })
            }
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
            self.diags.error(
                "E301",
                e.span,
                format!("expected a value of enumeration {}", def.name),
            );
            return None;
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

    fn const_scalar(
        &self,
        e: &Expr,
        elem: ElemType,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Result<Const, (&'static str, String)> {
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
            ExprKind::Name(id) => {
                let key = id.key();
                let var = local
                    .and_then(|l| l.get(&key))
                    .or_else(|| self.globals.get(&key));
                match var {
                    Some(v) if v.constant => match (&v.value, self.types.scalar(v.ty)) {
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
                        _ => Err(("E301", format!("constant `{}` is not a {elem}", id.name))),
                    },
                    _ => Err((
                        "E205",
                        format!(
                            "`{}` is not a constant; initial values must be constant",
                            id.name
                        ),
                    )),
                }
            }
            ExprKind::Binary(op, a, b) if elem.is_int() => {
                let x = self.const_scalar(a, elem, local)?;
                let y = self.const_scalar(b, elem, local)?;
                let (Const::Bits(x), Const::Bits(y)) = (x, y) else {
                    return Err(("E205", "not a constant integer expression".into()));
                };
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
            ExprKind::Binary(op, a, b) if elem.is_real() => {
                let x = self.const_scalar(a, elem, local)?;
                let y = self.const_scalar(b, elem, local)?;
                let (Const::Bits(x), Const::Bits(y)) = (x, y) else {
                    return Err(("E205", "not a constant expression".into()));
                };
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
                real_to_slot(r, elem)
                    .map(Const::Bits)
                    .ok_or(("E305", format!("constant overflows {elem}")))
            }
            _ => Err(("E205", "initial values must be constant expressions".into())),
        }
    }

    /// The default initial value of a type (zero, empty string, first enum value).
    pub(super) fn default_init(&self, ty: TypeId) -> ConstInit {
        if let Some(ci) = self.type_inits.get(&ty) {
            return ci.clone();
        }
        match &self.types.get(ty).kind {
            TypeKind::Enum { values, .. } => {
                ConstInit::Scalar(values.first().map(|v| v.1 as u64).unwrap_or(0))
            }
            TypeKind::Subrange { lo, .. } => ConstInit::Scalar(*lo as u64),
            TypeKind::Str { .. } => ConstInit::Str(String::new()),
            _ => ConstInit::Scalar(0),
        }
    }

    /// `offset + size`, reporting E206 (once per call site) when an
    /// instance or structure would exceed [`super::MAX_FRAME_SLOTS`].
    fn grow(&mut self, offset: u32, size: u32, span: Span) -> u32 {
        match offset.checked_add(size) {
            Some(end) if end <= super::MAX_FRAME_SLOTS => end,
            _ => {
                self.diags.error(
                    "E206",
                    span,
                    format!(
                        "this declaration makes the POU or structure larger than {} Mi slots",
                        super::MAX_FRAME_SLOTS >> 20
                    ),
                );
                offset
            }
        }
    }

    /// Lays out the variables of POU `p` (idempotent).
    pub(super) fn layout_pou(&mut self, p: usize) {
        match self.pou_state[p] {
            LayoutState::Done => return,
            LayoutState::InProgress => {
                let span = self.pous[p].span;
                self.diags.error(
                    "E204",
                    span,
                    format!(
                        "`{}` contains an instance of itself (directly or through another block)",
                        self.pous[p].name
                    ),
                );
                return;
            }
            LayoutState::Pending => {}
        }
        self.pou_state[p] = LayoutState::InProgress;
        let (u, i) = self.pous[p].ast;
        let Item::Pou(pou) = &self.units[u].items[i] else {
            return;
        };
        let kind = pou.kind;
        let mut vars: IndexMap<String, VarInfo> = IndexMap::new();
        let mut params = Vec::new();
        let mut offset = 0u32;
        let mut members = Vec::new();
        if kind == PouKind::Function {
            let ret = match &pou.return_type {
                Some(t) => self.resolve_type(t, None),
                None => TypeTable::void(),
            };
            self.pous[p].ret = ret;
            if ret != TypeTable::void() {
                if !self.types.get(ret).kind.is_value_type() {
                    self.diags.error(
                        "E209",
                        pou.name.span,
                        "a function cannot return a function block instance",
                    );
                }
                vars.insert(
                    pou.name.key(),
                    VarInfo {
                        name: pou.name.name.clone(),
                        ty: ret,
                        kind: MemberKind::Output,
                        storage: Storage::Frame(0),
                        constant: false,
                        value: None,
                        init: None,
                        location: None,
                        span: pou.name.span,
                    },
                );
                offset = self.types.size(ret);
            }
        }
        for block in &pou.var_blocks {
            if block.retain == Some(crate::syntax::ast::Retain::Retain) {
                self.diags.warning(
                    "W203",
                    block.span,
                    "RETAIN is accepted but has no effect: plcrun starts every run from the declared initial values",
                );
            }
            if block.kind == VarKind::Global {
                self.diags.error(
                    "E209",
                    block.span,
                    "VAR_GLOBAL is only allowed in a CONFIGURATION, a RESOURCE or at top level",
                );
                continue;
            }
            for decl in &block.decls {
                let ty = self.resolve_type(&decl.ty, Some(&vars));
                let tkind = self.types.get(ty).kind.clone();
                let is_fb = matches!(tkind, TypeKind::NativeFb(_) | TypeKind::Pou { .. });
                if matches!(tkind, TypeKind::Pou { program: true, .. }) {
                    self.diags.error(
                        "E209",
                        decl.ty.span(),
                        "a PROGRAM cannot be instantiated inside a POU",
                    );
                    continue;
                }
                if is_fb && kind == PouKind::Function && block.kind != VarKind::InOut {
                    self.diags.error(
                        "E209",
                        decl.ty.span(),
                        "a FUNCTION cannot hold function block instances (they have state)",
                    );
                    continue;
                }
                if ty == TypeTable::void() {
                    continue;
                }
                let init = decl
                    .init
                    .as_ref()
                    .and_then(|i| self.resolve_init(i, ty, Some(&vars)));
                for name in &decl.names {
                    let key = name.key();
                    if vars.contains_key(&key) {
                        self.diags.error(
                            "E202",
                            name.span,
                            format!("`{}` is declared twice in `{}`", name.name, pou.name.name),
                        );
                        continue;
                    }
                    let mkind = member_kind(block.kind);
                    let (storage, location) = if let Some(a) = &decl.location {
                        if kind != PouKind::Program {
                            self.diags.error(
                                "E207",
                                a.span,
                                "located variables (AT %...) are only allowed in PROGRAMs and globals",
                            );
                            continue;
                        }
                        match self.located_slot(a, ty) {
                            Some(addr) => (Storage::Abs(addr), Some(normalize_address(a))),
                            None => continue,
                        }
                    } else if block.kind == VarKind::External {
                        match self.globals.get(&key) {
                            Some(g) => {
                                if g.ty != ty && ty != TypeTable::error() {
                                    self.diags.error(
                                        "E301",
                                        name.span,
                                        format!(
                                            "VAR_EXTERNAL `{}` is declared {} but the global is {}",
                                            name.name,
                                            self.types.name(ty),
                                            self.types.name(g.ty)
                                        ),
                                    );
                                }
                                if g.constant && !block.constant {
                                    self.diags.error(
                                        "E401",
                                        name.span,
                                        format!(
                                            "global `{}` is CONSTANT: declare it in VAR_EXTERNAL CONSTANT",
                                            name.name
                                        ),
                                    );
                                }
                                (g.storage, g.location.clone())
                            }
                            None => {
                                self.diags.error(
                                    "E201",
                                    name.span,
                                    format!(
                                        "no VAR_GLOBAL named `{}` for this VAR_EXTERNAL",
                                        name.name
                                    ),
                                );
                                continue;
                            }
                        }
                    } else if block.kind == VarKind::InOut {
                        let s = Storage::Ref(offset);
                        offset += 1;
                        (s, None)
                    } else {
                        let s = Storage::Frame(offset);
                        offset = self.grow(offset, self.types.size(ty), name.span);
                        (s, None)
                    };
                    let value = if block.constant {
                        init.as_ref().and_then(init_const)
                    } else {
                        None
                    };
                    if block.constant
                        && value.is_none()
                        && block.kind != VarKind::External
                        && !self.is_aggregate(ty)
                    {
                        self.diags.error(
                            "E205",
                            name.span,
                            format!("constant `{}` needs a constant initial value", name.name),
                        );
                    }
                    let value = if block.kind == VarKind::External {
                        self.globals.get(&key).and_then(|g| g.value.clone())
                    } else {
                        value
                    };
                    if matches!(
                        block.kind,
                        VarKind::Input | VarKind::Output | VarKind::InOut
                    ) {
                        params.push(key.clone());
                    }
                    if let Storage::Frame(o) | Storage::Ref(o) = storage {
                        members.push(Member {
                            name: name.name.clone(),
                            ty,
                            offset: o,
                            kind: mkind,
                            constant: block.constant,
                        });
                    }
                    vars.insert(
                        key,
                        VarInfo {
                            name: name.name.clone(),
                            ty,
                            kind: mkind,
                            storage,
                            constant: block.constant,
                            value,
                            init: init.clone(),
                            location,
                            span: name.span,
                        },
                    );
                }
            }
        }
        if let crate::syntax::ast::Body::Sfc(elems) = &pou.body {
            self.layout_chart(pou, elems, &mut vars, &mut members, &mut offset);
        }
        let code = self.codes.len() as u32;
        self.codes.push(crate::ir::image::CodeBlock {
            name: pou.name.name.clone(),
            kind: match kind {
                PouKind::Program => crate::ir::image::CodeKind::Program,
                PouKind::FunctionBlock => crate::ir::image::CodeKind::FunctionBlock,
                PouKind::Function => crate::ir::image::CodeKind::Function,
            },
            ops: Vec::new(),
            spans: Vec::new(),
            entry_init: Vec::new(),
            entry_strings: Vec::new(),
            frame: 0,
            frame_size: offset,
        });
        let ty = self.types.add(TypeDef {
            name: pou.name.name.clone(),
            kind: TypeKind::Pou {
                code,
                members,
                program: kind == PouKind::Program,
            },
            size: offset,
        });
        let info = &mut self.pous[p];
        info.vars = vars;
        info.params = params;
        info.code = code;
        info.vars_size = offset;
        info.ty = ty;
        self.pou_state[p] = LayoutState::Done;
    }
}

/// The folded value of a scalar initializer, for CONSTANT variables.
fn init_const(ci: &ConstInit) -> Option<Const> {
    match ci {
        ConstInit::Scalar(b) => Some(Const::Bits(*b)),
        ConstInit::Str(s) => Some(Const::Str(s.clone())),
        _ => None,
    }
}

impl TypeKind {
    /// True for types whose values can be copied (not FB instances).
    pub fn is_value_type(&self) -> bool {
        !matches!(
            self,
            TypeKind::NativeFb(_) | TypeKind::Pou { .. } | TypeKind::Step
        )
    }
}
