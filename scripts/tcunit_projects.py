#!/usr/bin/env python3
"""Runs `plcrun test` on TwinCAT projects with TcUnit suites and prints
the table of docs/compatibility.md ("TwinCAT projects and TcUnit").

    python3 scripts/tcunit_projects.py [--plcrun BIN] [--keep-going]
        [--library-path DIR]... PROJECT...

Each PROJECT is a folder holding one .plcproj, or a .plcproj file
(docs/twincat.md). The projects are public repositories fetched outside
this repository (docs/compatibility.md names them and their commits).

For each project it runs `plcrun check PROJECT` and `plcrun test PROJECT`
(timing both), and prints one Markdown row:

    project | compiles | tests | passed | failed | errored | assertions | check s | test s

"compiles" is `ok` or the number of errors `plcrun test` reports before
running anything (the sources checked with TcUnit's functions declared),
with the three most frequent codes. With --keep-going, `plcrun test
--keep-going` runs what compiles, and "compiles" gives the number of
files it left out (their suites count as errored tests). "tests" counts the TcUnit tests (and `TEST_`
tests) reported; "assertions" the assertion calls they ran, each counted
once per test (the figure `plcrun test` prints per test). When the sources
do not compile, the test columns are empty.

With --library-path DIR (repeatable), both commands get it: the libraries
a project references that are TwinCAT projects under DIR are loaded with
it (docs/twincat.md, "Library projects"); a row counts the tests of the
project's own files only, not those of the libraries loaded with it.

BIN defaults to target/release/plcrun (build it with
`cargo build --release`).
"""

import collections
import os
import re
import subprocess
import sys
import time

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
# A test's name may hold spaces (`TEST('Lookups for Ge')`).
CASE = re.compile(r"^(PASS |FAIL |ERROR) (.+) \(([^()]*), (\d+) cycles?(?:, (\d+) assertions?)?\)$")
CODE = re.compile(r"^error\[(\w+)\]")
COUNT = re.compile(r"^(\d+) errors?, ")


def run(args):
    start = time.monotonic()
    proc = subprocess.run(args, capture_output=True, text=True, errors="replace")
    return proc, time.monotonic() - start


LEFT_OUT = re.compile(r"^note: --keep-going left out (\d+) file")


def compile_column(stdout, stderr):
    left = next((m.group(1) for line in stderr.splitlines() if (m := LEFT_OUT.match(line))), None)
    if left:
        # The list under the note names a global as `FILE, global `x``.
        globals_out = sum(1 for line in stderr.splitlines() if line.startswith("  ") and ", global `" in line)
        files = int(left) - globals_out
        if globals_out:
            return f"{files} files and {globals_out} globals left out"
        return f"{files} files left out"
    if any(CASE.match(line) for line in stdout.splitlines()):
        return "ok"
    usage = next((line for line in stderr.splitlines() if line.startswith("error: ")), None)
    if usage:
        return usage.removeprefix("error: ")
    codes = collections.Counter(
        m.group(1) for line in stderr.splitlines() if (m := CODE.match(line))
    )
    total = next((int(m.group(1)) for line in stderr.splitlines() if (m := COUNT.match(line))), sum(codes.values()))
    top = ", ".join(f"{c}×{n}" for c, n in codes.most_common(3))
    return f"{total} errors ({top})" if top else f"{total} errors"


def measure(plcrun, project, keep_going, libraries):
    paths = [arg for lib in libraries for arg in ("--library-path", lib)]
    _, check_s = run([plcrun, "check", project] + paths)
    test, test_s = run([plcrun, "test", project] + paths + (["--keep-going"] if keep_going else []))
    own = os.path.dirname(project) if project.endswith(".plcproj") else project
    own = os.path.normpath(own)
    verdicts = collections.Counter()
    assertions = 0
    for line in test.stdout.splitlines():
        m = CASE.match(line)
        if m and (not libraries or os.path.normpath(m.group(3)).startswith(own)):
            verdicts[m.group(1).strip()] += 1
            assertions += int(m.group(5) or 0)
    tests = sum(verdicts.values())
    name = os.path.basename(os.path.normpath(project))
    row = [name.removesuffix(".plcproj"), compile_column(test.stdout, test.stderr)]
    if tests:
        row += [str(tests), str(verdicts["PASS"]), str(verdicts["FAIL"]), str(verdicts["ERROR"]), str(assertions)]
    else:
        row += ["", "", "", "", ""]
    row += [f"{check_s:.2f}", f"{test_s:.2f}"]
    return row


def main(argv):
    plcrun = os.path.join(ROOT, "target", "release", "plcrun")
    if len(argv) >= 2 and argv[0] == "--plcrun":
        plcrun, argv = argv[1], argv[2:]
    keep_going = bool(argv) and argv[0] == "--keep-going"
    if keep_going:
        argv = argv[1:]
    libraries = []
    while len(argv) >= 2 and argv[0] == "--library-path":
        libraries.append(argv[1])
        argv = argv[2:]
    if not argv:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    if not os.access(plcrun, os.X_OK):
        print(f"{plcrun} is not there: run `cargo build --release` first", file=sys.stderr)
        return 2
    print("| project | compiles | tests | passed | failed | errored | assertions | check s | test s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for project in argv:
        print("| " + " | ".join(measure(plcrun, project, keep_going, libraries)) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
