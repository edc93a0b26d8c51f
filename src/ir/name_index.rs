//! Case-insensitive look-up of members and globals by name, for the names
//! given from outside the program (`Plc::read`, `resolve`, traces,
//! stimuli). A scan of the declarations is kept for short lists; a long
//! one (a program of ten thousand SFC steps, an S7-200 byte image) gets a
//! hash table when the image is verified, so that reading every variable
//! of a program by name stays linear instead of quadratic in its size.
//!
//! The tables are built once, eagerly, and hold no interior mutability: an
//! `Image` with a cell in it (a lazily filled `OnceLock`, tried first) is
//! no longer immutable behind `&Image` for the compiler, which then
//! reloads the image's fields in the executor's loop after every store
//! (bench a 1.46x slower, docs/performance.md).

use super::image::RootVar;
use super::type_table::{Member, MemberKind, TypeId, TypeTable};
use std::collections::HashMap;

/// Lists shorter than this are scanned: hashing the name costs more.
const INDEXED_FROM: usize = 64;

/// The tables of an image's long lists (empty until
/// [`NameIndex::build`]; a list without its table is scanned).
#[derive(Debug, Clone, Default)]
pub struct NameIndex {
    /// Per type with a long member list: upper-cased name → index of the
    /// first member of that name that is not a VAR_IN_OUT.
    members: HashMap<TypeId, HashMap<String, usize>>,
    /// Upper-cased name → index of the first global of that name, when
    /// the globals are many.
    globals: HashMap<String, usize>,
}

impl NameIndex {
    /// Member `name` of type `ty` that is not a VAR_IN_OUT (an in-out is
    /// a reference, not a place of the instance), or `None`.
    pub fn member<'t>(&self, types: &'t TypeTable, ty: TypeId, name: &str) -> Option<&'t Member> {
        let members = types.members(ty);
        match self.members.get(&ty) {
            Some(table) => table.get(&name.to_ascii_uppercase()).map(|&i| &members[i]),
            None => members
                .iter()
                .find(|m| m.name.eq_ignore_ascii_case(name) && m.kind != MemberKind::InOut),
        }
    }

    /// The global (or located variable) named `name`, or `None`.
    pub fn global<'g>(&self, globals: &'g [RootVar], name: &str) -> Option<&'g RootVar> {
        if self.globals.is_empty() {
            return globals.iter().find(|r| r.name.eq_ignore_ascii_case(name));
        }
        self.globals
            .get(&name.to_ascii_uppercase())
            .map(|&i| &globals[i])
    }

    /// The tables of `types` and `globals` (the image's final lists).
    pub fn build(types: &TypeTable, globals: &[RootVar]) -> NameIndex {
        let mut tables = NameIndex::default();
        for ty in (0..types.len()).map(|i| TypeId(i as u32)) {
            let members = types.members(ty);
            if members.len() < INDEXED_FROM {
                continue;
            }
            let mut table = HashMap::with_capacity(members.len());
            for (i, m) in members.iter().enumerate() {
                if m.kind != MemberKind::InOut {
                    table.entry(m.name.to_ascii_uppercase()).or_insert(i);
                }
            }
            tables.members.insert(ty, table);
        }
        if globals.len() >= INDEXED_FROM {
            for (i, r) in globals.iter().enumerate() {
                tables
                    .globals
                    .entry(r.name.to_ascii_uppercase())
                    .or_insert(i);
            }
        }
        tables
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elementary::ElemType;
    use crate::ir::type_table::{Retention, TypeDef, TypeKind};

    fn member(name: &str, offset: u32, kind: MemberKind) -> Member {
        Member {
            kind,
            retain: Retention::Inherit,
            ..Member::field(name, TypeTable::elem(ElemType::Int), offset)
        }
    }

    /// A struct of `n` fields `F0..`, with an in-out `DUP` before a
    /// field `dup`, so that the first *place* of that name is the field.
    fn table(n: usize) -> (TypeTable, TypeId) {
        let mut fields = vec![
            member("DUP", 0, MemberKind::InOut),
            member("dup", 1, MemberKind::Field),
        ];
        fields.extend((0..n).map(|i| member(&format!("F{i}"), 2 + i as u32, MemberKind::Field)));
        let mut types = TypeTable::new();
        let size = fields.len() as u32;
        let ty = types.add(TypeDef {
            name: "S".into(),
            kind: TypeKind::Struct { fields },
            size,
        });
        (types, ty)
    }

    #[test]
    fn long_and_short_lists_find_the_same_members() {
        for n in [3, INDEXED_FROM * 2] {
            let (types, ty) = table(n);
            let index = NameIndex::build(&types, &[]);
            let found = |name| index.member(&types, ty, name).map(|m| m.offset);
            assert_eq!(found("Dup"), Some(1), "{n} fields: the in-out is skipped");
            assert_eq!(found("f2"), Some(4), "{n} fields");
            assert_eq!(found("F2x"), None, "{n} fields");
        }
    }

    #[test]
    fn many_globals_are_found_by_any_spelling_and_the_first_wins() {
        let global = |name: &str, addr| RootVar {
            name: name.to_string(),
            ty: TypeTable::elem(ElemType::Bool),
            addr,
            kind: MemberKind::Local,
            location: None,
            constant: false,
        };
        let mut globals: Vec<RootVar> = (0..INDEXED_FROM as u32 * 2)
            .map(|i| global(&format!("g{i}"), i))
            .collect();
        globals.push(global("G5", 999));
        let index = NameIndex::build(&TypeTable::new(), &globals);
        assert_eq!(index.global(&globals, "G5").map(|r| r.addr), Some(5));
        assert_eq!(index.global(&globals, "nope").map(|r| r.addr), None);
        // An image never verified has no tables: its lists are scanned.
        let unbuilt = NameIndex::default();
        assert_eq!(unbuilt.global(&globals, "g7").map(|r| r.addr), Some(7));
    }
}
