//! `plcrun --realtime`, `--stats` and `--stimulus -` from the command line:
//! a run until stopped by SIGTERM ends with exit 0 and a complete trace,
//! the statistics are printed, stimulus rows come from standard input.

#[path = "support/cli.rs"]
mod cli;

use cli::{plcrun, temp_file};
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdout, Command, Stdio};
use std::time::{Duration, Instant};

const TWO_TASKS: &str = "
PROGRAM Count VAR_OUTPUT n : DINT; END_VAR n := n + 1; END_PROGRAM
CONFIGURATION C RESOURCE R ON PLC
  TASK fast(INTERVAL := T#2ms, PRIORITY := 1);
  TASK slow(INTERVAL := T#5ms, PRIORITY := 0);
  PROGRAM a WITH fast : Count;
  PROGRAM b WITH slow : Count;
END_RESOURCE END_CONFIGURATION";

const DOUBLE: &str = "PROGRAM P VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR
y := 2 * x; END_PROGRAM";

fn spawn(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("plcrun starts")
}

fn sigterm(child: &Child) {
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
}

/// Reads trace lines until one satisfies `done` (or 10 s pass).
fn read_until(
    lines: &mut BufReader<ChildStdout>,
    seen: &mut Vec<String>,
    done: impl Fn(&str) -> bool,
) {
    let deadline = Instant::now() + Duration::from_secs(10);
    while Instant::now() < deadline {
        let mut line = String::new();
        if lines.read_line(&mut line).expect("readable stdout") == 0 {
            break;
        }
        let line = line.trim_end().to_string();
        let stop = done(&line);
        seen.push(line);
        if stop {
            return;
        }
    }
    panic!("never saw the expected line; got {seen:?}");
}

#[test]
fn sigterm_stops_a_realtime_run_cleanly_with_a_complete_trace() {
    let program = temp_file("two.st", TWO_TASKS);
    let mut child = spawn(&[&program, "--realtime", "--trace", "a.n,b.n"]);
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    let mut seen = Vec::new();
    // Rows arrive live, while the run goes on.
    read_until(&mut stdout, &mut seen, |l| l.starts_with("20,"));
    sigterm(&child);
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0), "{status:?}");
    assert!(rest.is_empty() || rest.ends_with('\n'), "{rest:?}");
    seen.extend(rest.lines().map(str::to_string));
    assert_eq!(seen[0], "cycle,time,a.n,b.n");
    // Every row is complete and the cycles follow each other.
    for (k, row) in seen[1..].iter().enumerate() {
        let fields: Vec<&str> = row.split(',').collect();
        assert_eq!(fields.len(), 4, "{row}");
        assert_eq!(fields[0], k.to_string(), "{row}");
        assert!(fields[1].starts_with("T#"), "{row}");
    }
}

#[test]
fn stats_are_printed_as_text_or_json() {
    let program = temp_file("two.st", TWO_TASKS);
    let (code, out, err) = plcrun(&[
        &program,
        "--realtime",
        "--cycles",
        "40",
        "--stats",
        "--stats-format",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 41);
    let json: serde_json::Value =
        serde_json::from_str(err.lines().last().unwrap()).expect("JSON statistics");
    assert_eq!(json[0]["name"], "fast");
    assert_eq!(json[1]["interval_ns"], 5_000_000);
    let activations = json[0]["cycles"].as_u64().unwrap() + json[0]["overruns"].as_u64().unwrap();
    assert!(activations >= 19, "{json}");
    assert!(json[0]["cycles"].as_u64().unwrap() <= 21, "{json}");
    assert!(json[0]["start_jitter"]["max_ns"].as_i64().unwrap() >= 0);

    // In virtual time: execution times, no jitter; the trace is unchanged.
    let (code, out, err) = plcrun(&[&program, "--cycles", "10", "--stats"]);
    assert_eq!(code, 0, "{err}");
    let (_, plain, _) = plcrun(&[&program, "--cycles", "10"]);
    assert_eq!(out, plain);
    assert!(err.contains("task statistics"), "{err}");
    let fast = err
        .lines()
        .find(|l| l.starts_with("fast"))
        .expect("a row per task");
    assert!(fast.split_whitespace().nth(3) == Some("5"), "{fast}");
    let jitter: Vec<&str> = fast.split_whitespace().skip(9).collect();
    assert_eq!(jitter, ["-", "-", "-", "-"], "{fast}");
}

#[test]
fn cycles_are_required_without_realtime() {
    let program = temp_file("two.st", TWO_TASKS);
    let (code, _, err) = plcrun(&[&program]);
    assert_eq!(code, 2);
    assert!(err.contains("--cycles is required"), "{err}");
}

#[test]
fn a_stimulus_on_standard_input_is_read_to_its_end_in_virtual_time() {
    let program = temp_file("double.st", DOUBLE);
    let mut child = spawn(&[&program, "--cycles", "4", "--stimulus", "-"]);
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"cycle,x\n0,5\n2,7\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "cycle,time,y\n0,T#0s,10\n1,T#10ms,10\n2,T#20ms,14\n3,T#30ms,14\n"
    );
}

