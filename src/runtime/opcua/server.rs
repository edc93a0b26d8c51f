//! The server: its settings, its start (the socket, the certificate, the
//! tokio runtime its tasks run on) and its stop.
//!
//! The runtime's threads run at the normal priority whatever the process
//! runs at (they leave an inherited real-time policy when they start, as
//! the Modbus server's do), so a busy network never competes with the
//! scan.

use super::auth::PlcAuth;
use super::exchange::{ClientWrite, OpcUaExchange};
use super::glob::Globs;
use super::model::Model;
use super::node_manager::{PLCRUN_NAMESPACE, PlcNodes};
use super::published::Published;
use super::pump::pump;
use super::stats::{Counters, OpcUaStats};
use super::users::Users;
use crate::runtime::engine::Plc;
use async_opcua::crypto::SecurityPolicy;
use async_opcua::server::address_space::AddressSpace;
use async_opcua::server::node_manager::ServerContext;
use async_opcua::server::node_manager::memory::{InMemoryNodeManager, InMemoryNodeManagerBuilder};
use async_opcua::server::{ANONYMOUS_USER_TOKEN_ID, ServerBuilder, ServerEndpoint, ServerHandle};
use async_opcua::types::{MessageSecurityMode, VariableId, Variant};
use std::fmt;
use std::net::{IpAddr, Ipv4Addr, SocketAddr, TcpListener, ToSocketAddrs};
use std::path::PathBuf;
use std::sync::atomic::AtomicU16;
use std::sync::mpsc::sync_channel;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Monitored items one subscription may hold.
const MAX_ITEMS_PER_SUBSCRIPTION: usize = 100_000;

/// Data changes in one Publish response at most.
const MAX_NOTIFICATIONS_PER_PUBLISH: u64 = 500;

/// How long stopping the server waits for its tasks.
const SHUTDOWN_WAIT: Duration = Duration::from_secs(2);

/// How an OPC UA server serves its clients (docs/opcua.md, "Security").
#[derive(Debug, Clone)]
pub struct OpcUaConfig {
    /// Which variables to serve, by path (`*`, `?`); empty: all.
    pub expose: Vec<String>,
    /// The users who may log in and write; none: read-only for all.
    pub users: Users,
    /// Where the server's certificate and private key are kept (made on
    /// first start) and where client certificates are trusted or
    /// rejected (`trusted/`, `rejected/`).
    pub pki_dir: PathBuf,
    /// Also serve the `None` security policy (no signature, no
    /// encryption; anonymous, read-only logins only).
    pub allow_insecure: bool,
    /// Accept any client certificate, instead of only those copied into
    /// `pki_dir/trusted/certs` (a refused one is kept in
    /// `pki_dir/rejected/certs` for the administrator to move).
    pub trust_client_certs: bool,
    /// Client writes waiting for the next cycle boundary (default 256);
    /// a write that finds the queue full gets BadResourceUnavailable.
    pub write_queue: usize,
    /// Sessions open at once (default 32).
    pub max_sessions: usize,
}

impl Default for OpcUaConfig {
    fn default() -> Self {
        OpcUaConfig {
            expose: Vec::new(),
            users: Users::none(),
            pki_dir: PathBuf::from("opcua-pki"),
            allow_insecure: false,
            trust_client_certs: false,
            write_queue: 256,
            max_sessions: 32,
        }
    }
}

/// Why an OPC UA server could not start. [`code`](Self::code) gives its
/// stable code (docs/diagnostics.md, E950-E969).
#[derive(Debug)]
#[non_exhaustive]
pub enum OpcUaError {
    /// The address is not `HOST:PORT` (or `PORT`).
    BadAddress(String),
    /// The address cannot be listened on (in use, not local, no right).
    Bind {
        /// The address as given.
        address: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// A setting of [`OpcUaConfig`] that is 0.
    ZeroSetting {
        /// `write_queue` or `max_sessions`.
        setting: &'static str,
    },
    /// `expose` selects no variable.
    NothingExposed(Vec<String>),
    /// The certificate directory cannot be made or used.
    Pki {
        /// The directory.
        dir: PathBuf,
        /// What went wrong.
        problem: String,
    },
    /// The server or its runtime could not be started.
    Start(String),
}

impl OpcUaError {
    /// The error's stable code.
    pub fn code(&self) -> &'static str {
        match self {
            OpcUaError::BadAddress(_) => "E950",
            OpcUaError::Bind { .. } => "E951",
            OpcUaError::ZeroSetting { .. } => "E953",
            OpcUaError::NothingExposed(_) => "E954",
            OpcUaError::Pki { .. } => "E955",
            OpcUaError::Start(_) => "E956",
        }
    }
}

