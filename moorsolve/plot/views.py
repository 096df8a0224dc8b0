"""Elevation, 3-D view and line profiles of an equilibrium, and the figure of all views.

Each function takes a :class:`~moorsolve.Result` (or a :class:`.scene.Scene` made from
one) and an optional Axes, draws on it and returns it; nothing calls ``plt.show()``.
Lines are coloured by their T/MBL (largest tension over MBL) when every line has an
MBL, else by their largest tension, on one scale shared by every view of a figure
(:mod:`.style`).
"""

from __future__ import annotations

import math

import numpy as np

from .plan import plot_plan
from .scene import Scene, scene_of
from .style import POINT_STYLE, SEABED, WATER, as_scene, line_colours, line_label, new_axes, nice

__all__ = ["plot_plan", "plot_elevation", "plot_3d", "plot_profiles", "plot_equilibrium",
           "view_direction"]


# ---- elevation ---------------------------------------------------------------------------


def view_direction(scene: Scene) -> float:
    """The horizontal direction [deg] along which the scene spreads most (x or y when
    within 10 deg of one, or when no direction dominates; x for a scene without lines, held
    by its fenders or pile guides), for the elevation's axis."""
    if not scene.lines:
        return 0.0
    xy = np.vstack([line.xyz[:, :2] for line in scene.lines])
    xy = xy - xy.mean(axis=0)
    w, v = np.linalg.eigh(xy.T @ xy)
    if w[1] < 2.0 * w[0]:
        # No dominant direction (a symmetric spread): the axis with the larger spread.
        return 0.0 if np.ptp(xy[:, 0]) >= np.ptp(xy[:, 1]) else 90.0
    angle = math.degrees(math.atan2(v[1, -1], v[0, -1])) % 180.0
    for axis in (0.0, 90.0, 180.0):
        if abs(angle - axis) < 10.0:
            return axis % 180.0
    return angle


