//! The C examples in examples/c/, each compiled with the system C compiler
//! against include/plcrun.h (every warning an error) and the static
//! library that this test run built, then run: its output must be exactly
//! the example's `.expected` file.

#[path = "support/c_build.rs"]
mod c_build;

use std::process::Command;

/// Compiles and runs examples/c/`name`.c and compares its output.
fn run_example(name: &str) {
    let exe = c_build::compile(&format!("examples/c/{name}.c"), name);
    let run = Command::new(&exe).output().expect("run the C example");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "the C example {name} failed ({}):\n{stdout}\n{}",
        run.status,
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        stdout,
        c_build::repo_text(&format!("examples/c/{name}.expected"))
    );
}

#[test]
fn the_c_example_compiles_without_warnings_and_prints_what_is_expected() {
    run_example("counter");
}

#[test]
fn the_process_image_and_forcing_example_prints_what_is_expected() {
    run_example("io_force");
}
