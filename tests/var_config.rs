//! `VAR_CONFIG` and incomplete located variables (`AT %I*`, `%Q*`, `%M*`)
//! in function blocks and programs, completed per instance by the
//! configuration (docs/semantics.md, "VAR_CONFIG"); the errors E710-E714; an
//! incomplete address that no VAR_CONFIG completes gets the next free
//! address of its area (docs/runtime.md, "Incomplete addresses").

use plcrun::{CompileError, Options, Plc};

/// A valve block whose coil and position sensor are wired per instance.
const VALVE: &str = "
FUNCTION_BLOCK Valve
VAR_INPUT open_cmd : BOOL; END_VAR
VAR_OUTPUT position : INT; END_VAR
VAR
  coil AT %Q* : BOOL;
  sensor AT %IW* : INT;
END_VAR
coil := open_cmd;
position := sensor;
END_FUNCTION_BLOCK

PROGRAM Plant
VAR v1, v2 : Valve; cmd : BOOL := TRUE; END_VAR
VAR_OUTPUT sum : INT; END_VAR
v1(open_cmd := cmd);
v2(open_cmd := NOT cmd);
sum := v1.position + v2.position;
END_PROGRAM
";

fn with_config(var_config: &str) -> String {
    format!(
        "{VALVE}
CONFIGURATION Cell
RESOURCE R ON PLC
  TASK t (INTERVAL := T#10ms);
  PROGRAM main WITH t : Plant;
END_RESOURCE
VAR_CONFIG
{var_config}
END_VAR
END_CONFIGURATION
"
    )
}

const COMPLETE: &str = "
  R.main.v1.coil AT %QX1.0 : BOOL;
  R.main.v2.coil AT %QX1.1 : BOOL;
  R.main.v1.sensor AT %IW2 : INT;
  R.main.v2.sensor AT %IW4 : INT := 7;";

fn compile(src: &str) -> Result<Plc, CompileError> {
    Plc::compile_files(&[("cell.st", src)], &Options::default())
}

/// The codes of a compilation that must fail.
fn error_codes(src: &str) -> Vec<&'static str> {
    match compile(src) {
        Ok(_) => panic!("compiled, but should not:\n{src}"),
        Err(e) => e.diagnostics.iter().map(|d| d.code).collect(),
    }
}

#[test]
fn each_instance_drives_the_address_its_configuration_gives() {
    let mut plc = compile(&with_config(COMPLETE)).unwrap_or_else(|e| panic!("{e}"));
    plc.run_cycle().unwrap();
    // v1 is opened (cmd TRUE), v2 closed.
    assert_eq!(plc.process_image().read_bit("%QX1.0"), Ok(true));
    assert_eq!(plc.process_image().read_bit("%QX1.1"), Ok(false));
    assert_eq!(plc.read("%QX1.0").unwrap().to_literal(), "TRUE");
    // Inputs: written into the image by the host, read by the instance.
    plc.process_image_mut().write_word("%IW2", 40).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("main.v1.position").unwrap().to_literal(), "40");
    // v2's sensor starts at its VAR_CONFIG initial value.
    assert_eq!(plc.read("main.v2.position").unwrap().to_literal(), "7");
    assert_eq!(plc.read("main.sum").unwrap().to_literal(), "47");
}

#[test]
fn the_resource_name_may_be_left_out_when_there_is_one() {
    let short = COMPLETE.replace("R.main", "main");
    let mut plc = compile(&with_config(&short)).unwrap_or_else(|e| panic!("{e}"));
    plc.run_cycle().unwrap();
    assert_eq!(plc.process_image().read_bit("%QX1.0"), Ok(true));
}

/// The address `name` ended up at.
fn address_of(plc: &Plc, name: &str) -> Option<String> {
    plc.image()
        .globals
        .iter()
        .find(|r| r.name.eq_ignore_ascii_case(name))
        .and_then(|r| r.location.clone())
}

#[test]
fn an_incomplete_address_left_uncompleted_gets_the_next_free_address() {
    let partial = COMPLETE.replace("  R.main.v2.coil AT %QX1.1 : BOOL;", "");
    let mut plc = compile(&with_config(&partial)).unwrap_or_else(|e| panic!("{e}"));
    // %QX1.0 is the highest output used: v2.coil takes the next byte.
    assert_eq!(address_of(&plc, "main.v2.coil").as_deref(), Some("%QX2.0"));
    plc.run_cycle().unwrap();
    // v2 is closed (cmd is TRUE, v2 gets NOT cmd), v1 open.
    assert_eq!(plc.process_image().read_bit("%QX2.0"), Ok(false));
    assert_eq!(plc.process_image().read_bit("%QX1.0"), Ok(true));
}

