"""Weathervaning under crossed wind and current: the stable heading, from rest, in every
solve and sweep row.

The scenes: a tanker on a weightless hawser to a CALM buoy held by four chains, and the
shipped turret ship with a current across its wind. Every answer is checked against an
independent scan of the yaw circle: the body held at headings round the circle (a case
with its yaw not free, solved), the yaw moment about its origin summed here from the
reported line forces and the drag loads written out from the README's load model; the
stable headings are where that moment falls through zero (Brent's method on held solves).
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pandas as pd
import pytest
from scipy.optimize import brentq

import moorsolve
from moorsolve import load_case, solve

AIR, WATER = 1.225, 1025.0
HAWSER = 64.0           # the hawser's length [m]
BOW = 140.0             # the tanker's bow fairlead ahead of its origin [m]


def calm_case(wind_deg: float, current_deg: float) -> dict:
    """A CALM buoy free in surge and sway on four chains in 80 m of water, and a 280 m
    tanker free in surge, sway and yaw on a weightless 64 m hawser from the buoy to its
    bow, with wind and current drag (the wind's centre aft, the current's near midships)."""
    anchors = [[round(450 * math.cos(math.radians(45 + 90 * k)), 3),
                round(450 * math.sin(math.radians(45 + 90 * k)), 3)] for k in range(4)]
    return {
        "name": "CALM buoy and tanker",
        "environment": {"depth": 80.0, "wind": {"speed": 25.0, "toward_deg": wind_deg},
                        "current": {"speed": 1.0, "toward_deg": current_deg}},
        "line_types": {"chain": {"weight_in_water": "1.5 kN/m", "ea": 1.2e9, "mbl": 9.0e6},
                       "hawser": {"weight_in_water": 0, "ea": 1.5e8, "mbl": 6.0e6}},
        "bodies": [
            {"name": "buoy", "free": ["surge", "sway"]},
            {"name": "tanker", "position": [-HAWSER - BOW - 1.0, 0.0, 0.0],
             "free": ["surge", "sway", "yaw"],
             "loads": {"wind": {"model": "drag", "area_x": 1100, "area_y": 5200, "cx": 0.8,
                                "cy": 0.9, "centre": [-40.0, 0.0]},
                       "current": {"model": "drag", "area_x": 850, "area_y": 4760,
                                   "cx": 0.1, "cy": 0.7, "centre": [10.0, 0.0]}}}],
        "points": [{"name": f"A{k + 1}", "position": anchors[k]} for k in range(4)],
        "lines": [{"name": f"C{k + 1}", "from": f"A{k + 1}",
                   "to": {"body": "buoy", "at": [0.0, 0.0, -5.0]},
                   "segments": [{"type": "chain", "length": 470.0}]} for k in range(4)]
        + [{"name": "hawser", "from": {"body": "buoy", "at": [0.0, 0.0, 0.0]},
            "to": {"body": "tanker", "at": [BOW, 0.0, 0.0]},
            "segments": [{"type": "hawser", "length": HAWSER}]}],
    }


def turret_case(current_deg: float, speed: float) -> dict:
    """The shipped turret ship (wind toward 0) with a current across it and a current drag
    model on the hull."""
    data = copy.deepcopy(load_case("cases/turret_ship.yaml").source)
    data["environment"]["current"] = {"speed": speed, "toward_deg": current_deg}
    data["bodies"][0]["loads"]["current"] = {"model": "drag", "area_x": 480, "area_y": 2400,
                                             "cx": 0.8, "cy": 1.0}
    return data


# ---- the independent yaw moment -----------------------------------------------------------


def drag_loads(data, body, yaw):
    """The drag loads on ``body`` at heading ``yaw`` [rad], written out from the README's
    model: ``Fx = 1/2 rho cx Ax V^2 cos t |cos t|``, ``Fy`` likewise with sin, in body axes,
    ``t = toward - yaw``, at the model's centre. ``[(F global xy, centre global xy)]``."""
    out = []
    c, s = math.cos(yaw), math.sin(yaw)
    for slot, rho in (("wind", AIR), ("current", WATER)):
        model = body["loads"].get(slot)
        flow = data["environment"].get(slot)
        if model is None or flow is None:
            continue
        v2 = flow["speed"] ** 2
        t = math.radians(flow["toward_deg"]) - yaw
        fx = 0.5 * rho * model.get("cx", 1.0) * model["area_x"] * v2 * math.cos(t) * abs(math.cos(t))
        fy = 0.5 * rho * model.get("cy", 1.0) * model["area_y"] * v2 * math.sin(t) * abs(math.sin(t))
        cx, cy = model.get("centre", [0.0, 0.0])[:2]
        out.append((np.array([c * fx - s * fy, s * fx + c * fy]),
                    np.array([c * cx - s * cy, s * cx + c * cy])))
    return out