def plot_elevation(result, ax=None, depth=None, *, along_deg=None):
    """Elevation: the scene projected on a vertical plane, with the real seabed, the
    bodies' hulls, quay walls, piles and fenders; everything drawn is inside the Axes
    (lines to fairleads on deck and bollards on the quay included).

    Parameters
    ----------
    result : Result or Scene
    ax : matplotlib Axes, optional
    depth : float, optional
        Ignored (the seabed comes from the case); kept for older calls.
    along_deg : float, optional
        Direction of the horizontal axis, counter-clockwise from +x [deg]; default the
        direction the scene spreads most (:func:`view_direction`).

    Returns
    -------
    matplotlib Axes

    Notes
    -----
    A sloped seabed is a band: its height across the section varies over the depth of the
    scene behind it; the solid line is the seabed through the body origin. The vertical
    scale is exaggerated by the factor in the title; the Axes fill their box by showing
    more water or more length, never by changing that factor.
    """
    from matplotlib.patches import Rectangle

    from .berth import draw_berth_elevation
    from .plan import FIXED_STYLE
    scene = as_scene(result)
    ax = new_axes(ax, figsize=(9, 4.5))
    colour, _, _ = line_colours(scene)
    theta = math.radians(view_direction(scene) if along_deg is None else along_deg)
    e = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-math.sin(theta), math.cos(theta)])
    drawn = scene.drawn_points()
    s_all, t_all = drawn[:, :2] @ e, drawn[:, :2] @ n
    width = float(s_all.max() - s_all.min()) + 1.0
    pad = 0.04 * width
    s = np.linspace(s_all.min() - 2 * width, s_all.max() + 2 * width, 600)
    through = scene.bodies[0].origin[:2] @ n if scene.bodies else float(np.mean(t_all))
    bed = [scene.seabed_z(s * e[0] + t * n[0], s * e[1] + t * n[1])
           for t in (t_all.min(), t_all.max(), through)]
    near = (s >= s_all.min() - pad) & (s <= s_all.max() + pad)
    low = float(np.min([np.min(b[near]) for b in bed]))
    ground = low - 2.0 * scene.depth
    ax.fill_between(s, bed[2], 0.0, color=WATER, zorder=0)
    ax.fill_between(s, np.minimum(bed[0], bed[1]), np.maximum(bed[0], bed[1]),
                    color=SEABED, alpha=0.35, lw=0, zorder=1)
    ax.fill_between(s, np.minimum(bed[0], bed[1]), ground, color=SEABED, alpha=0.6, lw=0,
                    zorder=1)
    ax.plot(s, bed[2], color=SEABED, lw=1.5, zorder=2)
    ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--", zorder=2)
    draw_berth_elevation(ax, scene.berth, e, ground)
    top = max(0.0, float(drawn[:, 2].max()))
    height = top - low
    thin = 0.012 * max(height, 1.0)
    for body in scene.bodies:
        for shape in body.shapes:
            span = shape.ring @ e
            bottom, up = shape.bottom, max(shape.top, shape.bottom + thin)
            if shape.bottom == shape.top:       # no height known: a slab about it
                bottom, up = shape.bottom - thin / 2, shape.top + thin / 2
            ax.add_patch(Rectangle((span.min(), bottom), np.ptp(span), up - bottom,
                                   fc="0.6", ec="0.3", lw=0.8, alpha=0.75, zorder=4,
                                   hatch="..." if shape.kind == "fairleads" else None))
        ax.plot(body.fairleads[:, :2] @ e, body.fairleads[:, 2], "s", color="k", ms=3,
                zorder=5)
    for line in scene.removed:
        ax.plot(line.xyz[:, :2] @ e, line.xyz[:, 2], color="0.55", lw=1.0, ls=(0, (4, 3)),
                zorder=3)
    for line in scene.lines:
        xy = line.xyz[:, :2]
        ax.plot(xy @ e, line.xyz[:, 2], color=colour(line), lw=1.5,
                ls=":" if line.slack else "-", zorder=3)
        for kind, end in ((line.a_kind, line.xyz[0]), (line.b_kind, line.xyz[-1])):
            if kind in FIXED_STYLE:
                style = {k: v for k, v in FIXED_STYLE[kind].items() if k != "label"}
                ax.plot(end[:2] @ e, end[2], ls="", zorder=6, **dict(style, ms=5))
    for p in scene.points:
        style = {k: v for k, v in POINT_STYLE[p.kind].items() if k != "label"}
        ax.plot(p.xyz[:2] @ e, p.xyz[2], zorder=5, **style)
    above = max(0.06 * height, 0.1 * top + 0.02 * height)
    ax._moorsolve_section = {
        "limits": (s_all.min() - pad, s_all.max() + pad,
                   low - 0.06 * max(height, scene.depth), top + above),
        "title": f"elevation {_view_words(theta, scene.north_deg)}"}
    ax.set_xlabel(_axis_name(theta, scene.north_deg))
    ax.set_ylabel("z [m]")
    ax.annotate("still water ", (1.0, 0.0), xycoords=("axes fraction", "data"),
                color="tab:blue", fontsize=7, ha="right", va="bottom")
    ax.annotate(" seabed" + (" through the body; band: across the scene" if scene.sloped
                             else ""), (0.0, float(bed[2][near][0])),
                xycoords=("axes fraction", "data"), color="#5c4424", fontsize=7,
                ha="left", va="bottom")
    fit_section(ax)
    return ax


