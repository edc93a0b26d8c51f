//! `plcrun --realtime --reload`: a rewritten source file is loaded into the
//! running PLC by online change, its variables carried over; a version that
//! does not compile is refused with its diagnostics and the program runs on.

use crate::support::cli;

use cli::{plcrun, temp_file};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const COUNT_BY_1: &str = "PROGRAM P VAR_OUTPUT n : DINT; END_VAR n := n + 1; END_PROGRAM\n";
const COUNT_BY_100: &str = "PROGRAM P VAR_OUTPUT n : DINT; END_VAR n := n + 100; END_PROGRAM\n";
const BROKEN: &str = "PROGRAM P VAR_OUTPUT n : DINT; END_VAR n := n + ; END_PROGRAM\n";

/// Starts `plcrun SRC --realtime --reload --trace n`, the trace and the
/// standard error going to files next to the source.
fn start(src: &str) -> Child {
    let dir = Path::new(src).parent().expect("a directory");
    let out = std::fs::File::create(dir.join("trace.csv")).expect("trace file");
    let err = std::fs::File::create(dir.join("stderr.txt")).expect("stderr file");
    Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .args([
            src,
            "--realtime",
            "--reload",
            "--trace",
            "n",
            "--format",
            "csv",
        ])
        .stdout(Stdio::from(out))
        .stderr(Stdio::from(err))
        .spawn()
        .expect("plcrun starts")
}

/// Replaces the file at once (write aside, rename), as editors do.
fn rewrite(src: &str, text: &str) {
    let aside = format!("{src}.new");
    std::fs::write(&aside, text).expect("write");
    std::fs::rename(&aside, src).expect("rename");
}

fn read(src: &str, name: &str) -> String {
    let path = Path::new(src).parent().expect("a directory").join(name);
    std::fs::read_to_string(path).unwrap_or_default()
}

/// Waits (at most 20 s) until `done` holds for the file `name` next to `src`.
fn wait_for(src: &str, name: &str, done: impl Fn(&str) -> bool) -> bool {
    let deadline = Instant::now() + Duration::from_secs(20);
    while Instant::now() < deadline {
        if done(&read(src, name)) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    false
}

/// Trace rows (complete lines only) after the header.
fn rows(trace: &str) -> usize {
    trace.matches('\n').count().saturating_sub(1)
}

/// Stops the run with SIGTERM and returns its exit status, the values of
/// `n` row by row and the standard error.
fn stop(mut child: Child, src: &str) -> (Option<i32>, Vec<i64>, String) {
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
    let code = child.wait().expect("plcrun ends").code();
    let trace = read(src, "trace.csv");
    let mut lines = trace.lines();
    assert_eq!(lines.next(), Some("cycle,time,n"), "{trace}");
    let n = lines
        .map(|l| l.rsplit(',').next().unwrap().parse().expect("n is a DINT"))
        .collect();
    (code, n, read(src, "stderr.txt"))
}

fn steps(n: &[i64]) -> Vec<i64> {
    n.windows(2).map(|w| w[1] - w[0]).collect()
}

#[test]
fn a_rewritten_source_is_loaded_and_n_keeps_its_value() {
    let src = temp_file("count.st", COUNT_BY_1);
    let child = start(&src);
    assert!(wait_for(&src, "trace.csv", |t| rows(t) >= 30), "no trace");
    rewrite(&src, COUNT_BY_100);
    let loaded = wait_for(&src, "stderr.txt", |e| e.contains("new version loaded"));
    let at = rows(&read(&src, "trace.csv"));
    let ran_on = wait_for(&src, "trace.csv", |t| rows(t) >= at + 20);
    let (code, n, stderr) = stop(child, &src);
    assert!(loaded && ran_on, "{stderr}");
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("kept P"), "{stderr}");
    // Counting by 1, then by 100 from where it was: n carried over (a
    // restart would have started again from 100).
    let steps = steps(&n);
    let switch = steps
        .iter()
        .position(|d| *d == 100)
        .expect("the new version ran");
    assert!(switch >= 29, "{steps:?}");
    assert!(steps[..switch].iter().all(|d| *d == 1), "{steps:?}");
    assert!(steps[switch..].iter().all(|d| *d == 100), "{steps:?}");
    assert_eq!(n[0], 1);
}

#[test]
fn a_version_that_does_not_compile_is_refused_and_the_program_runs_on() {
    let src = temp_file("count.st", COUNT_BY_1);
    let child = start(&src);
    assert!(wait_for(&src, "trace.csv", |t| rows(t) >= 30), "no trace");
    rewrite(&src, BROKEN);
    let refused = wait_for(&src, "stderr.txt", |e| e.contains("refused"));
    let at = rows(&read(&src, "trace.csv"));
    let ran_on = wait_for(&src, "trace.csv", |t| rows(t) >= at + 20);
    let (code, n, stderr) = stop(child, &src);
    assert!(refused && ran_on, "{stderr}");
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("error[E"), "{stderr}");
    assert!(stderr.contains("count.st:1:"), "{stderr}");
    assert!(stderr.contains("the program runs on"), "{stderr}");
    // The old version counted on, one by one, through and after the refusal.
    assert!(n.len() >= 50, "{n:?}");
    assert!(steps(&n).iter().all(|d| *d == 1), "{n:?}");
}

#[test]
fn reload_needs_realtime() {
    let src = temp_file("count.st", COUNT_BY_1);
    let (code, _, stderr) = plcrun(&[&src, "--cycles", "3", "--reload"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("--reload") && stderr.contains("--realtime"),
        "{stderr}"
    );
}
