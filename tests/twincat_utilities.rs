//! Tc2_Utilities' `FB_FormatString` with its `T_Arg` arguments (`F_INT`,
//! `F_LREAL`, `F_STRING`...), `FB_MemRingBuffer` and `FB_HashTableCtrl`,
//! and Tc3_JsonXml's `FB_JsonSaxWriter`, as plcrun's TwinCAT library
//! provides them (docs/twincat.md). Expected texts worked out by
//! hand from the format rules (C's printf where Beckhoff's manual follows
//! it); the ring buffer's sizes from its layout (a 4-byte length before
//! each record).

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile_ok, pou};

/// The outputs of FB_FormatString for each `(format, arguments)`.
fn formatted(cases: &[(&str, &str)]) -> Vec<String> {
    let decl = "PROGRAM P\nVAR\n  fb : FB_FormatString;\n  n : INT := -42; u : UDINT := 255; w : WORD := 16#BEEF; b : BYTE := 65;\n  r : REAL := 3.14159; l : LREAL := -0.000123; s : STRING(80) := 'abc'; bo : BOOL := TRUE;\n  out : ARRAY[1..10] OF T_MaxString; err : ARRAY[1..10] OF UDINT;\nEND_VAR";
    let body: String = cases
        .iter()
        .enumerate()
        .map(|(i, (format, args))| {
            let k = i + 1;
            format!(
                "fb(sFormat := '{format}'{args}); out[{k}] := fb.sOut; err[{k}] := fb.nErrId;\n"
            )
        })
        .collect();
    let main = pou("P", decl, &body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    (1..=cases.len())
        .map(|k| {
            let e = lit(&plc, &format!("err[{k}]"));
            let o = lit(&plc, &format!("out[{k}]"));
            if e == "0" {
                o
            } else {
                format!("{o} error {e}")
            }
        })
        .collect()
}

#[test]
fn integers_in_every_base_with_flags_width_and_precision() {
    let got = formatted(&[
        (
            "n=%d u=%u x=%x X=%#X o=%o b=%b",
            ", arg1 := F_INT(n), arg2 := F_UDINT(u), arg3 := F_UDINT(u), arg4 := F_WORD(w), arg5 := F_BYTE(b), arg6 := F_BYTE(b)",
        ),
        (
            "[%5d][%-5d][%05d][%+d][%.4d]",
            ", arg1 := F_INT(n), arg2 := F_INT(n), arg3 := F_INT(n), arg4 := F_INT(n), arg5 := F_INT(n)",
        ),
        // A negative value as %u and %x: its bits in its own width.
        ("%u %x", ", arg1 := F_INT(n), arg2 := F_INT(n)"),
        (
            "%c%c bo=%d 100%%",
            ", arg1 := F_BYTE(b), arg2 := F_BYTE(b), arg3 := F_BOOL(bo)",
        ),
    ]);
    assert_eq!(
        got,
        [
            "'n=-42 u=255 x=ff X=0XBEEF o=101 b=1000001'",
            "'[  -42][-42  ][-0042][-42][-0042]'",
            "'65494 ffd6'",
            "'AA bo=1 100%'",
        ]
    );
}

#[test]
fn reals_strings_and_the_errors_of_a_bad_format() {
    let got = formatted(&[
        (
            "r=%f r2=%.2f l=%e r3=%08.3f %+.1f",
            ", arg1 := F_REAL(r), arg2 := F_REAL(r), arg3 := F_LREAL(l), arg4 := F_REAL(r), arg5 := F_REAL(r)",
        ),
        (
            "s=%s [%6s] [%-6s] [%.2s]",
            ", arg1 := F_STRING(s), arg2 := F_STRING(s), arg3 := F_STRING(s), arg4 := F_STRING(s)",
        ),
        (":%02.0f %s", ", arg1 := F_REAL(r), arg2 := F_STRING(s)"),
        // An unknown type letter: bError, nErrId 16#8000 + its position.
        ("bad %q", ", arg1 := F_INT(n)"),
        // A string where a number is wanted, and an argument missing.
        ("%d", ", arg1 := F_STRING(s)"),
        ("%d %d", ", arg1 := F_INT(n)"),
    ]);
    assert_eq!(
        got,
        [
            "'r=3.141590 r2=3.14 l=-1.230000e-04 r3=0003.142 +3.1'",
            "'s=abc [   abc] [abc   ] [ab]'",
            "':03 abc'",
            "'bad ' error 32774",
            "'' error 32770",
            "'-42 ' error 32773",
        ]
    );
}

#[test]
fn a_ring_buffer_keeps_records_of_any_length_in_order_across_its_end() {
    let decl = "PROGRAM P\nVAR\n  rb : FB_MemRingBuffer; buf : ARRAY[0..19] OF BYTE;\n  a : DINT := 16#01020304; b : STRING(5) := 'xy'; c : INT := 7;\n  ra : DINT; rs : STRING(5); rc : INT;\n  ok : ARRAY[1..6] OF BOOL; n1, n2, s1, need : UDINT;\nEND_VAR";
    let body = "rb.A_Reset();
rb.A_AddTail(pWrite := ADR(a), cbWrite := SIZEOF(a), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf)); ok[1] := rb.bOk;
rb.A_AddTail(pWrite := ADR(b), cbWrite := SIZEOF(b)); ok[2] := rb.bOk; n1 := rb.nCount; s1 := rb.cbSize;
rb.A_AddTail(pWrite := ADR(c), cbWrite := SIZEOF(c)); ok[3] := rb.bOk;
rb.A_RemoveHead(pRead := ADR(ra), cbRead := SIZEOF(ra)); ok[4] := rb.bOk;
rb.A_AddTail(pWrite := ADR(c), cbWrite := SIZEOF(c)); ok[5] := rb.bOk;
rb.A_GetHead(pRead := ADR(rc), cbRead := SIZEOF(rc)); ok[6] := rb.bOk; need := rb.cbReturn;
rb.A_RemoveHead(pRead := ADR(rs), cbRead := SIZEOF(rs));
rb.A_RemoveHead(pRead := ADR(rc), cbRead := SIZEOF(rc)); n2 := rb.nCount;";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let ok: Vec<String> = (1..=6).map(|k| lit(&plc, &format!("ok[{k}]"))).collect();
    // The third record (4 + 2 bytes) does not fit behind 18 of 20 bytes;
    // once the first is removed it does, across the buffer's end. Reading
    // the 6-byte string record into an INT fails and says 6 bytes.
    assert_eq!(ok, ["TRUE", "TRUE", "FALSE", "TRUE", "TRUE", "FALSE"]);
    assert_eq!(
        (lit(&plc, "n1"), lit(&plc, "s1")),
        ("2".into(), "18".into())
    );
    assert_eq!(lit(&plc, "ra"), "16909060");
    assert_eq!(lit(&plc, "need"), "6");
    assert_eq!(
        (lit(&plc, "rs"), lit(&plc, "rc")),
        ("'xy'".into(), "7".into())
    );
    assert_eq!(lit(&plc, "n2"), "0");
}

