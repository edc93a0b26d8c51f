//! Runtime: everything around the executor that talks to the outside world
//! while a program runs.
//!
//! - [`engine`]: the soft PLC — compile, run cycles, read and write variables;
//! - [`access`]: reading and writing variables by name or handle;
//! - [`plc_value`]: the values read and written;
//! - [`session`]: a run as the command line does it — stimulus, trace;
//! - [`scheduler`]: which program instances run at a tick, in which order;
//! - [`clock`]: where a cycle's `now` comes from (virtual, wall, caller's);
//! - [`tasks`]: listing tasks, one cycle of one task, timed ticks;
//! - [`task_stats`]: per-task cycles, execution time, jitter, overruns;
//! - [`realtime`]: running the tasks on the wall clock, on a thread;
//! - [`rt_thread`]: preparing that thread (priority, CPU, locked memory);
//! - [`live_stimulus`]: stimulus rows read while the program runs;
//! - [`default_trace`]: what is traced when the user names nothing;
//! - [`host_blocks`]: FUNCTIONs and FUNCTION_BLOCKs implemented by the host;
//! - [`ads_log`]: the messages of TwinCAT's ADS logger functions;
//! - [`names`]: variable paths from outside (`inst.Q`, `arr[2]`, `%IX0.1`);
//! - [`var_error`]: why such a path cannot be resolved, read or written;
//! - [`online_change`]: a new program version taking over a running PLC,
//!   with its [`change_report`];
//! - [`stop`]: asking a run to end from another thread;
//! - [`debugger`]: breakpoints, steps and stops for a debugger front end,
//!   with [`debug_lines`] (where statements start), [`debug_view`] (what a
//!   stopped PLC shows) and [`debug_eval`] (watch expressions);
//! - [`life_cycle`]: the faulted STOP state and the resets;
//! - [`fault_path`]: a fault's instance path and chain of callers;
//! - [`watchdog`]: per-task cycle-time limits and the thread enforcing them;
//! - [`retain`]: RETAIN and PERSISTENT values kept over a restart in a file;
//! - [`stimulus`]: reading stimulus CSV files and deciding which rows are due;
//! - [`process_image`]: the `%I`/`%Q`/`%M` byte tables exchanged with the
//!   located variables (addresses and conventions: `crate::address`;
//!   `addressing`: changing the convention of a compiled PLC);
//! - [`forcing`]: forced variables and soft writes;
//! - [`modbus`]: a Modbus TCP server on the process image;
//! - `opcua` (cargo feature `opcua`): an OPC UA server on the variables;
//! - [`variables`]: the list of variables with their types, and chart step
//!   states;
//! - [`trace`]: writing the per-cycle trace as a table, CSV or JSON lines;
//! - [`trace_vcd`]: the trace as a VCD waveform.

pub mod access;
mod addressing;
pub mod ads_log;
mod byte_view;
pub mod change_report;
pub mod clock;
mod copy_calls;
pub mod debug_eval;
pub mod debug_lines;
mod debug_sfc_xml;
pub mod debug_view;
pub mod debugger;
pub mod default_trace;
pub mod engine;
pub mod fault_path;
pub mod forcing;
pub mod host_blocks;
pub(crate) mod host_check;
pub mod life_cycle;
pub mod live_stimulus;
pub mod modbus;
pub mod names;
pub mod online_change;
#[cfg(feature = "opcua")]
pub mod opcua;
pub mod plc_value;
pub mod process_image;
pub mod realtime;
pub mod retain;
pub mod rt_thread;
mod s7_names;
pub mod scheduler;
pub mod session;
pub mod stimulus;
pub mod stop;
mod table_rows;
mod task_info;
pub mod task_stats;
pub mod tasks;
pub mod trace;
pub mod trace_vcd;
pub mod var_error;
pub mod variables;
pub mod watchdog;
