//! Runs the real `plcrun` binary, for the tests about the command line
//! itself: exit statuses, option parsing, what it prints on standard error,
//! the files it writes, and a few end-to-end runs that keep the whole path
//! from arguments to printed trace covered. Tests that only need a trace
//! or diagnostics call the library instead (`support/session.rs`,
//! `plcrun::check`).
#![allow(dead_code)]

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Runs `plcrun` with `args` from the repository root (so repository paths
/// such as `programs/alg01.il` can be given as they are) and returns its
/// exit code (-1 when killed by a signal), standard output and standard
/// error.
pub fn plcrun(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("the plcrun binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs `plcrun` and expects exit status 0; returns standard output.
pub fn plcrun_ok(args: &[&str]) -> String {
    let (code, out, err) = plcrun(args);
    assert_eq!(code, 0, "plcrun {args:?}\n{err}");
    out
}

/// Writes `contents` to a file called `name` in a directory of its own and
/// returns its path. Every call gets a fresh directory: tests run in
/// parallel and often use the same file names.
pub fn temp_file(name: &str, contents: impl AsRef<[u8]>) -> String {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir: PathBuf = std::env::temp_dir().join(format!("plcrun-test-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create a temporary directory");
    let path = dir.join(name);
    std::fs::write(&path, contents).expect("write a temporary file");
    path.to_string_lossy().into_owned()
}

/// Writes `files` (path inside the folder, contents) into a fresh folder
/// and returns the folder: a project laid out on disk.
pub fn temp_project(files: &[(&str, &str)]) -> String {
    let marker = temp_file(".project", "");
    let dir = std::path::Path::new(&marker)
        .parent()
        .unwrap()
        .to_path_buf();
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
    }
    dir.to_string_lossy().into_owned()
}

/// The address a `plcrun --modbus ADDR:0` child listens on, read from the
/// first line of its standard error (piped); the rest of standard error is
/// drained on a thread so that the child never blocks writing it.
pub fn modbus_address(child: &mut Child) -> String {
    let mut err = BufReader::new(child.stderr.take().expect("standard error is piped"));
    let mut line = String::new();
    err.read_line(&mut line).unwrap();
    let addr = line
        .trim()
        .strip_prefix("modbus: listening on ")
        .unwrap_or_else(|| panic!("unexpected first line: {line:?}"))
        .to_string();
    std::thread::spawn(move || std::io::copy(&mut err, &mut std::io::sink()));
    addr
}
