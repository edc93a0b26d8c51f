//! Structural checks of the committed source files that do not need the
//! plcrun engine: one reference block per `stdlib/` file, named after the
//! file, and comments in `programs/` and `stdlib/` that open and close
//! cleanly (no `(*` inside a comment, none left open -- the kind of damage the
//! OCR did to the seed listings).

use std::fs;
use std::path::{Path, PathBuf};

fn files(dir: &str, exts: &[&str]) -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    let mut out: Vec<PathBuf> = fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .map(|e| e.expect("dir entry").path())
        .filter(|p| {
            p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| exts.contains(&e))
        })
        .collect();
    out.sort();
    out
}

#[test]
fn each_stdlib_file_defines_its_reference_block() {
    let expected_stems = [
        "r_trig", "f_trig", "sr", "rs", "ctu", "ctd", "ctud", "ton", "tof", "tp", "rtc",
    ]
    .into_iter()
    .map(String::from)
    .chain(["ctu", "ctd", "ctud"].into_iter().flat_map(|c| {
        ["dint", "lint", "udint", "ulint"]
            .into_iter()
            .map(move |t| format!("{c}_{t}"))
    }));
    let mut expected: Vec<String> = expected_stems.collect();
    expected.sort();
    let paths = files("stdlib", &["st"]);
    let mut stems: Vec<String> = paths
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    stems.sort();
    assert_eq!(stems, expected);
    for path in paths {
        let text = fs::read_to_string(&path).unwrap();
        let stem = path.file_stem().unwrap().to_string_lossy().to_uppercase();
        let decls: Vec<&str> = text
            .lines()
            .filter(|l| l.trim_start().starts_with("FUNCTION_BLOCK "))
            .collect();
        assert_eq!(
            decls,
            [format!("FUNCTION_BLOCK REF_{stem}").as_str()],
            "{}",
            path.display()
        );
        assert_eq!(text.matches("END_FUNCTION_BLOCK").count(), 1);
    }
}

/// Returns an error message if a `(*` appears inside a comment or a comment
/// is never closed.
fn comment_problem(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut i = 0;
    let mut open_at: Option<usize> = None;
    let line_of = |pos: usize| text[..pos].lines().count().max(1);
    while i + 1 < bytes.len() {
        let pair = &bytes[i..i + 2];
        match (open_at, pair) {
            (None, b"(*") => {
                open_at = Some(i);
                i += 2;
            }
            (Some(start), b"(*") => {
                return Some(format!(
                    "'(*' at line {} inside the comment opened at line {}",
                    line_of(i),
                    line_of(start)
                ));
            }
            (Some(_), b"*)") => {
                open_at = None;
                i += 2;
            }
            _ => i += 1,
        }
    }
    open_at.map(|start| format!("comment opened at line {} never closed", line_of(start)))
}

#[test]
fn comments_are_balanced_in_programs_and_stdlib() {
    let mut paths = files("programs", &["il", "st", "sfc"]);
    paths.extend(files("stdlib", &["st"]));
    assert!(!paths.is_empty());
    for path in paths {
        let text = fs::read_to_string(&path).unwrap();
        if let Some(problem) = comment_problem(&text) {
            panic!("{}: {problem}", path.display());
        }
    }
}

/// The text outside comments (comments do not nest: the first `*)` ends one).
fn strip_comments(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find("(*") {
        out.push_str(&rest[..start]);
        out.push(' ');
        match rest[start + 2..].find("*)") {
            Some(end) => rest = &rest[start + 2 + end + 2..],
            None => return out,
        }
    }
    out.push_str(rest);
    out
}

/// A comment closed too early (e.g. by a quoted `*)`) leaves its tail as
/// code: catch that in the file header, where only comments may precede the
/// first POU, and anywhere as a stray `*)`.
#[test]
fn no_comment_is_closed_early() {
    let mut paths = files("programs", &["il", "st", "sfc"]);
    paths.extend(files("stdlib", &["st"]));
    for path in paths {
        let code = strip_comments(&fs::read_to_string(&path).unwrap());
        assert!(!code.contains("*)"), "{}: stray '*)'", path.display());
        let first = code.split_whitespace().next().unwrap_or("");
        assert!(
            [
                "PROGRAM",
                "FUNCTION",
                "FUNCTION_BLOCK",
                "CONFIGURATION",
                "INTERFACE",
                "TYPE"
            ]
            .contains(&first),
            "{}: code starts with {first:?}",
            path.display()
        );
    }
}

#[test]
fn the_comment_checker_catches_the_seed_damage() {
    assert!(comment_problem("(* DES VARIABLES*\n(*1.Variables*)").is_some());
    assert!(comment_problem("(* open").is_some());
    assert!(comment_problem("(* a *) x (* b *)").is_none());
}
