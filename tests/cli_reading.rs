//! `--encoding` and `--strict` on every subcommand that reads sources
//! (issue #11): draw, export, compare, test, and the new versions of
//! `run --reload` / `--online-change-at`, besides run and check.

use crate::support::cli;

use cli::{plcrun, temp_file};

/// A program whose comment holds a Windows-1252 byte (0xE9, `é`) and that
/// uses one compatibility extension (W324, unary `-` on a DWORD).
fn latin_program() -> Vec<u8> {
    let mut src =
        b"PROGRAM P\nVAR d : DWORD := 1; END_VAR\nVAR_OUTPUT r : DWORD; END_VAR (* caf".to_vec();
    src.push(0xE9);
    src.extend_from_slice(b" *)\nr := -d;\nEND_PROGRAM\n");
    src
}

/// A clean program of pure IEC with the same Windows-1252 comment.
fn latin_pure() -> Vec<u8> {
    let mut src =
        b"PROGRAM P\nVAR d : DINT := 1; END_VAR\nVAR_OUTPUT r : DINT; END_VAR (* caf".to_vec();
    src.push(0xE9);
    src.extend_from_slice(b" *)\nr := -d;\nEND_PROGRAM\n");
    src
}

#[test]
fn export_reads_the_encoding_given_and_strict_refuses_extensions() {
    let f = temp_file("p.st", latin_program());
    // UTF-8 only: the byte is an error (E011).
    let (code, _, err) = plcrun(&["export", "--plcopen", &f, "--encoding", "utf-8"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E011"), "{err}");
    // Detected: exported with W020.
    let (code, out, err) = plcrun(&["export", "--plcopen", &f]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("W020"), "{err}");
    assert!(out.contains("<project"), "{out}");
    // Strict: the extension is an error and nothing is written.
    let (code, out, err) = plcrun(&["export", "--plcopen", &f, "--strict"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[W324]"), "{err}");
    assert!(out.is_empty(), "{out}");
}

#[test]
fn draw_takes_the_encoding_and_strict() {
    let chart = "PROGRAM P\nVAR d : DWORD := 1; r : DWORD; END_VAR\nINITIAL_STEP S0 : END_STEP\n\
                 TRANSITION FROM S0 TO S1 := TRUE; END_TRANSITION\nSTEP S1 : END_STEP\n\
                 TRANSITION FROM S1 TO S0 := -d = 16#FFFFFFFF; END_TRANSITION\nEND_PROGRAM\n";
    let f = temp_file("c.st", chart);
    let (code, out, err) = plcrun(&["draw", &f]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("<svg"), "{out}");
    let (code, _, err) = plcrun(&["draw", &f, "--strict"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[W324]"), "{err}");
    let (code, _, err) = plcrun(&["draw", &f, "--encoding", "shift-jis"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn test_runner_takes_the_encoding_and_strict() {
    let mut src = latin_program();
    src.extend_from_slice(
        b"PROGRAM TEST_Neg\nVAR d : DWORD := 2; END_VAR\nAssertEquals(16#FFFFFFFE, -d, 'neg');\nEND_PROGRAM\n",
    );
    let f = temp_file("t.st", src);
    let (code, out, err) = plcrun(&["test", &f, "--encoding", "windows-1252"]);
    assert_eq!(code, 0, "{out}{err}");
    let (code, _, err) = plcrun(&["test", &f, "--encoding", "utf-8"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E011"), "{err}");
    let (code, out, err) = plcrun(&["test", &f, "--strict"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(format!("{out}{err}").contains("W324"), "{out}{err}");
}

#[test]
fn compare_reads_both_programs_with_the_encoding_and_strict() {
    let a = temp_file("a.st", latin_pure());
    let b = temp_file("b.st", latin_program());
    let (code, _, err) = plcrun(&[
        "compare",
        &a,
        "--cycles",
        "2",
        "--random",
        "1",
        "--encoding",
        "utf-8",
        "--",
        &a,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("E011"), "{err}");
    let (code, _, err) = plcrun(&["compare", &a, "--cycles", "2", "--random", "1", "--", &a]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = plcrun(&[
        "compare", &a, "--cycles", "2", "--random", "1", "--strict", "--", &b,
    ]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("W324"), "{err}");
}

#[test]
fn an_online_change_reads_the_new_version_with_the_encoding() {
    let old = temp_file(
        "old.st",
        "PROGRAM P\nVAR d : DINT := 1; r : DINT; END_VAR\nr := -d;\nEND_PROGRAM\n",
    );
    let new = temp_file("new.st", latin_pure());
    let at = format!("1:{new}");
    let (code, _, err) = plcrun(&[
        "run",
        &old,
        "--cycles",
        "3",
        "--encoding",
        "windows-1252",
        "--online-change-at",
        &at,
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("refused"), "{err}");
    // The same new version read as UTF-8 is refused (E011); the program runs on.
    let (code, _, err) = plcrun(&[
        "run",
        &old,
        "--cycles",
        "3",
        "--encoding",
        "utf-8",
        "--online-change-at",
        &at,
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("E011") && err.contains("refused"), "{err}");
}
