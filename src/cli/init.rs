//! `plcrun init [FILE]`: writes a commented `plcrun.toml` to start a
//! project from (docs/project-file.md). An existing file is kept unless
//! `--force` is given.

use super::{EXIT_OK, EXIT_USAGE};
use clap::Args;
use std::io::Write;
use std::path::PathBuf;

/// The file written: every key, the optional ones commented out.
const TEMPLATE: &str = include_str!("init_template.toml");

/// `plcrun init [FILE] [--force]`.
#[derive(Debug, Args)]
pub struct InitArgs {
    /// Where to write it.
    #[arg(default_value = super::project::DEFAULT_NAME, value_name = "FILE")]
    pub file: PathBuf,
    /// Overwrite an existing file.
    #[arg(long)]
    pub force: bool,
}

/// `plcrun init [FILE]`
pub fn init(args: &InitArgs) -> i32 {
    let path = &args.file;
    let mut options = std::fs::OpenOptions::new();
    options.write(true);
    if args.force {
        options.create(true).truncate(true);
    } else {
        // Refused by the system if the file exists: no race with a check.
        options.create_new(true);
    }
    let written = options
        .open(path)
        .and_then(|mut f| f.write_all(TEMPLATE.as_bytes()));
    match written {
        Ok(()) => {
            sayln!(
                "init: wrote {}; name your sources in `sources`, then `plcrun serve {}`",
                path.display(),
                path.display()
            );
            EXIT_OK
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            sayln!(
                "error: `{}` exists; `plcrun init --force` overwrites it",
                path.display()
            );
            EXIT_USAGE
        }
        Err(e) => {
            sayln!("error: cannot write `{}`: {e}", path.display());
            EXIT_USAGE
        }
    }
}
