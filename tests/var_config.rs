//! `VAR_CONFIG` and incomplete located variables (`AT %I*`, `%Q*`, `%M*`)
//! in function blocks and programs, completed per instance by the
//! configuration (docs/semantics.md, "VAR_CONFIG"); the errors E710-E714.

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

#[test]
fn an_incomplete_address_left_uncompleted_is_e710_at_its_declaration() {
    let partial = COMPLETE.replace("  R.main.v2.coil AT %QX1.1 : BOOL;", "");
    let err = match compile(&with_config(&partial)) {
        Ok(_) => panic!("v2.coil has no address"),
        Err(e) => e,
    };
    let d: Vec<_> = err.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{err}");
    assert_eq!(d[0].code, "E710");
    assert!(d[0].message.contains("main.v2.coil"), "{}", d[0].message);
    // Points at `%Q*` in the FB's declaration (line 6, column 11).
    assert_eq!(err.sources.location(d[0].span), "cell.st:6:11");
}

#[test]
fn without_a_configuration_an_incomplete_address_is_e710() {
    let src = "PROGRAM P VAR x AT %I* : BOOL; y : BOOL; END_VAR y := x; END_PROGRAM";
    assert_eq!(error_codes(src), ["E710"]);
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
