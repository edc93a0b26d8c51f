"""The examples of docs/python.md and README.md, run as tests: every
```python block is run from the repository's root; a block whose first
line is a comment naming a `test_*.py` file is run by pytest (through
`pytester`) instead."""

import re
import shutil

import pytest

from conftest import REPO

DOCS = [REPO / "docs" / "python.md", REPO / "README.md"]
BLOCK = re.compile(r"^```python\n(.*?)^```", re.DOTALL | re.MULTILINE)
PYTEST_FILE = re.compile(r"^# (test_\w+\.py)\n")


def _blocks():
    for doc in DOCS:
        text = doc.read_text(encoding="utf-8")
        for m in BLOCK.finditer(text):
            line = text[: m.start()].count("\n") + 1
            yield pytest.param(m.group(1), id=f"{doc.name}:{line}")


def test_the_guide_has_examples():
    assert len([b for b in _blocks() if "python.md" in b.id]) >= 7
    assert len([b for b in _blocks() if "README" in b.id]) >= 1


@pytest.mark.parametrize("code", list(_blocks()))
def test_example(code, monkeypatch, pytester):
    named = PYTEST_FILE.match(code)
    if named is None:
        monkeypatch.chdir(REPO)
        exec(compile(code, "docs example", "exec"), {"__name__": "docs_example"})
        return
    # A pytest example: run it where programs/ is at the root directory.
    shutil.copytree(REPO / "programs", pytester.path / "programs")
    pytester.makepyfile(**{named.group(1)[:-3]: code})
    result = pytester.runpytest("-q")
    outcomes = result.parseoutcomes()
    assert outcomes.get("passed", 0) >= 1 and not outcomes.get("failed") and not outcomes.get("errors"), result.stdout.str()
