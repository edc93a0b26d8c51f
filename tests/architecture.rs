//! The stages of `src/` depend on each other in one direction only
//! (docs/architecture.md). This test reads every `crate::stage` path in the
//! sources (in `use` lines and inline paths; comments and unit-test modules
//! excluded) and checks it against the allowed matrix below, so a backward
//! dependency fails the build's tests instead of rotting in silently.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Each stage and the stages it may use. A stage not listed may not be
/// used by anyone but `lib.rs`, which only re-exports.
const ALLOWED: &[(&str, &[&str])] = &[
    ("source", &[]),
    ("elementary", &[]),
    // Direct addresses and the addressing conventions (which image bytes
    // an address names): the checker warns of overlaps, the runtime lays
    // out the image.
    ("address", &[]),
    // How far long work has got: reported by the driver, the runtime's
    // runs, comparisons and tests; shown by a front end.
    ("progress", &[]),
    ("value", &["elementary"]),
    ("diagnostics", &["source"]),
    ("syntax", &["source", "diagnostics", "elementary", "value"]),
    ("ir", &["source", "elementary", "value"]),
    ("stdlib", &["ir", "elementary"]),
    (
        "sema",
        &[
            "address",
            "source",
            "diagnostics",
            "elementary",
            "value",
            "syntax",
            "ir",
            "stdlib",
        ],
    ),
    ("vm", &["elementary", "value", "ir", "stdlib"]),
    (
        "driver",
        &[
            "address",
            "source",
            "diagnostics",
            "elementary",
            "value",
            "syntax",
            "sema",
            "ir",
            "progress",
        ],
    ),
    (
        "runtime",
        &[
            "address",
            "source",
            "diagnostics",
            "elementary",
            "value",
            "ir",
            "stdlib",
            "vm",
            "driver",
            "progress",
        ],
    ),
    // What an editor asks (plcrun lsp): the parsed sources indexed, the
    // check's diagnostics, the standard blocks' pins.
    (
        "ide",
        &[
            "source",
            "diagnostics",
            "elementary",
            "syntax",
            "driver",
            "stdlib",
        ],
    ),
    // Pictures: charts read from the parsed sources, timing diagrams
    // sampled from a running PLC.
    (
        "draw",
        &[
            "source",
            "diagnostics",
            "elementary",
            "value",
            "syntax",
            "runtime",
        ],
    ),
    // Runs two programs through the runtime's public face; reads the
    // program instances' inputs from the image.
    (
        "compare",
        &["runtime", "ir", "elementary", "value", "progress"],
    ),
    // The unit-test runner: finds tests in the parsed sources, runs them
    // through the runtime with host-function assertions whose names the
    // checker (sema) rewrites calls into.
    (
        "testing",
        &[
            "address",
            "source",
            "diagnostics",
            "elementary",
            "syntax",
            "sema",
            "runtime",
            "progress",
        ],
    ),
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable src/") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The stage a file belongs to: `src/vm/exec.rs` → `vm`, `src/types.rs` → `types`.
fn stage_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).expect("file under src/");
    let first = rel.components().next().expect("a path component");
    let name = first.as_os_str().to_string_lossy();
    name.trim_end_matches(".rs").to_string()
}

/// The first path segment after every `crate::` in `code` (also inside
/// `crate::{a, b::c}` groups), with the byte offset of its `crate::`.
fn crate_paths(code: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let offset = code.len() - rest.len() + at;
        let after = &rest[at + "crate::".len()..];
        if let Some(group) = after.strip_prefix('{') {
            let inner = &group[..group.find('}').unwrap_or(group.len())];
            for item in inner.split(',') {
                let head = item.trim().split("::").next().unwrap_or("");
                if !head.is_empty() {
                    found.push((offset, head.to_string()));
                }
            }
        } else {
            let ident: String = after
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !ident.is_empty() {
                found.push((offset, ident));
            }
        }
        rest = after;
    }
    found
}

/// Every `(from stage, to stage, file:line)` of the library's sources.
fn dependencies(src: &Path) -> Vec<(String, String, String)> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files.sort();
    let mut deps = Vec::new();
    for file in files {
        let stage = stage_of(src, &file);
        if matches!(stage.as_str(), "lib" | "main" | "cli") {
            continue;
        }
        // Unit tests may drive the whole pipeline (a verifier test compiles
        // real programs): they are not dependencies of the stage's code.
        if file.file_name().is_some_and(|n| n == "tests.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&file).expect("readable source");
        // Comments out, lines joined (a `use crate::{...}` group may span
        // lines), up to the file's `#[cfg(test)]` module.
        let code: Vec<&str> = text
            .lines()
            .take_while(|line| line.trim() != "#[cfg(test)]")
            .map(|line| line.split("//").next().unwrap_or(""))
            .collect();
        let joined = code.join("\n");
        for (offset, to) in crate_paths(&joined) {
            if to != stage {
                let line = joined[..offset].matches('\n').count() + 1;
                let place = format!("{}:{line}", file.display());
                deps.push((stage.clone(), to, place));
            }
        }
    }
    deps
}

