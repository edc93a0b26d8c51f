//! Runs the real `plcrun` binary on a source text (written to a temporary
//! file) or a repository file, and returns its CSV trace or its diagnostics.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// A fresh temporary directory for one test's files.
pub fn scratch_dir() -> PathBuf {
    let n = COUNTER.fetch_add(1, Ordering::SeqCst);
    let dir = std::env::temp_dir().join(format!("plcrun-sfc-{}-{n}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// Path of a repository file.
pub fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// Output of one run.
pub struct Run {
    /// Exit status code.
    pub code: i32,
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
}

/// Runs plcrun with `args`.
pub fn plcrun(args: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .args(args)
        .output()
        .expect("plcrun binary runs");
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// Writes `text` to a temporary file named `name` and returns its path.
pub fn write_temp(name: &str, text: &str) -> String {
    let path = scratch_dir().join(name);
    std::fs::write(&path, text).expect("temp file");
    path.to_string_lossy().into_owned()
}

/// Runs a source text for `cycles` cycles with an optional stimulus text,
/// tracing `trace`; returns the CSV trace (panics with the diagnostics if
/// the run fails).
pub fn trace_src(src: &str, stimulus: Option<&str>, cycles: u64, trace: &str) -> String {
    let file = write_temp("prog.st", src);
    let stim = stimulus.map(|s| write_temp("stim.csv", s));
    let n = cycles.to_string();
    let mut args = vec![
        file.as_str(),
        "--cycles",
        &n,
        "--trace",
        trace,
        "--format",
        "csv",
    ];
    if let Some(s) = &stim {
        args.push("--stimulus");
        args.push(s);
    }
    let r = plcrun(&args);
    assert_eq!(r.code, 0, "plcrun failed:\n{}\n{}", r.stderr, r.stdout);
    r.stdout
}

/// Checks a source text (`plcrun check`) and returns the exit code and
/// everything printed (the diagnostics).
pub fn diagnostics(src: &str) -> (i32, String) {
    let file = write_temp("prog.st", src);
    let r = plcrun(&["check", file.as_str()]);
    (r.code, format!("{}{}", r.stderr, r.stdout))
}

/// The rows of a CSV trace without the header, each split into cells.
pub fn rows(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// One column of a CSV trace (by header name), one entry per row.
pub fn column(csv: &str, name: &str) -> Vec<String> {
    let header: Vec<&str> = csv.lines().next().unwrap_or("").split(',').collect();
    let k = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows(csv).into_iter().map(|r| r[k].clone()).collect()
}

/// A BOOL column as a string of `1`/`0`, one character per cycle.
pub fn bits(csv: &str, name: &str) -> String {
    column(csv, name)
        .iter()
        .map(|v| match v.as_str() {
            "TRUE" => '1',
            "FALSE" => '0',
            other => panic!("{name}: not a BOOL: {other}"),
        })
        .collect()
}

/// A cycle-keyed stimulus CSV with one row per cycle, from per-input bit
/// strings (`"0011"`: FALSE in cycles 0-1, TRUE in 2-3; missing cycles FALSE).
pub fn stimulus(inputs: &[(&str, &str)]) -> String {
    let n = inputs.iter().map(|(_, b)| b.len()).max().unwrap_or(0);
    let mut s = String::from("cycle");
    for (name, _) in inputs {
        s.push(',');
        s.push_str(name);
    }
    s.push('\n');
    for k in 0..n {
        s.push_str(&k.to_string());
        for (_, b) in inputs {
            let v = b.as_bytes().get(k).copied().unwrap_or(b'0');
            s.push_str(if v == b'1' { ",TRUE" } else { ",FALSE" });
        }
        s.push('\n');
    }
    s
}
