//! `plcrun completions SHELL` and `plcrun man [DIR]`: the shell completion
//! script and the manual pages, generated from the command line's own
//! definition (packages install them: docs/install.md).

use super::args::Cli;
use super::{EXIT_OK, EXIT_USAGE};
use clap::{Args, CommandFactory};
use std::path::PathBuf;

/// `plcrun completions SHELL`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// bash, zsh, fish, elvish or powershell.
    pub shell: clap_complete::Shell,
}

/// `plcrun man [DIR]`.
#[derive(Debug, Args)]
pub struct ManArgs {
    /// Write plcrun.1 and one page per subcommand (plcrun-run.1...) into
    /// DIR; without it, print plcrun.1 on standard output.
    #[arg(value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

/// Prints the completion script for `args.shell`.
pub fn completions(args: &CompletionsArgs) -> i32 {
    let mut command = Cli::command();
    clap_complete::generate(args.shell, &mut command, "plcrun", &mut std::io::stdout());
    EXIT_OK
}

/// Writes the manual pages.
pub fn man(args: &ManArgs) -> i32 {
    let command = Cli::command();
    let Some(dir) = &args.dir else {
        return match clap_mangen::Man::new(command).render(&mut std::io::stdout()) {
            Ok(()) => EXIT_OK,
            Err(e) => {
                sayln!("error: cannot write the manual page: {e}");
                EXIT_USAGE
            }
        };
    };
    let written =
        std::fs::create_dir_all(dir).and_then(|()| clap_mangen::generate_to(command, dir));
    match written {
        Ok(()) => EXIT_OK,
        Err(e) => {
            sayln!(
                "error: cannot write the manual pages into {}: {e}",
                dir.display()
            );
            EXIT_USAGE
        }
    }
}
