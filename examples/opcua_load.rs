//! OPC UA under load next to a 10 ms task: reads per second, subscription
//! latency, and the task's start jitter with and without subscribed
//! clients.
//!
//! `cargo run --release --example opcua_load -- [--seconds S] [--clients N]
//!  [--vars V] [--readers R]`
//!
//! Three phases of S seconds (default 10) each, on the wall clock, with a
//! program of V DINT variables (default 1000; variable `k` changes every
//! `k mod 10 + 1` cycles) and a 10 ms task:
//! 1. the task alone (no server);
//! 2. the task served, N clients (default 10) each subscribed to all V
//!    variables and to the cycle counter (sampling and publishing every
//!    10 ms): notifications received, and the latency from the scan's copy
//!    (SourceTimestamp) to the client's callback for the counter;
//! 3. the task served, R clients (default 4) each reading 10 variables
//!    back to back: reads per second.
//!
//! Prints the statistics table of each phase. Anonymous sessions over
//! Basic256Sha256 SignAndEncrypt; the certificates are made in a
//! temporary directory.

use async_opcua::client::{ClientBuilder, DataChangeCallback, IdentityToken, Session};
use async_opcua::crypto::SecurityPolicy;
use async_opcua::types::{
    AttributeId, DateTime, MessageSecurityMode, MonitoredItemCreateRequest, NodeId, ReadValueId,
    TimestampsToReturn, UserTokenPolicy,
};
use plcrun::opcua::{OpcUaConfig, OpcUaServer};
use plcrun::{
    Options, Plc, Session as PlcSession, TaskRunner, TaskStats, TraceFormat, TraceWriter,
    format_stats_table,
};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

