//! `ARRAY[*]` (CODESYS and TwinCAT): a VAR_IN_OUT whose bounds come with
//! the argument, so one function serves arrays of any length. The
//! parameter's slots hold the argument's address, then its lower and upper
//! bound per dimension (`ir::type_table::open_array_layout`). The body may
//! index it (one checked step per dimension against those bounds), read
//! the bounds with `LOWER_BOUND` / `UPPER_BOUND`, and pass it on to another
//! `ARRAY[*]`; nothing else (E307).

use super::body::BodyBuilder;
use super::calls::Param;
use super::consts::Const;
use super::declare::Declarer;
use super::emit::{Place, PlaceRef, Ty, Val};
use super::model::{Storage, VarInfo};
use crate::elementary::ElemType;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{TypeDef, TypeId, TypeKind, TypeTable, open_array_layout};
use crate::source::Span;
use crate::syntax::ast::{Arg, Call, Expr, ExprKind, TypeSpec, VarKind};
use indexmap::IndexMap;

/// What E307 says an `ARRAY[*]` may do.
const ALLOWED: &str = "an ARRAY[*] parameter can only be indexed, measured with LOWER_BOUND / UPPER_BOUND, or passed on to another ARRAY[*] VAR_IN_OUT";

/// An `ARRAY[*]` parameter of the block being emitted.
struct OpenParam {
    /// The frame slot holding the argument's address (its bounds follow).
    at: Slot,
    /// Dimensions.
    rank: u32,
    /// Element type.
    elem: TypeId,
}

impl OpenParam {
    /// The slot of dimension `k`'s lower bound (`k` from 0).
    fn lower(&self, k: u32) -> Slot {
        self.at.offset(open_array_layout::lower(k))
    }

    /// The slot of dimension `k`'s upper bound.
    fn upper(&self, k: u32) -> Slot {
        self.at.offset(open_array_layout::lower(k) + 1)
    }
}

impl Declarer<'_> {
    /// The type of VAR_IN_OUT `decl` when it is written `ARRAY[*] OF T`.
    pub(super) fn open_array_param(
        &mut self,
        kind: VarKind,
        spec: &TypeSpec,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> Option<TypeId> {
        let TypeSpec::OpenArray { rank, elem, span } = spec else {
            return None;
        };
        if kind != VarKind::InOut {
            return None;
        }
        let elem_ty = self.resolve_type(elem, local);
        if elem_ty == TypeTable::error() {
            return Some(elem_ty);
        }
        if self.types.size(elem_ty) == 0 {
            self.diags.error(
                "E211",
                *span,
                format!("an array of {} cannot exist", self.types.name(elem_ty)),
            );
            return Some(TypeTable::error());
        }
        let stars = vec!["*"; *rank].join(",");
        Some(self.types.intern(TypeDef {
            name: format!("ARRAY[{stars}] OF {}", self.types.name(elem_ty)),
            kind: TypeKind::OpenArray {
                rank: *rank as u32,
                elem: elem_ty,
            },
            size: 0,
        }))
    }

    /// E211: `ARRAY[*]` anywhere but as the type of a VAR_IN_OUT.
    pub(super) fn open_array_refused(&mut self, span: Span) -> TypeId {
        self.diags.error(
            "E211",
            span,
            "ARRAY[*] is only allowed as the type of a VAR_IN_OUT (the argument gives its bounds)",
        );
        TypeTable::error()
    }
}

