//! The listening socket, its acceptor thread and the client threads.
//!
//! One thread accepts; each client gets its own thread (both at the normal
//! priority, whatever the process runs at: see `priority`), at most
//! [`ModbusConfig::max_clients`] of them: a connection over the limit is
//! accepted and closed at once. Stopping the server (drop or
//! [`ModbusServer::shutdown`]) wakes the acceptor, shuts every client
//! socket down and waits for the threads.

use super::connection;
use super::exchange::{ClientWrite, ModbusExchange};
use super::mapping::Tables;
use super::published::Published;
use super::stats::{Counters, ModbusStats, bump};
use std::fmt;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{SyncSender, sync_channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long [`ModbusServer::shutdown`] waits for the client threads.
const SHUTDOWN_WAIT: Duration = Duration::from_secs(2);

/// How a Modbus server serves its clients.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ModbusConfig {
    /// Clients connected at once (default 16); more are closed on arrival.
    pub max_clients: usize,
    /// A connection with no complete request for this long is closed
    /// (default 30 s): idle clients, and half-open ones that sent part of
    /// a frame.
    pub idle_timeout: Duration,
    /// Client writes waiting for the next cycle boundary (default 256);
    /// a write that finds the queue full gets exception 06 (server busy).
    pub write_queue: usize,
}

impl Default for ModbusConfig {
    fn default() -> Self {
        ModbusConfig {
            max_clients: 16,
            idle_timeout: Duration::from_secs(30),
            write_queue: 256,
        }
    }
}

/// Why a Modbus server could not start.
#[derive(Debug)]
#[non_exhaustive]
pub enum ModbusError {
    /// A setting of [`ModbusConfig`] that is 0.
    ZeroSetting {
        /// `max_clients`, `idle_timeout` or `write_queue`.
        setting: &'static str,
    },
    /// The address cannot be listened on.
    Bind {
        /// The address as given.
        address: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// The acceptor thread could not be started.
    Thread(std::io::Error),
}

impl fmt::Display for ModbusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModbusError::ZeroSetting { setting } => {
                write!(f, "modbus: {setting} must be greater than 0")
            }
            ModbusError::Bind { address, source } => {
                write!(f, "modbus: cannot listen on `{address}`: {source}")
            }
            ModbusError::Thread(e) => write!(f, "modbus: cannot start the server thread: {e}"),
        }
    }
}

impl std::error::Error for ModbusError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ModbusError::Bind { source, .. } | ModbusError::Thread(source) => Some(source),
            ModbusError::ZeroSetting { .. } => None,
        }
    }
}

/// What the server's threads share.
#[derive(Debug)]
pub(crate) struct Shared {
    pub(crate) config: ModbusConfig,
    pub(crate) published: Published,
    pub(crate) counters: Counters,
    pub(crate) stop: AtomicBool,
    /// The open client sockets, to shut them down on stop.
    clients: Mutex<Vec<(u64, TcpStream)>>,
    next_client: AtomicU64,
}

impl Shared {
    /// The state of a server with `config` that has no client yet.
    pub(crate) fn new(config: ModbusConfig) -> Shared {
        Shared {
            config,
            published: Published::default(),
            counters: Counters::default(),
            stop: AtomicBool::new(false),
            clients: Mutex::new(Vec::new()),
            next_client: AtomicU64::new(0),
        }
    }
}

/// A Modbus TCP server on a PLC's process image (see `docs/modbus.md`).
///
/// The network side runs on its own threads; the scan side is the
/// [`ModbusExchange`] that [`bind`](Self::bind) returns with it, called
/// between cycles.
///
/// ```
/// use plcrun::{ModbusConfig, ModbusServer, Options, Plc};
///
/// let src = "PROGRAM P VAR n AT %QW0 : INT; END_VAR n := n + 1; END_PROGRAM";
/// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
/// let (server, mut exchange) = ModbusServer::bind("127.0.0.1:0", ModbusConfig::default())?;
/// println!("serving on {}", server.local_addr());
/// for _ in 0..3 {
///     plc.run_cycle()?;
///     exchange.exchange(&mut plc); // clients now read n = 1, 2, 3 in holding register 0
/// }
/// assert_eq!(server.stats().publishes, 3);
/// server.shutdown();
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct ModbusServer {
    shared: Arc<Shared>,
    local_addr: SocketAddr,
    acceptor: Option<JoinHandle<()>>,
}

