"""The real designs the speed benchmarks run (issue 16): the OC4-DeepCwind semi and the
IEA-15 MW VolturnUS-S moorings, written from their published definitions
(cases/oc4_semi.yaml, cases/volturnus_s.yaml).

The line weights are checked against the definitions' own numbers (mass per length in air
less the displaced water of the volume-equivalent diameter), the layouts against the
three-fold symmetry the definitions give them, and the equilibria against MoorPy where the
``bench`` extra is installed.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import moorsolve
from moorsolve.model import BodyLoads

from conftest import CASES
from solve.test_network import _compare_with_moorpy

DESIGNS = {
    # name: (mass per length in air [kg/m], volume-equivalent diameter [m], fairlead radius,
    #        anchor radius [m]) as the definitions give them
    "oc4_semi": (113.35, 0.0766, 40.868, 837.6),
    "volturnus_s": (685.0, 0.333, 58.0, 837.6),
}


@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_line_weight_and_layout_follow_the_definition(name):
    mass, diameter, r_fair, r_anchor = DESIGNS[name]
    case = moorsolve.load_case(CASES / f"{name}.yaml")
    env = case.environment
    w = (mass - env.water_density * math.pi * diameter**2 / 4) * env.gravity
    for line in case.lines:
        assert line.line_type.weight_in_water == pytest.approx(w, abs=1e-3)
        assert math.hypot(*line.a.position[:2]) == pytest.approx(r_anchor, abs=1e-3)
        assert math.hypot(*line.b.position[:2]) == pytest.approx(r_fair, abs=1e-3)
        assert line.b.position[2] == -14.0 and line.a.position[2] == -env.depth
    headings = sorted(math.degrees(math.atan2(line.a.position[1], line.a.position[0])) % 360
                      for line in case.lines)
    assert np.diff(headings) == pytest.approx([120.0, 120.0], abs=1e-3)


@pytest.mark.parametrize("name", sorted(DESIGNS))
@pytest.mark.parametrize("heading", [0.0, 75.0, 180.0])
def test_design_under_a_load_agrees_with_moorpy_and_both_solvers(name, heading):
    case = moorsolve.load_case(CASES / f"{name}.yaml")
    f = case.body.loads.force[0]
    a = math.radians(heading)
    loaded = dataclasses.replace(case, bodies=(dataclasses.replace(
        case.body, loads=BodyLoads(force=(f * math.cos(a), f * math.sin(a), 2e6))),))
    result = _compare_with_moorpy(loaded)
    fast = moorsolve.solve(loaded, solver="newton", tol=1e-12)
    assert fast.solver == "newton"
    for key in ("x_m", "y_m", "yaw_deg"):
        assert fast.body[key] == pytest.approx(result.body[key], abs=1e-8)
    # Pushed toward `heading`, the body moves that way.
    assert result.body["x_m"] * math.cos(a) + result.body["y_m"] * math.sin(a) > 1.0


@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_symmetric_layout_gives_a_symmetric_answer(name):
    """Pushed along the x axis (a symmetry axis of both layouts), no sway and no yaw."""
    case = moorsolve.load_case(CASES / f"{name}.yaml")
    result = moorsolve.solve(case)
    assert abs(result.body["y_m"]) < 1e-9 and abs(result.body["yaw_deg"]) < 1e-9
    tensions = sorted(leg.fairlead_tension_N for leg in result.legs)
    assert tensions[0] == pytest.approx(tensions[1], rel=1e-9) or \
        tensions[1] == pytest.approx(tensions[2], rel=1e-9)
