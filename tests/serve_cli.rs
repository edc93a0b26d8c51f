//! `plcrun serve` and `plcrun init` (docs/project-file.md): the CHARIOT
//! example runs in real time until SIGTERM, stops with exit status 0 and
//! leaves its retained data saved at the stop; `init` writes a file that
//! checks, and keeps an existing one unless `--force`.

use crate::support::cli;

use cli::{plcrun, temp_file};
use plcrun::{Diagnostics, Options, Plc, RestoreMode, load_files};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const EXAMPLE: &str = "examples/chariot/plcrun.toml";

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// A fresh folder for one test.
fn fresh_dir() -> PathBuf {
    Path::new(&temp_file(".keep", ""))
        .parent()
        .unwrap()
        .to_path_buf()
}

#[cfg(target_os = "linux")]
fn sigterm(child: &Child) {
    let pid = libc::pid_t::try_from(child.id()).expect("a pid");
    // SAFETY: kill(2) on the pid of a child this test started and has not
    // yet waited for, so the pid cannot have been reused.
    let sent = unsafe { libc::kill(pid, libc::SIGTERM) };
    assert_eq!(sent, 0, "kill failed");
}

#[cfg(target_os = "linux")]
/// Reads standard error until a line starts with `prefix` (10 s at most,
/// else panics with what was read); the rest is drained on a thread.
fn wait_for_line(child: &mut Child, prefix: &str) -> (String, std::thread::JoinHandle<String>) {
    let mut err = BufReader::new(child.stderr.take().expect("stderr piped"));
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut seen = String::new();
    while Instant::now() < deadline {
        let mut line = String::new();
        if err.read_line(&mut line).unwrap() == 0 {
            break;
        }
        seen.push_str(&line);
        if line.starts_with(prefix) {
            let rest = std::thread::spawn(move || {
                let mut rest = String::new();
                std::io::Read::read_to_string(&mut err, &mut rest).unwrap();
                rest
            });
            return (seen, rest);
        }
    }
    panic!("no line starting with {prefix:?}; standard error:\n{seen}");
}

#[cfg(target_os = "linux")]
/// The cycle count the retain file at `path` was saved after, read back
/// through the library with the example's program.
fn saved_after(path: &Path) -> u64 {
    let mut diags = Diagnostics::new();
    let sources = load_files(
        &[
            repo("programs/chariot.sfc"),
            repo("examples/modbus/chariot_modbus.st"),
        ],
        &mut diags,
    )
    .expect("the example's sources load");
    let mut plc = Plc::compile(sources, &Options::default()).expect("the example compiles");
    plc.restore_retain(path, RestoreMode::Exact)
        .expect("the retain file fits the program")
        .cycle
}

