//! CODESYS's and TwinCAT's `__SYSTEM.ExceptionCode`: the enumeration a
//! `__CATCH` variable is declared with (a type named with a namespace is
//! the type of its last name, so `__SYSTEM.ExceptionCode` is this one).
//! The values are the runtime's documented exception numbers; the faults
//! plcrun raises map onto them in `vm::fault`.

use super::declare::Declarer;
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeDef, TypeId, TypeKind, TypeTable};

/// The enumeration's name.
pub(super) const EXCEPTION_CODE: &str = "ExceptionCode";

/// The values, as the vendors document them.
const VALUES: [(&str, i64); 49] = [
    ("RTSEXCPT_UNKNOWN", 0xFFFF_FFFF),
    ("RTSEXCPT_NOEXCEPTION", 0x0000),
    ("RTSEXCPT_WATCHDOG", 0x0010),
    ("RTSEXCPT_HARDWAREWATCHDOG", 0x0011),
    ("RTSEXCPT_IO_CONFIG_ERROR", 0x0012),
    ("RTSEXCPT_PROGRAMCHECKSUM", 0x0013),
    ("RTSEXCPT_FIELDBUS_ERROR", 0x0014),
    ("RTSEXCPT_IOUPDATE_ERROR", 0x0015),
    ("RTSEXCPT_CYCLE_TIME_EXCEED", 0x0016),
    ("RTSEXCPT_ONLCHANGE_PROGRAM_EXCEEDED", 0x0017),
    ("RTSEXCPT_UNRESOLVED_EXTREFS", 0x0018),
    ("RTSEXCPT_DOWNLOAD_REJECTED", 0x0019),
    ("RTSEXCPT_BOOTPROJECT_REJECTED_DUE_RETAIN_ERROR", 0x001A),
    ("RTSEXCPT_LOADBOOTPROJECT_FAILED", 0x001B),
    ("RTSEXCPT_OUT_OF_MEMORY", 0x001C),
    ("RTSEXCPT_RETAIN_MEMORY_ERROR", 0x001D),
    ("RTSEXCPT_BOOTPROJECT_CRASH", 0x001E),
    ("RTSEXCPT_BOOTPROJECTTARGETMISMATCH", 0x0021),
    ("RTSEXCPT_SCHEDULEERROR", 0x0022),
    ("RTSEXCPT_FILE_CHECKSUM_ERR", 0x0023),
    ("RTSEXCPT_RETAIN_IDENTITY_MISMATCH", 0x0024),
    ("RTSEXCPT_IEC_TASK_CONFIG_ERROR", 0x0025),
    ("RTSEXCPT_APP_TARGET_MISMATCH", 0x0026),
    ("RTSEXCPT_ILLEGAL_INSTRUCTION", 0x0050),
    ("RTSEXCPT_ACCESS_VIOLATION", 0x0051),
    ("RTSEXCPT_PRIV_INSTRUCTION", 0x0052),
    ("RTSEXCPT_IN_PAGE_ERROR", 0x0053),
    ("RTSEXCPT_STACK_OVERFLOW", 0x0054),
    ("RTSEXCPT_INVALID_DISPOSITION", 0x0055),
    ("RTSEXCPT_INVALID_HANDLE", 0x0056),
    ("RTSEXCPT_GUARD_PAGE", 0x0057),
    ("RTSEXCPT_DOUBLE_FAULT", 0x0058),
    ("RTSEXCPT_INVALID_OPCODE", 0x0059),
    ("RTSEXCPT_MISALIGNMENT", 0x0100),
    ("RTSEXCPT_ARRAYBOUNDS", 0x0101),
    ("RTSEXCPT_DIVIDEBYZERO", 0x0102),
    ("RTSEXCPT_OVERFLOW", 0x0103),
    ("RTSEXCPT_NONCONTINUABLE", 0x0104),
    ("RTSEXCPT_PROCESSORLOAD_WATCHDOG", 0x0105),
    ("RTSEXCPT_FPU_ERROR", 0x0150),
    ("RTSEXCPT_FPU_DENORMAL_OPERAND", 0x0151),
    ("RTSEXCPT_FPU_DIVIDEBYZERO", 0x0152),
    ("RTSEXCPT_FPU_INEXACT_RESULT", 0x0153),
    ("RTSEXCPT_FPU_INVALID_OPERATION", 0x0154),
    ("RTSEXCPT_FPU_OVERFLOW", 0x0155),
    ("RTSEXCPT_FPU_STACK_CHECK", 0x0156),
    ("RTSEXCPT_FPU_UNDERFLOW", 0x0157),
    ("RTSEXCPT_BREAKPOINT", 0x0200),
    ("RTSEXCPT_LICENSE_INVALID", 0x100D_0001),
];

/// The enumeration (interned), stored as UDINT.
fn exception_code_enum(types: &mut TypeTable) -> TypeId {
    types.intern(TypeDef {
        name: EXCEPTION_CODE.to_string(),
        kind: TypeKind::Enum {
            base: ElemType::Udint,
            values: VALUES.iter().map(|&(n, v)| (n.to_string(), v)).collect(),
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
