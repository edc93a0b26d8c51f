//! A Modbus TCP server on the process image, OpenPLC's way: coils are
//! `%QX`, discrete inputs `%IX`, input registers `%IW`, holding registers
//! `%QW` then `%MW`, `%MD`, `%ML`, numbered as the image's addressing
//! convention says (the table and every difference from OpenPLC are in
//! `docs/modbus.md`).
//!
//! - [`mapping`]: which image bytes each Modbus address is;
//! - [`server`]: the listening socket and its threads, [`ModbusServer`];
//! - [`connection`]: one client's frames, timeouts and limits;
//! - [`request`]: one request, decoded and answered with `rmodbus`;
//! - [`exchange`]: the scan side, [`ModbusExchange`], called between cycles;
//! - [`published`]: the last completed cycle's image as clients read it;
//! - [`stats`]: the server's counters;
//! - `priority`: the server's threads leave a real-time priority to the scan.
//!
//! Consistency: clients read the image published after the last completed
//! cycle; their writes wait in a bounded queue and are applied between two
//! cycles, never during one. The scan side only copies and `try_`-locks,
//! so no client can hold up a cycle.

pub mod connection;
pub mod exchange;
pub mod fuzzing;
pub mod mapping;
pub(crate) mod priority;
pub mod published;
pub mod request;
pub mod server;
pub mod stats;

pub use exchange::{ExchangeReport, ModbusExchange};
pub use mapping::{ImagePlace, ModbusTable, modbus_place};
pub use server::{ModbusConfig, ModbusError, ModbusServer};
pub use stats::ModbusStats;