impl ModbusServer {
    /// Listens on `address` (`"0.0.0.0:502"`, `"127.0.0.1:0"` for a free
    /// port) and starts accepting clients; returns the server and its scan
    /// side. Until the first exchange, clients read zeros.
    pub fn bind(
        address: &str,
        config: ModbusConfig,
    ) -> Result<(ModbusServer, ModbusExchange), ModbusError> {
        for (setting, zero) in [
            ("max_clients", config.max_clients == 0),
            ("idle_timeout", config.idle_timeout.is_zero()),
            ("write_queue", config.write_queue == 0),
        ] {
            if zero {
                return Err(ModbusError::ZeroSetting { setting });
            }
        }
        let bind_error = |source| ModbusError::Bind {
            address: address.to_string(),
            source,
        };
        let listener = TcpListener::bind(address).map_err(bind_error)?;
        let local_addr = listener.local_addr().map_err(bind_error)?;
        let (tx, rx) = sync_channel(config.write_queue);
        let per_exchange = config.write_queue;
        let shared = Arc::new(Shared::new(config));
        let acceptor_shared = Arc::clone(&shared);
        let acceptor = std::thread::Builder::new()
            .name("modbus-accept".into())
            .spawn(move || {
                // Client threads, spawned from here, inherit the policy.
                super::priority::leave_real_time();
                accept(&listener, &acceptor_shared, &tx);
            })
            .map_err(ModbusError::Thread)?;
        let server = ModbusServer {
            shared: Arc::clone(&shared),
            local_addr,
            acceptor: Some(acceptor),
        };
        let exchange = ModbusExchange {
            shared,
            writes: rx,
            shadow: Tables::default(),
            per_exchange,
        };
        Ok((server, exchange))
    }

    /// The address the server listens on (with the port the system chose
    /// for port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// The counters so far.
    pub fn stats(&self) -> ModbusStats {
        self.shared.counters.snapshot()
    }

    /// The configuration in force.
    pub fn config(&self) -> &ModbusConfig {
        &self.shared.config
    }

    /// Stops accepting, closes every connection and waits (up to 2 s) for
    /// the client threads. Dropping the server does the same.
    pub fn shutdown(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        let Some(acceptor) = self.acceptor.take() else {
            return;
        };
        self.shared.stop.store(true, Ordering::SeqCst);
        // Wake the acceptor out of `accept` with a connection of our own.
        let ip = match self.local_addr.ip() {
            IpAddr::V4(ip) if ip.is_unspecified() => IpAddr::V4(Ipv4Addr::LOCALHOST),
            IpAddr::V6(ip) if ip.is_unspecified() => IpAddr::V6(Ipv6Addr::LOCALHOST),
            ip => ip,
        };
        let wake = SocketAddr::new(ip, self.local_addr.port());
        let _ = TcpStream::connect_timeout(&wake, Duration::from_secs(1));
        let _ = acceptor.join();
        for (_, stream) in lock(&self.shared.clients).iter() {
            let _ = stream.shutdown(Shutdown::Both);
        }
        let until = Instant::now() + SHUTDOWN_WAIT;
        while self.shared.counters.connections_open.load(Ordering::SeqCst) > 0
            && Instant::now() < until
        {
            std::thread::sleep(Duration::from_millis(5));
        }
    }
}

impl Drop for ModbusServer {
    fn drop(&mut self) {
        self.stop();
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The acceptor's loop.
fn accept(listener: &TcpListener, shared: &Arc<Shared>, writes: &SyncSender<ClientWrite>) {
    for conn in listener.incoming() {
        if shared.stop.load(Ordering::SeqCst) {
            break;
        }
        let Ok(stream) = conn else {
            // Out of descriptors and the like: wait rather than spin.
            std::thread::sleep(Duration::from_millis(10));
            continue;
        };
        let open = &shared.counters.connections_open;
        if open.load(Ordering::SeqCst) >= shared.config.max_clients as u64 {
            bump(&shared.counters.connections_refused);
            let _ = stream.shutdown(Shutdown::Both);
            continue;
        }
        let Ok(registered) = stream.try_clone() else {
            continue;
        };
        let id = shared.next_client.fetch_add(1, Ordering::Relaxed);
        lock(&shared.clients).push((id, registered));
        open.fetch_add(1, Ordering::SeqCst);
        bump(&shared.counters.connections_accepted);
        let (client_shared, client_writes) = (Arc::clone(shared), writes.clone());
        let spawned = std::thread::Builder::new()
            .name("modbus-client".into())
            .spawn(move || {
                connection::serve(stream, &client_shared, &client_writes);
                leave(&client_shared, id);
            });
        if spawned.is_err() {
            leave(shared, id);
        }
    }
}

/// A client thread's end: unregisters its socket.
fn leave(shared: &Shared, id: u64) {
    lock(&shared.clients).retain(|(other, _)| *other != id);
    shared
        .counters
        .connections_open
        .fetch_sub(1, Ordering::SeqCst);
}
