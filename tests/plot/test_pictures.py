"""Pictures for a report: hulls drawn from the case's geometry, the berth in every view,
every drawn thing inside its Axes, labels that do not collide, bollards called bollards,
one direction convention per case, and no warning while drawing any shipped case."""

from __future__ import annotations

import itertools
import math
import warnings

import matplotlib
import numpy as np
import pytest

import moorsolve
from moorsolve.plot import plot_3d, plot_elevation, plot_equilibrium, plot_plan, scene_of
from moorsolve.plot.labels import LABEL_GID

from conftest import CASES

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHIPPED = sorted(p.name for p in CASES.glob("*.yaml"))


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


_SOLVED: dict = {}


def _solve(name):
    if name not in _SOLVED:
        _SOLVED[name] = moorsolve.solve(moorsolve.load_case(CASES / name))
    return _SOLVED[name]


def _solve_without_outline(name, key="outline"):
    """The shipped case ``name`` with its drawn ``outline`` (or ``outline_members``) taken
    away."""
    import yaml
    data = yaml.safe_load((CASES / name).read_text(encoding="utf-8"))
    for body in [data.get("body")] + list(data.get("bodies") or []):
        if body:
            body.pop(key, None)
    from moorsolve.model import build_case
    return moorsolve.solve(build_case(data, name))


def _sides(ring: np.ndarray) -> np.ndarray:
    return np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T)


def _heading(ring: np.ndarray) -> float:
    """Direction [deg] of the ring's first side (its body-x side for a rectangle)."""
    d = ring[1] - ring[0]
    return math.degrees(math.atan2(d[1], d[0]))


# ---- hulls ---------------------------------------------------------------------------------


def test_box_member_drawn_at_its_plan_dimensions_and_pose():
    """The pontoon's hull member (a 30 m x 8 m box) is drawn as that box, turned by the
    solved yaw about the solved origin; in the plan it is a filled polygon with those
    corners."""
    result = _solve("pontoon_piles.yaml")
    (body,) = scene_of(result).bodies
    (shape,) = body.shapes
    member = result.case.bodies[0].hull[0]
    pose = result.bodies[0]
    assert shape.kind == "box"
    np.testing.assert_allclose(_sides(shape.ring), [member.length, member.width] * 2,
                               rtol=1e-12)
    np.testing.assert_allclose(shape.ring.mean(axis=0), [pose["x_m"], pose["y_m"]],
                               atol=1e-9)
    assert _heading(shape.ring) == pytest.approx(pose["yaw_deg"], abs=1e-9)
    assert shape.bottom == pytest.approx(pose["z_m"] + member.bottom)
    assert shape.top == pytest.approx(pose["z_m"] + member.top)
    ax = plot_plan(result)
    drawn = [p.get_xy() for p in ax.patches if hasattr(p, "get_xy") and len(p.get_xy()) == 5]
    assert any(np.allclose(xy[:4], shape.ring, atol=1e-9) for xy in drawn)


def test_length_and_beam_of_the_case_make_the_hull():
    """The dock's drift model gives 246.4 m x 51 m: the hull drawn is that rectangle at the
    solved pose; the ship's beam alone (15.8 m) is completed by twice its bow fairlead's
    distance from the origin (48.5 m: the 97 m of the case's title)."""
    dock = _solve("floating_dock.yaml")
    (shape,) = scene_of(dock).bodies[0].shapes
    assert shape.kind == "dimensions"
    np.testing.assert_allclose(_sides(shape.ring), [246.4, 51.0] * 2, rtol=1e-12)
    assert _heading(shape.ring) == pytest.approx(dock.body["yaw_deg"], abs=1e-9)
    np.testing.assert_allclose(shape.ring.mean(axis=0), [dock.body["x_m"], dock.body["y_m"]],
                               atol=1e-9)
    ship = _solve_without_outline("ship_97m.yaml")
    (shape,) = scene_of(ship).bodies[0].shapes
    np.testing.assert_allclose(_sides(shape.ring), [97.0, 15.8] * 2, rtol=1e-12)


