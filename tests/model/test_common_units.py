"""Units converted without pint's registry give pint's floats, and a case in them never
builds the registry."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from moorsolve.model import units
from moorsolve.model.common_units import COMMON_UNITS

from conftest import CASES

NUMBERS = np.concatenate([np.random.default_rng(0).uniform(-1e4, 1e4, 500),
                          np.round(np.random.default_rng(1).uniform(0, 10, 500), 3),
                          10.0 ** np.random.default_rng(2).uniform(-6, 9, 500),
                          np.arange(1.0, 300.0)])


@pytest.mark.parametrize("text", sorted(COMMON_UNITS))
def test_each_common_unit_converts_to_the_bit_as_pint_does(text):
    kind, factor = COMMON_UNITS[text]
    reg = units.registry()
    parsed = reg.parse_units(text)
    if kind == "angle":
        assert str(parsed) in units._ANGLE_UNITS
    else:
        assert parsed.dimensionality == units._dimensionality(kind)
    for x in NUMBERS:
        expected = reg.Quantity(float(x), parsed).to(units.KINDS[kind][0]).magnitude
        assert units.to_si(f"{float(x)!r} {text}", kind, "f") == expected


def test_a_common_unit_of_the_wrong_kind_is_still_refused():
    with pytest.raises(units.CaseError, match="f"):
        units.to_si("81 mm", "force", "f")


def test_loading_a_case_in_common_units_never_builds_the_registry():
    code = ("import sys, moorsolve; from moorsolve.model import units; "
            f"moorsolve.load_case({str(CASES / 'floating_dock.yaml')!r}); "
            "print(bool(units._REGISTRY), 'pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "False"]
