"""Hunting for certified wrong answers (issue 20): hypothesis draws whole scenes in every
regime and every result is checked against an independent reference.

Regimes drawn: slack, touchdown, suspended (uplift) and nearly taut chains on a flat seabed,
with and without friction, elastic or not; chains on a sloped seabed (anchors up or down the
slope, above or below their fairleads); chains from anchors above the seabed (folded, sagging
onto it, suspended); buoyant lines (floating to a surface buoy or between two submerged
points, suspended, slack and afloat); weightless lines; lazy waves (chain, buoyant segment,
chain); lines in a current (lumped nodes); a body on a spread of such legs under a load.

Every solve either raises ConvergenceError (refused: counted) or returns a result that
must pass (1) both audits, which ``solve(..., audit="full")`` runs on it
(``moorsolve.audit``: the profile audit of boundaries, end forces and body balance,
and for one-segment lines on a flat seabed the closed-form audit of the end forces), and
(2) for every analytic one-segment leg, an independent integration of the line's
equilibrium ODE (``tests/reference_ode.py``) from the reported end forces, which must land
on the leg's other end: flat and lifted contact from the fairlead or the anchor, the free
surface from the anchor, a sloped seabed to its
touchdown.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from hypothesis_budget import examples
from reference_ode import (integrate_from_anchor, integrate_leg, integrate_to_slope)

from moorsolve import ConvergenceError, load_case, solve

REL = 1e-7


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0 ** e)


@st.composite
def one_leg(draw):
    """A line from its anchor to a fixed point (no body): the regime follows the draws."""
    kind = draw(st.sampled_from(["chain", "chain_friction", "sloped", "lifted", "buoyant",
                                 "neutral"]))
    depth = draw(st.floats(5.0, 500.0))
    ea = draw(st.none() | log_uniform(1e5, 1e11)) if kind != "chain_friction" \
        else draw(log_uniform(1e5, 1e9))
    w = draw(log_uniform(1.0, 3e3)) * (-1 if kind == "buoyant" else 1)
    if kind == "neutral":
        w = 0.0
    env = {"depth": depth}
    gradient = (0.0, 0.0)
    if kind == "chain_friction":
        env["seabed"] = {"friction": draw(st.floats(0.05, 1.0))}
    if kind == "sloped":
        slope = draw(st.floats(0.01, 0.3))
        gradient = (slope, 0.0)
        env["seabed"] = {"gradient": list(gradient), "friction": draw(st.floats(0.0, 1.0))}
    X = depth * draw(st.floats(0.0, 3.0))
    fz = -depth * draw(st.sampled_from([0.0, 0.0, 0.3, 0.8]))
    anchor = [0.0, 0.0]
    if kind == "sloped":
        # The seabed rises toward the fairlead, or falls: put the anchor either side.
        X = X if draw(st.booleans()) else -X
        reach = depth - 0.01 * depth
        if gradient[0] * X > reach:
            X = reach / gradient[0]
    if kind == "lifted":
        anchor = [0.0, 0.0, -depth * draw(st.floats(0.05, 0.95))]
    if kind == "buoyant" and draw(st.booleans()):
        fz = 0.0
    bed_under_fairlead = -depth + gradient[0] * X
    fz = max(fz, bed_under_fairlead + 0.01 * depth)
    a_z = anchor[2] if len(anchor) == 3 else -depth
    chord = math.dist([0.0, a_z], [abs(X), fz])
    # Nearly taut to very slack, most draws near taut where the regimes change.
    L = chord * draw(st.floats(1.0 if ea else 1.0005, 1.15) | st.floats(1.15, 2.5))
    line = {"weight_in_water": w}
    if ea:
        line["ea"] = ea
    data = {"environment": env, "line_types": {"line": line},
            "legs": [{"name": "A", "anchor": anchor, "fairlead": [X, 0.0, fz],
                      "segments": [{"type": "line", "length": L}]}]}
    return kind, data


def reference_check(kind, case, leg):
    """The leg's own ODE, from its reported end forces, must reach its other end."""
    lc = case.legs[0]
    L, w, ea = lc.length, lc.line_type.weight_in_water, lc.line_type.ea
    X = math.dist(leg.anchor[:2], leg.fairlead[:2])
    Z = leg.fairlead[2] - leg.anchor[2]
    T = max(leg.fairlead_tension_N, leg.anchor_tension_N, abs(w) * L)
    size = L * (1 + (T / ea if ea else 0.0))
    H, V = leg.horizontal_tension_N, leg.fairlead_vertical_N
    loose = leg.slack
    if kind == "neutral":
        return
    if kind == "sloped":
        t = case.environment.seabed.gradient[0] * (1 if leg.fairlead[0] > leg.anchor[0] else -1)
        ref = integrate_to_slope(H=H, V=V, L=L, w=w, t=t, ea=ea,
                                 mu=case.environment.seabed.friction)
        if not loose:
            assert ref["X"] == pytest.approx(X, abs=REL * size)
            assert ref["Z"] == pytest.approx(Z, abs=REL * size)
            assert ref["TA"] == pytest.approx(leg.anchor_tension_N, abs=REL * T)
        return
    if kind in ("lifted", "buoyant"):
        # From the anchor: the line's pull there, lying along its boundary for the length
        # the result reports (grounded or afloat).
        lying = leg.grounded_length_m if kind == "lifted" else leg.floating_length_m
        ref = integrate_from_anchor(HA=leg.anchor_horizontal_N, VA=leg.anchor_vertical_N, L=L,
                                    w=w, ea=ea, float_length=lying)
        if not loose:
            assert ref["X"] == pytest.approx(X, abs=REL * size)
        assert ref["Z"] == pytest.approx(Z, abs=REL * size)
        assert ref["VF"] == pytest.approx(V, abs=REL * T)
        if lying > 0:
            boundary = -case.environment.depth if kind == "lifted" else 0.0
            assert leg.anchor[2] + ref["z_vertex"] == pytest.approx(boundary, abs=REL * size)
        return
    ref = integrate_leg(H=H, V=V, L=L, w=w, ea=ea, mu=case.environment.seabed.friction,
                        contact=True)
    if not loose:
        assert ref["X"] == pytest.approx(X, abs=REL * size)
    assert ref["Z"] == pytest.approx(Z, abs=REL * size)
    assert ref["HA"] == pytest.approx(leg.anchor_horizontal_N, abs=REL * T)
    assert max(ref["VA"], 0.0) == pytest.approx(leg.anchor_vertical_N, abs=REL * T)
    assert ref["grounded"] == pytest.approx(leg.grounded_length_m, abs=REL * size)


