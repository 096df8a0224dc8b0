"""Shared fixtures and settings for the whole suite.

Paths are resolved from this file, never from the working directory, so the suite runs
from anywhere. Plots are drawn headless.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

TESTS = Path(__file__).resolve().parent
ROOT = TESTS.parent
CASES = ROOT / "cases"
DATA = TESTS / "data"


@pytest.fixture(scope="session")
def cases_dir() -> Path:
    """The shipped case files (``cases/``)."""
    return CASES


@pytest.fixture(scope="session")
def data_dir() -> Path:
    """Test data files (``tests/data/``)."""
    return DATA
