"""Free points on a bathymetry grid: each rests on the plane that touches the grid where it
lies (moorsolve/solve/bathymetry.py), found with the lines' planes by the same fixed-point
iteration.

References: a grid that samples one plane reproduces the plane-seabed solve (an established
path) to round-off; on a curved grid the point lies on the grid's surface and the scene
equals a plane-seabed solve whose plane is the grid's tangent plane at the point found
(independent: the plane solver knows nothing of the grid); a MoorDyn file with a free point
over a SeafloorFile imports (network form) and solves.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
from conftest import DATA

import moorsolve
from moorsolve import load_case, solve


def _grid(xs, ys, depth):
    return {"x": [float(v) for v in xs], "y": [float(v) for v in ys],
            "depth": [[float(depth(x, y)) for x in xs] for y in ys]}


def _clump_scene(seabed) -> dict:
    """A clump resting on the seabed between a line up to a buoy-like fixed point and a
    line to a fixed point 20 m above the seabed (no line lies on the seabed)."""
    return {"environment": {"depth": 100.0, "seabed": seabed},
            "line_types": {"chain": {"weight_in_water": 800.0, "ea": 5e8}},
            "points": [{"name": "post", "position": [0.0, 0.0, -75.0]},
                       {"name": "clump", "position": [150.0, 10.0, -80.0], "free": True,
                        "mass": 20000.0, "volume": 1.0},
                       {"name": "top", "position": [330.0, 40.0, -10.0]}],
            "lines": [{"name": "low", "from": "post", "to": "clump",
                       "segments": [{"type": "chain", "length": 152.5}]},
                      {"name": "high", "from": "clump", "to": "top",
                       "segments": [{"type": "chain", "length": 203.5}]}]}


def _bump(x, y):
    """Depth [m]: 95 m, with a mound 4 m high around (150, 0)."""
    return 95.0 - 4.0 * np.exp(-((x - 150.0) ** 2 + y ** 2) / 100.0 ** 2)


def _compare(a, b, rel):
    pa, pb = a.points[0], b.points[0]
    for k in ("x_m", "y_m", "z_m"):
        assert pa[k] == pytest.approx(pb[k], abs=rel * 100.0), k
    assert pa["seabed_reaction_N"] == pytest.approx(pb["seabed_reaction_N"], rel=rel)
    for la, lb in zip(a.lines, b.lines):
        assert la.fairlead_tension_N == pytest.approx(lb.fairlead_tension_N, rel=rel)
        assert la.anchor_tension_N == pytest.approx(lb.anchor_tension_N, rel=rel)


def test_a_grid_holding_a_plane_is_the_plane_seabed():
    plane = _clump_scene({"gradient": [0.01, -0.005]})
    grid = _clump_scene({"bathymetry": _grid([-100, 120, 400], [-100, 50, 200],
                                             lambda x, y: 100.0 - 0.01 * x + 0.005 * y)})
    a, b = solve(load_case(plane)), solve(load_case(grid))
    assert a.points[0]["seabed_reaction_N"] > 1e4          # it rests on the seabed
    _compare(a, b, 1e-9)


def test_on_a_curved_grid_the_point_rests_on_the_surface_as_on_its_tangent_plane():
    """On the flank of a mound the clump lies on the grid's surface (to 1e-9 m), and the
    plane-seabed solve on the tangent plane at that point gives the same scene (to the
    iteration's settling tolerance)."""
    xs, ys = np.linspace(-100, 400, 101), np.linspace(-150, 150, 61)
    grid = _clump_scene({"bathymetry": _grid(xs, ys, _bump)})
    result = solve(load_case(grid))
    pt = result.points[0]
    env = result.case.environment
    assert pt["seabed_reaction_N"] > 1e4
    assert pt["z_m"] == pytest.approx(env.seabed_z(pt["x_m"], pt["y_m"]), abs=1e-9)
    gx, gy = env.seabed.slope_at(pt["x_m"], pt["y_m"])
    assert abs(gx) + abs(gy) > 0.01                         # on the flank, not the top
    z0 = env.seabed_z(pt["x_m"], pt["y_m"])
    depth0 = -(z0 - gx * pt["x_m"] - gy * pt["y_m"])
    tangent = _clump_scene({"gradient": [gx, gy]})
    tangent["environment"]["depth"] = depth0
    for p in tangent["points"][::2]:                        # fixed points: same heights
        p["position"][2] = max(p["position"][2], -depth0 + gx * p["position"][0]
                               + gy * p["position"][1])
    # The last solve's plane touches the grid where the point was a round before (it
    # settles to 1e-6 of the depth): the scenes agree to that (measured 4.7e-7).
    _compare(result, solve(load_case(tangent)), 2e-6)
    assert any("settled" in n for n in result.notes)


def test_a_moordyn_file_with_a_free_point_on_a_seafloor_file_solves():
    """A clump on the first chain of a three-leg MoorDyn file over its SeafloorFile (a
    0.4 % slope): imported in the network form (the grid takes free points as points),
    the clump put on the grid where the file had it below, solved; the same as with the
    plane seabed (a line lies flat between anchor and clump, which certifies at 1e-8)."""
    path = DATA / "moordyn_bathymetry" / "free_point_seafloor_v2.dat"
    from moorsolve.io.moordyn import convert_moordyn
    imp = convert_moordyn(moorsolve.read_moordyn(path))
    assert imp.form == "network" and "bathymetry grid" in imp.form_reason
    data = imp.data
    clump = next(p for p in data["points"] if p.get("free"))
    assert clump["position"][2] == pytest.approx(-100.0 + 0.004 * 450.0, abs=1e-9)
    grid = solve(load_case(data), tol=1e-8)
    plane = copy.deepcopy(data)
    plane["environment"]["seabed"] = {"gradient": [0.004, 0.0]}
    _compare(grid, solve(load_case(plane), tol=1e-8), 1e-7)
