//! `plcrun --force NAME=VALUE` (docs/cli.md): the forced value holds for the
//! whole run and is marked in the trace; bad names and values are usage
//! errors naming them.

use crate::support::cli;

use cli::{plcrun, plcrun_ok, temp_file};

const COUNTER: &str = "PROGRAM Count
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; lamp : BOOL; END_VAR
n := n + 1; lamp := go;
END_PROGRAM
";

#[test]
fn forced_values_hold_and_are_marked_in_csv() {
    let p = temp_file("count.st", COUNTER);
    let out = plcrun_ok(&[&p, "--cycles", "2", "--force", "n=7", "--force", "go=TRUE"]);
    assert_eq!(out, "cycle,time,n,lamp\n0,T#0s,7!,TRUE\n1,T#10ms,7!,TRUE\n");
}

#[test]
fn forced_values_are_listed_in_json_lines() {
    let p = temp_file("count.st", COUNTER);
    let out = plcrun_ok(&[
        &p,
        "--cycles",
        "1",
        "--format",
        "jsonl",
        "--force",
        "lamp=TRUE",
    ]);
    assert_eq!(
        out,
        "{\"cycle\":0,\"time\":\"T#0s\",\"n\":1,\"lamp\":true,\"forced\":[\"lamp\"]}\n"
    );
}

#[test]
fn a_forced_input_ignores_the_stimulus() {
    let p = temp_file("count.st", COUNTER);
    let s = temp_file("s.csv", "cycle,go\n0,FALSE\n1,FALSE\n");
    let out = plcrun_ok(&[
        &p,
        "--cycles",
        "2",
        "--stimulus",
        &s,
        "--force",
        "go=TRUE",
        "--trace",
        "go,lamp",
    ]);
    assert_eq!(
        out,
        "cycle,time,go,lamp\n0,T#0s,TRUE!,TRUE\n1,T#10ms,TRUE!,TRUE\n"
    );
}

#[test]
fn unknown_names_and_wrong_values_are_usage_errors_naming_them() {
    let p = temp_file("count.st", COUNTER);
    let (code, _, err) = plcrun(&[&p, "--cycles", "1", "--force", "nope=1"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--force nope=1") && err.contains("unknown variable `nope`"),
        "{err}"
    );
    let (code, _, err) = plcrun(&[&p, "--cycles", "1", "--force", "n=TRUE"]);
    assert_eq!(code, 2);
    assert!(err.contains("`n`") && err.contains("`TRUE`"), "{err}");
    let (code, _, err) = plcrun(&[&p, "--cycles", "1", "--force", "n"]);
    assert_eq!(code, 2);
    assert!(err.contains("expected NAME=VALUE"), "{err}");
}

#[test]
fn step_flags_cannot_be_forced_or_set() {
    let (code, _, err) = plcrun(&[
        "programs/chariot.sfc",
        "--cycles",
        "1",
        "--set",
        "AV.X=TRUE",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("AV.X") && err.contains("step flags"), "{err}");
    let (code, _, _) = plcrun(&[
        "programs/chariot.sfc",
        "--cycles",
        "1",
        "--force",
        "AV.X=TRUE",
    ]);
    assert_eq!(code, 2);
}
