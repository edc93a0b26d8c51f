//! The process image (docs/runtime.md, "The process image"): the mapping of
//! direct addresses to bytes and bits (Moeller's five-field form
//! included), host access by bit, byte, word, double and long word, typed
//! errors outside an area, inputs latched at the start of a cycle and
//! outputs published at its end, overlapping located variables. Under the
//! default `iec` addressing (words numbered by word); the other
//! conventions are in tests/addressing.rs.

use plcrun::{AddressError, Area, Options, Plc, Width};

fn compile(src: &str) -> Plc {
    Plc::compile_files(&[("p.st", src)], &Options::default()).expect("compiles")
}

const MOELLER: &str = "PROGRAM M
VAR
    sw AT %I0.0.0.0.1 : BOOL;
    level AT %IW1 : INT;
    lamp AT %Q0.0.0.1.7 : BOOL;
    copy AT %QW2 : INT;
    big AT %QD2 : DINT;
    huge AT %QL2 : LINT;
    flag AT %M0.0.0.2.2 : BOOL;
END_VAR
lamp := sw;
copy := level;
big := level * 1000;
huge := big;
flag := NOT sw;
END_PROGRAM
";

#[test]
fn areas_are_as_long_as_the_highest_address_used() {
    let plc = compile(MOELLER);
    let io = plc.process_image();
    assert_eq!(io.area(Area::Input).len(), 4); // %IW1 is bytes 2-3
    assert_eq!(io.area(Area::Output).len(), 24); // %QL2 is bytes 16-23
    assert_eq!(io.area(Area::Memory).len(), 3); // %M0.0.0.2.2 is byte 2
    assert!(io.unmapped().is_empty());
}

#[test]
fn moeller_addresses_map_to_their_last_two_fields() {
    let mut plc = compile(MOELLER);
    plc.process_image_mut()
        .write_bit("%I0.0.0.0.1", true)
        .unwrap();
    plc.process_image_mut().write_word("%IW1", 0xFFFE).unwrap(); // -2
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("sw").unwrap().to_literal(), "TRUE");
    assert_eq!(plc.read("level").unwrap().to_literal(), "-2");
    let io = plc.process_image();
    // %Q0.0.0.1.7 is byte 1, bit 7, and the same place as %QX1.7.
    assert!(io.read_bit("%Q0.0.0.1.7").unwrap());
    assert!(io.read_bit("%QX1.7").unwrap());
    assert_eq!(io.area(Area::Output)[1], 0x80);
    assert_eq!(io.read_word("%QW2").unwrap(), 0xFFFE);
    assert_eq!(io.read_dword("%QD2").unwrap(), (-2000i32) as u32);
    assert_eq!(io.read_lword("%QL2").unwrap(), (-2000i64) as u64);
    // Little-endian: the low byte first; %QW2 is bytes 4-5, %QD2 8-11.
    assert_eq!(&io.area(Area::Output)[4..6], &[0xFE, 0xFF]);
    assert_eq!(&io.area(Area::Output)[8..12], &(-2000i32).to_le_bytes());
    assert!(!io.read_bit("%M0.0.0.2.2").unwrap());
    // %IX0.1 is %I0.0.0.0.1, the input byte the host wrote.
    assert_eq!(io.area(Area::Input)[0], 0b10);
}

#[test]
fn bulk_input_bytes_are_seen_by_the_program() {
    let mut plc = compile(MOELLER);
    plc.process_image_mut()
        .inputs_mut()
        .copy_from_slice(&[0b10, 0, 0x34, 0x12]);
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("level").unwrap().to_literal(), "4660");
    assert_eq!(plc.process_image().read_word("%QW2").unwrap(), 0x1234);
    assert_eq!(plc.process_image().read_byte("%QB1").unwrap(), 0x80);
    assert!(plc.process_image().read_byte("%QX1.7").is_err()); // a bit address
}

