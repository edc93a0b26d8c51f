//! The sources checked once, with the assertions declared, before any
//! test runs: the errors of every file (as `plcrun check` reports them)
//! stop the run, and the warnings go into the report.

use super::assertions::{self, Log};
use super::tcunit::{self, Plan};
use super::{TestError, TestOptions};
use crate::diagnostics::{Diagnostics, Severity};
use crate::runtime::engine::Options;
use crate::runtime::host_blocks::HostBlocks;
use crate::runtime::host_check::check_with_hosts;
use crate::source::SourceMap;

/// Every diagnostic of `sources` checked as the tests will be compiled.
pub(super) fn check(
    sources: &SourceMap,
    options: &TestOptions,
    suites: &Plan,
) -> Result<Diagnostics, TestError> {
    let mut hosts = HostBlocks::new();
    if suites.suites.is_empty() {
        assertions::register(&mut hosts, &Log::default()).map_err(TestError::Host)?;
    } else {
        tcunit::register(&mut hosts, &Default::default())?;
    }
    // The user's files come first; what plcrun adds follows them.
    let given = sources.files().len();
    let with_base;
    let sources = if suites.add_base {
        with_base = tcunit::sources_for(sources, suites, false);
        &with_base
    } else {
        sources
    };
    let plc_options = Options {
        cycle_time: options.cycle_time,
        strict: options.strict,
        hosts,
        ..Options::default()
    };
    let mut diags = Diagnostics::new();
    // The warnings of what plcrun adds (its TcUnit stand-in) are not the
    // user's, and point into files the user's source map does not hold.
    for d in check_with_hosts(sources, &plc_options).iter() {
        if d.severity == Severity::Error || (d.span.file.0 as usize) < given {
            diags.push(d.clone());
        }
    }
    Ok(diags)
}

/// The warnings of `diags` that point into `sources` (not into the
/// declarations of the assertions), their spans in `given`, the files
/// `sources` were taken from (the same, or more when files were left out).
pub(super) fn warnings_in(
    diags: &Diagnostics,
    sources: &SourceMap,
    given: &SourceMap,
) -> Diagnostics {
    let mut out = Diagnostics::new();
    let files = sources.files();
    let in_given =
        |f: &crate::source::SourceFile| given.files().iter().position(|g| g.name == f.name);
    let ids: Vec<Option<usize>> = files.iter().map(in_given).collect();
    for d in diags.iter() {
        if d.severity != Severity::Warning {
            continue;
        }
        if let Some(Some(id)) = ids.get(d.span.file.0 as usize) {
            let mut d = d.clone();
            d.span.file = crate::source::FileId(*id as u32);
            out.push(d);
        }
    }
    out
}
