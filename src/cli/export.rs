//! The `export` command: textual sources written as PLCopen XML.

use super::args::ExportArgs;
use super::{EXIT_COMPILE, EXIT_OK, EXIT_USAGE};
use plcrun::{Diagnostics, ExportError, export_plcopen, load_files};

/// `plcrun export --plcopen FILES... [-o OUT.xml]`.
pub fn export(args: &ExportArgs) -> i32 {
    let mut diags = Diagnostics::new();
    let sources = match load_files(&args.files, &mut diags) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    if diags.has_errors() {
        eprint!("{}", diags.render(&sources));
        return EXIT_COMPILE;
    }
    let xml = match export_plcopen(&sources) {
        Ok(xml) => xml,
        Err(e @ (ExportError::NotTextual { .. } | ExportError::S7Source { .. })) => {
            eprintln!("error: {e}");
            return EXIT_USAGE;
        }
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_COMPILE;
        }
    };
    match &args.output {
        Some(path) => match std::fs::write(path, xml) {
            Ok(()) => EXIT_OK,
            Err(e) => {
                eprintln!("error: cannot write `{}`: {e}", path.display());
                EXIT_USAGE
            }
        },
        None => {
            print!("{xml}");
            EXIT_OK
        }
    }
}