#[test]
fn accesses_outside_an_area_or_of_the_wrong_width_are_typed_errors() {
    let mut plc = compile(MOELLER);
    let io = plc.process_image_mut();
    assert!(matches!(
        io.read_word("%IW2"),
        Err(AddressError::OutOfRange { area_size: 4, .. })
    ));
    assert!(matches!(
        io.write_bit("%IX4.0", true),
        Err(AddressError::OutOfRange { .. })
    ));
    assert!(matches!(
        io.read_word("%IX0.1"),
        Err(AddressError::WrongWidth {
            expected: Width::Word,
            ..
        })
    ));
    assert!(matches!(
        io.write_word("%QW2", 1),
        Err(AddressError::NotWritable { .. })
    ));
    assert!(matches!(
        io.read_bit("IX0.1"),
        Err(AddressError::Syntax { .. })
    ));
    assert!(matches!(
        io.read_bit("%IX0.9"),
        Err(AddressError::BitOutOfRange { bit: 9, .. })
    ));
    assert!(matches!(
        io.read_bit("%I0.1.0.0.1"),
        Err(AddressError::LeadingField { value: 1, .. })
    ));
    let msg = io.read_word("%IW2").unwrap_err().to_string();
    assert!(msg.contains("%IW2") && msg.contains("4 bytes"), "{msg}");
}

#[test]
fn inputs_are_latched_at_the_start_of_a_cycle() {
    let mut plc = compile(MOELLER);
    plc.run_cycle().unwrap();
    plc.process_image_mut().write_bit("%IX0.1", true).unwrap();
    // Written into the image, not yet seen by the program.
    assert_eq!(plc.read("sw").unwrap().to_literal(), "FALSE");
    assert!(!plc.process_image().read_bit("%QX1.7").unwrap());
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("sw").unwrap().to_literal(), "TRUE");
    assert!(plc.process_image().read_bit("%QX1.7").unwrap());
}

#[test]
fn outputs_are_published_at_the_end_of_the_cycle_only() {
    let mut plc = compile(MOELLER);
    plc.process_image_mut().write_word("%IW1", 7).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.process_image().read_word("%QW2").unwrap(), 7);
    // The new input is in the image, the output not yet.
    plc.process_image_mut().write_word("%IW1", 8).unwrap();
    assert_eq!(plc.process_image().read_word("%QW2").unwrap(), 7);
    plc.run_cycle().unwrap();
    assert_eq!(plc.process_image().read_word("%QW2").unwrap(), 8);
}

#[test]
fn host_writes_by_name_reach_the_image_at_once() {
    let mut plc = compile(MOELLER);
    plc.write("%IX0.1", "TRUE").unwrap();
    assert!(plc.process_image().read_bit("%IX0.1").unwrap());
    assert_eq!(plc.read("sw").unwrap().to_literal(), "TRUE");
    plc.write("level", "-3").unwrap();
    assert_eq!(plc.process_image().read_word("%IW1").unwrap(), 0xFFFD);
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("copy").unwrap().to_literal(), "-3");
}

#[test]
fn a_program_write_to_an_input_lasts_until_the_host_changes_it() {
    // W202: the program writes %I; the next host value overwrites it.
    let src = "PROGRAM P VAR x AT %IX0.0 : BOOL; n : INT; END_VAR
        n := n + 1; IF n = 1 THEN x := TRUE; END_IF END_PROGRAM";
    let mut plc = compile(src);
    plc.run_cycle().unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("x").unwrap().to_literal(), "TRUE");
    plc.process_image_mut().write_bit("%IX0.0", false).unwrap();
    plc.process_image_mut().write_bit("%IX0.0", true).unwrap();
    plc.process_image_mut().write_bit("%IX0.0", false).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("x").unwrap().to_literal(), "TRUE"); // image unchanged
    plc.process_image_mut().write_bit("%IX0.0", true).unwrap();
    plc.run_cycle().unwrap();
    plc.process_image_mut().write_bit("%IX0.0", false).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("x").unwrap().to_literal(), "FALSE");
}

