#!/usr/bin/env python3
"""Summarises `scripts/fuzz.sh plateau` runs as the rows of the table in
docs/robustness.md ("Fuzzing", "Results").

    python3 scripts/fuzz_summary.py [TARGET...]      (default: every target with a log)

For each target it reads fuzz/logs/TARGET.log (libFuzzer's output: the
INITED line, the final `stat::` lines) and fuzz/logs/TARGET.curve (one
sample every 10 s after INITED: seconds, cov, ft, corpus, execs), counts
the files in fuzz/artifacts/TARGET/ (crashes, timeouts, out-of-memory),
and prints one Markdown row:

    target | time | total execs | execs/s | cov after seeds -> end | ft at end |
    corpus | last new cov | last quarter | plateau | artifacts

"last quarter" is what the edge count gained during the last quarter of
the run, in edges and as a share of the final count; "plateau" is the
rule `fuzz.sh plateau` stops on, judged here without its MIN: "no new
edge" when the last quarter added none, "< 0.5 %" when it added at most
0.5 % of the edges (the default FUZZ_PLATEAU_PERMILLE), else "no".
"""

import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "fuzz")


def read_curve(target):
    """(seconds, cov, ft, corpus, execs) samples, in order."""
    path = os.path.join(ROOT, "logs", target + ".curve")
    rows = []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if len(parts) == 5:
                rows.append(tuple(int(p) for p in parts))
    return rows


def read_log(target):
    """The edge count at INITED and the final `stat::` values."""
    path = os.path.join(ROOT, "logs", target + ".log")
    inited = None
    stats = {}
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("utf-8", "replace")
            m = re.match(r"#\d+\s+INITED\s+cov: (\d+)", line)
            if m:
                inited = int(m.group(1))
            m = re.match(r"stat::(\w+):\s+(\d+)", line)
            if m:
                stats[m.group(1)] = int(m.group(2))
    return inited, stats


def artifacts(target):
    path = os.path.join(ROOT, "artifacts", target)
    if not os.path.isdir(path):
        return 0
    return len([n for n in os.listdir(path) if not n.startswith(".")])


def number(n):
    """Thousands separated by a thin space, as the docs write them."""
    return f"{n:,}".replace(",", "\u202f")


def row(target):
    curve = read_curve(target)
    inited, stats = read_log(target)
    if not curve:
        return f"| `{target}` | no samples (INITED not reached) |"
    end_s, end_cov, end_ft, end_corpus, _ = curve[-1]
    execs = stats.get("number_of_executed_units", curve[-1][4])
    rate = stats.get("average_exec_per_sec", 0)
    start_cov = inited if inited is not None else curve[0][1]
    # When the edge count last changed (the first sample that shows the
    # final count).
    last_new = next(s for s, c, *_ in curve if c == end_cov)
    quarter_start = end_s - end_s // 4
    before = [c for s, c, *_ in curve if s <= quarter_start]
    base = before[-1] if before else start_cov
    gained = end_cov - base
    share = 100.0 * gained / end_cov if end_cov else 0.0
    if gained == 0:
        plateau = "no new edge"
    elif 1000 * gained <= 5 * end_cov:
        plateau = "≤ 0.5 %"
    else:
        plateau = "no"
    return (
        f"| `{target}` | {end_s} s | {number(execs)} | {number(rate)} | "
        f"{number(start_cov)} → {number(end_cov)} | {number(end_ft)} | "
        f"{number(end_corpus)} | at {last_new} s | +{gained} ({share:.2f} %) | "
        f"{plateau} | {artifacts(target)} |"
    )


def main():
    targets = sys.argv[1:]
    if not targets:
        logs = os.path.join(ROOT, "logs")
        targets = sorted(n[: -len(".curve")] for n in os.listdir(logs) if n.endswith(".curve"))
    print(
        "| target | time | total execs | execs/s | cov (after seeds → end) | ft at end "
        "| corpus | last new cov | last quarter | plateau | artifacts |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for t in targets:
        print(row(t))


if __name__ == "__main__":
    main()