struct Args {
    seconds: f64,
    clients: usize,
    vars: usize,
    readers: usize,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        seconds: 10.0,
        clients: 10,
        vars: 1000,
        readers: 4,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let value = it.next().ok_or(format!("{arg} needs a value"))?;
        let bad = |e: std::num::ParseIntError| format!("{arg}: {e}");
        match arg.as_str() {
            "--seconds" => args.seconds = value.parse().map_err(|e| format!("{arg}: {e}"))?,
            "--clients" => args.clients = value.parse().map_err(bad)?,
            "--vars" => args.vars = value.parse().map_err(bad)?,
            "--readers" => args.readers = value.parse().map_err(bad)?,
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    Ok(args)
}

/// V variables, variable `k` changing every `k mod 10 + 1` cycles.
fn source(vars: usize) -> String {
    let mut s = String::from("PROGRAM Work\nVAR n : DINT;\n");
    for k in 1..=vars {
        s.push_str(&format!("v{k} : DINT;\n"));
    }
    s.push_str("END_VAR\nn := n + 1;\n");
    for k in 1..=vars {
        s.push_str(&format!("v{k} := n / {};\n", k % 10 + 1));
    }
    s.push_str(
        "END_PROGRAM
CONFIGURATION Load RESOURCE R ON PLC
    TASK ms10 (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM main WITH ms10 : Work;
END_RESOURCE END_CONFIGURATION\n",
    );
    s
}

/// What a phase measured.
#[derive(Default)]
struct Phase {
    stats: Vec<TaskStats>,
    notifications: u64,
    latencies_us: Vec<u64>,
    reads: u64,
}

/// Which load a phase puts on the server.
#[derive(Clone, Copy, PartialEq)]
enum Load {
    None,
    Subscribe(usize),
    Read(usize),
}

fn phase(args: &Args, load: Load, dir: &Path) -> Result<Phase, Box<dyn std::error::Error>> {
    let plc = Plc::compile_files(&[("load.st", &source(args.vars))], &Options::default())?;
    let stop = plc.stop_handle();
    let mut runner = TaskRunner::real_time(&plc);
    let stats = runner.stats();
    let mut server = None;
    let mut plc = plc;
    if load != Load::None {
        let config = OpcUaConfig {
            pki_dir: dir.join("server"),
            trust_client_certs: true,
            ..OpcUaConfig::default()
        };
        let (s, mut exchange) = OpcUaServer::bind("127.0.0.1:0", &plc, config)?;
        exchange.exchange(&mut plc);
        runner.set_between_ticks(exchange.into_between_ticks());
        server = Some(s);
    }
    let session = PlcSession::new(plc);
    let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    let run = runner.spawn(session, None, trace);
    let mut out = Phase::default();
    match (&server, load) {
        (Some(server), Load::Subscribe(n)) | (Some(server), Load::Read(n)) => {
            let rt = tokio::runtime::Builder::new_multi_thread()
                .worker_threads(2)
                .enable_all()
                .build()?;
            let url = server.endpoint_url();
            let ns = server.namespace_index();
            let subscribe = matches!(load, Load::Subscribe(_));
            let (count, lat, reads) =
                rt.block_on(drive(&url, ns, n, args, subscribe, &dir.join("client")))?;
            out.notifications = count;
            out.latencies_us = lat;
            out.reads = reads;
        }
        _ => std::thread::sleep(Duration::from_secs_f64(args.seconds)),
    }
    stop.stop();
    run.join().result?;
    drop(server);
    out.stats = stats.snapshot();
    Ok(out)
}

async fn connect(url: &str, pki: &Path) -> Result<Arc<Session>, String> {
    let mut client = ClientBuilder::new()
        .application_name("opcua_load")
        .application_uri("urn:plcrun:opcua-load")
        .create_sample_keypair(true)
        .trust_server_certs(true)
        .pki_dir(pki)
        .session_retry_limit(0)
        .client()
        .map_err(|e| format!("{e:?}"))?;
    let endpoint = (
        url,
        SecurityPolicy::Basic256Sha256.to_uri(),
        MessageSecurityMode::SignAndEncrypt,
        UserTokenPolicy::anonymous(),
    );
    let (session, event_loop) = client
        .connect_to_matching_endpoint(endpoint, IdentityToken::Anonymous)
        .await
        .map_err(|e| e.to_string())?;
    event_loop.spawn();
    if !session.wait_for_connection().await {
        return Err("no connection".into());
    }
    Ok(session)
}

/// N sessions subscribing (or reading) for the phase's length; the
/// notifications, the counter's latencies and the reads.
async fn drive(
    url: &str,
    ns: u16,
    n: usize,
    args: &Args,
    subscribe: bool,
    pki: &Path,
) -> Result<(u64, Vec<u64>, u64), Box<dyn std::error::Error>> {
    let count = Arc::new(AtomicU64::new(0));
    let reads = Arc::new(AtomicU64::new(0));
    let latencies: Arc<Mutex<Vec<u64>>> = Arc::default();
    let done = Arc::new(AtomicBool::new(false));
    let mut sessions = Vec::new();
    let mut readers = Vec::new();
    let ids: Vec<NodeId> = (1..=args.vars)
        .map(|k| NodeId::new(ns, format!("v{k}")))
        .collect();
    let counter = NodeId::new(ns, "n");
    for _ in 0..n {
        let session = connect(url, pki).await?;
        if subscribe {
            let (count, latencies, watched) = (count.clone(), latencies.clone(), counter.clone());
            let sub = session
                .create_subscription(
                    Duration::from_millis(10),
                    1000,
                    10,
                    0,
                    0,
                    true,
                    DataChangeCallback::new(move |dv, item| {
                        count.fetch_add(1, Ordering::Relaxed);
                        if item.item_to_monitor().node_id == watched
                            && let Some(at) = dv.source_timestamp
                        {
                            let now = DateTime::now().ticks();
                            let us = (now - at.ticks()).max(0) / 10;
                            latencies.lock().unwrap().push(us as u64);
                        }
                    }),
                )
                .await?;
            let mut items: Vec<MonitoredItemCreateRequest> =
                ids.iter().map(|id| id.clone().into()).collect();
            items.push(counter.clone().into());
            for item in &mut items {
                item.requested_parameters.sampling_interval = 10.0;
                item.requested_parameters.queue_size = 10;
            }
            // In requests of 500: the stack decodes arrays of at most
            // 1000 elements by default.
            for chunk in items.chunks(500) {
                session
                    .create_monitored_items(sub, TimestampsToReturn::Both, chunk.to_vec())
                    .await?;
            }
        } else {
            let (session, reads, done) = (session.clone(), reads.clone(), done.clone());
            let batch: Vec<ReadValueId> = ids
                .iter()
                .take(10)
                .map(|id| ReadValueId {
                    node_id: id.clone(),
                    attribute_id: AttributeId::Value as u32,
                    ..Default::default()
                })
                .collect();
            readers.push(tokio::spawn(async move {
                while !done.load(Ordering::Relaxed) {
                    if session
                        .read(&batch, TimestampsToReturn::Source, 0.0)
                        .await
                        .is_ok()
                    {
                        reads.fetch_add(batch.len() as u64, Ordering::Relaxed);
                    }
                }
            }));
        }
        sessions.push(session);
    }
    // Measure from here: every session is set up.
    count.store(0, Ordering::Relaxed);
    latencies.lock().unwrap().clear();
    reads.store(0, Ordering::Relaxed);
    tokio::time::sleep(Duration::from_secs_f64(args.seconds)).await;
    done.store(true, Ordering::Relaxed);
    let total = count.load(Ordering::Relaxed);
    let read_total = reads.load(Ordering::Relaxed);
    for r in readers {
        let _ = r.await;
    }
    for s in sessions {
        let _ = s.disconnect().await;
    }
    let lat = latencies.lock().unwrap().clone();
    Ok((total, lat, read_total))
}

fn percentile(sorted: &[u64], p: f64) -> u64 {
    if sorted.is_empty() {
        return 0;
    }
    sorted[((sorted.len() - 1) as f64 * p) as usize]
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let dir: PathBuf =
        std::env::temp_dir().join(format!("plcrun-opcua-load-{}", std::process::id()));
    let run = || -> Result<(), Box<dyn std::error::Error>> {
        let quiet = phase(&args, Load::None, &dir)?;
        println!("== the 10 ms task alone, {} s", args.seconds);
        print!("{}", format_stats_table(&quiet.stats));
        let sub = phase(&args, Load::Subscribe(args.clients), &dir)?;
        println!(
            "== served, {} clients subscribed to {} variables each, {} s",
            args.clients, args.vars, args.seconds
        );
        print!("{}", format_stats_table(&sub.stats));
        let mut lat = sub.latencies_us.clone();
        lat.sort_unstable();
        println!(
            "notifications: {:.0}/s; latency from the scan's copy to the client (counter, {} samples): median {} us, p99 {} us, max {} us",
            sub.notifications as f64 / args.seconds,
            lat.len(),
            percentile(&lat, 0.5),
            percentile(&lat, 0.99),
            lat.last().copied().unwrap_or(0)
        );
        let read = phase(&args, Load::Read(args.readers), &dir)?;
        println!(
            "== served, {} clients reading 10 variables back to back, {} s",
            args.readers, args.seconds
        );
        print!("{}", format_stats_table(&read.stats));
        println!(
            "reads: {:.0} values/s ({:.0} requests/s)",
            read.reads as f64 / args.seconds,
            read.reads as f64 / 10.0 / args.seconds
        );
        Ok(())
    };
    let result = run();
    let _ = std::fs::remove_dir_all(&dir);
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
