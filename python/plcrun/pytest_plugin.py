"""pytest plugin of plcrun (registered by the package's ``pytest11`` entry
point; ``pytest -p plcrun.pytest_plugin`` loads it explicitly).

It gives two things:

* a ``plc`` fixture compiled from the test's marker::

      @pytest.mark.plc("programs/chariot.sfc", cycle_time="10ms")
      def test_leaves_station_a(plc):
          plc["FcA"] = True
          plc["Dcy"] = True
          plc.until("AV.X", timeout="1s")   # virtual time
          assert plc["KMAV"]

  The marker's arguments are the sources (paths, or one dict
  ``{name: text}``); its keywords are those of ``plcrun.Plc.compile``.
  Relative paths are looked up next to the test file first, then from
  pytest's root directory.

* collection of unit tests written in IEC: every ``*_test.st`` or
  ``test_*.st`` file (the ini option ``plcrun_test_files`` changes the
  patterns) becomes a collector whose items are its ``TEST_`` POUs (and
  TcUnit tests), run by the library as ``plcrun test`` runs them. The code
  under test is named in the file by a comment
  ``(* plcrun: sources = ../../programs/comparator.st *)`` (paths relative
  to the file) and by the ini option ``plcrun_sources`` (paths relative to
  the root directory, for every file). A file's tests run once, when it is
  collected; each item then reports its own case.
"""

from __future__ import annotations

import fnmatch
import re
from pathlib import Path
from typing import Any, Iterator, List, Sequence

import pytest

import plcrun

_DEFAULT_PATTERNS = ["*_test.st", "test_*.st"]
# `plcrun: sources = a.st b.st` inside a comment, up to the comment's end.
_SOURCES_DIRECTIVE = re.compile(r"\bplcrun:\s*sources\s*=\s*([^*]*?)\s*\*\)")


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addini(
        "plcrun_test_files",
        type="args",
        default=_DEFAULT_PATTERNS,
        help="glob patterns of IEC unit-test files collected by plcrun (default: *_test.st test_*.st)",
    )
    parser.addini(
        "plcrun_sources",
        type="args",
        default=[],
        help="sources compiled with every IEC unit-test file (paths relative to the root directory)",
    )


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers",
        "plc(*sources, **compile_options): sources of the `plc` fixture "
        "(paths or a dict {name: text}) and plcrun.Plc.compile's keywords",
    )


def _resolve(path: str, near: Path, root: Path) -> str:
    """``path`` as given if absolute, else next to ``near`` if it exists
    there, else from ``root``."""
    p = Path(path)
    if p.is_absolute():
        return str(p)
    for base in (near, root):
        candidate = base / p
        if candidate.exists():
            return str(candidate)
    return str(root / p)


@pytest.fixture
def plc(request: pytest.FixtureRequest) -> plcrun.Plc:
    """A ``plcrun.Plc`` compiled from the test's ``@pytest.mark.plc(...)``
    marker, at cycle 0 of its virtual clock."""
    marker = request.node.get_closest_marker("plc")
    if marker is None or not marker.args:
        pytest.fail(
            "the plc fixture needs a marker naming the sources: "
            '@pytest.mark.plc("programs/chariot.sfc", cycle_time="10ms")',
            pytrace=False,
        )
    if len(marker.args) == 1 and isinstance(marker.args[0], dict):
        sources: Any = marker.args[0]
    else:
        near = Path(str(request.node.path)).parent
        root = Path(str(request.config.rootpath))
        sources = [_resolve(str(a), near, root) for a in marker.args]
    return plcrun.Plc.compile(sources, **marker.kwargs)


def pytest_collect_file(file_path: Path, parent: pytest.Collector) -> pytest.Collector | None:
    patterns: Sequence[str] = parent.config.getini("plcrun_test_files")
    if any(fnmatch.fnmatch(file_path.name, p) for p in patterns):
        return StTestFile.from_parent(parent, path=file_path)
    return None


class StTestFailed(Exception):
    """An IEC unit test failed or stopped on a fault."""


class StTestFile(pytest.File):
    """A file of IEC unit tests: its ``TEST_`` POUs, run by plcrun."""

    def _sources(self) -> List[str]:
        root = Path(str(self.config.rootpath))
        here = Path(str(self.path)).parent
        found = [str(root / p) for p in self.config.getini("plcrun_sources")]
        text = Path(str(self.path)).read_text(encoding="utf-8", errors="replace")
        for m in _SOURCES_DIRECTIVE.finditer(text):
            for name in re.split(r"[\s,]+", m.group(1).strip()):
                if name:
                    found.append(str((here / name).resolve()))
        return found

    def collect(self) -> Iterator[pytest.Item]:
        files = self._sources() + [str(self.path)]
        try:
            cases = plcrun.run_st_tests(files)
        except plcrun.CompileError as e:
            raise self.CollectError(f"plcrun could not compile {self.path.name}:\n{e}") from None
        for case in cases:
            yield StTestItem.from_parent(self, name=case.name, case=case)


class StTestItem(pytest.Item):
    """One IEC unit test; its outcome comes from the library's run."""

    def __init__(self, *, case: plcrun.StTest, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.case = case

    def runtest(self) -> None:
        for line in self.case.output:
            print(line)
        if self.case.outcome != "passed":
            raise StTestFailed(self.case.report())

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> Any:
        if isinstance(excinfo.value, StTestFailed):
            return f"{self.case.name} {self.case.outcome} after {self.case.cycles} cycles:\n{excinfo.value}"
        return super().repr_failure(excinfo)

    def reportinfo(self) -> tuple[Path, int | None, str]:
        return Path(str(self.path)), None, f"{self.case.name} ({self.case.cycles} cycles)"
