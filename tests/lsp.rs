//! `plcrun lsp` driven over stdio with real protocol messages by a scripted
//! client (tests/support/lsp_client.rs): diagnostics as you type, hover,
//! go to definition across files, completion, rename, references,
//! symbols, signature help, semantic tokens and folding.

use crate::support::cli::temp_file;
use crate::support::lsp_client::{LspClient, position_of, uri};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

const TYPES: &str = "\
TYPE Color : (Red, Green, Blue); END_TYPE

(* Drives one conveyor motor. *)
FUNCTION_BLOCK Motor
VAR_INPUT
    start : BOOL;
    speed : INT; (* set point, rpm *)
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    count : INT;
END_VAR
running := start AND speed > 0;
count := count + 1;
END_FUNCTION_BLOCK
";

const MAIN: &str = "\
PROGRAM Main
VAR
    m : Motor;
    c : Color;
    t : TON;
    level : INT;
END_VAR
m(start := TRUE, speed := 5);
c := Color#Red;
t(IN := m.running, PT := T#1s);
level := LIMIT(0, level + 1, 100);
IF t.Q THEN
    level := 0;
END_IF;
END_PROGRAM
";

/// A project folder holding `plcrun.toml`, types.st and main.st.
fn project() -> (PathBuf, PathBuf, PathBuf) {
    let manifest = PathBuf::from(temp_file(
        "plcrun.toml",
        "sources = [\"types.st\", \"main.st\"]\ncycle_time = \"10ms\"\n",
    ));
    let dir = manifest.parent().unwrap().to_path_buf();
    let types = dir.join("types.st");
    let main = dir.join("main.st");
    std::fs::write(&types, TYPES).unwrap();
    std::fs::write(&main, MAIN).unwrap();
    (dir, types, main)
}

/// A started server with both files open, their first diagnostics read.
fn session() -> (LspClient, PathBuf, PathBuf) {
    let (dir, types, main) = project();
    let (mut client, _) = LspClient::start(&dir);
    client.open(&types, TYPES);
    client.open(&main, MAIN);
    assert_eq!(client.diagnostics(&main, 0), Vec::<Value>::new());
    (client, types, main)
}

fn line_of(location: &Value) -> u64 {
    location["range"]["start"]["line"].as_u64().unwrap()
}

#[test]
fn the_server_announces_what_it_answers_and_exits_cleanly() {
    let (dir, _, _) = project();
    let (client, caps) = LspClient::start(&dir);
    for cap in [
        "hoverProvider",
        "definitionProvider",
        "referencesProvider",
        "renameProvider",
        "completionProvider",
        "signatureHelpProvider",
        "documentSymbolProvider",
        "workspaceSymbolProvider",
        "semanticTokensProvider",
        "foldingRangeProvider",
    ] {
        assert!(!caps[cap].is_null(), "{cap} missing in {caps}");
    }
    // plcrun has no formatter: it does not claim one.
    assert!(caps["documentFormattingProvider"].is_null());
    assert_eq!(client.shutdown(), Some(0));
}

#[test]
fn a_typo_gets_its_diagnostic_at_the_right_range_and_goes_when_fixed() {
    let (mut client, _, main) = session();
    let typo = MAIN.replace("t(IN := m.running", "t(IN := moter.running");
    client.change(&main, 2, &typo);
    let found = client.diagnostics(&main, 1);
    let d = found
        .iter()
        .find(|d| d["code"] == "E201")
        .unwrap_or_else(|| panic!("no E201 in {found:?}"));
    assert!(d["message"].as_str().unwrap().contains("moter"), "{d}");
    assert_eq!(d["severity"], 1);
    let start = &position_of(&main, &typo, "moter", 0, 0)["position"];
    assert_eq!(d["range"]["start"], *start);
    assert_eq!(
        d["range"]["end"]["character"].as_u64().unwrap(),
        start["character"].as_u64().unwrap() + 5
    );
    client.change(&main, 3, MAIN);
    assert_eq!(client.diagnostics(&main, 0), Vec::<Value>::new());
}

#[test]
fn hover_shows_the_type_the_range_and_the_comment() {
    let (mut client, _, main) = session();
    let at = position_of(&main, MAIN, "speed := 5", 0, 1);
    let hover = client.request("textDocument/hover", at);
    let text = hover["contents"]["value"].as_str().unwrap();
    assert!(text.contains("VAR_INPUT speed : INT"), "{text}");
    assert!(text.contains("-32768..32767"), "{text}");
    assert!(text.contains("set point, rpm"), "{text}");
    // A standard block's pins, and a standard function's signature.
    let at = position_of(&main, MAIN, "TON;", 0, 0);
    let text = client.request("textDocument/hover", at)["contents"]["value"].clone();
    assert!(
        text.as_str().unwrap().contains("IN : BOOL, PT : TIME"),
        "{text}"
    );
    let at = position_of(&main, MAIN, "LIMIT", 0, 2);
    let text = client.request("textDocument/hover", at)["contents"]["value"].clone();
    assert!(text.as_str().unwrap().contains("LIMIT(MN"), "{text}");
    // The block's documentation comment, above its header.
    let at = position_of(&main, MAIN, "Motor;", 0, 1);
    let text = client.request("textDocument/hover", at)["contents"]["value"].clone();
    assert!(
        text.as_str()
            .unwrap()
            .contains("Drives one conveyor motor."),
        "{text}"
    );
}

#[test]
fn definition_jumps_across_files_and_to_a_variables_type() {
    let (mut client, types, main) = session();
    let at = position_of(&main, MAIN, "Motor;", 0, 2);
    let found = client.request("textDocument/definition", at);
    assert_eq!(found["uri"], json!(uri(&types)));
    assert_eq!(line_of(&found), 3);
    // A formal parameter of a call: the block's input.
    let at = position_of(&main, MAIN, "speed := 5", 0, 0);
    let found = client.request("textDocument/definition", at);
    assert_eq!(
        (found["uri"].clone(), line_of(&found)),
        (json!(uri(&types)), 6)
    );
    // Type definition of `m`: the block.
    let at = position_of(&main, MAIN, "m(start", 0, 0);
    let found = client.request("textDocument/typeDefinition", at);
    assert_eq!(
        (found["uri"].clone(), line_of(&found)),
        (json!(uri(&types)), 3)
    );
    // An enumeration value written `Color#Red`.
    let at = position_of(&main, MAIN, "#Red", 0, 1);
    let found = client.request("textDocument/definition", at);
    assert_eq!(
        (found["uri"].clone(), line_of(&found)),
        (json!(uri(&types)), 0)
    );
}

fn labels(items: &Value) -> Vec<String> {
    items
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn completion_after_an_instance_dot_lists_the_blocks_interface() {
    let (mut client, _, main) = session();
    let editing = MAIN.replace("level := 0;", "level := m.");
    client.change(&main, 2, &editing);
    let at = position_of(&main, &editing, "m.\n", 0, 2);
    let found = labels(&client.request("textDocument/completion", at));
    for member in ["start", "speed", "running"] {
        assert!(
            found.contains(&member.to_string()),
            "{member} not in {found:?}"
        );
    }
    // Its local variable is not reachable from outside.
    assert!(!found.contains(&"count".to_string()), "{found:?}");
    // A standard block's pins.
    let editing = MAIN.replace("level := 0;", "level := t.");
    client.change(&main, 3, &editing);
    let at = position_of(&main, &editing, "t.\n", 0, 2);
    let found = labels(&client.request("textDocument/completion", at));
    assert_eq!(found, ["IN", "PT", "Q", "ET"]);
}

#[test]
fn completion_offers_names_in_scope_parameters_and_types() {
    let (mut client, _, main) = session();
    let editing = MAIN.replace("level := 0;", "lev");
    client.change(&main, 2, &editing);
    let at = position_of(&main, &editing, "lev\n", 0, 3);
    let found = labels(&client.request("textDocument/completion", at));
    for name in ["level", "m", "Motor", "LIMIT", "IF", "Red"] {
        assert!(found.contains(&name.to_string()), "{name} not in {found:?}");
    }
    // Inside a call's parentheses: the block's parameters.
    let editing = MAIN.replace("m(start := TRUE, speed := 5);", "m(");
    client.change(&main, 3, &editing);
    let at = position_of(&main, &editing, "m(\n", 0, 2);
    let found = labels(&client.request("textDocument/completion", at));
    assert!(found.contains(&"start :=".to_string()), "{found:?}");
    assert!(found.contains(&"running =>".to_string()), "{found:?}");
    // After a declaration's colon: types.
    let editing = MAIN.replace("level : INT;", "level : ");
    client.change(&main, 4, &editing);
    let at = position_of(&main, &editing, "level : ", 0, 8);
    let found = labels(&client.request("textDocument/completion", at));
    for ty in ["INT", "Motor", "Color", "TON", "ARRAY"] {
        assert!(found.contains(&ty.to_string()), "{ty} not in {found:?}");
    }
}

#[test]
fn rename_changes_every_file_and_only_that_symbol() {
    let (mut client, types, main) = session();
    let mut params = position_of(&main, MAIN, "Motor;", 0, 0);
    params["newName"] = json!("Drive");
    let edit = client.request("textDocument/rename", params);
    let changes = edit["changes"].as_object().unwrap();
    assert_eq!(changes[&uri(&types)].as_array().unwrap().len(), 1);
    assert_eq!(changes[&uri(&main)].as_array().unwrap().len(), 1);
    // `speed` the input: its declaration and the formal name in the call.
    let mut params = position_of(&types, TYPES, "speed > 0", 0, 0);
    params["newName"] = json!("rpm");
    let edit = client.request("textDocument/rename", params);
    let changes = edit["changes"].as_object().unwrap();
    assert_eq!(changes[&uri(&types)].as_array().unwrap().len(), 2);
    assert_eq!(changes[&uri(&main)].as_array().unwrap().len(), 1);
    // Refused: a keyword, a name taken in the same scope, a standard block.
    for (needle, name) in [("level :=", "END_IF"), ("level :=", "c"), ("TON;", "Timer")] {
        let mut params = position_of(&main, MAIN, needle, 0, 0);
        params["newName"] = json!(name);
        let refused = client.call("textDocument/rename", params);
        assert!(refused.is_err(), "renaming to {name} was accepted");
    }
}

#[test]
fn references_symbols_signature_tokens_and_folding() {
    let (mut client, types, main) = session();
    let mut params = position_of(&main, MAIN, "level", 0, 0);
    params["context"] = json!({"includeDeclaration": true});
    let found = client.request("textDocument/references", params);
    // Its declaration, `level := LIMIT(0, level + 1, 100)` and `level := 0`.
    assert_eq!(found.as_array().unwrap().len(), 4, "{found}");

    let doc = json!({"textDocument": {"uri": uri(&types)}});
    let symbols = client.request("textDocument/documentSymbol", doc.clone());
    let names: Vec<&str> = symbols
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["Color", "Motor"]);
    let members: Vec<&str> = symbols[1]["children"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(members, ["start", "speed", "running", "count"]);

    let found = client.request("workspace/symbol", json!({"query": "mot"}));
    assert_eq!(found[0]["name"], "Motor");

    let editing = MAIN.replace("m(start := TRUE, speed := 5);", "m(start := TRUE, ");
    client.change(&main, 2, &editing);
    let at = position_of(&main, &editing, "TRUE, ", 0, 6);
    let sig = client.request("textDocument/signatureHelp", at);
    assert_eq!(sig["activeParameter"], 1);
    let label = sig["signatures"][0]["label"].as_str().unwrap();
    assert!(
        label.starts_with("FUNCTION_BLOCK Motor(start : BOOL, speed : INT)"),
        "{label}"
    );
    client.change(&main, 3, MAIN);

    let tokens = client.request("textDocument/semanticTokens/full", doc.clone());
    // Five numbers per token; `Motor`, `start`... all classified.
    let data = tokens["data"].as_array().unwrap();
    assert!(data.len() >= 5 * 10 && data.len() % 5 == 0, "{tokens}");

    let folds = client.request("textDocument/foldingRange", doc);
    let starts: Vec<u64> = folds
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["startLine"].as_u64().unwrap())
        .collect();
    assert!(starts.contains(&3) && starts.contains(&4), "{folds}");
}

#[test]
fn a_chart_steps_are_symbols_and_transitions_point_at_them() {
    let source =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("programs/chariot.sfc"))
            .unwrap();
    let path = PathBuf::from(temp_file("chariot.sfc", &source));
    let (mut client, _) = LspClient::start(path.parent().unwrap());
    client.open(&path, &source);
    let diagnostics = client.diagnostics(&path, 0);
    assert!(
        diagnostics.iter().all(|d| d["severity"] != 1),
        "{diagnostics:?}"
    );
    let doc = json!({"textDocument": {"uri": uri(&path)}});
    let symbols = client.request("textDocument/documentSymbol", doc);
    let program = &symbols[0];
    let steps: Vec<&str> = program["children"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["kind"] == 24)
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert!(steps.len() >= 3, "{symbols}");
    // A transition's `FROM` names a step: definition goes to it.
    let from = source.find("FROM ").expect("CHARIOT has transitions") + 5;
    let step = source[from..]
        .split(|c: char| !c.is_ascii_alphanumeric() && c != '_')
        .next()
        .unwrap();
    let at = position_of(&path, &source, &format!("FROM {step}"), 0, 5);
    let found = client.request("textDocument/definition", at);
    let declared = source
        .find(&format!("STEP {step}"))
        .expect("the step is declared");
    let line = source[..declared].matches('\n').count() as u64;
    assert_eq!(line_of(&found), line);
}