def yaw_moment(result, data, name) -> float:
    """The yaw moment [N m] on body ``name`` about its origin at ``result``: the reported
    forces of the lines ending on it at their reported ends, and the drag loads."""
    b = next(b for b in result.bodies if b["name"] == name)
    body = next(b for b in data["bodies"] if b["name"] == name)
    origin = np.array([b["x_m"], b["y_m"]])
    total = 0.0
    for line, leg in zip(data["lines"], result.legs):
        for end, force, where in (("to", leg.fairlead_force, leg.fairlead),
                                  ("from", leg.anchor_force, leg.anchor)):
            if isinstance(line[end], dict) and line[end].get("body") == name:
                r = np.array(where[:2]) - origin
                total += r[0] * force[1] - r[1] * force[0]
    for force, centre in drag_loads(data, body, math.radians(b["yaw_deg"])):
        total += centre[0] * force[1] - centre[1] * force[0]
    return total


# ---- the independent scan of the yaw circle -------------------------------------------------


def held_moment(data, name, psi, place) -> float:
    """The yaw moment on ``name`` held at heading ``psi`` [rad] (its yaw not free; the rest
    solved), placed by ``place(data, psi) -> [x, y]``."""
    d = copy.deepcopy(data)
    body = next(b for b in d["bodies"] if b["name"] == name)
    body["free"] = [f for f in body["free"] if f != "yaw"]
    x, y = place(data, psi)
    body["position"] = [float(x), float(y), 0.0]
    body["orientation_deg"] = [0.0, 0.0, math.degrees(psi)]
    return yaw_moment(solve(load_case(d), solver="newton"), d, name)


def place_tanker(data, psi):
    """The tanker at heading ``psi`` with its hawser along the net drag load (where the
    held tanker settles), its bow a hawser's length from the buoy."""
    body = data["bodies"][1]
    force = sum(f for f, _ in drag_loads(data, body, psi))
    bow = HAWSER * force / np.linalg.norm(force)
    return bow[0] - BOW * math.cos(psi), bow[1] - BOW * math.sin(psi)


def place_turret(data, psi):
    """The turret ship at heading ``psi`` with its turret (body [40, 0]) where it is at the
    case pose."""
    return 40.0 - 40.0 * math.cos(psi), -40.0 * math.sin(psi)


def stable_headings(data, name, place, step_deg=10.0):
    """``(roots, moment)``: the headings [deg, in [0, 360)] where the held yaw moment
    falls through zero, each refined by Brent's method; and the moment function [rad]."""
    def moment(psi):
        return held_moment(data, name, psi, place)

    grid = np.radians(np.arange(0.0, 360.0 + step_deg, step_deg))
    values = [moment(psi) for psi in grid[:-1]]
    values.append(values[0])
    roots = []
    for a, b, ma, mb in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if ma > 0 >= mb:
            roots.append(math.degrees(brentq(moment, a, b, xtol=1e-10)) % 360.0)
    return roots, moment


def angle_between(a_deg, b_deg) -> float:
    return abs((a_deg - b_deg + 180.0) % 360.0 - 180.0)


def check_stable_equilibrium(result, data, name):
    """Certified, stable by its eigenvalues, and a true equilibrium of the yaw moment
    summed here."""
    assert result.converged
    cert = result.certificate
    assert cert.relative <= cert.tolerance
    assert result.stability.stable and not result.stability.unstable_dofs
    values = np.array(result.stability.eigenvalues)
    assert result.stability.min_eigenvalue == pytest.approx(values.real.min())
    assert values.real.min() > 0
    b = next(b for b in data["bodies"] if b["name"] == name)
    scale = max(np.linalg.norm(f) for f, _ in drag_loads(
        data, b, math.radians(next(x for x in result.bodies if x["name"] == name)["yaw_deg"])))
    assert abs(yaw_moment(result, data, name)) <= 1e-6 * scale * BOW


def walked(result) -> bool:
    return any("turning from the case heading" in note for note in result.notes)


# ---- the CALM buoy and tanker --------------------------------------------------------------

#: Crossed wind and current (toward, deg). Before the heading walk the solve returned the
#: tanker at 80.84, -116.33 and 110.81 deg for the first, second and last, unstable in yaw,
#: with exit status 0.
CROSSED = [(30.0, 150.0), (200.0, 300.0), (120.0, 270.0), (90.0, 180.0), (0.0, 100.0),
           (330.0, 200.0), (250.0, 20.0), (160.0, 45.0)]


