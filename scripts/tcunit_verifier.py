#!/usr/bin/env python3
"""Runs TcUnit's own verifier under `plcrun test` and checks plcrun's
results against the verifier's expectations (docs/compatibility.md,
"TcUnit's verifier").

    python3 scripts/tcunit_verifier.py [--plcrun BIN] [--verbose] TCUNIT_REPO

TCUNIT_REPO is a copy of the public tcunit/TcUnit repository, fetched
outside this repository. Its `TcUnit-Verifier` folder holds a TwinCAT
project of test suites written to pass or fail in chosen ways
(`TcUnit-Verifier_TwinCAT`) and a .NET program that reads TcUnit's
messages after a run in TwinCAT and checks them (`TcUnit-Verifier_DotNet`,
one class per suite). This script reads the expectations those classes
state, runs `plcrun test --keep-going --junit` on the TwinCAT project,
and prints, per suite, how many expectations plcrun meets:

- "fails with": `AssertContainsMessage` of a failure message: the test
  must fail with that assertion message, and expected and actual values
  equal to those TcUnit prints (compared as values: `0xAB` is `16#AB`,
  `T#694m13s244ms` is `T#11h34m13s244ms`, a REAL by its digits); with
  `AssertMessageCount(message, n)`, exactly n such failures;
- "does not fail with": `AssertDoesNotContainMessage` (or a count of 0):
  the test has no failure with that message and those values.

An expectation about a suite that plcrun left out (a file that does not
compile) counts as not met. The other checks of the verifier (message
of several messages, the test-run summary lines, timings, TcUnit's own
log texts) are about TcUnit's ADS log, which plcrun does not write, and
are not counted.

BIN defaults to target/release/plcrun (build it with
`cargo build --release`).
"""

import collections
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

VERIFIER = "TcUnit-Verifier"
PROJECT = (
    "TcUnit-Verifier_TwinCAT/TcUnit-Verifier_TwinCAT/TcUnitVerifier/"
    "TcUnitVerifier.plcproj"
)
DOTNET = "TcUnit-Verifier_DotNet/TcUnit-Verifier"

CREATE = re.compile(
    r'(\w+)\s*=\s*CreateFailedTestMessage(NoAssertionMessage)?\(\s*'
    r'"([^"]*)"\s*,\s*"([^"]*)"\s*,\s*"([^"]*)"\s*(?:,\s*"([^"]*)"\s*)?\)'
)
CHECK = re.compile(
    r'\b(AssertContainsMessage|AssertDoesNotContainMessage|AssertMessageCount)\(\s*(\w+)\s*,\s*(\d+)?'
)


def expectations(dotnet):
    """(suite instance, test, times, expected, actual, message) per check:
    `times` failures of the test with those values and message (0: none;
    AssertContainsMessage is at least one, written -1)."""
    out = []
    for name in sorted(os.listdir(dotnet)):
        if not (name.startswith("FB_") and name.endswith(".cs")):
            continue
        instance = name[3:-3]
        text = open(os.path.join(dotnet, name), encoding="utf-8-sig").read()
        # Messages are made and checked in order, a variable often reused.
        events = [(m.start(), "make", m) for m in CREATE.finditer(text)]
        events += [(m.start(), "check", m) for m in CHECK.finditer(text)]
        made = {}
        for _, kind, m in sorted(events, key=lambda e: e[0]):
            if kind == "make":
                made[m.group(1)] = (m.group(3), m.group(4), m.group(5), m.group(6))
                continue
            if m.group(2) not in made:
                continue
            test, exp, act, msg = made[m.group(2)]
            if m.group(1) == "AssertContainsMessage":
                times = -1
            elif m.group(1) == "AssertDoesNotContainMessage":
                times = 0
            else:
                times = int(m.group(3) or 0)
            out.append((instance, test, times, exp, act, msg))
    return out


FAILURE = re.compile(
    r'^.*?: cycle \d+: (?:element ([^:]*): )?expected (.*?), actual (.*?)(?:: (.*))?$', re.S
)


def results(plcrun, project):
    """{(instance, test): (outcome, [(expected, actual, message)])} and
    the suite instances left out."""
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "junit.xml")
        subprocess.run(
            [plcrun, "test", "--keep-going", "--junit", report, project],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False,
        )
        root = ET.parse(report).getroot()
    tests, left_out = {}, set()
    for case in root.iter("testcase"):
        # A test: name `Test`, class `PRG_TEST.Instance` (as TcUnit-Runner
        # names them); a suite left out: name `PRG_TEST.Instance`, class
        # its file.
        name, classname = case.get("name", ""), case.get("classname", "")
        if "/" in classname or "\\" in classname or "." not in classname:
            left_out.add(name.split(".")[-1])
            continue
        instance, test = classname.split(".")[-1], name
        failures = []
        for f in case.iter("failure"):
            # One failed assertion per line of the failure's text.
            for line in (f.text or "").splitlines():
                m = FAILURE.match(line)
                if m:
                    # (element, expected, actual, message)
                    failures.append((m.group(1) or "", m.group(2), m.group(3), m.group(4) or ""))
        if case.find("skipped") is not None:
            outcome = "skipped"
        else:
            outcome = "failed" if failures else "passed"
        tests[(instance, test)] = (outcome, failures)
    return tests, left_out


