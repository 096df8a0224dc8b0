"""A tide (``environment.water_level``) is refused where a line meets the free surface,
whose model sits at the datum: a buoyant segment, a float, an end in air weighed by
``weight_in_air``. Lines that stay under water (the dock's chains, with or without a weight
in air given) take the tide."""

from __future__ import annotations

import pytest
import yaml
from conftest import CASES

import moorsolve
from moorsolve.errors import CaseError


def _dock(level, fairlead_z=0.0, **line_type):
    data = yaml.safe_load((CASES / "floating_dock.yaml").read_text(encoding="utf-8"))
    data["environment"]["water_level"] = level
    data["line_types"]["chain81"].update(line_type)
    data["legs"][0]["fairlead"][2] = fairlead_z
    return data


@pytest.mark.parametrize("line_type", [{}, {"weight_in_air": "0.15 t/m"}])
def test_chains_under_water_take_the_tide(line_type):
    assert moorsolve.load_case(_dock(3.0, **line_type)).environment.water_level == 3.0


@pytest.mark.parametrize("fairlead_z, line_type, what", [
    (2.0, {"weight_in_air": "0.15 t/m"}, "an end in air"),
    (0.0, {"weight_in_water": -200.0}, "a buoyant segment"),
])
def test_a_line_meeting_the_surface_refuses_a_tide(fairlead_z, line_type, what):
    with pytest.raises(CaseError, match="environment.water_level") as info:
        moorsolve.load_case(_dock(3.0, fairlead_z, **line_type))
    assert what in str(info.value) and "'L1'" in str(info.value)
    moorsolve.load_case(_dock(0.0, fairlead_z, **line_type))   # at the datum it is modelled


def test_an_end_in_air_without_a_weight_in_air_takes_the_tide():
    moorsolve.load_case(_dock(3.0, 2.0))


def test_the_edit_path_refuses_it_too():
    case = moorsolve.load_case(_dock(0.0, 2.0, weight_in_air="0.15 t/m"))
    with pytest.raises(CaseError, match="environment.water_level"):
        case.with_values({"environment.water_level": 2.0})
