#!/usr/bin/env python3
"""Measures `plcrun lsp` on a real project: the time from an edit
(textDocument/didChange) to the diagnostics it publishes, the time of a
hover and a completion after it, and the server's memory (VmRSS).

    scripts/lsp_latency.py --plcrun target/release/plcrun FILE... [--edits 20]

The files are copied into a temporary folder with a plcrun.toml naming
them, so they form one project as in an editor. Each edit changes one
character of the first file's text (a digit of a literal), alternating, so
every edit is a real re-check. Prints a Markdown table.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import tempfile
import time


class Client:
    def __init__(self, plcrun, root):
        self.proc = subprocess.Popen([plcrun, "lsp"], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE)
        self.next_id = 1
        uri = "file://" + root
        self.request("initialize", {"processId": None, "rootUri": uri,
                                    "workspaceFolders": [{"uri": uri, "name": "p"}],
                                    "capabilities": {}})
        self.notify("initialized", {})

    def send(self, message):
        body = json.dumps(message).encode()
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.proc.stdin.flush()

    def read(self):
        length = None
        while True:
            line = self.proc.stdout.readline()
            if not line:
                raise SystemExit("plcrun lsp closed its output")
            line = line.strip()
            if not line:
                break
            if line.lower().startswith(b"content-length:"):
                length = int(line.split(b":")[1])
        return json.loads(self.proc.stdout.read(length))

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method, params):
        rid = self.next_id
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": rid, "method": method, "params": params})
        while True:
            m = self.read()
            if m.get("id") == rid:
                return m.get("result")

    def diagnostics(self, uri):
        while True:
            m = self.read()
            if m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri:
                return m["params"]["diagnostics"]

    def rss_kib(self):
        with open("/proc/%d/status" % self.proc.pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
        return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plcrun", required=True)
    ap.add_argument("--edits", type=int, default=20)
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    root = tempfile.mkdtemp(prefix="plcrun-lsp-")
    names = []
    for i, f in enumerate(args.files):
        name = "f%d_%s" % (i, os.path.basename(f))
        shutil.copy(f, os.path.join(root, name))
        names.append(name)
    with open(os.path.join(root, "plcrun.toml"), "w") as f:
        f.write("sources = [%s]\n" % ", ".join('"%s"' % n for n in names))
    first = os.path.join(root, names[0])
    text = open(first, encoding="utf-8", errors="replace").read()
    uri = "file://" + first
    client = Client(os.path.abspath(args.plcrun), root)
    t0 = time.perf_counter()
    client.notify("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "iec-st", "version": 1, "text": text}})
    found = client.diagnostics(uri)
    opened = time.perf_counter() - t0
    # The literal to flip: the first `:= <digit>` of the text.
    m = re.search(r":= ?([0-9])", text)
    if not m:
        raise SystemExit("no literal to edit in " + first)
    at = m.start(1)
    line = text[:at].count("\n")
    column = at - (text.rfind("\n", 0, at) + 1)
    latencies, hovers, completions = [], [], []
    for n in range(args.edits):
        digit = "7" if n % 2 == 0 else text[at]
        edited = text[:at] + digit + text[at + 1:]
        t0 = time.perf_counter()
        client.notify("textDocument/didChange", {
            "textDocument": {"uri": uri, "version": n + 2},
            "contentChanges": [{"text": edited}]})
        client.diagnostics(uri)
        latencies.append(time.perf_counter() - t0)
        pos = {"textDocument": {"uri": uri}, "position": {"line": line, "character": column}}
        t0 = time.perf_counter()
        client.request("textDocument/hover", pos)
        hovers.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        client.request("textDocument/completion", pos)
        completions.append(time.perf_counter() - t0)
    rss = client.rss_kib()
    client.request("shutdown", None)
    client.notify("exit", None)
    client.proc.wait(timeout=10)
    shutil.rmtree(root)
    size = sum(os.path.getsize(f) for f in args.files)
    ms = lambda xs: "%.0f / %.0f" % (statistics.median(xs) * 1000, max(xs) * 1000)
    print("| files | bytes | diagnostics at open | open to diagnostics (ms) | edit to diagnostics, median / max (ms) | hover (ms) | completion (ms) | RSS (MiB) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    print("| %d | %d | %d | %.0f | %s | %s | %s | %.1f |" % (
        len(args.files), size, len(found), opened * 1000, ms(latencies), ms(hovers),
        ms(completions), rss / 1024))


if __name__ == "__main__":
    main()