def fit_section(ax) -> None:
    """Choose the elevation's vertical exaggeration (the largest 1-2-5 factor, at least 1,
    at which what it shows fits the box the figure's layout gives it) and widen its limits
    about what it shows (more water and sky, or more length) to fill that box. Idempotent;
    called again once a figure is laid out (a later change of layout that resizes the box
    changes the factor by as much)."""
    section = getattr(ax, "_moorsolve_section", None)
    if section is None:
        return
    x0, x1, y0, y1 = section["limits"]
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.figure.draw_without_rendering()
    box = ax.get_window_extent()
    if box.width <= 0 or box.height <= 0:
        return
    # metres of z per pixel over metres of x per pixel, when the content fills the box
    gain = max(1.0, nice(box.height * (x1 - x0) / (box.width * (y1 - y0))))
    dz = box.height * (x1 - x0) / (box.width * gain)       # the height the box shows
    if dz >= y1 - y0:
        grow = dz - (y1 - y0)
        # More sky than ground: the seabed's band is drawn, the sky is empty.
        ax.set_ylim(y0 - 0.35 * grow, y1 + 0.65 * grow)
    else:
        grow = box.width * gain * (y1 - y0) / box.height - (x1 - x0)
        ax.set_xlim(x0 - 0.5 * grow, x1 + 0.5 * grow)
    ax.set_title(f"{section['title']} (vertical x{gain:g})", fontsize=9)


def _view_words(theta: float, north_deg) -> str:
    """Where the elevation looks along, in the case's convention."""
    deg = math.degrees(theta) % 180.0
    if north_deg is None:
        return f"along {deg:.0f} deg from +x"
    bearing = (north_deg - deg) % 180.0
    return f"along bearing {bearing:03.0f}-{bearing + 180:03.0f} (compass)"


def _axis_name(theta: float, north_deg=None) -> str:
    deg = math.degrees(theta) % 180.0
    if abs(deg) < 1e-9:
        name = "x [m]"
    elif abs(deg - 90.0) < 1e-9:
        name = "y [m]"
    else:
        name = f"distance along {deg:.0f} deg from +x [m]"
    if north_deg is not None:
        name += f", increasing toward {(north_deg - deg) % 360:03.0f} (compass)"
    return name


# ---- 3-D ---------------------------------------------------------------------------------


def _prism_faces(shape, thin: float) -> list:
    """Top, bottom and side faces of a body's shape (a flat slab when its height is not
    known)."""
    bottom, top = shape.bottom, shape.top
    if top - bottom < thin:
        bottom, top = bottom - thin / 2, top + thin / 2
    ring = shape.ring
    lower = [[x, y, bottom] for x, y in ring]
    upper = [[x, y, top] for x, y in ring]
    sides = [[lower[k], lower[(k + 1) % len(ring)], upper[(k + 1) % len(ring)], upper[k]]
             for k in range(len(ring))]
    return [lower, upper] + sides


