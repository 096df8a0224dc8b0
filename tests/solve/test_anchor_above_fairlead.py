"""Anchors above their fairleads (issue 20): a deep spar fairlead with anchors up a slope,
and a chain from a pile head down to a deeper fairlead. Once refused by the case builder;
every line block takes either sign of the height, checked here against independent ODE
integrations (``tests/reference_ode.py``)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference_ode import integrate_leg, integrate_to_slope

from moorsolve import load_case, solve


def spar(gradient=0.3, friction=0.5, force=(-1e5, 0.0, 0.0)):
    """A spar with fairleads 170 m down in 200 m of water on a steep slope: the up-slope
    anchor lies at z = -110 m, 60 m above its fairlead."""
    legs = []
    for k, heading in enumerate((0.0, 120.0, 240.0)):
        a = math.radians(heading)
        legs.append({"name": f"L{k + 1}", "anchor": [300 * math.cos(a), 300 * math.sin(a)],
                     "fairlead": [5 * math.cos(a), 5 * math.sin(a), -170.0],
                     "segments": [{"type": "chain", "length": 330.0}]})
    return load_case({
        "environment": {"depth": 200.0,
                        "seabed": {"gradient": [gradient, 0.0], "friction": friction}},
        "line_types": {"chain": {"weight_in_water": 1500.0, "ea": 5e8}},
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": list(force)}},
        "legs": legs})


@pytest.mark.parametrize("force", [(-1e5, 0.0, 0.0), (0.0, 0.0, 0.0), (5e4, 3e4, 1e5)])
def test_spar_with_an_anchor_up_the_slope(force):
    case = spar(force=force)
    assert case.legs[0].anchor[2] > case.legs[0].fairlead[2]
    result = solve(case)
    g = case.environment.seabed.gradient
    mu = case.environment.seabed.friction
    for leg in result.legs:
        X = math.dist(leg.anchor[:2], leg.fairlead[:2])
        e = np.subtract(leg.fairlead[:2], leg.anchor[:2]) / X
        t = g[0] * e[0] + g[1] * e[1]
        if leg.slack:
            # Straight down to the seabed under the fairlead (loose chain lies on the slope,
            # held by friction 0.5 > its slope): V is the weight of that hanging length.
            bed = case.environment.seabed_z(*leg.fairlead[:2])
            hang = leg.fairlead_vertical_N / 1500.0
            assert hang * (1 + leg.fairlead_vertical_N / 2 / 5e8) == pytest.approx(
                leg.fairlead[2] - bed, rel=1e-9)
            assert leg.anchor_tension_N == 0.0
            continue
        ref = integrate_to_slope(H=leg.horizontal_tension_N, V=leg.fairlead_vertical_N,
                                 L=330.0, w=1500.0, t=t, ea=5e8, mu=mu)
        assert ref["X"] == pytest.approx(X, abs=1e-7 * 330)
        assert ref["Z"] == pytest.approx(leg.fairlead[2] - leg.anchor[2], abs=1e-7 * 330)
        assert ref["TA"] == pytest.approx(leg.anchor_tension_N,
                                          abs=1e-7 * leg.fairlead_tension_N + 1e-6)
        assert ref["grounded"] == pytest.approx(leg.grounded_length_m, abs=1e-7 * 330)


def test_pile_head_anchor_above_a_deeper_fairlead():
    """A chain from a pile head 80 m above the seabed down to a fairlead 40 m lower."""
    case = load_case({
        "environment": {"depth": 100.0},
        "line_types": {"c": {"weight_in_water": 500.0, "ea": 1e8}},
        "legs": [{"name": "A", "anchor": [0, 0, -20.0], "fairlead": [80.0, 0, -60.0],
                  "segments": [{"type": "c", "length": 100.0}]}]})
    leg = solve(case).legs[0]
    ref = integrate_leg(H=leg.horizontal_tension_N, V=leg.fairlead_vertical_N, L=100.0,
                        w=500.0, ea=1e8, contact=False)
    assert ref["X"] == pytest.approx(80.0, abs=1e-8 * 100)
    assert ref["Z"] == pytest.approx(-40.0, abs=1e-8 * 100)
    assert ref["VA"] == pytest.approx(leg.anchor_vertical_N, rel=1e-8)
    assert leg.anchor_vertical_N < 0            # the chain pulls the pile head down


def test_slack_line_on_a_slope_friction_cannot_hold_is_refused():
    """Loose chain on a 0.13-0.3 slope with no friction would slide: outside the model, so
    refused with the reason (the audit), never reported."""
    from moorsolve import ConvergenceError
    with pytest.raises(ConvergenceError, match="would slide"):
        solve(spar(friction=0.0))
