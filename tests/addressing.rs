//! The three addressing conventions through the library's process image
//! API (docs/runtime.md, "Addressing"): where each convention puts words,
//! double and long words; host accessors and tables; the overlap warning
//! W204; the default chosen from the sources (S7-200 STL, PLCopen XML from
//! the OpenPLC Editor or Beremiz); `Options::addressing` winning over the
//! detection; `Plc::set_addressing`; retained located variables across
//! conventions.

use plcrun::{Addressing, Area, Options, Plc, RestoreMode, Severity, Width};

fn compile_with(name: &str, src: &str, addressing: Option<Addressing>) -> Plc {
    let options = Options {
        addressing,
        ..Options::default()
    };
    Plc::compile_files(&[(name, src)], &options).unwrap_or_else(|e| panic!("{e}"))
}

fn repo_text(path: &str) -> String {
    std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// The W204 warnings as (`line:col`, message, notes).
fn overlaps(plc: &Plc) -> Vec<(String, String, String)> {
    plc.warnings()
        .iter()
        .filter(|d| d.code == "W204")
        .map(|d| {
            assert_eq!(d.severity, Severity::Warning);
            let loc = plc.sources().location(d.span);
            let lc = loc.split_once(':').map(|x| x.1).unwrap_or("").to_string();
            (lc, d.message.clone(), d.notes.join("\n"))
        })
        .collect()
}

/// A bit, a word, a double and a long word whose bytes depend on the
/// convention, none overlapping another under any of them.
const SPREAD: &str = "PROGRAM P
VAR
    b AT %QX0.1 : BOOL := TRUE;
    w AT %QW1 : WORD := 16#1234;
    d AT %MD1 : DWORD := 16#89ABCDEF;
    l AT %ML8 : LWORD := 16#0102030405060708;
END_VAR
END_PROGRAM
";

#[test]
fn iec_numbers_words_by_word_in_one_image_per_area() {
    let mut plc = compile_with("p.st", SPREAD, Some(Addressing::Iec));
    assert!(plc.warnings().is_empty(), "{:?}", overlaps(&plc));
    plc.run_cycle().unwrap();
    let io = plc.process_image();
    assert_eq!(io.addressing(), Addressing::Iec);
    // %QW1 is bytes 2-3, beside the bit in byte 0.
    assert_eq!(io.area(Area::Output), &[0b10, 0, 0x34, 0x12]);
    assert_eq!(io.table(Area::Output, Width::Word), io.area(Area::Output));
    // %MD1 is bytes 4-7, %ML8 bytes 64-71, in the one %M image.
    let m = io.area(Area::Memory);
    assert_eq!(m.len(), 72);
    assert_eq!(&m[4..8], &0x89AB_CDEFu32.to_le_bytes());
    assert_eq!(&m[64..72], &0x0102_0304_0506_0708u64.to_le_bytes());
    assert_eq!(io.read_word("%QW1"), Ok(0x1234));
    assert_eq!(io.read_dword("%MD1"), Ok(0x89AB_CDEF));
    assert_eq!(io.read_lword("%ML8"), Ok(0x0102_0304_0506_0708));
    // The same bytes by other addresses: %QB2 is the low byte of %QW1.
    assert_eq!(io.read_byte("%QB2"), Ok(0x34));
    // %MW2 (bytes 4-5) is the low half of %MD1.
    assert_eq!(io.read_word("%MW2"), Ok(0xCDEF));
}

#[test]
fn openplc_gives_each_size_a_table_of_its_own() {
    let mut plc = compile_with("p.st", SPREAD, Some(Addressing::OpenPlc));
    assert!(plc.warnings().is_empty(), "{:?}", overlaps(&plc));
    plc.run_cycle().unwrap();
    let io = plc.process_image();
    assert_eq!(io.addressing(), Addressing::OpenPlc);
    assert_eq!(io.table(Area::Output, Width::Bit), &[0b10]);
    assert_eq!(io.table(Area::Output, Width::Word), &[0, 0, 0x34, 0x12]);
    assert_eq!(
        io.table(Area::Memory, Width::Dword),
        &[0, 0, 0, 0, 0xEF, 0xCD, 0xAB, 0x89]
    );
    let l = io.table(Area::Memory, Width::Lword);
    assert_eq!(l.len(), 72);
    assert_eq!(&l[64..72], &0x0102_0304_0506_0708u64.to_le_bytes());
    // No byte address in the program: the byte tables are empty.
    assert!(io.area(Area::Output).is_empty());
    assert!(io.table(Area::Memory, Width::Word).is_empty());
    assert_eq!(io.read_word("%QW1"), Ok(0x1234));
    assert_eq!(io.read_dword("%MD1"), Ok(0x89AB_CDEF));
    assert_eq!(io.read_lword("%ML8"), Ok(0x0102_0304_0506_0708));
    assert!(io.read_bit("%QX0.1").unwrap());
    // %QW0 is in the %QW table, not on top of the coils.
    assert_eq!(io.read_word("%QW0"), Ok(0));
}

#[test]
fn byte_numbers_every_address_by_byte() {
    let mut plc = compile_with("p.st", SPREAD, Some(Addressing::Byte));
    assert!(plc.warnings().is_empty(), "{:?}", overlaps(&plc));
    plc.run_cycle().unwrap();
    let io = plc.process_image();
    assert_eq!(io.addressing(), Addressing::Byte);
    // %QW1 is bytes 1-2.
    assert_eq!(io.area(Area::Output), &[0b10, 0x34, 0x12]);
    let m = io.area(Area::Memory);
    assert_eq!(m.len(), 16);
    assert_eq!(&m[1..5], &0x89AB_CDEFu32.to_le_bytes());
    assert_eq!(&m[8..16], &0x0102_0304_0506_0708u64.to_le_bytes());
}

#[test]
fn host_writes_reach_the_program_through_the_convention() {
    let src = "PROGRAM P
VAR raw AT %IW1 : INT; m AT %MD1 : DINT; copy AT %QW0 : INT; sum AT %QD2 : DINT; END_VAR
copy := raw; sum := m + 1;
END_PROGRAM";
    for addressing in Addressing::ALL {
        let mut plc = compile_with("p.st", src, Some(addressing));
        let io = plc.process_image_mut();
        io.write_word("%IW1", 0xFFF6).unwrap(); // -10
        io.write_dword("%MD1", 41).unwrap();
        plc.run_cycle().unwrap();
        assert_eq!(
            plc.read("copy").unwrap().to_literal(),
            "-10",
            "{addressing}"
        );
        assert_eq!(plc.read("sum").unwrap().to_literal(), "42", "{addressing}");
        let io = plc.process_image();
        // The input word sits where the convention says.
        let at = if addressing == Addressing::Byte { 1 } else { 2 };
        let table = io.table(Area::Input, Width::Word);
        assert_eq!(&table[at..at + 2], &[0xF6, 0xFF], "{addressing}");
        assert_eq!(io.read_dword("%QD2"), Ok(42), "{addressing}");
    }
    // Bulk writes go to the tables the host may write.
    let mut plc = compile_with("p.st", src, Some(Addressing::OpenPlc));
    let table = plc
        .process_image_mut()
        .table_mut(Area::Input, Width::Word)
        .unwrap();
    table.copy_from_slice(&[0, 0, 7, 0]);
    assert!(
        plc.process_image_mut()
            .table_mut(Area::Output, Width::Word)
            .is_none()
    );
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("copy").unwrap().to_literal(), "7");
}

