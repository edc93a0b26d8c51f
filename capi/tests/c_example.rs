//! examples/c/counter.c, compiled with the system C compiler against
//! include/plcrun.h (every warning an error) and the static library that
//! this test run built, then run: its output must be exactly
//! examples/c/counter.expected.

#[path = "support/c_build.rs"]
mod c_build;

use std::process::Command;

#[test]
fn the_c_example_compiles_without_warnings_and_prints_what_is_expected() {
    let exe = c_build::compile("examples/c/counter.c", "counter");
    let run = Command::new(&exe).output().expect("run the C example");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "the C example failed ({}):\n{stdout}\n{}",
        run.status,
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(stdout, c_build::repo_text("examples/c/counter.expected"));
}
