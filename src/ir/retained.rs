//! The table of retained variables a compiled image carries: every single
//! value that a RETAIN or PERSISTENT declaration keeps over a restart,
//! named by its path from outside, with its type and where it lives.

use crate::ir::type_table::TypeId;

/// Where a retained value lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RetainedStorage {
    /// The value is the slot at this absolute address.
    Slot(u32),
    /// A STRING or WSTRING: the string with this id (the id the slot at
    /// `slot` holds; strings are never moved).
    Text {
        /// Absolute address of the slot holding the string id.
        slot: u32,
        /// The string id.
        string: u32,
    },
}

/// One retained single value.
#[derive(Debug, Clone, PartialEq)]
pub struct RetainedVar {
    /// The path from outside, as the names layer spells it: `P.counter`,
    /// `P.inst.t1.ET`, `g_total`, `P.arr[3]`, `P.grid[1,2]` (program
    /// variables are qualified by the program instance's name).
    pub path: String,
    /// The value's type: elementary, string, enumeration or subrange.
    pub ty: TypeId,
    /// Where it lives.
    pub storage: RetainedStorage,
    /// Declared PERSISTENT (or inside a PERSISTENT instance).
    pub persistent: bool,
    /// A timer's start instant (TON/TOF/TP): saved relative to the clock
    /// of the snapshot, so that a restored timer goes on from the elapsed
    /// time it had instead of waiting for the old clock value.
    pub clock_instant: bool,
}
