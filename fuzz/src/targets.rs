//! The bodies of the fuzz targets, one function per target. Each takes any
//! bytes and must return without panicking; the libFuzzer targets in
//! `fuzz_targets/` and the stable smoke test `tests/fuzz_smoke.rs` call
//! the same functions.

use plcrun::syntax::{lexer, plcopen, s7};
use plcrun::{CheckOptions, Diagnostics, FileId, Options, Plc, SourceMap};
use std::time::Duration;

/// The input as text, as `plcrun` reads a file (invalid UTF-8 replaced).
fn text(data: &[u8]) -> std::borrow::Cow<'_, str> {
    String::from_utf8_lossy(data)
}

/// The lexer (with literal decoding) on any text.
pub fn lex(data: &[u8]) {
    let mut diags = Diagnostics::new();
    let tokens = lexer::lex(FileId(0), &text(data), &mut diags);
    std::hint::black_box(tokens);
}

/// The IEC text parser (ST, IL and SFC share it): lexer, IL line
/// handling, grammar and error recovery.
pub fn parse(data: &[u8]) {
    let mut diags = Diagnostics::new();
    let unit = plcrun::syntax::parse(FileId(0), &text(data), &mut diags);
    std::hint::black_box(unit);
}

/// The PLCopen TC6 XML reader, from bytes.
pub fn plcopen(data: &[u8]) {
    let (unit, diags) = plcopen::parse_bytes(data);
    std::hint::black_box((unit, diags));
}

/// The S7-200 STL reader.
pub fn s7(data: &[u8]) {
    let mut diags = Diagnostics::new();
    let unit = s7::parse(FileId(0), &text(data), &mut diags);
    std::hint::black_box(unit);
}

/// The file name a whole-pipeline input is read as: the first byte picks
/// the front-end the way `plcrun` does from a file name, the rest is the
/// file.
fn named(data: &[u8]) -> (&'static str, &[u8]) {
    match data.split_first() {
        Some((b, rest)) => {
            let name = match b % 4 {
                0 => "fuzz.st",
                1 => "fuzz.il",
                2 => "fuzz.awl",
                _ => "fuzz.xml",
            };
            (name, rest)
        }
        None => ("fuzz.st", data),
    }
}

/// Parse and check (`plcrun check`): every declaration, every body, with
/// the IR built and verified when there is one runnable program, under a
/// 1 MiB data budget.
pub fn check(data: &[u8]) {
    let (name, body) = named(data);
    let mut sources = SourceMap::new();
    sources.add(name, text(body).into_owned());
    let options = CheckOptions {
        ir_listing: true,
        max_data_bytes: 1 << 20,
        ..CheckOptions::default()
    };
    let report = plcrun::check(&sources, &options);
    // Rendering walks every span back into the source.
    std::hint::black_box(report.diagnostics.render(&sources));
}

/// The whole pipeline: compile with a 1 MiB data budget, then run up to
/// three cycles under a 20 ms watchdog, reading every variable after each.
pub fn run(data: &[u8]) {
    let (name, body) = named(data);
    let mut sources = SourceMap::new();
    sources.add(name, text(body).into_owned());
    let options = Options {
        watchdog: Some(Duration::from_millis(20)),
        max_data_bytes: 1 << 20,
        ..Options::default()
    };
    let Ok(mut plc) = Plc::compile(sources, &options) else {
        return;
    };
    for _ in 0..3 {
        let result = plc.run_cycle();
        for v in plc.variables() {
            let _ = std::hint::black_box(plc.read(&v.path).map(|x| x.to_literal()));
        }
        if result.is_err() {
            break;
        }
    }
}

/// A generated, type-correct ST program run optimized and unoptimized,
/// compared cycle by cycle (see [`super::differential::check`]).
pub fn gen_diff(data: &[u8]) {
    let mut u = arbitrary::Unstructured::new(data);
    if let Ok(program) = super::st_gen::generate(&mut u) {
        super::differential::check(&program);
    }
}

/// A generated, type-correct IL program run optimized and unoptimized,
/// compared cycle by cycle (see [`super::il_gen`]).
pub fn gen_il_diff(data: &[u8]) {
    let mut u = arbitrary::Unstructured::new(data);
    if let Ok(program) = super::il_gen::generate(&mut u) {
        super::differential::check(&program);
    }
}
