"""A plane sloped seabed under one-segment legs (issue 4).

The sloped leg block is checked against an independent numerical integration of the
thread equations (Merkin 1980, seed 004, sections 2.1 and 2.3): along the slope the tension
changes by ``w (sin(theta) + mu cos(theta))`` per metre; from the touchdown the line rises
with ``dT_v/ds = w`` from ``T_v = H tan(theta)``.
"""

import copy
import math

import numpy as np
import pytest
import yaml
from scipy.integrate import solve_ivp

from moorsolve import CaseError, load_case, solve
from moorsolve.physics.catenary import (LEG_OUTPUTS, LegKind, evaluate_leg)
from moorsolve.physics.sloped import sloped_leg_function
from conftest import ROOT

CASES = ROOT / "cases"


def one_leg(gradient, friction=0.0, ea=5e8, X=400.0):
    return {"environment": {"depth": 100.0,
                            "seabed": {"friction": friction, "gradient": list(gradient)}},
            "line_types": {"chain": {"weight_in_water": 1000.0, "ea": ea}},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [X, 0.0, -5.0],
                      "segments": [{"type": "chain", "length": 460}]}]}


@pytest.mark.parametrize("case", [
    (30.0, 50.0, 5e4, 4e4), (100.0, 30.0, 5e4, 9e4), (60.0, 30.0, -1e3, 2e4),
    (100.0, 30.0, 5e4, 1.6e5)])
def test_flat_slope_is_the_leg_block(case):
    X, Z, u, V = case
    kind = LegKind(elastic=True, contact=True, friction=True)
    flat = evaluate_leg(kind, X, Z, u, V, 150.0, 1000.0, 1e-8, 0.5)
    sloped = [float(v) for v in sloped_leg_function(True, True)(X, Z, u, V, 150.0, 1000.0,
                                                                1e-8, 0.5, 0.0)]
    for name, value in zip(LEG_OUTPUTS, sloped):
        assert value == pytest.approx(flat[name], rel=1e-12, abs=1e-9)


def _integrate(H, LB, L, w, ea, mu, t):
    """Anchor to fairlead: straight on the slope, then the suspended thread (scipy)."""
    sec = math.sqrt(1 + t * t)
    cos_t, sin_t = 1 / sec, t / sec
    k = w * (sin_t + mu * cos_t)
    fine = np.linspace(0.0, LB, 20001)
    T = np.maximum(H * sec - k * (LB - fine), 0.0)
    along = LB + np.trapezoid(T, fine) / ea
    x0, z0 = along * cos_t, along * sin_t

    def rhs(s, y):
        Tt = math.hypot(H, y[2])
        return [H / Tt * (1 + Tt / ea), y[2] / Tt * (1 + Tt / ea), w]
    sol = solve_ivp(rhs, (0.0, L - LB), [x0, z0, H * t], rtol=1e-12, atol=1e-10)
    return sol.y[:, -1], T[0]


@pytest.mark.parametrize("gradient, friction", [((0.02, 0.0), 0.0), ((-0.03, 0.0), 0.0),
                                                ((0.02, 0.01), 0.4), ((-0.04, 0.0), 0.3)])
def test_sloped_leg_matches_integrated_thread(gradient, friction):
    res = solve(load_case(one_leg(gradient, friction)))
    leg = res.legs[0]
    assert "sloped_seabed" in res.effects
    t = gradient[0]  # the leg runs along +x
    (x, z, V), TA = _integrate(leg.horizontal_tension_N, leg.grounded_length_m, 460.0,
                               1000.0, 5e8, friction, t)
    assert x == pytest.approx(400.0, abs=1e-6)
    assert z == pytest.approx(95.0, abs=1e-6)
    assert V == pytest.approx(leg.fairlead_vertical_N, rel=1e-9)
    assert leg.anchor_tension_N == pytest.approx(TA, rel=1e-9, abs=1e-6)
    # The touchdown point lies on the slope.
    tx, ty, tz = leg.touchdown_point
    assert tz == pytest.approx(-100.0 + gradient[0] * tx + gradient[1] * ty, abs=1e-9)
    assert np.all(leg.profile["z_m"] >= -100.0 + gradient[0] * leg.profile["x_m"] - 1e-9)


def test_seabed_rising_toward_the_fairlead_slackens_the_leg():
    tensions = [solve(load_case(one_leg((g, 0.0)))).legs[0].fairlead_tension_N
                for g in (-0.02, 0.0, 0.02)]
    assert tensions[0] > tensions[1] > tensions[2]


def test_slope_across_the_leg_changes_nothing():
    flat = solve(load_case(one_leg((0.0, 0.0)))).legs[0]
    across = solve(load_case(one_leg((0.0, 0.05)))).legs[0]
    assert across.fairlead_tension_N == pytest.approx(flat.fairlead_tension_N, rel=1e-12)


def test_anchor_depth_follows_the_plane():
    case = load_case(one_leg((0.01, -0.02)))
    assert case.legs[0].anchor[2] == pytest.approx(-100.0)
    data = one_leg((0.01, -0.02))
    data["legs"][0]["anchor"] = [200.0, 100.0]
    assert load_case(data).legs[0].anchor[2] == pytest.approx(-100.0 + 2.0 - 2.0)


@pytest.mark.parametrize("edit, field, words", [
    (lambda d: d["environment"]["seabed"].update(gradient=[0.9, 0.9]),
     "environment.seabed.gradient", "45 deg"),
    (lambda d: d["environment"]["seabed"].update(gradient=[0.1]),
     "environment.seabed.gradient", "[dz/dx, dz/dy]"),
    (lambda d: d["legs"][0].update(anchor=[0.0, 0.0, -120.0]), "legs[0].anchor[2]",
     "below the seabed"),
    (lambda d: d["legs"][0].update(segments=[{"type": "chain", "length": 200},
                                             {"type": "chain", "length": 260}]),
     "legs[0].segments", "flat seabed"),
])
def test_bad_slopes_are_case_errors(edit, field, words):
    data = one_leg((0.02, 0.0))
    edit(data)
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == field and words in str(err.value)


def test_shipped_sloped_case_solves():
    data = yaml.safe_load((CASES / "floating_dock_sloped.yaml").read_text())
    res = solve(load_case(copy.deepcopy(data)))
    assert res.converged and "sloped_seabed" in res.effects
