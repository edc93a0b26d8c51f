//! `__POUNAME()` (CODESYS / TwinCAT): the name of the POU whose code
//! calls it, as a STRING constant — in a METHOD, `FB.Method`, the FB
//! that declares the method (TwinCAT's logging helpers pass it as the
//! source of a message).

use super::body::BodyBuilder;
use super::emit::Val;
use crate::syntax::ast::{Call, ExprKind};

impl BodyBuilder<'_> {
    /// `__POUNAME()`, unless a POU or variable of that name wins; `None`
    /// for any other call.
    pub(super) fn pou_name_call(&mut self, call: &Call) -> Option<Val> {
        let ExprKind::Name(id) = &call.callee.kind else {
            return None;
        };
        let key = id.key();
        if key != "__POUNAME"
            || self.model.pou_index.contains_key(&key)
            || self.lookup_var(&key).is_some()
        {
            return None;
        }
        if !call.args.is_empty() {
            self.diags
                .error("E251", call.span, "__POUNAME takes no argument");
            return Some(Val::error());
        }
        let name = self.running_pou_name();
        let text = super::assert_calls::string_literal(&name, call.span);
        Some(self.expr(&text, None))
    }

    /// The running code's POU name: `FB.Method` inside a method.
    fn running_pou_name(&self) -> String {
        let pou = &self.model.pous[self.block.pou].name;
        let Some(scope) = &self.oop else {
            return pou.clone();
        };
        let Some(fb) = self.model.oop.fbs.get(&scope.origin) else {
            return pou.clone();
        };
        match scope
            .version
            .and_then(|v| self.model.oop.fbs.get(&scope.fb)?.versions.get(v))
        {
            Some(v) if v.name.name != super::oop::model::BODY => {
                format!("{}.{}", fb.name, v.name.name)
            }
            _ => fb.name.clone(),
        }
    }
}
