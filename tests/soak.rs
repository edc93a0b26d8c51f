//! Soak: a 1 ms task serves Modbus TCP and OPC UA while clients connect,
//! flood, drop mid-frame and reconnect, for `PLCRUN_SOAK_SECONDS` (8 s
//! by default; docs/robustness.md reports an hour). Checked: no write is
//! lost (every acknowledged Modbus write and OPC UA write is seen by the
//! program), the servers answer to the end, the scan keeps running, and
//! the resident memory stays flat. Its own test binary: it measures wall
//! time and memory of the whole process.

#[path = "support/opcua_client.rs"]
mod opcua_client;

use async_opcua::types::{NodeId, StatusCode, Variant};
use opcua_client::{Security, connect};
use plcrun::opcua::{OpcUaConfig, OpcUaServer, Users};
use plcrun::{
    ModbusConfig, ModbusServer, Options, Plc, Session, TaskRunner, TraceFormat, TraceWriter,
};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

const PROGRAM: &str = "
PROGRAM Soak
VAR
    w0 AT %MW0 : UINT; w1 AT %MW1 : UINT; w2 AT %MW2 : UINT; w3 AT %MW3 : UINT;
    e0 AT %QW0 : UINT; e1 AT %QW1 : UINT; e2 AT %QW2 : UINT; e3 AT %QW3 : UINT;
    beat AT %QW10 : UINT;
    setpoint1 : INT; doubled1 : INT;
    setpoint2 : INT; doubled2 : INT;
END_VAR
e0 := w0; e1 := w1; e2 := w2; e3 := w3;
beat := beat + 1;
doubled1 := setpoint1 * 2;
doubled2 := setpoint2 * 2;
END_PROGRAM
";

fn soak_time() -> Duration {
    let secs = std::env::var("PLCRUN_SOAK_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(8);
    Duration::from_secs(secs)
}

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        })
        .unwrap_or(0)
}

/// A Modbus request frame: transaction `t`, unit 1, PDU `pdu`.
fn frame(t: u16, pdu: &[u8]) -> Vec<u8> {
    let mut f = t.to_be_bytes().to_vec();
    f.extend([0, 0]);
    f.extend(((pdu.len() + 1) as u16).to_be_bytes());
    f.push(1);
    f.extend(pdu);
    f
}

/// Reads one answer frame.
fn answer(s: &mut TcpStream) -> std::io::Result<Vec<u8>> {
    let mut head = [0u8; 6];
    s.read_exact(&mut head)?;
    let len = usize::from(u16::from_be_bytes([head[4], head[5]]));
    let mut body = vec![0u8; len];
    s.read_exact(&mut body)?;
    let mut all = head.to_vec();
    all.extend(body);
    Ok(all)
}

fn connect_modbus(addr: SocketAddr) -> TcpStream {
    let s = TcpStream::connect(addr).expect("the Modbus server accepts");
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    s
}

fn read_register(s: &mut TcpStream, t: u16, register: u16) -> std::io::Result<u16> {
    let r = register.to_be_bytes();
    s.write_all(&frame(t, &[0x03, r[0], r[1], 0, 1]))?;
    let a = answer(s)?;
    assert_eq!(a[7], 0x03, "read answered with {a:?}");
    Ok(u16::from_be_bytes([a[9], a[10]]))
}

/// What one client did.
#[derive(Default)]
struct Tally {
    /// Writes confirmed (or requests answered).
    done: u64,
    /// Connections the server refused or broke, retried.
    retried: u64,
}

/// Sends `request` and reads its answer, on `stream` or, when the server
/// refuses or drops the connection (over `max_clients`, say), on a new one.
fn ask(addr: SocketAddr, stream: &mut TcpStream, request: &[u8], tally: &mut Tally) -> Vec<u8> {
    for _ in 0..1000 {
        if stream.write_all(request).is_ok()
            && let Ok(a) = answer(stream)
        {
            return a;
        }
        tally.retried += 1;
        std::thread::sleep(Duration::from_millis(5));
        *stream = connect_modbus(addr);
    }
    panic!("the Modbus server refused 1000 connections in a row");
}

/// Client `k`: writes 1, 2, 3... to holding register 1024 + k (`%MWk`) and
/// waits for the program's echo in register k (`%QWk`) after each, on a
/// new connection every 20 writes. A write the server acknowledged must
/// reach the program, whatever happens to the connection after.
fn writer(addr: SocketAddr, k: u16, until: Instant) -> Result<Tally, String> {
    let mut tally = Tally::default();
    let mut value: u16 = 0;
    while Instant::now() < until {
        let mut s = connect_modbus(addr);
        for _ in 0..20 {
            value = value.wrapping_add(1).max(1);
            let r = (1024 + k).to_be_bytes();
            let v = value.to_be_bytes();
            let a = ask(
                addr,
                &mut s,
                &frame(value, &[0x06, r[0], r[1], v[0], v[1]]),
                &mut tally,
            );
            if a[7] != 0x06 {
                return Err(format!("write {value} refused: {a:?}"));
            }
            let seen_by = Instant::now() + Duration::from_secs(10);
            let r = k.to_be_bytes();
            loop {
                let a = ask(
                    addr,
                    &mut s,
                    &frame(value, &[0x03, r[0], r[1], 0, 1]),
                    &mut tally,
                );
                let echo = u16::from_be_bytes([a[9], a[10]]);
                if echo == value {
                    break;
                }
                if Instant::now() > seen_by {
                    return Err(format!("write {value} acknowledged and lost (echo {echo})"));
                }
                std::thread::sleep(Duration::from_millis(1));
            }
            tally.done += 1;
        }
    }
    Ok(tally)
}

