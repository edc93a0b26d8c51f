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
//!
//! A function block may refer to its own type the same way: a
//! `VAR_IN_OUT other : FB_Self` of the block or of one of its methods, or a
//! `REF_TO FB_Self` / `POINTER TO` / `REFERENCE TO` variable, is one slot
//! (a pointer). Such a declaration met while the block itself is being
//! laid out gets an id reserved for the block's type, which the finished
//! layout fills in; the block's body (and its methods') is emitted only
//! after that, so it sees the complete type. Only the block being laid out
//! right now refers to itself this way: an instance of it inside itself,
//! or a reference reached through another block that is still being laid
//! out, stays E204.

use super::declare::Declarer;
use super::model::LayoutState;
use crate::ir::type_table::{TypeDef, TypeId, TypeKind};
use crate::syntax::ast::{PouKind, TypeSpec};

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
    /// structure is still being resolved (the reference is inside it), or
    /// of the function block being laid out when it names that block.
    pub(super) fn reference_to_unfinished(&mut self, target: &TypeSpec) -> Option<TypeId> {
        let TypeSpec::Named(id) = target else {
            return None;
        };
        let key = id.key();
        if self.type_state.get(&key) != Some(&LayoutState::InProgress) {
            return self.own_fb_type(&key);
        }
        self.reserved_structs.get(&key).copied()
    }

    /// The type of the function block `target` names, laid out but its
    /// body not emitted yet: a reference to it needs only its type, and
    /// emitting the body now could read globals not declared yet
    /// (`suites : ARRAY[1..4] OF POINTER TO FB_Suite;` before `count :
    /// INT;` in a list, and FB_Suite's body writing `count`). `None` for
    /// any other name, and for a block being laid out (the caller's path
    /// reports or resolves that).
    pub(super) fn fb_laid_out(&mut self, target: &TypeSpec) -> Option<TypeId> {
        let TypeSpec::Named(id) = target else {
            return None;
        };
        let key = id.key();
        if crate::elementary::ElemType::from_name(&id.name).is_some()
            || self.type_decls.contains_key(&key)
        {
            return None;
        }
        let &p = self.model.pou_index.get(&key)?;
        if self.model.pous[p].kind != PouKind::FunctionBlock
            || self.pou_state[p] == LayoutState::InProgress
        {
            return None;
        }
        self.layout_pou(p);
        (self.pou_state[p] == LayoutState::Done).then(|| self.model.pous[p].ty)
    }

    /// The id of the function block named `key` when it is the POU being
    /// laid out (reserved on first use), for a declaration that refers to
    /// it through a pointer slot.
    pub(super) fn own_fb_type(&mut self, key: &str) -> Option<TypeId> {
        let &p = self.model.pou_index.get(key)?;
        let info = &self.model.pous[p];
        if self.layout_path.last() != Some(&p)
            || info.kind != PouKind::FunctionBlock
            || self.pou_state[p] != LayoutState::InProgress
        {
            return None;
        }
        let name = info.name.clone();
        let types = &mut self.types;
        Some(*self.reserved_fbs.entry(p).or_insert_with(|| {
            types.add(TypeDef {
                name,
                kind: TypeKind::Pou {
                    code: crate::ir::op::CodeIdx::new(u32::MAX),
                    members: Vec::new(),
                    program: false,
                },
                size: 1,
            })
        }))
    }

    /// Stores the finished type of POU `p` at the id reserved for it, if
    /// one was, else adds it.
    pub(super) fn place_pou_type(&mut self, p: usize, def: TypeDef) -> TypeId {
        match self.reserved_fbs.remove(&p) {
            Some(id) => {
                self.types.set(id, def);
                id
            }
            None => self.types.add(def),
        }
    }
}