#[test]
fn an_openplc_program_overlaps_under_iec_and_byte_only() {
    let src = repo_text("tests/addressing/openplc_tank.st");
    let iec = compile_with("tank.st", &src, None);
    assert_eq!(iec.addressing(), Addressing::Iec);
    let found = overlaps(&iec);
    assert_eq!(found.len(), 2, "{found:#?}");
    let (at, message, note) = &found[0];
    assert_eq!(at, "17:14");
    assert_eq!(
        message,
        "`%QW0` (bytes 0..1 of %Q under iec addressing) overlaps `%QX0.0` and 2 other \
         addresses: writing one changes the other"
    );
    assert!(note.contains("written for `openplc`"), "{note}");
    assert!(note.contains("--addressing openplc"), "{note}");
    assert_eq!(found[1].0, "20:14");
    assert!(
        found[1].1.starts_with("`%MD0` (bytes 0..3 of %M"),
        "{}",
        found[1].1
    );
    assert!(found[1].1.contains("overlaps `%MW0`"), "{}", found[1].1);

    let byte = compile_with("tank.st", &src, Some(Addressing::Byte));
    let found = overlaps(&byte);
    // %QW0/coils, %QW1/%QW0 and %QX1.0, %MD0/%MW0, %QW2/%QW1.
    assert_eq!(found.len(), 4, "{found:#?}");
    assert!(found[0].2.contains("byte offset"), "{}", found[0].2);

    let open = compile_with("tank.st", &src, Some(Addressing::OpenPlc));
    assert!(overlaps(&open).is_empty());
}

#[test]
fn under_iec_the_openplc_program_reads_back_garbage_and_under_openplc_what_it_wrote() {
    let src = repo_text("tests/addressing/openplc_tank.st");
    let run = |addressing| {
        let mut plc = compile_with("tank.st", &src, Some(addressing));
        plc.process_image_mut().write_word("%MW0", 7).unwrap();
        plc.run_cycle().unwrap();
        plc.run_cycle().unwrap();
        let io = plc.process_image();
        (
            io.read_word("%QW0").unwrap(),
            io.read_word("%QW1").unwrap(),
            io.read_bit("%QX0.0").unwrap(),
            io.read_word("%MW0").unwrap(),
        )
    };
    // OpenPLC's reading: level, echo = setpoint + 1, the pump coil, the setpoint.
    assert_eq!(run(Addressing::OpenPlc), (0xABCD, 8, true, 7));
    // Under iec the coils share byte 0 with %QW0, and %MD0 (total) writes
    // over %MW0 (setpoint): not what the program meant.
    assert_ne!(run(Addressing::Iec), (0xABCD, 8, true, 7));
}

