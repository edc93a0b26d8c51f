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

/// MAIN reads the entries of `TC_EVENTS.PlantEvents` and the class's GUID
/// `TC_EVENT_CLASSES.PlantEvents`, and sends a message of one, the way
/// SLAC's `FB_LogMessage` does.
fn main_pou() -> String {
    pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n  nId : UDINT;\n  bWarning : BOOL;\n  bTraceVerbose : BOOL;\n  nData1 : DWORD;\n  nLast : BYTE;\n  bSameClass : BOOL;\n  msgs : ARRAY[0..4] OF FB_TcMessage;\n  msg : REFERENCE TO FB_TcMessage;\n  hr : HRESULT;\n  nSent : UDINT;\nEND_VAR\n",
        "nId := TC_EVENTS.PlantEvents.Overheat.nEventId;\nbWarning := TC_EVENTS.PlantEvents.Overheat.eSeverity = TcEventSeverity.Warning;\nbTraceVerbose := TC_EVENTS.PlantEvents.Trace.eSeverity = TcEventSeverity.Verbose;\nnData1 := TC_EVENTS.PlantEvents.Overheat.uuidEventClass.Data1;\nnLast := TC_EVENTS.PlantEvents.Critical.uuidEventClass.Data4[7];\nbSameClass := TC_EVENT_CLASSES.PlantEvents.Data1 = nData1 AND TC_EVENT_CLASSES.PlantEvents.Data4[7] = nLast;\nmsg REF= msgs[TC_EVENTS.PlantEvents.Overheat.nEventId];\nhr := msg.CreateEx(TC_EVENTS.PlantEvents.Overheat, 0);\nmsg.ipArguments.Clear().AddString('boiler').AddLReal(97.5);\nIF NOT FAILED(hr) AND msg.eSeverity >= TcEventSeverity.Info THEN\n  hr := msg.Send(0);\nEND_IF\nnSent := msgs[3].nSent;\n",
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
    let vars = "MAIN.nId,MAIN.bWarning,MAIN.bTraceVerbose,MAIN.nData1,MAIN.nLast,MAIN.bSameClass,MAIN.hr,MAIN.nSent";
    let out = plcrun_ok(&[&plc, "--cycles", "2", "--trace", vars]);
    assert_eq!(
        out,
        format!(
            "cycle,time,{vars}\n0,T#0s,3,TRUE,TRUE,16#97CF8247,16#57,TRUE,0,1\n1,T#10ms,3,TRUE,TRUE,16#97CF8247,16#57,TRUE,0,2\n"
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

/// A listener built on `FB_ListenerBase`, as SLAC's logger and Beckhoff's
/// example build theirs: it counts what `OnMessageSent` receives and keeps
/// the last event's number, source, argument count and JSON attribute.
fn listener_pou() -> String {
    pou(
        "FB_Counter",
        "FUNCTION_BLOCK FB_Counter EXTENDS FB_ListenerBase\nVAR\n  nReceived : UDINT;\n  nLastId : UDINT;\n  sLastSource : STRING;\n  nLastArgs : UDINT;\n  sLastJson : STRING(80);\n  hrJson : HRESULT;\n  sTiny : STRING(3);\n  hrTiny : HRESULT;\nEND_VAR\n",
        "",
        "    <Method Name=\"OnMessageSent\" Id=\"{00000000-0000-0000-0000-000000000011}\">\n      <Declaration><![CDATA[METHOD OnMessageSent\nVAR_INPUT\n  fbEvent : REFERENCE TO FB_TcEvent;\nEND_VAR\n]]></Declaration>\n      <Implementation>\n        <ST><![CDATA[nReceived := nReceived + 1;\nnLastId := fbEvent.nEventId;\nsLastSource := fbEvent.ipSourceInfo.sName;\nnLastArgs := fbEvent.ipArguments.nCount;\nhrJson := fbEvent.GetJsonAttribute(sLastJson, SIZEOF(sLastJson));\nhrTiny := fbEvent.GetJsonAttribute(sTiny, SIZEOF(sTiny));]]></ST>\n      </Implementation>\n    </Method>\n",
    )
}

/// Messages sent through `FB_TcMessage` reach the listeners subscribed
/// before them: through a filter of event classes and least severities,
/// or all of them without one.
#[test]
fn listeners_receive_the_messages_sent_after_they_subscribe() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  filtered, all, late : FB_Counter;\n  ipFilter : ITcEventFilterConfig;\n  plant : GUID := (Data1 := 16#97CF8247);\n  other : GUID := (Data1 := 16#1);\n  warn : TcEventEntry := (uuidEventClass := (Data1 := 16#97CF8247), nEventId := 3, eSeverity := TcEventSeverity.Warning);\n  info : TcEventEntry := (uuidEventClass := (Data1 := 16#97CF8247), nEventId := 4, eSeverity := TcEventSeverity.Info);\n  elsewhere : TcEventEntry := (uuidEventClass := (Data1 := 16#1), nEventId := 5, eSeverity := TcEventSeverity.Error);\n  mWarn, mInfo, mElse, mEarly : FB_TcMessage;\n  src : FB_TcSourceInfo;\n  hrSub, hrAgain, hrAdd : HRESULT;\n  bGotFilter : BOOL;\n  n : INT;\nEND_VAR",
        "n := n + 1;\n\
         IF n = 1 THEN\n\
           mEarly.CreateEx(warn, 0); mEarly.Send(0);\n\
           hrSub := filtered.Subscribe(ADR(ipFilter), 0);\n\
           hrAgain := filtered.Subscribe(ADR(ipFilter), 0);\n\
           bGotFilter := ipFilter <> 0;\n\
           hrAdd := ipFilter.AddEventClass(plant, TcEventSeverity.Warning);\n\
           all.Subscribe(0, 0);\n\
           src.sName := 'P.boiler';\n\
           mWarn.CreateEx(warn, src); mWarn.ipArguments.Clear().AddString('boiler').AddDInt(97);\n\
           mWarn.SetJsonAttribute('{\"zone\":2}');\n\
           mInfo.CreateEx(info, src); mElse.CreateEx(elsewhere, 0);\n\
           mWarn.Send(0); mInfo.Send(0); mElse.Send(0);\n\
         END_IF\n\
         IF n = 2 THEN late.Subscribe(0, 0); mElse.Send(0); END_IF\n\
         filtered.Execute(); all.Execute(); late.Execute();",
        "",
    );
    let mut plc = compile_ok(&[("FB_Counter.TcPOU", &listener_pou()), ("P.TcPOU", &main)]);
    run(&mut plc, 3);
    // Subscribed once; the second call fails with E_FAIL.
    assert_eq!(
        [
            lit(&plc, "P.hrSub"),
            lit(&plc, "P.hrAgain"),
            lit(&plc, "P.bGotFilter"),
            lit(&plc, "P.hrAdd")
        ],
        ["0", "-2147467259", "TRUE", "0"]
    );
    // Through the filter only the plant's warning; the message sent
    // before the subscription reaches nobody.
    assert_eq!(
        [
            lit(&plc, "P.filtered.nReceived"),
            lit(&plc, "P.filtered.nLastId"),
            lit(&plc, "P.filtered.sLastSource"),
            lit(&plc, "P.filtered.nLastArgs"),
            lit(&plc, "P.filtered.sLastJson"),
            lit(&plc, "P.filtered.hrJson"),
            lit(&plc, "P.filtered.hrTiny")
        ],
        [
            "1",
            "3",
            "'P.boiler'",
            "2",
            "'{\"zone\":2}'",
            "0",
            "-2147467259"
        ]
    );
    // Without a filter: the three of cycle 0 and the one of cycle 1; the
    // late listener only that one.
    assert_eq!(
        [
            lit(&plc, "P.all.nReceived"),
            lit(&plc, "P.all.nLastId"),
            lit(&plc, "P.late.nReceived"),
            lit(&plc, "P.late.sLastSource")
        ],
        ["4", "5", "1", "''"]
    );
}

/// Without type descriptions there is no event text: a request for one
/// fails at once, and the program's fallback runs (SLAC's logger writes
/// "(Unable to retrieve message)").
#[test]
fn an_event_text_request_fails_without_a_text() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  req : FB_RequestEventText;\n  args : FB_TcArguments;\n  cls : GUID := (Data1 := 16#97CF8247);\n  hr, hrGet : HRESULT;\n  s : STRING(40) := 'old';\nEND_VAR",
        "hr := req.Request(eventClass := cls, nEventId := 1, nLangId := 1033, ipArgs := args);\n\
         hrGet := req.GetString(s, SIZEOF(s));",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(
        [
            lit(&plc, "P.hr"),
            lit(&plc, "P.req.bBusy"),
            lit(&plc, "P.req.bError"),
            lit(&plc, "P.hrGet"),
            lit(&plc, "P.s")
        ],
        ["-2147467259", "FALSE", "TRUE", "-2147467259", "''"]
    );
}

/// An event class whose events have display texts, with placeholders for
/// the arguments and characters that need escaping in ST.
const TEXTS: &str = "<?xml version='1.0' encoding='UTF-8'?>\n<TcModuleClass>\n  <DataTypes>\n    <DataType>\n      <Name GUID=\"{97CF8247-B59C-4E2C-B4B0-7350D0471457}\">PlantEvents</Name>\n      <EventId>\n        <Name Id=\"3\">Overheat</Name>\n        <DisplayName TxtId=\"\">Overheat of {0}: {1} 'degrees' ({2}) for $ {x}</DisplayName>\n        <Severity>Warning</Severity>\n      </EventId>\n      <EventId>\n        <Name Id=\"4\">Trace</Name>\n      </EventId>\n    </DataType>\n  </DataTypes>\n</TcModuleClass>\n";

/// The display texts of the project's event classes answer
/// `FB_RequestEventText`, the arguments put in for their placeholders.
#[test]
fn an_event_text_is_the_display_text_with_its_arguments() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n  req, none : FB_RequestEventText;\n  args : FB_TcArguments;\n  hr, hrNone, hrGet, hrSmall : HRESULT;\n  s : STRING(80);\n  small : STRING(10);\n  n : UDINT;\nEND_VAR\n",
        "args.Clear().AddString('boiler').AddDInt(97);\nhr := req.Request(eventClass := TC_EVENT_CLASSES.PlantEvents, nEventId := TC_EVENTS.PlantEvents.Overheat.nEventId, nLangId := 1033, ipArgs := args);\nn := req.nStringSize;\nhrGet := req.GetString(s, SIZEOF(s));\nhrSmall := req.GetString(small, SIZEOF(small));\nhrNone := none.Request(eventClass := TC_EVENT_CLASSES.PlantEvents, nEventId := 4, nLangId := 1033, ipArgs := args);\n",
        "",
    );
    let dir = temp_project(&[
        ("Plc/Plc.plcproj", PLC_PROJECT),
        ("Plc/MAIN.TcPOU", &main),
        ("Plc/Plc.tmc", TEXTS),
    ]);
    let plc = format!("{dir}/Plc/Plc.plcproj");
    let vars =
        "MAIN.hr,MAIN.s,MAIN.n,MAIN.hrGet,MAIN.hrSmall,MAIN.small,MAIN.hrNone,MAIN.none.bError";
    let out = plcrun_ok(&[&plc, "--cycles", "1", "--trace", vars]);
    // {2} has no argument and {x} is no placeholder: both stay.
    assert_eq!(
        out,
        format!(
            "cycle,time,{vars}\n0,T#0s,0,'Overheat of boiler: 97 $'degrees$' ({{2}}) for $$ {{x}}',49,0,-2147467259,'',-2147467259,TRUE\n"
        )
    );
}