impl BodyBuilder<'_> {
    /// True for an `ARRAY[*]` type.
    pub(super) fn is_open_array(&self, ty: TypeId) -> bool {
        matches!(self.types.get(ty).kind, TypeKind::OpenArray { .. })
    }

    /// The `ARRAY[*]` parameter `e` names, with E307 when `e` is one that
    /// is not this block's own (reached through an instance or a
    /// pointer, its bounds are out of reach).
    fn open_param(&mut self, e: &Expr, place: &PlaceRef) -> Option<OpenParam> {
        let TypeKind::OpenArray { rank, elem } = self.types.get(place.ty).kind else {
            return None;
        };
        // `THIS^.arr` names the block's own parameter as `arr` does.
        if let ExprKind::Member(base, id) = &e.kind
            && super::oop::calls::is_this(base)
        {
            let plain = Expr {
                kind: ExprKind::Name(id.clone()),
                span: e.span,
            };
            if let Some(p) = self.place(&plain) {
                return self.open_param(&plain, &p);
            }
        }
        let own = match &e.kind {
            ExprKind::Name(id) => self
                .lookup_var(&id.key())
                .and_then(|v| match v.storage {
                    Storage::Ref(o) => Some(Slot::new(o)),
                    _ => None,
                })
                .filter(|&o| place.place == Place::Ind { p: o, off: 0 }),
            _ => None,
        };
        match own {
            Some(at) => Some(OpenParam { at, rank, elem }),
            None => {
                self.diags.error(
                    "E307",
                    e.span,
                    "an ARRAY[*] parameter is only usable in the block that declares it",
                );
                None
            }
        }
    }

    /// E307 for an `ARRAY[*]` used as a whole at `span`.
    pub(super) fn open_array_misused(&mut self, span: Span) {
        self.diags.error("E307", span, ALLOWED);
    }

    /// `base[i, j, ...]` where `base` (at `b`) is an `ARRAY[*]`
    /// parameter: the element's address from the argument's address and
    /// the index checked against the argument's bounds.
    pub(super) fn open_array_element(
        &mut self,
        e: &Expr,
        base: &Expr,
        b: &PlaceRef,
        indexes: &[Expr],
    ) -> Option<PlaceRef> {
        let param = self.open_param(base, b)?;
        if indexes.len() != param.rank as usize {
            self.diags.error(
                "E404",
                e.span,
                format!(
                    "array has {} dimension(s), {} index(es) given",
                    param.rank,
                    indexes.len()
                ),
            );
            return None;
        }
        let vals = self.index_values(indexes)?;
        let acc = self.block.temp();
        self.block.emit(Op::LoadI { d: acc, imm: 0 });
        for (k, (v, _)) in vals.iter().enumerate() {
            let idx = self.materialize(v);
            // The upper bound follows the lower one.
            self.block.emit(Op::OpenIndexStep {
                acc,
                idx,
                bounds: param.lower(k as u32),
            });
        }
        let stride = self.types.size(param.elem);
        if stride != 1 {
            let s = self.block.const_slot(stride as u64);
            self.block.emit(Op::MulU {
                d: acc,
                a: acc,
                b: s,
                shift: 0,
            });
        }
        let p = self.block.temp();
        self.block.emit(Op::AddU {
            d: p,
            a: param.at,
            b: acc,
            shift: 0,
        });
        self.block.last_def = None;
        Some(PlaceRef {
            place: Place::Ind { p, off: 0 },
            ty: param.elem,
            ..*b
        })
    }

    /// The slots an `ARRAY[*]` VAR_IN_OUT `prm` receives for argument
    /// `e`: its address, then its lower and upper bound per dimension.
    /// The argument is an array of the same element type and number of
    /// dimensions, or an `ARRAY[*]` parameter of the caller.
    pub(super) fn open_array_argument(&mut self, prm: &Param, e: &Expr) -> Option<Vec<Slot>> {
        let TypeKind::OpenArray { rank, elem } = self.types.get(prm.ty).kind else {
            return None;
        };
        let arg = self.place(e)?;
        let what = format!("VAR_IN_OUT `{}`", prm.name);
        let bounds: Vec<Slot> = match self.types.get(arg.ty).kind.clone() {
            TypeKind::Array { dims, elem: e2 } if dims.len() == rank as usize && e2 == elem => {
                let dint = Ty::T(TypeTable::elem(ElemType::Dint));
                dims.iter()
                    .flat_map(|d| [d.lo, d.hi])
                    .map(|x| self.materialize(&Val::Const(Const::Int(x as i128), dint)))
                    .collect()
            }
            TypeKind::OpenArray { rank: r2, elem: e2 } if r2 == rank && e2 == elem => {
                let from = self.open_param(e, &arg)?;
                (0..rank)
                    .flat_map(|k| [from.lower(k), from.upper(k)])
                    .collect()
            }
            _ => {
                if arg.ty != TypeTable::error() {
                    self.mismatch(e.span, Ty::T(arg.ty), prm.ty, &what);
                }
                return None;
            }
        };
        if !self.in_out_bindable(prm, &arg, e.span) {
            return None;
        }
        let mut slots = vec![self.address_of(&arg)];
        slots.extend(bounds);
        Some(slots)
    }

    /// Binds `ARRAY[*]` VAR_IN_OUT `prm`, whose slots start at `at`, to
    /// argument `e`.
    pub(super) fn connect_open_array(&mut self, prm: &Param, at: &PlaceRef, e: &Expr) {
        let Some(slots) = self.open_array_argument(prm, e) else {
            return;
        };
        for (k, s) in slots.into_iter().enumerate() {
            let place = self.offset_place(at.place, k as u32);
            let dst = PlaceRef {
                place,
                ty: TypeTable::elem(ElemType::Lint),
                ..*at
            };
            self.write_place(&dst, s);
        }
    }

    /// `LOWER_BOUND(a, dim)` and `UPPER_BOUND(a, dim)` (DINT): constants
    /// for an array of fixed bounds, the argument's bounds for an
    /// `ARRAY[*]` parameter. `None` when the call is something else (a
    /// user POU of that name wins).
    pub(super) fn bound_call(&mut self, call: &Call) -> Option<Val> {
        let ExprKind::Name(id) = &call.callee.kind else {
            return None;
        };
        let key = id.key();
        let upper = match key.as_str() {
            "LOWER_BOUND" => false,
            "UPPER_BOUND" => true,
            _ => return None,
        };
        if self.model.pou_index.contains_key(&key) || self.lookup_var(&key).is_some() {
            return None;
        }
        let args: Vec<&Expr> = call
            .args
            .iter()
            .filter_map(|a| match a {
                Arg::Positional(e) => Some(e),
                Arg::Input { value, .. } => Some(value),
                Arg::Output { .. } => None,
            })
            .collect();
        let [array, dim] = args.as_slice() else {
            self.diags.error(
                "E251",
                call.span,
                format!("{} takes two arguments: an array and a dimension", id.name),
            );
            return Some(Val::error());
        };
        Some(self.array_bound(array, dim, upper))
    }

    /// The bound of dimension `dim` (a constant from 1) of `array`.
    fn array_bound(&mut self, array: &Expr, dim: &Expr, upper: bool) -> Val {
        let Some(p) = self.place(array) else {
            return Val::error();
        };
        let rank = match &self.types.get(p.ty).kind {
            TypeKind::Array { dims, .. } => dims.len() as u32,
            TypeKind::OpenArray { rank, .. } => *rank,
            _ => {
                if p.ty != TypeTable::error() {
                    let found = self.types.name(p.ty).to_string();
                    self.diags.error(
                        "E302",
                        array.span,
                        format!("LOWER_BOUND and UPPER_BOUND need an array, found {found}"),
                    );
                }
                return Val::error();
            }
        };
        let k = match self.expr(dim, None) {
            Val::Const(Const::Int(k), _) if (1..=rank as i128).contains(&k) => k as u32 - 1,
            v => {
                if !v.is_error() {
                    self.diags.error(
                        "E308",
                        dim.span,
                        format!("the dimension must be a constant from 1 to {rank}"),
                    );
                }
                return Val::error();
            }
        };
        let dint = TypeTable::elem(ElemType::Dint);
        if let TypeKind::Array { dims, .. } = &self.types.get(p.ty).kind {
            let d = dims[k as usize];
            let x = if upper { d.hi } else { d.lo };
            return Val::Const(Const::Int(x as i128), Ty::T(dint));
        }
        let Some(param) = self.open_param(array, &p) else {
            return Val::error();
        };
        let s = if upper {
            param.upper(k)
        } else {
            param.lower(k)
        };
        Val::Slot(s, dint)
    }
}
