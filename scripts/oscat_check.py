#!/usr/bin/env python3
"""Measure how much of an OSCAT BASIC copy plcrun compiles, and run our
own checks of OSCAT functions against independently worked-out values.

    python3 scripts/oscat_check.py PATH [--json | --markdown] [options]

PATH is a copy of OSCAT BASIC in one of the forms it circulates in:

* the CoDeSys 2.3 export: one big Windows-1252 ``.TXT``/``.EXP`` file with
  all POUs, or a folder of per-POU ``.EXP`` files;
* the OpenPLC/matiec port: a PLCopen TC6 XML ``plc.xml``, or a folder
  searched recursively for ``plc.xml`` files (one per category).

The copy is only read; nothing of it is written into the repository (the
units are cut into a temporary directory that is removed at the end).

Definition (docs/compatibility.md says the same):

* The source is cut into units: one per FUNCTION, FUNCTION_BLOCK, PROGRAM,
  TYPE ... END_TYPE and VAR_GLOBAL list (XML: one per <pou>/<dataType>).
* A unit depends on every other unit whose name it uses (outside comments
  and strings, not counting its own variable names); the closure of that
  relation is what it needs to compile.
* Each unit is checked with ``plcrun check`` together with its closure,
  each unit in its own file, so every diagnostic names the unit it is in.
  - clean:     no error and no warning in the closure's units;
  - warnings:  no error; warnings in the unit itself (e.g. compatibility
               extensions W3xx); it compiles, so it counts as checking clean;
  - failing:   an error located in the unit's own text (the first one is
               reported with its code and message);
  - blocked:   no error in its own text, but a unit it depends on fails
               (named); it is not clean, and is counted separately.
* The figure is (clean + warnings) / (FUNCTIONs + FUNCTION_BLOCKs).
  TYPEs, PROGRAMs and global lists are reported but not in the figure.

Functional checks: every TEST_* PROGRAM/FUNCTION_BLOCK in tests/oscat/*.st
(our own test programs, written from the OSCAT manual's examples or from a
derivation written beside each expected value) is run with ``plcrun test``
together with the closure of the OSCAT units it uses.  A test named
``TEST_<POU>`` or ``TEST_<POU>_<anything>`` checks OSCAT's ``<POU>``.

Only the Python 3 standard library is used.  Without ``--plcrun`` the
script builds plcrun with cargo (``--release``) and uses that binary.
"""

from __future__ import annotations

import argparse
import codecs
import concurrent.futures
import contextlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

# Kinds that open a unit at top level, and the keyword that closes each.
UNIT_END = {
    "FUNCTION": "END_FUNCTION",
    "FUNCTION_BLOCK": "END_FUNCTION_BLOCK",
    "PROGRAM": "END_PROGRAM",
    "TYPE": "END_TYPE",
    "VAR_GLOBAL": "END_VAR",
    "CONFIGURATION": "END_CONFIGURATION",
    "FUNCTIONBLOCK": "END_FUNCTION_BLOCK",  # a spelling the OSCAT export uses 7 times
}
COUNTED_KINDS = ("FUNCTION", "FUNCTION_BLOCK")
XML_KIND = {"function": "FUNCTION", "functionBlock": "FUNCTION_BLOCK", "program": "PROGRAM"}


# --------------------------------------------------------------------------
# Lexing just enough of IEC 61131-3 text to cut units and find names
# --------------------------------------------------------------------------

