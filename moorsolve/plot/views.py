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

from .berth import plot_berth
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


def _exaggeration(horizontal: float, vertical: float) -> float:
    """A 1-2-5 vertical exaggeration that makes a section about half as tall as wide."""
    if vertical <= 0:
        return 1.0
    return max(1.0, nice(0.5 * horizontal / vertical))


def plot_elevation(result, ax=None, depth=None, *, along_deg=None):
    """Elevation: the scene projected on a vertical plane, with the real seabed.

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
    scale is exaggerated by the factor in the title.
    """
    scene = as_scene(result)
    ax = new_axes(ax, figsize=(9, 4.5))
    colour, _, _ = line_colours(scene)
    theta = math.radians(view_direction(scene) if along_deg is None else along_deg)
    e = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-math.sin(theta), math.cos(theta)])
    allxy = np.vstack([line.xyz[:, :2] for line in scene.lines]
                      + [b.outline[:, :2] for b in scene.bodies])
    s_all, t_all = allxy @ e, allxy @ n
    pad = 0.04 * (s_all.max() - s_all.min() + 1.0)
    s = np.linspace(s_all.min() - pad, s_all.max() + pad, 200)
    through = scene.bodies[0].origin[:2] @ n if scene.bodies else float(np.mean(t_all))
    bed = [scene.seabed_z(s * e[0] + t * n[0], s * e[1] + t * n[1])
           for t in (t_all.min(), t_all.max(), through)]
    low = float(np.min([np.min(b) for b in bed]))
    ax.fill_between(s, bed[2], 0.0, color=WATER, zorder=0)
    ax.fill_between(s, np.minimum(bed[0], bed[1]), np.maximum(bed[0], bed[1]),
                    color=SEABED, alpha=0.35, lw=0, zorder=1)
    ax.fill_between(s, np.minimum(bed[0], bed[1]), low - 0.08 * scene.depth,
                    color=SEABED, alpha=0.6, lw=0, zorder=1)
    ax.plot(s, bed[2], color=SEABED, lw=1.5, zorder=2)
    ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--", zorder=2)
    for line in scene.removed:
        ax.plot(line.xyz[:, :2] @ e, line.xyz[:, 2], color="0.55", lw=1.0, ls=(0, (4, 3)),
                zorder=3)
    for line in scene.lines:
        xy = line.xyz[:, :2]
        ax.plot(xy @ e, line.xyz[:, 2], color=colour(line), lw=1.5,
                ls=":" if line.slack else "-", zorder=3)
        ax.plot(line.anchor[:2] @ e, line.anchor[2], "v", color="k", ms=5, zorder=4)
    for p in scene.points:
        style = {k: v for k, v in POINT_STYLE[p.kind].items() if k != "label"}
        ax.plot(p.xyz[:2] @ e, p.xyz[2], zorder=5, **style)
    for body in scene.bodies:
        span = body.outline[:, :2] @ e
        ax.plot([span.min(), span.max()], [0.0, 0.0], color="0.3", lw=6, alpha=0.6,
                solid_capstyle="butt", zorder=4)
        ax.plot(body.fairleads[:, :2] @ e, body.fairleads[:, 2], "s", color="k", ms=3,
                zorder=5)
    if scene.fixed_ends.size:
        ax.plot(scene.fixed_ends[:, :2] @ e, scene.fixed_ends[:, 2], "s", color="k", ms=4)
    height = max([0.0] + [line.xyz[:, 2].max() for line in scene.lines]) - low
    gain = _exaggeration(s[-1] - s[0], height)
    ax.set_aspect(gain)
    ax.set_ylim(low - 0.08 * scene.depth, max(0.05 * scene.depth, 0.0 + 0.05 * height))
    ax.set_xlim(s[0], s[-1])
    ax.set_xlabel(_axis_name(theta))
    ax.set_ylabel("z [m]")
    ax.set_title(f"elevation along {math.degrees(theta):.0f} deg from +x "
                 f"(vertical x{gain:g})", fontsize=9)
    ax.text(s[-1], 0.0, "still water ", color="tab:blue", fontsize=7, ha="right",
            va="bottom")
    ax.text(s[0], bed[2][0], " seabed" + (" through the body; band: across the scene"
                                          if scene.sloped else ""),
            color="#5c4424", fontsize=7, ha="left", va="bottom")
    return ax


def _axis_name(theta: float) -> str:
    deg = math.degrees(theta) % 180.0
    if abs(deg) < 1e-9:
        return "x [m]"
    if abs(deg - 90.0) < 1e-9:
        return "y [m]"
    return f"distance along {deg:.0f} deg from +x [m]"


# ---- 3-D ---------------------------------------------------------------------------------


