"""A berth drawn in plan (issue 15): quay walls, piles, the bodies' hull footprints, fenders
coloured by utilisation (compression over rated deflection) and pile guides. Drawn over
:func:`~moorsolve.plot.plan.plot_plan` by :func:`~moorsolve.plot.views.plot_equilibrium`;
the lines (hawsers among them) are the plan's own.
"""

from __future__ import annotations

import numpy as np

__all__ = ["plot_berth"]


def _utilisation_colour(value):
    """Green to red over utilisation 0..1 (dark red beyond); grey where unknown."""
    import matplotlib.pyplot as plt
    if value is None:
        return "0.5"
    return plt.get_cmap("RdYlGn_r")(min(max(value, 0.0), 1.0))


def _hull_footprints(result, ax) -> None:
    """Each body's exact hull members (boxes, cylinders) in plan at the solved pose."""
    from matplotlib.patches import Circle, Polygon
    for body, pose in zip(result.case.bodies, result.bodies):
        yaw = np.radians(pose["yaw_deg"])
        c, s = np.cos(yaw), np.sin(yaw)
        origin = np.array([pose["x_m"], pose["y_m"]])
        for m in body.hull:
            centre = origin + np.array([[c, -s], [s, c]]) @ np.array(m.centre)
            if m.shape == "cylinder":
                ax.add_patch(Circle(centre, m.radius, color="0.8", alpha=0.6, zorder=1))
                continue
            half = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]]) * [m.length / 2, m.width / 2]
            corners = centre + half @ np.array([[c, s], [-s, c]])
            ax.add_patch(Polygon(corners, color="0.8", alpha=0.6, zorder=1))


def _show_all(ax, first: int, points: np.ndarray) -> None:
    """Widen the axes' limits to the berth's patches drawn from ``first`` on and the
    ``points`` (a plan drawn for lines alone may not reach the piles and hulls: a scene
    its pile guides alone hold has no lines)."""
    boxes = [p.get_path().transformed(p.get_patch_transform()).get_extents()
             for p in ax.patches[first:]]
    xs = [b.x0 for b in boxes] + [b.x1 for b in boxes] + list(points[:, 0])
    ys = [b.y0 for b in boxes] + [b.y1 for b in boxes] + list(points[:, 1])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    lo_x, hi_x, lo_y, hi_y = min(xs + [x0]), max(xs + [x1]), min(ys + [y0]), max(ys + [y1])
    if (lo_x, hi_x, lo_y, hi_y) != (x0, x1, y0, y1):
        pad = 0.05 * max(hi_x - lo_x, hi_y - lo_y)
        ax.set_xlim(lo_x - pad, hi_x + pad)
        ax.set_ylim(lo_y - pad, hi_y + pad)


def _walls(result, ax, points: np.ndarray) -> None:
    """Each wall's trace in plan, as far along it as the scene reaches."""
    for wall in result.case.contacts.walls:
        n = np.array(wall.normal[:2])
        if np.linalg.norm(n) < 1e-9:
            continue          # a horizontal wall has no trace in plan
        n = n / np.linalg.norm(n)
        t = np.array([-n[1], n[0]])
        p0 = np.array(wall.point[:2])
        along = (points - p0) @ t
        reach = 0.1 * max(np.ptp(along), 1.0)
        ends = p0 + np.outer([along.min() - reach, along.max() + reach], t)
        ax.plot(ends[:, 0], ends[:, 1], color="0.25", lw=3, solid_capstyle="butt", zorder=2)
        back = ends + 0.02 * np.ptp(along) * (-n)
        ax.fill(np.r_[ends[:, 0], back[::-1, 0]], np.r_[ends[:, 1], back[::-1, 1]],
                color="0.75", zorder=0)
        ax.annotate(wall.name, ends.mean(axis=0), fontsize=7, color="0.25", xytext=(4, 4),
                    textcoords="offset points")


def plot_berth(result, ax=None, *, colour_bar: bool = True):
    """Plan view of a berth: quay walls, piles, hull footprints, fenders coloured by
    utilisation with their reactions, pile guides (their collars, coloured by contact).

    Parameters
    ----------
    result : Result
        A solved case with fenders or pile guides.
    ax : matplotlib Axes, optional
        Drawn over (a plan from :func:`~moorsolve.plot.plan.plot_plan`), else new Axes.
    colour_bar : bool
        Draw the fenders' utilisation colour bar.

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 7))
        ax.set_aspect("equal")
    contacts = result.case.contacts
    points = [f["contact_point_m"][:2] for f in result.fenders]
    points += [leg.anchor[:2] for leg in result.legs] + [leg.fairlead[:2] for leg in result.legs]
    points = np.array(points) if points else np.zeros((1, 2))
    _walls(result, ax, points)
    before = len(ax.patches)         # the walls span what the rest reaches
    for pile in contacts.piles:
        ax.add_patch(Circle(pile.position, pile.radius, color="0.3", zorder=3))
    _hull_footprints(result, ax)
    for f in result.fenders:
        x, y = f["contact_point_m"][:2]
        ax.plot(x, y, "s", ms=7, mfc=_utilisation_colour(f["utilisation"]), mec="k",
                zorder=4)
        text = (f"{f['name']}\n{f['reaction_N'] / 1e3:.0f} kN" if f["in_contact"]
                else f"{f['name']}\nopen")
        ax.annotate(text, (x, y), fontsize=6, ha="center", va="bottom", xytext=(0, 6),
                    textcoords="offset points")
    for g in result.guides:
        pile = contacts.pile_named(g["pile"])
        ax.add_patch(Circle(pile.position, pile.radius + g["clearance_m"], fill=False,
                            ec=_utilisation_colour(1.0 if g["in_contact"] else 0.0), lw=1.5,
                            zorder=4))
        ax.annotate(f"{g['name']} {g['reaction_N'] / 1e3:.0f} kN", pile.position,
                    fontsize=6, xytext=(6, -10), textcoords="offset points")
    _show_all(ax, before, points)
    if colour_bar and result.fenders:
        sm = plt.cm.ScalarMappable(cmap="RdYlGn_r", norm=plt.Normalize(0, 1))
        ax.figure.colorbar(sm, ax=ax, label="fender compression / rated deflection",
                           shrink=0.6)
    return ax
