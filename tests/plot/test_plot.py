"""Pictures (issue 18): what the scene reads from a Result, and that every view draws it
whole (nothing clipped off the figure), takes an Axes and returns it, and never shows."""

from __future__ import annotations

import copy
import math

import matplotlib
import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve.plot import (plot_3d, plot_elevation, plot_envelope, plot_equilibrium,
                            plot_plan, plot_profiles, plot_restoring, scene_of, view_direction)
from moorsolve.plot.style import line_colours

from conftest import CASES

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHIPPED = sorted(p.name for p in CASES.glob("*.yaml"))


@pytest.fixture(autouse=True)
def _no_show(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("a plot function called plt.show()")
    monkeypatch.setattr(plt, "show", refuse)
    yield
    plt.close("all")


def _solve(name, **kwargs):
    return moorsolve.solve(moorsolve.load_case(CASES / name), **kwargs)


def _inside_figure(fig) -> None:
    """Every Axes (colour bars, insets and legends included) lies within the figure."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    for artist in fig.axes + fig.legends:
        tight = artist.get_tightbbox(renderer)
        assert tight.x0 >= box.x0 - 1 and tight.y0 >= box.y0 - 1, artist
        assert tight.x1 <= box.x1 + 1 and tight.y1 <= box.y1 + 1, artist


# ---- the scene -------------------------------------------------------------------------


@pytest.mark.parametrize("name", SHIPPED)
def test_scene_lines_run_from_anchor_to_fairlead(name):
    result = _solve(name)
    scene = scene_of(result)
    assert [line.name for line in scene.lines] == [leg.name for leg in result.legs]
    for line, leg in zip(scene.lines, result.legs):
        scale = max(result.case.environment.depth, 1.0)
        assert np.allclose(line.xyz[0], leg.anchor, atol=1e-6 * scale)
        assert np.allclose(line.xyz[-1], leg.fairlead, atol=1e-6 * scale)
        assert line.tension_N >= max(leg.fairlead_tension_N, leg.anchor_tension_N)


def test_scene_reads_the_sloped_seabed():
    result = _solve("floating_dock_sloped.yaml")
    scene = scene_of(result)
    env = result.case.environment
    assert scene.sloped
    for line in scene.lines:
        assert scene.seabed_z(*line.anchor[:2]) == pytest.approx(line.anchor[2], abs=1e-9)
        assert scene.seabed_z(*line.anchor[:2]) == pytest.approx(
            env.seabed_z(*line.anchor[:2]), abs=1e-12)
    # The lines lie on the seabed where they say they do, and nowhere below it.
    for line in scene.lines:
        below = line.xyz[:, 2] - scene.seabed_z(line.xyz[:, 0], line.xyz[:, 1])
        assert below.min() > -1e-6 and np.all(np.abs(below[line.grounded]) < 1e-4)


def test_scene_has_the_clumps_and_buoys():
    clumps = scene_of(_solve("chain_polyester_clump.yaml"))
    kinds = [p.kind for p in clumps.points]
    assert kinds.count("clump") == 4 and all(p.weight_N > 0 for p in clumps.points
                                             if p.kind == "clump")
    with open(CASES / "chain_polyester_clump.yaml", encoding="utf-8") as f:
        data = yaml.safe_load(f)
    for leg in data["legs"]:
        for item in leg["segments"]:
            if "clump" in item:
                item["clump"] = {"weight": -2.0e4}           # a 2 t buoy in place of the clump
    buoyed = scene_of(moorsolve.solve(moorsolve.load_case(data)))
    assert [p.kind for p in buoyed.points].count("buoy") == 4


def test_body_outline_moves_with_the_body():
    result = _solve("floating_dock.yaml")
    (body,) = scene_of(result).bodies
    assert np.allclose(body.origin[:2], [result.body["x_m"], result.body["y_m"]])
    assert np.allclose(body.offset[:2], [result.body["x_m"], result.body["y_m"]])
    fair = np.array([leg.fairlead[:2] for leg in result.case.legs])
    # At rest the outline is the case-file fairleads' hull: its corners are fairleads.
    for corner in body.outline_rest[:, :2]:
        assert np.min(np.linalg.norm(fair - corner, axis=1)) < 1e-9
    # At equilibrium every corner is a fairlead turned by the yaw and shifted by the offset.
    c, s = math.cos(math.radians(result.body["yaw_deg"])), math.sin(
        math.radians(result.body["yaw_deg"]))
    moved = fair @ np.array([[c, s], [-s, c]]) + body.origin[:2]
    for corner in body.outline[:, :2]:
        assert np.min(np.linalg.norm(moved - corner, axis=1)) < 1e-6


def test_view_direction_follows_the_scene():
    assert view_direction(scene_of(_solve("floating_dock.yaml"))) == 0.0
    assert view_direction(scene_of(_solve("ship_97m.yaml"))) == 0.0
    with open(CASES / "ship_97m.yaml", encoding="utf-8") as f:
        data = yaml.safe_load(f)
    turn = math.radians(30.0)
    rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
    for leg in data["legs"]:
        leg["anchor"][:2] = (rot @ np.array(leg["anchor"][:2], float)).tolist()
        leg["fairlead"][:2] = (rot @ np.array(leg["fairlead"][:2], float)).tolist()
    data["body"] = {"free": [], "loads": {}}          # held where the case puts it
    turned = moorsolve.solve(moorsolve.load_case(data))
    assert view_direction(scene_of(turned)) == pytest.approx(30.0, abs=0.5)


# ---- colouring -------------------------------------------------------------------------


def test_overloaded_line_is_on_the_colour_bar_not_clipped():
    data = {"name": "short", "environment": {"depth": 50.0},
            "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5e8, "mbl": 5e6}},
            "legs": [{"name": "L1", "anchor": [-130.0, 0.0], "fairlead": [0.0, 0.0, 0.0],
                      "segments": [{"type": "chain", "length": 130.0}]},
                     {"name": "L2", "anchor": [300.0, 0.0], "fairlead": [0.0, 0.0, 0.0],
                      "segments": [{"type": "chain", "length": 400.0}]}]}
    result = moorsolve.solve(moorsolve.load_case(data), allow_overload=True)
    scene = scene_of(result)
    colour, mappable, label = line_colours(scene)
    worst = max(line.t_over_mbl for line in scene.lines)
    assert worst > 1 and mappable.norm.vmax == pytest.approx(worst)
    assert "T/MBL" in label
    top = mappable.cmap(1.0)
    assert colour(max(scene.lines, key=lambda line: line.t_over_mbl)) == pytest.approx(top)
    fig = plot_equilibrium(result)
    _inside_figure(fig)


def test_tension_colouring_without_mbl():
    scene = scene_of(_solve("buoy_vida.yaml"))
    assert scene.colour_by == "tension"
    _, mappable, label = line_colours(scene)
    assert mappable.norm.vmax == pytest.approx(max(line.tension_N for line in scene.lines) / 1e3)


# ---- the views ------------------------------------------------------------------------


@pytest.mark.parametrize("name", SHIPPED)
def test_equilibrium_figure_is_whole(name):
    fig = plot_equilibrium(_solve(name))
    assert len([ax for ax in fig.axes if ax.name == "3d"]) == 1
    _inside_figure(fig)


@pytest.mark.parametrize("view", [plot_plan, plot_elevation, plot_3d, plot_profiles])
def test_views_draw_on_the_axes_given_and_return_it(view):
    result = _solve("chain_polyester_clump.yaml")
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d" if view is plot_3d else None)
    assert view(result, ax) is ax
    assert ax.lines                                 # something was drawn on it
    assert len(fig.axes) >= 1


def test_elevation_is_a_projection_with_the_seabed_band():
    result = _solve("floating_dock_sloped.yaml")
    ax = plot_elevation(result, along_deg=90.0)
    scene = scene_of(result)
    drawn = [line.get_xydata() for line in ax.lines]
    for line in scene.lines:
        expected = np.column_stack([line.xyz[:, 1], line.xyz[:, 2]])
        assert any(d.shape == expected.shape and np.allclose(d, expected) for d in drawn)
    assert "vertical x" in ax.get_title()


def test_plan_shows_loads_offset_scale_and_north():
    result = _solve("floating_dock.yaml")
    ax = plot_plan(result)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for name, (fx, fy, _) in result.loads.items():
        assert any(t.startswith(f"{name.replace('_', ' ')} load") for t in labels), name
    assert any(t.startswith("offset 0.971 m") for t in labels)
    assert any(a.get_title() == "body loads" for a in ax.child_axes)
    scale = [a for a in ax.artists if type(a).__name__ == "AnchoredSizeBar"]
    assert len(scale) == 1
    # A compass case gets a north arrow.
    with open(CASES / "floating_dock.yaml", encoding="utf-8") as f:
        data = yaml.safe_load(f)
    data["environment"]["directions"] = "nautical"
    nautical = plot_plan(moorsolve.solve(moorsolve.load_case(data)))
    assert any(t.get_text() == "N" for t in nautical.texts)


# ---- studies ---------------------------------------------------------------------------


def test_envelope_rings_what_each_plot_shows():
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    env = moorsolve.offset_envelope(case, step_deg=30)
    ax_off, ax_t = plot_envelope(env)
    far, worst = env.largest_offset(), env.worst()
    assert f"largest offset {far['offset_m']:.3f} m" in ax_off.get_xlabel()
    assert f"toward {far['heading_deg']:g} deg" in ax_off.get_xlabel()
    assert f"({worst['worst_leg']}),\nwind toward {worst['heading_deg']:g} deg" \
        in ax_t.get_xlabel()
    ring = [line for line in ax_t.lines if line.get_markersize() == 12][0]
    assert ring.get_xdata()[0] == pytest.approx(math.radians(worst["heading_deg"]))


def test_restoring_curve_marks_the_operating_point_and_tangent():
    case = moorsolve.load_case(CASES / "floating_dock.yaml")
    result = moorsolve.solve(case)
    K = moorsolve.stiffness(result)
    about = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
    curve = moorsolve.restoring_curve(case, "surge", [-1.0, 0.0, 1.0], about=about)
    ax = plot_restoring(curve, stiffness=K)
    ring = [line for line in ax.lines if line.get_marker() == "o" and line.get_markersize() == 10]
    f0 = curve["force"][1, 0] / 1e3
    assert ring[0].get_ydata()[0] == pytest.approx(f0)
    # At equilibrium the mooring force balances the body loads.
    assert f0 * 1e3 == pytest.approx(-sum(v[0] for v in result.loads.values()), rel=1e-6)
    tangent = [line for line in ax.lines if line.get_linestyle() == "--"][0]
    x, y = tangent.get_xdata(), tangent.get_ydata()
    assert (y[1] - y[0]) / (x[1] - x[0]) == pytest.approx(-K[0, 0] / 1e3)


def test_no_matplotlib_on_import():
    import subprocess
    import sys
    code = ("import sys, moorsolve, moorsolve.plot; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "False", out.stderr


def test_scene_keeps_the_case_untouched():
    result = _solve("floating_dock.yaml")
    before = copy.deepcopy(result.to_dict())
    plot_equilibrium(result)
    assert result.to_dict() == before
