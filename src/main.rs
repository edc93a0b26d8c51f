//! The `plcrun` command: run a PLC program against a stimulus and print a
//! trace, or check sources. See `docs/cli.md`.

mod cli;

fn main() {
    std::process::exit(cli::main());
}