/// Sends 100 reads without waiting, then takes the 100 answers, which
/// must come in order (a burst on a refused connection is sent again).
fn flooder(addr: SocketAddr, until: Instant) -> Result<Tally, String> {
    let mut tally = Tally::default();
    let burst: Vec<u8> = (0..100u16)
        .flat_map(|t| frame(t, &[0x03, 0, 0, 0, 16]))
        .collect();
    while Instant::now() < until {
        let mut s = connect_modbus(addr);
        if s.write_all(&burst).is_err() {
            tally.retried += 1;
            continue;
        }
        for t in 0..100u16 {
            match answer(&mut s) {
                Ok(a) if u16::from_be_bytes([a[0], a[1]]) == t => tally.done += 1,
                Ok(a) => return Err(format!("answer {t} out of order: {a:?}")),
                // Refused at once (no answer at all): try again.
                Err(_) if t == 0 => {
                    tally.retried += 1;
                    break;
                }
                Err(e) => return Err(format!("the server dropped a flood at answer {t}: {e}")),
            }
        }
    }
    Ok(tally)
}

/// Connections that break the protocol: half a frame then gone, a header
/// that cannot be Modbus, a connection closed at once.
fn dropper(addr: SocketAddr, until: Instant) -> Result<Tally, String> {
    let mut tally = Tally::default();
    while Instant::now() < until {
        let whole = frame(7, &[0x10, 0, 0, 0, 2, 4, 0, 1, 0, 2]);
        let mut s = connect_modbus(addr);
        let _ = s.write_all(&whole[..whole.len() / 2]);
        drop(s);
        let mut s = connect_modbus(addr);
        let _ = s.write_all(&[0, 1, 0xDE, 0xAD, 0, 6, 1, 3, 0, 0, 0, 1]);
        let mut sink = [0u8; 16];
        let _ = s.read(&mut sink);
        drop(TcpStream::connect(addr));
        tally.done += 3;
        std::thread::sleep(Duration::from_millis(2));
    }
    Ok(tally)
}

/// OPC UA client `n` (1 or 2): logs in, writes `setpoint<n>`, waits for
/// the program's `doubled<n>`, and reconnects every 10 writes. A write
/// answered Good must reach the program. Connections that fail are
/// retried; more than one in five failing is an error.
fn opcua_writer(
    url: String,
    ns: u16,
    pki: std::path::PathBuf,
    n: i16,
    until: Instant,
) -> Result<Tally, String> {
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async move {
        let mut tally = Tally::default();
        let mut attempts = 0u64;
        let mut value = 0i16;
        let (setpoint, doubled) = (format!("setpoint{n}"), format!("doubled{n}"));
        while Instant::now() < until {
            attempts += 1;
            let c = match connect(&url, Security::Encrypt, Some(("op", "pw")), &pki).await {
                Ok(c) => c,
                Err(e) => {
                    tally.retried += 1;
                    if tally.retried * 5 > attempts.max(5) {
                        return Err(format!(
                            "{} of {attempts} connections failed: {e}",
                            tally.retried
                        ));
                    }
                    continue;
                }
            };
            for _ in 0..10 {
                value = (value + 1) % 10_000;
                let status = c
                    .write(&NodeId::new(ns, setpoint.as_str()), Variant::Int16(value))
                    .await;
                if status != StatusCode::Good {
                    return Err(format!("OPC UA write {value}: {status}"));
                }
                let want = Variant::Int16(value * 2);
                let got = c
                    .read_until(
                        &NodeId::new(ns, doubled.as_str()),
                        Duration::from_secs(10),
                        |v| *v == want,
                    )
                    .await;
                if got != Some(want.clone()) {
                    return Err(format!(
                        "OPC UA write {value} answered Good and lost: read {got:?}"
                    ));
                }
                tally.done += 1;
            }
            c.close().await;
        }
        Ok(tally)
    })
}

