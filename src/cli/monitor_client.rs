//! A client of a running plcrun's web monitor (docs/web.md): one JSON
//! `GET` at a time, for `plcrun health` and the editor's live values.

use std::io::{Read, Write};
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

/// `http://host:port/...`, `host:port` or `port` as `host:port`.
pub fn host_port(address: &str) -> String {
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

/// The JSON body of `GET path` from the web monitor at `host_port`.
pub fn monitor_get(
    host_port: &str,
    path: &str,
    timeout: Duration,
) -> Result<serde_json::Value, String> {
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
    let request = format!("GET {path} HTTP/1.1\r\nHost: {host_port}\r\nConnection: close\r\n\r\n");
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