/// A program with a typo on line 9 (`levle`), `level` used on line 8.
const NEOVIM_PROGRAM: &str = "\
PROGRAM Main
VAR
    (* liquid level, mm *)
    level : INT;
    t : TON;
END_VAR
t(IN := TRUE, PT := T#1s);
IF t.Q THEN
level := level + 1;
levle := 0;
END_IF;
END_PROGRAM
";

#[test]
fn neovims_own_client_gets_diagnostics_hover_and_definition() {
    let found = std::process::Command::new("nvim").arg("--version").output();
    if !found.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: nvim is not installed (apt-get install neovim runs this test)");
        return;
    }
    let file = PathBuf::from(temp_file("main.st", NEOVIM_PROGRAM));
    let dir = file.parent().unwrap().to_path_buf();
    let out = dir.join("neovim.json");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/lsp/neovim_client.lua");
    let status = std::process::Command::new("nvim")
        .args(["--headless", "-u", "NONE", "-i", "NONE", "-n"])
        .arg("-c")
        .arg(format!("luafile {}", script.display()))
        .env("PLCRUN", env!("CARGO_BIN_EXE_plcrun"))
        .env("ROOT", &dir)
        .env("FILE", &file)
        .env("OUT", &out)
        .env("XDG_STATE_HOME", &dir)
        .env("XDG_DATA_HOME", &dir)
        .stdin(std::process::Stdio::null())
        .status()
        .expect("nvim runs");
    assert!(status.success(), "nvim exited with {status}");
    let result: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let diagnostics = result["diagnostics"].as_array().unwrap();
    assert!(
        diagnostics
            .iter()
            .any(|d| d["code"] == "E201" && d["line"] == 9 && d["col"] == 0),
        "{result}"
    );
    let hover = result["hover"].as_str().unwrap();
    assert!(
        hover.contains("level : INT") && hover.contains("liquid level, mm"),
        "{hover}"
    );
    assert_eq!(result["definition_line"], 3);
}

