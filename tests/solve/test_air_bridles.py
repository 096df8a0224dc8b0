"""Lines with both ends above the water: a CALM-buoy-like scene of two chain bridles from
deck padeyes to a free apex and a hawser from the apex to a ship's fairlead, all above
the water (moorsolve/physics/air.py).

As the ship moves away the apex rises from under the water (bridles and hawser dipping in,
their lower end submerged) to above it (every line in air throughout); a chain festoon
between two bollards, held up in the middle by a crane, dips into the water between its
ends (two crossings per line). In every position the solve certifies, passes its
own audit, and each line's reported force at end B, integrated down the line's ODE whose
weight changes wherever it crosses the surface (``reference_ode.integrate_air_and_water``,
independent of moorsolve), lands on end A with the reported force there, to 1e-8.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference_ode import integrate_air_and_water

from moorsolve import load_case, solve

CHAIN = {"weight_in_water": 1300.0, "weight_in_air": 1500.0, "ea": 5.0e8}
HAWSER = {"weight_in_water": 20.0, "weight_in_air": 80.0, "ea": 2.0e7}
APEX_MASS = 500.0


def calm_scene(ship_x: float, chain=None) -> dict:
    return {
        "name": "CALM buoy: chain bridles in air to a free apex, hawser to a ship",
        "environment": {"depth": 50.0},
        "line_types": {"chain": dict(chain or CHAIN), "hawser": dict(HAWSER)},
        "points": [{"name": "pad1", "position": [5.0, 3.0, 3.0]},
                   {"name": "pad2", "position": [5.0, -3.0, 3.0]},
                   {"name": "apex", "position": [15.0, 0.0, 2.0], "free": True,
                    "mass": APEX_MASS},
                   {"name": "ship", "position": [ship_x, 0.0, 6.0]}],
        "lines": [{"name": "b1", "from": "apex", "to": "pad1",
                   "segments": [{"type": "chain", "length": 10.8}]},
                  {"name": "b2", "from": "apex", "to": "pad2",
                   "segments": [{"type": "chain", "length": 10.8}]},
                  {"name": "hawser", "from": "apex", "to": "ship",
                   "segments": [{"type": "hawser", "length": 55.5}]}]}


def _check_line(line, lt, length):
    """End B's reported force down the ODE: end A's position and force, to 1e-8."""
    a, b = np.asarray(line.anchor, float), np.asarray(line.fairlead, float)
    fb, fa = np.asarray(line.fairlead_force, float), np.asarray(line.anchor_force, float)
    H = math.hypot(fb[0], fb[1])
    ref = integrate_air_and_water(H=H, V=-fb[2], L=length, w_water=lt["weight_in_water"],
                                  w_air=lt["weight_in_air"], z_top=b[2], ea=lt["ea"])
    T = math.hypot(H, fb[2])
    assert ref["X"] == pytest.approx(math.hypot(*(b - a)[:2]), abs=1e-8 * length)
    assert ref["Z"] == pytest.approx(b[2] - a[2], abs=1e-8 * length)
    assert ref["VA"] == pytest.approx(fa[2], abs=1e-8 * T)
    assert math.hypot(fa[0], fa[1]) == pytest.approx(H, abs=1e-8 * T)
    return ref


@pytest.mark.parametrize("ship_x, apex_above, dipping", [
    (60.0, False, {"b1", "b2", "hawser"}),       # apex 7 m under: every line dips in
    (70.0, False, {"b1", "b2", "hawser"}),       # apex just under the surface
    (70.6, True, set()),                         # apex 1 m above the water
    (72.0, True, set()),                         # everything in air
    (73.0, True, set())])                        # the apex above the padeyes
def test_calm_bridles_in_air_solve_to_the_ode(ship_x, apex_above, dipping):
    result = solve(load_case(calm_scene(ship_x)))       # raises on an audit failure
    assert result.converged and result.certificate.relative <= result.certificate.tolerance
    apex = result.points[0]
    assert (apex["z_m"] > 0) == apex_above
    types = {"b1": CHAIN, "b2": CHAIN, "hawser": HAWSER}
    lengths = {"b1": 10.8, "b2": 10.8, "hawser": 55.5}
    wet = set()
    force = np.array([0.0, 0.0, -APEX_MASS * 9.80665])   # in air: no buoyancy
    for line in result.lines:
        ref = _check_line(line, types[line.name], lengths[line.name])
        if ref["crossings"]:
            wet.add(line.name)
        force += np.asarray(line.anchor_force, float)     # end A of every line is the apex
    assert wet == dipping
    # The apex in equilibrium under the three lines and its weight (independent sum).
    scale = max(line.fairlead_tension_N for line in result.lines)
    assert np.max(np.abs(force)) <= 1e-8 * scale


def test_rope_and_chain_bridles_agree_where_the_weight_is_the_same():
    """A chain whose weight in air equals its weight in water is one catenary whether its
    parts are in air or not: the scene solves to the same apex as with a weight in air
    that differs by 1e-9 of it (the regimes meet continuously)."""
    same = dict(CHAIN, weight_in_air=CHAIN["weight_in_water"])
    near = dict(CHAIN, weight_in_air=CHAIN["weight_in_water"] * (1 + 1e-9))
    r1 = solve(load_case(calm_scene(72.0, chain=same)))
    r2 = solve(load_case(calm_scene(72.0, chain=near)))
    assert r1.points[0]["z_m"] == pytest.approx(r2.points[0]["z_m"], abs=1e-7)
    assert r1.lines[0].fairlead_tension_N == pytest.approx(r2.lines[0].fairlead_tension_N,
                                                           rel=1e-7)


def test_chain_festoon_dips_between_ends_in_air():
    """Two chains from bollards 2 and 2.5 m above the water to a free point held up by a
    crane rope: the point stays in air, each chain sags into the water and rises out of it
    again (two crossings, the ODE's count), and all three lines land on the ODE."""
    data = {"name": "festoon", "environment": {"depth": 20.0},
            "line_types": {"chain": dict(CHAIN), "hawser": dict(HAWSER)},
            "points": [{"name": "p1", "position": [0.0, 0.0, 2.0]},
                       {"name": "m", "position": [15.0, 0.0, 1.5], "free": True,
                        "mass": 100.0},
                       {"name": "p2", "position": [30.0, 0.0, 2.5]},
                       {"name": "crane", "position": [16.0, 0.0, 20.0]}],
            "lines": [{"name": "l1", "from": "m", "to": "p1",
                       "segments": [{"type": "chain", "length": 18.0}]},
                      {"name": "l2", "from": "m", "to": "p2",
                       "segments": [{"type": "chain", "length": 18.0}]},
                      {"name": "lift", "from": "m", "to": "crane",
                       "segments": [{"type": "hawser", "length": 18.0}]}]}
    result = solve(load_case(data))
    assert result.converged and result.points[0]["z_m"] > 1.0
    crossings = {line.name: len(_check_line(line, HAWSER if line.name == "lift" else CHAIN,
                                            18.0)["crossings"]) for line in result.lines}
    assert crossings == {"l1": 2, "l2": 2, "lift": 0}
    for line in result.lines[:2]:          # the drawn profile goes under the water
        assert min(line.profile["z_m"]) < -0.5


def test_a_multi_segment_bridle_in_air_says_what_to_change():
    """Multi-segment lines still weigh their weight in water above it (README, "Not yet"):
    the audit catches the weight it does not carry, and its message says what the user
    can change (one segment with a weight in air, or ends below the water)."""
    from moorsolve.audit import AuditFailure
    data = calm_scene(72.0)
    for line in data["lines"][:2]:
        line["segments"] = [{"type": "chain", "length": 5.4}] * 2
    with pytest.raises(AuditFailure, match=r"line b1 has an end above the water but, as a "
                                           r"multi-segment.*give it as one segment"):
        solve(load_case(data))
