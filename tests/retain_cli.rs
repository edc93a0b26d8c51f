//! `--retain FILE` on the command line: warm and cold starts, the messages
//! for missing, damaged and mismatching files, and the kill -9 loop — a
//! running plcrun saving every cycle is killed at random moments, and
//! every time the file left behind must parse, fit the program and hold a
//! counter that never went backwards and was never torn.

use crate::support::cli;
use crate::support::rng;

use cli::{plcrun, plcrun_ok, temp_file};
use plcrun::{Options, Plc, RestoreMode};
use std::process::{Command, Stdio};
use std::time::Duration;

const COUNTER: &str = "
PROGRAM P
VAR RETAIN n : DINT; copies : ARRAY[1..64] OF DINT; text : STRING[16]; END_VAR
VAR i : INT; END_VAR
VAR_OUTPUT out : DINT; END_VAR
n := n + 1;
FOR i := 1 TO 64 DO copies[i] := n; END_FOR;
text := DINT_TO_STRING(n);
out := n;
END_PROGRAM
";

/// The counter the retain file at `path` holds, after checking that the
/// file fits the program and is consistent (every copy and the text agree).
fn saved_counter(path: &str) -> i64 {
    let mut plc = Plc::compile_files(&[("c.st", COUNTER)], &Options::default()).unwrap();
    let report = plc
        .restore_retain(path, RestoreMode::Exact)
        .unwrap_or_else(|e| panic!("{e}\n{}", std::fs::read_to_string(path).unwrap_or_default()));
    assert_eq!(report.restored, 66);
    let n = plc.read_i64("n").unwrap();
    for i in 1..=64 {
        assert_eq!(
            plc.read_i64(&format!("copies[{i}]")).unwrap(),
            n,
            "torn at copies[{i}]"
        );
    }
    assert_eq!(
        plc.read("text").unwrap().as_str(),
        Some(n.to_string().as_str())
    );
    n
}

#[test]
fn a_run_is_continued_from_its_retain_file_and_a_missing_file_is_a_cold_start() {
    let src = temp_file("c.st", COUNTER);
    let retain = temp_file("r.json", "");
    std::fs::remove_file(&retain).unwrap();
    let (code, out, err) = plcrun(&[&src, "--cycles", "3", "--retain", &retain]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("cold start: retain file") && err.contains("does not exist"),
        "{err}"
    );
    assert!(out.ends_with("2,T#20ms,3\n"), "{out}");
    assert_eq!(saved_counter(&retain), 3);

    let (code, out, err) = plcrun(&[&src, "--cycles", "2", "--retain", &retain]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warm start: 66 retained values restored"),
        "{err}"
    );
    assert_eq!(out, "cycle,time,out\n0,T#0s,4\n1,T#10ms,5\n");

    let (code, out, err) = plcrun(&[&src, "--cycles", "1", "--retain", &retain, "--cold"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("cold start"), "{err}");
    assert_eq!(out, "cycle,time,out\n0,T#0s,1\n");
    assert_eq!(saved_counter(&retain), 1, "overwritten at the save");
}

#[test]
fn retain_every_saves_periodically_and_needs_retain() {
    let src = temp_file("c.st", COUNTER);
    let (code, _, err) = plcrun(&[&src, "--cycles", "3", "--retain-every", "2"]);
    assert_eq!(code, 2, "{err}");
    let retain = temp_file("r.json", "");
    std::fs::remove_file(&retain).unwrap();
    let (code, _, err) = plcrun(&[
        &src,
        "--cycles",
        "3",
        "--retain",
        &retain,
        "--retain-every",
        "0",
    ]);
    assert_eq!(code, 2, "{err}");
    plcrun_ok(&[
        &src,
        "--cycles",
        "7",
        "--retain",
        &retain,
        "--retain-every",
        "3",
    ]);
    assert_eq!(saved_counter(&retain), 7);
}

#[test]
fn a_damaged_or_mismatching_file_stops_the_run_with_a_clear_message() {
    let src = temp_file("c.st", COUNTER);
    let damaged = temp_file("r.json", "{\"format\": \"plcrun-retain\",");
    let (code, out, err) = plcrun(&[&src, "--cycles", "3", "--retain", &damaged]);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty());
    assert!(
        err.contains(&format!("error: retain file `{damaged}` line 1")),
        "{err}"
    );

    let other = temp_file(
        "o.st",
        "PROGRAM P VAR RETAIN n : INT; extra : BOOL; END_VAR n := n + 1; END_PROGRAM",
    );
    let retain = temp_file("r.json", "");
    std::fs::remove_file(&retain).unwrap();
    plcrun_ok(&[&other, "--cycles", "5", "--retain", &retain]);
    let (code, _, err) = plcrun(&[&src, "--cycles", "1", "--retain", &retain]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("does not fit this program"), "{err}");
    assert!(
        err.contains("changed type: P.n (file INT, program DINT)"),
        "{err}"
    );
    assert!(err.contains("P.extra"), "{err}");
    assert!(err.contains("--retain-partial"), "{err}");

    let (code, out, err) = plcrun(&[
        &src,
        "--cycles",
        "1",
        "--retain",
        &retain,
        "--retain-partial",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warm start: 0 retained values restored"),
        "{err}"
    );
    assert!(err.contains("not restored:"), "{err}");
    assert_eq!(out, "cycle,time,out\n0,T#0s,1\n");
}

#[test]
fn a_retain_file_that_cannot_be_written_is_reported_before_the_run() {
    let src = temp_file("c.st", COUNTER);
    let dir = temp_file("x", "");
    let retain = format!("{dir}.d/missing/r.json");
    let (code, out, err) = plcrun(&[&src, "--cycles", "3", "--retain", &retain]);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains(&format!("error: cannot write retain file `{retain}`")),
        "{err}"
    );
}

/// 50 runs, each killed with SIGKILL at a random moment while it saves
/// every cycle; each restart continues from the file the previous run
/// left. The file must always be complete and the counter never go back.
#[cfg(unix)]
#[test]
fn kill_9_at_random_moments_never_leaves_a_torn_or_older_file() {
    let src = temp_file("c.st", COUNTER);
    let retain = temp_file("r.json", "");
    std::fs::remove_file(&retain).unwrap();
    let mut rng = rng::Rng(0x9E37_79B9_7F4A_7C15);
    let mut last = 0;
    let mut first_seen = None;
    for round in 0..50 {
        let mut child = Command::new(env!("CARGO_BIN_EXE_plcrun"))
            .args([
                &src,
                "--cycles",
                "100000000",
                "--cycle-time",
                "1ms",
                "--realtime",
            ])
            .args([
                "--retain",
                &retain,
                "--retain-every",
                "1",
                "--watchdog",
                "0",
            ])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("plcrun starts");
        std::thread::sleep(Duration::from_millis(20 + rng.below(130) as u64));
        child.kill().expect("SIGKILL");
        let status = child.wait().unwrap();
        assert!(
            status.code().is_none(),
            "round {round}: ended by itself: {status:?}"
        );
        if !std::path::Path::new(&retain).exists() {
            assert_eq!(last, 0, "round {round}: the file disappeared");
            continue;
        }
        let n = saved_counter(&retain);
        assert!(
            n >= last,
            "round {round}: counter went back from {last} to {n}"
        );
        first_seen.get_or_insert(n);
        last = n;
    }
    let first = first_seen.expect("at least one save in 50 runs");
    assert!(last > first, "the runs made no progress: {first} .. {last}");
}
