//! TwinCAT's event logger and ADS devices as plcrun's TwinCAT library
//! stands in for them (docs/twincat.md, "Libraries"): the event classes a
//! project's type descriptions declare are `TC_EVENTS.<class>.<event>`,
//! `FB_TcMessage` records what it sends, and an ADS function block fails
//! as it does when its device is not there. Expected values worked out by
//! hand from the descriptions and the library's documented rules.

use crate::support::cli::{plcrun, plcrun_ok, temp_project};
use crate::support::plc::{lit, run};
use crate::support::twincat::{compile_ok, pou};

/// A `.plcproj` compiling MAIN and pinning nothing.
const PLC_PROJECT: &str = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project xmlns=\"http://schemas.microsoft.com/developer/msbuild/2003\">\n  <ItemGroup>\n    <Compile Include=\"MAIN.TcPOU\" />\n  </ItemGroup>\n</Project>\n";

/// A solution naming an additional description, as SLAC's libraries keep
/// their event classes.
const SOLUTION: &str = "<?xml version=\"1.0\"?>\n<TcSmProject>\n  <Project>\n    <System>\n      <AdditionalTmcFile Name=\"GlobalEvents\" File=\"GlobalEvents.tmc\"/>\n    </System>\n  </Project>\n</TcSmProject>\n";

/// An event class in its current version (the older one it hides has
/// other numbers) with three events, one without a severity.
const EVENTS: &str = "<?xml version='1.0' encoding='UTF-8'?>\n<TcModuleClass>\n  <DataTypes>\n    <DataType>\n      <Name GUID=\"{97CF8247-B59C-4E2C-B4B0-7350D0471457}\">PlantEvents</Name>\n      <EventId>\n        <Name Id=\"0\">Critical</Name>\n        <Severity>Critical</Severity>\n      </EventId>\n      <EventId>\n        <Name Id=\"3\">Overheat</Name>\n        <Severity>Warning</Severity>\n      </EventId>\n      <EventId>\n        <Name Id=\"4\">Trace</Name>\n      </EventId>\n      <Hides><Hide GUID=\"{11111111-2222-3333-4444-555555555555}\"/></Hides>\n    </DataType>\n    <DataType>\n      <Name GUID=\"{11111111-2222-3333-4444-555555555555}\">PlantEvents</Name>\n      <EventId>\n        <Name Id=\"9\">Overheat</Name>\n        <Severity>Error</Severity>\n      </EventId>\n    </DataType>\n  </DataTypes>\n</TcModuleClass>\n";

/// MAIN reads the entries of `TC_EVENTS.PlantEvents` and sends a message
/// of one, the way SLAC's `FB_LogMessage` does.
fn main_pou() -> String {
    pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n  nId : UDINT;\n  bWarning : BOOL;\n  bTraceVerbose : BOOL;\n  nData1 : DWORD;\n  nLast : BYTE;\n  msgs : ARRAY[0..4] OF FB_TcMessage;\n  msg : REFERENCE TO FB_TcMessage;\n  hr : HRESULT;\n  nSent : UDINT;\nEND_VAR\n",
        "nId := TC_EVENTS.PlantEvents.Overheat.nEventId;\nbWarning := TC_EVENTS.PlantEvents.Overheat.eSeverity = TcEventSeverity.Warning;\nbTraceVerbose := TC_EVENTS.PlantEvents.Trace.eSeverity = TcEventSeverity.Verbose;\nnData1 := TC_EVENTS.PlantEvents.Overheat.uuidEventClass.Data1;\nnLast := TC_EVENTS.PlantEvents.Critical.uuidEventClass.Data4[7];\nmsg REF= msgs[TC_EVENTS.PlantEvents.Overheat.nEventId];\nhr := msg.CreateEx(TC_EVENTS.PlantEvents.Overheat, 0);\nmsg.ipArguments.Clear().AddString('boiler').AddLReal(97.5);\nIF NOT FAILED(hr) AND msg.eSeverity >= TcEventSeverity.Info THEN\n  hr := msg.Send(0);\nEND_IF\nnSent := msgs[3].nSent;\n",
        "",
    )
}

#[test]
fn the_event_classes_of_the_type_system_are_tc_events_entries() {
    let main = main_pou();
    // The project's own .tmc holds the class too (TwinCAT copies the
    // classes a project uses there): it is declared once.
    let dir = temp_project(&[
        ("Plc/Plc.plcproj", PLC_PROJECT),
        ("Plc/MAIN.TcPOU", &main),
        ("Plc/Plc.tmc", EVENTS),
        ("Solution.tsproj", SOLUTION),
        ("GlobalEvents.tmc", EVENTS),
    ]);
    let plc = format!("{dir}/Plc/Plc.plcproj");
    let vars =
        "MAIN.nId,MAIN.bWarning,MAIN.bTraceVerbose,MAIN.nData1,MAIN.nLast,MAIN.hr,MAIN.nSent";
    let out = plcrun_ok(&[&plc, "--cycles", "2", "--trace", vars]);
    assert_eq!(
        out,
        format!(
            "cycle,time,{vars}\n0,T#0s,3,TRUE,TRUE,16#97CF8247,16#57,0,1\n1,T#10ms,3,TRUE,TRUE,16#97CF8247,16#57,0,2\n"
        )
    );
    // Read from the additional description alone.
    std::fs::remove_file(format!("{dir}/Plc/Plc.tmc")).unwrap();
    let again = plcrun_ok(&[&plc, "--cycles", "2", "--trace", vars]);
    assert_eq!(again, out);
}

