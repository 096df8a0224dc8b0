"""The audit's per-line checks run over all lines at once (``moorsolve.audit.lines``).

Every line's profile is laid end to end in one array, so the checks must keep the lines
apart: a defect in one line is found in that line only, whichever line it is (the first,
a middle one, the last, the only one), and a step from one line's last point to the next
line's first is no step at all. The scenes reach what the shipped cases do not: a line
floating on the surface, lumped and analytic lines in one scene, a weightless line beside
chains, multi-segment lines with joints.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from moorsolve import load_case, solve
from moorsolve.audit import audit_findings
from conftest import ROOT

CASES = ROOT / "cases"


def _corrupt(result, index, key, change):
    legs = list(result.legs)
    profile = {k: np.array(v, float) if isinstance(v, np.ndarray) else v
               for k, v in legs[index].profile.items()}
    profile[key] = change(profile[key].copy())
    legs[index] = dataclasses.replace(legs[index], profile=profile)
    return dataclasses.replace(result, legs=legs)


def _solved(name):
    case = load_case(CASES / name)
    return case, solve(case, solver="newton")


def _lift_middle(z):
    z[len(z) // 2] += 5.0
    return z


def _first_point_off(x):
    x[0] += 2.0
    return x


def _last_point_off(x):
    x[-1] -= 2.0
    return x


@pytest.mark.parametrize("name", ["chain_polyester_clump.yaml", "dock_quay.yaml",
                                  "buoy_vida_current.yaml", "ship_97m.yaml",
                                  "floating_dock_sloped.yaml"])
@pytest.mark.parametrize("change", [_lift_middle, _first_point_off, _last_point_off])
def test_a_defect_is_found_in_its_own_line_only(name, change):
    case, result = _solved(name)
    assert audit_findings(result, case) == []
    key = "z_m" if change is _lift_middle else "x_m"
    for index in sorted({0, len(result.legs) // 2, len(result.legs) - 1}):
        found = audit_findings(_corrupt(result, index, key, change), case)
        named = {f.split(":")[0] for f in found if f.startswith("leg ")}
        assert named == {f"leg {result.legs[index].name}"}, found


def test_the_lines_of_a_scene_are_audited_apart():
    """Two lines whose profiles would join with a jump (one ends where the other starts
    far away) pass: the step between them is not a step of either line."""
    case, result = _solved("floating_dock.yaml")
    ends = [(leg.profile["x_m"][-1], leg.profile["x_m"][0]) for leg in result.legs]
    assert any(abs(a - b) > 10.0 for (a, _), (_, b) in zip(ends, ends[1:]))
    assert audit_findings(result, case) == []


def _floating_scene():
    return load_case({
        "environment": {"depth": 40.0},
        "line_types": {"chain": {"weight_in_water": 800.0, "ea": 5e8},
                       "float": {"weight_in_water": -60.0, "ea": 1e8}},
        "legs": [
            {"name": "chain", "anchor": [-150.0, 0.0], "fairlead": [0.0, 0.0, 0.0],
             "segments": [{"type": "chain", "length": 170.0}]},
            {"name": "floater", "anchor": [0.0, 100.0, 0.0], "fairlead": [0.0, 0.0, 0.0],
             "segments": [{"type": "float", "length": 120.0}]},
        ]})


def test_a_line_floating_on_the_surface_beside_a_chain():
    case = _floating_scene()
    result = solve(case, solver="newton")
    assert result.legs[1].floating_length_m > 0
    assert audit_findings(result, case) == []
    # The floating run lifted out of the water is found, and only in that line.
    found = audit_findings(_corrupt(result, 1, "z_m", lambda z: z + 2.0), case)
    assert found and all(f.startswith("leg floater:") for f in found)


def test_an_end_tension_off_by_a_little_is_found_in_any_line():
    case, result = _solved("chain_polyester_clump.yaml")
    for index, leg in enumerate(result.legs):
        legs = list(result.legs)
        legs[index] = dataclasses.replace(leg, anchor_tension_N=leg.anchor_tension_N * 1.001
                                          + 1.0)
        found = audit_findings(dataclasses.replace(result, legs=legs), case)
        assert any(f.startswith(f"leg {leg.name}:") and "anchor tension" in f
                   for f in found), found
