//! Array elements in `VAR_CONFIG` paths: `R.main.valves[2].coil` (an
//! element of an array of function block instances) and
//! `R.main.fb.lamps[3]` (an element of an array declared `AT %Q*`, whose
//! elements each get their own address). Edition 3 names only variables
//! and FB instances in a VAR_CONFIG path; the elements are a CODESYS form,
//! W326.

use super::Linker;
use super::auto_address::Unplaced;
use crate::ir::type_table::{Dim, TypeId, TypeKind, linear_index};
use crate::sema::incomplete_address::element_suffix;
use crate::sema::model::VarInfo;
use crate::source::Span;
use crate::syntax::ast::Expr;
use std::collections::HashSet;

/// A VAR_CONFIG path that names nothing (as in `var_config.rs`).
const UNKNOWN_PATH: &str = "E711";

impl Linker<'_> {
    /// W326 once for a VAR_CONFIG line whose path goes through array
    /// elements (`first` is the first subscript).
    pub(super) fn warn_config_elements(&mut self, first: Span) {
        self.diags.warning(
            "W326",
            first,
            "an array element in a VAR_CONFIG path is a CODESYS form (edition 3 names \
             variables and FB instances)",
        );
    }

    /// The offset (in slots) and type of element `index` of the array type
    /// `ty`, named `name` in messages; E711 when `ty` is not an array, the
    /// count of indexes differs or one is outside its bounds.
    pub(super) fn config_element(
        &mut self,
        ty: TypeId,
        index: &[Expr],
        name: &str,
        span: Span,
    ) -> Option<(u32, TypeId, String)> {
        let TypeKind::Array { dims, elem } = self.types.get(ty).kind.clone() else {
            self.diags.error(
                UNKNOWN_PATH,
                span,
                format!("`{name}` is not an array: VAR_CONFIG cannot index it"),
            );
            return None;
        };
        if dims.len() != index.len() {
            self.diags.error(
                UNKNOWN_PATH,
                span,
                format!(
                    "`{name}` has {} dimension(s), {} index(es) given",
                    dims.len(),
                    index.len()
                ),
            );
            return None;
        }
        let mut values = Vec::with_capacity(index.len());
        for e in index {
            values.push(self.consts().const_int(e, None)?);
        }
        let Some(linear) = linear_index(&dims, &values) else {
            self.diags.error(
                UNKNOWN_PATH,
                span,
                format!("an index of `{name}` is outside the array's bounds"),
            );
            return None;
        };
        let stride = u64::from(self.types.size(elem));
        let offset = u32::try_from(linear * stride).ok()?;
        let text: Vec<String> = values.iter().map(|v| v.to_string()).collect();
        Some((offset, elem, format!("{name}[{}]", text.join(","))))
    }

    /// The element type, element count and stride of an array type.
    pub(super) fn array_elements(&self, ty: TypeId) -> Option<(TypeId, u64, u32)> {
        let TypeKind::Array { dims, elem } = &self.types.get(ty).kind else {
            return None;
        };
        let count = dims.iter().map(Dim::len).product();
        Some((*elem, count, self.types.size(*elem)))
    }
}

impl Linker<'_> {
    /// Collects the incomplete addresses inside each element of the array
    /// of FB instances `var` (of POU `p`, at absolute slot `at`, named
    /// `here`) that no VAR_CONFIG line completed (an array declared
    /// `AT %Q*` itself is `collect_uncompleted`'s).
    pub(super) fn collect_uncompleted_elements(
        &mut self,
        var: &VarInfo,
        at: u32,
        here: &str,
        completed: &HashSet<u32>,
        depth: usize,
        out: &mut Vec<Unplaced>,
    ) {
        let Some((elem, count, stride)) = self.array_elements(var.ty) else {
            return;
        };
        let TypeKind::Array { dims, .. } = self.types.get(var.ty).kind.clone() else {
            return;
        };
        let slot = |k: u64| u32::try_from(at as u64 + k * u64::from(stride)).ok();
        if let Some(q) = self.fb_pou(elem) {
            for k in 0..count {
                let Some(s) = slot(k) else {
                    return;
                };
                let name = element_name(here, &dims, k);
                self.collect_uncompleted(q, s, &name, completed, depth + 1, out);
            }
        }
    }
}

/// `name[i,j]` for row-major element number `k` of an array of `dims`.
fn element_name(name: &str, dims: &[Dim], k: u64) -> String {
    format!("{name}{}", element_suffix(dims, k))
}