/// TcUnit's message queue: records of a structure of strings written into
/// the ring buffer's bytes and read back whole, in order.
#[test]
fn a_ring_buffer_queues_structures_of_strings() {
    let dut = crate::support::twincat::declaration(
        "DUT",
        "ST_Msg",
        "TYPE ST_Msg :\nSTRUCT\n  mask : DWORD;\n  fmt : T_MaxString;\n  arg : STRING(20);\nEND_STRUCT\nEND_TYPE",
    );
    let decl = "PROGRAM P\nVAR\n  rb : FB_MemRingBuffer; buf : ARRAY[0..(3 * (SIZEOF(ST_Msg) + 4) - 1)] OF BYTE;\n  m, r1, r2 : ST_Msg; k : INT; n : UDINT;\nEND_VAR";
    let body = "rb.A_Reset();
FOR k := 1 TO 2 DO
  m.mask := 16#10 * INT_TO_DWORD(k); m.fmt := CONCAT('failed: %s #', INT_TO_STRING(k)); m.arg := 'expected 1';
  rb.A_AddTail(pWrite := ADR(m), cbWrite := SIZEOF(m), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf));
END_FOR
n := rb.nCount;
rb.A_RemoveHead(pRead := ADR(r1), cbRead := SIZEOF(r1));
rb.A_RemoveHead(pRead := ADR(r2), cbRead := SIZEOF(r2));";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("ST_Msg.TcDUT", &dut), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let got: Vec<String> = ["n", "r1.mask", "r1.fmt", "r1.arg", "r2.mask", "r2.fmt"]
        .iter()
        .map(|v| lit(&plc, v))
        .collect();
    assert_eq!(
        got,
        [
            "2",
            "16#10",
            "'failed: %s #1'",
            "'expected 1'",
            "16#20",
            "'failed: %s #2'"
        ]
    );
}

