"""Invariance of the equilibrium over random layouts (issue 7, deliverable 4).

Hypothesis draws a spread mooring (3 to 6 elastic chains, anchors around a body, depths 20
to 100 m, a constant load and moment) and checks that the solve does not depend on how the
scene is written down:

- rotating the whole case about the vertical axis rotates the offset and nothing else;
- translating the whole case (anchors, fairleads and the body's reference point) leaves
  tensions and yaw unchanged and moves the reference point's displacement by the rigid
  rotation of the translation;
- mirroring it about the x axis mirrors the offset and yaw;
- renumbering the legs changes nothing per leg;
- writing one leg's segment as two equal segments (issue 4's multi-segment legs: two
  catenary blocks and a joint) changes nothing;
- swapping which end is the "anchor" of a leg held at both ends (leg block level, a line
  with no seabed contact) swaps its end forces.
"""

from __future__ import annotations

import copy
import math

import casadi as ca
import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from hypothesis_budget import examples

from moorsolve import ConvergenceError, load_case, solve
from moorsolve.physics.catenary import (LEG_INPUTS, LegKind, leg_function)

SETTINGS = {"deadline": None, "suppress_health_check": [HealthCheck.too_slow]}


@st.composite
def layouts(draw):
    n = draw(st.integers(3, 6))
    depth = draw(st.floats(20.0, 100.0))
    w = draw(st.floats(200.0, 2000.0))
    ea = draw(st.floats(1e8, 1e10))
    turn = draw(st.floats(0.0, 360.0))
    legs = []
    for i in range(n):
        a = math.radians(turn + 360.0 * i / n + draw(st.floats(-15.0, 15.0)))
        b = a + math.radians(draw(st.floats(-20.0, 20.0)))
        r_f = draw(st.floats(5.0, 40.0))
        r_a = draw(st.floats(150.0, 300.0))
        fair = [r_f * math.cos(b), r_f * math.sin(b), 0.0]
        anchor = [r_a * math.cos(a), r_a * math.sin(a)]
        X0 = math.hypot(anchor[0] - fair[0], anchor[1] - fair[1])
        L = X0 + depth * draw(st.floats(0.3, 0.9))
        legs.append({"name": f"L{i}", "anchor": anchor, "fairlead": fair,
                     "segments": [{"type": "chain", "length": L}]})
    F = draw(st.floats(0.0, 0.5)) * w * depth * 10
    heading = math.radians(draw(st.floats(0.0, 360.0)))
    # A moderate couple: with a large one (F x 20 m on fairleads 5 m from the centre) a
    # spread mooring twisted far round has several equilibria, and which one a cold solve
    # lands on depends on the description (see the issue 7 note).
    M = draw(st.floats(-1.0, 1.0)) * F * 2
    return {
        "name": "random layout",
        "environment": {"depth": depth},
        "line_types": {"chain": {"weight_in_water": w, "ea": ea}},
        "body": {"free": ["surge", "sway", "yaw"],
                 "loads": {"force": [F * math.cos(heading), F * math.sin(heading), M]}},
        "legs": legs,
    }


def solved(data):
    try:
        return solve(load_case(data))
    except ConvergenceError:
        return None


def tensions(result):
    return {lr.name: (lr.fairlead_tension_N, lr.anchor_tension_N, lr.horizontal_tension_N,
                      lr.grounded_length_m) for lr in result.legs}


def assert_same_legs(a, b):
    ta, tb = tensions(a), tensions(b)
    assert ta.keys() == tb.keys()
    t_max = max(v[0] for v in ta.values())
    for name in ta:
        for x, y in zip(ta[name][:3], tb[name][:3]):
            assert x == pytest.approx(y, rel=1e-7, abs=1e-8 * t_max), name
        assert ta[name][3] == pytest.approx(tb[name][3], abs=1e-6), name


def rotate(v, angle):
    c, s = math.cos(angle), math.sin(angle)
    return [c * v[0] - s * v[1], s * v[0] + c * v[1]] + list(v[2:])


