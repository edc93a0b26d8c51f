#!/usr/bin/env python3
"""Start jitter of plcrun's 1 ms task against cyclictest, alternated.

For each round and each policy (default, then SCHED_FIFO at --priority),
runs cyclictest and then plcrun on benches/realtime/jitter.st for the same
number of 1 ms cycles, and prints mean / p99 / max of both and the ratios
plcrun / cyclictest. cyclictest's p99 is read from its histogram (1 us
buckets); plcrun's comes from `--stats` (to within 1/16 of its value).

Needs rt-tests (`apt-get install rt-tests`) and, for SCHED_FIFO and
memory locking, root. Usage:

    python3 scripts/jitter_vs_cyclictest.py [--plcrun BIN] [--rounds 3]
        [--cycles 10000] [--priority 50] [--cpu K]
"""

import argparse
import os
import statistics
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROGRAM = os.path.join(ROOT, "benches", "realtime", "jitter.st")


def cyclictest(cycles, priority, cpu):
    """Runs cyclictest; returns (mean, p99, max) in microseconds."""
    cmd = ["cyclictest", "-m", "-i", "1000", "-l", str(cycles), "-q", "-h", "100000"]
    if priority:
        cmd += ["-p", str(priority)]
    if cpu is not None:
        cmd += ["-a", str(cpu)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    counts = {}
    mean = maximum = overflows = None
    for line in out.splitlines():
        if line.startswith("# Avg Latencies:"):
            mean = float(line.split(":")[1])
        elif line.startswith("# Max Latencies:"):
            maximum = float(line.split(":")[1])
        elif line.startswith("# Histogram Overflows:"):
            overflows = int(line.split(":")[1])
        elif line and not line.startswith("#"):
            fields = line.split()
            if len(fields) >= 2 and fields[0].isdigit():
                counts[int(fields[0])] = int(fields[1])
    if mean is None or maximum is None:
        sys.exit("cyclictest printed no summary:\n" + out)
    total = sum(counts.values()) + (overflows or 0)
    wanted = total * 0.99
    seen = 0
    p99 = maximum
    for latency in sorted(counts):
        seen += counts[latency]
        if seen >= wanted:
            p99 = float(latency)
            break
    return mean, p99, maximum


def plcrun(binary, cycles, priority, cpu):
    """Runs plcrun --realtime --stats; returns the 1 ms task's (mean, p99, max, overruns)."""
    cmd = [binary, PROGRAM, "--realtime", "--cycles", str(cycles), "--stats",
           "--output", "/dev/null"]
    if priority:
        cmd += ["--rt-priority", str(priority)]
    if cpu is not None:
        cmd += ["--cpu", str(cpu)]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"plcrun failed ({run.returncode}):\n{run.stderr}")
    text = run.stdout + run.stderr
    header = None
    for line in text.splitlines():
        fields = line.split()
        if fields[:2] == ["task", "interval"]:
            header = fields
        elif header and fields and fields[0] == "ms1":
            row = dict(zip(header, fields))
            return (float(row["jit_mean"]), float(row["jit_p99"]),
                    float(row["jit_max"]), int(row["overruns"]))
    sys.exit("plcrun printed no statistics for task ms1:\n" + text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plcrun", default=os.path.join(ROOT, "target", "release", "plcrun"))
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--cycles", type=int, default=10000)
    parser.add_argument("--priority", type=int, default=50)
    parser.add_argument("--cpu", type=int)
    args = parser.parse_args()
    if shutil.which("cyclictest") is None:
        sys.exit("cyclictest not found: apt-get install rt-tests")
    if not os.path.exists(args.plcrun):
        sys.exit(f"{args.plcrun} not found: cargo build --release")

    rows = {0: [], args.priority: []}
    print("| policy | round | cyclictest mean / p99 / max | plcrun mean / p99 / max "
          "| overruns | mean ratio | p99 ratio |")
    print("|---|---|---|---|---:|---:|---:|")
    for round_no in range(1, args.rounds + 1):
        for priority in (0, args.priority):
            policy = f"SCHED_FIFO {priority}" if priority else "default"
            c_mean, c_p99, c_max = cyclictest(args.cycles, priority, args.cpu)
            p_mean, p_p99, p_max, overruns = plcrun(args.plcrun, args.cycles, priority, args.cpu)
            rows[priority].append((c_mean, c_p99, c_max, p_mean, p_p99, p_max, overruns))
            print(f"| {policy} | {round_no} | {c_mean:.0f} / {c_p99:.0f} / {c_max:.0f} "
                  f"| {p_mean:.1f} / {p_p99:.1f} / {p_max:.1f} | {overruns} "
                  f"| {p_mean / c_mean:.2f} | {p_p99 / c_p99:.2f} |", flush=True)
    # One round is at the mercy of a few host stalls: the medians of the
    # rounds are what the two are compared by.
    for priority, runs in rows.items():
        policy = f"SCHED_FIFO {priority}" if priority else "default"
        c_mean, c_p99, c_max, p_mean, p_p99, p_max, overruns = (
            statistics.median(column) for column in zip(*runs))
        print(f"| {policy} | median | {c_mean:.0f} / {c_p99:.0f} / {c_max:.0f} "
              f"| {p_mean:.1f} / {p_p99:.1f} / {p_max:.1f} | {overruns:.0f} "
              f"| {p_mean / c_mean:.2f} | {p_p99 / c_p99:.2f} |")


if __name__ == "__main__":
    main()
