//! `UNION ... END_UNION` (CODESYS, TwinCAT): members that share memory.
//!
//! plcrun's memory is typed 64-bit slots, so a union is laid out as a
//! structure whose first field holds the union's bytes (LWORDs, eight
//! bytes each, little-endian) and every member of an elementary type, an
//! enumeration or an array of those is a byte view of them
//! (docs/semantics.md §23): `u.dw := 16#11223344` then `u.b[0]` reads
//! 16#44, exactly as in TwinCAT. STRING and WSTRING members cannot be
//! views here (a view reads elementary values only); they get storage of
//! their own after the bytes, with a warning that they do not overlay
//! (docs/semantics.md §27). Members of other types are refused.

use super::body::BodyBuilder;
use super::declare::Declarer;
use super::emit::{Place, PlaceRef};
use super::model::VarInfo;
use super::refs::{size_bytes, viewable};
use crate::elementary::ElemType;
use crate::ir::op::Op;
use crate::ir::type_table::{Dim, Member, TypeDef, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Ident, VarDecl};
use indexmap::IndexMap;

/// The name of a union's hidden first field, its bytes.
pub(super) const BYTES_FIELD: &str = "__UNION_BYTES";

/// What the body builders know of a union type.
#[derive(Debug, Clone)]
pub(crate) struct UnionInfo {
    /// The members that overlay the bytes: name and type.
    pub overlays: Vec<(String, TypeId)>,
    /// Slots of the bytes (eight bytes each).
    pub slots: u32,
    /// `SIZEOF` of the union: its largest member's bytes, as TwinCAT
    /// counts them (a STRING member included).
    pub bytes: u64,
}

impl Declarer<'_> {
    /// The type of `UNION fields END_UNION`.
    pub(super) fn union_type(
        &mut self,
        fields: &[VarDecl],
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let mut overlays: Vec<(String, TypeId)> = Vec::new();
        let mut apart: Vec<(String, TypeId, Span)> = Vec::new();
        let mut bytes = 0u64;
        for decl in fields {
            let ty = self.resolve_type(&decl.ty, local);
            if let (Some(_), Some(first)) = (&decl.init, decl.names.first()) {
                self.diags.error(
                    "E218",
                    first.span,
                    "a UNION member has no initial value of its own: give the union one in the variable's declaration, or assign a member",
                );
            }
            for name in &decl.names {
                let taken = overlays
                    .iter()
                    .map(|o| &o.0)
                    .chain(apart.iter().map(|a| &a.0));
                if taken
                    .into_iter()
                    .any(|n| n.eq_ignore_ascii_case(&name.name))
                {
                    self.diags.error(
                        "E202",
                        name.span,
                        format!("member `{}` is declared twice", name.name),
                    );
                    continue;
                }
                if let Some(b) = size_bytes(&self.types, ty) {
                    bytes = bytes.max(b);
                }
                match member_shape(&self.types, ty) {
                    Shape::Overlay => overlays.push((name.name.clone(), ty)),
                    Shape::Apart => apart.push((name.name.clone(), ty, name.span)),
                    Shape::Refused => self.refuse_member(name, ty),
                }
            }
        }
        self.union_layout(overlays, apart, bytes)
    }

    fn refuse_member(&mut self, name: &Ident, ty: TypeId) {
        if ty == TypeTable::error() {
            return;
        }
        let tname = self.types.name(ty).to_string();
        self.diags.error(
            "E219",
            name.span,
            format!(
                "UNION member `{}` is a {tname}: only elementary types, enumerations, arrays of them and strings can share a union's memory here",
                name.name
            ),
        );
    }

    /// The structure that holds a union: its bytes, then the members kept
    /// apart (with W318 for each).
    fn union_layout(
        &mut self,
        overlays: Vec<(String, TypeId)>,
        apart: Vec<(String, TypeId, Span)>,
        bytes: u64,
    ) -> TypeId {
        let overlaid: u64 = overlays
            .iter()
            .filter_map(|(_, t)| size_bytes(&self.types, *t))
            .max()
            .unwrap_or(0);
        let slots = u32::try_from(overlaid.div_ceil(8).max(1)).unwrap_or(u32::MAX);
        let lword = TypeTable::elem(ElemType::Lword);
        let storage = self.types.intern(TypeDef {
            name: format!("ARRAY[0..{}] OF LWORD", slots - 1),
            kind: TypeKind::Array {
                dims: vec![Dim {
                    lo: 0,
                    hi: slots as i64 - 1,
                }],
                elem: lword,
            },
            size: slots,
        });
        let mut fields = vec![Member::field(BYTES_FIELD, storage, 0)];
        let mut offset = slots;
        for (name, ty, span) in apart {
            self.diags.warning(
                "W318",
                span,
                format!(
                    "UNION member `{name}` ({}) has memory of its own here: writing it does not change the other members, nor they it",
                    self.types.name(ty)
                ),
            );
            fields.push(Member::field(&name, ty, offset));
            offset = offset.saturating_add(self.types.size(ty));
        }
        let id = self.types.add(TypeDef {
            name: "UNION".into(),
            kind: TypeKind::Struct { fields },
            size: offset,
        });
        let info = UnionInfo {
            overlays,
            slots,
            bytes,
        };
        self.model.unions.insert(id, info);
        id
    }
}

/// How a member of a union is stored.
enum Shape {
    /// A byte view of the union's bytes.
    Overlay,
    /// Storage of its own (strings).
    Apart,
    /// Not allowed.
    Refused,
}

fn member_shape(types: &TypeTable, ty: TypeId) -> Shape {
    match &types.get(ty).kind {
        TypeKind::Str { .. } => Shape::Apart,
        // A subrange read from bytes could hold a value outside its range.
        TypeKind::Subrange { .. } => Shape::Refused,
        TypeKind::Array { elem, .. } => match member_shape(types, *elem) {
            Shape::Overlay if viewable(types, *elem).is_some() => Shape::Overlay,
            _ => Shape::Refused,
        },
        _ if viewable(types, ty).is_some() => Shape::Overlay,
        _ => Shape::Refused,
    }
}

impl BodyBuilder<'_> {
    /// `u.m` for a member `m` that overlays union `u`'s bytes: a byte view
    /// of them at byte 0 (`None` when `name` is not such a member).
    pub(super) fn union_member(&mut self, b: &PlaceRef, name: &Ident) -> Option<PlaceRef> {
        let info = self.model.unions.get(&b.ty)?;
        let (_, ty) = info
            .overlays
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(&name.name))?;
        let (ty, slots) = (*ty, info.slots);
        let addr = self.address_of(b);
        let r = self.block.temp();
        self.block.emit(Op::RefMake {
            d: r,
            p: addr,
            len: slots,
            layout: crate::ir::refs::elem_code(ElemType::Lword).into(),
        });
        self.block.emit(Op::RefView { d: r, unit: 8 });
        self.block.last_def = None;
        // An array member's elements are views too (`place_index`); the
        // array as a whole has no value to read (R037).
        let elem = viewable(self.types, ty).map_or(0, crate::ir::refs::elem_code);
        Some(PlaceRef {
            place: Place::View { r, elem },
            ty,
            ..*b
        })
    }

    /// `SIZEOF` of a union type: its largest member's bytes.
    pub(super) fn union_bytes(&self, ty: TypeId) -> Option<u64> {
        self.model.unions.get(&ty).map(|u| u.bytes)
    }
}
