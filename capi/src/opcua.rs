//! The OPC UA server from C: serve a PLC's variables (docs/opcua.md) while
//! the host runs its cycles with `plc_run_cycle`, which then exchanges
//! with the server after each cycle (the values published, the clients'
//! writes applied), as the Rust runner's between-ticks hook does.

use crate::failure::Failure;
use crate::guard::guard;
use crate::handles::{self, PlcHandle};
use crate::status::{PLC_E_INVALID_ARGUMENT, PLC_E_SERVER};
use crate::text::{input, store};
use plcrun::opcua::{OpcUaConfig, OpcUaServer, Users};
use std::ffi::{c_char, c_int};
use std::path::PathBuf;

/// Also serve SecurityPolicy None (anonymous, read-only).
pub const PLC_OPCUA_ALLOW_INSECURE: u32 = 1;
/// Accept every client certificate.
pub const PLC_OPCUA_TRUST_CLIENTS: u32 = 2;

/// Starts an OPC UA server on `address` (`"127.0.0.1:4840"`, port 0 for a
/// free one) serving every variable of the PLC. `users_file` (NULL: none,
/// every client reads only) is a users file as `plcrun opcua-user add`
/// writes it; `pki_dir` keeps the server's certificate (made on first
/// start). `flags`: `PLC_OPCUA_ALLOW_INSECURE`, `PLC_OPCUA_TRUST_CLIENTS`.
/// A server already running on this PLC is stopped first. After this,
/// each `plc_run_cycle` exchanges with the server. `PLC_E_SERVER` when it
/// cannot start (`plc_last_error` gives the E95x code and why).
///
/// # Safety
/// `address` and `pki_dir` are NULL or NUL-terminated; `users_file` is
/// NULL or NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_opcua_start(
    plc: PlcHandle,
    address: *const c_char,
    users_file: *const c_char,
    pki_dir: *const c_char,
    flags: u32,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's contract.
        let address = unsafe { input(address, "address") }?;
        // SAFETY: the caller's contract.
        let pki_dir = unsafe { input(pki_dir, "pki_dir") }?;
        let users = if users_file.is_null() {
            Users::none()
        } else {
            // SAFETY: not NULL, NUL-terminated by the caller's contract.
            let path = unsafe { input(users_file, "users_file") }?;
            Users::load(path.as_ref())
                .map_err(|e| Failure::new(PLC_E_SERVER, format!("E952: opcua: {e}")))?
        };
        if flags & !(PLC_OPCUA_ALLOW_INSECURE | PLC_OPCUA_TRUST_CLIENTS) != 0 {
            return Err(Failure::new(
                PLC_E_INVALID_ARGUMENT,
                format!("unknown OPC UA flags {flags:#x}"),
            ));
        }
        let config = OpcUaConfig {
            users,
            pki_dir: PathBuf::from(pki_dir),
            allow_insecure: flags & PLC_OPCUA_ALLOW_INSECURE != 0,
            trust_client_certs: flags & PLC_OPCUA_TRUST_CLIENTS != 0,
            ..OpcUaConfig::default()
        };
        handles::with_entry(plc, |e| {
            e.opcua = None;
            let (server, mut exchange) = OpcUaServer::bind(address, &e.plc, config)
                .map_err(|err| Failure::new(PLC_E_SERVER, err.to_string()))?;
            exchange.exchange(&mut e.plc);
            e.opcua = Some((server, exchange));
            Ok(())
        })
    })
}

/// The port the PLC's OPC UA server listens on (`*port`), and the
/// namespace index of its variables' NodeIds (`*namespace`, may be NULL).
/// `PLC_E_INVALID_ARGUMENT` when no server runs.
///
/// # Safety
/// `port` is NULL or writable; `namespace` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn plc_opcua_port(
    plc: PlcHandle,
    port: *mut u16,
    namespace: *mut u16,
) -> c_int {
    guard(|| {
        if port.is_null() {
            return Err(Failure::null("port"));
        }
        let (p, ns) = handles::with_entry(plc, |e| match &e.opcua {
            Some((server, _)) => Ok((server.local_addr().port(), server.namespace_index())),
            None => Err(Failure::new(
                PLC_E_INVALID_ARGUMENT,
                "no OPC UA server runs on this PLC (plc_opcua_start)",
            )),
        })?;
        // SAFETY: the caller's contract.
        unsafe { store(port, "port", p) }?;
        if !namespace.is_null() {
            // SAFETY: not NULL, writable by the caller's contract.
            unsafe { store(namespace, "namespace", ns) }?;
        }
        Ok(())
    })
}

/// Stops the PLC's OPC UA server (nothing when none runs). `plc_free`
/// stops it too.
#[unsafe(no_mangle)]
pub extern "C" fn plc_opcua_stop(plc: PlcHandle) -> c_int {
    guard(|| {
        let server = handles::with_entry(plc, |e| Ok(e.opcua.take()))?;
        if let Some((server, _)) = server {
            server.shutdown();
        }
        Ok(())
    })
}
