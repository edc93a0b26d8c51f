//! Helpers shared by the engine-level tests: compile sources with the
//! embedding API, run cycles, read values as IEC literals.
#![allow(dead_code)]

use plcrun::{Options, Plc};

/// Compiles `files` or panics with the rendered diagnostics.
pub fn compile_files(files: &[(&str, &str)]) -> Plc {
    match Plc::compile_files(files, &Options::default()) {
        Ok(plc) => plc,
        Err(e) => panic!("compile error:\n{e}"),
    }
}

/// Compiles one source text (file name `test.st`).
pub fn compile(src: &str) -> Plc {
    compile_files(&[("test.st", src)])
}

/// Wraps `decls` and `body` in `PROGRAM P VAR decls END_VAR body END_PROGRAM`
/// (after any `prelude`: types, functions, FBs).
pub fn program(prelude: &str, decls: &str, body: &str) -> String {
    format!("{prelude}\nPROGRAM P\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n")
}

/// Runs `cycles` cycles, panicking on a runtime fault.
pub fn run(plc: &mut Plc, cycles: u64) {
    for _ in 0..cycles {
        if let Err(f) = plc.run_cycle() {
            panic!("runtime fault: {f}");
        }
    }
}

/// Reads `name` as an IEC literal.
pub fn lit(plc: &Plc, name: &str) -> String {
    plc.read(name)
        .unwrap_or_else(|e| panic!("read {name}: {e}"))
        .to_literal()
}

/// Compiles a program and runs one cycle; returns the PLC.
pub fn run_once(src: &str) -> Plc {
    let mut plc = compile(src);
    run(&mut plc, 1);
    plc
}

/// The error codes of a failed compilation with their `line:col`, in order.
pub fn error_codes(files: &[(&str, &str)]) -> Vec<(String, String)> {
    match Plc::compile_files(files, &Options::default()) {
        Ok(_) => Vec::new(),
        Err(e) => e
            .diagnostics
            .iter()
            .filter(|d| d.severity == plcrun::Severity::Error)
            .map(|d| {
                let loc = e.sources.location(d.span);
                // `file:line:col` -> `line:col`
                let lc = loc.split_once(':').map(|x| x.1).unwrap_or("").to_string();
                (d.code.to_string(), lc)
            })
            .collect(),
    }
}

/// Runs `src` for up to ten cycles and returns its first runtime fault
/// (panics when none comes).
pub fn first_fault(src: &str) -> plcrun::RuntimeFault {
    let mut plc = compile(src);
    for _ in 0..10 {
        if let Err(f) = plc.run_cycle() {
            return f;
        }
    }
    panic!("no fault in 10 cycles");
}

/// The `line:col` of a `file:line:col` location.
pub fn line_col(location: &str) -> (usize, usize) {
    let mut it = location.rsplitn(3, ':');
    let col = it.next().unwrap().parse().unwrap();
    let line = it.next().unwrap().parse().unwrap();
    (line, col)
}