#[cfg(target_os = "linux")]
#[test]
fn the_chariot_example_serves_until_sigterm_and_saves_its_retained_data() {
    let dir = fresh_dir();
    let retain = dir.join("chariot.retain");
    let retain_arg = retain.to_str().unwrap();
    let pki = dir.join("pki");
    let pki_arg = pki.to_str().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        // A free port and a retain file of the test's own: the file's
        // values overridden from the command line.
        .args([
            "serve",
            EXAMPLE,
            "--modbus",
            "127.0.0.1:0",
            "--web",
            "127.0.0.1:0",
            "--opcua",
            "127.0.0.1:0",
            "--opcua-pki",
            pki_arg,
            "--retain",
            retain_arg,
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("plcrun starts");
    let (head, rest) = wait_for_line(&mut child, "web: token for changes: ");
    assert!(head.contains("modbus: listening on 127.0.0.1:"), "{head}");
    assert!(
        head.contains("opcua: listening on opc.tcp://127.0.0.1:"),
        "{head}"
    );
    assert!(
        head.contains("web: listening on http://127.0.0.1:"),
        "{head}"
    );
    assert!(
        head.contains("serve: examples/chariot/plcrun.toml (2 source files)"),
        "{head}"
    );
    assert!(head.contains("cold start"), "{head}");
    // Cycles run in real time; the file is saved every 100 of them and at the stop.
    std::thread::sleep(Duration::from_millis(500));
    sigterm(&child);
    let output = child.wait_with_output().expect("plcrun ends");
    let rest = rest.join().unwrap();
    assert_eq!(output.status.code(), Some(0), "{head}{rest}");
    // No [trace] table: nothing on standard output.
    assert!(
        output.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stdout)
    );
    // Saved at the stop: after the cycles run, not only at the start.
    let cycles = saved_after(&retain);
    assert!(cycles > 0, "saved after {cycles} cycles\n{head}{rest}");
    // The next start is warm, from that save.
    let (code, _, err) = plcrun(&[
        "serve",
        EXAMPLE,
        "--modbus",
        "127.0.0.1:0",
        "--web",
        "127.0.0.1:0",
        "--opcua",
        "127.0.0.1:0",
        "--opcua-pki",
        pki_arg,
        "--retain",
        retain_arg,
        "--cycles",
        "3",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains(&format!("warm start: 0 retained values restored from `{retain_arg}` (saved after {cycles} cycles)")),
        "{err}"
    );
}

#[test]
fn the_chariot_example_checks() {
    let (code, out, err) = plcrun(&["serve", EXAMPLE, "--check"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("ok: 2 files checked"), "{err}");
    assert_eq!(
        out.trim(),
        "plcrun run --realtime --watchdog 100ms --retain examples/chariot/chariot.retain \
         --retain-every 100 --no-trace --modbus 127.0.0.1:5020 --modbus-max-clients 4 \
         --modbus-idle-timeout 60s --web 127.0.0.1:8080 --opcua 127.0.0.1:4840 \
         --opcua-pki examples/chariot/opcua-pki -- programs/chariot.sfc \
         examples/modbus/chariot_modbus.st"
    );
    // Flags of the flattened option groups (OPC UA, reading) override the
    // file too: they were once refused as "`--OpcUaArgs`".
    let (code, out, err) = plcrun(&[
        "serve",
        EXAMPLE,
        "--check",
        "--opcua",
        "127.0.0.1:4841",
        "--strict",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains(" --strict "), "{out}");
    assert!(out.contains(" --opcua 127.0.0.1:4841 "), "{out}");
}

#[test]
fn init_writes_a_file_that_checks_and_keeps_an_existing_one() {
    let dir = fresh_dir();
    let file = dir.join("plcrun.toml");
    let file_arg = file.to_str().unwrap();
    let (code, _, err) = plcrun(&["init", file_arg]);
    assert_eq!(code, 0, "{err}");
    let written = std::fs::read_to_string(&file).unwrap();
    assert!(written.starts_with("# plcrun project file"), "{written}");
    // Its globs match the sources put next to it.
    std::fs::write(
        dir.join("main.st"),
        "PROGRAM Main VAR_OUTPUT n : INT; END_VAR n := n + 1; END_PROGRAM\n",
    )
    .unwrap();
    let (code, out, err) = plcrun(&["serve", file_arg, "--check"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.starts_with("plcrun run --realtime --no-trace -- "),
        "{out}"
    );
    let (code, _, err) = plcrun(&["check", "--project", file_arg]);
    assert_eq!(code, 0, "{err}");
    // A second init keeps the file; --force overwrites it.
    std::fs::write(&file, "sources = [\"main.st\"]\n").unwrap();
    let (code, _, err) = plcrun(&["init", file_arg]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("exists; `plcrun init --force` overwrites it"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        "sources = [\"main.st\"]\n"
    );
    let (code, _, err) = plcrun(&["init", file_arg, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), written);
}

#[test]
fn every_key_of_the_init_file_parses_when_uncommented() {
    // The commented keys are real keys with valid values: uncommenting all
    // of them (but [opcua] in a build without it) gives a valid file.
    let dir = fresh_dir();
    let file = dir.join("plcrun.toml");
    let (code, _, err) = plcrun(&["init", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let mut text = String::new();
    for line in std::fs::read_to_string(&file).unwrap().lines() {
        let key_or_table = line.strip_prefix("# ").filter(|l| {
            l.starts_with('[') || l.split_once(" = ").is_some_and(|(k, _)| !k.contains(' '))
        });
        text.push_str(key_or_table.unwrap_or(line));
        text.push('\n');
    }
    if cfg!(not(feature = "opcua")) {
        let cut = text.find("[opcua]").unwrap();
        let end = text.find("[web]").unwrap();
        text.replace_range(cut..end, "");
    }
    assert!(
        text.contains("\n[web]\nlisten = \"127.0.0.1:8080\""),
        "{text}"
    );
    std::fs::write(&file, &text).unwrap();
    std::fs::write(
        dir.join("main.st"),
        "PROGRAM Main VAR_INPUT setpoint : INT; enable : BOOL; END_VAR VAR_OUTPUT out : INT; END_VAR VAR delay : TIME; END_VAR out := setpoint; END_PROGRAM\n",
    )
    .unwrap();
    std::fs::write(dir.join("stimulus.csv"), "cycle,Main.enable\n0,TRUE\n").unwrap();
    std::fs::write(dir.join("opcua-users.txt"), "").unwrap();
    let (code, out, err) = plcrun(&["serve", file.to_str().unwrap(), "--check"]);
    assert_eq!(code, 0, "{text}\n{err}");
    assert!(out.contains("--modbus 0.0.0.0:502"), "{out}");
    assert!(out.contains("--force Main.enable=TRUE"), "{out}");
}
