//! `--online-change-at N:FILE`: the command line loads a new version of the
//! program before cycle N; a version that cannot apply is refused and the
//! old program runs on.

use crate::support::cli;

use cli::{plcrun, temp_file};

const V1: &str = "PROGRAM P
VAR_OUTPUT et : TIME; n : INT; END_VAR
VAR t : TON; END_VAR
t(IN := TRUE, PT := T#1s); et := t.ET; n := n + 1;
END_PROGRAM
";

/// The same timer; `n` now counts by ten.
const V2: &str = "PROGRAM P
VAR_OUTPUT et : TIME; n : INT; END_VAR
VAR t : TON; extra : BOOL; END_VAR
t(IN := TRUE, PT := T#1s); et := t.ET; n := n + 10;
END_PROGRAM
";

#[test]
fn a_new_version_is_loaded_before_the_given_cycle() {
    let v1 = temp_file("v1.st", V1);
    let v2 = temp_file("v2.st", V2);
    let change = format!("3:{v2}");
    let (code, out, err) = plcrun(&[&v1, "--cycles", "5", "--online-change-at", &change]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "cycle,time,et,n\n0,T#0s,T#0s,1\n1,T#10ms,T#10ms,2\n2,T#20ms,T#20ms,3\n\
         3,T#30ms,T#30ms,13\n4,T#40ms,T#40ms,23\n"
    );
    assert!(err.contains("online change before cycle 3"), "{err}");
    assert!(err.contains("kept P.t"), "{err}");
    assert!(err.contains("initialised P.extra"), "{err}");
}

#[test]
fn a_version_that_does_not_compile_is_refused_and_the_run_goes_on() {
    let v1 = temp_file("v1.st", V1);
    let bad = temp_file("bad.st", "PROGRAM P n := ; END_PROGRAM");
    let change = format!("2:{bad}");
    let (code, out, err) = plcrun(&[&v1, "--cycles", "4", "--online-change-at", &change]);
    assert_eq!(code, 0, "{err}");
    assert!(out.ends_with("3,T#30ms,T#30ms,4\n"), "{out}");
    assert!(err.contains("refused"), "{err}");
}

#[test]
fn a_malformed_option_is_a_usage_error() {
    let v1 = temp_file("v1.st", V1);
    let (code, _, err) = plcrun(&[&v1, "--cycles", "4", "--online-change-at", "x.st"]);
    assert_eq!(code, 2);
    assert!(err.contains("expected N:FILE"), "{err}");
}
