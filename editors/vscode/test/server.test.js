// Drives `plcrun lsp` over stdio with the JSON-RPC library VS Code's own
// client is built on (vscode-jsonrpc, a dependency of
// vscode-languageclient), as the extension does: initialise, open a file,
// receive its diagnostics, hover. PLCRUN names the binary (default: the
// repository's debug build). Also checks that every grammar parses and
// that the manifest names files that exist.
const { test } = require("node:test");
const assert = require("node:assert");
const { spawn } = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");
const rpc = require("vscode-jsonrpc/node");

const root = path.resolve(__dirname, "..");
const plcrun = process.env.PLCRUN || path.resolve(root, "../../target/debug/plcrun");

test("the manifest's grammars and configuration exist and parse", () => {
  const manifest = JSON.parse(fs.readFileSync(path.join(root, "package.json"), "utf8"));
  for (const g of manifest.contributes.grammars) {
    const grammar = JSON.parse(fs.readFileSync(path.join(root, g.path), "utf8"));
    assert.strictEqual(grammar.scopeName, g.scopeName);
    for (const p of grammar.patterns) {
      if (p.include) {
        assert.ok(grammar.repository[p.include.slice(1)], `${g.path}: ${p.include}`);
      }
    }
  }
  for (const l of manifest.contributes.languages) {
    JSON.parse(fs.readFileSync(path.join(root, l.configuration), "utf8"));
  }
});

test("plcrun lsp answers the extension's client", { skip: !fs.existsSync(plcrun) && `no ${plcrun}` }, async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "plcrun-vscode-"));
  const file = path.join(dir, "main.st");
  const text = "PROGRAM Main\nVAR\n    speed : INT; (* rpm *)\nEND_VAR\nsped := 1;\nEND_PROGRAM\n";
  fs.writeFileSync(file, text);
  const child = spawn(plcrun, ["lsp", "--stdio"], { stdio: ["pipe", "pipe", "inherit"] });
  const connection = rpc.createMessageConnection(
    new rpc.StreamMessageReader(child.stdout),
    new rpc.StreamMessageWriter(child.stdin),
  );
  const uri = "file://" + file;
  const diagnostics = new Promise((resolve) => {
    connection.onNotification("textDocument/publishDiagnostics", (p) => {
      if (p.uri === uri) {
        resolve(p.diagnostics);
      }
    });
  });
  connection.listen();
  const init = await connection.sendRequest("initialize", {
    processId: process.pid,
    rootUri: "file://" + dir,
    capabilities: {},
  });
  assert.ok(init.capabilities.hoverProvider);
  connection.sendNotification("initialized", {});
  connection.sendNotification("textDocument/didOpen", {
    textDocument: { uri, languageId: "iec-st", version: 1, text },
  });
  const found = await diagnostics;
  assert.strictEqual(found.length, 1);
  assert.strictEqual(found[0].code, "E201");
  assert.deepStrictEqual(found[0].range.start, { line: 4, character: 0 });
  const hover = await connection.sendRequest("textDocument/hover", {
    textDocument: { uri },
    position: { line: 2, character: 5 },
  });
  assert.match(hover.contents.value, /speed : INT/);
  assert.match(hover.contents.value, /rpm/);
  await connection.sendRequest("shutdown");
  connection.sendNotification("exit");
  const code = await new Promise((resolve) => child.on("exit", resolve));
  assert.strictEqual(code, 0);
  connection.dispose();
});
