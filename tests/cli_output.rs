//! What the command line prints around the results (issue #30, point 3):
//! `--color auto|always|never` on every command (NO_COLOR respected), the
//! progress bar of long work drawn on a terminal only, and `--quiet`.
//!
//! A terminal is given to `plcrun` by `script` (util-linux), where it is
//! installed; those tests say so and pass without it.

use crate::support::cli;

use cli::{plcrun, temp_file};
use std::process::Command;

const ESC: char = '\x1b';

fn typo() -> String {
    temp_file(
        "typo.st",
        "PROGRAM P\nVAR n : INT; END_VAR\nn := m + 1;\nEND_PROGRAM\n",
    )
}

#[test]
fn diagnostics_are_plain_into_a_pipe_and_coloured_when_asked() {
    let file = typo();
    let (code, _, plain) = plcrun(&["check", &file]);
    assert_eq!(code, 1);
    assert!(
        plain.starts_with("error[E201]: undeclared variable `m`"),
        "{plain}"
    );
    assert!(
        !plain.contains(ESC),
        "auto into a pipe: no colour\n{plain:?}"
    );

    let (code, _, painted) = plcrun(&["check", &file, "--color", "always"]);
    assert_eq!(code, 1);
    assert!(
        painted.starts_with("\x1b[1;31merror[E201]\x1b[0m"),
        "{painted:?}"
    );
    assert!(
        painted.contains("\x1b[1;31m^\x1b[0m"),
        "the caret in the error's colour"
    );
    assert_eq!(strip_escapes(&painted), plain, "the same text, painted");

    // Before the subcommand's name too, and `never` wins over a terminal.
    let (_, _, never) = plcrun(&["--color=never", "check", &file]);
    assert_eq!(never, plain);
}

#[test]
fn a_bad_colour_choice_is_a_usage_error() {
    let (code, _, err) = plcrun(&["check", "programs/alg01.il", "--color", "pink"]);
    assert_eq!(code, 2);
    assert!(err.contains("invalid value 'pink'"), "{err}");
    assert!(err.contains("auto") && err.contains("always") && err.contains("never"));
}