#[test]
fn a_hash_table_adds_finds_removes_and_walks_its_entries_in_place() {
    // PMPS's way: the index of an entry (A_GetIndexAtPosPtr) picks its
    // data, and stays the entry's own until it is removed.
    let decl = "PROGRAM P\nVAR\n  entries : ARRAY[0..3] OF T_HashTableEntry; hTable : T_HHASHTABLE; fbTable : FB_HashTableCtrl;\n  data : ARRAY[0..3] OF INT := [10, 20, 30, 40];\n  bInit, okIdx, okRem, okFull, okLook, okMiss, okBad : BOOL;\n  idx : PVOID; pos : POINTER TO T_HashTableEntry; v : PVOID; pInt : POINTER TO INT;\n  nAfterAdd, nAfterAll, nFree, looked : UDINT; sum : INT; walked : DINT;\nEND_VAR";
    let body = "okBad := F_CreateHashTableHnd(0, 64, hTable);
bInit := F_CreateHashTableHnd(ADR(entries), SIZEOF(entries), hTable);
fbTable.A_Add(hTable := hTable, key := 16#100, putValue := ADR(data[0]));
fbTable.A_Add(hTable := hTable, key := 16#200, putValue := ADR(data[1]));
fbTable.A_Add(hTable := hTable, key := 16#300, putValue := ADR(data[2]), getPosPtr => pos);
fbTable.A_GetIndexAtPosPtr(hTable := hTable, putPosPtr := pos, getValue => idx, bOk => okIdx);
fbTable.A_Remove(hTable := hTable, key := 16#200, bOk => okRem);
fbTable.A_Add(hTable := hTable, key := 16#400, putValue := ADR(data[3]), getPosPtr => pos);
fbTable.A_GetIndexAtPosPtr(hTable := hTable, putPosPtr := pos, getValue => looked);
fbTable.A_Add(hTable := hTable, key := 16#100, putValue := ADR(data[1]));
fbTable.A_Add(hTable := hTable, key := 16#500, putValue := ADR(data[3]));
fbTable.A_Add(hTable := hTable, key := 16#600, putValue := ADR(data[3]), bOk => okFull);
nAfterAdd := hTable.nCount; nFree := hTable.nFree;
fbTable.A_Lookup(hTable := hTable, key := 16#100, getValue => v, bOk => okLook);
pInt := v; sum := pInt^;
fbTable.A_Lookup(hTable := hTable, key := 16#999, bOk => okMiss);
fbTable.A_GetFirst(hTable := hTable, getPosPtr => pos, getValue => v);
WHILE fbTable.bOk DO
  pInt := v; walked := walked * 100 + pInt^;
  fbTable.A_GetNext(hTable := hTable, putPosPtr := pos, getPosPtr => pos, getValue => v);
END_WHILE
fbTable.A_RemoveAll(hTable := hTable);
nAfterAll := hTable.nCount;";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!([lit(&plc, "okBad"), lit(&plc, "bInit")], ["FALSE", "TRUE"]);
    assert_eq!([lit(&plc, "okIdx"), lit(&plc, "idx")], ["TRUE", "2"]);
    // 16#400 takes the slot 16#200 left; 16#100 again replaces its value.
    assert_eq!([lit(&plc, "okRem"), lit(&plc, "looked")], ["TRUE", "1"]);
    assert_eq!(
        [
            lit(&plc, "okFull"),
            lit(&plc, "nAfterAdd"),
            lit(&plc, "nFree")
        ],
        ["FALSE", "4", "0"]
    );
    assert_eq!(
        [lit(&plc, "okLook"), lit(&plc, "sum"), lit(&plc, "okMiss")],
        ["TRUE", "20", "FALSE"]
    );
    // The walk goes by index: 16#100 (20), 16#400 (40), 16#300 (30),
    // 16#500 (40).
    assert_eq!(lit(&plc, "walked"), "20403040");
    assert_eq!(lit(&plc, "nAfterAll"), "0");
}

#[test]
fn a_json_writer_builds_a_compact_document_with_escaped_strings() {
    let decl = "PROGRAM P\nVAR\n  fbJson : FB_JsonSaxWriter;\n  s : STRING(255); big : STRING(7000); small : STRING(5);\n  len, n, m : UDINT; hrAfter : HRESULT; long : STRING(255);\nEND_VAR";
    let body = "fbJson.StartObject();
fbJson.AddKey('typecode');
fbJson.AddUdint(42);
fbJson.AddKey('say \"hi\" \\ x');
fbJson.AddString('a$Nb$T');
fbJson.AddKey('list');
fbJson.StartArray();
fbJson.AddBool(TRUE); fbJson.AddLreal(1.5); fbJson.AddNull(); fbJson.AddDint(-7);
fbJson.StartObject(); fbJson.EndObject();
fbJson.EndArray();
fbJson.EndObject();
s := fbJson.GetDocument();
len := fbJson.GetDocumentLength();
n := fbJson.CopyDocument(pDoc := big, SIZEOF(big));
m := fbJson.CopyDocument(small, SIZEOF(small));
fbJson.ResetDocument();
fbJson.StartArray();
fbJson.AddString('0123456789012345678901234567890123456789012345678901234567890123456789012345678901234567890123456789012345678901234567890123456789');
fbJson.AddString('0123456789012345678901234567890123456789012345678901234567890123456789012345678901234567890123456789012345678901234567890123456789');
fbJson.EndArray();
long := fbJson.GetDocument();";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let doc = r#"{"typecode":42,"say \"hi\" \\ x":"a\nb\t","list":[true,1.5,null,-7,{}]}"#;
    assert_eq!(lit(&plc, "s"), format!("'{doc}'"));
    assert_eq!(lit(&plc, "len"), doc.len().to_string());
    // CopyDocument counts the closing NUL; a string too small is emptied.
    assert_eq!(lit(&plc, "n"), (doc.len() + 1).to_string());
    assert_eq!(lit(&plc, "big"), format!("'{doc}'"));
    assert_eq!([lit(&plc, "m"), lit(&plc, "small")], ["0", "''"]);
    // A document longer than 255 characters is not given by GetDocument.
    assert_eq!(lit(&plc, "long"), "''");
}

#[test]
fn system_times_convert_between_their_forms_and_time_zones() {
    // Central European time: UTC + 1 h, + 2 h from the last Sunday of
    // March 02:00 to the last Sunday of October 03:00 (local times).
    let decl = "PROGRAM P\nVAR\n  fbTime : FB_LocalSystemTime := (bEnable := TRUE, dwCycle := 1);\n  fbTz, fbRemote : FB_GetTimeZoneInformation;\n  toUtc : FB_TzSpecificLocalTimeToSystemTime;\n  cet : ST_TimeZoneInformation := (bias := -60, standardDate := (wMonth := 10, wDayOfWeek := 0, wDay := 5, wHour := 3), daylightDate := (wMonth := 3, wDayOfWeek := 0, wDay := 5, wHour := 2), daylightBias := -60);\n  summer : TIMESTRUCT := (wYear := 2024, wMonth := 7, wDay := 15, wHour := 14, wMinute := 30);\n  winter : TIMESTRUCT := (wYear := 2024, wMonth := 1, wDay := 15, wHour := 14, wMinute := 30);\n  beforeSwitch : TIMESTRUCT := (wYear := 2024, wMonth := 3, wDay := 31, wHour := 1, wMinute := 59);\n  uS, uW, uB : TIMESTRUCT; zS, zW : E_TimeZoneID;\n  now : DT; ft : T_FILETIME; back, leap : TIMESTRUCT;\nEND_VAR";
    let body = "fbTime();
fbTz(sNetID := '', bExecute := TRUE);
fbRemote(sNetID := '5.1.2.3.1.1', bExecute := TRUE);
now := SYSTEMTIME_TO_DT(fbTime.systemTime);
toUtc(in := summer, tzInfo := cet); uS := toUtc.out; zS := toUtc.eTzID;
toUtc(in := winter, tzInfo := cet); uW := toUtc.out; zW := toUtc.eTzID;
toUtc(in := beforeSwitch, tzInfo := cet); uB := toUtc.out;
ft := Tc2_Utilities.SYSTEMTIME_TO_FILETIME(summer);
back := FILETIME_TO_SYSTEMTIME(ft);
leap := DT_TO_SYSTEMTIME(DT#2024-02-29-23:59:58);";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    // plcrun's system time starts at 2000-01-01 00:00 UTC, a Saturday.
    assert_eq!(lit(&plc, "fbTime.bValid"), "TRUE");
    assert_eq!(lit(&plc, "now"), "DT#2000-01-01-00:00:00");
    assert_eq!(lit(&plc, "fbTime.systemTime.wDayOfWeek"), "16#6");
    assert_eq!(
        [
            lit(&plc, "fbTz.bError"),
            lit(&plc, "fbTz.tzInfo.bias"),
            lit(&plc, "fbTz.tzID")
        ],
        ["FALSE", "0", "eTimeZoneID_Unknown"]
    );
    assert_eq!(
        [lit(&plc, "fbRemote.bError"), lit(&plc, "fbRemote.nErrId")],
        ["TRUE", "7"]
    );
    // 14:30 local is 12:30 UTC in summer, 13:30 in winter; 01:59 on the
    // day of the switch is still winter time.
    assert_eq!(
        [lit(&plc, "uS.wHour"), lit(&plc, "uS.wMinute")],
        ["16#C", "16#1E"]
    );
    assert_eq!(lit(&plc, "zS"), "eTimeZoneID_Daylight");
    assert_eq!(
        [lit(&plc, "uW.wHour"), lit(&plc, "zW")],
        ["16#D", "eTimeZoneID_Standard"]
    );
    assert_eq!(
        [lit(&plc, "uB.wHour"), lit(&plc, "uB.wMinute")],
        ["16#0", "16#3B"]
    );
    // 2024-07-15 14:30 as 100 ns since 1601: 133 655 274 000 000 000,
    // 16#1DAD6C3_xxxxxxxx; back again it is a Monday.
    assert_eq!(lit(&plc, "ft.dwHighDateTime"), "16#1DAD6C3");
    assert_eq!(
        [
            lit(&plc, "back.wYear"),
            lit(&plc, "back.wDay"),
            lit(&plc, "back.wDayOfWeek")
        ],
        ["16#7E8", "16#F", "16#1"]
    );
    // A leap day, a Thursday.
    assert_eq!(
        [
            lit(&plc, "leap.wMonth"),
            lit(&plc, "leap.wDay"),
            lit(&plc, "leap.wSecond"),
            lit(&plc, "leap.wDayOfWeek")
        ],
        ["16#2", "16#1D", "16#3A", "16#4"]
    );
}

#[test]
fn lreal_to_fmtstr_rounds_or_cuts_at_the_precision() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  a : T_MaxString; b : T_MaxString; c : T_MaxString; d : T_MaxString; e : T_MaxString;\nEND_VAR",
        "a := LREAL_TO_FMTSTR(2.345678, 3, TRUE);\n\
         b := LREAL_TO_FMTSTR(2.345678, 3, FALSE);\n\
         c := LREAL_TO_FMTSTR(-0.05, 2, TRUE);\n\
         d := LREAL_TO_FMTSTR(-0.004, 2, TRUE);\n\
         e := LREAL_TO_FMTSTR(12.5, 0, TRUE);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "'2.346'");
    assert_eq!(lit(&plc, "P.b"), "'2.345'");
    assert_eq!(lit(&plc, "P.c"), "'-0.05'");
    assert_eq!(lit(&plc, "P.d"), "'0.00'");
    assert_eq!(lit(&plc, "P.e"), "'13'");
}

#[test]
fn ams_addresses_and_hex_digits() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  ids : T_AmsNetIdArr := [192, 168, 0, 7, 1, 1];\n  s : T_AmsNetId;\n  d : BYTE; f : BYTE; x : BYTE;\nEND_VAR",
        "s := F_CreateAmsNetId(ids);\n\
         d := HEXASCNIBBLE_TO_BYTE(16#37);\n\
         f := HEXASCNIBBLE_TO_BYTE(16#66);\n\
         x := HEXASCNIBBLE_TO_BYTE(16#67);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.s"), "'192.168.0.7.1.1'");
    assert_eq!(lit(&plc, "P.d"), "16#7");
    assert_eq!(lit(&plc, "P.f"), "16#F");
    assert_eq!(lit(&plc, "P.x"), "16#FF");
}

#[test]
fn ads_requests_and_coe_access_fail_as_without_a_device() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  rd : ADSREAD; wr : ADSWRITE; sdo : FB_EcCoeSdoWrite; n : UDINT;\nEND_VAR",
        "rd(NETID := '', PORT := 501, IDXGRP := 16#4000, LEN := 4, DESTADDR := ADR(n), READ := TRUE);\n\
         wr(NETID := '5.1.2.3.1.1', PORT := 501, LEN := 4, SRCADDR := ADR(n), WRITE := TRUE);\n\
         sdo(sNetId := '', nSlaveAddr := 1001, nIndex := 16#8010, pSrcBuf := ADR(n), cbBufLen := 4, bExecute := TRUE);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.rd.ERR"), "TRUE");
    assert_eq!(lit(&plc, "P.rd.ERRID"), "6");
    assert_eq!(lit(&plc, "P.rd.BUSY"), "FALSE");
    assert_eq!(lit(&plc, "P.wr.ERRID"), "7");
    assert_eq!(lit(&plc, "P.sdo.bError"), "TRUE");
    assert_eq!(lit(&plc, "P.sdo.nErrId"), "6");
}

#[test]
fn system_times_and_guids_as_text_and_strings_copied_through_pointers() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  t : TIMESTRUCT := (wYear := 2024, wMonth := 2, wDay := 9, wHour := 7, wMinute := 5, wSecond := 3, wMilliseconds := 42);\n  g : GUID := (Data1 := 16#0A1B2C3D, Data2 := 16#00EF, Data3 := 16#1234, Data4 := [16#FE, 16#01, 16#2, 16#3, 16#4, 16#5, 16#60, 16#7F]);\n  zero : GUID;\n  ts, gs, gz : T_MaxString;\n  src : STRING(40) := 'a text of twenty-four ch';\n  small : STRING(10); wide : STRING(80); same : STRING(80);\n  okSmall, okWide, okNull : BOOL; cut : UDINT; whole : UDINT; n : UDINT; nNull : UDINT;\nEND_VAR",
        "ts := SYSTEMTIME_TO_STRING(t);\n\
         gs := GUID_TO_STRING(g);\n\
         gz := GUID_TO_STRING(zero);\n\
         okSmall := STRNCPY(ADR(small), ADR(src), 8, nDstLen => cut, nSrcLen => whole);\n\
         okWide := STRNCPY(ADR(wide), ADR(src), SIZEOF(wide));\n\
         okNull := STRNCPY(0, ADR(src), SIZEOF(wide));\n\
         n := LEN2(ADR(src));\n\
         nNull := LEN2(0);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.ts"), "'2024-02-09-07:05:03.042'");
    assert_eq!(lit(&plc, "P.gs"), "'0A1B2C3D-00EF-1234-FE01-02030405607F'");
    assert_eq!(lit(&plc, "P.gz"), "'00000000-0000-0000-0000-000000000000'");
    // Eight bytes hold seven characters and the terminating zero.
    assert_eq!(
        [
            lit(&plc, "P.okSmall"),
            lit(&plc, "P.small"),
            lit(&plc, "P.cut"),
            lit(&plc, "P.whole")
        ],
        ["FALSE", "'a text '", "7", "24"]
    );
    assert_eq!(
        [lit(&plc, "P.okWide"), lit(&plc, "P.wide")],
        ["TRUE", "'a text of twenty-four ch'"]
    );
    assert_eq!(lit(&plc, "P.okNull"), "FALSE");
    assert_eq!([lit(&plc, "P.n"), lit(&plc, "P.nNull")], ["24", "0"]);
}

/// Tc2_TcpIp's UDP socket and Tc2_Utilities' host queries need TwinCAT's
/// Connection Server and ADS router, which plcrun does not have: they fail
/// as requests to a missing server do, and the program's error path runs.
#[test]
fn udp_sockets_and_host_queries_fail_as_without_the_servers() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  sock : FB_ConnectionlessSocket := (nMode := CONNECT_MODE_ENABLEDBG);\n  send : FB_SocketUdpSendTo;\n  host : FB_GetHostName;\n  nics : FB_GetAdaptersInfo := (sNetID := '5.1.2.3.1.1');\n  msg : STRING := 'hello';\n  n : INT;\n  created : BOOL; sockErr, sendErr, hostErr, nicErr : UDINT; slots : UDINT;\nEND_VAR",
        "n := n + 1;\n\
         sock(bEnable := n < 3);\n\
         IF n = 1 THEN sockErr := sock.nErrID; END_IF\n\
         created := sock.eState = E_SocketConnectionlessState.eSOCKET_CREATED;\n\
         send(hSocket := sock.hSocket, sRemoteHost := '10.0.0.1', nRemotePort := 5000, pSrc := ADR(msg), cbLen := LEN2(ADR(msg)), bExecute := TRUE);\n\
         sendErr := send.nErrId;\n\
         host(bExecute := TRUE); hostErr := host.nErrID;\n\
         nics(bExecute := TRUE); nicErr := nics.nErrID;\n\
         slots := UPPER_BOUND(nics.arrAdapters, 1) + 1;",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 3);
    assert_eq!(
        [
            lit(&plc, "P.sockErr"),
            lit(&plc, "P.created"),
            lit(&plc, "P.sendErr"),
            lit(&plc, "P.send.bError")
        ],
        ["6", "FALSE", "6", "TRUE"]
    );
    // bEnable fell in the third cycle: the error is gone.
    assert_eq!(
        [lit(&plc, "P.sock.bError"), lit(&plc, "P.sock.nErrID")],
        ["FALSE", "0"]
    );
    assert_eq!(
        [
            lit(&plc, "P.hostErr"),
            lit(&plc, "P.host.sHostName"),
            lit(&plc, "P.nicErr"),
            lit(&plc, "P.nics.nCount"),
            lit(&plc, "P.slots")
        ],
        ["6", "''", "7", "0", "6"]
    );
}

