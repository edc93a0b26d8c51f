//! `plcrun --opcua` driven by Python's asyncua, a client written
//! independently of plcrun and of async-opcua: the test makes a virtual
//! environment, installs asyncua from PyPI into it and runs
//! tests/python/opcua_asyncua.py (read, write and reaction, subscription,
//! CONSTANT, unknown NodeId, browse, anonymous write refused). Where
//! Python, venv or the network is missing it says so and skips.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// A Python with asyncua importable, made once per target directory;
/// `Err` says why there is none.
fn python_with_asyncua() -> Result<PathBuf, String> {
    let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join("asyncua-venv");
    let python = venv.join("bin/python");
    let has = |p: &Path| {
        Command::new(p)
            .args(["-c", "import asyncua"])
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if has(&python) {
        return Ok(python);
    }
    let made = Command::new("python3")
        .args(["-m", "venv"])
        .arg(&venv)
        .output()
        .map_err(|e| format!("no python3 ({e})"))?;
    if !made.status.success() {
        return Err(format!(
            "python3 -m venv failed: {}",
            String::from_utf8_lossy(&made.stderr).trim()
        ));
    }
    let pip = Command::new(venv.join("bin/pip"))
        .args([
            "install",
            "--quiet",
            "--disable-pip-version-check",
            "asyncua",
        ])
        .output()
        .map_err(|e| format!("no pip in the venv ({e})"))?;
    if !pip.status.success() || !has(&python) {
        return Err(format!(
            "pip install asyncua failed (no network?): {}",
            String::from_utf8_lossy(&pip.stderr).trim()
        ));
    }
    Ok(python)
}

#[test]
fn python_asyncua_reads_writes_subscribes_and_is_refused() {
    let python = match python_with_asyncua() {
        Ok(p) => p,
        Err(why) => {
            eprintln!("skipped: {why}");
            return;
        }
    };
    let dir = std::env::temp_dir().join(format!("plcrun-opcua-python-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let users = dir.join("users");
    let mut add = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .args(["opcua-user", "add"])
        .arg(&users)
        .arg("op")
        .stdin(Stdio::piped())
        .spawn()
        .unwrap();
    writeln!(add.stdin.take().unwrap(), "pw").unwrap();
    assert!(add.wait().unwrap().success());
    let mut plc = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .args([
            "tests/python/opcua_counter.st",
            "--realtime",
            "--opcua",
            "127.0.0.1:0",
        ])
        .arg("--opcua-users")
        .arg(&users)
        .arg("--opcua-pki")
        .arg(dir.join("pki"))
        .args([
            "--opcua-trust-clients",
            "--trace",
            "ticks",
            "--changes-only",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = BufReader::new(plc.stderr.take().unwrap());
    let url = loop {
        let mut line = String::new();
        assert!(err.read_line(&mut line).unwrap() > 0, "no announcement");
        if let Some(rest) = line.trim().strip_prefix("opcua: listening on ") {
            break rest.split(' ').next().unwrap().to_string();
        }
    };
    std::thread::spawn(move || std::io::copy(&mut err, &mut std::io::sink()));
    let out = Command::new(&python)
        .arg("tests/python/opcua_asyncua.py")
        .arg(&url)
        .arg(&dir)
        .output()
        .unwrap();
    plc.kill().unwrap();
    plc.wait().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    eprintln!("{stdout}");
    assert!(
        out.status.success() && stdout.lines().last() == Some("OK"),
        "asyncua failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
