//! Diagnostics of a one-file compile as `(code, line:col)` pairs, warnings
//! included (used by the access tests: partial access, FB internals, input
//! writes, input qualifiers).

#![allow(dead_code)]

use plcrun::{Diagnostics, Options, Plc, Severity};

/// Every diagnostic of compiling `src`, as `(code, severity, "line:col")`.
pub fn diags(src: &str) -> Vec<(String, Severity, String)> {
    let collect = |d: &Diagnostics, sources: &plcrun::SourceMap| {
        d.iter()
            .map(|d| {
                let loc = sources.location(d.span);
                let lc = loc.split_once(':').map(|x| x.1).unwrap_or("").to_string();
                (d.code.to_string(), d.severity, lc)
            })
            .collect::<Vec<_>>()
    };
    match Plc::compile_files(&[("t.st", src)], &Options::default()) {
        Ok(p) => collect(p.warnings(), p.sources()),
        Err(e) => collect(&e.diagnostics, &e.sources),
    }
}

/// The diagnostics of `src` as `CODE@line:col` strings.
pub fn codes_at(src: &str) -> Vec<String> {
    diags(src)
        .into_iter()
        .map(|(c, _, at)| format!("{c}@{at}"))
        .collect()
}

/// The codes of the errors of `src` (warnings left out).
pub fn error_codes(src: &str) -> Vec<String> {
    diags(src)
        .into_iter()
        .filter(|d| d.1 == Severity::Error)
        .map(|d| d.0)
        .collect()
}
