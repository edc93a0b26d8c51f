//! Every input the fuzzer found a crash with, run again through the same
//! target body: `tests/fuzz_regressions/TARGET/NAME` is fed to the target
//! `TARGET` of `fuzz/src/targets.rs` (included as it is), which must
//! return without panicking. scripts/fuzz.sh leaves crashes in
//! fuzz/artifacts/TARGET/; copy each here with a name saying what it was.

use crate::fuzz::targets;

use std::path::Path;

/// The target body named `name`.
fn target(name: &str) -> Option<fn(&[u8])> {
    Some(match name {
        "lex" => targets::lex,
        "parse" => targets::parse,
        "plcopen" => targets::plcopen,
        "s7" => targets::s7,
        "check" => targets::check,
        "run" => targets::run,
        "gen_diff" => targets::gen_diff,
        "gen_il_diff" => targets::gen_il_diff,
        _ => return None,
    })
}

#[test]
fn every_recorded_crash_input_is_handled() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let mut inputs = 0;
    for entry in std::fs::read_dir(&dir).expect("tests/fuzz_regressions") {
        let sub = entry.expect("directory entry").path();
        if !sub.is_dir() {
            continue;
        }
        let name = sub.file_name().and_then(|n| n.to_str()).unwrap_or("");
        let run = target(name).unwrap_or_else(|| panic!("{}: no such fuzz target", sub.display()));
        let mut files: Vec<_> = std::fs::read_dir(&sub)
            .expect("target directory")
            .map(|e| e.expect("file").path())
            .collect();
        files.sort();
        for file in files {
            let bytes = std::fs::read(&file).expect("regression input");
            let outcome = std::panic::catch_unwind(|| run(&bytes));
            assert!(outcome.is_ok(), "{} crashes again", file.display());
            inputs += 1;
        }
    }
    eprintln!("{inputs} recorded inputs handled");
}
