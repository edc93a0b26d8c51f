//! Runtime: everything around the executor that talks to the outside world
//! while a program runs.
//!
//! - [`engine`]: the soft PLC — compile, run cycles, read and write variables;
//! - [`access`]: reading and writing variables by name or handle;
//! - [`plc_value`]: the values read and written;
//! - [`session`]: a run as the command line does it — stimulus, trace;
//! - [`scheduler`]: which program instances run at a tick, in which order;
//! - [`default_trace`]: what is traced when the user names nothing;
//! - [`host_blocks`]: FUNCTIONs and FUNCTION_BLOCKs implemented by the host;
//! - [`names`]: variable paths from outside (`inst.Q`, `arr[2]`, `%IX0.1`);
//! - [`var_error`]: why such a path cannot be resolved, read or written;
//! - [`online_change`]: a new program version taking over a running PLC,
//!   with its [`change_report`];
//! - [`stop`]: asking a run to end from another thread;
//! - [`stimulus`]: reading stimulus CSV files and deciding which rows are due;
//! - [`trace`]: writing the per-cycle trace as a table, CSV or JSON lines.

pub mod access;
pub mod change_report;
pub mod default_trace;
pub mod engine;
pub mod host_blocks;
pub mod names;
pub mod online_change;
pub mod plc_value;
pub mod scheduler;
pub mod session;
pub mod stimulus;
pub mod stop;
pub mod trace;
pub mod var_error;