/// Tc2_Utilities' character codes, Tc2_System's `MAX_STRING_LENGTH`, and
/// `FB_GetLocalAmsNetId` failing as a local ADS request does without a
/// router (error 6 at the rising edge).
#[test]
fn character_codes_the_string_length_and_the_local_ams_address() {
    let decl = "PROGRAM P\nVAR\n  a, z : BYTE; s, e : STRING; n : UDINT; buf : STRING(MAX_STRING_LENGTH);\n  fb : FB_GetLocalAmsNetId; err : UDINT; failed : BOOL; addr : T_AmsNetId;\nEND_VAR";
    let body = "a := F_ToASC('Hello');\nz := F_ToASC('');\ns := F_ToCHR(65);\ne := F_ToCHR(0);\nn := MAX_STRING_LENGTH;\nfb(bExecute := TRUE);\nerr := fb.nErrId; failed := fb.bError; addr := fb.AddrString;";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let got: Vec<String> = ["a", "z", "s", "e", "n", "err", "failed", "addr"]
        .iter()
        .map(|v| lit(&plc, v))
        .collect();
    assert_eq!(
        got,
        ["16#48", "16#0", "'A'", "''", "255", "6", "TRUE", "''"]
    );
}

/// Tc3_JsonXml's `FB_JsonReadWriteDataType`: a structure written as JSON
/// from its type's name and address (SLAC's logger sends its events so),
/// through a reference too, as the writer's next value or into a string;
/// a type nobody declares fails.
#[test]
fn a_structure_is_written_as_json_from_its_type_name() {
    let en = crate::support::twincat::declaration(
        "DUT",
        "E_Sev",
        "TYPE E_Sev : (Info := 1, Warn := 2); END_TYPE",
    );
    let dut = crate::support::twincat::declaration(
        "DUT",
        "ST_Info",
        "TYPE ST_Info :\nSTRUCT\n  msg : STRING(80);\n  id : UDINT;\n  sev : E_Sev;\n  ok : BOOL;\n  r : LREAL;\n  a : ARRAY[1..3] OF INT;\n  t : TIME;\nEND_STRUCT\nEND_TYPE",
    );
    let decl = "PROGRAM P\nVAR\n  st : ST_Info := (msg := 'say \"hi\"', id := 7, sev := E_Sev.Warn, ok := TRUE, r := 1.5, a := [1, -2, 3], t := T#1S500MS);\n  rs : REFERENCE TO ST_Info;\n  fbJson : FB_JsonSaxWriter; fbType : FB_JsonReadWriteDataType;\n  sDoc, sOut : STRING(1000); n : UDINT := 1000; small : UDINT := 10;\n  ok1, ok2, tooSmall, unknown : BOOL; hr : HRESULT;\nEND_VAR";
    let body = "rs REF= st;
fbJson.ResetDocument();
fbJson.StartObject();
fbJson.AddKey('info');
ok1 := fbType.AddJsonValueFromSymbol(fbJson, 'ST_Info', SIZEOF(rs), ADR(rs));
fbJson.EndObject();
fbJson.CopyDocument(sDoc, SIZEOF(sDoc));
ok2 := fbType.GetJsonFromSymbol('st_info', SIZEOF(st), ADR(st), n, ADR(sOut));
tooSmall := fbType.GetJsonFromSymbol('ST_Info', SIZEOF(st), ADR(st), small, ADR(sOut));
unknown := fbType.AddJsonValueFromSymbol(fbJson, 'ST_Nope', SIZEOF(st), ADR(st), hrErrorCode => hr);";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[
        ("E_Sev.TcDUT", &en),
        ("ST_Info.TcDUT", &dut),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    let json =
        r#"{"msg":"say \"hi\"","id":7,"sev":2,"ok":true,"r":1.5,"a":[1,-2,3],"t":"T#1s500ms"}"#;
    assert_eq!(lit(&plc, "sOut"), format!("'{json}'"));
    assert_eq!(lit(&plc, "sDoc"), format!("'{{\"info\":{json}}}'"));
    assert_eq!(lit(&plc, "n"), (json.len() + 1).to_string());
    let flags: Vec<String> = ["ok1", "ok2", "tooSmall", "unknown", "small", "hr"]
        .iter()
        .map(|v| lit(&plc, v))
        .collect();
    assert_eq!(
        flags,
        ["TRUE", "TRUE", "FALSE", "FALSE", "10", "-2147467259"]
    );
}

