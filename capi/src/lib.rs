//! The C ABI of plcrun: `libplcrun_capi.so` / `libplcrun_capi.a` with the
//! hand-written header `include/plcrun.h` (docs/embedding.md, "From C").
//!
//! Every entry point returns a status code (`PLC_OK` or a negative
//! `PLC_E_*`, see [`status`]), catches any panic (`PLC_E_PANIC`), refuses
//! NULL pointers (`PLC_E_NULL_ARGUMENT`) and checks every handle against a
//! table (`PLC_E_INVALID_HANDLE`) before using it. The message of the last
//! failure on a thread is `plc_last_error()`.
//!
//! The functions are also callable from Rust (the tests do), but a Rust
//! program should use the `plcrun` crate itself.

#![warn(missing_docs)]

mod addressing;
mod cycle;
mod failure;
mod forcing;
mod guard;
mod handles;
mod image;
mod image_tables;
mod lifecycle;
mod opcua;
mod realtime;
mod retain;
mod scalar;
mod slot_table;
pub mod status;
mod stop;
mod text;
mod vars;

pub use addressing::{
    PLC_ADDRESSING_BYTE, PLC_ADDRESSING_IEC, PLC_ADDRESSING_OPENPLC, plc_addressing,
    plc_set_addressing,
};
pub use cycle::{
    plc_cycle, plc_cycle_time_ns, plc_fault_message, plc_is_faulted, plc_reset_cold,
    plc_reset_warm, plc_run_cycle, plc_time_ns,
};
pub use forcing::{
    plc_force, plc_force_at, plc_force_count, plc_soft_write, plc_unforce, plc_unforce_all,
};
pub use guard::plc_last_error;
pub use handles::{PlcHandle, PlcVar};
pub use image::{
    PLC_AREA_INPUT, PLC_AREA_MEMORY, PLC_AREA_OUTPUT, plc_image_area_size, plc_image_read_area,
    plc_image_read_bit, plc_image_read_byte, plc_image_read_dword, plc_image_read_lword,
    plc_image_read_word, plc_image_write_area, plc_image_write_bit, plc_image_write_byte,
    plc_image_write_dword, plc_image_write_lword, plc_image_write_word,
};
pub use image_tables::{
    PLC_WIDTH_BIT, PLC_WIDTH_BYTE, PLC_WIDTH_DWORD, PLC_WIDTH_LWORD, PLC_WIDTH_WORD,
    plc_image_read_table, plc_image_table_size, plc_image_write_table,
};
pub use lifecycle::{
    PLC_ABI_VERSION, PlcOptions, PlcSource, plc_abi_version, plc_create, plc_free,
    plc_options_init, plc_version, plc_warnings,
};
pub use opcua::{
    PLC_OPCUA_ALLOW_INSECURE, PLC_OPCUA_TRUST_CLIENTS, plc_opcua_port, plc_opcua_start,
    plc_opcua_stop,
};
pub use retain::{plc_retain_restore, plc_retain_save};
pub use status::plc_status_text;
pub use stop::{PlcStop, plc_abort, plc_set_watchdog_ms, plc_stop_token, plc_stop_token_free};
pub use vars::{
    plc_get_bool, plc_get_f64, plc_get_i64, plc_get_literal, plc_resolve, plc_set_bool,
    plc_set_f64, plc_set_i64, plc_set_literal, plc_var_get_bool, plc_var_get_f64, plc_var_get_i64,
    plc_var_get_literal, plc_var_set_bool, plc_var_set_f64, plc_var_set_i64, plc_var_set_literal,
};
