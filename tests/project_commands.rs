//! `plcrun check`, `test` and `compare` given no source read the project
//! file's (`--project FILE`, else `./plcrun.toml` in the current folder),
//! with its reading settings unless the command line gives them.

use crate::support::cli;

use cli::{plcrun, temp_file};
use std::path::{Path, PathBuf};
use std::process::Command;

const COUNTER: &str =
    "FUNCTION_BLOCK Counter VAR_OUTPUT n : INT; END_VAR n := n + 1; END_FUNCTION_BLOCK
PROGRAM Count VAR c : Counter; END_VAR VAR_OUTPUT n : INT; END_VAR c(); n := c.n; END_PROGRAM
";
const COUNTER_TEST: &str = "PROGRAM TEST_counts
VAR c : Counter; END_VAR
c(); c();
AssertEquals(2, c.n, 'two calls count two');
END_PROGRAM
";

/// A fresh folder holding `files`.
fn project(files: &[(&str, &[u8])]) -> PathBuf {
    let dir = Path::new(&temp_file(".keep", ""))
        .parent()
        .unwrap()
        .to_path_buf();
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    dir
}

/// `plcrun ARGS...` run in `dir`.
fn plcrun_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("plcrun runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn check_reads_the_project_file_of_the_current_folder_or_the_one_named() {
    let dir = project(&[
        ("count.st", COUNTER.as_bytes()),
        (
            "main.st",
            b"PROGRAM Main VAR c : Counter; END_VAR c(); END_PROGRAM\n",
        ),
        (
            "plcrun.toml",
            b"sources = [\"*.st\"]\nprogram = \"Count\"\n",
        ),
    ]);
    let (code, _, err) = plcrun_in(&dir, &["check"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("ok: 2 files checked"), "{err}");
    let file = dir.join("plcrun.toml");
    let (code, _, err) = plcrun(&["check", "--project", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    // Sources and --project together are refused.
    let (code, _, _) = plcrun(&[
        "check",
        "programs/alg01.il",
        "--project",
        file.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    // A folder without one.
    let empty = project(&[]);
    let (code, _, err) = plcrun_in(&empty, &["check"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with("error[E970]: cannot read the project file"),
        "{err}"
    );
}

#[test]
fn check_reports_errors_of_the_project_file_itself() {
    let dir = project(&[
        ("count.st", COUNTER.as_bytes()),
        ("plcrun.toml", b"sources = [\"count.st\"]\ncycle_time = 5\n"),
    ]);
    let (code, _, err) = plcrun_in(&dir, &["check"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with("error[E973]: `cycle_time`: invalid type"),
        "{err}"
    );
    assert!(err.contains("--> plcrun.toml:2:14"), "{err}");
}

#[test]
fn the_encoding_of_the_file_is_used_unless_the_command_line_gives_one() {
    // A Latin-1 é in a comment: read as latin-1 it is plain text; detected,
    // it is Windows-1252 with warning W020; as UTF-8 it is error E011.
    let mut source = b"(* caf\xe9 *)\n".to_vec();
    source.extend_from_slice(COUNTER.as_bytes());
    let dir = project(&[
        ("count.st", &source),
        (
            "plcrun.toml",
            b"sources = [\"count.st\"]\nencoding = \"latin-1\"\n",
        ),
    ]);
    let (code, _, err) = plcrun_in(&dir, &["check"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("W020"), "{err}");
    let (code, _, err) = plcrun_in(&dir, &["check", "--encoding", "utf-8"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E011"), "{err}");
}

#[test]
fn test_runs_the_tests_among_the_project_sources() {
    let dir = project(&[
        ("count.st", COUNTER.as_bytes()),
        ("tests.st", COUNTER_TEST.as_bytes()),
        ("plcrun.toml", b"sources = [\"count.st\", \"tests.st\"]\n"),
    ]);
    let (code, out, err) = plcrun_in(&dir, &["test"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("TEST_counts"), "{out}");
    let file = dir.join("plcrun.toml");
    let (code, out, err) = plcrun(&["test", "--project", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn compare_takes_program_a_from_the_project() {
    let dir = project(&[
        ("count.st", COUNTER.as_bytes()),
        (
            "other.st",
            b"PROGRAM Count VAR_OUTPUT n : INT; END_VAR n := 1 + n; END_PROGRAM\n" as &[u8],
        ),
        ("plcrun.toml", b"sources = [\"count.st\"]\n"),
    ]);
    let (code, out, err) = plcrun_in(
        &dir,
        &[
            "compare", "--", "other.st", "--cycles", "20", "--random", "1",
        ],
    );
    assert_eq!(code, 0, "{out}{err}");
}
