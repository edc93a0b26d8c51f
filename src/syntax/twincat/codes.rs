//! The diagnostic codes of the TwinCAT 3 project reader (`E870`-`E874`,
//! `W870`-`W879`), documented in `docs/diagnostics.md`.

/// A TwinCAT file that is not well-formed XML.
pub const MALFORMED_XML: &str = "E870";
/// An object or body plcrun cannot run (an SFC, FBD, LD, CFC or UML body,
/// a visualisation...), refused by name.
pub const REFUSED: &str = "E871";
/// An element is missing what it must hold (a POU without `<Declaration>`,
/// a task without `<CycleTime>`...).
pub const MISSING: &str = "E872";
/// A task's cycle time or priority that is not a number in range.
pub const BAD_TASK_SETTING: &str = "E873";
/// A data type of a type description (`.tmc`, `.tsproj`) that is not a
/// structure, an enumeration or an alias, or whose name is not an
/// identifier: plcrun cannot declare it.
pub const UNDECLARABLE_TYPE: &str = "E874";
/// An element plcrun does not know, skipped.
pub const UNKNOWN_ELEMENT: &str = "W870";