#[test]
fn without_a_configuration_incomplete_addresses_are_placed_in_declaration_order() {
    let src = "PROGRAM P VAR x AT %I* : BOOL; w AT %IW* : INT; y AT %I* : BOOL; \
               z AT %IX0.5 : BOOL; out AT %Q* : DINT; s AT %I* : STRING; END_VAR \
               out := SEL(x, 1, 2); END_PROGRAM";
    // A STRING cannot get an address.
    assert_eq!(error_codes(src), ["E710"]);
    let src = src.replace(" s AT %I* : STRING;", "");
    let mut plc = compile(&src).unwrap_or_else(|e| panic!("{e}"));
    let got: Vec<Option<String>> = ["P.x", "P.w", "P.y", "P.out"]
        .iter()
        .map(|n| address_of(&plc, n))
        .collect();
    // Byte 0 holds z: bits go to byte 1, the word to bytes 2-3 (%IW1).
    let want = ["%IX1.0", "%IW1", "%IX1.1", "%QD0"].map(|a| Some(a.to_string()));
    assert_eq!(got, want);
    plc.process_image_mut().write_bit("%IX1.0", true).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.process_image().read_dword("%QD0"), Ok(2));
    // Checking a library that declares such blocks but runs none is fine.
    let lib = VALVE
        .replace("PROGRAM Plant", "FUNCTION_BLOCK Plant2")
        .replace("END_PROGRAM", "END_FUNCTION_BLOCK");
    let report = plcrun::check(
        &{
            let mut m = plcrun::SourceMap::new();
            m.add("lib.st", lib);
            m
        },
        &plcrun::CheckOptions::default(),
    );
    assert!(report.is_ok(), "{:?}", report.diagnostics);
}

#[test]
fn a_path_that_names_nothing_is_e711() {
    for bad in [
        "X.main.v1.coil AT %QX1.0 : BOOL;",
        "R.other.v1.coil AT %QX1.0 : BOOL;",
        "R.main.v9.coil AT %QX1.0 : BOOL;",
        "R.main.v1.nothing AT %QX1.0 : BOOL;",
        "R.main.cmd.x AT %QX1.0 : BOOL;",
    ] {
        let src = with_config(&format!("{COMPLETE}\n{bad}"));
        assert_eq!(error_codes(&src), ["E711"], "{bad}");
    }
}

#[test]
fn a_type_other_than_the_declared_one_is_e712() {
    let src = with_config(&COMPLETE.replace(
        "R.main.v1.sensor AT %IW2 : INT",
        "R.main.v1.sensor AT %IW2 : UINT",
    ));
    let codes = error_codes(&src);
    assert!(codes.contains(&"E712"), "{codes:?}");
}

#[test]
fn an_address_that_cannot_complete_the_declaration_is_e713() {
    for (from, to) in [
        // another area
        ("R.main.v1.coil AT %QX1.0", "R.main.v1.coil AT %IX1.0"),
        // another size than the declared %IW*
        ("R.main.v1.sensor AT %IW2", "R.main.v1.sensor AT %ID2"),
        // a size that cannot hold a BOOL
        ("R.main.v1.coil AT %QX1.0", "R.main.v1.coil AT %QB1"),
        // still incomplete
        ("R.main.v1.coil AT %QX1.0", "R.main.v1.coil AT %Q*"),
    ] {
        let src = with_config(&COMPLETE.replace(from, to));
        let codes = error_codes(&src);
        assert!(codes.contains(&"E713"), "{to}: {codes:?}");
    }
    // A variable without an incomplete address cannot be given one.
    let src = with_config(&format!("{COMPLETE}\nR.main.v1.open_cmd AT %QX3.0 : BOOL;"));
    assert_eq!(error_codes(&src), ["E713"]);
}

#[test]
fn a_variable_configured_twice_is_e714() {
    let src = with_config(&format!("{COMPLETE}\nR.main.v1.coil AT %QX2.0 : BOOL;"));
    assert_eq!(error_codes(&src), ["E714"]);
}

#[test]
fn var_config_gives_initial_values_to_instance_variables() {
    let src = with_config(&format!("{COMPLETE}\nR.main.cmd : BOOL := FALSE;"));
    let mut plc = compile(&src).unwrap_or_else(|e| panic!("{e}"));
    plc.run_cycle().unwrap();
    // cmd FALSE: v1 closed, v2 open.
    assert_eq!(plc.process_image().read_bit("%QX1.0"), Ok(false));
    assert_eq!(plc.process_image().read_bit("%QX1.1"), Ok(true));
}

#[test]
fn incomplete_addresses_are_refused_where_no_instance_holds_them() {
    let src = "FUNCTION F : BOOL VAR x AT %I* : BOOL; END_VAR F := TRUE; END_FUNCTION";
    assert_eq!(error_codes(src), ["E207"]);
    let src = "FUNCTION_BLOCK B VAR_IN_OUT x AT %I* : BOOL; END_VAR END_FUNCTION_BLOCK";
    assert_eq!(error_codes(src), ["E207"]);
    let src = "FUNCTION_BLOCK B VAR x AT %IW* : BOOL; END_VAR END_FUNCTION_BLOCK";
    assert_eq!(error_codes(src), ["E207"]);
}
