//! CODESYS's and TwinCAT's `__SYSTEM.ExceptionCode`: the enumeration a
//! `__CATCH` variable is declared with (a type named with a namespace is
//! the type of its last name, so `__SYSTEM.ExceptionCode` is this one).
//! The values are the runtime's documented exception numbers
//! (`ir::exception_codes`); the faults plcrun raises map onto them in
//! `vm::exception`.

use super::declare::Declarer;
use crate::elementary::ElemType;
use crate::ir::exception_codes::TABLE;
use crate::ir::type_table::{TypeDef, TypeId, TypeKind, TypeTable};

/// The enumeration's name.
pub(super) const EXCEPTION_CODE: &str = "ExceptionCode";

/// The enumeration (interned), stored as UDINT.
fn exception_code_enum(types: &mut TypeTable) -> TypeId {
    types.intern(TypeDef {
        name: EXCEPTION_CODE.to_string(),
        kind: TypeKind::Enum {
            base: ElemType::Udint,
            values: TABLE.iter().map(|&(n, v)| (n.to_string(), v)).collect(),
        },
        size: 1,
    })
}

impl Declarer<'_> {
    /// Makes `ExceptionCode` a type of the program unless a source
    /// declares a TYPE or POU of that name (then theirs is the one meant).
    pub(super) fn register_exception_code(&mut self) {
        let key = EXCEPTION_CODE.to_ascii_uppercase();
        if self.type_decls.contains_key(&key) || self.model.pou_index.contains_key(&key) {
            return;
        }
        let t = exception_code_enum(&mut self.types);
        self.model.type_ids.insert(key, t);
    }
}
