#!/usr/bin/env python3
"""What a debugger costs per statement (docs/editors.md, "What a debugger
costs"): runs one program N cycles three ways with the same binary and
prints the median wall times and the cost per statement start.

  plain     plcrun run PROGRAM --cycles N --no-trace (no debugger)
  attached  plcrun debug, launched with the same flags, no breakpoint
  elsewhere plcrun debug with a breakpoint on a line that never runs

The program (written to a temporary folder) loops 1000 times per cycle
over BODY statements on their own lines, so a cycle runs 1000 * (BODY + 1)
statement starts (the FOR line's own code runs at each iteration too);
`--check-count` steps through one iteration to show that count.

  scripts/debug_cost.py --plcrun target/release/plcrun [-n RUNS] [--cycles N]
"""
import argparse, json, os, statistics, subprocess, sys, tempfile, threading, queue, time

BODY = 10


def program():
    lines = ["PROGRAM Bench",
             "VAR i : DINT; a : DINT; b : DINT; never : BOOL; hit : DINT; END_VAR",
             "FOR i := 1 TO 1000 DO"]
    for k in range(BODY):
        lines.append(f"    a := a + i + {k};" if k % 2 == 0 else f"    b := a - b;")
    lines += ["END_FOR", "IF never THEN", "    hit := hit + 1;", "END_IF", "END_PROGRAM", ""]
    never_line = lines.index("    hit := hit + 1;") + 1
    return "\n".join(lines), never_line


class Dap:
    def __init__(self, plcrun):
        self.p = subprocess.Popen([plcrun, "debug"], stdin=subprocess.PIPE,
                                  stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        self.q = queue.Queue()
        self.seq = 0
        threading.Thread(target=self.read, daemon=True).start()

    def read(self):
        while True:
            line = self.p.stdout.readline()
            if not line:
                self.q.put(None)
                return
            n = int(line.split(b":")[1])
            self.p.stdout.readline()
            self.q.put(json.loads(self.p.stdout.read(n)))

    def send(self, command, arguments):
        self.seq += 1
        body = json.dumps({"seq": self.seq, "type": "request", "command": command,
                           "arguments": arguments}).encode()
        self.p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.p.stdin.flush()
        return self.seq

    def wait(self, pred):
        while True:
            m = self.q.get(timeout=600)
            if m is None:
                sys.exit("plcrun debug ended early")
            if pred(m):
                return m

    def request(self, command, arguments):
        s = self.send(command, arguments)
        return self.wait(lambda m: m.get("type") == "response" and m.get("request_seq") == s)

    def event(self, name):
        return self.wait(lambda m: m.get("type") == "event" and m.get("event") == name)


def plain(plcrun, path, cycles):
    t = time.perf_counter()
    subprocess.run([plcrun, path, "--cycles", str(cycles), "--no-trace"], check=True, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t


def debugged(plcrun, path, cycles, line):
    d = Dap(plcrun)
    d.request("initialize", {"adapterID": "cost"})
    d.request("launch", {"program": path, "args": ["--cycles", str(cycles)]})
    d.event("initialized")
    bps = [{"line": line}] if line else []
    r = d.request("setBreakpoints", {"source": {"path": path}, "breakpoints": bps})
    assert all(b["verified"] for b in r["body"]["breakpoints"]), r
    t = time.perf_counter()
    d.request("configurationDone", {})
    d.event("exited")
    took = time.perf_counter() - t
    d.request("disconnect", {})
    d.p.wait()
    return took


def check_count(plcrun, path):
    d = Dap(plcrun)
    d.request("initialize", {"adapterID": "cost"})
    d.request("launch", {"program": path, "args": ["--cycles", "1"]})
    d.event("initialized")
    d.request("setBreakpoints", {"source": {"path": path}, "breakpoints": [{"line": 4}]})
    d.request("configurationDone", {})
    d.event("stopped")
    lines = []
    for _ in range(BODY + 2):
        d.request("next", {"threadId": 1})
        d.event("stopped")
        st = d.request("stackTrace", {"threadId": 1})
        lines.append(st["body"]["stackFrames"][0]["line"])
    d.request("disconnect", {})
    d.p.wait()
    print("lines stepped through from line 4:", lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plcrun", default="target/release/plcrun")
    ap.add_argument("-n", type=int, default=5)
    ap.add_argument("--cycles", type=int, default=2000)
    ap.add_argument("--check-count", action="store_true")
    a = ap.parse_args()
    text, never = program()
    folder = tempfile.mkdtemp(prefix="plcrun-debug-cost-")
    path = os.path.join(folder, "bench.st")
    with open(path, "w") as f:
        f.write(text)
    if a.check_count:
        check_count(a.plcrun, path)
        return
    runs = {"plain": [], "attached": [], "elsewhere": []}
    for _ in range(a.n):
        runs["plain"].append(plain(a.plcrun, path, a.cycles))
        runs["attached"].append(debugged(a.plcrun, path, a.cycles, None))
        runs["elsewhere"].append(debugged(a.plcrun, path, a.cycles, never))
    statements = a.cycles * 1000 * (BODY + 1)
    base = statistics.median(runs["plain"])
    print(f"{a.cycles} cycles, {statements} statement starts, {a.n} runs each (median seconds):")
    for k, v in runs.items():
        m = statistics.median(v)
        extra = "" if k == "plain" else f"  +{(m - base) / statements * 1e9:.1f} ns per statement"
        print(f"  {k:10} {m:8.3f} s  x{m / base:5.2f}{extra}")


if __name__ == "__main__":
    main()