def plot_3d(result, ax=None, *, elev: float = 24.0, azim: float = -60.0):
    """A 3-D view: seabed plane, still-water outline, lines, anchors, clumps and buoys,
    bodies; the vertical scale exaggerated by the factor in the title.

    Returns
    -------
    matplotlib Axes3D
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    scene = as_scene(result)
    ax = new_axes(ax, projection="3d", figsize=(8, 6))
    colour, _, _ = line_colours(scene)
    lo, hi = scene.extent()
    pad = 0.06 * max(hi[0] - lo[0], hi[1] - lo[1], 1.0)
    gx = np.array([lo[0] - pad, hi[0] + pad])
    gy = np.array([lo[1] - pad, hi[1] + pad])
    X, Y = np.meshgrid(gx, gy)
    Z = scene.seabed_z(X, Y)
    ax.plot_surface(X, Y, Z, color=SEABED, alpha=0.3, lw=0, shade=False)
    ax.plot([gx[0], gx[1], gx[1], gx[0], gx[0]], [gy[0], gy[0], gy[1], gy[1], gy[0]],
            [0.0] * 5, color="tab:blue", lw=0.8, ls="--")
    for line in scene.removed:
        ax.plot(*line.xyz.T, color="0.55", lw=1.0, ls=(0, (4, 3)))
    for line in scene.lines:
        ax.plot(*line.xyz.T, color=colour(line), lw=1.6, ls=":" if line.slack else "-")
        ax.plot(*line.anchor[:, None], "v", color="k", ms=4)
    for p in scene.points:
        style = {k: v for k, v in POINT_STYLE[p.kind].items() if k != "label"}
        ax.plot(*p.xyz[:, None], **style)
    for body in scene.bodies:
        if len(body.outline) > 2:
            ax.add_collection3d(Poly3DCollection([body.outline], facecolor="0.6", alpha=0.7,
                                                 edgecolor="0.3"))
        else:
            ax.plot(*body.outline.T, color="0.5", lw=5, marker="o" if len(body.outline) == 1
                    else None)
    zlow = float(np.min(Z))
    height = max(0.0, hi[2]) - zlow
    horizontal = float(max(gx[1] - gx[0], gy[1] - gy[0]))
    gain = max(1.0, nice(0.3 * horizontal / height)) if height > 0 else 1.0
    # A little under full size: the tick labels of a 3-D box reach past its Axes.
    ax.set_box_aspect((gx[1] - gx[0], gy[1] - gy[0], height * gain), zoom=0.9)
    from matplotlib.ticker import MaxNLocator
    ax.zaxis.set_major_locator(MaxNLocator(4))
    ax.set_zlim(zlow, max(0.0, hi[2]))
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x [m]", fontsize=8)
    ax.set_ylabel("y [m]", fontsize=8)
    ax.set_zlabel("z [m]", fontsize=8)
    ax.tick_params(labelsize=7)
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


def plot_equilibrium(result, depth=None, *, layout: str = "landscape", removed_from=None):
    """Plan (with the colour bar and legend), elevation and 3-D view in one figure.

    Parameters
    ----------
    result : Result or Scene
    depth : float, optional
        Ignored (the seabed comes from the case); kept for older calls.
    layout : {"landscape", "portrait"}
        Plan left and the other views right (a screen), or the plan above them (a page).
    removed_from : Result, optional
        Another result (the intact condition) whose lines missing here are drawn as
        ghosts: the broken line of a damaged condition.

    Returns
    -------
    matplotlib Figure
    """
    import matplotlib.pyplot as plt
    scene = result if isinstance(result, Scene) else scene_of(result, removed_from)
    if layout == "portrait":
        mosaic, size, ratios = [["plan", "plan"], ["elev", "3d"]], (11, 12.5), {
            "height_ratios": [1.5, 1]}
    elif layout == "landscape":
        mosaic, size, ratios = [["plan", "elev"], ["plan", "3d"]], (15, 9), {
            "width_ratios": [1.25, 1]}
    else:
        raise ValueError(f"layout {layout!r}: must be 'landscape' or 'portrait'")
    fig, axes = plt.subplot_mosaic(mosaic, figsize=size, layout="constrained",
                                   per_subplot_kw={"3d": {"projection": "3d"}}, **ratios)
    plot_plan(scene, axes["plan"], legend="figure")
    if not isinstance(result, Scene) and (result.fenders or result.guides):
        plot_berth(result, axes["plan"])       # walls, piles, fenders, guides (issue 15)
    plot_elevation(scene, axes["elev"])
    plot_3d(scene, axes["3d"])
    fig.suptitle(scene.title)
    return fig
