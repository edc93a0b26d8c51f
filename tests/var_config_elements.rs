//! VAR_CONFIG through array elements (issue #11): an element of an array
//! of FB instances (`R.main.vs[2].coil`) and an element of an array
//! declared `AT %Q*` (`R.main.vs[1].lamps[3]`); every element left
//! uncompleted gets the next free address; bad indexes E711; the form warns W326.

use plcrun::{CompileError, Options, Plc, Severity};

const PLANT: &str = "
FUNCTION_BLOCK Valve
VAR_INPUT open_cmd : BOOL; END_VAR
VAR coil AT %Q* : BOOL; lamps AT %Q* : ARRAY[1..2] OF BOOL; level : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
coil := open_cmd; lamps[1] := open_cmd; lamps[2] := NOT open_cmd; q := level;
END_FUNCTION_BLOCK
PROGRAM Plant
VAR vs : ARRAY[1..2] OF Valve; END_VAR
VAR_OUTPUT sum : INT; END_VAR
vs[1](open_cmd := TRUE); vs[2](open_cmd := FALSE); sum := vs[1].q + vs[2].q;
END_PROGRAM
";

fn with_config(lines: &str) -> String {
    format!(
        "{PLANT}CONFIGURATION Cell\nRESOURCE R ON PLC\n  TASK t (INTERVAL := T#10ms);\n  \
         PROGRAM main WITH t : Plant;\nEND_RESOURCE\nVAR_CONFIG\n{lines}\nEND_VAR\nEND_CONFIGURATION\n"
    )
}

const ALL: &str = "
  R.main.vs[1].coil AT %QX1.0 : BOOL;
  R.main.vs[2].coil AT %QX1.1 : BOOL;
  R.main.vs[1].lamps[1] AT %QX2.0 : BOOL;
  R.main.vs[1].lamps[2] AT %QX2.1 : BOOL;
  R.main.vs[2].lamps[1] AT %QX3.0 : BOOL;
  R.main.vs[2].lamps[2] AT %QX3.1 : BOOL;
  R.main.vs[2].level : INT := 5;";

fn compile(src: &str) -> Result<Plc, CompileError> {
    Plc::compile_files(&[("cell.st", src)], &Options::default())
}

fn error_codes(src: &str) -> Vec<&'static str> {
    match compile(src) {
        Ok(_) => panic!("compiled, but should not:\n{src}"),
        Err(e) => e
            .diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .map(|d| d.code)
            .collect(),
    }
}

#[test]
fn each_element_drives_the_address_its_line_gives() {
    let mut plc = compile(&with_config(ALL)).unwrap_or_else(|e| panic!("{e}"));
    plc.run_cycle().unwrap();
    let image = plc.process_image();
    // vs[1] opened: its coil and lamp 1 on, lamp 2 off; vs[2] the opposite.
    assert_eq!(image.read_bit("%QX1.0"), Ok(true));
    assert_eq!(image.read_bit("%QX1.1"), Ok(false));
    assert_eq!(image.read_bit("%QX2.0"), Ok(true));
    assert_eq!(image.read_bit("%QX2.1"), Ok(false));
    assert_eq!(image.read_bit("%QX3.0"), Ok(false));
    assert_eq!(image.read_bit("%QX3.1"), Ok(true));
    // vs[2].level starts at its VAR_CONFIG value, vs[1]'s at 0.
    assert_eq!(plc.read("main.sum").unwrap().to_literal(), "5");
}

#[test]
fn the_form_warns_w326_once_per_line() {
    let plc = compile(&with_config(ALL)).unwrap_or_else(|e| panic!("{e}"));
    let n = plc.warnings().iter().filter(|d| d.code == "W326").count();
    assert_eq!(n, 7);
}

#[test]
fn an_element_left_uncompleted_gets_the_next_free_address() {
    let located = |plc: &plcrun::Plc, name: &str| {
        plc.image()
            .globals
            .iter()
            .find(|r| r.name.eq_ignore_ascii_case(name))
            .and_then(|r| r.location.clone())
    };
    // vs[2].lamps[2] has no line: it goes after the highest output, %QX3.1.
    let some = ALL.replace("  R.main.vs[2].lamps[2] AT %QX3.1 : BOOL;", "");
    let plc = compile(&with_config(&some)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        located(&plc, "main.vs[2].lamps[2]").as_deref(),
        Some("%QX4.0"),
        "the highest is %QX3.0 now"
    );
    // No VAR_CONFIG at all: every coil and lamp is placed, in instance order.
    let plc = compile(&with_config("")).unwrap_or_else(|e| panic!("{e}"));
    let names = [
        "main.vs[1].coil",
        "main.vs[1].lamps[1]",
        "main.vs[1].lamps[2]",
        "main.vs[2].coil",
    ];
    let got: Vec<Option<String>> = names.iter().map(|n| located(&plc, n)).collect();
    assert!(got.iter().all(Option::is_some), "{got:?}");
    let mut distinct = got.clone();
    distinct.sort();
    distinct.dedup();
    assert_eq!(distinct.len(), got.len(), "{got:?}");
}

#[test]
fn a_bad_index_or_an_index_on_no_array_is_e711() {
    let out = ALL.replace("R.main.vs[2].level", "R.main.vs[3].level");
    assert_eq!(error_codes(&with_config(&out)), vec!["E711"]);
    let two = ALL.replace("R.main.vs[2].level", "R.main.vs[2, 1].level");
    assert_eq!(error_codes(&with_config(&two)), vec!["E711"]);
    let scalar = ALL.replace("R.main.vs[2].level", "R.main.vs[2].level[1]");
    assert_eq!(error_codes(&with_config(&scalar)), vec!["E711"]);
    let program = ALL.replace("R.main.vs[2].level", "R.main[1].vs[2].level");
    assert_eq!(error_codes(&with_config(&program)), vec!["E711"]);
}

#[test]
fn an_incomplete_address_on_an_array_of_instances_is_still_e207() {
    let src = "PROGRAM P\nVAR x AT %Q* : ARRAY[1..2] OF TON; END_VAR\nEND_PROGRAM\n";
    assert_eq!(error_codes(src), vec!["E207"]);
    // An array of structures: each field of each element has an address.
    let src = "TYPE S : STRUCT a : INT; b : BOOL; END_STRUCT END_TYPE\nPROGRAM P\nVAR x AT %Q* : ARRAY[1..2] OF S; END_VAR\nEND_PROGRAM\n";
    if let Err(e) = compile(src) {
        panic!("{e}");
    }
}
