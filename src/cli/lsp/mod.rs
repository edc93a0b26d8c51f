//! `plcrun lsp`: a Language Server Protocol server on standard input and
//! output (docs/editors.md). The protocol's framing is `lsp-server`'s, its
//! types `lsp-types`'; the answers come from the library's [`plcrun::Analysis`].

mod convert;
mod handlers;
mod live;
mod position;
mod server;
mod uri;
mod workspace;

use super::{EXIT_OK, EXIT_USAGE};
use clap::Args;
use lsp_server::Connection;

/// `plcrun lsp`: serve the Language Server Protocol on stdio.
#[derive(Debug, Args)]
pub struct LspArgs {
    /// Accepted for the editors that pass it: standard input and output
    /// are the only transport.
    #[arg(long)]
    pub stdio: bool,
    /// Show the values of a running plcrun as inlay hints: the address of
    /// its web monitor (`--web` of the run; HOST:PORT, a port, or an
    /// http:// URL). An editor may also give it as the initialization
    /// option `live`.
    #[arg(long, value_name = "ADDR")]
    pub live: Option<String>,
}

/// Runs the server until the client says `exit`.
pub fn lsp(args: &LspArgs) -> i32 {
    let (connection, threads) = Connection::stdio();
    let outcome = server::serve(&connection, args.live.as_deref());
    drop(connection);
    // The reader thread may fail on a message sent after `exit` (an
    // editor closing its documents as it quits): the session is over.
    let _ = threads.join();
    match outcome {
        Ok(()) => EXIT_OK,
        Err(e) => {
            sayln!("error: plcrun lsp: {e}");
            EXIT_USAGE
        }
    }
}
