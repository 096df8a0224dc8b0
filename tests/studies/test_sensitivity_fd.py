"""Every documented sensitivity parameter against central differences of re-solved cases,
edited as the case file defines them (issue 20).

The exact sensitivities (``moorsolve.sensitivity``, implicit function theorem on the
equilibrium) must equal central differences of cases re-built from their case-file data with
one value moved: an anchor given on a sloped seabed is moved there in x or y and stays on the
seabed (the derivative once held its z fixed: 0.4 % off on the shipped sloped dock, 11 % to
3x on steeper slopes), a multi-segment leg's segment or line type moves in every segment
that uses it, a current drags on lumped-node lines. Scenes: flat and sloped seabeds, with and
without friction, a multi-segment leg with clumps, lumped-node lines in a current, a floating
buoyant line and a leg from an anchor above the seabed.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

import moorsolve
from moorsolve.model.paths import with_values
from test_study import _outputs as outputs_of
from conftest import ROOT

CASES = ROOT / "cases"
TOL = 1e-12
LEG_OUTPUTS = ("fairlead_tension_N", "horizontal_tension_N", "fairlead_vertical_N",
               "anchor_tension_N", "anchor_horizontal_N", "anchor_vertical_N",
               "grounded_length_m")


def _source(name, edits=None):
    data = copy.deepcopy(moorsolve.load_case(CASES / name).source)
    return with_values(data, edits) if edits else data


def _leg_item(data, name):
    return next(i for i, leg in enumerate(data["legs"]) if leg["name"] == name)


def _own_line_type(data, leg_name):
    """Give a one-segment leg a copy of its line type, so its ea or weight moves alone."""
    data = copy.deepcopy(data)
    i = _leg_item(data, leg_name)
    seg = data["legs"][i]["segments"][0]
    own = f"{seg['type']}__{leg_name}"
    data["line_types"][own] = copy.deepcopy(data["line_types"][seg["type"]])
    data["legs"][i]["segments"] = [dict(seg, type=own)]
    return data, own


def editor(data, case, name):
    """``(value, step, edit)`` for the documented parameter ``name``: ``edit(v)`` is the case
    rebuilt from its data with the parameter set to ``v`` (SI)."""
    leg_name = name[len("legs["):name.index("]")] if name.startswith("legs[") else None
    if leg_name is not None:
        i = _leg_item(data, leg_name)
        leg = case.legs[i]
        field = name.split("].", 1)[1]
        if field in ("ea", "weight"):
            own_data, own = _own_line_type(data, leg_name)
            key = "ea" if field == "ea" else "weight_in_water"
            value = getattr(leg.line_type, key)
            return value, 1e-4 * abs(value), lambda v: moorsolve.load_case(
                with_values(own_data, {f"line_types.{own}.{key}": v}))
        if field == "length" or field.startswith("segments["):
            # The item of the case file's segment list (a clump is an item too).
            k = 0 if field == "length" else int(field[len("segments["):field.index("]")])
            value = float(data["legs"][i]["segments"][k]["length"])
            return value, 1e-5 * value, lambda v: moorsolve.load_case(
                with_values(data, {f"legs[{leg_name}].segments[{k}].length": v}))
        end, axis = field.split("_")
        point = leg.anchor if end == "anchor" else leg.fairlead
        k = "xyz".index(axis)
        bed = case.environment.seabed_z(leg.anchor[0], leg.anchor[1])
        on_seabed = end == "anchor" and leg.anchor[2] <= bed + 1e-9

        def move(v):
            p = list(point)
            p[k] = v
            # As the case file says it: an anchor on the seabed is given by [x, y].
            return moorsolve.load_case(with_values(data, {
                f"legs[{leg_name}].{end}": p[:2] if on_seabed else p}))
        return point[k], 1e-4, move
    if name.startswith("line_types["):
        type_name, key = name[len("line_types["):].split("].")
        value = getattr(case.line_types[type_name], key)
        return value, 1e-4 * abs(value), lambda v: moorsolve.load_case(
            with_values(data, {f"line_types.{type_name}.{key}": v}))
    if name.startswith("body.loads.force["):
        k = int(name[-2])
        value = case.body.loads.force[k]
        return value, max(1e-4 * abs(value), 1.0), lambda v: moorsolve.load_case(
            with_values(data, {name: v}))
    value = _get(data, name)
    step = 1e-4 if name.endswith("toward_deg") else 1e-5 * max(abs(value), 1.0)
    return value, step, lambda v: moorsolve.load_case(with_values(data, {name: v}))


def _get(data, path):
    node = data
    for part in path.split("."):
        node = node[part]
    return float(node)


def check_parameters(data, params, legs):
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case, tol=TOL)
    outputs = [o for o in ("x_m", "y_m", "yaw_deg")
               if result.body is not None and (o != "yaw_deg" or "yaw" in case.body.free)]
    outputs += [f"legs[{leg}].{f}" for leg in legs for f in LEG_OUTPUTS]
    sens = moorsolve.sensitivity(result, outputs, params)
    base = outputs_of(result, outputs)
    failures = []
    for j, p in enumerate(params):
        value, h, edit = editor(data, case, p)
        up = moorsolve.solve(edit(value + h), tol=TOL)
        down = moorsolve.solve(edit(value - h), tol=TOL)
        fd = (outputs_of(up, outputs) - outputs_of(down, outputs)) / (2 * h)
        ad = sens.matrix[:, j]
        scale = np.maximum(np.abs(fd), np.abs(ad))
        floor = 2e-9 * np.maximum(np.abs(base), 1.0) / h
        bad = np.abs(ad - fd) > 2e-5 * scale + floor
        failures += [(p, o, a, f) for o, a, f, b in zip(outputs, ad, fd, bad) if b]
    assert not failures, failures


def leg_parameters(leg, items=None, anchor_z=False):
    """A leg's parameters; ``items``: the case-file items of a multi-segment leg's
    segments (clumps are items too)."""
    names = ["anchor_x", "anchor_y", "fairlead_x", "fairlead_y", "fairlead_z"]
    names += ["anchor_z"] if anchor_z else []
    names += ["length", "ea", "weight"] if items is None else [
        f"segments[{k}].length" for k in items]
    return [f"legs[{leg}].{n}" for n in names]


ENVIRONMENT = ["environment.wind.speed", "environment.wind.toward_deg",
               "environment.current.speed", "environment.current.toward_deg",
               "environment.waves.hs", "environment.waves.toward_deg",
               "body.loads.force[0]", "body.loads.force[1]", "body.loads.force[2]"]
DOCK_LOADS = {"body.loads.force": [2.0e4, -1.0e4, 5.0e5]}


@pytest.mark.parametrize("gradient", [[0.0, 0.02], [0.04, 0.06], [-0.05, 0.04]])
@pytest.mark.parametrize("friction", [0.0, 0.5])
def test_sloped_dock(gradient, friction):
    """The shipped sloped dock and steeper slopes, with and without friction."""
    edits = {**DOCK_LOADS, "environment.seabed.gradient": gradient,
             "environment.seabed.friction": friction, "line_types.chain81.ea": 5.0e7}
    params = leg_parameters("L3") + leg_parameters("L9")[:2] + [
        "line_types[chain81].ea", "line_types[chain81].weight_in_water"] + ENVIRONMENT
    if friction:
        params.append("environment.seabed.friction")
    check_parameters(_source("floating_dock_sloped.yaml", edits), params, ["L3", "L9"])


def steep_buoy(gradient, friction):
    """A buoy on three 260 m chains in 100 m of water on a steep plane seabed."""
    legs = []
    for k, heading in enumerate((0.0, 120.0, 240.0)):
        a = np.radians(heading)
        legs.append({"name": f"L{k + 1}", "anchor": [220 * np.cos(a), 220 * np.sin(a)],
                     "fairlead": [2 * np.cos(a), 2 * np.sin(a), 0.0],
                     "segments": [{"type": "chain", "length": 260.0}]})
    return {"environment": {"depth": 100.0,
                            "seabed": {"gradient": gradient, "friction": friction}},
            "line_types": {"chain": {"weight_in_water": 900.0, "ea": 3e7}},
            "body": {"free": ["surge", "sway", "yaw"],
                     "loads": {"force": [3e4, 1e4, 2e5]}},
            "legs": legs}


@pytest.mark.parametrize("gradient", [[0.3, 0.1], [-0.2, 0.25]])
@pytest.mark.parametrize("friction", [0.0, 0.6])
def test_steep_slope(gradient, friction):
    """Steep slopes, where holding the anchor's z was 11 % to 3x off."""
    params = leg_parameters("L1") + leg_parameters("L2")[:2] + [
        "line_types[chain].ea", "body.loads.force[0]", "body.loads.force[2]"]
    if friction:
        params.append("environment.seabed.friction")
    check_parameters(steep_buoy(gradient, friction), params, ["L1", "L2", "L3"])


