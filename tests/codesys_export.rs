//! File-level parts of a CoDeSys 2.3 export (docs/semantics.md, "Source
//! encodings"): the `(* @NESTEDCOMMENTS := 'Yes' *)`-style object headers
//! are comments, and the `LIBRARY ... END_LIBRARY` list the export ends
//! with is skipped with warning W021.

use plcrun::{CheckOptions, Severity, SourceMap};

/// An export of one function written here in CoDeSys 2.3's layout.
const EXPORT: &str = "
(* @NESTEDCOMMENTS := 'Yes' *)
(* @PATH := '\\/Math' *)
(* @OBJECTFLAGS := '0, 8' *)
(* @SYMFILEFLAGS := '2048' *)
FUNCTION _TWICE : INT
VAR_INPUT
\tX_IN : INT;
END_VAR
(* @END_DECLARATION := '0' *)
_TWICE := X_IN * 2;
END_FUNCTION

LIBRARY
Standard.lib 4.10.05 11:14:46
(* @LIBRARYSYMFILEINFO := '0' *)
NumOfPOUs: 2
CONCAT: 0
TON: 0
NumOfGVLs: 0
END_LIBRARY
";

fn check(text: &str) -> plcrun::CheckReport {
    let mut map = SourceMap::new();
    map.add("lib.EXP", text);
    plcrun::check(&map, &CheckOptions::default())
}

#[test]
fn the_library_list_of_an_export_is_skipped_with_a_warning() {
    let report = check(EXPORT);
    let d: Vec<_> = report
        .diagnostics
        .iter()
        .map(|d| (d.code, d.severity))
        .collect();
    assert_eq!(d, [("W021", Severity::Warning)]);
    let w = report.diagnostics.iter().next().unwrap();
    assert!(w.message.contains("Standard.lib"), "{}", w.message);
}

#[test]
fn library_elsewhere_is_an_ordinary_word() {
    // Not at the start of a line, or without END_LIBRARY: not a list.
    let src = "PROGRAM P VAR library : INT; END_VAR library := 1; END_PROGRAM\n";
    assert!(check(src).diagnostics.is_empty());
    let unterminated = EXPORT.replace("END_LIBRARY", "");
    let report = check(&unterminated);
    assert!(report.diagnostics.iter().all(|d| d.code != "W021"));
    assert!(!report.is_ok());
}
