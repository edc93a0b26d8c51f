//! An OpenPLC-style program (coils at `%QX0.0`, registers at `%QW0`,
//! `%QW1`, `%MW0`, `%MD0`) served by `plcrun --addressing openplc
//! --modbus` in real time: a Modbus TCP client written here from the
//! protocol's frames (MBAP header, function codes 1, 3, 4, 6), independent
//! of the server's own Modbus library, reads back what OpenPLC's table
//! gives: coil n is `%QX(n/8).(n%8)`, holding register n is `%QWn`,
//! 1024 + n is `%MWn`, 2048 + 2k and 2049 + 2k are `%MDk` (most
//! significant word first), input register n is `%IWn`. Also: the same
//! program checked without the flag gets W204, with it none.

use crate::support::cli;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const TANK: &str = "tests/addressing/openplc_tank.st";

fn plcrun() -> Command {
    Command::new(env!("CARGO_BIN_EXE_plcrun"))
}

/// A Modbus TCP client over a plain socket.
struct Client {
    stream: TcpStream,
    transaction: u16,
}

impl Client {
    /// Sends the PDU `pdu` to unit 1, returns the response PDU (function
    /// code first); an exception response is an `Err` with its code.
    fn call(&mut self, pdu: &[u8]) -> Result<Vec<u8>, u8> {
        self.transaction = self.transaction.wrapping_add(1);
        let mut frame = Vec::with_capacity(7 + pdu.len());
        frame.extend_from_slice(&self.transaction.to_be_bytes());
        frame.extend_from_slice(&0u16.to_be_bytes()); // protocol: Modbus
        frame.extend_from_slice(&(pdu.len() as u16 + 1).to_be_bytes());
        frame.push(1); // unit
        frame.extend_from_slice(pdu);
        self.stream.write_all(&frame).unwrap();
        let mut header = [0u8; 7];
        self.stream.read_exact(&mut header).unwrap();
        assert_eq!(&header[..2], &self.transaction.to_be_bytes());
        assert_eq!(&header[2..4], &[0, 0]);
        let len = usize::from(u16::from_be_bytes([header[4], header[5]]));
        let mut body = vec![0u8; len - 1];
        self.stream.read_exact(&mut body).unwrap();
        if body[0] & 0x80 != 0 {
            return Err(body[1]);
        }
        assert_eq!(body[0], pdu[0]);
        Ok(body)
    }

    /// FC 1 (coils) or 2 (discrete inputs): `count` bits from `start`.
    fn bits(&mut self, function: u8, start: u16, count: u16) -> Vec<bool> {
        let mut pdu = vec![function];
        pdu.extend_from_slice(&start.to_be_bytes());
        pdu.extend_from_slice(&count.to_be_bytes());
        let body = self.call(&pdu).expect("a bit read");
        assert_eq!(usize::from(body[1]), usize::from(count).div_ceil(8));
        (0..usize::from(count))
            .map(|i| body[2 + i / 8] >> (i % 8) & 1 == 1)
            .collect()
    }

    /// FC 3 (holding) or 4 (input registers): `count` registers.
    fn registers(&mut self, function: u8, start: u16, count: u16) -> Vec<u16> {
        let mut pdu = vec![function];
        pdu.extend_from_slice(&start.to_be_bytes());
        pdu.extend_from_slice(&count.to_be_bytes());
        let body = self.call(&pdu).expect("a register read");
        assert_eq!(usize::from(body[1]), 2 * usize::from(count));
        body[2..]
            .chunks(2)
            .map(|w| u16::from_be_bytes([w[0], w[1]]))
            .collect()
    }

    /// FC 6: one holding register.
    fn write_register(&mut self, n: u16, value: u16) {
        let mut pdu = vec![6];
        pdu.extend_from_slice(&n.to_be_bytes());
        pdu.extend_from_slice(&value.to_be_bytes());
        assert_eq!(self.call(&pdu), Ok(pdu.clone()), "the echo of FC 6");
    }
}

/// Starts the served run; returns the child and a connected client.
fn serve(extra: &[&str]) -> (Child, Client) {
    let mut child = plcrun()
        .args([
            TANK,
            "--realtime",
            "--modbus",
            "127.0.0.1:0",
            "--cycle-time",
            "10ms",
        ])
        .args(extra)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("plcrun starts");
    let addr = cli::modbus_address(&mut child);
    let stream = TcpStream::connect(&addr).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    (
        child,
        Client {
            stream,
            transaction: 0,
        },
    )
}

fn stop(child: Child) {
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{:?}", out.status);
}

#[test]
fn an_openplc_program_reads_back_over_modbus_as_on_openplc() {
    let (child, mut c) = serve(&["--addressing", "openplc"]);
    // The HMI writes the setpoint, %MW0, holding register 1024.
    c.write_register(1024, 7);
    let until = Instant::now() + Duration::from_secs(10);
    while Instant::now() < until && c.registers(3, 1, 1) != [8] {
        std::thread::sleep(Duration::from_millis(20));
    }
    // Coils 0..8: pump (%QX0.0) on, valve (%QX0.1) off, alarm (%QX1.0),
    // coil 8, on; nothing else.
    let coils = c.bits(1, 0, 10);
    assert_eq!(
        coils,
        [
            true, false, false, false, false, false, false, false, true, false
        ]
    );
    // Holding registers 0, 1, 2: level, echo = setpoint + 1, doubled.
    assert_eq!(c.registers(3, 0, 3), [0xABCD, 8, 0]);
    // 1024: the setpoint as written; 2048-2049: total = 700 000, most
    // significant word first.
    assert_eq!(c.registers(3, 1024, 1), [7]);
    assert_eq!(c.registers(3, 2048, 2), [0x000A, 0xAE60]);
    // Input register 0 is %IW0 (raw), not written by anyone.
    assert_eq!(c.registers(4, 0, 1), [0]);
    // An address past the table is exception 02, as on OpenPLC.
    assert_eq!(c.call(&[3, 0x20, 0x00, 0, 1]), Err(2));
    stop(child);
}

#[test]
fn the_same_program_warns_of_overlaps_unless_run_as_openplc() {
    let check = |extra: &[&str]| {
        let out = plcrun()
            .arg("check")
            .arg(TANK)
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        String::from_utf8(out.stderr).unwrap()
    };
    let plain = check(&[]);
    assert_eq!(plain.matches("warning[W204]").count(), 2, "{plain}");
    assert!(plain.contains("openplc_tank.st:17:14"), "{plain}");
    assert!(plain.contains("--addressing openplc"), "{plain}");
    let open = check(&["--addressing", "openplc"]);
    assert!(!open.contains("W204"), "{open}");
    let byte = check(&["--addressing", "byte"]);
    assert_eq!(byte.matches("warning[W204]").count(), 4, "{byte}");
    let bad = plcrun()
        .args(["check", TANK, "--addressing", "codesys"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let err = String::from_utf8(bad.stderr).unwrap();
    assert!(
        err.contains("unknown addressing `codesys` (expected iec, openplc or byte)"),
        "{err}"
    );
}
