//! Arguments of generic inputs (`x : ANY`, any_params.rs): the call
//! fills the input's three fields with the argument's type class, a
//! `POINTER TO BYTE` to it and its size in bytes. A variable is passed by
//! its address; anything else (a literal, an expression, a constant, a
//! function's result) is first computed into a temporary of the caller,
//! whose address is passed. A generic input of the caller given as the
//! argument passes its three fields on.
//!
//! Refused at the argument: a type outside the input's class (E439), and
//! a value plcrun has no byte layout for or CODESYS no type class for (a
//! structure, an FB instance, a pointer, an array of strings, CHAR: E440).

use super::any_params::{GenericClass, type_class_name, type_class_of};
use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Place, PlaceRef, Ty, Val};
use super::refs::{layout_code, size_bytes, view_unit};
use crate::elementary::ElemType;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{TypeDef, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind};

impl BodyBuilder<'_> {
    /// The class of a generic input's type, if `ty` is one.
    pub(super) fn any_class(&self, ty: TypeId) -> Option<GenericClass> {
        self.model.any_types.get(&ty).copied()
    }

    /// The three slots (type class, pointer, size) generic input `name`
    /// of class `class` receives for argument `e`.
    pub(super) fn any_argument(
        &mut self,
        class: GenericClass,
        name: &str,
        e: &Expr,
    ) -> Option<[Slot; 3]> {
        let arg = if self.is_variable(e) {
            self.place(e)?
        } else {
            self.any_temporary(class, name, e)?
        };
        if arg.ty == TypeTable::error() {
            return None;
        }
        if let Some(from) = self.any_class(arg.ty) {
            return self.any_passed_on(class, from, name, &arg, e.span);
        }
        let t = self.any_admitted(class, name, arg.ty, e.span)?;
        let size = size_bytes(self.types, arg.ty).unwrap_or(0);
        let tc = self.block.const_slot(t as u64);
        let pointer = self.any_pointer(&arg);
        let size = self.block.const_slot(size);
        Some([tc, pointer, size])
    }

    /// Binds generic input `dst` of an FB or method instance (named `name`)
    /// to argument `e`: its three fields are written in the instance.
    pub(super) fn connect_any(
        &mut self,
        class: GenericClass,
        dst: &PlaceRef,
        e: &Expr,
        name: &str,
    ) {
        let Some(slots) = self.any_argument(class, name, e) else {
            return;
        };
        for (k, s) in slots.into_iter().enumerate() {
            let place = self.offset_place(dst.place, k as u32);
            let field = PlaceRef {
                place,
                ty: TypeTable::elem(ElemType::Ulint),
                ..*dst
            };
            self.write_place(&field, s);
        }
    }

    /// The address of three consecutive temporaries holding what generic
    /// input `name` (of type `ty`, class `class`) receives for argument
    /// `e`: a call through an interface copies them into each
    /// implementing block's input as a structure.
    pub(super) fn any_block(
        &mut self,
        class: GenericClass,
        ty: TypeId,
        name: &str,
        e: &Expr,
    ) -> Option<Slot> {
        let slots = self.any_argument(class, name, e)?;
        let at = self.block.temps(slots.len() as u32);
        for (k, s) in slots.into_iter().enumerate() {
            self.block.emit(Op::Mov {
                d: at.offset(k as u32),
                s,
            });
        }
        self.block.last_def = None;
        let place = PlaceRef {
            place: Place::Frame(at),
            ty,
            writable: true,
            readonly_reason: None,
            input_image: false,
        };
        Some(self.address_of(&place))
    }

    /// E404 for generic input `name` of `callee` left out of a call of a
    /// FUNCTION or METHOD: it has no initial value to take.
    pub(super) fn any_missing(&mut self, name: &str, callee: &str, span: Span) {
        self.diags.error(
            "E404",
            span,
            format!(
                "input `{name}` of `{callee}` must be given: a generic (ANY) input has no initial value"
            ),
        );
    }

    /// True when `e` denotes a variable (passed by address); false for
    /// what is computed (passed through a temporary).
    fn is_variable(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Name(id) => self.lookup_var(&id.key()).is_some_and(|v| !v.constant),
            ExprKind::Member(base, field) => match &base.kind {
                // `GVL.x` is a variable; `E.Value`, `Ns.E.Value` are values.
                ExprKind::Name(b) if self.lookup_var(&b.key()).is_none() => {
                    self.is_list_qualifier(base, field)
                }
                ExprKind::Member(..) | ExprKind::Name(_) => self.is_variable(base),
                _ => true,
            },
            ExprKind::Index(..) | ExprKind::Deref(_) | ExprKind::Direct(_) => true,
            _ => false,
        }
    }

    /// `e` computed into a temporary of the caller, typed as written (an
    /// integer literal INT, DINT or LINT by its value, a real literal
    /// LREAL; both LREAL for ANY_REAL), a string literal as a STRING of
    /// its length.
    fn any_temporary(&mut self, class: GenericClass, name: &str, e: &Expr) -> Option<PlaceRef> {
        let v = self.expr(e, None);
        if v.is_error() {
            return None;
        }
        let ty = match (&v, v.ty()) {
            (_, Ty::AnyReal) => TypeTable::elem(ElemType::Lreal),
            (_, Ty::AnyInt) if class == GenericClass::Real => TypeTable::elem(ElemType::Lreal),
            (Val::Const(Const::Int(i), _), Ty::AnyInt) => TypeTable::elem(literal_int(*i)),
            (_, Ty::AnyInt) => TypeTable::elem(ElemType::Lint),
            (Val::Const(Const::Str(s), _), Ty::T(t)) => self.literal_string(s, t),
            (_, Ty::T(t)) => t,
        };
        self.any_admitted(class, name, ty, e.span)?;
        let what = format!("argument `{name}`");
        let v = self.coerce(v, ty, e.span, &what);
        if v.is_error() {
            return None;
        }
        let s = self.materialize(&v);
        let slot = match self.types.get(ty).kind {
            TypeKind::Str { max, wide } => {
                let st = self.string_temp(max, wide);
                self.block.emit(Op::StrMov { d: st, s });
                st
            }
            _ if self.types.size(ty) == 1 => {
                // A slot of its own: the callee may write through the pointer.
                let t = self.block.temp();
                self.block.emit(Op::Mov { d: t, s });
                t
            }
            _ => {
                let found = self.types.name(ty).to_string();
                self.diags.error(
                    "E440",
                    e.span,
                    format!("{found} computed by an expression cannot be passed to ANY input `{name}`: store it in a variable and pass the variable"),
                );
                return None;
            }
        };
        self.block.last_def = None;
        Some(PlaceRef {
            place: Place::Frame(slot),
            ty,
            writable: true,
            readonly_reason: None,
            input_image: false,
        })
    }

    /// The type of string literal `s` written where a `t` was found: a
    /// STRING (or WSTRING) of its length, at least 1.
    fn literal_string(&mut self, s: &str, t: TypeId) -> TypeId {
        let TypeKind::Str { wide, .. } = self.types.get(t).kind else {
            return t;
        };
        let max = (s.chars().count() as u32).max(1);
        let kw = if wide { "WSTRING" } else { "STRING" };
        self.types.intern(TypeDef {
            name: format!("{kw}[{max}]"),
            kind: TypeKind::Str { wide, max },
            size: 1,
        })
    }

    /// The type class of an argument of type `ty` for an input of
    /// `class`, after E440 (no class, no bytes) or E439 (outside the
    /// class).
    fn any_admitted(
        &mut self,
        class: GenericClass,
        name: &str,
        ty: TypeId,
        span: Span,
    ) -> Option<u32> {
        if ty == TypeTable::error() {
            return None;
        }
        let ty_name = self.types.name(ty).to_string();
        let strings_inside = matches!(self.types.get(ty).kind, TypeKind::Array { .. })
            && matches!(
                self.types.get(self.types.innermost(ty)).kind,
                TypeKind::Str { .. }
            );
        let Some(t) = type_class_of(self.types, ty) else {
            self.diags.error(
                "E440",
                span,
                format!("{ty_name} cannot be passed to ANY input `{name}`: CODESYS's TYPE_CLASS has no value for it"),
            );
            return None;
        };
        if layout_code(self.types, ty) == 0 || strings_inside {
            self.diags.push(
                crate::diagnostics::Diagnostic::error(
                    "E440",
                    span,
                    format!("{ty_name} cannot be passed to ANY input `{name}`: plcrun has no byte layout for it"),
                )
                .with_note("an ANY input is read through a POINTER TO BYTE; plcrun lays out elementary values, strings and arrays of them as CODESYS does, not structures, function block instances, pointers or arrays of strings (docs/semantics.md §23)"),
            );
            return None;
        }
        if !class.accepts(t) {
            self.any_outside(class, name, &ty_name, type_class_name(t), span);
            return None;
        }
        Some(t)
    }

    /// E439: an argument of type `found` (class `tc`) for input `name` of
    /// `class`.
    fn any_outside(&mut self, class: GenericClass, name: &str, found: &str, tc: &str, span: Span) {
        self.diags.error(
            "E439",
            span,
            format!(
                "input `{name}` is {}: {found} ({tc}) is not of that class",
                class.name()
            ),
        );
    }

    /// The fields of generic input `arg` (class `from`) of the caller,
    /// passed on to input `name` of `class` (E439 when `class` does not
    /// take every type `from` takes).
    fn any_passed_on(
        &mut self,
        class: GenericClass,
        from: GenericClass,
        name: &str,
        arg: &PlaceRef,
        span: Span,
    ) -> Option<[Slot; 3]> {
        if !class.includes(from) {
            let tc = "its argument's class is only known when it runs";
            self.any_outside(class, name, from.name(), tc, span);
            return None;
        }
        let mut slots = [Slot::new(0); 3];
        for (k, s) in slots.iter_mut().enumerate() {
            let place = self.offset_place(arg.place, k as u32);
            let field = PlaceRef {
                place,
                ty: TypeTable::elem(ElemType::Ulint),
                ..*arg
            };
            let v = self.read_place(&field);
            *s = self.materialize(&v);
        }
        Some(slots)
    }

    /// A `POINTER TO BYTE` to the whole of `arg`: a byte view (§23 of
    /// docs/semantics.md) unless its elements are bytes already.
    fn any_pointer(&mut self, arg: &PlaceRef) -> Slot {
        let d = self.reference_value(arg);
        let inner = self.types.innermost(arg.ty);
        if self.types.get(inner).kind != TypeKind::Elem(ElemType::Byte) {
            self.block.emit(Op::RefView {
                d,
                unit: view_unit(self.types, arg.ty),
            });
        }
        self.block.last_def = None;
        d
    }
}

/// The type of an integer literal passed to a generic input: the
/// smallest of INT, DINT and LINT that holds it (ULINT beyond).
fn literal_int(i: i128) -> ElemType {
    if i16::try_from(i).is_ok() {
        ElemType::Int
    } else if i32::try_from(i).is_ok() {
        ElemType::Dint
    } else if i64::try_from(i).is_ok() {
        ElemType::Lint
    } else {
        ElemType::Ulint
    }
}