/// `SetSymbolFromJson`: a structure filled from JSON text by its fields'
/// names (a field without a key kept, a key without a field ignored,
/// enumerations by number or name, durations as IEC literals), the text
/// `GetJsonFromSymbol` wrote read back the same; text that does not fit
/// the type (a fraction for an integer, a value out of range, not JSON)
/// writes nothing.
#[test]
fn a_structure_is_filled_from_json_by_its_type_name() {
    let en = crate::support::twincat::declaration(
        "DUT",
        "E_Sev",
        "TYPE E_Sev : (Info := 1, Warn := 2); END_TYPE",
    );
    let dut = crate::support::twincat::declaration(
        "DUT",
        "ST_Cmd",
        "TYPE ST_Cmd :\nSTRUCT\n  name : STRING(20);\n  n : SINT;\n  sev : E_Sev;\n  on : BOOL;\n  r : REAL;\n  a : ARRAY[0..2] OF INT;\n  t : TIME;\n  kept : INT := 9;\nEND_STRUCT\nEND_TYPE",
    );
    let decl = "PROGRAM P\nVAR\n  cmd, back, bad : ST_Cmd;\n  fbType : FB_JsonReadWriteDataType;\n  sOut : STRING(500); n : UDINT := 500;\n  ok1, ok2, frac, range, notJson : BOOL;\nEND_VAR";
    let body = "ok1 := fbType.SetSymbolFromJson('{\"name\":\"pump 1\",\"N\":-5,\"sev\":\"Warn\",\"on\":true,\"r\":0.5,\"a\":[7,8,9,10],\"t\":\"T#2s\",\"extra\":1}', 'ST_Cmd', SIZEOF(cmd), ADR(cmd));
fbType.GetJsonFromSymbol('ST_Cmd', SIZEOF(cmd), ADR(cmd), n, ADR(sOut));
ok2 := fbType.SetSymbolFromJson(sOut, 'ST_Cmd', SIZEOF(back), ADR(back));
frac := fbType.SetSymbolFromJson('{\"name\":\"x\",\"n\":1.5}', 'ST_Cmd', SIZEOF(bad), ADR(bad));
range := fbType.SetSymbolFromJson('{\"n\":300}', 'ST_Cmd', SIZEOF(bad), ADR(bad));
notJson := fbType.SetSymbolFromJson('{\"n\":', 'ST_Cmd', SIZEOF(bad), ADR(bad));";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[
        ("E_Sev.TcDUT", &en),
        ("ST_Cmd.TcDUT", &dut),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    let got: Vec<String> = [
        "cmd.name", "cmd.n", "cmd.sev", "cmd.on", "cmd.r", "cmd.a[2]", "cmd.t", "cmd.kept",
    ]
    .iter()
    .map(|v| lit(&plc, v))
    .collect();
    assert_eq!(
        got,
        ["'pump 1'", "-5", "Warn", "TRUE", "0.5", "9", "T#2s", "9"]
    );
    for v in ["name", "n", "sev", "r", "a[1]", "t"] {
        assert_eq!(
            lit(&plc, &format!("back.{v}")),
            lit(&plc, &format!("cmd.{v}")),
            "{v}"
        );
    }
    let flags: Vec<String> = [
        "ok1", "ok2", "frac", "range", "notJson", "bad.name", "bad.n",
    ]
    .iter()
    .map(|v| lit(&plc, v))
    .collect();
    assert_eq!(
        flags,
        ["TRUE", "TRUE", "FALSE", "FALSE", "FALSE", "''", "0"]
    );
}