#[test]
fn stages_depend_in_one_direction() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let allowed: BTreeMap<&str, BTreeSet<&str>> = ALLOWED
        .iter()
        .map(|(stage, uses)| (*stage, uses.iter().copied().collect()))
        .collect();
    let mut wrong = Vec::new();
    for (from, to, place) in dependencies(&src) {
        let ok = allowed
            .get(from.as_str())
            .is_some_and(|uses| uses.contains(to.as_str()));
        if !ok {
            wrong.push(format!("{place}: {from} uses {to}"));
        }
    }
    assert!(
        wrong.is_empty(),
        "dependencies against the direction of the pipeline:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn every_stage_of_src_is_in_the_matrix() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let known: BTreeSet<&str> = ALLOWED.iter().map(|(stage, _)| *stage).collect();
    let unknown: BTreeSet<String> = files
        .iter()
        .map(|f| stage_of(&src, f))
        .filter(|s| !matches!(s.as_str(), "lib" | "main" | "cli") && !known.contains(s.as_str()))
        .collect();
    assert!(
        unknown.is_empty(),
        "stages missing from ALLOWED: {unknown:?}"
    );
}

#[test]
fn the_matrix_has_no_cycle() {
    // Depth-first search over the allowed edges: a stage reached again
    // while still on the path closes a cycle.
    fn visit<'a>(
        stage: &'a str,
        allowed: &BTreeMap<&'a str, Vec<&'a str>>,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) {
        assert!(!path.contains(&stage), "cycle: {path:?} -> {stage}");
        if done.contains(stage) {
            return;
        }
        path.push(stage);
        for next in allowed.get(stage).into_iter().flatten() {
            visit(next, allowed, path, done);
        }
        path.pop();
        done.insert(stage);
    }
    let allowed: BTreeMap<&str, Vec<&str>> = ALLOWED
        .iter()
        .map(|(stage, uses)| (*stage, uses.to_vec()))
        .collect();
    let mut done = BTreeSet::new();
    for stage in allowed.keys() {
        visit(stage, &allowed, &mut Vec::new(), &mut done);
    }
}

#[test]
fn the_scanner_sees_grouped_and_inline_paths() {
    let heads = |code: &str| -> Vec<String> {
        crate_paths(code)
            .into_iter()
            .map(|(_, head)| head)
            .collect()
    };
    assert_eq!(
        heads("use crate::{ir::op::Op, vm::Fault}; let x = crate::value::f();"),
        ["ir", "vm", "value"]
    );
    assert_eq!(
        heads("use crate::{\n    ir::op::Op,\n    vm::Fault,\n};"),
        ["ir", "vm"]
    );
    assert_eq!(crate_paths("fn f() {}"), Vec::new());
}

#[test]
fn the_command_line_uses_only_the_public_api() {
    let cli = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/cli");
    let mut files = Vec::new();
    rust_files(&cli, &mut files);
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable source");
        for (i, line) in text.lines().enumerate() {
            // `plcrun::Name` (root re-exports) is fine, `plcrun::stage::` is not.
            let mut rest = line.split("//").next().unwrap_or("");
            while let Some(at) = rest.find("plcrun::") {
                rest = &rest[at + "plcrun::".len()..];
                let ident: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                let is_module = ident.starts_with(|c: char| c.is_ascii_lowercase())
                    && rest[ident.len()..].starts_with("::");
                assert!(
                    !is_module,
                    "{}:{}: the CLI reaches into `plcrun::{ident}`",
                    file.display(),
                    i + 1
                );
            }
        }
    }
}

/// The length in lines of every `fn` of `text` whose body closes at the
/// indentation it opened at (rustfmt's layout): `(first line, name, lines)`.
fn function_lengths(text: &str) -> Vec<(usize, String, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let code = line.trim_start();
        let indent = &line[..line.len() - code.len()];
        let rest = ["pub(crate) ", "pub(super) ", "pub ", "const ", "unsafe "]
            .iter()
            .fold(code, |c, p| c.strip_prefix(p).unwrap_or(c));
        let Some(after) = rest.strip_prefix("fn ") else {
            continue;
        };
        let name: String = after
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if code.ends_with('}') {
            continue; // a one-line function
        }
        let close = format!("{indent}}}");
        if let Some(end) = lines[i + 1..].iter().position(|l| *l == close) {
            found.push((i + 1, name, end + 2));
        }
    }
    found
}

#[test]
fn no_function_but_the_dispatch_loop_is_longer_than_150_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut long = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable source");
        for (line, name, length) in function_lengths(&text) {
            let dispatch_loop = file.ends_with("vm/exec.rs") && name == "run";
            if length > 150 && !dispatch_loop {
                long.push(format!(
                    "{}:{line}: `{name}` has {length} lines",
                    file.display()
                ));
            }
        }
    }
    assert!(long.is_empty(), "split these by case:\n{}", long.join("\n"));
}

#[test]
fn function_lengths_are_measured_from_fn_to_its_closing_brace() {
    let text = "impl X {\n    pub fn a() {\n        1;\n    }\n}\nfn b() {}\nfn c() {\n}\n";
    assert_eq!(
        function_lengths(text),
        [(2, "a".to_string(), 3), (7, "c".to_string(), 2)]
    );
}
