//! Command-line front end: a thin driver over the library's public API.
//! Exit status: 0 ok, 1 compile errors, 2 usage errors, 3 runtime fault.

mod args;
mod compare;
mod draw;
mod export;
mod modbus;
mod online;
#[cfg(feature = "opcua")]
mod opcua;
mod reload;
mod retain;
mod run;
mod test;

use clap::Parser;

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
    match args::Cli::try_parse_from(compare::reorder(std::env::args_os().collect())) {
        Ok(cli) => match cli.command {
            Some(args::Command::Check(a)) => run::check(&a),
            Some(args::Command::Compare(a)) => compare::compare(&a),
            Some(args::Command::Run(a)) => run::run(&a),
            Some(args::Command::Draw(a)) => draw::draw(&a),
            Some(args::Command::Export(a)) => export::export(&a),
            Some(args::Command::Test(a)) => test::test(&a),
            #[cfg(feature = "opcua")]
            Some(args::Command::OpcUaUser(a)) => opcua::user(&a),
            None => run::run(&cli.run),
        },
        Err(e) => usage(e),
    }
}

fn usage(e: clap::Error) -> i32 {
    let code = if e.use_stderr() { EXIT_USAGE } else { EXIT_OK };
    let _ = e.print();
    code
}