impl fmt::Display for OpcUaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: opcua: ", self.code())?;
        match self {
            OpcUaError::BadAddress(a) => {
                write!(
                    f,
                    "`{a}` is not an address to listen on (HOST:PORT or PORT)"
                )
            }
            OpcUaError::Bind { address, source } => {
                write!(f, "cannot listen on `{address}`: {source}")
            }
            OpcUaError::ZeroSetting { setting } => write!(f, "{setting} must be greater than 0"),
            OpcUaError::NothingExposed(globs) => write!(
                f,
                "--opcua-expose {} selects no variable of the program",
                globs.join(" ")
            ),
            OpcUaError::Pki { dir, problem } => {
                write!(f, "certificate directory `{}`: {problem}", dir.display())
            }
            OpcUaError::Start(e) => write!(f, "cannot start the server: {e}"),
        }
    }
}

impl std::error::Error for OpcUaError {}

/// What the scan side and the server's tasks share.
pub(crate) struct Shared {
    /// The served tree and values.
    pub(crate) model: Model,
    /// The last completed cycle's values.
    pub(crate) published: Published,
    /// Woken after each publish.
    pub(crate) wake: tokio::sync::Notify,
    /// The counters.
    pub(crate) counters: Counters,
    /// The namespace index of the PLC's nodes.
    pub(crate) namespace: AtomicU16,
    /// The task's cycle time in milliseconds (MinimumSamplingInterval).
    pub(crate) cycle_ms: f64,
}

/// A running OPC UA server on a PLC's variables (docs/opcua.md). Made by
/// [`OpcUaServer::bind`] with its [`OpcUaExchange`], which the scan side
/// calls between cycles. Dropping it stops the server.
pub struct OpcUaServer {
    runtime: Option<tokio::runtime::Runtime>,
    handle: ServerHandle,
    local_addr: SocketAddr,
    shared: Arc<Shared>,
    certificate: PathBuf,
}

impl fmt::Debug for OpcUaServer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("OpcUaServer")
            .field("local_addr", &self.local_addr)
            .finish_non_exhaustive()
    }
}

/// The socket address of `text`: `HOST:PORT`, or `PORT` alone for
/// 127.0.0.1.
fn socket_address(text: &str) -> Result<SocketAddr, OpcUaError> {
    let t = text.trim();
    if let Ok(port) = t.parse::<u16>() {
        return Ok(SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), port));
    }
    t.to_socket_addrs()
        .ok()
        .and_then(|mut a| a.next())
        .ok_or_else(|| OpcUaError::BadAddress(text.to_string()))
}