@settings(max_examples=examples(20), **SETTINGS)
@given(layouts(), st.floats(-180.0, 180.0))
def test_rotating_the_whole_case(data, angle_deg):
    base = solved(data)
    assume(base is not None)
    a = math.radians(angle_deg)
    turned = copy.deepcopy(data)
    for leg in turned["legs"]:
        leg["anchor"] = rotate(leg["anchor"], a)
        leg["fairlead"] = rotate(leg["fairlead"], a)
    turned["body"]["loads"]["force"] = rotate(data["body"]["loads"]["force"], a)
    r = solved(turned)
    assert r is not None, "the rotated case must converge as the original did"
    assert_same_legs(base, r)
    x, y = rotate([base.body["x_m"], base.body["y_m"]], a)
    assert (r.body["x_m"], r.body["y_m"]) == pytest.approx((x, y), abs=1e-6)
    assert r.body["yaw_deg"] == pytest.approx(base.body["yaw_deg"], abs=1e-7)


def with_current(data, speed, toward_deg):
    """The layout's load as a current drag acting at the body origin, plus the couple."""
    out = copy.deepcopy(data)
    out["environment"]["current"] = {"speed": speed, "toward_deg": toward_deg}
    M = out["body"]["loads"]["force"][2]
    out["body"]["loads"] = {
        "force": [0.0, 0.0, M],
        "current": {"model": "drag", "area_x": 300.0, "area_y": 900.0, "cx": 0.8, "cy": 1.0,
                    "centre": [0.0, 0.0]}}
    return out


@settings(max_examples=examples(20), **SETTINGS)
@given(layouts(), st.floats(-200.0, 200.0), st.floats(-200.0, 200.0),
       st.floats(0.1, 1.5), st.floats(0.0, 360.0))
def test_translating_the_whole_case(data, dx, dy, speed, toward):
    """Anchors, fairleads and the load's point of action move by d.

    The body's reference point (the body-frame origin) does not move with them: it is now
    the material point -d from the old one. A load given at a body-frame ``centre`` is
    translated with the body; a constant force is not (it acts at the origin, wherever
    that is on the body), so the load here is a current drag with a centre, plus a couple.
    """
    data = with_current(data, speed, toward)
    base = solved(data)
    assume(base is not None)
    moved = copy.deepcopy(data)
    for leg in moved["legs"]:
        leg["anchor"] = [leg["anchor"][0] + dx, leg["anchor"][1] + dy]
        leg["fairlead"] = [leg["fairlead"][0] + dx, leg["fairlead"][1] + dy, 0.0]
    moved["body"]["loads"]["current"]["centre"] = [dx, dy]
    r = solved(moved)
    assert r is not None, "the translated case must converge as the original did"
    assert_same_legs(base, r)
    yaw = math.radians(base.body["yaw_deg"])
    # The certificate bounds the moment residual by tol x tension x the body's radius,
    # which the translation enlarges (here up to 5x): yaw agrees to what that allows.
    assert r.body["yaw_deg"] == pytest.approx(base.body["yaw_deg"], abs=1e-5)
    # The new reference point ends at d + u - R(yaw) d, u the old point's displacement.
    ex, ey = rotate([dx, dy], yaw)
    assert (r.body["x_m"], r.body["y_m"]) == pytest.approx(
        (base.body["x_m"] + dx - ex, base.body["y_m"] + dy - ey), abs=1e-5)


@settings(max_examples=examples(20), **SETTINGS)
@given(layouts())
def test_mirroring_the_case(data):
    base = solved(data)
    assume(base is not None)
    mirrored = copy.deepcopy(data)
    for leg in mirrored["legs"]:
        leg["anchor"][1] = -leg["anchor"][1]
        leg["fairlead"][1] = -leg["fairlead"][1]
    Fx, Fy, M = data["body"]["loads"]["force"]
    mirrored["body"]["loads"]["force"] = [Fx, -Fy, -M]
    r = solved(mirrored)
    assert r is not None
    assert_same_legs(base, r)
    assert (r.body["x_m"], r.body["y_m"]) == pytest.approx(
        (base.body["x_m"], -base.body["y_m"]), abs=1e-6)
    assert r.body["yaw_deg"] == pytest.approx(-base.body["yaw_deg"], abs=1e-7)


