//! Command-line front end. Exit status: 0 ok, 1 compile errors, 2 usage
//! errors, 3 runtime fault.

mod args;
mod load;
mod run;

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
    let argv: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let is_check = argv.get(1).is_some_and(|a| a == "check");
    if is_check {
        let mut rest = vec![argv[0].clone()];
        rest.extend(argv[2..].iter().cloned());
        match args::CheckArgs::try_parse_from(rest) {
            Ok(a) => run::check(&a),
            Err(e) => usage(e),
        }
    } else {
        match args::RunArgs::try_parse_from(argv) {
            Ok(a) => run::run(&a),
            Err(e) => usage(e),
        }
    }
}

fn usage(e: clap::Error) -> i32 {
    let code = if e.use_stderr() { EXIT_USAGE } else { EXIT_OK };
    let _ = e.print();
    code
}
