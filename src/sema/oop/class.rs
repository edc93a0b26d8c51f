//! Classes (edition 3): FBs without a body, lowered as such. This file
//! records which FBs are classes, checks that a class extends only a class
//! (E926), and refuses calling a class instance as if it were an FB (E925).

use super::model::OopInfo;
use crate::diagnostics::Diagnostics;
use crate::ir::type_table::{TypeId, TypeKind};
use crate::sema::body::BodyBuilder;
use crate::source::Span;
use crate::syntax::ast::{CompilationUnit, Item};

/// Records the classes of `units` in `info`; E926 for a class whose parent
/// is a FUNCTION_BLOCK.
pub(crate) fn collect(units: &[CompilationUnit], info: &mut OopInfo, diags: &mut Diagnostics) {
    let classes = units.iter().flat_map(|u| &u.items).filter_map(|i| match i {
        Item::Pou(p) if p.oop.as_ref().is_some_and(|o| o.is_class) => Some(p),
        _ => None,
    });
    let classes: Vec<_> = classes.collect();
    for p in &classes {
        info.classes.insert(p.name.key());
    }
    for p in classes {
        let Some(ext) = p.oop.as_ref().and_then(|o| o.extends.as_ref()) else {
            continue;
        };
        if info.fbs.contains_key(&ext.key()) && !info.classes.contains(&ext.key()) {
            diags.error(
                "E926",
                ext.span,
                format!(
                    "`{}` is a FUNCTION_BLOCK: a CLASS can only extend another CLASS",
                    ext.name
                ),
            );
        }
    }
}

impl BodyBuilder<'_> {
    /// E925 when the instance of type `ty` being called is a class
    /// instance (it has no body: call its methods). True when refused.
    pub(in crate::sema) fn class_instance_called(&mut self, ty: TypeId, span: Span) -> bool {
        if self.model.oop.classes.is_empty()
            || !matches!(self.types.get(ty).kind, TypeKind::Pou { .. })
        {
            return false;
        }
        let name = self.types.get(ty).name.clone();
        if !self.model.oop.classes.contains(&name.to_ascii_uppercase()) {
            return false;
        }
        self.diags.error(
            "E925",
            span,
            format!(
                "`{name}` is a CLASS: its instances have no body to call; call one of its methods (`inst.Method()`)"
            ),
        );
        true
    }
}