@pytest.mark.parametrize("name, length, beam, draft, freeboard", [
    ("ship_97m.yaml", 97.0, 15.8, 3.8, 3.9),          # Hu & Tang (2004), example 1
    ("ship_berth.yaml", 200.0, 32.0, 11.5, 8.0),
    ("turret_ship.yaml", 160.0, 28.0, 9.0, 12.0),
])
def test_a_ship_outline_is_drawn_as_a_ship(name, length, beam, draft, freeboard):
    """A body's ``outline`` is drawn at the solved pose: as long and as broad as the case
    says (measured along and across its heading), its stem on the bow side, from the draft
    to the freeboard; the pictures' legend says where it came from."""
    result = _solve(name)
    body = scene_of(result).bodies[0]
    (shape,) = [s for s in body.shapes if s.kind == "ship"]
    pose = result.bodies[0]
    yaw = pose["yaw_deg"]
    along = np.array([math.cos(math.radians(yaw)), math.sin(math.radians(yaw))])
    across = np.array([-along[1], along[0]])
    assert np.ptp(shape.ring @ along) == pytest.approx(length, rel=1e-12)
    assert np.ptp(shape.ring @ across) == pytest.approx(beam, rel=1e-12)
    # The stem (the one point at the bow's end) is on the centreline, half a length ahead
    # of the body origin (midship).
    stem = shape.ring[np.argmax(shape.ring @ along)] - [pose["x_m"], pose["y_m"]]
    assert stem @ along == pytest.approx(length / 2, rel=1e-12)
    assert abs(stem @ across) < 1e-9 * length
    assert shape.top - shape.bottom == pytest.approx(draft + freeboard, rel=1e-12)
    texts = [t.get_text() for t in plot_plan(result).get_legend().get_texts()]
    assert any("ship outline from the case" in t for t in texts)


def test_without_hull_geometry_the_outline_of_the_line_ends_says_so():
    """A body the case gives no hull for is drawn through its line ends, fender points and
    origin, and the legend says that no hull was given."""
    result = _solve_without_outline("ship_berth.yaml")
    (body,) = scene_of(result).bodies
    (shape,) = body.shapes
    assert shape.kind == "fairleads"
    assert shape.top == pytest.approx(8.0)               # fairleads on deck
    for f in result.fenders:                             # the ship's side is inside it
        from matplotlib.path import Path
        assert Path(shape.ring).contains_point(f["contact_point_m"][:2], radius=1e-6) or \
            np.min(np.linalg.norm(shape.ring - f["contact_point_m"][:2], axis=1)) < 1e-6
    ax = plot_plan(result)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("no hull given" in t for t in texts)


# ---- the berth in every view ---------------------------------------------------------------