@pytest.mark.parametrize("friction", [0.0, 0.4])
def test_flat_buoy(friction):
    edits = {"environment.seabed.friction": friction, "line_types.chain.ea": 2.0e6,
             "body.loads.force": [500.0, 200.0, 0.0]}
    params = leg_parameters("W") + ["line_types[chain].weight_in_water",
                                    "environment.wind.speed", "environment.wind.toward_deg",
                                    "body.loads.force[0]", "body.loads.force[1]"]
    if friction:
        params.append("environment.seabed.friction")
    check_parameters(_source("buoy_vida.yaml", edits), params, ["W", "NNE"])


def test_multi_segment_legs_with_clumps():
    """A segment's length, and a line type used by two segments of every leg."""
    params = leg_parameters("NE", items=(0, 2, 3)) + [
        "line_types[chain84].ea", "line_types[chain84].weight_in_water",
        "line_types[polyester160].ea", "environment.current.speed",
        "body.loads.force[0]"]
    check_parameters(_source("chain_polyester_clump.yaml"), params, ["NE", "SW"])


def test_lumped_node_lines_in_a_current():
    """The current drags on the lines themselves: its heading moves them without any body
    current model (the derivative was once zero there)."""
    params = ["environment.current.toward_deg", "environment.current.speed",
              "line_types[chain].weight_in_water", "legs[W].anchor_x",
              "legs[W].segments[0].length", "environment.wind.speed"]
    check_parameters(_source("buoy_vida_current.yaml", {"solver.line_elements": 8}), params,
                     ["W", "NNE"])