#[test]
fn an_event_the_reader_cannot_declare_is_named_in_the_description() {
    let main = main_pou();
    let broken = EVENTS.replace("<Severity>Warning</Severity>", "<Severity>Loud</Severity>");
    let dir = temp_project(&[
        ("Plc/Plc.plcproj", PLC_PROJECT),
        ("Plc/MAIN.TcPOU", &main),
        ("Plc/Plc.tmc", &broken),
    ]);
    let (code, _, err) = plcrun(&["check", &format!("{dir}/Plc/Plc.plcproj")]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains(
            "error[E874]: `Loud` is not a severity (one of Verbose, Info, Warning, Error, Critical)"
        ),
        "{err}"
    );
    assert!(err.contains("Plc.tmc:12:9"), "{err}");
    let no_id = EVENTS.replace("<Name Id=\"3\">Overheat", "<Name>Overheat");
    std::fs::write(format!("{dir}/Plc/Plc.tmc"), no_id).unwrap();
    let (code, _, err) = plcrun(&["check", &format!("{dir}/Plc/Plc.plcproj")]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("error[E874]: an event's `<Name>` needs its number"),
        "{err}"
    );
}

#[test]
fn a_message_records_what_it_sends_and_fails_before_it_is_created() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  fresh : FB_TcMessage;\n  msg : FB_TcMessage;\n  ip : I_TcMessage;\n  src : FB_TcSourceInfo;\n  entry : TcEventEntry := (nEventId := 2, eSeverity := TcEventSeverity.Error);\n  hrFresh, hrCreate, hrSend : HRESULT;\n  nArgs : UDINT;\n  sName : STRING;\n  bSame, bOther : BOOL;\n  nId : UDINT;\nEND_VAR",
        "hrFresh := fresh.Send(0);\nsrc.sName := CONCAT('P.msg', '/Motion');\nhrCreate := msg.CreateEx(stEventEntry := entry, ipSourceInfo := src);\nip := msg;\nnId := ip.stEventEntry.nEventId;\nmsg.ipArguments.Clear();\nmsg.ipArguments.AddString('axis').AddDInt(-3).AddBool(TRUE);\nnArgs := msg.ipArguments.nCount;\nmsg.SetJsonAttribute('{}');\nhrSend := msg.Send(0);\nsName := src.sName;\nbSame := msg.EqualsToEventEntryEx(entry);\nentry.uuidEventClass.Data4[3] := 1;\nbOther := msg.EqualsToEventEntryEx(entry);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    // E_FAIL (16#80004005) as a DINT.
    assert_eq!(lit(&plc, "hrFresh"), "-2147467259");
    assert_eq!(lit(&plc, "fresh.nSent"), "0");
    assert_eq!(
        [lit(&plc, "hrCreate"), lit(&plc, "hrSend"), lit(&plc, "nId")],
        ["0", "0", "2"]
    );
    assert_eq!(lit(&plc, "nArgs"), "3");
    assert_eq!(lit(&plc, "msg.nSent"), "1");
    assert_eq!(lit(&plc, "msg.sLastText"), "'axis, -3, TRUE'");
    // The task time of cycle 0: 2000-01-01 in 100 ns since 1601.
    assert_eq!(lit(&plc, "msg.nTimeSent"), "125911584000000000");
    assert_eq!(lit(&plc, "sName"), "'P.msg/Motion'");
    assert_eq!([lit(&plc, "bSame"), lit(&plc, "bOther")], ["TRUE", "FALSE"]);
}

#[test]
fn the_task_time_counts_100_ns_from_1601() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR t0, t : ULINT; n : INT; END_VAR",
        "IF n = 0 THEN t0 := F_GetTaskTime(); END_IF\nt := F_GetTaskTime() - t0;\nn := n + 1;",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "t0"), "125911584000000000");
    // Two cycles of the default 10 ms: 200 000 units.
    assert_eq!(lit(&plc, "t"), "200000");
}

#[test]
fn an_ads_block_fails_as_with_its_device_missing() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  get : FB_EcGetSlaveState;\n  set : FB_EcSetSlaveState;\n  req : FB_EcReqSlaveState;\n  states : ARRAY[1..2] OF BYTE := [EC_DEVICE_STATE_PREOP, EC_DEVICE_STATE_OP];\n  n : INT;\nEND_VAR",
        "get(sNetId := '', nSlaveAddr := 1001, bExecute := n = 1);\nset(sNetId := '5.1.2.3.1.1', nSlaveAddr := 1001, bExecute := n = 1, reqState := EC_DEVICE_STATE_OP);\nreq(sNetId := '127.0.0.1.1.1', bExecute := TRUE, state := EC_DEVICE_STATE_INIT);\nn := n + 1;",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    // Before its rising edge a block has not run.
    assert_eq!(
        [lit(&plc, "get.bError"), lit(&plc, "set.bError")],
        ["FALSE", "FALSE"]
    );
    assert_eq!(
        [lit(&plc, "req.bError"), lit(&plc, "req.nErrId")],
        ["TRUE", "6"]
    );
    run(&mut plc, 1);
    // The local system: no ADS server (6); another system: no route (7).
    assert_eq!(
        [
            lit(&plc, "get.bBusy"),
            lit(&plc, "get.bError"),
            lit(&plc, "get.nErrId")
        ],
        ["FALSE", "TRUE", "6"]
    );
    assert_eq!(
        [lit(&plc, "set.bError"), lit(&plc, "set.nErrId")],
        ["TRUE", "7"]
    );
    assert_eq!(
        [lit(&plc, "states[1]"), lit(&plc, "states[2]")],
        ["16#2", "16#8"]
    );
}
