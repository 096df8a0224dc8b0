"""Weightless lines (hawsers) that go slack and taut freely (issue 15).

A hawser is a line whose type weighs nothing in water: straight and stretched by ``T L/EA``
when taut, carrying nothing when its unstretched length exceeds the chord. A hawser slack at
rest is the usual state at a berth; a load must draw it taut, and removing the load must
let it go slack again.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import moorsolve
from moorsolve.physics.catenary import (LegKind, evaluate_leg, weightless_line_function)

EA = 2.0e7          # [N] a synthetic hawser
BOLLARD_X = -30.0   # [m] bollards on the quay, the body's fairleads at x = 0
SPREAD = 5.0        # [m] the two hawsers at y = +-5, horizontal at z = 2


def hawser_case(force_x: float, length: float = 31.0, free=("surge", "sway", "yaw")) -> dict:
    """A body held only by two parallel horizontal hawsers to bollards 30 m away."""
    return {
        "name": "body on two hawsers",
        "environment": {"depth": 20.0},
        "line_types": {"hawser": {"weight_in_water": 0, "ea": EA, "mbl": 1.0e6}},
        "bodies": [{"name": "b", "free": list(free), "loads": {"force": [force_x, 0, 0]}}],
        "points": [{"name": "P1", "position": [BOLLARD_X, SPREAD, 2.0]},
                   {"name": "P2", "position": [BOLLARD_X, -SPREAD, 2.0]}],
        "lines": [
            {"name": "H1", "from": "P1", "to": {"body": "b", "at": [0, SPREAD, 2.0]},
             "segments": [{"type": "hawser", "length": length}]},
            {"name": "H2", "from": "P2", "to": {"body": "b", "at": [0, -SPREAD, 2.0]},
             "segments": [{"type": "hawser", "length": length}]},
        ],
    }


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
@pytest.mark.parametrize("force", [1.0e3, 1.0e5, 1.0e6])
def test_a_load_draws_slack_hawsers_taut(solver, force):
    """Hand-derived: 31 m hawsers, slack at rest over a 30 m chord, pulled 'force' N away
    from the bollards. By symmetry each carries T = F/2, horizontal along x, and the body
    moves until the chord equals the stretched length: D = 31 (1 + T/EA), so the body
    origin sits at x = D - 30 (sway and yaw stay zero)."""
    case = moorsolve.load_case(hawser_case(force))
    result = moorsolve.solve(case, solver=solver, tol=1e-12)
    T = force / 2
    D = 31.0 * (1 + T / EA)
    assert result.body["x_m"] == pytest.approx(D + BOLLARD_X, rel=1e-9, abs=1e-10)
    assert result.body["y_m"] == pytest.approx(0.0, abs=1e-9)
    for name in ("H1", "H2"):
        leg = result.leg(name)
        assert leg.fairlead_tension_N == pytest.approx(T, rel=1e-9)
        assert not leg.slack


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_hawsers_go_slack_again_when_the_load_reverses(solver):
    """Taut under a load away from the bollards, then the load reversed (toward them):
    nothing can push, so with a spring holding the body the hawsers go slack and carry
    exactly nothing."""
    data = hawser_case(2.0e5)
    data["bodies"][0]["stiffness"] = [[1e5 if i == j else 0 for j in range(6)]
                                      for i in range(6)]
    loaded = moorsolve.solve(moorsolve.load_case(data), solver=solver, tol=1e-12)
    assert not loaded.leg("H1").slack
    data["bodies"][0]["loads"]["force"] = [-2.0e5, 0, 0]
    back = moorsolve.solve(moorsolve.load_case(data), solver=solver, tol=1e-12,
                           start=loaded.state)
    # Hand-derived: only the spring (1e5 N/m) resists 2e5 N: x = -2 m, the hawsers' chord
    # 28 m < 31 m: slack, zero tension.
    assert back.body["x_m"] == pytest.approx(-2.0, rel=1e-9)
    for name in ("H1", "H2"):
        assert back.leg(name).slack
        assert back.leg(name).fairlead_tension_N == 0.0


def test_weightless_block_taut_and_slack():
    """The block on floats: a taut line's tension closes its span; a slack one's is zero."""
    f = weightless_line_function(True)
    L, X, Z = 30.0, 24.0, 18.3   # chord 30.18...
    D = math.hypot(X, Z)
    T = EA * (D / L - 1)
    out = f(X=X, Z=Z, u=T, V=T * Z / D, L=L, ea_inv=1 / EA, k=1e4, eps=0.0)
    assert abs(float(out["rX"])) < 1e-12 * L
    assert float(out["H"]) == pytest.approx(T * X / D, rel=1e-12)
    slack = f(X=X, Z=Z, u=0.0, V=0.0, L=40.0, ea_inv=1 / EA, k=1e4, eps=0.0)
    assert float(slack["rX"]) == pytest.approx(0.0, abs=1e-12)
    assert float(slack["H"]) == 0.0
    # a pulling chord shorter than the line with a tension is not a solution
    wrong = f(X=X, Z=Z, u=1e3, V=0.0, L=40.0, ea_inv=1 / EA, k=1e4, eps=0.0)
    assert abs(float(wrong["rX"])) > 1e-3


def test_weightless_leg_equations_keep_the_taut_convention():
    """evaluate_leg on a neutral kind: u is the tension of a taut line."""
    kind = LegKind(elastic=True, contact=False, neutral=True)
    L, X, Z = 30.0, 30.2, 0.0
    T = EA * (X / L - 1)
    out = evaluate_leg(kind, X, Z, T, 0.0, L, 0.0, 1 / EA)
    assert abs(out["rX"]) < 1e-12 and out["H"] == pytest.approx(T)
    assert np.isfinite(out["rZ"])
