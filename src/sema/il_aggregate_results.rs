//! In IL, a call of a FUNCTION that returns a STRUCT or an ARRAY.
//!
//! The IL current result holds one value (one slot); a structured result
//! does not fit it. Before, such a call left the CR at 0 and `ST p` then
//! stored that 0 into `p`'s first field: a wrong value without a word.
//! It is refused by name now (E431) until IL gets a structured current
//! result; ST calls it (`p := MakePt(3);`, also `MakePt(3).x`).

use super::body::BodyBuilder;
use crate::ir::type_table::TypeKind;
use crate::source::Span;
use crate::syntax::ast::Ident;

impl BodyBuilder<'_> {
    /// E431 when `name` is a user FUNCTION whose result is a STRUCT or an
    /// ARRAY (the caller then does not emit the call).
    pub(super) fn il_refuses_aggregate_result(&mut self, name: &Ident, span: Span) -> bool {
        let Some(&p) = self.model.pou_index.get(&name.key()) else {
            return false;
        };
        let ret = self.model.pous[p].ret;
        if !matches!(
            self.types.get(ret).kind,
            TypeKind::Struct { .. } | TypeKind::Array { .. }
        ) {
            return false;
        }
        let ty = self.types.name(ret).to_string();
        self.diags.error(
            "E431",
            span,
            format!(
                "in IL the current result holds one value: `{}` returns a {ty}, which it cannot \
                 hold; call it from ST (`x := {}(...);`)",
                name.name, name.name
            ),
        );
        true
    }
}
