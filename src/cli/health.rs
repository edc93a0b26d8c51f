//! `plcrun health [ADDR]`: asks a running plcrun's web monitor whether its
//! PLC runs, for container health checks and monitoring scripts (the
//! Dockerfile's HEALTHCHECK). Exit status 0 when it runs, 1 when it is
//! faulted or cannot be asked, as Docker reads a health check's status.

use super::EXIT_USAGE;
use super::monitor_client::{host_port, monitor_get};
use clap::Args;
use std::time::Duration;

/// Options of `plcrun health`.
#[derive(Debug, Args)]
pub struct HealthArgs {
    /// The web monitor's address (`--web` of the run, `[web] listen` of a
    /// project file): HOST:PORT, a port alone, or an http:// URL.
    #[arg(default_value = "127.0.0.1:8080", value_name = "ADDR")]
    pub address: String,
    /// How long to wait for the answer.
    #[arg(long, default_value = "5s", value_name = "DURATION")]
    pub timeout: String,
}

/// Exit status: the PLC runs.
const HEALTHY: i32 = 0;
/// Exit status: faulted, or no answer (Docker's "unhealthy").
const UNHEALTHY: i32 = 1;

/// `plcrun health [ADDR] [--timeout D]`.
pub fn health(args: &HealthArgs) -> i32 {
    let timeout = match plcrun::parse_time_literal(&args.timeout) {
        Ok(ns) if ns > 0 => Duration::from_nanos(ns as u64),
        _ => {
            sayln!("error: --timeout must be a positive duration (`5s`)");
            return EXIT_USAGE;
        }
    };
    let host_port = host_port(&args.address);
    match monitor_get(&host_port, "/api/state", timeout) {
        Ok(state) => report(&state),
        Err(why) => {
            sayln!("unreachable: {host_port}: {why}");
            UNHEALTHY
        }
    }
}

/// Prints what `state` says; the exit status.
fn report(state: &serde_json::Value) -> i32 {
    let cycle = state["cycle"].as_u64().unwrap_or(0);
    match state["state"].as_str() {
        Some("running") => {
            println!("running: cycle {cycle}");
            HEALTHY
        }
        Some("faulted") => {
            let fault = &state["fault"];
            println!(
                "faulted: {} in cycle {}: {}",
                fault["code"].as_str().unwrap_or("?"),
                fault["cycle"].as_u64().unwrap_or(cycle),
                fault["message"].as_str().unwrap_or("")
            );
            UNHEALTHY
        }
        _ => {
            sayln!("unreachable: the answer has no state (is it plcrun's web monitor?)");
            UNHEALTHY
        }
    }
}
