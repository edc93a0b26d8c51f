//! `--web ADDR:PORT`: the web monitor (docs/web.md). A page served from
//! the binary shows the variables with live values, the task statistics,
//! the faulted state and each SFC chart with its active steps, and lets
//! the holder of the token write, force and unforce variables and reset a
//! faulted PLC; a JSON API under `/api/` does all of it, and `/metrics`
//! gives the statistics to Prometheus.
//!
//! - [`state`]: what the monitor's threads share with the scan;
//! - [`scan`]: the scan's side, called between two cycles, never waiting;
//! - [`server`]: the HTTP server's threads;
//! - [`http`]: reading a request and writing an answer;
//! - [`api`]: the JSON API;
//! - [`sse`]: the event stream;
//! - [`metrics`]: the Prometheus page;
//! - [`auth`]: the token.

mod api;
mod auth;
mod http;
mod metrics;
mod scan;
mod server;
mod sse;
mod state;

pub use scan::{AfterFault, ScanSide};
pub use server::WebServer;

use plcrun::{ChartPicture, Plc, TaskStatsHandle};
use state::{Chart, Counters, Shared, Snapshot};
use std::net::TcpListener;
use std::sync::mpsc::sync_channel;
use std::sync::{Arc, Mutex, OnceLock};

/// Changes waiting for the scan at most.
const QUEUE: usize = 16;

/// The server's handle for what is known only once the run is set up.
#[derive(Clone)]
pub struct WebLinks {
    shared: Arc<Shared>,
}

impl std::fmt::Debug for WebLinks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("WebLinks(..)")
    }
}

impl WebLinks {
    /// The run's task statistics (set once; later calls are ignored).
    pub fn set_stats(&self, stats: TaskStatsHandle) {
        let _ = self.shared.stats.set(stats);
    }

    /// Adds the Modbus server's counters to `/metrics`.
    pub fn add_modbus(&self, server: Arc<plcrun::ModbusServer>) {
        self.push(metrics::modbus(server));
    }

    /// Adds the OPC UA server's counters to `/metrics`.
    #[cfg(feature = "opcua")]
    pub fn add_opcua(&self, server: Arc<plcrun::OpcUaServer>) {
        self.push(metrics::opcua(server));
    }

    fn push(&self, source: metrics::Source) {
        self.shared
            .extra_metrics
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(source);
    }
}

/// A started monitor: its server, the scan's side and the links.
pub type Started = (WebServer, ScanSide, WebLinks);

/// The address to listen on: `HOST:PORT`, or a port alone on 127.0.0.1.
fn address(text: &str) -> String {
    let t = text.trim();
    if !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit()) {
        format!("127.0.0.1:{t}")
    } else {
        t.to_string()
    }
}

/// Starts the monitor `--web` asks for (none without it) on the
/// variables of `plc`, and says on standard error where it listens and,
/// unless one was given, the token drawn for changes.
pub fn start(web: Option<&str>, token: Option<&str>, plc: &Plc) -> Result<Option<Started>, String> {
    let Some(web) = web else {
        return Ok(None);
    };
    let (token, drawn) = match token {
        Some(t) => {
            auth::check_token(t)?;
            (t.to_string(), false)
        }
        None => (auth::random_token()?, true),
    };
    let address = address(web);
    let listener = TcpListener::bind(&address)
        .map_err(|e| format!("E962: web: cannot listen on {address}: {e}"))?;
    let (tx, rx) = sync_channel(QUEUE);
    let shared = Arc::new(Shared {
        variables: plc.variables(),
        charts: charts(plc),
        snapshot: Mutex::new(Arc::new(Snapshot::empty())),
        commands: tx,
        stats: OnceLock::new(),
        token,
        counters: Counters::default(),
        extra_metrics: Mutex::new(Vec::new()),
        closing: std::sync::atomic::AtomicBool::new(false),
    });
    let mut scan = ScanSide::new(Arc::clone(&shared), plc, rx);
    let server = WebServer::start(listener, Arc::clone(&shared))?;
    sayln!("web: listening on http://{}/", server.local_addr());
    if drawn {
        sayln!("web: token for changes: {}", shared.token);
    }
    // The page shows the initial values until the first cycle ends.
    scan.publish_now(plc);
    Ok(Some((server, scan, WebLinks { shared })))
}

/// The charts of `plc` with their drawings (a chart that cannot be drawn
/// is listed with an empty drawing).
fn charts(plc: &Plc) -> Vec<Chart> {
    plc.chart_states()
        .into_iter()
        .map(|c| {
            let svg = ChartPicture::from_sources(plc.sources(), Some(c.pou.as_str()))
                .map(|p| p.to_svg())
                .unwrap_or_default();
            Chart {
                path: c.path,
                pou: c.pou,
                svg,
            }
        })
        .collect()
}
