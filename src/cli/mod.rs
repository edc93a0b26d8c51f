//! Command-line front end: a thin driver over the library's public API.
//! Exit status: 0 ok, 1 compile errors, 2 usage errors, 3 runtime fault.

// First: its `say!` and `sayln!` print every message of the modules below.
#[macro_use]
mod style;

mod args;
mod broken_pipe;
mod compare;
mod completions;
mod debug;
mod draw;
mod export;
mod given;
mod health;
mod init;
mod lsp;
mod modbus;
mod monitor_client;
mod online;
#[cfg(feature = "opcua")]
mod opcua;
mod progress_bar;
mod project;
mod reload;
mod retain;
mod run;
mod serve;
mod test;
mod web;

use clap::{CommandFactory, FromArgMatches};
use given::Given;

/// Exit status for success.
pub const EXIT_OK: i32 = 0;
/// Exit status for compile errors.
pub const EXIT_COMPILE: i32 = 1;
/// Exit status for usage errors.
pub const EXIT_USAGE: i32 = 2;
/// Exit status for runtime faults.
pub const EXIT_FAULT: i32 = 3;

/// Parses the command line and runs the chosen command.
pub fn main() -> i32 {
    broken_pipe::end_quietly_on_broken_pipe();
    let words = compare::reorder(std::env::args_os().collect());
    let color = style::choice_in(&words);
    let mut command = args::Cli::command().color(style::for_clap(color));
    let subcommands: Vec<String> = command
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .collect();
    let words = style::globals_after_subcommand(words, &subcommands);
    let matches = match command.try_get_matches_from_mut(words) {
        Ok(m) => m,
        Err(e) => return usage(e),
    };
    // The flags typed (not defaulted) of the subcommand: those that
    // override a project file.
    let given = matches
        .subcommand()
        .and_then(|(name, sub)| Some(Given::of(sub, command.find_subcommand(name)?)))
        .unwrap_or_default();
    match args::Cli::from_arg_matches(&matches) {
        Ok(cli) => {
            style::configure(cli.color, cli.quiet);
            dispatch(cli, &given)
        }
        Err(e) => usage(e),
    }
}

/// Runs the command `cli` names.
fn dispatch(cli: args::Cli, given: &Given) -> i32 {
    match cli.command {
        Some(args::Command::Check(a)) => run::check(&a, given),
        Some(args::Command::Compare(a)) => compare::compare(a, given),
        Some(args::Command::Run(a)) => run::run(&a),
        Some(args::Command::Draw(a)) => draw::draw(&a),
        Some(args::Command::Export(a)) => export::export(&a),
        Some(args::Command::Test(a)) => test::test(a, given),
        Some(args::Command::Serve(a)) => serve::serve(&a, given),
        Some(args::Command::Init(a)) => init::init(&a),
        Some(args::Command::Lsp(a)) => lsp::lsp(&a),
        Some(args::Command::Debug(a)) => debug::debug(&a),
        Some(args::Command::Health(a)) => health::health(&a),
        Some(args::Command::Completions(a)) => completions::completions(&a),
        Some(args::Command::Man(a)) => completions::man(&a),
        #[cfg(feature = "opcua")]
        Some(args::Command::OpcUaUser(a)) => opcua::user(&a),
        None => run::run(&cli.run),
    }
}

fn usage(e: clap::Error) -> i32 {
    let code = if e.use_stderr() { EXIT_USAGE } else { EXIT_OK };
    let _ = e.print();
    code
}
