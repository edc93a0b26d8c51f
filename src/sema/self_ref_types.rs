//! Structures that refer to themselves through a reference: a linked
//! list `TYPE Node : STRUCT next : REF_TO Node; v : INT; END_STRUCT
//! END_TYPE` (and `POINTER TO Node`, `REFERENCE TO Node`, or a structure
//! reached through another one: `A` holds `REF_TO B`, `B` holds `REF_TO A`).
//!
//! A structure cannot contain itself (E204: its size would be infinite),
//! but a reference is one slot whatever it designates, so the layout does
//! not need the target's layout. A STRUCT TYPE therefore gets its type id
//! *before* its fields are resolved (a placeholder the finished definition
//! replaces); a reference to a structure still being resolved uses that
//! id, and everything else about the structure (its size, its fields) is
//! read only once it is complete. Anything but a reference to it inside
//! itself is still E204.

use super::declare::Declarer;
use super::model::LayoutState;
use crate::ir::type_table::{TypeDef, TypeId, TypeKind};
use crate::syntax::ast::TypeSpec;

impl Declarer<'_> {
    /// Gives the STRUCT TYPE `key` its id before its fields are resolved.
    pub(super) fn reserve_struct_id(&mut self, key: &str, name: &str, spec: &TypeSpec) {
        if !matches!(spec, TypeSpec::Struct { .. }) {
            return;
        }
        let id = self.types.add(TypeDef {
            name: name.to_string(),
            kind: TypeKind::Struct { fields: Vec::new() },
            size: 1,
        });
        self.reserved_structs.insert(key.to_string(), id);
    }

    /// The finished named STRUCT or ENUM type `def`: stored at the id
    /// reserved for `key` if there is one, else added.
    pub(super) fn place_named_type(&mut self, key: &str, def: TypeDef) -> TypeId {
        match self.reserved_structs.remove(key) {
            Some(id) => {
                self.types.set(id, def);
                id
            }
            None => self.types.add(def),
        }
    }

    /// The reserved id of the structure a reference designates when that
    /// structure is still being resolved (the reference is inside it).
    pub(super) fn reference_to_unfinished(&self, target: &TypeSpec) -> Option<TypeId> {
        let TypeSpec::Named(id) = target else {
            return None;
        };
        let key = id.key();
        if self.type_state.get(&key) != Some(&LayoutState::InProgress) {
            return None;
        }
        self.reserved_structs.get(&key).copied()
    }
}
