"""Bathymetry grids (issue 19, item 3): bilinear interpolation against hand values, the
gradient, the edges, and every validation message of the inline grid and the seabed block."""

import copy

import numpy as np
import pytest

from moorsolve import load_case
from moorsolve.errors import CaseError
from moorsolve.model.bathymetry import bathymetry_from_mapping

GRID = {"x": [0.0, 10.0, 30.0], "y": [0.0, 20.0],
        "depth": [[100.0, 104.0, 110.0],
                  [102.0, 110.0, 120.0]]}


def test_bilinear_heights_by_hand():
    g = bathymetry_from_mapping(GRID, "grid")
    # Nodes.
    assert g.height(10.0, 20.0) == -110.0
    assert g.height(0.0, 0.0) == -100.0
    # Cell (0..10, 0..20) at (5, 10): the mean of its four corners, 104.
    assert g.height(5.0, 10.0) == pytest.approx(-(100 + 104 + 102 + 110) / 4, abs=1e-12)
    # Cell (10..30) at x = 15 (fx = 1/4), y = 5 (fy = 1/4):
    # 104*(3/4)(3/4) + 110*(1/4)(3/4) + 110*(3/4)(1/4) + 120*(1/4)(1/4) = 107.25
    assert g.height(15.0, 5.0) == pytest.approx(-107.25, abs=1e-12)
    # Arrays of points give the same values.
    z = g.height(np.array([5.0, 15.0]), np.array([10.0, 5.0]))
    np.testing.assert_allclose(z, [-104.0, -107.25], atol=1e-12)


def test_held_constant_beyond_the_edges():
    g = bathymetry_from_mapping(GRID, "grid")
    assert g.height(-50.0, 0.0) == -100.0           # west of the grid: its edge
    assert g.height(60.0, 20.0) == -120.0           # past a corner: the corner
    assert g.height(-5.0, 10.0) == pytest.approx(-101.0)    # the edge's own interpolation
    assert g.gradient(-5.0, 10.0)[0] == 0.0         # no slope out there
    assert g.gradient(15.0, 50.0)[1] == 0.0


def test_gradient_by_hand_and_against_differences():
    g = bathymetry_from_mapping(GRID, "grid")
    gx, gy = g.gradient(15.0, 5.0)
    # dz/dx = -[(110-104)(3/4) + (120-110)(1/4)]/20; dz/dy = -[(110-104)(3/4)+(120-110)(1/4)]/20
    assert gx == pytest.approx(-(6 * 0.75 + 10 * 0.25) / 20, abs=1e-12)
    assert gy == pytest.approx(-(6 * 0.75 + 10 * 0.25) / 20, abs=1e-12)
    h = 1e-6
    assert gx == pytest.approx((g.height(15 + h, 5) - g.height(15 - h, 5)) / (2 * h), rel=1e-6)


def test_a_plane_is_reproduced_exactly_inside_the_grid():
    xs, ys = [-100.0, 0.0, 250.0], [-50.0, 80.0]
    g = bathymetry_from_mapping({"x": xs, "y": ys,
                                 "depth": [[50 - 0.01 * x + 0.03 * y for x in xs] for y in ys]},
                                "grid")
    rng = np.random.default_rng(1)
    x, y = rng.uniform(-100, 250, 50), rng.uniform(-50, 80, 50)
    np.testing.assert_allclose(g.height(x, y), -(50 - 0.01 * x + 0.03 * y), atol=1e-12)
    assert g.gradient(30.0, 10.0) == pytest.approx((0.01, -0.03), abs=1e-15)


def _leg_case(seabed):
    return {"environment": {"depth": 100.0, "seabed": seabed},
            "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5e8}},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [20.0, 0.0, -5.0],
                      "segments": [{"type": "chain", "length": 120}]}]}


def _edit(grid_edit=None, seabed_edit=None):
    grid = copy.deepcopy(GRID)
    if grid_edit:
        grid_edit(grid)
    seabed = {"bathymetry": grid}
    if seabed_edit:
        seabed_edit(seabed)
    return _leg_case(seabed)


@pytest.mark.parametrize("data, field, words", [
    (_edit(lambda g: g.update(x=[0.0, 30.0, 10.0])), "environment.seabed.bathymetry.x[2]",
     "strictly increasing"),
    (_edit(lambda g: g.update(y=[0.0, 0.0])), "environment.seabed.bathymetry.y[1]",
     "strictly increasing"),
    (_edit(lambda g: g.update(x=[])), "environment.seabed.bathymetry.x", "is empty"),
    (_edit(lambda g: g.update(x=[0.0, "a", 3.0])), "environment.seabed.bathymetry.x[1]",
     "not a finite number"),
    (_edit(lambda g: g["depth"].pop()), "environment.seabed.bathymetry.depth",
     "1 rows for 2 y values"),
    (_edit(lambda g: g["depth"][1].pop()), "environment.seabed.bathymetry.depth[1]",
     "2 depths for 3 x values"),
    (_edit(lambda g: g["depth"][0].__setitem__(1, -3.0)),
     "environment.seabed.bathymetry.depth[0][1]", "must be > 0"),
    (_edit(lambda g: g["depth"][1].__setitem__(2, float("nan"))),
     "environment.seabed.bathymetry.depth[1][2]", "not a finite depth"),
    (_edit(lambda g: g.pop("y")), "environment.seabed.bathymetry.y", "required"),
    (_edit(lambda g: g.update(z=1)), "environment.seabed.bathymetry.z", "unknown key"),
    (_leg_case({"bathymetry": [1, 2]}), "environment.seabed.bathymetry", "is not a grid"),
    (_edit(seabed_edit=lambda s: s.update(gradient=[0.0, 0.01])),
     "environment.seabed.bathymetry", "not both"),
    (_leg_case({"tolerance": 0.2}), "environment.seabed.tolerance", "bathymetry grid only"),
    (_edit(seabed_edit=lambda s: s.update(tolerance=-1)), "environment.seabed.tolerance",
     "must be > 0"),
])
def test_validation_names_the_field(data, field, words):
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == field
    assert words in str(err.value)


def test_anchors_sit_on_the_grid_and_below_it_is_refused():
    case = load_case(_leg_case({"bathymetry": GRID}))
    assert case.lines[0].a.position[2] == -100.0
    assert case.lines[0].a.on_seabed
    data = _leg_case({"bathymetry": GRID})
    data["legs"][0]["anchor"] = [5.0, 10.0, -104.5]          # the surface is at -104 there
    with pytest.raises(CaseError, match="below the seabed") as err:
        load_case(data)
    assert err.value.field == "legs[0].anchor[2]"


def test_what_the_grid_does_not_model_is_refused_by_name():
    data = _leg_case({"bathymetry": GRID})
    data["legs"][0]["segments"] = [{"type": "chain", "length": 60},
                                   {"type": "chain", "length": 60}]
    with pytest.raises(CaseError, match="one-segment legs") as err:
        load_case(data)
    assert err.value.field == "legs[0].segments"
    data = _leg_case({"bathymetry": GRID})
    data["line_types"]["chain"].update(diameter=0.1, drag={"normal": 1.2, "tangential": 0.1})
    data["environment"]["current"] = {"speed": 0.5}
    with pytest.raises(CaseError, match="lumped-node"):
        load_case(data)
