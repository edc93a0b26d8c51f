//! Source encodings (docs/semantics.md, "Source encodings"): UTF-8 with or
//! without a byte-order mark, Windows-1252 detected (W020) or given,
//! Latin-1 given; damaged UTF-8 stays E011. Diagnostics of a file read in
//! a single-byte code page point at the right line and column (in
//! characters) and show its text; a STRING literal keeps the file's bytes.

use plcrun::{
    Diagnostics, Options, Plc, Severity, SourceEncoding, SourceMap, TextEncoding, add_source_bytes,
    load_files_with,
};

/// Windows-1252 bytes of `text` (which must only hold characters of that
/// code page): written here by hand for the few characters the tests use.
fn cp1252(text: &str) -> Vec<u8> {
    text.chars()
        .map(|c| match c {
            '€' => 0x80,
            '„' => 0x84,
            '“' => 0x93,
            '•' => 0x95,
            'Š' => 0x8A,
            c if (c as u32) < 0x100 => c as u32 as u8,
            c => panic!("{c:?} is not in the test's table"),
        })
        .collect()
}

fn compile(bytes: &[u8], encoding: SourceEncoding) -> Result<Plc, plcrun::CompileError> {
    let options = Options {
        encoding,
        ..Options::default()
    };
    Plc::compile_bytes(&[("p.st", bytes)], &options)
}

fn fails(bytes: &[u8], encoding: SourceEncoding) -> plcrun::CompileError {
    match compile(bytes, encoding) {
        Ok(_) => panic!("compiled, but should not"),
        Err(e) => e,
    }
}

fn codes(d: &Diagnostics) -> Vec<&'static str> {
    d.iter().map(|d| d.code).collect()
}

const STRINGS: &str = "PROGRAM P
(* Zähler für „Grüße“ • Maß *)
VAR_OUTPUT
  euro_is_80 : BOOL; umlaut_is_e4 : BOOL; wide_euro : BOOL; len : INT; s_caron : BOOL;
END_VAR
VAR s : STRING; w : WSTRING; END_VAR
s := '€'; euro_is_80 := s = '$80'; len := LEN(s);
s := 'ä'; umlaut_is_e4 := s = '$E4';
w := \"€\"; wide_euro := w = \"$20AC\";
s := 'Š'; s_caron := s = '$8A';
END_PROGRAM
";

#[test]
fn a_windows_1252_file_is_detected_with_a_warning_naming_its_first_byte() {
    let plc = compile(&cp1252(STRINGS), SourceEncoding::Detect).expect("compiles");
    let warnings: Vec<_> = plc.warnings().iter().collect();
    assert_eq!(codes(plc.warnings()), ["W020"], "{warnings:?}");
    let w = warnings[0];
    assert_eq!(w.severity, Severity::Warning);
    assert!(w.message.contains("Windows-1252"), "{}", w.message);
    assert!(w.message.contains("0xE4"), "{}", w.message);
    // `ä` of `Zähler`, line 2, column 5 (characters).
    assert_eq!(plc.sources().location(w.span), "p.st:2:5");
    assert_eq!(
        plc.sources().files()[0].encoding(),
        TextEncoding::Windows1252
    );
}

#[test]
fn a_string_literal_keeps_the_bytes_of_the_file() {
    for encoding in [SourceEncoding::Detect, SourceEncoding::Windows1252] {
        let mut plc = compile(&cp1252(STRINGS), encoding).expect("compiles");
        plc.run_cycle().unwrap();
        for (name, want) in [
            ("euro_is_80", "TRUE"),
            ("umlaut_is_e4", "TRUE"),
            ("wide_euro", "TRUE"),
            ("len", "1"),
            ("s_caron", "TRUE"),
        ] {
            assert_eq!(plc.read(name).unwrap().to_literal(), want, "{name}");
        }
    }
}

#[test]
fn a_given_encoding_is_not_warned_about() {
    for encoding in [SourceEncoding::Windows1252, SourceEncoding::Latin1] {
        let plc = compile(&cp1252(STRINGS), encoding).expect("compiles");
        assert!(plc.warnings().is_empty(), "{:?}", codes(plc.warnings()));
    }
}

#[test]
fn latin_1_reads_0x80_to_0x9f_as_control_characters() {
    // In a STRING literal the byte is the same either way; in a WSTRING
    // literal Latin-1 gives U+0080, Windows-1252 gives `€`.
    let src = b"PROGRAM P VAR_OUTPUT a, b : BOOL; END_VAR
a := '\x80' = '$80'; b := \"\x80\" = \"$0080\"; END_PROGRAM";
    let mut plc = compile(src, SourceEncoding::Latin1).expect("compiles");
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("a").unwrap().to_literal(), "TRUE");
    assert_eq!(plc.read("b").unwrap().to_literal(), "TRUE");
    let mut plc = compile(src, SourceEncoding::Windows1252).expect("compiles");
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("a").unwrap().to_literal(), "TRUE");
    assert_eq!(plc.read("b").unwrap().to_literal(), "FALSE");
}

