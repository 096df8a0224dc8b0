"""A berth drawn in every view: quay walls, piles, fenders coloured by utilisation
(compression over rated deflection) and pile guides (their collars, coloured by contact),
read from the scene's :class:`~.geometry.Berth`. :func:`~moorsolve.plot.plan.plot_plan`,
:func:`~moorsolve.plot.views.plot_elevation` and :func:`~moorsolve.plot.views.plot_3d` draw
it; :func:`plot_berth` draws it alone over a plan (the lines are the plan's own).
"""

from __future__ import annotations

import numpy as np

from .labels import LabelRequest

__all__ = ["plot_berth", "fender_colour", "draw_berth_plan", "draw_berth_elevation",
           "draw_berth_3d", "QUAY", "PILE"]

QUAY = "0.35"
LAND = "0.86"
PILE = "0.2"


def fender_colour(value):
    """Green to red over utilisation 0..1 (dark red beyond); grey where unknown: the
    lines' utilisation scale below the MBL."""
    import matplotlib as mpl
    if value is None:
        return "0.5"
    return mpl.colormaps["RdYlGn_r"](min(max(value, 0.0), 1.0))


def _fender_text(f) -> str:
    return f"{f.name} {f.reaction_N / 1e3:.0f} kN" if f.in_contact else f"{f.name} open"


