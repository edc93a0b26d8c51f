//! `<configVars>` of a PLCopen XML configuration: each `<configVariable>`
//! completes an incomplete address (`AT %Q*`) or gives one instance's
//! initial value, as a textual VAR_CONFIG line does (tests/var_config.rs).

use plcrun::{Options, Plc};

const HEAD: &str = "<?xml version=\"1.0\"?>\n<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\" xmlns:xhtml=\"http://www.w3.org/1999/xhtml\">\n<fileHeader companyName=\"x\" productName=\"x\" productVersion=\"1\" creationDateTime=\"2026-01-01T00:00:00\"/>\n<contentHeader name=\"x\"/>\n";

/// A valve block whose coil is wired per instance, a program with two
/// valves, and a configuration whose `<configVars>` is `config_vars`.
fn project(config_vars: &str) -> String {
    format!(
        "{HEAD}<types><dataTypes/><pous>\n\
<pou name=\"Valve\" pouType=\"functionBlock\"><interface>\
<inputVars><variable name=\"open_cmd\"><type><BOOL/></type></variable></inputVars>\
<outputVars><variable name=\"level\"><type><INT/></type></variable></outputVars>\
<localVars><variable name=\"coil\" address=\"%Q*\"><type><BOOL/></type></variable>\
<variable name=\"setting\"><type><INT/></type></variable></localVars>\
</interface><body><ST><xhtml:p>coil := open_cmd; level := setting;</xhtml:p></ST></body></pou>\n\
<pou name=\"Plant\" pouType=\"program\"><interface><localVars>\
<variable name=\"v1\"><type><derived name=\"Valve\"/></type></variable>\
<variable name=\"v2\"><type><derived name=\"Valve\"/></type></variable>\
</localVars><outputVars><variable name=\"sum\"><type><INT/></type></variable></outputVars></interface>\
<body><ST><xhtml:p>v1(open_cmd := TRUE); v2(open_cmd := FALSE); sum := v1.level + v2.level;</xhtml:p></ST></body></pou>\n\
</pous></types>\n<instances><configurations><configuration name=\"Cell\">\
<resource name=\"R\"><task name=\"t\" interval=\"T#10ms\" priority=\"1\">\
<pouInstance name=\"main\" typeName=\"Plant\"/></task></resource>\
{config_vars}</configuration></configurations></instances>\n</project>\n"
    )
}

const COMPLETE: &str = "<configVars>\
<configVariable instancePathAndName=\"R.main.v1.coil\" address=\"%QX1.0\"><type><BOOL/></type></configVariable>\
<configVariable instancePathAndName=\"R.main.v2.coil\" address=\"%QX1.1\"><type><BOOL/></type></configVariable>\
<configVariable instancePathAndName=\"R.main.v2.setting\"><type><INT/></type>\
<initialValue><simpleValue value=\"7\"/></initialValue></configVariable>\
</configVars>";

#[test]
fn config_vars_complete_the_addresses_and_give_initial_values() {
    let xml = project(COMPLETE);
    let mut plc = Plc::compile_files(&[("cell.xml", &xml)], &Options::default())
        .unwrap_or_else(|e| panic!("{e}"));
    plc.run_cycle().unwrap();
    // v1 is opened, v2 closed: each drives the address its line gives.
    assert_eq!(plc.process_image().read_bit("%QX1.0"), Ok(true));
    assert_eq!(plc.process_image().read_bit("%QX1.1"), Ok(false));
    // v2's setting starts at 7, v1's at 0.
    assert_eq!(plc.read("main.sum").unwrap().to_literal(), "7");
}

#[test]
fn a_missing_config_variable_leaves_the_address_to_be_placed_automatically() {
    let partial = COMPLETE.replace(
        "<configVariable instancePathAndName=\"R.main.v2.coil\" address=\"%QX1.1\"><type><BOOL/></type></configVariable>",
        "",
    );
    let xml = project(&partial);
    let plc = Plc::compile_files(&[("cell.xml", &xml)], &Options::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let coil = plc
        .image()
        .globals
        .iter()
        .find(|r| r.name.eq_ignore_ascii_case("main.v2.coil"));
    assert!(
        coil.and_then(|r| r.location.as_deref()).is_some(),
        "{coil:?}"
    );
}

#[test]
fn a_config_variable_with_a_wrong_path_or_type_is_refused_with_its_xml_location() {
    let wrong = COMPLETE.replace(
        "R.main.v2.setting\"><type><INT/>",
        "R.main.v9.setting\"><type><INT/>",
    );
    let xml = project(&wrong);
    let e = Plc::compile_files(&[("cell.xml", &xml)], &Options::default())
        .err()
        .expect("v9 does not exist");
    let d = e
        .diagnostics
        .iter()
        .find(|d| d.code == "E711")
        .expect("E711");
    let at = e.sources.location(d.span);
    assert!(at.starts_with("cell.xml:"), "{at}");
    let wrong = COMPLETE.replace(
        "R.main.v2.setting\"><type><INT/>",
        "R.main.v2.setting\"><type><BOOL/>",
    );
    let e = Plc::compile_files(&[("cell.xml", &project(&wrong))], &Options::default())
        .err()
        .expect("setting is an INT");
    assert!(e.diagnostics.iter().any(|d| d.code == "E712"), "{e}");
}

#[test]
fn a_config_variable_without_its_path_is_refused_by_name() {
    let bad = "<configVars><configVariable address=\"%QX1.0\"><type><BOOL/></type></configVariable></configVars>";
    let e = Plc::compile_files(&[("cell.xml", &project(bad))], &Options::default())
        .err()
        .expect("no path");
    assert!(e.diagnostics.iter().any(|d| d.code == "E807"), "{e}");
}
