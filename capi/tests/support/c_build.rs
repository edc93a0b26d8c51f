//! Compiling C against include/plcrun.h and the static library of this
//! build, for the tests.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root (the workspace, one level above `capi/`).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("capi/ has a parent")
        .to_path_buf()
}

/// A file of the repository, as text.
pub fn repo_text(path: &str) -> String {
    let p = repo_root().join(path);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("read {}: {e}", p.display()))
}

/// The directory of this build's static library: the test executable
/// runs from `<target>/<profile>/deps/`, where cargo writes
/// `libplcrun_capi.a` when it builds the library for this test (with all
/// its crate types). This holds for any target directory and profile, and
/// the library there is always the one this test was built against.
pub fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test executable's path");
    let dir = exe.parent().expect("deps directory").to_path_buf();
    let lib = dir.join("libplcrun_capi.a");
    assert!(
        lib.exists(),
        "{} is missing: run the tests through `cargo test --workspace`",
        lib.display()
    );
    dir
}

/// Compiles the C file `source` (relative to the repository) into an
/// executable named `name` in a fresh temporary directory, linked with
/// the static library; fails the test with the compiler's messages.
pub fn compile(source: &str, name: &str) -> PathBuf {
    let out_dir = std::env::temp_dir().join(format!("plcrun-capi-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&out_dir).expect("create the output directory");
    let exe = out_dir.join(name);
    let root = repo_root();
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
    let result = Command::new(&cc)
        .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "-I"])
        .arg(root.join("include"))
        .arg(root.join(source))
        .arg(library_dir().join("libplcrun_capi.a"))
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&exe)
        .output()
        .unwrap_or_else(|e| panic!("run the C compiler `{cc}` (set CC to choose one): {e}"));
    assert!(
        result.status.success(),
        "{cc} failed on {source}:\n{}",
        String::from_utf8_lossy(&result.stderr)
    );
    exe
}