@settings(max_examples=examples(150), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(one_leg())
def test_one_leg_scenes_are_right_or_refused(scene):
    kind, data = scene
    case = load_case(data)
    try:
        result = solve(case, audit="full")
    except ConvergenceError as exc:
        event(f"{kind}: refused")
        assert exc.reason
        return
    leg = result.legs[0]
    regime = ("slack" if leg.slack else "floating" if leg.floating_length_m > 0 else
              "grounded" if leg.grounded_length_m > 0 else "suspended")
    event(f"{kind}: {regime}")
    assert result.converged
    reference_check(kind, case, leg)


@st.composite
def spread(draw):
    """A body on three to five legs of mixed kinds under a load."""
    depth = draw(st.floats(20.0, 300.0))
    n = draw(st.integers(3, 5))
    kinds = [draw(st.sampled_from(["chain", "hose", "lazy_wave"])) for _ in range(n)]
    friction = draw(st.sampled_from([0.0, 0.0, 0.4]))
    legs = []
    for k, kind in enumerate(kinds):
        a = 2 * math.pi * k / n + draw(st.floats(-0.3, 0.3))
        r = depth * draw(st.floats(1.5, 4.0))
        chord = math.hypot(r, depth)
        segs = ([{"type": "chain", "length": chord * draw(st.floats(1.02, 1.6))}]
                if kind == "chain" else
                [{"type": "hose", "length": chord * draw(st.floats(1.05, 1.8))}]
                if kind == "hose" else
                [{"type": "chain", "length": 0.5 * chord},
                 {"type": "hose", "length": draw(st.floats(0.3, 1.2)) * chord},
                 {"type": "chain", "length": 0.5 * chord}])
        legs.append({"name": f"L{k + 1}", "anchor": [r * math.cos(a), r * math.sin(a)],
                     "fairlead": [5 * math.cos(a), 5 * math.sin(a), 0.0], "segments": segs})
    load = draw(st.floats(0.0, 2e5))
    heading = draw(st.floats(0, 2 * math.pi))
    return {"environment": {"depth": depth, "seabed": {"friction": friction}},
            "line_types": {"chain": {"weight_in_water": draw(st.floats(200.0, 2000.0)),
                                     "ea": draw(log_uniform(1e7, 1e10))},
                           "hose": {"weight_in_water": -draw(st.floats(20.0, 800.0)),
                                    "ea": draw(log_uniform(1e6, 1e9))}},
            "body": {"free": ["surge", "sway", "yaw"],
                     "loads": {"force": [load * math.cos(heading), load * math.sin(heading),
                                         draw(st.floats(-1e6, 1e6))]}},
            "legs": legs}


@settings(max_examples=examples(40), deadline=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(spread())
def test_spread_moorings_are_right_or_refused(data):
    case = load_case(data)
    try:
        result = solve(case, audit="full")
    except ConvergenceError as exc:
        event("refused")
        assert exc.reason
        return
    event("floating" if any(leg.floating_length_m > 0 for leg in result.legs)
          else "submerged")
    # Every one-segment leg against its own ODE; the multi-segment legs and the body are
    # covered by the audit ``solve`` ran.
    for leg_case, leg in zip(case.legs, result.legs):
        if leg_case.multi_segment:
            continue
        one = type(case)(name="leg", environment=case.environment,
                         line_types=case.line_types, lines=(leg_case,))
        kind = "buoyant" if leg_case.line_type.weight_in_water < 0 else (
            "chain_friction" if case.environment.seabed.friction else "chain")
        reference_check(kind, one, leg)


@settings(max_examples=examples(25), deadline=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(depth=st.floats(20.0, 100.0), speed=st.floats(0.1, 1.5),
       reverse=st.booleans(), turn=st.floats(0.0, 180.0), buoyant=st.booleans())
def test_lines_in_a_current_are_right_or_refused(depth, speed, reverse, turn, buoyant):
    """Lumped-node lines in a current that turns and reverses with depth, sinking or
    buoyant (floating nodes): certified results pass the audit, whose end-force and boundary
    checks hold for lumped nodes too."""
    profile = [[-depth, speed * (-1 if reverse else 1) * 0.5], [0.0, speed]]
    if turn:
        profile = [[-depth, abs(profile[0][1]), turn], [0.0, speed, 0.0]]
    data = {"environment": {"depth": depth,
                            "current": {"speed": speed, "toward_deg": 0.0,
                                        "profile": profile}},
            "line_types": {"l": {"weight_in_water": -150.0 if buoyant else 300.0, "ea": 1e8,
                                 "diameter": 0.1, "drag": {"normal": 1.2,
                                                           "tangential": 0.05}}},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [1.8 * depth, 0.0, 0.0],
                      "segments": [{"type": "l", "length": 2.3 * depth}]}],
            "solver": {"line_elements": 12}}
    try:
        result = solve(load_case(data), audit="full")
    except ConvergenceError as exc:
        event("refused")
        assert exc.reason
        return
    leg = result.legs[0]
    event("floating" if leg.floating_length_m > 0 else "submerged")
    z = np.asarray(leg.profile["z_m"])
    assert np.all(z <= 1e-9) and np.all(z >= -depth - 1e-9)
