//! `--opcua ADDR:PORT`: an OPC UA server on the run's variables (see
//! docs/opcua.md), and `plcrun opcua-user add FILE NAME`, which adds a
//! user to a users file.

use super::{EXIT_OK, EXIT_USAGE};
use clap::{Args, Subcommand};
use plcrun::Plc;
use plcrun::{OpcUaConfig, OpcUaExchange, OpcUaServer, Users};
use std::io::BufRead;
use std::path::PathBuf;

/// The OPC UA options of `run`.
#[derive(Debug, Args)]
pub struct OpcUaArgs {
    /// Serve the program's variables over OPC UA on ADDR:PORT
    /// (127.0.0.1:4840; a port alone listens on 127.0.0.1; port 0 for a
    /// free port); see docs/opcua.md.
    #[arg(long, value_name = "ADDR:PORT")]
    pub opcua: Option<String>,
    /// Serve only the variables whose path matches GLOB (`*`, `?`;
    /// repeat for several); default all.
    #[arg(long, value_name = "GLOB", requires = "opcua")]
    pub opcua_expose: Vec<String>,
    /// The users who may log in and write (lines made by `plcrun
    /// opcua-user add`); without it every client reads only.
    #[arg(long, value_name = "FILE", requires = "opcua")]
    pub opcua_users: Option<PathBuf>,
    /// Where the server's certificate is made on first start and kept,
    /// with the trusted and rejected client certificates.
    #[arg(
        long,
        value_name = "DIR",
        default_value = "opcua-pki",
        requires = "opcua"
    )]
    pub opcua_pki: PathBuf,
    /// Also serve the None security policy (anonymous, read-only; nothing
    /// signed nor encrypted).
    #[arg(long, requires = "opcua")]
    pub opcua_allow_insecure: bool,
    /// Accept every client certificate instead of only those in
    /// DIR/trusted/certs.
    #[arg(long, requires = "opcua")]
    pub opcua_trust_clients: bool,
}

/// `plcrun opcua-user ...`
#[derive(Debug, Args)]
pub struct UserArgs {
    /// What to do.
    #[command(subcommand)]
    pub action: UserAction,
}

/// The actions of `opcua-user`.
#[derive(Debug, Subcommand)]
pub enum UserAction {
    /// Add NAME to FILE (made if missing) or change its password; the
    /// password is the first line of standard input.
    Add {
        /// The users file.
        file: PathBuf,
        /// The user's name.
        name: String,
    },
}

/// Starts the server `--opcua` asks for (none without it) and says where
/// it listens on standard error.
pub(super) fn start(
    args: &OpcUaArgs,
    plc: &Plc,
) -> Result<Option<(OpcUaServer, OpcUaExchange)>, String> {
    let Some(address) = &args.opcua else {
        return Ok(None);
    };
    let users = match &args.opcua_users {
        Some(path) => Users::load(path).map_err(|e| format!("E952: opcua: {e}"))?,
        None => Users::none(),
    };
    let config = OpcUaConfig {
        expose: args.opcua_expose.clone(),
        users,
        pki_dir: args.opcua_pki.clone(),
        allow_insecure: args.opcua_allow_insecure,
        trust_client_certs: args.opcua_trust_clients,
        ..OpcUaConfig::default()
    };
    let (server, exchange) = OpcUaServer::bind(address, plc, config).map_err(|e| e.to_string())?;
    sayln!(
        "opcua: listening on {} ({} values, ns={} {})",
        server.endpoint_url(),
        server.served_values(),
        server.namespace_index(),
        server.namespace_uri()
    );
    Ok(Some((server, exchange)))
}

/// `plcrun opcua-user add FILE NAME`
pub fn user(args: &UserArgs) -> i32 {
    match &args.action {
        UserAction::Add { file, name } => {
            let mut password = String::new();
            if let Err(e) = std::io::stdin().lock().read_line(&mut password) {
                sayln!("error: E957: cannot read the password from standard input: {e}");
                return EXIT_USAGE;
            }
            let password = password.trim_end_matches(['\r', '\n']);
            if password.is_empty() {
                sayln!("error: E957: the password (standard input) is empty");
                return EXIT_USAGE;
            }
            match Users::add_to_file(file, name, password) {
                Ok(()) => {
                    sayln!("opcua: user `{name}` written to {}", file.display());
                    EXIT_OK
                }
                Err(e) => {
                    sayln!("error: E952: {e}");
                    EXIT_USAGE
                }
            }
        }
    }
}
