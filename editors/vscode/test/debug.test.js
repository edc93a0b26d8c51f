// Checks the manifest's debugger contribution and drives `plcrun debug`
// over stdio with Content-Length framed Debug Adapter Protocol messages,
// as VS Code does for a "plcrun" launch configuration: initialize, launch
// a program with a breakpoint, stop there, read the stack, disconnect.
// PLCRUN names the binary (default: the repository's debug build).
const { test } = require("node:test");
const assert = require("node:assert");
const { spawn } = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");

const root = path.resolve(__dirname, "..");
const plcrun = process.env.PLCRUN || path.resolve(root, "../../target/debug/plcrun");

test("the manifest contributes the plcrun debugger and its launch snippets", () => {
  const manifest = JSON.parse(fs.readFileSync(path.join(root, "package.json"), "utf8"));
  const debuggers = manifest.contributes.debuggers;
  assert.strictEqual(debuggers.length, 1);
  assert.strictEqual(debuggers[0].type, "plcrun");
  assert.deepStrictEqual(debuggers[0].configurationAttributes.launch.required, ["program"]);
  assert.ok(debuggers[0].configurationSnippets.length >= 1);
  for (const s of debuggers[0].configurationSnippets) {
    assert.strictEqual(s.body.type, "plcrun");
    assert.strictEqual(s.body.request, "launch");
  }
  const languages = manifest.contributes.breakpoints.map((b) => b.language);
  assert.ok(languages.includes("iec-st") && languages.includes("iec-sfc"));
});

// A minimal DAP client: framed requests, responses and events by callback.
function client(child) {
  let buffer = Buffer.alloc(0);
  let seq = 0;
  const waiting = [];
  const seen = [];
  child.stdout.on("data", (chunk) => {
    buffer = Buffer.concat([buffer, chunk]);
    for (;;) {
      const end = buffer.indexOf("\r\n\r\n");
      if (end < 0) return;
      const length = Number(/Content-Length: *(\d+)/i.exec(buffer.slice(0, end).toString())[1]);
      if (buffer.length < end + 4 + length) return;
      const message = JSON.parse(buffer.slice(end + 4, end + 4 + length).toString());
      buffer = buffer.slice(end + 4 + length);
      seen.push(message);
      for (const w of [...waiting]) {
        if (w.want(message)) {
          waiting.splice(waiting.indexOf(w), 1);
          w.resolve(message);
        }
      }
    }
  });
  const wait = (want) =>
    new Promise((resolve) => {
      const found = seen.find(want);
      if (found) {
        seen.splice(seen.indexOf(found), 1);
        resolve(found);
      } else {
        waiting.push({ want, resolve });
      }
    });
  return {
    request(command, args) {
      const body = JSON.stringify({ seq: ++seq, type: "request", command, arguments: args });
      child.stdin.write(`Content-Length: ${Buffer.byteLength(body)}\r\n\r\n${body}`);
      const s = seq;
      return wait((m) => m.type === "response" && m.request_seq === s);
    },
    event(name) {
      return wait((m) => m.type === "event" && m.event === name);
    },
  };
}

test("plcrun debug stops at a breakpoint", { skip: !fs.existsSync(plcrun) && `no ${plcrun}` }, async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "plcrun-vscode-"));
  const file = path.join(dir, "main.st");
  fs.writeFileSync(file, "PROGRAM Main\nVAR n : INT; END_VAR\nn := n + 1;\nn := n * 2;\nEND_PROGRAM\n");
  const child = spawn(plcrun, ["debug"], { stdio: ["pipe", "pipe", "inherit"] });
  const dap = client(child);
  const init = await dap.request("initialize", { adapterID: "plcrun" });
  assert.strictEqual(init.success, true);
  assert.strictEqual((await dap.request("launch", { program: file, args: ["--cycles", "10"] })).success, true);
  await dap.event("initialized");
  const set = await dap.request("setBreakpoints", { source: { path: file }, breakpoints: [{ line: 4 }] });
  assert.strictEqual(set.body.breakpoints[0].verified, true);
  await dap.request("configurationDone", {});
  const stopped = await dap.event("stopped");
  assert.strictEqual(stopped.body.reason, "breakpoint");
  const stack = await dap.request("stackTrace", { threadId: 1 });
  assert.strictEqual(stack.body.stackFrames[0].name, "Main");
  assert.strictEqual(stack.body.stackFrames[0].line, 4);
  const n = await dap.request("evaluate", { expression: "n", frameId: 1 });
  assert.strictEqual(n.body.result, "1");
  await dap.request("disconnect", {});
  await new Promise((resolve) => child.on("exit", resolve));
});
