//! The `export` command: sources (IL, ST, SFC, PLCopen XML) written as one
//! PLCopen XML project.

use super::args::ExportArgs;
use super::{EXIT_COMPILE, EXIT_OK, EXIT_USAGE};
use plcrun::{CheckOptions, Diagnostics, ExportError, check as check_sources, export_plcopen};

/// `plcrun export --plcopen FILES... [-o OUT.xml]`.
pub fn export(args: &ExportArgs) -> i32 {
    let mut diags = Diagnostics::new();
    let sources = match args.reading.load(&args.files, &mut diags) {
        Ok(s) => s,
        Err(e) => {
            sayln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    // `--strict`: sources that use a compatibility extension (W300-W399)
    // are not exported as IEC 61131-3.
    if args.reading.strict {
        let options = CheckOptions {
            strict: true,
            addressing: args.reading.addressing,
            ..CheckOptions::default()
        };
        diags.extend(check_sources(&sources, &options).diagnostics);
    }
    if !diags.is_empty() {
        say!("{}", diags.render(&sources));
    }
    if diags.has_errors() {
        return EXIT_COMPILE;
    }
    let xml = match export_plcopen(&sources) {
        Ok(xml) => xml,
        Err(e @ (ExportError::NotTextual { .. } | ExportError::S7Source { .. })) => {
            sayln!("error: {e}");
            return EXIT_USAGE;
        }
        Err(e) => {
            sayln!("error: {e}");
            return EXIT_COMPILE;
        }
    };
    match &args.output {
        Some(path) => match std::fs::write(path, xml) {
            Ok(()) => EXIT_OK,
            Err(e) => {
                sayln!("error: cannot write `{}`: {e}", path.display());
                EXIT_USAGE
            }
        },
        None => {
            print!("{xml}");
            EXIT_OK
        }
    }
}