/// `plcrun lsp --live ADDR` shows the values of a running plcrun (its web
/// monitor at ADDR) as inlay hints after the program's variables, and
/// asks the client to fetch them again as the scan goes on: the counter
/// `n` is shown, and grows between two requests a second apart.
#[cfg(feature = "cli")]
#[test]
fn live_values_of_a_running_plc_are_inlay_hints_that_follow_the_scan() {
    let counter = "PROGRAM Main\nVAR n : DINT; fb : TON; END_VAR\nn := n + 1;\nfb(IN := n > 5, PT := T#1h);\nEND_PROGRAM\n";
    let main = PathBuf::from(temp_file("live.st", counter));
    let dir = main.parent().unwrap().to_path_buf();
    let monitor = crate::web_cli::Monitor::start(&[main.to_str().unwrap()]);
    let capabilities = json!({"workspace": {"inlayHint": {"refreshSupport": true}}});
    let (mut client, caps) = LspClient::start_with(&dir, &["--live", &monitor.addr], capabilities);
    assert!(!caps["inlayHintProvider"].is_null(), "{caps}");
    client.open(&main, counter);
    let all = json!({"start": {"line": 0, "character": 0}, "end": {"line": 5, "character": 0}});
    let values_of_n = |client: &mut LspClient| -> Vec<i64> {
        let hints = client.request(
            "textDocument/inlayHint",
            json!({"textDocument": {"uri": uri(&main)}, "range": all}),
        );
        // `n` is written three times: twice on line 2, once on line 3; the
        // TON instance `fb` has no single value and gets no hint.
        let hints = hints
            .as_array()
            .unwrap_or_else(|| panic!("not a list of hints: {hints}"))
            .clone();
        assert_eq!(hints.len(), 3, "{hints:?}");
        hints
            .iter()
            .map(|h| {
                let label = h["label"].as_str().unwrap();
                label.strip_prefix("= ").unwrap().parse().unwrap()
            })
            .collect()
    };
    let first = values_of_n(&mut client);
    std::thread::sleep(std::time::Duration::from_secs(1));
    let second = values_of_n(&mut client);
    assert!(second[0] > first[0], "{first:?} then {second:?}");
    // The server asked the client to refresh its hints on its own.
    assert!(
        client
            .notifications
            .iter()
            .any(|m| m["method"] == "workspace/inlayHint/refresh"),
        "no refresh request among {:?}",
        client.notifications
    );
    assert_eq!(client.shutdown(), Some(0));
    assert_eq!(monitor.stop(), 0);
}

#[test]
fn without_live_values_no_inlay_hints_are_offered() {
    let (dir, _, _) = project();
    let (client, caps) = LspClient::start(&dir);
    assert!(caps["inlayHintProvider"].is_null(), "{caps}");
    assert_eq!(client.shutdown(), Some(0));
}
