"""Shared fixtures and settings for the whole suite.

Paths are resolved from this file, never from the working directory, so the suite runs
from anywhere. Plots are drawn headless.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
# The suite compares compiled kernels with the reference: each first solve waits for its
# compile (the default compiles in the background; tests/solve/test_compile.py checks that).
os.environ.setdefault("MOORSOLVE_COMPILE", "wait")
# ... at -O0: a quarter of -O2's compile time (most of a cold suite's), and the same IEEE
# arithmetic (the libraries are cached apart from the -O2 ones benchmarks and users get).
os.environ.setdefault("MOORSOLVE_COMPILE_OPT", "-O0")

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


def _hypothesis_profiles() -> None:
    """The default run draws the same examples every time (CI and a developer's machine see
    the same cases; what a random hunt found is kept as explicit tests); the ``thorough``
    profile (MOORSOLVE_HYPOTHESIS_PROFILE=thorough) draws new ones each run."""
    from hypothesis import settings

    settings.register_profile("moorsolve-default", derandomize=True, print_blob=True)
    settings.register_profile("moorsolve-thorough", derandomize=False, print_blob=True)
    thorough = os.environ.get("MOORSOLVE_HYPOTHESIS_PROFILE") == "thorough"
    settings.load_profile("moorsolve-thorough" if thorough else "moorsolve-default")


_hypothesis_profiles()