@settings(max_examples=examples(20), **SETTINGS)
@given(layouts(), st.randoms(use_true_random=False))
def test_renumbering_the_legs(data, rng):
    base = solved(data)
    assume(base is not None)
    shuffled = copy.deepcopy(data)
    rng.shuffle(shuffled["legs"])
    r = solved(shuffled)
    assert r is not None
    assert_same_legs(base, r)
    assert (r.body["x_m"], r.body["y_m"], r.body["yaw_deg"]) == pytest.approx(
        (base.body["x_m"], base.body["y_m"], base.body["yaw_deg"]), abs=1e-7)


# ---- swapping the ends of a leg held at both ends -----------------------------------------

def _block_solver(kind):
    args = {n: ca.SX.sym(n) for n in LEG_INPUTS}
    out = leg_function(kind).call(args)
    uv = ca.vertcat(args["u"], args["V"])
    r = ca.vertcat(out["rX"], out["rZ"])
    rest = [args[n] for n in LEG_INPUTS if n not in ("u", "V")]
    return ca.Function("F", [uv, *rest], [r, ca.jacobian(r, uv), out["HA"], out["VA"]])


def _solve_block(F, start, *rest):
    z = np.array(start, float)
    for _ in range(100):
        r, J, _, _ = F(z, *rest)
        r, J = np.array(r).ravel(), np.array(J)
        step = np.linalg.solve(J, r)
        alpha = 1.0
        while alpha > 1e-6:
            trial = z - alpha * step
            if trial[0] > 0 and np.max(np.abs(np.array(F(trial, *rest)[0]))) < np.max(np.abs(r)):
                break
            alpha /= 2
        z = trial
        if np.max(np.abs(r)) < 1e-13 * rest[2]:
            break
    _, _, HA, VA = F(z, *rest)
    return z, float(HA), float(VA)


@settings(max_examples=examples(40), **SETTINGS)
@given(X=st.floats(1.0, 500.0), Z=st.floats(-300.0, 300.0), slack=st.floats(1.001, 1.5),
       w=st.floats(-2000.0, 2000.0).filter(lambda v: abs(v) > 1.0),
       ea=st.none() | st.floats(1e6, 1e10))
def test_swapping_the_ends_of_a_suspended_leg(X, Z, slack, w, ea):
    """The same line between the same two fixed points, described from either end.

    From end A to end B the block gives (H, V_B) and the force at A (H, V_A); from B to A
    (span X, height -Z) it must give (H, -V_A) at A and -V_B at B: the same line.
    """
    L = math.hypot(X, Z) * slack
    kind = LegKind(elastic=ea is not None, contact=False)
    F = _block_solver(kind)
    ea_inv = 0.0 if ea is None else 1.0 / ea
    H0 = abs(w) * L
    (H1, V1), HA1, VA1 = _solve_block(F, [H0, w * L / 2], X, Z, L, w, ea_inv, 0.0)
    (H2, V2), HA2, VA2 = _solve_block(F, [H0, w * L / 2], X, -Z, L, w, ea_inv, 0.0)
    T = math.hypot(H1, V1) + abs(w) * L
    for a, b in ((H1, H2), (HA1, HA2), (V1, -VA2), (VA1, -V2)):
        assert a == pytest.approx(b, rel=1e-8, abs=1e-9 * T)


@settings(max_examples=examples(10), **SETTINGS)
@given(layouts(), st.data())
def test_splitting_a_segment_into_two_equal_ones(data, draw):
    """One leg's segment written as two equal segments of the same line (issue 4's
    multi-segment legs, solved as two catenary blocks and a joint): the same equilibrium."""
    base = solved(data)
    assume(base is not None)
    i = draw.draw(st.integers(0, len(data["legs"]) - 1))
    split = copy.deepcopy(data)
    seg = split["legs"][i]["segments"][0]
    half = {"type": seg["type"], "length": seg["length"] / 2}
    split["legs"][i]["segments"] = [half, dict(half)]
    r = solved(split)
    assert r is not None, "the split case must converge as the original did"
    assert_same_legs(base, r)
    assert (r.body["x_m"], r.body["y_m"], r.body["yaw_deg"]) == pytest.approx(
        (base.body["x_m"], base.body["y_m"], base.body["yaw_deg"]), abs=1e-6)