DURATION = re.compile(r'(\d+(?:\.\d+)?)(d|h|ms|m|s|us|ns)', re.I)
UNIT_NS = {"d": 86400e9, "h": 3600e9, "m": 60e9, "s": 1e9, "ms": 1e6, "us": 1e3, "ns": 1.0}


def normal(value):
    """A value as TcUnit or plcrun prints it, reduced to one form."""
    v = value.strip()
    if len(v) >= 2 and v[0] == v[-1] and v[0] in "'\"":
        v = v[1:-1]
    u = v.upper()
    if u.startswith("0X"):
        return ("int", int(u[2:], 16))
    if re.fullmatch(r'16#[0-9A-F_]+', u):
        return ("int", int(u[3:].replace("_", ""), 16))
    if re.fullmatch(r'[+-]?\d+', v):
        return ("int", int(v))
    m = re.fullmatch(r'(?:L?TIME|L?T)#(-?)(.*)', u)
    if m:
        body = m.group(2).replace("_", "").lower()
        parts = DURATION.findall(body)
        if parts and "".join(n + unit for n, unit in parts) == body:
            ns = sum(float(n) * UNIT_NS[unit] for n, unit in parts)
            return ("duration", -ns if m.group(1) else ns)
    try:
        return ("real", float(v))
    except ValueError:
        return ("text", u)


def same(tcunit, ours):
    if "NOT POSSIBLE TO PRINT" in tcunit.upper() or "TYPE CLASS" in tcunit.upper():
        return True  # TcUnit prints no value there
    a, b = normal(tcunit), normal(ours)
    if a[0] == "real" or b[0] == "real":
        try:
            x, y = float(a[1]), float(b[1])
        except (TypeError, ValueError):
            return False
        return abs(x - y) <= 1e-6 * max(1.0, abs(x))
    return a == b


# `SIZE = 6`, or for several dimensions `SIZE = [-4..-2,-1..0] (3x2)`.
SIZE = re.compile(r'SIZE = (?:\[[^\]]*\] \()?([0-9x]+)\)?$')
ELEMENT = re.compile(r'ARRAY(\[[^\]]*\]) = (.*)$')
# TcUnit adds this to an array assertion's message when the sizes differ.
SIZE_NOTE = ", size of arrays not matching."


def meets(times, exp, act, msg, failures):
    def value_matches(tcunit, element, ours, own_index):
        size = SIZE.match(tcunit)
        if size:
            return ours.strip("'") == f"{size.group(1)} elements"
        at = ELEMENT.match(tcunit)
        if at:
            # plcrun names the element by the expected array's index;
            # TcUnit names each array's own (they differ when the bounds do).
            index_ok = not own_index or element.replace(" ", "") == at.group(1).replace(" ", "")
            return index_ok and same(at.group(2), ours)
        return same(tcunit, ours)

    def matches(f):
        element, e, a, m = f
        want = msg
        if want is not None and want.endswith(SIZE_NOTE):
            want = want[: -len(SIZE_NOTE)]
        # The verifier looks for its text inside TcUnit's line, which ends
        # with the message: its message may be the start of ours.
        message_ok = want is None or m.strip().upper().startswith(want.strip().upper())
        return (
            message_ok
            and value_matches(exp, element, e, True)
            and value_matches(act, element, a, False)
        )

    found = sum(1 for f in failures if matches(f))
    return found >= 1 if times < 0 else found == times


def main(argv):
    plcrun = "target/release/plcrun"
    verbose = False
    args = []
    it = iter(argv)
    for a in it:
        if a == "--plcrun":
            plcrun = next(it)
        elif a == "--verbose":
            verbose = True
        else:
            args.append(a)
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    base = os.path.join(args[0], VERIFIER)
    expected = expectations(os.path.join(base, DOTNET))
    tests, left_out = results(plcrun, os.path.join(base, PROJECT))
    per_suite = collections.OrderedDict()
    for instance, test, times, exp, act, msg in expected:
        row = per_suite.setdefault(instance, [0, 0, 0, 0, instance in left_out])
        # TcUnit names a disabled test without its `DISABLED_`, as plcrun.
        plain = test[len("DISABLED_"):] if test.upper().startswith("DISABLED_") else test
        outcome, failures = tests.get((instance, plain), ("missing", []))
        held = outcome != "missing" and meets(times, exp, act, msg, failures)
        fails = times != 0
        row[0 if fails else 2] += 1
        if held:
            row[1 if fails else 3] += 1
        elif verbose:
            print(f"not met: {instance}.{test} {times} EXP {exp} ACT {act} MSG {msg}; "
                  f"plcrun: {outcome} {failures}", file=sys.stderr)
    print("| suite | fails with (met / stated) | does not fail with (met / stated) | left out |")
    print("|---|---|---|---|")
    total = [0, 0, 0, 0]
    for instance, (c, cm, a, am, out) in per_suite.items():
        print(f"| {instance} | {cm} / {c} | {am} / {a} | {'yes' if out else ''} |")
        for k, v in enumerate((c, cm, a, am)):
            total[k] += v
    print(f"| **all** | **{total[1]} / {total[0]}** | **{total[3]} / {total[2]}** | |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
