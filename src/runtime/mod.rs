//! Runtime: everything around the executor that talks to the outside world
//! while a program runs.
//!
//! - [`engine`]: the soft PLC — compile, run cycles, read and write variables;
//! - [`access`]: reading and writing variables by name or handle;
//! - [`plc_value`]: the values read and written;
//! - [`session`]: a run as the command line does it — stimulus, trace;
//! - [`scheduler`]: which program instances run at a tick, in which order;
//! - [`default_trace`]: what is traced when the user names nothing;
//! - [`names`]: variable paths from outside (`inst.Q`, `arr[2]`, `%IX0.1`);
//! - [`var_error`]: why such a path cannot be resolved, read or written;
//! - [`stop`]: asking a run to end from another thread;
//! - [`retain`]: RETAIN and PERSISTENT values kept over a restart in a file;
//! - [`stimulus`]: reading stimulus CSV files and deciding which rows are due;
//! - [`trace`]: writing the per-cycle trace as a table, CSV or JSON lines.

pub mod access;
pub mod default_trace;
pub mod engine;
pub mod names;
pub mod plc_value;
pub mod retain;
pub mod scheduler;
pub mod session;
pub mod stimulus;
pub mod stop;
pub mod trace;
pub mod var_error;
