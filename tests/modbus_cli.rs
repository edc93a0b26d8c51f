//! `plcrun --modbus`: the CHARIOT example served in real time and driven
//! by a Modbus client; virtual-time runs unchanged without client writes;
//! bad flags are usage errors.

use crate::support::cli;

use rmodbus::client::ModbusRequest;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn plcrun() -> Command {
    Command::new(env!("CARGO_BIN_EXE_plcrun"))
}

const CHART: &str = "programs/chariot.sfc";
const WIRING: &str = "examples/modbus/chariot_modbus.st";

/// Sends one request built by `build`, returns the response frame.
fn call(
    stream: &mut TcpStream,
    build: impl FnOnce(&mut ModbusRequest, &mut Vec<u8>),
) -> (ModbusRequest, Vec<u8>) {
    let mut req = ModbusRequest::new_tcp_udp(1, 7);
    let mut frame = Vec::new();
    build(&mut req, &mut frame);
    stream.write_all(&frame).unwrap();
    let mut resp = vec![0u8; 6];
    stream.read_exact(&mut resp).unwrap();
    let len = usize::from(u16::from_be_bytes([resp[4], resp[5]]));
    resp.resize(6 + len, 0);
    stream.read_exact(&mut resp[6..]).unwrap();
    (req, resp)
}

fn coils(stream: &mut TcpStream, start: u16, count: u16) -> Vec<bool> {
    let (req, resp) = call(stream, |r, f| {
        r.generate_get_coils(start, count, f).unwrap();
    });
    let mut out = Vec::new();
    req.parse_bool(&resp, &mut out).unwrap();
    out
}

fn set_coils(stream: &mut TcpStream, start: u16, values: &[u8]) {
    let (req, resp) = call(stream, |r, f| {
        r.generate_set_coils_bulk(start, values, f).unwrap();
    });
    req.parse_ok(&resp).unwrap();
}

#[test]
fn chariot_served_in_real_time_is_driven_by_a_client() {
    let mut child = plcrun()
        .args([CHART, WIRING, "--realtime", "--modbus", "127.0.0.1:0"])
        .args(["--trace", "kmav,kmar,vom", "--changes-only"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("plcrun starts");
    let addr = cli::modbus_address(&mut child);
    let mut s = TcpStream::connect(&addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    // The cart at A, the operator presses start: forward.
    set_coils(&mut s, 0, &[1, 1, 0]);
    let until = Instant::now() + Duration::from_secs(10);
    let mut seen = Vec::new();
    while Instant::now() < until {
        seen = coils(&mut s, 8, 3);
        if seen[0] {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    // KMAV on, KMAR off, VOM (FcA) on.
    assert_eq!(seen, [true, false, true], "KMAV never came on");
    // Arrived at B: forward off.
    set_coils(&mut s, 0, &[0, 0, 1]);
    let until = Instant::now() + Duration::from_secs(10);
    while Instant::now() < until && coils(&mut s, 8, 1) != [false] {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert_eq!(coils(&mut s, 8, 3), [false, false, false]);
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{:?}", out.status);
    let trace = String::from_utf8(out.stdout).unwrap();
    assert!(
        trace.lines().any(|l| l.ends_with(",TRUE,FALSE,TRUE")),
        "{trace}"
    );
    assert!(
        trace.lines().any(|l| l.ends_with(",FALSE,FALSE,FALSE")),
        "{trace}"
    );
}

#[test]
fn a_virtual_time_run_with_an_idle_server_traces_as_without() {
    let run = |extra: &[&str]| {
        let out = plcrun()
            .args(["programs/alg01.il", "--cycles", "50", "--stimulus"])
            .arg("programs/alg01_s1.csv")
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        )
    };
    let (plain, _) = run(&[]);
    let (served, err) = run(&["--modbus", "127.0.0.1:0"]);
    assert_eq!(plain, served);
    assert!(err.starts_with("modbus: listening on 127.0.0.1:"), "{err}");
}

#[test]
fn bad_modbus_flags_are_usage_errors() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["--modbus", "no-port-here"],
            "cannot listen on `no-port-here`",
        ),
        (
            &["--modbus", "127.0.0.1:0", "--modbus-idle-timeout", "0s"],
            "--modbus-idle-timeout must be positive",
        ),
        (
            &["--modbus", "127.0.0.1:0", "--modbus-idle-timeout", "soon"],
            "--modbus-idle-timeout",
        ),
        (
            &["--modbus", "127.0.0.1:0", "--modbus-max-clients", "0"],
            "0",
        ),
        (&["--modbus-max-clients", "3"], "--modbus"),
        (
            &["--modbus", "127.0.0.1:0", "--online-change-at", "3:x.st"],
            "--online-change-at cannot be combined with --modbus",
        ),
    ];
    for (flags, message) in cases {
        let out = plcrun()
            .args(["programs/alg01.il", "--cycles", "3"])
            .args(*flags)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{flags:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{flags:?}: {err}");
    }
}