IDENT_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def tokens(text: str, base: int = 0):
    """Yield (offset, token) for identifiers and single punctuation of
    `text`, skipping comments (nested `(* *)`, `/* */`, `//`), pragmas `{ }`
    and string literals; `:=` is one token."""
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "(" and text.startswith("(*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("(*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*)", i):
                    depth, i = depth - 1, i + 2
                else:
                    i += 1
        elif c == "/" and text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
        elif c == "/" and text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif c == "{":
            j = text.find("}", i)
            i = n if j < 0 else j + 1
        elif c in "'\"":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "$" else 1
            i = j + 1
        elif c.isalpha() or c == "_":
            m = IDENT_RE.match(text, i)
            yield base + i, m.group(0)
            i = m.end()
        elif c.isdigit():
            # numbers, typed literals (16#FF, T#1s, DWORD#1): skip the lot
            m = re.compile(r"[0-9A-Za-z_#.]+").match(text, i)
            i = m.end()
        elif c == ":" and text.startswith(":=", i):
            yield base + i, ":="
            i += 2
        elif c.isspace():
            i += 1
        else:
            yield base + i, c
            i += 1


@dataclass
class Unit:
    """One POU, type block or global list of the copy."""

    name: str
    kind: str
    origin: str  # file it came from (display)
    line: int  # line of its first line in that file
    data: bytes  # its text (ST: raw bytes of the copy; XML: a whole project file)
    refs: set = field(default_factory=set)  # upper-case names it uses
    declared: set = field(default_factory=set)  # upper-case names it declares
    suffix: str = ".st"
    header_lines: int = 0  # lines of `data` before the unit's own first line
    also_names: list = field(default_factory=list)  # further types of one TYPE block


def analyse_names(toks):
    """Names used, and variable names declared, by a unit's tokens."""
    used, declared, typed = set(), set(), set()
    in_var = False
    prev = None
    for idx, (_, t) in enumerate(toks):
        u = t.upper()
        if u.startswith("VAR") and IDENT_RE.fullmatch(t):
            in_var = True
        elif u == "END_VAR":
            in_var = False
        if IDENT_RE.fullmatch(t):
            nxt = toks[idx + 1][1] if idx + 1 < len(toks) else ""
            if prev is not None and (prev[1] == ":" or prev[1].upper() in ("OF", "TO")):
                typed.add(u)
            if in_var and nxt in (":", ",") and not (prev and prev[1] == "."):
                declared.add(u)
            if not (prev and prev[1] == "."):
                used.add(u)
        prev = (0, t)
    return (used - declared) | typed, declared


def cut_st(data: bytes, origin: str) -> list[Unit]:
    """Cut a CoDeSys export (one file, bytes) into its units."""
    text = data.decode("latin-1")  # 1 char per byte: offsets are byte offsets
    toks = list(tokens(text))
    units, i, prev_end = [], 0, 0
    while i < len(toks):
        off, t = toks[i]
        kind = t.upper()
        if kind not in UNIT_END:
            i += 1
            continue
        end_kw = UNIT_END[kind]
        kind = "FUNCTION_BLOCK" if kind == "FUNCTIONBLOCK" else kind
        j = i + 1
        while j < len(toks) and toks[j][1].upper() != end_kw:
            j += 1
        body = toks[i : j + 1]
        if kind == "VAR_GLOBAL":
            name = "VAR_GLOBAL@%d" % (text.count("\n", 0, off) + 1)
        else:
            name = toks[i + 1][1] if i + 1 < len(toks) else "?"
        end_off = toks[j][0] + len(toks[j][1]) if j < len(toks) else len(text)
        # a unit keeps the comments and `(* @... *)` lines before it
        start = prev_end
        unit = Unit(
            name=name,
            kind=kind,
            origin=origin,
            line=text.count("\n", 0, start) + 1,
            data=data[start:end_off] + b"\n",
        )
        unit.refs, unit.declared = analyse_names(body)
        if kind == "TYPE":
            unit.also_names = type_names(body)
        elif kind == "VAR_GLOBAL":
            unit.also_names = sorted(unit.declared)
        units.append(unit)
        prev_end = end_off
        i = j + 1
    return units


def type_names(toks) -> list[str]:
    """The names a TYPE ... END_TYPE block declares (top level `name :`)."""
    names, depth = [], 0
    for k in range(1, len(toks) - 1):
        t = toks[k][1].upper()
        if t in ("STRUCT", "(") :
            depth += 1
        elif t in ("END_STRUCT", ")"):
            depth -= 1
        elif depth == 0 and IDENT_RE.fullmatch(toks[k][1]) and toks[k + 1][1] == ":":
            names.append(t)
    return names


# --------------------------------------------------------------------------
# PLCopen XML (the OpenPLC/matiec port)
# --------------------------------------------------------------------------

POU_RE = re.compile(r"<pou\b[^>]*?\bname=\"([^\"]+)\"[^>]*?\bpouType=\"([A-Za-z]+)\"[\s\S]*?</pou>")
POU_RE2 = re.compile(r"<pou\b[^>]*?\bpouType=\"([A-Za-z]+)\"[^>]*?\bname=\"([^\"]+)\"[\s\S]*?</pou>")
DT_RE = re.compile(r"<dataType\b[^>]*?\bname=\"([^\"]+)\"[\s\S]*?</dataType>")
XML_NAME_ATTR = re.compile(r"\b(?:name|typeName)=\"([A-Za-z_][A-Za-z0-9_]*)\"")
XML_VAR_NAME = re.compile(r"<variable\b[^>]*\bname=\"([A-Za-z_][A-Za-z0-9_]*)\"")
XML_TEXT = re.compile(r"<!\[CDATA\[([\s\S]*?)\]\]>|<xhtml:p>([\s\S]*?)</xhtml:p>")
XML_DOC = re.compile(r"<documentation>[\s\S]*?</documentation>")


def xml_unescape(s: str) -> str:
    return s.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", '"').replace("&apos;", "'").replace("&amp;", "&")


def cut_xml(text: str, origin: str) -> list[Unit]:
    """Cut one plc.xml into units, each a complete project of its own."""
    types_at = text.find("<types>")
    if types_at < 0:
        return []
    head = text[:types_at]
    head_lines = head.count("\n") + 1  # "<types><dataTypes>" or "<pous>" opens a line
    found = []
    for m in DT_RE.finditer(text):
        found.append((m.start(), m.end(), m.group(1), "TYPE"))
    for m in POU_RE.finditer(text):
        found.append((m.start(), m.end(), m.group(1), XML_KIND.get(m.group(2), m.group(2))))
    for m in POU_RE2.finditer(text):
        if not any(s == m.start() for s, _, _, _ in found):
            found.append((m.start(), m.end(), m.group(2), XML_KIND.get(m.group(1), m.group(1))))
    units = []
    for start, end, name, kind in sorted(found):
        elem = text[start:end]
        if kind == "TYPE":
            wrapped = "<types>\n<dataTypes>" + elem + "</dataTypes><pous/></types>"
        else:
            wrapped = "<types>\n<dataTypes/><pous>" + elem + "</pous></types>"
        doc = head + wrapped + "<instances><configurations/></instances></project>\n"
        code = XML_DOC.sub("", elem)
        used = {a.upper() for a in XML_NAME_ATTR.findall(code)}
        declared = {a.upper() for a in XML_VAR_NAME.findall(code)}
        body_toks = []
        for cm in XML_TEXT.finditer(code):
            chunk = cm.group(1) if cm.group(1) is not None else xml_unescape(cm.group(2))
            body_toks.extend(tokens(chunk))
        body_used, _ = analyse_names(body_toks)
        types_used = {m.upper() for m in re.findall(r"<derived\s+name=\"([^\"]+)\"", code)}
        types_used |= {m.upper() for m in re.findall(r"\btypeName=\"([^\"]+)\"", code)}
        unit = Unit(
            name=name,
            kind=kind,
            origin=origin,
            line=text.count("\n", 0, start) + 1,
            data=doc.encode("utf-8"),
            suffix=".xml",
            header_lines=head_lines,
        )
        unit.refs = ((used | body_used) - declared) | types_used
        unit.declared = declared
        units.append(unit)
    return units


# --------------------------------------------------------------------------
# Loading a copy
# --------------------------------------------------------------------------


def load(path: Path) -> tuple[str, list[Unit], list[str]]:
    """Units of the copy at `path`, its form and notes about the loading."""
    notes = []
    if path.is_dir():
        xmls = sorted(path.rglob("plc.xml"))
        exps = sorted(p for p in path.rglob("*") if p.suffix.upper() in (".EXP", ".TXT", ".ST") and p.is_file())
        if xmls:
            files, form = xmls, "plcopen-xml"
        else:
            files, form = exps, "codesys-export"
    else:
        files = [path]
        head = path.read_bytes()[:200].lstrip(b"\xef\xbb\xbf \t\r\n")
        form = "plcopen-xml" if head.startswith(b"<?xml") or head.startswith(b"<project") else "codesys-export"
    units: list[Unit] = []
    for f in files:
        shown = str(f.relative_to(path)) if path.is_dir() else f.name
        if form == "plcopen-xml":
            units.extend(cut_xml(f.read_text(encoding="utf-8", errors="replace"), shown))
        else:
            units.extend(cut_st(f.read_bytes(), shown))
    # Each plc.xml of the port is a project of its own, and some POUs are in
    # several of them (not always the same text): every copy is measured,
    # within its own file, and a name counts once, by its best copy.
    names = {}
    for u in units:
        names.setdefault(u.name.upper(), []).append(u)
    dups = sum(len(v) - 1 for v in names.values() if len(v) > 1)
    kept = units
    if dups:
        notes.append(
            "%d further copies of POUs that appear in more than one file; each copy is checked in its own file, "
            "and a POU counts once, by its best copy" % dups
        )
    return form, kept, notes


class NameIndex:
    """Unit names, looked up first in the file a unit comes from, then in
    the whole copy (first definition wins)."""

    def __init__(self, units: list[Unit]):
        self.everywhere: dict[str, Unit] = {}
        self.per_file: dict[str, dict[str, Unit]] = {}
        for u in units:
            local = self.per_file.setdefault(u.origin, {})
            for n in [u.name.upper()] + list(u.also_names):
                self.everywhere.setdefault(n, u)
                local.setdefault(n, u)

    def get(self, name: str, origin: str) -> Unit | None:
        return self.per_file.get(origin, {}).get(name) or self.everywhere.get(name)

    def __contains__(self, name: str) -> bool:
        return name in self.everywhere

    def __getitem__(self, name: str) -> Unit:
        return self.everywhere[name]


def closure(unit: Unit, index: NameIndex) -> list[Unit]:
    """The units `unit` needs (transitively), without itself."""
    seen, todo, out = {id(unit)}, [unit], []
    names = {unit.name.upper()}
    while todo:
        u = todo.pop()
        for r in sorted(u.refs):
            if r in names:
                continue
            d = index.get(r, u.origin)
            if d is not None and id(d) not in seen:
                seen.add(id(d))
                names.add(d.name.upper())
                out.append(d)
                todo.append(d)
    return out


def name_index(units: list[Unit]) -> NameIndex:
    return NameIndex(units)


# --------------------------------------------------------------------------
# Running plcrun
# --------------------------------------------------------------------------

DIAG_RE = re.compile(r"^(error|warning)\[([A-Z]\d+)\]: (.*)$")
LOC_RE = re.compile(r"^\s*--> (.*):(\d+):(\d+)\s*$")


def parse_diagnostics(output: str):
    """(severity, code, message, file, line, col) of each diagnostic."""
    diags, lines = [], output.splitlines()
    for k, line in enumerate(lines):
        m = DIAG_RE.match(line)
        if not m:
            continue
        loc = LOC_RE.match(lines[k + 1]) if k + 1 < len(lines) else None
        if loc:
            diags.append((m.group(1), m.group(2), m.group(3), loc.group(1), int(loc.group(2)), int(loc.group(3))))
        else:
            diags.append((m.group(1), m.group(2), m.group(3), None, 0, 0))
    return diags


def cp1252_to_utf8(data: bytes) -> bytes:
    """Windows-1252 to UTF-8; the five bytes 1252 leaves undefined are read
    as Latin-1 (as CODESYS does)."""
    return data.decode("cp1252", errors="oscat-latin1").encode("utf-8")


def _latin1_fallback(err):
    return (err.object[err.start : err.end].decode("latin-1"), err.end)


codecs.register_error("oscat-latin1", _latin1_fallback)


class Workspace:
    """A temporary directory holding each unit in a file of its own."""

    def __init__(self, units: list[Unit], transcode: bool):
        self.dir = Path(tempfile.mkdtemp(prefix="oscat_check_"))
        self.files: dict[int, Path] = {}
        self.unit_of_file: dict[str, Unit] = {}
        for k, u in enumerate(units):
            safe = re.sub(r"[^A-Za-z0-9_]", "_", u.name)
            p = self.dir / ("%04d_%s%s" % (k, safe, u.suffix))
            data = cp1252_to_utf8(u.data) if transcode and u.suffix == ".st" else u.data
            p.write_bytes(data)
            self.files[id(u)] = p
            self.unit_of_file[str(p)] = u

    def remove(self):
        shutil.rmtree(self.dir, ignore_errors=True)


def run(cmd: list[str], timeout: float = 120.0) -> tuple[int, str]:
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    except subprocess.TimeoutExpired:
        return -1, "timeout after %.0f s" % timeout
    return p.returncode, p.stdout.decode("utf-8", errors="replace")


def check_unit(plcrun: str, ws: Workspace, unit: Unit, index: dict[str, Unit]) -> dict:
    deps = closure(unit, index)
    files = [str(ws.files[id(d)]) for d in deps] + [str(ws.files[id(unit)])]
    rc, out = run([plcrun, "check"] + files)
    diags = parse_diagnostics(out)
    own_err, own_warn, failing_deps = [], [], []
    for sev, code, msg, f, line, col in diags:
        owner = ws.unit_of_file.get(f) if f else unit
        if owner is None:
            owner = unit
        if owner is unit:
            at = "%s:%d" % (unit.origin, unit.line + max(line - 1 - unit.header_lines, 0)) if f else unit.origin
            (own_err if sev == "error" else own_warn).append({"code": code, "message": msg, "at": at})
        elif sev == "error" and owner.name not in failing_deps:
            failing_deps.append(owner.name)
    # `unknown type `SIGNAL`` in SIGNAL_4 only repeats that SIGNAL failed
    consequential = [e for e in own_err if any("`%s`" % d.upper() in e["message"].upper() for d in failing_deps)]
    if own_err and len(consequential) == len(own_err):
        own_err = []
    if rc < 0:
        own_err.append({"code": "TIMEOUT", "message": out, "at": unit.origin})
    if own_err:
        status = "failing"
    elif failing_deps:
        status = "blocked"
    elif rc != 0:
        status = "failing"
        own_err.append({"code": "EXIT%d" % rc, "message": out.strip()[:200] or "plcrun check failed", "at": unit.origin})
    elif own_warn:
        status = "warnings"
    else:
        status = "clean"
    return {
        "name": unit.name,
        "kind": unit.kind,
        "origin": "%s:%d" % (unit.origin, unit.line),
        "status": status,
        "deps": [d.name for d in deps],
        "failing_deps": failing_deps,
        "errors": own_err,
        "warnings": own_warn,
    }


def encoding_probe(plcrun: str, units: list[Unit]) -> tuple[bool, str]:
    """Does plcrun read the copy's non-UTF-8 bytes?  Checks the first unit
    holding such a byte, alone."""
    for u in units:
        if u.suffix != ".st":
            continue
        try:
            u.data.decode("utf-8")
            continue
        except UnicodeDecodeError:
            pass
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "probe.st"
            p.write_bytes(u.data)
            _, out = run([plcrun, "check", str(p)])
        for _, code, msg, *_ in parse_diagnostics(out):
            if code == "E011":
                return True, (
                    "plcrun cannot read the Windows-1252 bytes of this copy (E011: %s); the measurement "
                    "reads them transcoded to UTF-8 (the copy itself is untouched)" % msg
                )
        return False, "the copy's Windows-1252 bytes were given to plcrun as they are"
    return False, "the copy is plain ASCII/UTF-8"


RANK = {"clean": 0, "warnings": 1, "blocked": 2, "failing": 3}


def check_all(plcrun: str, units: list[Unit], jobs: int, transcode: bool) -> list[dict]:
    index = name_index(units)
    ws = Workspace(units, transcode)
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            results = list(pool.map(lambda u: check_unit(plcrun, ws, u, index), units))
    finally:
        ws.remove()
    # one row per name: its best copy
    best: dict[str, dict] = {}
    order = []
    for r in results:
        key = r["name"].upper() if r["kind"] != "PROGRAM" else "%s@%s" % (r["name"].upper(), r["origin"])
        r["copies"] = 1
        if key not in best:
            best[key] = r
            order.append(key)
        else:
            copies = best[key]["copies"] + 1
            if RANK[r["status"]] < RANK[best[key]["status"]]:
                best[key] = r
            best[key]["copies"] = copies
    return [best[k] for k in order]


# --------------------------------------------------------------------------
# Functional checks: tests/oscat/*.st
# --------------------------------------------------------------------------

RESULT_RE = re.compile(r"^(PASS|FAIL|ERROR)\s+(\S+)")


def subject_of(test_name: str, index: dict[str, Unit]) -> str:
    """`TEST_<POU>[_suffix]` -> the OSCAT POU it checks."""
    rest = test_name[5:]
    parts = rest.split("_")
    for k in range(len(parts), 0, -1):
        cand = "_".join(parts[:k]).upper()
        if cand in index:
            return index[cand].name
    return rest


def run_tests(plcrun: str, units: list[Unit], test_dir: Path, jobs: int, transcode: bool) -> list[dict]:
    index = name_index(units)
    tests = []
    for f in sorted(test_dir.glob("*.st")):
        for t in cut_st(f.read_bytes(), str(f.relative_to(REPO) if f.is_relative_to(REPO) else f)):
            if t.kind in ("PROGRAM", "FUNCTION_BLOCK") and t.name.upper().startswith("TEST_"):
                tests.append(t)
    ws = Workspace(units, transcode)
    tdir = Path(tempfile.mkdtemp(prefix="oscat_tests_"))

    def one(t: Unit) -> dict:
        p = tdir / (t.name + ".st")
        p.write_bytes(t.data)
        deps = closure(t, index)
        files = [str(ws.files[id(d)]) for d in deps] + [str(p)]
        rc, out = run([plcrun, "test"] + files)
        out = out.replace(str(tdir) + os.sep, "")  # temporary paths would make the report differ run to run
        subject = subject_of(t.name, index)
        outcome, detail = "ERROR", ""
        for line in out.splitlines():
            m = RESULT_RE.match(line)
            if m and m.group(2) == t.name:
                outcome = {"PASS": "pass", "FAIL": "fail", "ERROR": "error"}[m.group(1)]
        if outcome != "pass":
            diags = [d for d in parse_diagnostics(out) if d[0] == "error"]
            if diags and not any(RESULT_RE.match(l) for l in out.splitlines()):
                outcome = "does-not-compile"
                d = diags[0]
                owner = ws.unit_of_file.get(d[3]) if d[3] else None
                where = owner.name if owner else t.name
                detail = "%s in %s: %s [needs: %s]" % (d[1], where, d[2], cause_of({"code": d[1], "message": d[2]}))
            else:
                lines = [l.strip() for l in out.splitlines() if l.strip() and not l.startswith(("PASS", "1 test"))]
                detail = " / ".join(lines[:3])[:300]
        return {"test": t.name, "subject": subject, "file": t.origin, "outcome": outcome, "detail": detail}

    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            return list(pool.map(one, tests))
    finally:
        ws.remove()
        shutil.rmtree(tdir, ignore_errors=True)


# --------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------


# (code, regular expression on the message) -> the feature it needs; the
# first that matches names the cause.  Everything else is "CODE message".
CAUSES = [
    ("E110", r"`POINTER`|`REFERENCE`|`REF_TO`", "POINTER TO / REFERENCE TO / ADR (pointers)"),
    ("E110", r"`[rf]_edge`", "R_EDGE/F_EDGE input qualifier"),
    ("E001", r"invalid character `\^`", "POINTER TO / REFERENCE TO / ADR (pointers)"),
    ("E011", r"", "Windows-1252 source bytes"),
    ("E205", r"constant `.*` needs a constant initial value", "VAR_INPUT CONSTANT (CoDeSys constant inputs)"),
    ("E205", r"expected a constant integer expression", "a VAR CONSTANT used as an array bound before its declaration"),
    ("E302", r"operator .* cannot be applied to (BYTE|WORD|DWORD|LWORD)", "arithmetic on BYTE/WORD/DWORD (CODESYS: unsigned)"),
    ("E306", r"cannot combine (BYTE|WORD|DWORD|LWORD) and|and (BYTE|WORD|DWORD|LWORD)$", "arithmetic on BYTE/WORD/DWORD (CODESYS: unsigned)"),
    ("E302", r"(DATE|DT|TOD|TIME)_TO_\w+: no such conversion|\w+_TO_(DATE|DT|TOD|TIME): no such conversion", "conversions between DATE/DT/TOD and DWORD/UDINT/DINT"),
    ("E302", r"no such conversion", "missing conversion function"),
    ("E401", r"input of the function|input of the function block|is an input", "writing a VAR_INPUT in the body"),
    ("E201", r"has no field|is internal to \w+: only inputs and outputs", "reading an FB instance's internal variable"),
    ("E202", r"is the name of a standard function", "a user POU named like a standard function"),
    ("E201", r"(?i)unknown function `(MEMSET|MEMCPY|MEMMOVE)`", "CODESYS memory functions (MEMSET, MEMCPY)"),
    ("E402", r"not a variable", "FUNCTION returning a STRUCT / inst(...).Q used as a value"),
    ("E101", r"found `(ON|STEP|on|step|Step|On)`", "a keyword used as a name (ON, STEP)"),
    ("E101", r"found `FUNCTIONBLOCK`", "`FUNCTIONBLOCK` spelling of FUNCTION_BLOCK"),
    ("E101", r"expected `;`, found `,`", "array initial value without brackets (1,2,3)"),
    ("E101", r"/\*|\*/", "/* */ comments"),
    ("E302", r"bit access needs a bit string", "`.n` bit access on INT/DINT"),
    ("E302", r"contain strings", "arrays/structs holding STRINGs copied"),
    ("E301", r"SHR: N must|SHL: N must|ROL: N must|ROR: N must", "shift count typed from an integer expression"),
    ("E301", r"_TO_\w+: expected \w+, found", "generic result typed from context (TRUNC, BCD_TO_INT)"),
    ("E301", r"assignment: expected INT, found BYTE|expected (INT|DINT|UINT|UDINT|WORD|DWORD), found (BYTE|USINT|SINT|WORD)", "implicit widening of a smaller integer/bit string"),
    ("E201", r"unknown function `TIME`", "TIME() as the PLC clock (CoDeSys)"),
    ("E201", r"unknown function `(ADR|SIZEOF|__ISVALIDREF|ISVALIDREF)`", "POINTER TO / REFERENCE TO / ADR (pointers)"),
    ("E201", r"(?i)unknown function `(MULTIME|DIVTIME)`", "MULTIME/DIVTIME"),
    ("E201", r"unknown function `(\w+_(INT|DINT|REAL|LREAL|BOOL|WORD|DWORD|BYTE|UINT|UDINT|TIME|STRING))`", "typed standard-function names (ADD_INT ...)"),
    ("E203", r"unknown type", "unknown type"),
]


def cause_of(err: dict, known_only: bool = False) -> str | None:
    for code, pattern, label in CAUSES:
        if err["code"] == code and re.search(pattern, err["message"]):
            return label
    if known_only:
        return None
    return "%s %s" % (err["code"], re.sub(r"`[^`]*`", "`…`", err["message"]))


def causes_of(errors: list[dict]) -> list[str]:
    """The recognised features behind a unit's errors; an unrecognised
    error counts only when it comes first (later ones are often echoes)."""
    found = {c for c in (cause_of(e, True) for e in errors) if c}
    if errors and cause_of(errors[0], True) is None:
        found.add(cause_of(errors[0]))
    return sorted(found)


def attach_causes(results: list[dict]) -> None:
    """Give each failing or blocked unit the features it waits for: those
    of its own errors, plus those of every failing unit it depends on."""
    by_name = {r["name"]: r for r in results}
    for r in results:
        r["causes"] = causes_of(r["errors"])
    for r in results:
        waits = set(r["causes"])
        for d in r["deps"]:
            dr = by_name.get(d)
            if dr is not None and dr["status"] == "failing":
                waits |= set(dr["causes"])
        r["waits_for"] = sorted(waits) if r["status"] in ("failing", "blocked") else []


def classify(results: list[dict]) -> list[dict]:
    """Per feature: how many counted POUs need it, and how many compile
    once it alone is added (as far as the first errors tell)."""
    counted = [r for r in results if r["kind"] in COUNTED_KINDS and r["waits_for"]]
    features = sorted({c for r in counted for c in r["waits_for"]})
    rows = []
    for f in features:
        needing = [r for r in counted if f in r["waits_for"]]
        alone = [r for r in needing if r["waits_for"] == [f]]
        first = [r for r in counted if r["status"] == "failing" and r["causes"] and cause_of(r["errors"][0]) == f]
        rows.append({"feature": f, "first_error": len(first), "needing": len(needing), "unblocked_alone": len(alone)})
    rows.sort(key=lambda x: (-x["unblocked_alone"], -x["needing"], x["feature"]))
    return rows


def summarise(results: list[dict]) -> dict:
    counted = [r for r in results if r["kind"] in COUNTED_KINDS]
    by = {s: sum(1 for r in counted if r["status"] == s) for s in ("clean", "warnings", "failing", "blocked")}
    ok = by["clean"] + by["warnings"]
    other = [r for r in results if r["kind"] not in COUNTED_KINDS]
    return {
        "pous": len(counted),
        "compiling": ok,
        "percent": round(100.0 * ok / len(counted), 1) if counted else 0.0,
        **by,
        "other_units": len(other),
        "other_compiling": sum(1 for r in other if r["status"] in ("clean", "warnings")),
    }


def first_error(r: dict) -> str:
    if r["status"] == "blocked":
        return "blocked by " + ", ".join(r["failing_deps"][:4]) + (" ..." if len(r["failing_deps"]) > 4 else "")
    if r["errors"]:
        e = r["errors"][0]
        return "%s %s (%s)" % (e["code"], e["message"], e["at"])
    if r["warnings"]:
        return ", ".join(sorted({w["code"] for w in r["warnings"]}))
    return ""


def test_summary(tests: list[dict]) -> dict:
    subjects = {t["subject"] for t in tests}
    passed = {t["subject"] for t in tests} - {t["subject"] for t in tests if t["outcome"] != "pass"}
    return {
        "tests": len(tests),
        "passed": sum(1 for t in tests if t["outcome"] == "pass"),
        "functions": len(subjects),
        "functions_passing": len(passed),
    }


def print_causes(causes, md: bool):
    if md:
        print("| feature plcrun lacks | POUs whose first error it is | POUs that need it | POUs it alone unblocks |")
        print("|---|---|---|---|")
    for c in causes:
        if md:
            print("| %s | %d | %d | %d |" % (md_escape(c["feature"]), c["first_error"], c["needing"], c["unblocked_alone"]))
        else:
            print("%4d first  %4d need  %4d alone  %s" % (c["first_error"], c["needing"], c["unblocked_alone"], c["feature"]))
    print()


def print_text(form, path, notes, results, summary, causes, tests, elapsed):
    print("OSCAT copy: %s (%s)" % (path, form))
    for n in notes:
        print("note: " + n)
    for r in results:
        print("%-9s %-15s %-28s %s" % (r["status"], r["kind"], r["name"], first_error(r)))
    print(
        "\n%d of %d FUNCTIONs and FUNCTION_BLOCKs compile (%.1f %%): %d clean, %d with warnings only, "
        "%d failing, %d blocked by a failing dependency; other units (types, programs, globals): %d of %d compile"
        % (summary["compiling"], summary["pous"], summary["percent"], summary["clean"], summary["warnings"],
           summary["failing"], summary["blocked"], summary["other_compiling"], summary["other_units"])
    )
    print("\nwhat the failing and blocked FUNCTIONs/FUNCTION_BLOCKs wait for:")
    print_causes(causes, md=False)
    if tests is not None:
        for t in tests:
            print("%-16s %-34s %-20s %s" % (t["outcome"], t["test"], t["subject"], t["detail"]))
        ts = test_summary(tests)
        print("\nfunctional checks: %d of %d tests pass; %d of %d OSCAT functions/blocks pass all their checks"
              % (ts["passed"], ts["tests"], ts["functions_passing"], ts["functions"]))
    print("(measured in %.1f s)" % elapsed)


def md_escape(s: str) -> str:
    return s.replace("|", "\\|").replace("\n", " ")


def print_markdown(form, path, notes, results, summary, causes, tests):
    print("<!-- generated by scripts/oscat_check.py --markdown; do not edit by hand -->")
    print("### %s (%s)\n" % (Path(path).name, form))
    for n in notes:
        print("- " + n)
    print(
        "- **%d of %d** FUNCTIONs and FUNCTION_BLOCKs compile (**%.1f %%**): %d clean, %d with warnings only; "
        "%d failing, %d blocked only by a failing dependency."
        % (summary["compiling"], summary["pous"], summary["percent"], summary["clean"], summary["warnings"],
           summary["failing"], summary["blocked"])
    )
    print("- Other units (TYPEs, PROGRAMs, global lists): %d of %d compile.\n" % (summary["other_compiling"], summary["other_units"]))
    if causes:
        print("What the failing and blocked FUNCTIONs and FUNCTION_BLOCKs wait for (a POU waits for the causes of "
              "its own errors and of the failing POUs it uses; \"alone\": it waits for nothing else):\n")
        print_causes(causes, md=True)
    bad = [r for r in results if r["status"] in ("failing", "blocked")]
    if bad:
        print("| POU | kind | status | first error / blocking dependencies |")
        print("|---|---|---|---|")
        for r in sorted(bad, key=lambda r: (r["status"], r["name"].upper())):
            print("| %s | %s | %s | %s |" % (r["name"], r["kind"], r["status"], md_escape(first_error(r))))
        print()
    if tests is not None:
        ts = test_summary(tests)
        print("Functional checks (tests/oscat): **%d of %d** tests pass; **%d of %d** OSCAT functions and blocks pass all their checks.\n"
              % (ts["passed"], ts["tests"], ts["functions_passing"], ts["functions"]))
        print("| test | OSCAT POU | outcome | detail |")
        print("|---|---|---|---|")
        for t in tests:
            print("| %s | %s | %s | %s |" % (t["test"], t["subject"], t["outcome"], md_escape(t["detail"])))
        print()


def update_doc(doc: Path, form: str, section: str) -> int:
    """Replace the text between `<!-- oscat_check:FORM begin -->` and
    `<!-- oscat_check:FORM end -->` in `doc`."""
    begin, end = "<!-- oscat_check:%s begin -->" % form, "<!-- oscat_check:%s end -->" % form
    text = doc.read_text(encoding="utf-8")
    i, j = text.find(begin), text.find(end)
    if i < 0 or j < i:
        print("oscat_check: %s has no %s ... %s markers" % (doc, begin, end), file=sys.stderr)
        return 2
    doc.write_text(text[: i + len(begin)] + "\n" + section + text[j:], encoding="utf-8")
    return 0


def find_plcrun(explicit: str | None) -> str:
    if explicit:
        if not os.access(explicit, os.X_OK):
            sys.exit("oscat_check: %s is not an executable plcrun" % explicit)
        return explicit
    try:
        rc = subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "plcrun"], cwd=REPO).returncode
    except FileNotFoundError:
        rc = -1
    if rc != 0:
        sys.exit("oscat_check: `cargo build --release` failed; pass --plcrun BINARY")
    return str(REPO / "target" / "release" / "plcrun")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("path", type=Path, help="OSCAT BASIC copy: export file, folder of .EXP files, plc.xml or folder of them")
    out = ap.add_mutually_exclusive_group()
    out.add_argument("--json", action="store_true", help="print the results as JSON")
    out.add_argument("--markdown", action="store_true", help="print the section docs/compatibility.md holds")
    ap.add_argument("--update-doc", type=Path, metavar="FILE",
                    help="replace this form's generated section of FILE (docs/compatibility.md) with --markdown's output")
    ap.add_argument("--plcrun", help="the plcrun binary (default: build target/release/plcrun with cargo)")
    ap.add_argument("--tests", type=Path, default=REPO / "tests" / "oscat", help="folder of our TEST_* programs (default tests/oscat)")
    ap.add_argument("--no-tests", action="store_true", help="only measure compilation")
    ap.add_argument("--only", help="measure only the units whose name matches this regular expression")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2, help="plcrun processes at once")
    args = ap.parse_args(argv)

    if not args.path.exists():
        print("oscat_check: %s does not exist" % args.path, file=sys.stderr)
        return 2
    plcrun = find_plcrun(args.plcrun)
    started = time.monotonic()
    form, units, notes = load(args.path)
    if not units:
        print("oscat_check: no POU found in %s" % args.path, file=sys.stderr)
        return 2
    transcode, enc_note = encoding_probe(plcrun, units)
    notes.append(enc_note)
    measured = [u for u in units if not args.only or re.search(args.only, u.name, re.I)]
    index = name_index(units)
    ws_units = units if not args.only else list({id(x): x for u in measured for x in [u] + closure(u, index)}.values())
    results = check_all(plcrun, ws_units, args.jobs, transcode)
    attach_causes(results)
    results = [r for r in results if not args.only or re.search(args.only, r["name"], re.I)]
    summary = summarise(results)
    causes = classify(results)
    tests = None
    if not args.no_tests and args.tests.is_dir():
        tests = run_tests(plcrun, units, args.tests, args.jobs, transcode)
    elapsed = time.monotonic() - started
    if args.json:
        doc = {"path": str(args.path), "form": form, "notes": notes, "summary": summary, "causes": causes, "pous": results}
        if tests is not None:
            doc["tests"] = tests
            doc["test_summary"] = test_summary(tests)
        print(json.dumps(doc, indent=1))
    elif args.markdown or args.update_doc:
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            print_markdown(form, args.path, notes, results, summary, causes, tests)
        if args.update_doc:
            return update_doc(args.update_doc, form, buf.getvalue())
        print(buf.getvalue(), end="")
    else:
        print_text(form, args.path, notes, results, summary, causes, tests, elapsed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