def test_floating_line_and_anchor_above_the_seabed():
    """A buoyant hose floating to a surface buoy, and a chain from a pile head that sags
    onto the seabed: the surface and lifted blocks' derivatives."""
    data = {
        "environment": {"depth": 50.0},
        "line_types": {"hose": {"weight_in_water": -80.0, "ea": 5e6},
                       "chain": {"weight_in_water": 300.0, "ea": 5e7}},
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": [2e3, 1e3, 1e4]}},
        "legs": [
            {"name": "H", "anchor": [-90.0, 0.0], "fairlead": [-5.0, 0.0, 0.0],
             "segments": [{"type": "hose", "length": 130.0}]},
            {"name": "C", "anchor": [100.0, 40.0, -44.0], "fairlead": [5.0, 0.0, -2.0],
             "segments": [{"type": "chain", "length": 130.0}]},
            {"name": "D", "anchor": [60.0, -90.0], "fairlead": [0.0, -5.0, 0.0],
             "segments": [{"type": "chain", "length": 120.0}]}]}
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case)
    assert result.leg("H").floating_length_m > 0 and result.leg("C").grounded_length_m > 0
    # (The fairlead at the surface is a model edge: fairlead_z is refused there, below.)
    params = ([p for p in leg_parameters("H") if not p.endswith("fairlead_z")]
              + leg_parameters("C", anchor_z=True)
              + ["body.loads.force[0]", "body.loads.force[2]"])
    check_parameters(data, params, ["H", "C"])


def test_slope_moves_the_anchor_along_the_seabed():
    """On a 0.3 slope the anchor tension's derivative by the anchor's x equals differences
    of re-solved cases with the anchor kept on the seabed (holding its z, as the derivative
    once did, was 6 % to 36 % off here)."""
    data = steep_buoy([0.3, 0.1], 0.0)
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case, tol=TOL)
    out = "legs[L2].anchor_tension_N"
    x, y, _ = case.legs[1].anchor
    h = 1e-4

    def tension(anchor):
        moved = moorsolve.load_case(with_values(data, {"legs[L2].anchor": anchor}))
        return moorsolve.solve(moved, tol=TOL).leg("L2").anchor_tension_N
    for k, par in enumerate(("legs[L2].anchor_x", "legs[L2].anchor_y")):
        exact = moorsolve.sensitivity(result, out, par)[out, par]
        plus, minus = [x, y], [x, y]
        plus[k] += h
        minus[k] -= h
        along = (tension(plus) - tension(minus)) / (2 * h)
        assert exact == pytest.approx(along, rel=1e-5), par


def test_multi_segment_leg_refuses_a_leg_wide_length():
    result = moorsolve.solve(moorsolve.load_case(CASES / "chain_polyester_clump.yaml"))
    with pytest.raises(ValueError, match=r"segments\[K\]\.length"):
        moorsolve.sensitivity(result, "x_m", "legs[NE].length")


def test_fairlead_at_the_surface_refuses_a_depth_derivative():
    """A buoyant line floating up to a fairlead at the surface: lowered by d, the line must
    leave the surface to reach it (its vertical force grows like sqrt(d)); raised, the
    fairlead leaves the water. No derivative: refused with the reason."""
    case = moorsolve.load_case({
        "environment": {"depth": 50.0},
        "line_types": {"hose": {"weight_in_water": -80.0, "ea": 5e6}},
        "legs": [{"name": "H", "anchor": [0.0, 0.0], "fairlead": [85.0, 0.0, 0.0],
                  "segments": [{"type": "hose", "length": 130.0}]}]})
    result = moorsolve.solve(case)
    with pytest.raises(ValueError, match="surface"):
        moorsolve.sensitivity(result, "legs[H].fairlead_tension_N", "legs[H].fairlead_z")
