//! Tc3_JsonXml's `FB_JsonDomParser` as plcrun's TwinCAT library provides
//! it (docs/twincat.md): documents built member by member and element by
//! element, read back by name and index, shared between parser instances
//! as SLAC's PMPS libraries share their beam-parameter document.

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile_ok, pou};

#[test]
fn a_dom_document_is_built_and_read_back_by_another_parser() {
    let decl = "PROGRAM P\nVAR\n  fbBuild, fbRead : FB_JsonDomParser;\n  root, dev, state, list, v : SJsonValue;\n  \
        sName : STRING := 'T1';\n  id : DINT; tran : STRING; special, hasDev, hasNone : BOOL;\n  \
        none : SJsonValue; size : UDINT; second : LREAL; third : STRING; big : LINT; memberName : STRING;\n  \
        kinds : STRING; notObject : SJsonValue; raised : BOOL;\nEND_VAR";
    let body = "root := fbBuild.NewDocument();
dev := fbBuild.AddObjectMember(root, 'XPP:DEV');
state := fbBuild.AddObjectMember(dev, sName);
fbBuild.AddIntMember(v := state, member := 'id', value := 7);
fbBuild.AddStringMember(v := state, member := 'nTran', value := '0.5');
fbBuild.AddBoolMember(v := state, member := 'special', value := TRUE);
fbBuild.AddInt64Member(state, 'big', 5000000000);
list := fbBuild.AddArrayMember(state, 'list');
fbBuild.PushbackIntValue(list, 1);
fbBuild.PushbackDoubleValue(list, 2.5);
fbBuild.PushbackStringValue(list, 'three');
fbBuild.AddNullMember(state, 'none');
(* Read with another parser, as PMPS's FB_JsonDocToSafeBP does. *)
hasDev := fbRead.HasMember(root, 'XPP:DEV');
hasNone := fbRead.HasMember(root, 'xpp:dev');
v := fbRead.FindMember(fbRead.FindMember(fbRead.FindMember(root, 'XPP:DEV'), 'T1'), 'id');
id := fbRead.GetInt(v);
memberName := fbRead.GetMemberName(v);
tran := fbRead.GetString(fbRead.FindMember(state, 'nTran'));
special := fbRead.GetBool(fbRead.FindMember(state, 'special'));
big := fbRead.GetInt64(fbRead.FindMember(state, 'big'));
none := fbRead.FindMember(state, 'absent');
size := fbRead.GetArraySize(list);
second := fbRead.GetDouble(fbRead.GetArrayValueByIdx(list, 1));
third := fbRead.GetString(fbRead.GetArrayValueByIdx(list, 2));
IF fbRead.IsNull(fbRead.FindMember(state, 'none')) THEN kinds := CONCAT(kinds, 'n'); END_IF
IF fbRead.IsObject(dev) THEN kinds := CONCAT(kinds, 'o'); END_IF
IF fbRead.IsArray(list) THEN kinds := CONCAT(kinds, 'a'); END_IF
IF NOT fbRead.IsString(v) THEN kinds := CONCAT(kinds, '-'); END_IF
(* A member added to what is no object: none, and an exception. *)
notObject := fbBuild.AddIntMember(list, 'x', 1);
raised := fbBuild.ExceptionRaised();";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let get = |n: &str| lit(&plc, n);
    assert_eq!([get("hasDev"), get("hasNone")], ["TRUE", "FALSE"]);
    assert_eq!(get("id"), "7");
    assert_eq!(get("memberName"), "'id'");
    assert_eq!(get("tran"), "'0.5'");
    assert_eq!(get("special"), "TRUE");
    assert_eq!(get("big"), "5000000000");
    assert_eq!(get("none"), "0");
    assert_eq!(
        [get("size"), get("second"), get("third")],
        ["3", "2.5", "'three'"]
    );
    assert_eq!(get("kinds"), "'noa-'");
    assert_eq!([get("notObject"), get("raised")], ["0", "TRUE"]);
}

#[test]
fn a_new_document_drops_the_parser_s_previous_one_and_keeps_the_others() {
    // Each cycle builds a document again: the values do not run out, and
    // another parser's document stays as it was.
    let decl = "PROGRAM P\nVAR\n  fbA, fbB : FB_JsonDomParser;\n  a, b, old : SJsonValue; i : INT;\n  \
        keptB : DINT; oldGone : BOOL; n : DINT;\nEND_VAR";
    let body = "IF b = 0 THEN
  b := fbB.NewDocument();
  fbB.AddIntMember(b, 'k', 99);
END_IF
old := a;
a := fbA.NewDocument();
FOR i := 1 TO 1000 DO
  fbA.AddIntMember(a, 'm', i);
END_FOR
n := fbA.GetInt(fbA.FindMember(a, 'm'));
keptB := fbA.GetInt(fbA.FindMember(b, 'k'));
oldGone := old <> a AND NOT fbA.IsObject(old);";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 10);
    // FindMember gives the first member of that name.
    assert_eq!(lit(&plc, "n"), "1");
    assert_eq!(lit(&plc, "keptB"), "99");
    assert_eq!(lit(&plc, "oldGone"), "TRUE");
}

#[test]
fn a_text_is_parsed_into_a_document_and_written_back_compact() {
    let decl = "PROGRAM P\nVAR\n  fb, other : FB_JsonDomParser;\n  root, dev, list : SJsonValue;\n  \
        text : STRING(255) := '{ \"dev\" : {\"id\": 42, \"name\":\"a\\\"b\\u0041\", \"on\": true, \"off\": false,$N \
        \"none\": null, \"list\": [1, -2.5e1, \"x\", [], {}]}, \"ok\": 1.5 }';\n  \
        id, size : DINT; name : STRING; on, off, isNull, bad1, bad2, bad3, raised : BOOL; second : LREAL;\n  \
        written : STRING(255); big : STRING(255); n, len : UDINT; part : STRING(255);\n  \
        r1, r2, r3 : SJsonValue;\nEND_VAR";
    let body = "root := fb.ParseDocument(text);
dev := fb.FindMember(root, 'dev');
id := fb.GetInt(fb.FindMember(dev, 'id'));
name := fb.GetString(fb.FindMember(dev, 'name'));
on := fb.GetBool(fb.FindMember(dev, 'on'));
off := fb.GetBool(fb.FindMember(dev, 'off'));
isNull := fb.IsNull(fb.FindMember(dev, 'none'));
list := fb.FindMember(dev, 'list');
size := UDINT_TO_DINT(fb.GetArraySize(list));
second := fb.GetDouble(fb.GetArrayValueByIdx(list, 1));
written := fb.GetDocument();
len := fb.GetDocumentLength();
n := fb.CopyDocument(big, SIZEOF(big));
part := other.GetJson(list);
(* Texts that are no JSON value: 0, an exception, no document. *)
r1 := other.ParseDocument('{\"a\": }');
bad1 := r1 = 0;
r2 := other.ParseDocument('[1, 2');
bad2 := r2 = 0;
r3 := other.ParseDocument('{\"a\": 1} x');
bad3 := r3 = 0;
raised := other.ExceptionRaised();";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let get = |n: &str| lit(&plc, n);
    assert_eq!(get("id"), "42");
    assert_eq!(get("name"), "'a\"bA'");
    assert_eq!(
        [get("on"), get("off"), get("isNull")],
        ["TRUE", "FALSE", "TRUE"]
    );
    assert_eq!([get("size"), get("second")], ["5", "-25.0"]);
    let doc = r#"{"dev":{"id":42,"name":"a\"bA","on":true,"off":false,"none":null,"list":[1,-25.0,"x",[],{}]},"ok":1.5}"#;
    assert_eq!(get("written"), format!("'{doc}'"));
    assert_eq!(get("len"), doc.len().to_string());
    assert_eq!(get("n"), (doc.len() + 1).to_string());
    assert_eq!(get("big"), format!("'{doc}'"));
    assert_eq!(get("part"), r#"'[1,-25.0,"x",[],{}]'"#);
    assert_eq!(
        [get("bad1"), get("bad2"), get("bad3"), get("raised")],
        ["TRUE", "TRUE", "TRUE", "TRUE"]
    );
}