impl OpcUaServer {
    /// Starts a server on `address` (`127.0.0.1:4840`, `0.0.0.0:4840`,
    /// port 0 for any free port, or a port alone for 127.0.0.1) serving
    /// `plc`'s variables as `config` says, with the values they have now.
    /// Returns the server and the exchange to call between cycles.
    pub fn bind(
        address: &str,
        plc: &Plc,
        config: OpcUaConfig,
    ) -> Result<(OpcUaServer, OpcUaExchange), OpcUaError> {
        for (setting, value) in [
            ("write_queue", config.write_queue),
            ("max_sessions", config.max_sessions),
        ] {
            if value == 0 {
                return Err(OpcUaError::ZeroSetting { setting });
            }
        }
        let model = Model::build(plc, &Globs::new(&config.expose));
        if model.leaves.is_empty() && !config.expose.is_empty() {
            return Err(OpcUaError::NothingExposed(config.expose.clone()));
        }
        let addr = socket_address(address)?;
        let listener = TcpListener::bind(addr).map_err(|source| OpcUaError::Bind {
            address: address.to_string(),
            source,
        })?;
        let local_addr = listener
            .local_addr()
            .map_err(|e| OpcUaError::Start(e.to_string()))?;
        listener
            .set_nonblocking(true)
            .map_err(|e| OpcUaError::Start(e.to_string()))?;
        prepare_pki(&config.pki_dir)?;
        let published = Published::new(model.leaves.len());
        let shared = Arc::new(Shared {
            model,
            published,
            wake: tokio::sync::Notify::new(),
            counters: Counters::default(),
            namespace: AtomicU16::new(0),
            cycle_ms: plc.cycle_time() as f64 / 1e6,
        });
        // The values the clients see until the first exchange.
        shared
            .published
            .try_publish(|f| super::exchange::capture(plc, &shared.model.leaves, f));
        let (writes_tx, writes_rx) = sync_channel::<ClientWrite>(config.write_queue);
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .thread_name("plcrun-opcua")
            .on_thread_start(crate::runtime::modbus::priority::leave_real_time)
            .enable_all()
            .build()
            .map_err(|e| OpcUaError::Start(e.to_string()))?;
        let certificate = config.pki_dir.join("own/cert.der");
        let host = match local_addr.ip() {
            ip if ip.is_unspecified() => "localhost".to_string(),
            ip => ip.to_string(),
        };
        let nodes_shared = shared.clone();
        let builder = server_builder(&config, &host, local_addr.port(), shared.cycle_ms)
            .with_node_manager(InMemoryNodeManagerBuilder::new(
                move |context: ServerContext, space: &mut AddressSpace| {
                    PlcNodes::new(nodes_shared, writes_tx, context, space)
                },
            ));
        let (server, handle) = {
            let _in_runtime = runtime.enter();
            builder.build().map_err(OpcUaError::Start)?
        };
        let manager = handle
            .node_managers()
            .get_of_type::<InMemoryNodeManager<PlcNodes>>()
            .ok_or_else(|| OpcUaError::Start("the PLC's node manager is missing".into()))?;
        let listener = {
            let _in_runtime = runtime.enter();
            tokio::net::TcpListener::from_std(listener)
                .map_err(|e| OpcUaError::Start(e.to_string()))?
        };
        let failure: Arc<Mutex<Option<String>>> = Arc::default();
        let failed = failure.clone();
        runtime.spawn(async move {
            if let Err(e) = server.run_with(listener).await {
                *failed.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
            }
        });
        runtime.spawn(pump(
            shared.clone(),
            manager,
            handle.subscriptions().clone(),
            handle.token().clone(),
        ));
        let exchange = OpcUaExchange {
            shared: shared.clone(),
            writes: writes_rx,
            per_exchange: config.write_queue,
        };
        Ok((
            OpcUaServer {
                runtime: Some(runtime),
                handle,
                local_addr,
                shared,
                certificate,
            },
            exchange,
        ))
    }

    /// The address the server listens on (the port the system chose, for
    /// port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// The endpoint URL clients connect to (`opc.tcp://127.0.0.1:4840/`).
    pub fn endpoint_url(&self) -> String {
        let host = match self.local_addr.ip() {
            ip if ip.is_unspecified() => "localhost".to_string(),
            IpAddr::V6(ip) => format!("[{ip}]"),
            ip => ip.to_string(),
        };
        format!("opc.tcp://{host}:{}/", self.local_addr.port())
    }

    /// The namespace index of the PLC's nodes (`ns=` of their NodeIds).
    pub fn namespace_index(&self) -> u16 {
        self.shared
            .namespace
            .load(std::sync::atomic::Ordering::Acquire)
    }