/// TwinCAT's own event classes, named without a description that declares
/// them (lcls-twincat-general's log handler subscribes to all five): the
/// GUIDs TwinCAT's descriptions give them, the null GUID for the one
/// plcrun does not know; a project description's own version wins.
#[test]
fn twincat_system_event_classes_are_known_by_name() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n  nAds, nRouter, nRTime, nSystem, nWin32 : DWORD;\n  nPlant : DWORD;\nEND_VAR\n",
        "nAds := TC_EVENT_CLASSES.TcGeneralAdsEventClass.Data1;\nnRouter := TC_EVENT_CLASSES.TcRouterEventClass.Data1;\nnRTime := TC_EVENT_CLASSES.TcRTimeEventClass.Data1;\nnSystem := TC_EVENT_CLASSES.TcSystemEventClass.Data1;\nnWin32 := TC_EVENT_CLASSES.Win32EventClass.Data1;\n",
        "",
    );
    let dir = temp_project(&[("Plc/Plc.plcproj", PLC_PROJECT), ("Plc/MAIN.TcPOU", &main)]);
    let plc = format!("{dir}/Plc/Plc.plcproj");
    let vars = "MAIN.nAds,MAIN.nRouter,MAIN.nRTime,MAIN.nSystem,MAIN.nWin32";
    let out = plcrun_ok(&[&plc, "--cycles", "1", "--trace", vars]);
    assert_eq!(
        out,
        format!("cycle,time,{vars}\n0,T#0s,16#7D760066,16#E759605A,16#0,16#BB2A9999,16#4ABEFBBF\n")
    );
    // A description declaring one of them gives its GUID.
    let described = EVENTS.replace("PlantEvents", "TcRTimeEventClass");
    std::fs::write(format!("{dir}/Plc/Plc.tmc"), described).unwrap();
    let out = plcrun_ok(&[&plc, "--cycles", "1", "--trace", "MAIN.nRTime"]);
    assert_eq!(out, "cycle,time,MAIN.nRTime\n0,T#0s,16#97CF8247\n");
}