def draw_berth_plan(ax, berth, labels: list | None = None) -> list:
    """Walls (with the land behind them), piles, fenders and guides on a plan Axes.

    ``labels``: a list the fenders', guides' and walls' :class:`.labels.LabelRequest` are
    appended to (placed later); None: labelled at once beside each item. Returns the
    legend handles.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle
    handles = []
    pending = [] if labels is None else labels
    for wall in berth.walls:
        span = float(np.linalg.norm(wall.ends[1] - wall.ends[0]))
        back = wall.ends - 0.06 * span * wall.normal        # the land behind the face
        ax.fill(np.r_[wall.ends[:, 0], back[::-1, 0]], np.r_[wall.ends[:, 1], back[::-1, 1]],
                fc=LAND, hatch="///", ec="0.6", lw=0, zorder=0)
        ax.plot(wall.ends[:, 0], wall.ends[:, 1], color=QUAY, lw=3, solid_capstyle="butt",
                zorder=2, gid="wall")
        pending.append(LabelRequest(f"{wall.name} (wall)", tuple(wall.ends[0] * 0.9
                                                                 + wall.ends[1] * 0.1),
                                    tuple(-wall.normal), fontsize=7, color="0.25"))
    if berth.walls:
        handles.append(Line2D([], [], color=QUAY, lw=3, label="quay wall (land hatched)"))
    for pile in berth.piles:
        ax.add_patch(Circle(pile.xy, pile.radius, color=PILE, zorder=4, gid="pile"))
    if berth.piles:
        handles.append(Line2D([], [], marker="o", color=PILE, ls="", ms=6, label="pile"))
    for g in berth.guides:
        ax.add_patch(Circle(g.xy, g.radius, fill=False, lw=1.5, zorder=5,
                            ec=fender_colour(1.0 if g.in_contact else 0.0)))
        pending.append(LabelRequest(f"{g.name} {g.reaction_N / 1e3:.0f} kN", tuple(g.xy),
                                    None, fontsize=6))
    if berth.guides:
        handles.append(Line2D([], [], marker="o", mfc="none", mec="tab:red", ls="", ms=8,
                              label="pile guide (red: bearing)"))
    for f in berth.fenders:
        ax.plot(f.xyz[0], f.xyz[1], "s", ms=7, mfc=fender_colour(f.utilisation), mec="k",
                zorder=6, gid="fender")
        pending.append(LabelRequest(_fender_text(f), tuple(f.xyz[:2]), None, fontsize=6))
    if berth.fenders:
        handles.append(Line2D([], [], marker="s", ms=7, mfc=fender_colour(0.3), mec="k",
                              ls="", label="fender (colour: compression / rated)"))
    if labels is None:
        for req in pending:
            ax.annotate(req.text, req.xy, fontsize=req.fontsize, xytext=(4, 4),
                        textcoords="offset points", color=req.color)
    return handles


def draw_berth_elevation(ax, berth, e: np.ndarray, low: float) -> None:
    """The berth projected on the vertical plane along ``e`` (unit plan vector), from the
    seabed at ``low`` [m]."""
    from matplotlib.patches import Rectangle
    for wall in berth.walls:
        s = np.sort(wall.ends @ e)
        if abs(float(wall.normal @ e)) > 0.7:      # the section cuts the quay: its land
            reach = 1e5             # to the Axes' edge (clipped there)
            face = wall.point[:2] @ e
            x0 = face - reach if wall.normal @ e > 0 else face
            ax.add_patch(Rectangle((x0, low), reach, wall.top - low, fc=LAND, hatch="///",
                                   ec="0.6", lw=0, zorder=0.5))
            ax.plot([face, face], [low, wall.top], color=QUAY, lw=2, zorder=2, gid="wall")
        else:                                       # the quay's face behind the scene
            ax.add_patch(Rectangle((s[0], low), s[1] - s[0], wall.top - low, fill=False,
                                   ec=QUAY, lw=1.0, ls="--", zorder=0.5))
            ax.plot(s, [wall.top, wall.top], color=QUAY, lw=2.5, zorder=2, gid="wall")
    for pile in berth.piles:
        s = pile.xy @ e
        ax.add_patch(Rectangle((s - pile.radius, low), 2 * pile.radius, pile.top - low,
                               color=PILE, zorder=4, gid="pile"))
    for g in berth.guides:
        s = g.xy @ e
        ax.plot([s - g.radius, s + g.radius], [g.z, g.z], color=fender_colour(
            1.0 if g.in_contact else 0.0), lw=3, zorder=5)
    for f in berth.fenders:
        ax.plot(f.xyz[:2] @ e, f.xyz[2], "s", ms=6, mfc=fender_colour(f.utilisation),
                mec="k", zorder=6, gid="fender")


def draw_berth_3d(ax, berth, low: float) -> None:
    """Walls as vertical faces from the seabed at ``low`` [m] to their tops, piles as
    columns, guides as collars, fenders as coloured squares."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    for wall in berth.walls:
        (x0, y0), (x1, y1) = wall.ends
        face = [[x0, y0, low], [x1, y1, low], [x1, y1, wall.top], [x0, y0, wall.top]]
        ax.add_collection3d(Poly3DCollection([face], facecolor=LAND, edgecolor=QUAY,
                                             alpha=0.35, lw=1.0))
        ax.plot([x0, x1], [y0, y1], [wall.top] * 2, color=QUAY, lw=2.5, gid="wall")
    t = np.linspace(0.0, 2 * np.pi, 25)
    for pile in berth.piles:
        ax.plot([pile.xy[0]] * 2, [pile.xy[1]] * 2, [low, pile.top], color=PILE, lw=3,
                gid="pile")
    for g in berth.guides:
        ax.plot(g.xy[0] + g.radius * np.cos(t), g.xy[1] + g.radius * np.sin(t),
                np.full_like(t, g.z), color=fender_colour(1.0 if g.in_contact else 0.0), lw=1.5)
    for f in berth.fenders:
        ax.plot(*f.xyz[:, None], "s", ms=5, mfc=fender_colour(f.utilisation), mec="k",
                gid="fender")


def plot_berth(result, ax=None, *, colour_bar: bool = True):
    """Plan view of a berth: quay walls, piles, hull footprints, fenders coloured by
    utilisation with their reactions, pile guides (their collars, coloured by contact).

    Parameters
    ----------
    result : Result or Scene
        A solved case with fenders or pile guides.
    ax : matplotlib Axes, optional
        Drawn over (e.g. a plan of another result), else new Axes.
    colour_bar : bool
        Draw the fenders' utilisation colour bar.

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from .style import as_scene
    scene = as_scene(result)
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 7), layout="constrained")
        ax.set_aspect("equal")
    for body in scene.bodies:
        for shape in body.shapes:
            ax.add_patch(Polygon(shape.ring, color="0.8", alpha=0.6, zorder=1))
    draw_berth_plan(ax, scene.berth)
    ax.autoscale_view()
    if colour_bar and scene.berth.fenders:
        sm = plt.cm.ScalarMappable(cmap="RdYlGn_r", norm=plt.Normalize(0, 1))
        ax.figure.colorbar(sm, ax=ax, label="fender compression / rated deflection",
                           shrink=0.6)
    return ax
