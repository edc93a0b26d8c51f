"""Shared fixtures of the Python package's tests."""

from pathlib import Path

import pytest

pytest_plugins = ["pytester"]

#: The repository's root (the seed programs are under programs/).
REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def repo() -> Path:
    """The repository's root directory."""
    return REPO