def plot_3d(result, ax=None, *, elev: float = 24.0, azim: float = -60.0):
    """A 3-D view: seabed plane, still-water outline, lines, anchors, bollards, clumps and
    buoys, the bodies' hulls, quay walls, piles and fenders; the vertical scale exaggerated
    by the factor in the title, the box holding everything drawn.

    Returns
    -------
    matplotlib Axes3D
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from .berth import draw_berth_3d
    from .plan import FIXED_STYLE
    scene = as_scene(result)
    ax = new_axes(ax, projection="3d", figsize=(8, 6))
    colour, _, _ = line_colours(scene)
    lo, hi = scene.extent()
    pad = 0.04 * max(hi[0] - lo[0], hi[1] - lo[1], 1.0)
    gx = np.array([lo[0] - pad, hi[0] + pad])
    gy = np.array([lo[1] - pad, hi[1] + pad])
    X, Y = np.meshgrid(np.linspace(*gx, 12), np.linspace(*gy, 12))
    Z = scene.seabed_z(X, Y)
    zlow = float(np.min(Z))
    ztop = max(0.0, float(hi[2]))
    height = ztop - zlow
    ax.plot_surface(X, Y, Z, color=SEABED, alpha=0.3, lw=0, shade=False)
    ax.plot([gx[0], gx[1], gx[1], gx[0], gx[0]], [gy[0], gy[0], gy[1], gy[1], gy[0]],
            [0.0] * 5, color="tab:blue", lw=0.8, ls="--")
    draw_berth_3d(ax, scene.berth, zlow)
    for line in scene.removed:
        ax.plot(*line.xyz.T, color="0.55", lw=1.0, ls=(0, (4, 3)))
    for line in scene.lines:
        ax.plot(*line.xyz.T, color=colour(line), lw=1.6, ls=":" if line.slack else "-")
        for kind, end in ((line.a_kind, line.xyz[0]), (line.b_kind, line.xyz[-1])):
            if kind in FIXED_STYLE:
                style = {k: v for k, v in FIXED_STYLE[kind].items() if k != "label"}
                ax.plot(*end[:, None], ls="", **dict(style, ms=4))
    for p in scene.points:
        style = {k: v for k, v in POINT_STYLE[p.kind].items() if k != "label"}
        ax.plot(*p.xyz[:, None], **style)
    thin = 0.01 * max(height, 1.0)
    for body in scene.bodies:
        for shape in body.shapes:
            if len(shape.ring) > 2:
                # The limits are set below from the scene's extent (autoscaling a fine ring,
                # a ship's, can overflow in matplotlib's margin arithmetic).
                ax.add_collection3d(Poly3DCollection(
                    _prism_faces(shape, thin), facecolor="0.6", alpha=0.75, edgecolor="0.3",
                    lw=0.4), autolim=False)
            else:
                ring = np.column_stack([shape.ring, np.full(len(shape.ring), shape.top)])
                ax.plot(*ring.T, color="0.5", lw=5, marker="o" if len(ring) == 1 else None)
    horizontal = float(max(gx[1] - gx[0], gy[1] - gy[0]))
    gain = max(1.0, nice(0.3 * horizontal / height)) if height > 0 else 1.0
    # Full size: the tick labels are kept small and few, so the box stays in its Axes.
    ax.set_box_aspect((gx[1] - gx[0], gy[1] - gy[0], height * gain), zoom=0.95)
    from matplotlib.ticker import MaxNLocator
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(MaxNLocator(5))
    ax.zaxis.set_major_locator(MaxNLocator(4))
    ax.set_xlim(*gx)
    ax.set_ylim(*gy)
    ax.set_zlim(zlow, ztop)
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x [m]", fontsize=8, labelpad=-2)
    ax.set_ylabel("y [m]", fontsize=8, labelpad=-2)
    ax.set_zlabel("z [m]", fontsize=8, labelpad=-2)
    ax.tick_params(labelsize=6, pad=0)
    ax.set_title(f"3-D view (vertical x{gain:g})", fontsize=9)
    return ax


# ---- each line in its own plane ----------------------------------------------------------


def plot_profiles(result, ax=None):
    """Each line in its own vertical plane: height against horizontal distance from its
    anchor, with the seabed under that line (a straight line on a plane seabed).

    Returns
    -------
    matplotlib Axes
    """
    scene = as_scene(result)
    ax = new_axes(ax, figsize=(8, 4.5))
    colour, _, _ = line_colours(scene)
    for line in scene.lines:
        d = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(line.xyz[:, :2], axis=0).T))])
        c = colour(line)
        ax.plot(d, scene.seabed_z(line.xyz[:, 0], line.xyz[:, 1]), color=SEABED, lw=0.8,
                alpha=0.6)
        ax.plot(d, line.xyz[:, 2], color=c, lw=1.3, ls=":" if line.slack else "-",
                label=line_label(line, scene).replace("\n", " "))
        for p in scene.points:
            hit = np.linalg.norm(line.xyz - p.xyz, axis=1)
            k = int(np.argmin(hit))
            if hit[k] < 1e-6 * max(scene.depth, 1.0):
                style = {k2: v for k2, v in POINT_STYLE[p.kind].items() if k2 != "label"}
                ax.plot(d[k], p.xyz[2], **style)
    ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--")
    ax.set_xlabel("horizontal distance from the anchor [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("each line in its own vertical plane (brown: the seabed under it)",
                 fontsize=9)
    ax.legend(fontsize=6, ncol=2 if len(scene.lines) > 6 else 1, loc="upper left")
    return ax


# ---- the equilibrium figure ------------------------------------------------------------


def plot_equilibrium(result, depth=None, *, layout: str = "auto", removed_from=None):
    """Plan (with the colour bar and legend), elevation and 3-D view in one figure.

    Parameters
    ----------
    result : Result or Scene
    depth : float, optional
        Ignored (the seabed comes from the case); kept for older calls.
    layout : {"auto", "landscape", "portrait"}
        Plan left and the other views right (a screen), the plan above them side by side
        (a page), or (``"auto"``) whichever the plan's shape fills best: a plan much wider
        than tall (a ship at a berth, a line along x) goes above.
    removed_from : Result, optional
        Another result (the intact condition) whose lines missing here are drawn as
        ghosts: the broken line of a damaged condition.

    Returns
    -------
    matplotlib Figure
    """
    import matplotlib.pyplot as plt
    scene = result if isinstance(result, Scene) else scene_of(result, removed_from)
    lo, hi = scene.extent(min_ratio=0.3)
    ratio = float((hi[1] - lo[1]) / max(hi[0] - lo[0], 1e-9))
    if layout == "auto":
        layout = "portrait" if ratio < 0.45 else "landscape"
    if layout == "portrait":
        plan_h = float(np.clip(12.5 * ratio, 3.5, 8.0))
        mosaic, size, ratios = [["plan", "plan"], ["elev", "3d"]], (13, plan_h + 2.0 + 4.8), {
            "height_ratios": [plan_h + 2.0, 4.8], "width_ratios": [1.15, 1]}
    elif layout == "landscape":
        tall = float(np.clip(8.0 * ratio + 3.0, 7.5, 11.0))    # the plan's height, legend
        mosaic, size, ratios = [["plan", "elev"], ["plan", "3d"]], (15, tall), {
            "width_ratios": [1.2, 1], "height_ratios": [1, 1.25]}
    else:
        raise ValueError(f"layout {layout!r}: must be 'auto', 'landscape' or 'portrait'")
    fig, axes = plt.subplot_mosaic(mosaic, figsize=size, layout="constrained",
                                   per_subplot_kw={"3d": {"projection": "3d"}}, **ratios)
    fig.get_layout_engine().set(w_pad=0.03, h_pad=0.03, hspace=0.02, wspace=0.02)
    fig.suptitle(scene.title)
    # A 3-D box's decorations grow with its Axes, which constrained layout cannot settle
    # (it collapses every Axes); the 3-D view keeps its grid cell, drawn inside it.
    axes["3d"].set_in_layout(False)
    plot_elevation(scene, axes["elev"])
    plot_3d(scene, axes["3d"])
    # Last: the plan places its labels once everything else is laid out.
    plot_plan(scene, axes["plan"], legend="figure" if layout == "portrait" else "narrow")
    fit_section(axes["elev"])
    _place_3d(axes["3d"], axes["elev"], layout)
    return fig


def _place_3d(ax3d, elev, layout: str) -> None:
    """The 3-D view in the room the laid-out figure leaves it: beside the elevation (plan
    above) or under it (plan left)."""
    fig = elev.figure
    fig.draw_without_rendering()
    inv = fig.transFigure.inverted()
    tight = inv.transform_bbox(elev.get_tightbbox())
    if layout == "portrait":
        x0, x1 = tight.x1 + 0.01, 0.995
        y0, y1 = 0.0, tight.y1
    else:
        x0, x1 = tight.x0, 0.995
        y0, y1 = 0.0, tight.y0 - 0.035          # room for its title
    # A margin for the tick labels a 3-D box draws past its Axes, the box centred in it.
    ax3d.set_anchor("C")
    ax3d.set_position([x0 + 0.01, y0 + 0.015, max(x1 - x0 - 0.035, 0.05),
                       max(y1 - y0 - 0.03, 0.05)])
