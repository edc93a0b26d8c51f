//! Checking sources with the host POUs of [`Options::hosts`] declared, as
//! `plcrun check` checks them: every diagnostic of every file (syntax and
//! checker), without requiring or building a runnable program. `plcrun
//! test` uses it to report the sources' problems — and warnings such as a
//! POU hiding one of its assertions — once, before running any test.

use super::engine::Options;
use super::host_blocks::HOST_SOURCE;
use crate::diagnostics::Diagnostics;
use crate::driver;
use crate::source::SourceMap;

/// Every diagnostic of `sources` checked with `options` (its host POUs
/// declared in a source of their own, after `sources`).
pub(crate) fn check_with_hosts(sources: &SourceMap, options: &Options) -> Diagnostics {
    let mut sources = sources.clone();
    if !options.hosts.is_empty() {
        sources.add(HOST_SOURCE, options.hosts.declarations());
    }
    crate::driver::twincat_library::add_library(&mut sources);
    let build = options.compile_options(&sources, true);
    let mut diags = Diagnostics::new();
    driver::compile(&sources, &build, &mut diags);
    diags
}
