//! An OPC UA server on a PLC's variables (docs/opcua.md), on the
//! `async-opcua` crate (ADR 0007), behind the `opcua` cargo feature.
//!
//! - [`model`]: the address space worked out from the variables;
//! - [`types`]: IEC types as OPC UA built-in types, both ways;
//! - [`glob`]: `--opcua-expose` patterns;
//! - [`server`]: settings, start and stop, [`OpcUaServer`];
//! - [`node_manager`]: the PLC's namespace, and Write;
//! - [`exchange`]: the scan side, [`OpcUaExchange`], called between cycles;
//! - [`published`]: the last completed cycle's values as the server reads them;
//! - [`pump`]: the server's side, which sets changed values and so
//!   notifies subscriptions;
//! - [`auth`], [`users`]: who may write, and the users file;
//! - [`stats`]: the server's counters.
//!
//! Consistency is the Modbus server's: clients read the values published
//! after the last completed cycle; their writes wait in a bounded queue
//! and are applied between two cycles; the scan side only copies,
//! `try_`-locks and wakes, so no client can hold up a cycle.

mod auth;
pub mod exchange;
pub mod fuzzing;
pub mod glob;
pub(crate) mod model;
pub mod node_manager;
pub(crate) mod published;
mod pump;
pub mod server;
pub mod stats;
pub(crate) mod types;
pub mod users;

pub use exchange::{OpcUaExchange, OpcUaExchangeReport};
pub use glob::Globs;
pub use node_manager::PLCRUN_NAMESPACE;
pub use server::{OpcUaConfig, OpcUaError, OpcUaServer};
pub use stats::OpcUaStats;
pub use users::{Users, UsersError};