#[test]
fn servers_survive_floods_drops_and_reconnects_under_a_1ms_task() {
    let dir = std::env::temp_dir().join(format!("plcrun-soak-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let users = dir.join("users");
    Users::add_to_file(&users, "op", "pw").unwrap();
    let options = Options {
        cycle_time: 1_000_000,
        ..Options::default()
    };
    let plc = Plc::compile_files(&[("soak.st", PROGRAM)], &options).unwrap();
    let stop = plc.stop_handle();
    let (modbus, mut modbus_exchange) =
        ModbusServer::bind("127.0.0.1:0", ModbusConfig::default()).unwrap();
    let config = OpcUaConfig {
        users: Users::load(&users).unwrap(),
        pki_dir: dir.join("server-pki"),
        trust_client_certs: true,
        ..OpcUaConfig::default()
    };
    let (opcua, mut opcua_exchange) = OpcUaServer::bind("127.0.0.1:0", &plc, config).unwrap();
    let mut session = Session::new(plc);
    modbus_exchange.exchange(session.plc_mut());
    opcua_exchange.exchange(session.plc_mut());
    let mut runner = TaskRunner::real_time(session.plc());
    let stats = runner.stats();
    let mut modbus_hook = modbus_exchange.into_between_ticks();
    let mut opcua_hook = opcua_exchange.into_between_ticks();
    runner.set_between_ticks(move |s: &mut Session| {
        modbus_hook(s);
        opcua_hook(s);
    });
    let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    let run = runner.spawn(session, None, trace);

    let started = Instant::now();
    let until = started + soak_time();
    let addr = modbus.local_addr();
    let url = opcua.endpoint_url();
    let ns = opcua.namespace_index();
    let rss_samples = Arc::new(Mutex::new(Vec::new()));
    let sampler = {
        let samples = Arc::clone(&rss_samples);
        std::thread::spawn(move || {
            while Instant::now() < until {
                samples.lock().unwrap().push((started.elapsed(), rss_kib()));
                std::thread::sleep(Duration::from_millis(500));
            }
        })
    };
    let done = Arc::new(AtomicU64::new(0));
    let mut clients: Vec<(String, std::thread::JoinHandle<Result<Tally, String>>)> = Vec::new();
    for k in 0..4 {
        clients.push((
            format!("modbus writer {k}"),
            std::thread::spawn(move || writer(addr, k, until)),
        ));
    }
    for k in 0..2 {
        clients.push((
            format!("modbus flooder {k}"),
            std::thread::spawn(move || flooder(addr, until)),
        ));
        clients.push((
            format!("modbus dropper {k}"),
            std::thread::spawn(move || dropper(addr, until)),
        ));
    }
    for k in 0..2i16 {
        let (url, pki) = (url.clone(), dir.join(format!("client-{k}")));
        clients.push((
            format!("opcua writer {k}"),
            std::thread::spawn(move || opcua_writer(url, ns, pki, k + 1, until)),
        ));
    }
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for (name, client) in clients {
        match client.join() {
            Ok(Ok(t)) => {
                done.fetch_add(t.done, Ordering::Relaxed);
                report.push(format!("{name}: {} ({} retried)", t.done, t.retried));
                if t.done == 0 {
                    failures.push(format!("{name} did nothing"));
                }
            }
            Ok(Err(e)) => failures.push(format!("{name}: {e}")),
            Err(_) => failures.push(format!("{name} panicked")),
        }
    }
    sampler.join().unwrap();
    // The servers still answer after it all.
    let mut s = connect_modbus(addr);
    let beat_before = read_register(&mut s, 1, 10).expect("Modbus still answers");
    std::thread::sleep(Duration::from_millis(50));
    let beat_after = read_register(&mut s, 2, 10).expect("Modbus still answers");
    assert_ne!(beat_before, beat_after, "the scan stopped");
    let elapsed = started.elapsed();
    stop.stop();
    let outcome = run.join();
    outcome.result.expect("the scan ended without a fault");
    let task = &stats.snapshot()[0];
    let expected = elapsed.as_millis() as u64;
    let m = modbus.stats();
    let samples = rss_samples.lock().unwrap().clone();
    let third = samples.len() / 3;
    let (early, late) = (samples[third].1, samples.last().unwrap().1);
    eprintln!(
        "soak {:.0} s: {} | cycles {} of {} expected, overruns {}, exec max {} us, start jitter p99 {} us max {} us | modbus: {} accepted, {} refused, {} requests, {} exceptions, {} dropped malformed, {} timed out, {} writes applied | RSS {} -> {} KiB",
        elapsed.as_secs_f64(),
        report.join(", "),
        task.cycles,
        expected,
        task.overruns,
        task.execution.map_or(0, |e| e.max_ns / 1000),
        task.start_jitter.map_or(0, |j| j.p99_ns / 1000),
        task.start_jitter.map_or(0, |j| j.max_ns / 1000),
        m.connections_accepted,
        m.connections_refused,
        m.requests,
        m.exceptions,
        m.connections_dropped_malformed,
        m.connections_timed_out,
        m.writes_applied,
        early,
        late
    );
    assert!(failures.is_empty(), "{failures:#?}");
    // The scan ran (a loaded CI machine may skip ticks, each counted as
    // an overrun; a stall would leave far fewer cycles).
    assert!(
        task.cycles + task.overruns >= expected / 2,
        "the scan stalled"
    );
    // Flat memory: from the first third of the run to its end, less than
    // 16 MiB and 25 % of growth.
    assert!(
        late <= early + (16 << 10) && late * 4 <= early * 5 + (4 << 10),
        "resident memory grew from {early} to {late} KiB"
    );
    drop(opcua);
    modbus.shutdown();
    let _ = std::fs::remove_dir_all(&dir);
}
