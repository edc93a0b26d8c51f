//! `--modbus ADDR:PORT`: a Modbus TCP server on the run's process image
//! (see docs/modbus.md). The server's threads serve the clients; the
//! runner exchanges the image with them between two ticks.

use super::args::RunArgs;
use plcrun::{ModbusConfig, ModbusExchange, ModbusServer, parse_time_literal};
use std::time::Duration;

/// Starts the server `--modbus` asks for (none without it) and says
/// where it listens on standard error (the port the system chose for
/// port 0 included).
pub(super) fn start(args: &RunArgs) -> Result<Option<(ModbusServer, ModbusExchange)>, String> {
    let Some(address) = &args.modbus else {
        return Ok(None);
    };
    let idle_timeout = match parse_time_literal(&args.modbus_idle_timeout) {
        Ok(ns) if ns > 0 => Duration::from_nanos(ns as u64),
        Ok(_) => return Err("--modbus-idle-timeout must be positive".into()),
        Err(e) => return Err(format!("--modbus-idle-timeout: {e}")),
    };
    let config = ModbusConfig {
        max_clients: usize::try_from(args.modbus_max_clients).unwrap_or(usize::MAX),
        idle_timeout,
        ..ModbusConfig::default()
    };
    let (server, exchange) = ModbusServer::bind(address, config).map_err(|e| e.to_string())?;
    sayln!("modbus: listening on {}", server.local_addr());
    Ok(Some((server, exchange)))
}
