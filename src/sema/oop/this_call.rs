//! `THIS^(...)` in a METHOD (CODESYS / TwinCAT): calls the body of the
//! instance the method runs on, as `inst(...)` would from outside. In the
//! FB's own body (or a parent's body reached by `SUPER^()`) it would call
//! itself: recursion, E409.

use super::calls::{is_this, place_ref};
use super::model::BODY;
use crate::ir::op::Slot;
use crate::sema::body::BodyBuilder;
use crate::sema::emit::Place;
use crate::syntax::ast::Call;

impl BodyBuilder<'_> {
    /// Emits `call` when it is `THIS^(...)` (true then).
    pub(in crate::sema) fn this_body_call(&mut self, call: &Call) -> bool {
        if !is_this(&call.callee) {
            return false;
        }
        let span = call.callee.span;
        let Some(scope) = self.oop.clone() else {
            self.diags
                .error("E918", span, "`THIS^` can only be used in a FUNCTION_BLOCK");
            return true;
        };
        let fb = &self.model.oop.fbs[&scope.fb];
        let in_a_body = scope
            .version
            .is_none_or(|v| fb.versions[v].name.name == BODY);
        if in_a_body {
            self.diags.error(
                "E409",
                span,
                "`THIS^()` in a function block's body calls that body again: recursion is not allowed",
            );
            return true;
        }
        let Some(&p) = self.model.pou_index.get(&scope.fb) else {
            return true;
        };
        let ty = self.model.pous[p].ty;
        // The method runs on the instance's own frame: slot 0 is THIS^.
        self.fb_call(
            &place_ref(Place::Frame(Slot::new(0)), ty),
            &call.args,
            call.span,
        );
        true
    }
}
