//! Modbus TCP under load next to a 10 ms task: requests per second served
//! on 127.0.0.1, and the task's start jitter (the `--stats` figures) with
//! and without the server.
//!
//! `cargo run --release --example modbus_load -- [--seconds S] [--clients N]`
//!
//! Two phases of S seconds (default 10) each, on the wall clock:
//! 1. the 10 ms task alone (no server);
//! 2. the same task with a Modbus server exchanging between ticks and N
//!    client threads (default 4) each sending requests back to back over
//!    its own connection: read 10 holding registers (FC 3), read 16 coils
//!    (FC 1), write one holding register (FC 6), in turn.
//!
//! Prints the statistics table of each phase and the requests per second.
//! Under `chrt -f 50` the scan runs at the real-time priority and the
//! server's and the load's threads at the normal one.

use plcrun::{
    ModbusConfig, ModbusServer, Options, Plc, Session, TaskRunner, TaskStats, TraceFormat,
    TraceWriter, format_stats_table,
};
use rmodbus::ErrorKind;
use rmodbus::client::ModbusRequest;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The program: a little work every 10 ms, with located variables the
/// clients read and write.
const SOURCE: &str = "
PROGRAM Work
VAR
    n AT %QD0 : DINT;
    q AT %QX4.0 : BOOL;
    setpoint AT %MW0 : INT;
    echo AT %MW1 : INT;
    t : TON; i : INT; acc : DINT;
END_VAR
n := n + 1;
t(IN := NOT t.Q, PT := T#100ms);
q := t.Q;
FOR i := 1 TO 20 DO acc := acc + i * n; END_FOR;
echo := setpoint;
END_PROGRAM
CONFIGURATION Load RESOURCE R ON PLC
    TASK ms10 (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM main WITH ms10 : Work;
END_RESOURCE END_CONFIGURATION
";

struct Args {
    seconds: f64,
    clients: usize,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        seconds: 10.0,
        clients: 4,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--seconds" => {
                args.seconds = value()?.parse().map_err(|e| format!("--seconds: {e}"))?;
            }
            "--clients" => {
                args.clients = value()?.parse().map_err(|e| format!("--clients: {e}"))?;
            }
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    Ok(args)
}

/// What one phase measured.
struct Phase {
    stats: Vec<TaskStats>,
    /// Responses received (busy ones included).
    served: u64,
    /// Exception 06 responses among them.
    busy: u64,
}

/// Runs the task for `seconds` on the wall clock, with a server and
/// `clients` load threads when `clients > 0`; returns the task's
/// statistics and the requests served.
fn phase(seconds: f64, clients: usize) -> Result<Phase, Box<dyn std::error::Error>> {
    let plc = Plc::compile_files(&[("load.st", SOURCE)], &Options::default())?;
    let stop = plc.stop_handle();
    let mut session = Session::new(plc);
    let mut runner = TaskRunner::real_time(session.plc());
    let stats = runner.stats();
    let server = if clients > 0 {
        let (server, mut exchange) = ModbusServer::bind("127.0.0.1:0", ModbusConfig::default())?;
        exchange.exchange(session.plc_mut());
        runner.set_between_ticks(exchange.into_between_ticks());
        Some(server)
    } else {
        None
    };
    let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    let run = runner.spawn(session, None, trace);
    let done = Arc::new(AtomicBool::new(false));
    let served = Arc::new(AtomicU64::new(0));
    let busy = Arc::new(AtomicU64::new(0));
    let load: Vec<_> = match &server {
        Some(server) => (0..clients)
            .map(|k| {
                let addr = server.local_addr();
                let (done, served, busy) = (done.clone(), served.clone(), busy.clone());
                std::thread::spawn(move || hammer(addr, k, &done, &served, &busy))
            })
            .collect(),
        None => Vec::new(),
    };
    std::thread::sleep(Duration::from_secs_f64(seconds));
    done.store(true, Ordering::Relaxed);
    for l in load {
        l.join().map_err(|_| "a load thread panicked")??;
    }
    stop.stop();
    run.join().result?;
    if let Some(server) = server {
        server.shutdown();
    }
    Ok(Phase {
        stats: stats.snapshot(),
        served: served.load(Ordering::Relaxed),
        busy: busy.load(Ordering::Relaxed),
    })
}

/// The load threads stand for other machines on the network: under
/// `chrt` they leave the real-time priority to the scan, as the server's
/// own threads do.
#[cfg(target_os = "linux")]
fn normal_priority() {
    // SAFETY: plain system calls on the calling thread.
    unsafe {
        let normal = libc::sched_param { sched_priority: 0 };
        libc::sched_setscheduler(0, libc::SCHED_OTHER, &normal);
    }
}

#[cfg(not(target_os = "linux"))]
fn normal_priority() {}

/// One client: requests back to back until `done`.
fn hammer(
    addr: SocketAddr,
    k: usize,
    done: &AtomicBool,
    served: &AtomicU64,
    busy: &AtomicU64,
) -> Result<(), String> {
    normal_priority();
    let mut stream = TcpStream::connect(addr).map_err(|e| e.to_string())?;
    stream.set_nodelay(true).map_err(|e| e.to_string())?;
    let mut frame = Vec::new();
    let mut response = vec![0u8; 260];
    let mut tr_id = 0u16;
    while !done.load(Ordering::Relaxed) {
        tr_id = tr_id.wrapping_add(1);
        let mut req = ModbusRequest::new_tcp_udp(1, tr_id);
        let built = match tr_id % 3 {
            0 => req.generate_get_holdings(0, 10, &mut frame),
            1 => req.generate_get_coils(32, 16, &mut frame),
            _ => req.generate_set_holding(1024, (k as u16) << 8 | tr_id & 0xFF, &mut frame),
        };
        built.map_err(|e| e.to_string())?;
        stream.write_all(&frame).map_err(|e| e.to_string())?;
        stream
            .read_exact(&mut response[..6])
            .map_err(|e| e.to_string())?;
        let len = usize::from(u16::from_be_bytes([response[4], response[5]]));
        stream
            .read_exact(&mut response[6..6 + len])
            .map_err(|e| e.to_string())?;
        match req.parse_ok(&response[..6 + len]) {
            Ok(()) => {}
            // A write that found the queue full (more than 256 writes in
            // one cycle): answered, and counted apart.
            Err(ErrorKind::SlaveDeviceBusy) => {
                busy.fetch_add(1, Ordering::Relaxed);
            }
            Err(e) => return Err(e.to_string()),
        }
        served.fetch_add(1, Ordering::Relaxed);
    }
    Ok(())
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let run = || -> Result<(), Box<dyn std::error::Error>> {
        let t0 = Instant::now();
        let alone = phase(args.seconds, 0)?;
        println!("10 ms task alone ({:.0} s):", t0.elapsed().as_secs_f64());
        println!("{}", format_stats_table(&alone.stats));
        let t1 = Instant::now();
        let loaded = phase(args.seconds, args.clients)?;
        let secs = t1.elapsed().as_secs_f64();
        println!(
            "10 ms task with the Modbus server and {} clients ({secs:.0} s):",
            args.clients
        );
        println!("{}", format_stats_table(&loaded.stats));
        println!(
            "requests served: {} ({:.0} per second), of which {} writes answered busy (06)",
            loaded.served,
            loaded.served as f64 / args.seconds,
            loaded.busy
        );
        Ok(())
    };
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