#[test]
fn a_stimulus_on_standard_input_is_applied_live_in_real_time() {
    let program = temp_file("double.st", DOUBLE);
    let mut child = spawn(&[&program, "--realtime", "--stimulus", "-"]);
    let mut stdin = child.stdin.take().unwrap();
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    let mut seen = Vec::new();
    stdin.write_all(b"cycle,x\n0,5\n").unwrap();
    stdin.flush().unwrap();
    read_until(&mut stdout, &mut seen, |l| l.ends_with(",10"));
    // A row typed while it runs: applied when it arrives.
    stdin.write_all(b"# operator\n0,21\n").unwrap();
    stdin.flush().unwrap();
    read_until(&mut stdout, &mut seen, |l| l.ends_with(",42"));
    // A bad row ends the run with a usage error naming it.
    stdin.write_all(b"0,TRUE\n").unwrap();
    stdin.flush().unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("line 5") && err.contains("`x`"), "{err}");
}

#[test]
fn a_realtime_run_pinned_to_cpu_0_runs_and_locks_its_memory_or_says_why() {
    let program = temp_file("two.st", TWO_TASKS);
    let (code, out, err) = plcrun(&[&program, "--realtime", "--cycles", "10", "--cpu", "0"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 11);
    // Memory is locked and the CPUs kept awake by default: either it
    // worked (nothing said) or a note names the refusal and the way out.
    for line in err.lines() {
        assert!(
            (line.starts_with("note: memory was not locked") && line.contains("--no-lock-memory"))
                || (line.starts_with("note: the CPUs were not kept awake")
                    && line.contains("--allow-cpu-sleep")),
            "{err}"
        );
    }
    let (code, _, err) = plcrun(&[
        &program,
        "--realtime",
        "--cycles",
        "10",
        "--no-lock-memory",
        "--allow-cpu-sleep",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(err, "");
}

#[test]
fn an_unavailable_cpu_stops_the_run_before_its_first_cycle() {
    let program = temp_file("two.st", TWO_TASKS);
    let (code, out, err) = plcrun(&[&program, "--realtime", "--cycles", "10", "--cpu", "4096"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("error: CPU 4096 is not available to this process"),
        "{err}"
    );
    // Only the header: no cycle ran.
    assert!(out.lines().count() <= 1, "{out}");
}

#[test]
fn rt_priority_is_granted_or_refused_with_what_to_change() {
    let program = temp_file("two.st", TWO_TASKS);
    let (code, out, err) = plcrun(&[
        &program,
        "--realtime",
        "--cycles",
        "10",
        "--rt-priority",
        "20",
    ]);
    if code == 0 {
        assert_eq!(out.lines().count(), 11, "{err}");
    } else {
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains("SCHED_FIFO priority 20 is not permitted") && err.contains("ulimit -r"),
            "{err}"
        );
    }
}

#[test]
fn real_time_flags_need_realtime_and_a_priority_in_range() {
    let program = temp_file("two.st", TWO_TASKS);
    for args in [
        vec!["--cycles", "5", "--rt-priority", "10"],
        vec!["--cycles", "5", "--cpu", "0"],
        vec!["--cycles", "5", "--no-lock-memory"],
        vec!["--cycles", "5", "--allow-cpu-sleep"],
    ] {
        let mut all = vec![program.as_str()];
        all.extend(args);
        let (code, _, err) = plcrun(&all);
        assert_eq!(code, 2, "{all:?}: {err}");
        assert!(err.contains("--realtime"), "{all:?}: {err}");
    }
    for bad in ["0", "100"] {
        let (code, _, err) = plcrun(&[&program, "--realtime", "--rt-priority", bad]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("--rt-priority"), "{err}");
    }
}
