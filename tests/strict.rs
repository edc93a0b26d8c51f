//! `--strict` (docs/diagnostics.md, "Compatibility extensions (W300-W399)
//! and strict mode"): every compatibility-extension warning, any code
//! W300-W399 (or the dialect's W485-W490) whichever stage reports it,
//! becomes an error with the same code; no other diagnostic changes.

use plcrun::{
    CheckOptions, Diagnostic, Diagnostics, Options, Plc, STRICT_NOTE, Severity, SourceMap, Span,
    is_compatibility_code,
};

fn sources(text: &str) -> SourceMap {
    let mut map = SourceMap::new();
    map.add("t.st", text);
    map
}

fn check(text: &str, strict: bool) -> Diagnostics {
    let options = CheckOptions {
        strict,
        ..CheckOptions::default()
    };
    plcrun::check(&sources(text), &options).diagnostics
}

/// Matiec's embedded C (W360) next to a plain pragma (W001, not an
/// extension: pragmas are IEC).
const EMBEDDED: &str = "PROGRAM P
VAR_OUTPUT n : INT; END_VAR
{ plain pragma }
n := n + 1;
{{ printf(\"%d\", n); }}
END_PROGRAM
";

/// The rule itself: strict mode changes a diagnostic exactly when its code
/// is W300-W399 or W485-W490, keeps its code, span and message, and adds the note.
fn assert_strict_rule(lax: &Diagnostics, strict: &Diagnostics) {
    assert_eq!(lax.len(), strict.len());
    for (a, b) in lax.iter().zip(strict.iter()) {
        assert_eq!((a.code, a.span, &a.message), (b.code, b.span, &b.message));
        if a.severity == Severity::Warning && is_compatibility_code(a.code) {
            assert_eq!(b.severity, Severity::Error, "{} stays a warning", a.code);
            assert_eq!(b.notes.last().map(String::as_str), Some(STRICT_NOTE));
        } else {
            assert_eq!(a, b, "{} changed under --strict", a.code);
        }
    }
}

#[test]
fn strict_makes_the_embedded_c_warning_an_error_and_nothing_else() {
    let lax = check(EMBEDDED, false);
    let codes: Vec<_> = lax.iter().map(|d| (d.code, d.severity)).collect();
    assert_eq!(
        codes,
        [("W001", Severity::Warning), ("W360", Severity::Warning)]
    );
    let strict = check(EMBEDDED, true);
    assert_strict_rule(&lax, &strict);
    assert!(strict.has_errors());
    let rendered = strict.render(&sources(EMBEDDED));
    assert!(rendered.contains("error[W360]"), "{rendered}");
    assert!(rendered.contains("warning[W001]"), "{rendered}");
}

#[test]
fn a_strict_plc_refuses_the_program_a_lax_one_runs() {
    let lax = Plc::compile_files(&[("t.st", EMBEDDED)], &Options::default()).expect("compiles");
    assert!(lax.warnings().iter().any(|d| d.code == "W360"));
    let strict = Options {
        strict: true,
        ..Options::default()
    };
    let err = match Plc::compile_files(&[("t.st", EMBEDDED)], &strict) {
        Ok(_) => panic!("--strict must refuse embedded C"),
        Err(e) => e,
    };
    let w360 = err.diagnostics.iter().find(|d| d.code == "W360").unwrap();
    assert_eq!(w360.severity, Severity::Error);
}

#[test]
fn strict_leaves_an_encoding_warning_alone() {
    // W020 (a file read as Windows-1252) is a remark, not an extension.
    let bytes = b"PROGRAM P (* Z\xe4hler *) VAR n : INT; END_VAR n := 1; END_PROGRAM";
    let options = Options {
        strict: true,
        ..Options::default()
    };
    let plc = Plc::compile_bytes(&[("t.st", &bytes[..])], &options).expect("compiles");
    let w: Vec<_> = plc
        .warnings()
        .iter()
        .map(|d| (d.code, d.severity))
        .collect();
    assert_eq!(w, [("W020", Severity::Warning)]);
}

#[test]
fn the_rule_covers_every_code_from_w300_to_w399_and_the_dialects_w485_to_w493_and_no_other() {
    let mut all = Diagnostics::new();
    for letter in ['W', 'E', 'R'] {
        for n in 0..1000 {
            let code: &'static str = Box::leak(format!("{letter}{n:03}").into_boxed_str());
            all.push(Diagnostic::warning(code, Span::default(), "m"));
        }
    }
    all.push(Diagnostic::warning("W3", Span::default(), "short"));
    all.push(Diagnostic::warning("W3000", Span::default(), "long"));
    all.push(Diagnostic::warning("W3x0", Span::default(), "not a number"));
    let lax = all.clone();
    assert_eq!(all.make_strict(), 109);
    assert_strict_rule(&lax, &all);
    let upgraded: Vec<_> = all
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| d.code)
        .collect();
    assert_eq!(upgraded.first(), Some(&"W300"));
    assert_eq!(upgraded[99], "W399");
    assert_eq!(
        upgraded[100..],
        [
            "W485", "W486", "W487", "W488", "W489", "W490", "W491", "W492", "W493"
        ]
    );
    // An error already is left as it is (no second note).
    let mut twice = all.clone();
    assert_eq!(twice.make_strict(), 0);
    assert_eq!(
        twice.iter().collect::<Vec<_>>(),
        all.iter().collect::<Vec<_>>()
    );
}

/// The `st` examples of one `W3xx` section of docs/diagnostics.md.
fn documented_examples() -> Vec<(String, String)> {
    let doc = include_str!("../docs/diagnostics.md");
    let mut out = Vec::new();
    let mut code: Option<String> = None;
    let mut block: Option<String> = None;
    for line in doc.lines() {
        if let Some(b) = &mut block {
            if line.starts_with("```") {
                if let Some(c) = &code {
                    out.push((c.clone(), std::mem::take(b)));
                }
                block = None;
            } else {
                b.push_str(line);
                b.push('\n');
            }
            continue;
        }
        if line.starts_with("```st") {
            block = Some(String::new());
        } else if line.starts_with('#') {
            let title = line.trim_start_matches('#').trim();
            code = (title.len() == 4 && is_compatibility_code(title)).then(|| title.to_string());
        }
    }
    out
}

#[test]
fn every_documented_compatibility_warning_is_an_error_under_strict() {
    // Whoever adds a W3xx documents it with an example; compiled, the
    // example gives that warning, and under --strict that error.
    let mut seen = Vec::new();
    for (code, example) in documented_examples() {
        let lax = check(&example, false);
        if !lax
            .iter()
            .any(|d| d.code == code && d.severity == Severity::Warning)
        {
            continue;
        }
        let strict = check(&example, true);
        assert_strict_rule(&lax, &strict);
        assert!(
            strict
                .iter()
                .any(|d| d.code == code && d.severity == Severity::Error),
            "{code}"
        );
        seen.push(code);
    }
    assert!(seen.contains(&"W360".to_string()), "{seen:?}");
}
