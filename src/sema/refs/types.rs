//! Reference types in declarations.

use super::intern_ref;
use crate::ir::type_table::{RefFlavor, TypeId, TypeTable};
use crate::sema::declare::Declarer;
use crate::sema::model::VarInfo;
use crate::source::Span;
use crate::syntax::ast::{RefKind, TypeSpec};
use indexmap::IndexMap;

impl Declarer<'_> {
    /// `REF_TO T`, `POINTER TO T` (a CODESYS extension: W300) or
    /// `REFERENCE TO T` (CODESYS: W304).
    pub(in crate::sema) fn ref_type(
        &mut self,
        kind: RefKind,
        target: &TypeSpec,
        span: Span,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> TypeId {
        let t = match self.reference_to_unfinished(target) {
            Some(t) => t,
            None => match self.fb_laid_out(target) {
                Some(t) => t,
                None => self.resolve_type(target, local),
            },
        };
        let flavor = match kind {
            RefKind::RefTo => RefFlavor::RefTo,
            RefKind::Pointer => {
                self.diags.warning(
                    "W300",
                    span,
                    "`POINTER TO` is a CODESYS extension (IEC 61131-3 edition 3 has `REF_TO`)",
                );
                RefFlavor::Pointer
            }
            RefKind::Reference => {
                self.diags.warning(
                    "W304",
                    span,
                    "`REFERENCE TO` is a CODESYS extension (IEC 61131-3 edition 3 has `REF_TO`)",
                );
                RefFlavor::Reference
            }
        };
        if t == TypeTable::error() {
            return t;
        }
        if t == TypeTable::void() {
            self.diags
                .error("E250", span, "a reference needs a type to refer to");
            return TypeTable::error();
        }
        intern_ref(&mut self.types, t, flavor)
    }
}
