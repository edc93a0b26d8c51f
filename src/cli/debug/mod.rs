//! `plcrun debug`: a Debug Adapter Protocol server on standard input and
//! output (docs/editors.md, "Debugging"). The program runs as `plcrun run`
//! runs it, with the library's debugger attached
//! ([`plcrun::Plc::attach_debugger`]).
//!
//! The framing and the messages are written here ([`framing`],
//! [`protocol`]): the `dap` crate (0.4.1-alpha1, the only one on
//! crates.io) refuses the custom requests this adapter serves (`force`,
//! `unforce`, `cycleStep`, `pauseAtCycle`) and any header but
//! `Content-Length`, and DAP is not JSON-RPC.

mod framing;
mod front;
mod protocol;
mod server;

use super::EXIT_OK;
use super::args::{Cli, Command, RunArgs};
use clap::{Args, Parser};
use std::sync::Arc;

/// `plcrun debug`: serve the Debug Adapter Protocol on stdio.
#[derive(Debug, Args)]
pub struct DebugArgs {}

/// Runs the adapter until the client disconnects or closes its input.
pub fn debug(_args: &DebugArgs) -> i32 {
    let out = Arc::new(protocol::Output::new(Box::new(std::io::stdout())));
    server::serve(std::io::stdin().lock(), out);
    EXIT_OK
}

/// The flags of `plcrun run` from a launch's words (`plcrun run FILES...
/// FLAGS...`), made fit for a run under the debugger: no trace on
/// standard output (the protocol's) unless `--output` names a file, no
/// watchdog (a stop would trip it), no stimulus from standard input, and
/// without `--cycles` (nor `--realtime`) a run until the client stops it.
fn run_args(words: &[String]) -> Result<RunArgs, String> {
    let cli = Cli::try_parse_from(words).map_err(|e| e.to_string())?;
    let Some(Command::Run(mut args)) = cli.command else {
        return Err("launch: expected the sources and flags of `plcrun run`".into());
    };
    if args.stimulus.as_ref().is_some_and(|s| s.as_os_str() == "-") {
        return Err("launch: --stimulus - reads standard input, which is the debugger's".into());
    }
    if args.output.is_none() {
        args.no_trace = true;
    }
    args.watchdog = "0".into();
    if args.cycles.is_none() && !args.realtime {
        args.cycles = Some(u64::MAX);
    }
    Ok(*args)
}