@pytest.mark.parametrize("wind, current", CROSSED)
def test_calm_tanker_takes_a_stable_heading_under_crossed_flows(wind, current):
    data = calm_case(wind, current)
    roots, moment = stable_headings(data, "tanker", place_tanker)
    assert roots, "the scan finds a stable heading on every crossed pair here"
    headings = []
    for solver in ("ipopt", "newton"):
        result = solve(load_case(data), solver=solver)
        check_stable_equilibrium(result, data, "tanker")
        yaw = result.bodies[1]["yaw_deg"]
        assert min(angle_between(yaw, r) for r in roots) < 1e-4
        if walked(result):
            # The rule: from the case heading (0) the way the moment there turns the body,
            # the first heading where the moment falls through zero.
            forward = moment(0.0) >= 0
            first = min(roots, key=lambda r: r if forward else 360.0 - r)
            assert angle_between(yaw, first) < 1e-4
        headings.append(yaw)
    assert angle_between(*headings) < 1e-6


@pytest.mark.parametrize("wind, current, before", [(30.0, 150.0, 80.842),
                                                     (200.0, 300.0, -116.33),
                                                     (160.0, 45.0, 110.812)])
def test_calm_tanker_formerly_unstable_now_on_the_stable_branch(wind, current, before):
    """Before the walk: returned at ``before`` deg, unstable. Now a stable heading (which
    one: test_calm_tanker_takes_a_stable_heading_under_crossed_flows, against the scan);
    where the walk found it, a note says so. The first solve may itself end stable: since the
    derivatives at the lines' kinks changed, Newton's IPOPT fallback reaches a stable heading
    on two of these three without walking."""
    data = calm_case(wind, current)
    result = solve(load_case(data), solver="newton")
    yaw = result.bodies[1]["yaw_deg"]
    assert angle_between(yaw, before) > 90.0
    check_stable_equilibrium(result, data, "tanker")
    if walked(result):
        assert any("other stable headings may exist" in n for n in result.notes)


# ---- the turret ship with a crossed current ---------------------------------------------------


@pytest.mark.parametrize("current, speed", [(120.0, 1.0), (150.0, 1.0), (170.0, 1.0),
                                             (150.0, 2.0), (170.0, 2.0)])
def test_turret_ship_with_crossed_current_is_stable(current, speed):
    """Before the walk, 150 and 170 deg at 1 m/s and 170 deg at 2 m/s said "no equilibrium:
    the legs could not balance the body load"."""
    data = turret_case(current, speed)
    roots, moment = stable_headings(data, "ship", place_turret)
    assert roots
    for solver in ("ipopt", "newton"):
        result = solve(load_case(data), solver=solver)
        check_stable_equilibrium(result, data, "ship")
        yaw = result.bodies[0]["yaw_deg"]
        assert min(angle_between(yaw, r) for r in roots) < 1e-4


def _two_turret_ships(current_deg: float, speed: float) -> dict:
    """Two turret ships of :func:`turret_case` 3 km apart in one scene."""
    data = turret_case(current_deg, speed)
    one = copy.deepcopy(data)
    ship2 = copy.deepcopy(one["bodies"][0])
    ship2.update(name="ship2", position=[3000.0, 0.0, 0.0])
    data["bodies"].append(ship2)
    for point in copy.deepcopy(one["points"]):
        point["name"] += "b"
        point["position"][0] += 3000.0
        data["points"].append(point)
    for line in copy.deepcopy(one["lines"]):
        line.update(name=line["name"] + "b", **{"from": line["from"] + "b"})
        line["to"]["body"] = "ship2"
        data["lines"].append(line)
    return data


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_several_weathervaning_bodies_are_walked_in_turn(solver):
    """Two ships that do not touch each other: each takes the heading it takes alone
    (formerly "no equilibrium" for both)."""
    alone = solve(load_case(turret_case(150.0, 1.0)), solver=solver).bodies[0]["yaw_deg"]
    result = solve(load_case(_two_turret_ships(150.0, 1.0)), solver=solver)
    assert result.converged and result.stability.stable and walked(result)
    for body in result.bodies:
        assert angle_between(body["yaw_deg"], alone) < 1e-6


@pytest.mark.parametrize("path", ["cases/floating_dock.yaml", "cases/oc3_spar.yaml",
                                  "cases/oc4_semi.yaml"])
@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_a_scene_stable_at_once_never_walks(path, solver, monkeypatch):
    """The common case pays nothing: a solve whose first point is stable does not enter the
    walk (nor its rest-state look-up)."""
    from moorsolve.solve.stability import examine

    def refuse(*args, **kwargs):
        raise AssertionError("the heading walk was entered")

    monkeypatch.setattr(examine, "heading_walk", refuse)
    result = solve(load_case(path), solver=solver)
    assert result.stability.stable
