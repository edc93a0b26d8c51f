//! The command-line options of source files: `--encoding` and `--strict`
//! (docs/cli.md, "Source encodings and strict mode").

use crate::support::cli;

use cli::{plcrun, temp_file};

const EMBEDDED: &str = "PROGRAM P VAR_OUTPUT n : INT; END_VAR
n := n + 1; {{ printf(\"%d\", n); }}
END_PROGRAM
";

#[test]
fn strict_turns_the_compatibility_warning_into_an_error() {
    let f = temp_file("embedded.st", EMBEDDED);
    let (code, _, err) = plcrun(&["check", &f]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning[W360]"), "{err}");
    let (code, _, err) = plcrun(&["check", &f, "--strict"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[W360]"), "{err}");
    let (code, out, err) = plcrun(&["run", &f, "--cycles", "1", "--strict"]);
    assert_eq!(code, 1, "{out}{err}");
    let (code, out, _) = plcrun(&["run", &f, "--cycles", "1"]);
    assert_eq!((code, out.as_str()), (0, "cycle,time,n\n0,T#0s,1\n"));
}

#[test]
fn encoding_is_detected_or_given() {
    // `Zähler` in Windows-1252 (0xE4) in a comment.
    let f = temp_file(
        "latin.st",
        b"PROGRAM P (* Z\xe4hler *) VAR_OUTPUT n : INT; END_VAR n := 2; END_PROGRAM\n",
    );
    let (code, out, err) = plcrun(&["run", &f, "--cycles", "1"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "cycle,time,n\n0,T#0s,2\n");
    assert!(err.contains("warning[W020]"), "{err}");
    let (code, _, err) = plcrun(&["check", &f, "--encoding", "windows-1252"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("W020"), "{err}");
    let (code, _, err) = plcrun(&["check", &f, "--encoding", "utf-8"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[E011]"), "{err}");
    let (code, _, err) = plcrun(&["check", &f, "--encoding", "ebcdic"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("ebcdic"), "{err}");
}
