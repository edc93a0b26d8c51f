//! Cargo.toml turns test discovery off (`autotests = false`) and
//! tests/suite.rs names the test files one by one, so a new file under
//! tests/ that nobody adds would never run. This test finds such a file.

use std::path::Path;

/// The files cargo would have made test targets of: the `.rs` files
/// directly under tests/ and the `main.rs` of its folders (`syntax/main.rs`).
/// The support modules live in tests/support/, which has no `main.rs`.
fn test_files(root: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root.join("tests"))
        .expect("read tests/")
        .filter_map(|entry| {
            let entry = entry.ok()?;
            let name = entry.file_name().into_string().ok()?;
            if entry.path().join("main.rs").is_file() {
                Some(format!("{name}/main.rs"))
            } else {
                name.ends_with(".rs").then_some(name)
            }
        })
        .collect();
    names.sort();
    names
}

#[test]
fn every_test_file_is_in_the_suite_or_a_target_of_its_own() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let suite = std::fs::read_to_string(root.join("tests/suite.rs")).expect("read tests/suite.rs");
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).expect("read Cargo.toml");
    let left_out: Vec<String> = test_files(root)
        .into_iter()
        .filter(|name| name != "suite.rs")
        .filter(|name| {
            !suite.contains(&format!("#[path = \"{name}\"]"))
                && !manifest.contains(&format!("path = \"tests/{name}\""))
        })
        .collect();
    assert!(
        left_out.is_empty(),
        "tests/{left_out:?} would never run: add them to tests/suite.rs (or give them a [[test]] of their own in Cargo.toml)"
    );
}

#[test]
fn the_test_files_are_found() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = test_files(root);
    assert!(files.contains(&"suite.rs".to_string()), "{files:?}");
    assert!(
        files.contains(&"suite_membership.rs".to_string()),
        "{files:?}"
    );
}
