//! Which declarations of a global variable list hold function block
//! instances. They are declared after the list's other globals: laying
//! out an instance emits its FB's body, and that body may use any global
//! of the list (TcUnit's `GVL_TcUnit` starts with `TcUnitRunner :
//! FB_TcUnitRunner;`, whose body reads the list's later variables). Their
//! memory comes after the others'; nothing else depends on the order.

use super::declare::Declarer;
use crate::syntax::ast::{PouKind, TypeSpec, VarBlock};

impl Declarer<'_> {
    /// The indexes of `block`'s declarations whose type is a user
    /// FUNCTION_BLOCK or an array of one.
    pub(super) fn instance_decls(&self, block: &VarBlock) -> Vec<usize> {
        (0..block.decls.len())
            .filter(|&d| self.names_an_fb(&block.decls[d].ty))
            .collect()
    }

    fn names_an_fb(&self, spec: &TypeSpec) -> bool {
        match spec {
            TypeSpec::Named(id) => {
                let key = id.key();
                !self.type_decls.contains_key(&key)
                    && self
                        .model
                        .pou_index
                        .get(&key)
                        .is_some_and(|&p| self.model.pous[p].kind == PouKind::FunctionBlock)
            }
            TypeSpec::Array { elem, .. } => self.names_an_fb(elem),
            _ => false,
        }
    }
}