#[test]
fn overlapping_memory_variables_see_each_other_from_the_next_cycle() {
    let src = "PROGRAM P
        VAR w AT %MW0 : WORD; b AT %MX0.1 : BOOL; hi AT %MX1.0 : BOOL; n : INT; END_VAR
        n := n + 1;
        IF n = 1 THEN w := 16#0100; END_IF
        IF n = 2 THEN b := TRUE; END_IF
        END_PROGRAM";
    let mut plc = compile(src);
    plc.run_cycle().unwrap();
    // The word is published; the bits inside it are not seen yet.
    assert_eq!(plc.process_image().read_word("%MW0").unwrap(), 0x0100);
    assert_eq!(plc.read("hi").unwrap().to_literal(), "FALSE");
    plc.run_cycle().unwrap();
    // Cycle 2 latched the word's bits into hi, and wrote b on top of it.
    assert_eq!(plc.read("hi").unwrap().to_literal(), "TRUE");
    assert_eq!(plc.process_image().read_word("%MW0").unwrap(), 0x0102);
    assert_eq!(plc.read("w").unwrap().to_literal(), "16#100");
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("w").unwrap().to_literal(), "16#102");
    // The host writes %M like %I.
    plc.process_image_mut().write_word("%MW0", 0).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("b").unwrap().to_literal(), "FALSE");
    assert_eq!(plc.read("w").unwrap().to_literal(), "16#0");
}

#[test]
fn typed_values_use_the_documented_encoding() {
    let src = "PROGRAM P
        VAR r AT %ID0 : REAL; t AT %ID1 : TIME; out_r AT %QD0 : REAL; out_t AT %QD1 : TIME;
            neg AT %QD2 : TIME := T#-1ms; END_VAR
        out_r := r * 2.0; out_t := t + T#1s;
        END_PROGRAM";
    let mut plc = compile(src);
    let io = plc.process_image_mut();
    io.write_dword("%ID0", 1.25f32.to_bits()).unwrap();
    io.write_dword("%ID1", 250).unwrap(); // TIME in milliseconds
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("t").unwrap().to_literal(), "T#250ms");
    let io = plc.process_image();
    assert_eq!(f32::from_bits(io.read_dword("%QD0").unwrap()), 2.5);
    assert_eq!(io.read_dword("%QD1").unwrap(), 1250);
    // A negative TIME at %D: milliseconds modulo 2^32, as CODESYS' unsigned TIME.
    assert_eq!(io.read_dword("%QD2").unwrap(), u32::MAX);
    // A TIME past T#24d20h31m23s647ms read from the image stays positive.
    plc.process_image_mut()
        .write_dword("%ID1", 4_000_000_000)
        .unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("t").unwrap().to_literal(), "T#46d7h6m40s");
}

#[test]
fn a_program_without_located_variables_has_an_empty_image() {
    let mut plc = compile("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM");
    assert!(plc.process_image().area(Area::Input).is_empty());
    assert!(matches!(
        plc.process_image_mut().write_bit("%IX0.0", true),
        Err(AddressError::OutOfRange { area_size: 0, .. })
    ));
}

#[test]
fn addresses_with_no_place_in_the_image_still_work_by_name() {
    let src = "PROGRAM P VAR x AT %I1.0.0.0.1 : BOOL; y AT %QX0.0 : BOOL; END_VAR
        y := x; END_PROGRAM";
    let mut plc = compile(src);
    assert_eq!(plc.process_image().unmapped().len(), 1);
    plc.write("x", "TRUE").unwrap();
    plc.run_cycle().unwrap();
    assert!(plc.process_image().read_bit("%QX0.0").unwrap());
}

#[test]
fn the_il_seed_program_runs_from_the_image() {
    // ALG01: SW1 is %I0.0.0.0.0, L1 is %Q0.0.0.1.7.
    let src =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/programs/alg01.il")).unwrap();
    let mut plc = Plc::compile_files(&[("alg01.il", &src)], &Options::default()).unwrap();
    plc.process_image_mut()
        .write_bit("%I0.0.0.0.0", true)
        .unwrap();
    for _ in 0..3 {
        plc.run_cycle().unwrap();
    }
    assert_eq!(plc.read("SW1").unwrap().to_literal(), "TRUE");
    let l1 = plc.read("L1").unwrap().to_literal();
    assert_eq!(
        plc.process_image().read_bit("%Q0.0.0.1.7").unwrap(),
        l1 == "TRUE"
    );
}