#[test]
fn test_and_compare_verdicts_are_coloured_when_asked() {
    let tests = temp_file(
        "t_test.st",
        "PROGRAM TEST_One\nAssertEquals(INT#1, INT#1, 'one');\nEND_PROGRAM\n\
         PROGRAM TEST_Two\nAssertEquals(INT#1, INT#2, 'two');\nEND_PROGRAM\n",
    );
    let (code, out, _) = plcrun(&["test", &tests, "--color", "always"]);
    assert_eq!(code, 1);
    assert!(out.contains("\x1b[1;32mPASS\x1b[0m  TEST_One"), "{out:?}");
    assert!(out.contains("\x1b[1;31mFAIL\x1b[0m  TEST_Two"), "{out:?}");
    let (_, plain, _) = plcrun(&["test", &tests]);
    assert!(!plain.contains(ESC));
    // The same lines but the last (which gives the time taken).
    let lines = |s: &str| {
        s.lines()
            .rev()
            .skip(1)
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    assert_eq!(lines(&strip_escapes(&out)), lines(&plain));

    let (code, out, _) = plcrun(&[
        "compare",
        "programs/alg01.il",
        "--",
        "programs/alg01.il",
        "--random",
        "1",
        "--seeds",
        "3",
        "--cycles",
        "20",
        "--color",
        "always",
    ]);
    assert_eq!(code, 0);
    assert!(
        out.contains("verdict: \x1b[1;32mEQUIVALENT\x1b[0m on all 3 seeds"),
        "{out}"
    );
}

#[test]
fn quiet_drops_the_ok_line_not_the_errors() {
    let (code, _, err) = plcrun(&["check", "programs/alg01.il"]);
    assert_eq!((code, err.as_str()), (0, "ok: 1 file checked\n"));
    let (code, _, err) = plcrun(&["check", "-q", "programs/alg01.il"]);
    assert_eq!((code, err.as_str()), (0, ""));
    let (code, _, err) = plcrun(&["--quiet", "check", &typo()]);
    assert_eq!(code, 1);
    assert!(err.contains("error[E201]"), "{err}");
}

#[test]
fn serve_accepts_the_global_flags() {
    // They are the command line's, not options of the run the project
    // file describes: `serve --check` reads the file and stops.
    let dir = std::path::Path::new(&temp_file(
        "main.st",
        "PROGRAM Main VAR x : INT; END_VAR x := x + 1; END_PROGRAM\n",
    ))
    .parent()
    .expect("a folder")
    .to_path_buf();
    let project = dir.join("plcrun.toml");
    std::fs::write(&project, "sources = [\"main.st\"]\ncycle_time = \"10ms\"\n")
        .expect("project written");
    let project = project.display().to_string();
    let (code, _, err) = plcrun(&["serve", &project, "--check", "--color", "never", "-q"]);
    assert_eq!(code, 0, "{err}");
}

/// Runs `plcrun ARGS` with a terminal as its standard output and error
/// (through `script`), `env` added; `None` where `script` is missing.
fn on_a_terminal(args: &[&str], env: &[(&str, &str)]) -> Option<(bool, String)> {
    let probe = Command::new("script").arg("--version").output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: `script` (util-linux) is not installed");
        return None;
    }
    let mut line = env!("CARGO_BIN_EXE_plcrun").to_string();
    for a in args {
        line.push(' ');
        line.push_str(a);
    }
    let mut command = Command::new("script");
    command
        .args(["-qefc", &line, "/dev/null"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("CI")
        .env_remove("NO_COLOR")
        .env("TERM", "xterm");
    for (k, v) in env {
        command.env(k, v);
    }
    let out = command.output().expect("script runs");
    Some((
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    ))
}

/// A comparison long enough (a few seconds in a debug build) for the bar,
/// which waits 0.4 s before it shows.
const LONG_COMPARE: &[&str] = &[
    "compare",
    "programs/alg01.il",
    "--",
    "programs/alg01.il",
    "--random",
    "1",
    "--seeds",
    "600",
    "--cycles",
    "400",
    "--jobs",
    "1",
];

#[test]
fn a_long_comparison_draws_a_bar_on_a_terminal_only() {
    let (code, _, err) = plcrun(LONG_COMPARE);
    assert_eq!(code, 0);
    assert!(!err.contains("compare ["), "no bar into a pipe: {err:?}");

    let Some((ok, screen)) = on_a_terminal(LONG_COMPARE, &[]) else {
        return;
    };
    assert!(ok, "{screen}");
    assert!(
        screen.contains(" compare ["),
        "a bar on a terminal: {screen:?}"
    );
    assert!(screen.contains("/600 seeds"), "{screen:?}");
    // Cleared before the report: the verdict is on a clean line, coloured
    // (auto, on a terminal).
    assert!(
        screen.contains("verdict: \x1b[1;32mEQUIVALENT\x1b[0m on all 600 seeds"),
        "{screen:?}"
    );

    let mut quiet = LONG_COMPARE.to_vec();
    quiet.push("--quiet");
    let (_, screen) = on_a_terminal(&quiet, &[]).expect("script ran before");
    assert!(!screen.contains(" compare ["), "--quiet: {screen:?}");
    let (_, screen) = on_a_terminal(LONG_COMPARE, &[("CI", "true")]).expect("script ran before");
    assert!(!screen.contains(" compare ["), "CI: {screen:?}");
    let (_, screen) = on_a_terminal(LONG_COMPARE, &[("NO_COLOR", "1")]).expect("script ran before");
    assert!(
        screen.contains("verdict: EQUIVALENT"),
        "NO_COLOR: {screen:?}"
    );
}

#[test]
fn a_long_run_draws_its_bar_only_when_the_trace_goes_elsewhere() {
    let args = [
        "programs/alg01.il",
        "--cycles",
        "800000",
        "--changes-only",
        "--output",
        "/dev/null",
    ];
    let Some((ok, screen)) = on_a_terminal(&args, &[]) else {
        return;
    };
    assert!(ok, "{screen}");
    assert!(screen.contains("     run ["), "{screen:?}");
    assert!(screen.contains("/800000 cycles"), "{screen:?}");
    // The trace on the terminal: no bar to tear its lines.
    let (ok, screen) = on_a_terminal(&args[..4], &[]).expect("script ran before");
    assert!(ok);
    assert!(!screen.contains("     run ["), "{screen:?}");
}

fn strip_escapes(s: &str) -> String {
    let mut out = String::new();
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == ESC {
            for c in chars.by_ref() {
                if c.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

#[test]
fn a_reader_that_stops_reading_ends_plcrun_quietly() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    // `plcrun prog.st --cycles 1000000 | head -1`: the pipe closes after
    // the first line; plcrun stops with the status of SIGPIPE, no panic.
    let mut child = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["programs/alg01.il", "--cycles", "1000000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the plcrun binary runs");
    let mut first = String::new();
    let mut out = BufReader::new(child.stdout.take().unwrap());
    out.read_line(&mut first).unwrap();
    assert!(first.starts_with("cycle,time"), "{first}");
    drop(out);
    let done = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&done.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(done.status.code(), Some(141), "{err}");
}