#[test]
fn diagnostics_after_single_byte_characters_point_at_the_right_column() {
    let src = "PROGRAM P VAR x : INT; END_VAR\n(* Größe *) x := 'Maß' + y;\nEND_PROGRAM\n";
    let err = fails(&cp1252(src), SourceEncoding::Detect);
    let e201 = err
        .diagnostics
        .iter()
        .find(|d| d.code == "E201")
        .expect("E201 for y");
    // `y` is the 26th character of line 2 (`ö` and `ß` count one each).
    assert_eq!(err.sources.location(e201.span), "p.st:2:26");
    let rendered = e201.render(&err.sources);
    assert!(
        rendered.contains("2 | (* Größe *) x := 'Maß' + y;"),
        "{rendered}"
    );
    let caret_line = rendered.lines().nth(4).unwrap();
    assert_eq!(caret_line.find('^'), Some("  | ".len() + 25), "{rendered}");
}

#[test]
fn utf_8_with_and_without_byte_order_mark_is_read_silently() {
    let text =
        "PROGRAM P (* Zähler € *) VAR_OUTPUT b : BOOL; END_VAR b := 'ä' = '$E4'; END_PROGRAM";
    let mut with_bom = vec![0xEF, 0xBB, 0xBF];
    with_bom.extend_from_slice(text.as_bytes());
    for bytes in [text.as_bytes(), &with_bom[..]] {
        let mut plc = compile(bytes, SourceEncoding::Detect).expect("compiles");
        assert!(plc.warnings().is_empty(), "{:?}", codes(plc.warnings()));
        assert_eq!(plc.sources().files()[0].encoding(), TextEncoding::Utf8);
        plc.run_cycle().unwrap();
        assert_eq!(plc.read("b").unwrap().to_literal(), "TRUE");
    }
}

#[test]
fn utf_8_required_or_damaged_utf_8_is_e011() {
    let latin = cp1252("PROGRAM P (* Zähler *) END_PROGRAM");
    let err = fails(&latin, SourceEncoding::Utf8);
    assert_eq!(codes(&err.diagnostics), ["E011"]);
    // Valid UTF-8 (`ä` as two bytes) next to a lone Latin-1 byte: damaged
    // UTF-8, not a Windows-1252 file.
    let mut mixed = "PROGRAM P (* Zähler *) END_PROGRAM (* ".as_bytes().to_vec();
    mixed.extend_from_slice(b"\xe4 *)");
    let err = fails(&mixed, SourceEncoding::Detect);
    assert_eq!(codes(&err.diagnostics), ["E011"]);
    assert!(err.diagnostics.iter().next().unwrap().notes[0].contains("--encoding"));
}

#[test]
fn undefined_windows_1252_bytes_survive_in_comments_and_strings() {
    // 0x81 has no character in Windows-1252: it is read as U+0081, kept as
    // that byte in a STRING, harmless in a comment, E001 in code.
    let ok = b"PROGRAM P (* \x81 *) VAR_OUTPUT b : BOOL; END_VAR b := '\x81' = '$81'; END_PROGRAM";
    let mut plc = compile(ok, SourceEncoding::Detect).expect("compiles");
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("b").unwrap().to_literal(), "TRUE");
    let bad = b"PROGRAM P VAR x : INT; END_VAR x := 1 \x81; END_PROGRAM";
    let err = fails(bad, SourceEncoding::Detect);
    assert!(codes(&err.diagnostics).contains(&"E001"));
}

#[test]
fn files_are_loaded_in_the_encoding_asked_for() {
    let dir = std::env::temp_dir().join(format!("plcrun_encoding_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("latin.st");
    std::fs::write(&path, cp1252("PROGRAM P (* Zähler *) END_PROGRAM")).unwrap();
    let mut diags = Diagnostics::new();
    let detected = load_files_with(&[&path], SourceEncoding::Detect, &mut diags).unwrap();
    assert_eq!(codes(&diags), ["W020"]);
    assert_eq!(
        detected.files()[0].text,
        "PROGRAM P (* Zähler *) END_PROGRAM"
    );
    let mut diags = Diagnostics::new();
    let given = load_files_with(&[&path], SourceEncoding::Latin1, &mut diags).unwrap();
    assert!(diags.is_empty());
    assert_eq!(given.files()[0].encoding(), TextEncoding::Latin1);
    let _ = std::fs::remove_dir_all(&dir);

    // The same through a source map built by hand.
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let id = add_source_bytes(
        &mut sources,
        "m.st",
        b"x \xb0",
        SourceEncoding::Detect,
        &mut diags,
    );
    assert_eq!(sources.file(id).text, "x °");
    assert_eq!(codes(&diags), ["W020"]);
}

#[test]
fn encoding_names_are_read_as_the_command_line_gives_them() {
    for (name, want) in [
        ("utf-8", SourceEncoding::Utf8),
        ("UTF8", SourceEncoding::Utf8),
        ("windows-1252", SourceEncoding::Windows1252),
        ("cp1252", SourceEncoding::Windows1252),
        ("latin-1", SourceEncoding::Latin1),
        ("ISO-8859-1", SourceEncoding::Latin1),
        ("detect", SourceEncoding::Detect),
    ] {
        assert_eq!(name.parse::<SourceEncoding>(), Ok(want), "{name}");
    }
    let err = "utf-16".parse::<SourceEncoding>().unwrap_err();
    assert!(err.to_string().contains("utf-16"));
}
