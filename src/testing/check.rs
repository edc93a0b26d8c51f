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
    Ok(check_with_hosts(sources, &plc_options))
}

/// The warnings of `diags` that point into `sources` (not into the
/// declarations of the assertions).
pub(super) fn warnings_in(diags: &Diagnostics, sources: &SourceMap) -> Diagnostics {
    let mut out = Diagnostics::new();
    let files = sources.files().len();
    for d in diags.iter() {
        if d.severity == Severity::Warning && (d.span.file.0 as usize) < files {
            out.push(d.clone());
        }
    }
    out
}