    /// The namespace URI of the PLC's nodes.
    pub fn namespace_uri(&self) -> &'static str {
        PLCRUN_NAMESPACE
    }

    /// The server's certificate (DER), made on first start.
    pub fn certificate_path(&self) -> &std::path::Path {
        &self.certificate
    }

    /// How many single values are served.
    pub fn served_values(&self) -> usize {
        self.shared.model.leaves.len()
    }

    /// The server's counters now.
    pub fn stats(&self) -> OpcUaStats {
        let mut stats = self.shared.counters.snapshot();
        // The server's own diagnostics summary counts the sessions.
        let count = |id: VariableId| -> u64 {
            match self.handle.info().diagnostics.get(id).and_then(|v| v.value) {
                Some(Variant::UInt32(n)) => u64::from(n),
                _ => 0,
            }
        };
        stats.sessions = count(
            VariableId::Server_ServerDiagnostics_ServerDiagnosticsSummary_CurrentSessionCount,
        );
        stats.sessions_total = count(
            VariableId::Server_ServerDiagnostics_ServerDiagnosticsSummary_CumulatedSessionCount,
        );
        stats
    }

    /// Stops the server: closes the sessions and waits (a bounded time)
    /// for its tasks. Dropping the server does the same.
    pub fn shutdown(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        self.handle.cancel();
        if let Some(runtime) = self.runtime.take() {
            runtime.shutdown_timeout(SHUTDOWN_WAIT);
        }
    }
}

impl Drop for OpcUaServer {
    fn drop(&mut self) {
        self.stop();
    }
}

/// Makes the certificate directory if it is missing.
fn prepare_pki(dir: &std::path::Path) -> Result<(), OpcUaError> {
    std::fs::create_dir_all(dir).map_err(|e| OpcUaError::Pki {
        dir: dir.to_path_buf(),
        problem: e.to_string(),
    })?;
    let probe = dir.join(".plcrun-write-check");
    std::fs::write(&probe, b"").map_err(|e| OpcUaError::Pki {
        dir: dir.to_path_buf(),
        problem: format!("cannot write in it: {e}"),
    })?;
    let _ = std::fs::remove_file(probe);
    Ok(())
}

/// The server's settings: identity, certificate, endpoints, limits.
/// Subscriptions may sample at the task's cycle and publish as often,
/// down to 10 ms (the stack checks its subscriptions at that rate).
fn server_builder(config: &OpcUaConfig, host: &str, port: u16, cycle_ms: f64) -> ServerBuilder {
    let anonymous = [ANONYMOUS_USER_TOKEN_ID.to_string()];
    let poll_ms = cycle_ms.clamp(10.0, 100.0);
    let mut builder = ServerBuilder::new()
        .application_name("plcrun")
        .application_uri("urn:plcrun:server")
        .product_uri("urn:plcrun")
        .create_sample_keypair(true)
        .pki_dir(config.pki_dir.clone())
        .certificate_path("own/cert.der")
        .private_key_path("private/private.pem")
        .trust_client_certs(config.trust_client_certs)
        .host(host.to_string())
        .port(port)
        .max_sessions(config.max_sessions)
        // On for the session counts of `stats()` (and /metrics); it also
        // serves the standard ServerDiagnostics nodes.
        .diagnostics_enabled(true)
        .subscription_poll_interval_ms(poll_ms as u64)
        .with_authenticator(Arc::new(PlcAuth {
            users: config.users.clone(),
        }))
        .add_endpoint(
            "basic256sha256_sign_encrypt",
            ServerEndpoint::new(
                "/",
                SecurityPolicy::Basic256Sha256,
                MessageSecurityMode::SignAndEncrypt,
                &anonymous,
            ),
        )
        .add_endpoint(
            "basic256sha256_sign",
            ServerEndpoint::new(
                "/",
                SecurityPolicy::Basic256Sha256,
                MessageSecurityMode::Sign,
                &anonymous,
            ),
        )
        .default_endpoint("basic256sha256_sign_encrypt")
        .discovery_urls(vec!["/".to_string()]);
    let limits = &mut builder.limits_mut().subscriptions;
    limits.min_publishing_interval_ms = poll_ms;
    limits.min_sampling_interval_ms = cycle_ms.max(1.0);
    // A client may watch every value of a large program in one
    // subscription (the stack's default is 1000 items).
    limits.max_monitored_items_per_sub = MAX_ITEMS_PER_SUBSCRIPTION;
    // A Publish of more notifications than this is split: measured, a
    // client asking for no limit with 1000 changed values got none.
    limits.max_notifications_per_publish = MAX_NOTIFICATIONS_PER_PUBLISH;
    if config.allow_insecure {
        builder = builder.add_endpoint("none", ServerEndpoint::new_none("/", &anonymous));
    }
    builder
}