#[test]
fn plcopen_from_the_openplc_editor_defaults_to_openplc() {
    let xml = repo_text("tests/addressing/openplc_tank.xml");
    let plc = compile_with("tank.xml", &xml, None);
    assert_eq!(plc.addressing(), Addressing::OpenPlc);
    assert!(overlaps(&plc).is_empty());
    // The flag wins over the detection.
    let plc = compile_with("tank.xml", &xml, Some(Addressing::Iec));
    assert_eq!(plc.addressing(), Addressing::Iec);
    assert_eq!(overlaps(&plc).len(), 2);
    // The same project as another tool writes it (no Beremiz namespace
    // prefix, another product): iec.
    let other = xml
        .replace("xmlns:ns1=\"http://www.plcopen.org/xml/tc6_0201\" ", "")
        .replace(
            "companyName=\"Unknown\" productName=\"Unnamed\"",
            "companyName=\"CODESYS Development GmbH\" productName=\"CODESYS\"",
        );
    assert_ne!(other, xml);
    let plc = compile_with("tank.xml", &other, None);
    assert_eq!(plc.addressing(), Addressing::Iec);
    // A header that names OpenPLC is enough without the prefix.
    let named = other.replace(
        "companyName=\"CODESYS Development GmbH\"",
        "companyName=\"OpenPLC Project\"",
    );
    let plc = compile_with("tank.xml", &named, None);
    assert_eq!(plc.addressing(), Addressing::OpenPlc);
}

#[test]
fn s7_200_sources_default_to_byte_addressing() {
    let plc = compile_with("t.awl", "NETWORK 1\nLD I0.0\n= Q0.0\n", None);
    assert_eq!(plc.addressing(), Addressing::Byte);
    let plc = compile_with("p.st", SPREAD, None);
    assert_eq!(plc.addressing(), Addressing::Iec);
}

#[test]
fn set_addressing_lays_the_image_out_again_and_rejudges_the_overlaps() {
    let src = repo_text("tests/addressing/openplc_tank.st");
    let mut plc = compile_with("tank.st", &src, None);
    plc.run_cycle().unwrap();
    assert_eq!(overlaps(&plc).len(), 2);
    plc.set_addressing(Addressing::OpenPlc);
    assert_eq!(plc.addressing(), Addressing::OpenPlc);
    assert!(overlaps(&plc).is_empty());
    // The variables kept their values and the image took them at once.
    let io = plc.process_image();
    assert_eq!(io.read_word("%QW0"), Ok(0xABCD));
    assert!(io.read_bit("%QX1.0").unwrap());
    plc.process_image_mut().write_word("%MW0", 2).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.process_image().read_word("%QW1"), Ok(3));
    assert_eq!(plc.process_image().read_dword("%MD0"), Ok(200_000));
    plc.set_addressing(Addressing::Byte);
    assert_eq!(overlaps(&plc).len(), 4);
}

#[test]
fn a_retained_located_variable_is_restored_by_name_under_another_convention() {
    let src = "PROGRAM P
VAR RETAIN kept AT %MW1 : UINT; END_VAR
VAR n : UINT; END_VAR
n := n + 1; IF n = 1 THEN kept := kept + 100; END_IF;
END_PROGRAM";
    let path = std::env::temp_dir().join(format!(
        "plcrun-addressing-retain-{}.json",
        std::process::id()
    ));
    let mut iec = compile_with("p.st", src, Some(Addressing::Iec));
    iec.run_cycle().unwrap();
    assert_eq!(iec.process_image().read_word("%MW1"), Ok(100));
    assert_eq!(&iec.process_image().area(Area::Memory)[2..4], &[100, 0]);
    iec.save_retain(&path).unwrap();
    let mut byte = compile_with("p.st", src, Some(Addressing::Byte));
    byte.restore_retain(&path, RestoreMode::Exact).unwrap();
    byte.run_cycle().unwrap();
    std::fs::remove_file(&path).unwrap();
    // Restored by name, then incremented once; under byte %MW1 is bytes 1-2.
    assert_eq!(byte.read("kept").unwrap().to_literal(), "200");
    assert_eq!(byte.process_image().read_word("%MW1"), Ok(200));
    assert_eq!(&byte.process_image().area(Area::Memory)[1..3], &[200, 0]);
}

#[test]
fn an_online_change_brings_the_new_versions_addressing() {
    let src = repo_text("tests/addressing/openplc_tank.st");
    let mut plc = compile_with("tank.st", &src, None);
    plc.run_cycle().unwrap();
    assert_eq!(plc.addressing(), Addressing::Iec);
    let options = Options {
        addressing: Some(Addressing::OpenPlc),
        ..Options::default()
    };
    plc.online_change_files(&[("tank.st", &src)], &options)
        .unwrap();
    assert_eq!(plc.addressing(), Addressing::OpenPlc);
    assert!(overlaps(&plc).is_empty());
    // The carried values, in the openplc tables at once.
    assert_eq!(plc.process_image().read_word("%QW0"), Ok(0xABCD));
    assert_eq!(plc.process_image().table(Area::Output, Width::Bit), &[1, 1]);
}
