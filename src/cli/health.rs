//! `plcrun health [ADDR]`: asks a running plcrun's web monitor whether its
//! PLC runs, for container health checks and monitoring scripts (the
//! Dockerfile's HEALTHCHECK). Exit status 0 when it runs, 1 when it is
//! faulted or cannot be asked, as Docker reads a health check's status.

use super::EXIT_USAGE;
use clap::Args;
use std::io::{Read, Write};
use std::net::{TcpStream, ToSocketAddrs};
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
    match ask_state(&host_port, timeout) {
        Ok(state) => report(&state),
        Err(why) => {
            sayln!("unreachable: {host_port}: {why}");
            UNHEALTHY
        }
    }
}

/// `http://host:port/...`, `host:port` or `port` as `host:port`.
fn host_port(address: &str) -> String {
    let rest = address
        .strip_prefix("http://")
        .unwrap_or(address)
        .trim_end_matches('/');
    let rest = rest.split('/').next().unwrap_or(rest);
    if rest.chars().all(|c| c.is_ascii_digit()) {
        format!("127.0.0.1:{rest}")
    } else {
        rest.to_string()
    }
}

/// The JSON body of `GET /api/state`.
fn ask_state(host_port: &str, timeout: Duration) -> Result<serde_json::Value, String> {
    let address = host_port
        .to_socket_addrs()
        .map_err(|e| e.to_string())?
        .next()
        .ok_or("the address names no host")?;
    let mut stream = TcpStream::connect_timeout(&address, timeout).map_err(|e| e.to_string())?;
    stream
        .set_read_timeout(Some(timeout))
        .and_then(|()| stream.set_write_timeout(Some(timeout)))
        .map_err(|e| e.to_string())?;
    let request =
        format!("GET /api/state HTTP/1.1\r\nHost: {host_port}\r\nConnection: close\r\n\r\n");
    stream
        .write_all(request.as_bytes())
        .map_err(|e| e.to_string())?;
    let mut answer = Vec::new();
    stream
        .take(1 << 20)
        .read_to_end(&mut answer)
        .map_err(|e| e.to_string())?;
    let answer = String::from_utf8_lossy(&answer);
    let (head, body) = answer
        .split_once("\r\n\r\n")
        .ok_or("the answer is not HTTP")?;
    let status = head.split_whitespace().nth(1).unwrap_or("");
    if status != "200" {
        return Err(format!(
            "HTTP status {status} (is it plcrun's web monitor?)"
        ));
    }
    serde_json::from_str(body).map_err(|e| format!("the answer is not the monitor's JSON: {e}"))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_are_read_in_every_spelling() {
        assert_eq!(host_port("8080"), "127.0.0.1:8080");
        assert_eq!(host_port("10.0.0.2:8081"), "10.0.0.2:8081");
        assert_eq!(host_port("http://plc.local:8080/"), "plc.local:8080");
        assert_eq!(host_port("http://127.0.0.1:9/api/state"), "127.0.0.1:9");
    }
}
