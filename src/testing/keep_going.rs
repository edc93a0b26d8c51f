//! `plcrun test --keep-going`: the files that do not compile are left out,
//! then the files that no longer compile without them, until what is left
//! compiles; the tests declared in the files left out are reported as
//! errors (with the first error of their file), the others run. A TwinCAT
//! library that references a library plcrun does not have (Beckhoff's
//! compiled `Tc2_SerialCom`, say) still runs the suites that do not need it. In
//! a global variable list only the variables whose declarations fail are
//! left out (`blank_globals.rs`).

use super::blank_globals::blank_global_declarations;
use super::check;
use super::discover::Found;
use super::tcunit::Plan;
use super::{TestCase, TestError, TestOptions};
use crate::diagnostics::{Diagnostics, Severity};
use crate::source::{FileId, SourceMap, Span};
use std::collections::{HashMap, HashSet};
use std::time::Duration;

/// The sources that compile, and why the others were left out.
pub(super) struct Kept {
    /// The files that compile (with what they need), in the given order.
    pub(super) sources: SourceMap,
    /// The check of `sources`: their warnings.
    pub(super) checked: Diagnostics,
    /// Each file left out, by name: its first error (`code: message at
    /// file:line:col`), or the file it needed.
    pub(super) left_out: HashMap<String, String>,
    /// Each global variable left out of its list, as `file, global
    /// `name``, with its first error, in the order left out.
    pub(super) left_out_globals: Vec<(String, String)>,
}

/// Leaves out, round after round, the files of `sources` with errors,
/// checking the rest with the suites of `plan` and the tests `found` that
/// remain; `checked` is the first round's check. An error in none of the
/// given files (in the runner's own declarations) stops as before.
pub(super) fn leave_out_broken(
    sources: &SourceMap,
    options: &TestOptions,
    plan: &Plan,
    mut checked: Diagnostics,
) -> Result<Kept, TestError> {
    let mut kept = sources.clone();
    let mut left_out: HashMap<String, String> = HashMap::new();
    let mut left_out_globals: Vec<(String, String)> = Vec::new();
    while checked.has_errors() {
        let files = kept.files().len();
        let mut first: HashMap<FileId, String> = HashMap::new();
        let mut errors: HashMap<FileId, Vec<Span>> = HashMap::new();
        for d in checked.iter().filter(|d| d.severity == Severity::Error) {
            if (d.span.file.0 as usize) < files {
                first.entry(d.span.file).or_insert_with(|| {
                    format!("{}: {} at {}", d.code, d.message, kept.location(d.span))
                });
                errors.entry(d.span.file).or_default().push(d.span);
            }
        }
        if first.is_empty() {
            return Err(TestError::Compile(crate::runtime::engine::CompileError {
                diagnostics: checked,
                sources: kept,
            }));
        }
        let mut drop: HashSet<FileId> = HashSet::new();
        let mut ids: Vec<FileId> = first.keys().copied().collect();
        ids.sort_by_key(|id| id.0);
        for id in ids {
            let why = first.remove(&id).unwrap_or_default();
            let name = kept.file(id).name.clone();
            let spans = errors.remove(&id).unwrap_or_default();
            match blank_global_declarations(id, kept.file(id), &spans) {
                Some(blanked) => {
                    for global in &blanked.names {
                        left_out_globals.push((format!("{name}, global `{global}`"), why.clone()));
                    }
                    kept = kept.with_text(id, blanked.text);
                }
                None => {
                    left_out.insert(name, why);
                    drop.insert(id);
                }
            }
        }
        kept = kept.without(&drop);
        checked = check::check(&kept, options, &remaining(plan, &kept))?;
    }
    Ok(Kept {
        sources: kept,
        checked,
        left_out,
        left_out_globals,
    })
}

/// `plan` with the suites whose block is declared in a file of `sources`.
pub(super) fn remaining(plan: &Plan, sources: &SourceMap) -> Plan {
    let names: HashSet<&str> = sources.files().iter().map(|f| f.name.as_str()).collect();
    Plan {
        suites: plan
            .suites
            .iter()
            .filter(|s| names.contains(s.file.as_str()))
            .cloned()
            .collect(),
        ..plan.clone()
    }
}

/// One errored case per test of `tests` and suite of `plan` declared in
/// a file of `left_out`, named as it would have been, with the reason.
pub(super) fn left_out_cases(
    tests: &[Found],
    plan: &Plan,
    left_out: &HashMap<String, String>,
) -> Vec<TestCase> {
    let case = |name: &str, file: &str| {
        left_out.get(file).map(|why| TestCase {
            name: name.to_string(),
            suite: None,
            file: file.to_string(),
            cycles: 0,
            elapsed: Duration::ZERO,
            failures: Vec::new(),
            more_failures: 0,
            fault: None,
            unfinished: false,
            assertions: 0,
            output: Vec::new(),
            left_out: Some(format!("not run: its file does not compile ({why})")),
            skipped: false,
        })
    };
    let from_tests = tests.iter().filter_map(|t| case(&t.name, &t.file));
    let from_suites = plan.suites.iter().filter_map(|s| case(&s.path, &s.file));
    from_tests.chain(from_suites).collect()
}