def _gids(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def test_berth_in_plan_elevation_and_3d():
    result = _solve("ship_berth.yaml")
    scene = scene_of(result)
    assert len(scene.berth.walls) == 1 and len(scene.berth.fenders) == 4
    for view in (plot_plan, plot_elevation, plot_3d):
        ax = view(scene)
        assert len(_gids(ax, "wall")) == 1, view.__name__
        assert len(_gids(ax, "fender")) == 4, view.__name__
    piles = _solve("pontoon_piles.yaml")
    for view in (plot_plan, plot_elevation, plot_3d):
        ax = view(scene_of(piles))
        assert len(_gids(ax, "pile")) == 2, view.__name__


def test_bollards_are_not_anchors():
    """Fixed points on the quay above water are bollards in the scene and the legend."""
    result = _solve("ship_berth.yaml")
    scene = scene_of(result)
    assert {line.a_kind for line in scene.lines} == {"bollard"}
    ax = plot_plan(scene)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(t.startswith("bollard") for t in texts)
    assert "anchor" not in texts
    chains = scene_of(_solve("dock_quay.yaml"))
    assert {line.a_kind for line in chains.lines} == {"anchor", "bollard"}


# ---- everything inside its Axes ------------------------------------------------------------


def _contains(lo, hi, values, slack):
    return np.all(values >= lo - slack) and np.all(values <= hi + slack)


@pytest.mark.parametrize("name", SHIPPED)
def test_axes_hold_every_line_point_and_wall(name):
    """Plan, elevation and 3-D limits contain every line point, hull, wall and fender
    (hawsers to fairleads on deck included)."""
    result = _solve(name)
    fig = plot_equilibrium(result)
    scene = scene_of(result)
    pts = scene.drawn_points()
    axes = {ax.get_label(): ax for ax in fig.axes}
    plan, elev, view3d = (next(a for a in fig.axes if a.get_title().startswith(word))
                          for word in ("plan", "elevation", "3-D"))
    del axes
    size = float(np.ptp(pts[:, :2], axis=0).max()) + 1.0
    slack = 1e-9 * size
    for ax, (i, j) in ((plan, (0, 1)),):
        assert _contains(*ax.get_xlim(), pts[:, i], slack), name
        assert _contains(*ax.get_ylim(), pts[:, j], slack), name
    from moorsolve.plot.views import view_direction
    theta = math.radians(view_direction(scene))
    s = pts[:, :2] @ np.array([math.cos(theta), math.sin(theta)])
    assert _contains(*elev.get_xlim(), s, slack), name
    assert _contains(*elev.get_ylim(), pts[:, 2], slack), name
    assert _contains(*view3d.get_xlim(), pts[:, 0], slack), name
    assert _contains(*view3d.get_ylim(), pts[:, 1], slack), name
    assert _contains(*view3d.get_zlim(), pts[:, 2], slack), name
    for wall in scene.berth.walls:
        assert _contains(*elev.get_ylim(), np.array([wall.top]), slack)
        assert _contains(*view3d.get_zlim(), np.array([wall.top]), slack)


# ---- labels ----------------------------------------------------------------------------------


@pytest.mark.parametrize("name", SHIPPED)
def test_no_label_overlaps_another(name):
    """On the saved figure of every shipped case, no label's box overlaps another's, and
    every label is inside its Axes."""
    fig = plot_equilibrium(_solve(name))
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        boxes = [t.get_window_extent(renderer) for t in ax.texts if t.get_gid() == LABEL_GID]
        frame = ax.get_window_extent(renderer)
        for a, b in itertools.combinations(boxes, 2):
            w = min(a.x1, b.x1) - max(a.x0, b.x0)
            h = min(a.y1, b.y1) - max(a.y0, b.y0)
            assert w <= 0.5 or h <= 0.5, (name, a, b)
        for a in boxes:
            assert frame.x0 - 1 <= a.x0 and a.x1 <= frame.x1 + 1, (name, a)
            assert frame.y0 - 1 <= a.y0 and a.y1 <= frame.y1 + 1, (name, a)
    plan = next(a for a in fig.axes if a.get_title().startswith("plan"))
    labelled = [t for t in plan.texts if t.get_gid() == LABEL_GID]
    assert labelled, name


def test_berth_labels_apart():
    """The labels the issue saw collide: stern1/stern2, head1/head2, the fenders."""
    fig = plot_equilibrium(_solve("ship_berth.yaml"))
    fig.canvas.draw()
    plan = next(a for a in fig.axes if a.get_title().startswith("plan"))
    texts = {t.get_text().split()[0]: t for t in plan.texts if t.get_gid() == LABEL_GID}
    for name in ("stern1", "stern2", "head1", "head2", "F1", "F2", "F3", "F4"):
        assert name in texts
    assert any(k.startswith("quay") for k in texts)


# ---- layout and warnings ---------------------------------------------------------------------


@pytest.mark.parametrize("name", SHIPPED)
def test_every_shipped_case_draws_without_warnings(name, tmp_path):
    """Headless, no warning (matplotlib's layout included), and nothing off the figure."""
    result = _solve(name)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig = plot_equilibrium(result)
        fig.savefig(tmp_path / "x.png", dpi=60)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    for artist in fig.axes + [a.get_legend() for a in fig.axes if a.get_legend()]:
        tight = artist.get_tightbbox(renderer)
        assert tight.x0 >= box.x0 - 2 and tight.y0 >= box.y0 - 2, (name, artist)
        assert tight.x1 <= box.x1 + 2 and tight.y1 <= box.y1 + 2, (name, artist)


def test_layout_follows_the_plan_shape():
    """A plan much wider than tall goes above the elevation and 3-D view."""
    fig = plot_equilibrium(_solve("ship_berth.yaml"))
    plan = next(a for a in fig.axes if a.get_title().startswith("plan"))
    elev = next(a for a in fig.axes if a.get_title().startswith("elevation"))
    assert plan.get_position().y0 > elev.get_position().y1
    fig = plot_equilibrium(_solve("floating_dock.yaml"))
    plan = next(a for a in fig.axes if a.get_title().startswith("plan"))
    elev = next(a for a in fig.axes if a.get_title().startswith("elevation"))
    assert plan.get_position().x1 < elev.get_position().x0


# ---- one direction convention per case -----------------------------------------------------


def test_nautical_case_speaks_in_bearings():
    """A nautical case: the envelope's repr names the worst heading as the file does
    (wind from a bearing), and the elevation's title and axis speak in bearings."""
    import yaml
    from moorsolve.studies.envelope import offset_envelope
    with open(CASES / "buoy_vida.yaml", encoding="utf-8") as f:
        data = yaml.safe_load(f)
    env = data["environment"]
    env["directions"] = "nautical"
    for flow in ("wind", "current", "waves"):
        if flow in env:
            env[flow].pop("toward_deg", None)
            env[flow]["from_deg"] = 45.0
    case = moorsolve.load_case(data)
    envelope = offset_envelope(case, step_deg=90.0)
    text = repr(envelope)
    i = int(np.nanargmax(envelope.worst_tension_N))
    assert f"{envelope.flows[0]} from {envelope.file_heading(i):g} deg (compass)" in text
    worst = envelope.worst()
    assert f"worst {worst['worst_leg']} with" in text
    assert worst["case_heading"]["deg"] == pytest.approx(envelope.file_heading(i))
    ax = plot_elevation(moorsolve.solve(case))
    assert "compass" in ax.get_title() and "compass" in ax.get_xlabel()


# ---- the interactive view (optional extra) ---------------------------------------------------


def test_interactive_view_draws_the_scene():
    """Every line from end to end, the box hull as a prism of the box's size, the quay wall
    and the fenders, with the vertical exaggeration the title states."""
    pytest.importorskip("plotly")
    from moorsolve.plot import plot_3d_interactive
    result = _solve("pontoon_piles.yaml")
    scene = scene_of(result)
    fig = plot_3d_interactive(result)
    lines = {t.name.split()[0]: t for t in fig.data if t.type == "scatter3d"
             and t.mode == "lines" and t.name.split()[0] in {l.name for l in scene.lines}}
    for line in scene.lines:
        t = lines[line.name]
        np.testing.assert_allclose([t.x[0], t.y[0], t.z[0]], line.xyz[0])
        np.testing.assert_allclose([t.x[-1], t.y[-1], t.z[-1]], line.xyz[-1])
    (hull,) = [t for t in fig.data if t.type == "mesh3d" and "hull" in t.name]
    (shape,) = scene.bodies[0].shapes
    assert min(hull.z) == pytest.approx(shape.bottom) and max(hull.z) == pytest.approx(shape.top)
    np.testing.assert_allclose(sorted(set(np.round(hull.x, 9))), sorted(set(np.round(
        shape.ring[:, 0], 9))))
    assert sum(t.type == "scatter3d" and t.name in ("P1", "P2") for t in fig.data) == 2
    berth = plot_3d_interactive(_solve("ship_berth.yaml"))
    names = [t.name for t in berth.data]
    assert "quay (wall)" in names and "fenders" in names
    # The box's proportions are the scene's, the vertical times the title's factor.
    gain = float(berth.layout.title.text.split("vertical x")[1].split(";")[0])
    ratio = berth.layout.scene.aspectratio
    ship = scene_of(_solve("ship_berth.yaml"))
    lo, hi = ship.extent()
    width, depth_y = hi[0] - lo[0], hi[1] - lo[1]
    pad = 0.04 * max(width, depth_y)
    horizontal = max(width, depth_y) + 2 * pad
    height = max(0.0, hi[2]) + ship.depth                  # flat seabed at -depth
    assert ratio.x == pytest.approx((width + 2 * pad) / horizontal)
    assert ratio.y == pytest.approx((depth_y + 2 * pad) / horizontal)
    assert ratio.z == pytest.approx(gain * height / horizontal)


def test_interactive_view_without_plotly_says_how_to_get_it(monkeypatch):
    import sys
    from moorsolve.plot import plot_3d_interactive
    monkeypatch.setitem(sys.modules, "plotly", None)
    monkeypatch.setitem(sys.modules, "plotly.graph_objects", None)
    with pytest.raises(ImportError, match=r"moorsolve\[interactive\]"):
        plot_3d_interactive(_solve("buoy_vida.yaml"))


@pytest.mark.parametrize("name, members, radius", [
    ("oc4_semi.yaml", 7, 12.0),        # Robertson et al. (2014), Table 3-1: base columns
    ("volturnus_s.yaml", 4, 6.25),     # Allen et al. (2020): 12.5 m outer columns
    ("oc3_spar.yaml", 3, 4.7),         # Jonkman (2010): 9.4 m below the taper
])
def test_a_platforms_drawn_columns_are_its_outline_members(name, members, radius):
    """``outline_members`` are drawn as the columns they are, at the solved pose, without
    taking part in the solve (the same equilibrium as the case without them)."""
    result = _solve(name)
    shapes = [s for s in scene_of(result).bodies[0].shapes if s.kind == "cylinder"]
    assert len(shapes) == members
    widest = max(float(np.ptp(s.ring[:, 0])) for s in shapes)
    assert widest == pytest.approx(2 * radius, rel=1e-2)     # a 36-gon's width
    bare = _solve_without_outline(name, "outline_members")
    a, b = result.bodies[0], bare.bodies[0]
    for key in ("x_m", "y_m", "yaw_deg"):
        assert a[key] == b[key]


def test_an_offset_below_what_the_legend_shows_is_not_drawn():
    """OC3 at rest: an offset of rounding size is not magnified into an arrow."""
    result = _solve("oc3_spar.yaml")
    texts = [t.get_text() for t in plot_plan(result).get_legend().get_texts()]
    assert any("not drawn" in t for t in texts)
