//! Runtime: everything around the executor that talks to the outside world
//! while a program runs.
//!
//! - [`format`](mod@format): values as IEC literal text (and JSON) for traces and messages;
//! - [`stimulus`]: reading stimulus CSV files and deciding which rows are due;
//! - [`trace`]: writing the per-cycle trace as a table, CSV or JSON lines.

pub mod engine;
pub mod format;
pub mod names;
pub mod stimulus;
pub mod trace;
