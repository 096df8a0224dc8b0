"""Plan and elevation views of an equilibrium; the only module that imports matplotlib."""

from __future__ import annotations

import numpy as np

from .solve.result import Result


def _max_fairlead_tension(result: Result) -> float:
    return max((leg.fairlead_tension_N for leg in result.legs), default=0.0)


def _tension_colour(leg, t_max):
    import matplotlib.pyplot as plt
    return plt.get_cmap("viridis")(leg.fairlead_tension_N / t_max if t_max > 0 else 0.0)


def plot_plan(result: Result, ax=None):
    """Plan view: legs coloured by fairlead tension, anchors, touchdown points, body.

    Returns the Axes.
    """
    import matplotlib.pyplot as plt
    if ax is None:
        _, ax = plt.subplots()
    t_max = _max_fairlead_tension(result)
    for leg in result.legs:
        p = leg.profile
        colour = _tension_colour(leg, t_max)
        ax.plot(p["x_m"], p["y_m"], color=colour, lw=1.5, ls=":" if leg.slack else "-")
        ax.plot(*leg.anchor[:2], marker="v", color="k", ms=5)
        if leg.touchdown_point is not None:
            ax.plot(*leg.touchdown_point[:2], marker="o", mfc="none", color=colour, ms=4)
        ax.annotate(f"{leg.name}\n{leg.fairlead_tension_N / 1e3:.0f} kN", leg.anchor[:2],
                    fontsize=7, ha="center", va="top", xytext=(0, -6),
                    textcoords="offset points")
    fair = np.array([leg.fairlead[:2] for leg in result.legs])
    if result.body is not None and len(fair) > 2:
        ax.fill(*_hull(fair).T, color="0.8", alpha=0.6, zorder=0)
    ax.plot(fair[:, 0], fair[:, 1], "s", color="k", ms=3)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    title = "plan"
    if result.body is not None:
        b = result.body
        title += (f": offset ({b['x_m']:.2f}, {b['y_m']:.2f}) m, yaw {b['yaw_deg']:.3f} deg")
    ax.set_title(title, fontsize=9)
    sm = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(0, t_max / 1e3))
    ax.figure.colorbar(sm, ax=ax, label="fairlead tension [kN]", shrink=0.8)
    return ax


def plot_elevation(result: Result, ax=None, depth: float | None = None):
    """Elevation: each leg's profile against horizontal distance from its anchor.

    Returns the Axes.
    """
    import matplotlib.pyplot as plt
    if ax is None:
        _, ax = plt.subplots()
    t_max = _max_fairlead_tension(result)
    for leg in result.legs:
        p = leg.profile
        dist = np.hypot(p["x_m"] - leg.anchor[0], p["y_m"] - leg.anchor[1])
        ax.plot(dist, p["z_m"], color=_tension_colour(leg, t_max), lw=1.2,
                label=f"{leg.name} {leg.fairlead_tension_N / 1e3:.0f} kN")
    if depth is not None:
        ax.axhline(-depth, color="saddlebrown", lw=1)
    ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--")
    ax.set_xlabel("distance from anchor [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("elevation (each leg in its own vertical plane)", fontsize=9)
    ax.legend(fontsize=6, ncol=2, loc="upper left")
    return ax


def plot_equilibrium(result: Result, depth: float | None = None):
    """A figure with the plan and elevation views; returns the Figure."""
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(13, 5.5),
                                 gridspec_kw={"width_ratios": [1.2, 1]})
    plot_plan(result, a1)
    if result.fenders or result.guides:
        plot_berth(result, a1)
    plot_elevation(result, a2, depth=depth)
    fig.suptitle(result.case_name or "equilibrium")
    fig.tight_layout()
    return fig


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull of 2-D points (monotone chain), to outline the body."""
    pts = sorted(map(tuple, points))
    if len(pts) < 3:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def plot_utilisation(report, ax=None):
    """Tension utilisation per leg (columns) and condition (rows) of a check report.

    ``report`` is a :class:`moorsolve.checks.CheckReport`. Each cell is the line's tension
    over its allowed tension under the standard's factor (1 = at the limit); cells of the
    removed leg are blank, a condition without equilibrium is hatched. Returns the Axes.
    """
    import matplotlib.pyplot as plt
    legs = []
    for c in report.conditions:
        for item in c.items:
            if item.check == "tension" and item.leg not in legs:
                legs.append(item.leg)
    rows = [c.name for c in report.conditions]
    grid = np.full((len(rows), len(legs)), np.nan)
    for i, c in enumerate(report.conditions):
        for item in c.items:
            if item.check == "tension":
                grid[i, legs.index(item.leg)] = item.utilisation
    if ax is None:
        _, ax = plt.subplots(figsize=(1.0 + 0.6 * max(len(legs), 4), 1.0 + 0.35 * len(rows)))
    finite = grid[np.isfinite(grid)]
    vmax = max(1.2, float(finite.max()) if finite.size else 1.0)
    image = ax.imshow(np.ma.masked_invalid(grid), cmap="RdYlGn_r", vmin=0.0, vmax=vmax,
                      aspect="auto")
    for i, c in enumerate(report.conditions):
        if not c.solved:
            ax.axhspan(i - 0.5, i + 0.5, color="0.6", alpha=0.5, hatch="//")
            ax.text(len(legs) / 2 - 0.5, i, "no equilibrium", ha="center", va="center",
                    fontsize=7)
        for j in range(len(legs)):
            if np.isfinite(grid[i, j]):
                ax.text(j, i, f"{grid[i, j]:.2f}", ha="center", va="center", fontsize=6,
                        color="k")
    ax.set_xticks(range(len(legs)), legs, fontsize=7)
    ax.set_yticks(range(len(rows)), rows, fontsize=7)
    ax.set_title(f"tension utilisation ({report.standard}; 1.0 = limit)", fontsize=9)
    ax.figure.colorbar(image, ax=ax, label="utilisation", shrink=0.8)
    return ax


def figure_png(fig, dpi: int = 110) -> bytes:
    """The figure as PNG bytes; the figure is closed."""
    import io

    import matplotlib.pyplot as plt
    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format="png", dpi=dpi)
    finally:
        plt.close(fig)
    return buffer.getvalue()


def utilisation_figure(report):
    """A figure holding :func:`plot_utilisation`; returns the Figure."""
    ax = plot_utilisation(report)
    ax.figure.tight_layout()
    return ax.figure


def plot_accuracy(rungs, axes=None):
    """An accuracy ladder: error and solve time against the requested tolerance.

    Left: worst tension error over the largest tension, per solver, with each simpler
    model's error as a dashed line. Right: median solve time, the simpler models as dashed
    lines (IPOPT at 1e-9).

    Parameters
    ----------
    rungs : list of moorsolve.studies.accuracy.Rung
    axes : pair of matplotlib Axes, optional

    Returns
    -------
    pair of matplotlib Axes
    """
    import matplotlib.pyplot as plt

    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
    ax_err, ax_time = axes
    floor = 1e-17      # an exact match still needs a place on a log axis
    markers = {"ipopt": "o", "newton": "s"}
    for solver in sorted({r.solver for r in rungs if r.ladder == "tolerance"}):
        pts = [r for r in rungs if r.ladder == "tolerance" and r.solver == solver
               and np.isfinite(r.time_s)]
        tols = [r.tol for r in pts]
        ax_err.plot(tols, [max(r.tension_error_relative, floor) for r in pts],
                    marker=markers.get(solver, "o"), label=solver)
        ax_time.plot(tols, [r.time_s * 1e3 for r in pts], marker=markers.get(solver, "o"),
                     label=solver)
    for k, r in enumerate(r for r in rungs if r.ladder == "fidelity"
                          and r.setting != "as declared" and np.isfinite(r.time_s)):
        style = dict(color=f"C{k + 2}", linestyle="--", linewidth=1)
        ax_err.axhline(max(r.tension_error_relative, floor), label=r.setting, **style)
        ax_time.axhline(r.time_s * 1e3, label=r.setting, **style)
    ax_err.plot([1e-12, 1e-4], [1e-12, 1e-4], color="0.6", linewidth=0.8,
                label="error = tolerance")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("requested tolerance (force residual / largest tension)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    ax_err.set_ylabel("worst tension error / largest tension")
    ax_time.set_ylabel("solve time [ms], median from rest")
    ax_err.set_title("Error against a 1e-12 reference")
    ax_time.set_title("What it costs")
    return axes


def _closed(theta_deg, values):
    """Angles [rad] and values with the first point repeated when the headings go round."""
    theta = np.radians(np.asarray(theta_deg, float))
    values = np.asarray(values, float)
    if len(theta) > 2 and np.isclose((theta[0] + 2 * np.pi - theta[-1]) % (2 * np.pi),
                                     np.diff(theta).mean(), rtol=0.2):
        theta, values = np.append(theta, theta[0] + 2 * np.pi), np.append(values, values[0])
    return theta, values


def _mark_headings(ax, marks, r_max):
    colours = ("C3", "C1", "C6", "C9")
    for k, (name, heading) in enumerate((marks or {}).items()):
        t, colour = np.radians(heading), colours[k % len(colours)]
        ax.plot([t, t], [0, r_max], color=colour, linewidth=2.2)
        ax.annotate(f"{name} ({heading:g}°)", (t, r_max * 1.2), color=colour, fontsize=9,
                    fontweight="bold", ha="center", va="center", annotation_clip=False,
                    bbox=dict(boxstyle="round,pad=0.2", facecolor="white", edgecolor=colour))


def plot_envelope(envelope, axes=None, marks=None):
    """Polar plots of an offset envelope: offset and worst tension against heading.

    Angles are the heading the environment travels toward, counter-clockwise from +x
    (east up the page's right). The worst heading is ringed on both.

    Parameters
    ----------
    envelope : moorsolve.studies.envelope.Envelope
    axes : pair of polar matplotlib Axes, optional
    marks : dict of str to float, optional
        Named headings [deg] drawn as dashed rays (e.g. ``{"bora": 225}``).

    Returns
    -------
    pair of matplotlib Axes
    """
    import matplotlib.pyplot as plt

    e = envelope
    if axes is None:
        fig = plt.figure(figsize=(10, 4.8), layout="constrained")
        axes = (fig.add_subplot(1, 2, 1, projection="polar"),
                fig.add_subplot(1, 2, 2, projection="polar"))
    ax_off, ax_t = axes
    ok = np.isfinite(e.worst_tension_N)
    worst = int(np.argmax(np.where(ok, e.worst_tension_N, -np.inf))) if ok.any() else None
    for ax, values, label in ((ax_off, e.offset_m, "offset [m]"),
                              (ax_t, e.worst_tension_N / 1e3, "worst tension [kN]")):
        theta, r = _closed(e.heading_deg, values)
        ax.plot(theta, r, "o-", markersize=3)
        if worst is not None:
            ax.plot(np.radians(e.heading_deg[worst]), values[worst], "o", markersize=11,
                    markerfacecolor="none", markeredgecolor="C3")
        r_max = np.nanmax(values) * 1.05 if ok.any() else 1.0
        _mark_headings(ax, marks, r_max)
        ax.set_ylim(0, r_max * 1.02)
        ax.set_title(label + " against heading (toward)", fontsize=10)
    if worst is not None:
        ax_t.set_xlabel(f"worst: {e.worst_leg[worst]} "
                        f"{e.worst_tension_N[worst] / 1e3:.0f} kN toward "
                        f"{e.heading_deg[worst]:g} deg", fontsize=9)
    return axes


def plot_polar_field(heading_deg, radius, values, ax=None, radius_label="",
                     value_label="", marks=None, levels=12):
    """A filled polar contour of ``values[i, j]`` over headings ``heading_deg[i]`` [deg]
    and radii ``radius[j]`` (e.g. offset against wind direction and speed).

    Returns
    -------
    matplotlib Axes (polar)
    """
    import matplotlib.pyplot as plt

    if ax is None:
        fig = plt.figure(figsize=(6.4, 5.6), layout="constrained")
        ax = fig.add_subplot(projection="polar")
    values = np.asarray(values, float)
    theta = np.radians(np.asarray(heading_deg, float))
    theta = np.append(theta, theta[0] + 2 * np.pi)          # close the circle
    values = np.vstack([values, values[:1]])
    T, R = np.meshgrid(theta, np.asarray(radius, float), indexing="ij")
    filled = ax.contourf(T, R, values, levels=levels, cmap="viridis")
    ax.contour(T, R, values, levels=filled.levels, colors="k", linewidths=0.3)
    ax.figure.colorbar(filled, ax=ax, label=value_label, shrink=0.8)
    _mark_headings(ax, marks, float(np.max(radius)))
    ax.set_ylim(0, float(np.max(radius)))
    ax.set_title(f"{value_label} (radius: {radius_label})", fontsize=10)
    return ax


def plot_optimisation(opt, axes=None):
    """A design optimisation: line lengths before and after, and constraint utilisation.

    Left: each leg's unstretched length at the start and at the optimum. Right: per load
    case and constraint kind the tightest utilisation (value over limit, or limit over
    value for the lower limits: safety factor and grounded length); 1 is the limit.

    Parameters
    ----------
    opt : moorsolve.studies.optimise.Optimisation
    axes : pair of Axes, optional

    Returns
    -------
    tuple of Axes
    """
    import matplotlib.pyplot as plt
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    ax1, ax2 = axes
    start = {}
    for v in opt.variables:
        if v.kind == "length":
            start.update(dict.fromkeys(v.legs, v.start))
    legs = opt.optimised_case.legs
    names = [leg.name for leg in legs]
    after = [leg.length for leg in legs]
    before = [start.get(leg.name, leg.length) for leg in legs]
    x = np.arange(len(names))
    ax1.bar(x - 0.2, before, 0.4, label="start", color="0.65")
    ax1.bar(x + 0.2, after, 0.4, label="optimum", color="tab:blue")
    ax1.set_xticks(x, names, rotation=90 if len(names) > 12 else 0)
    lo = min(before + after)
    ax1.set_ylim(lo * 0.97, max(before + after) * 1.01)
    ax1.set_ylabel("unstretched length [m]")
    ax1.set_title(f"{opt.objective}: {opt.objective_start:,.0f} -> "
                  f"{opt.objective_optimum:,.0f} {opt.unit}")
    ax1.legend(loc="lower right")

    cases = list(dict.fromkeys(c.load_case for c in opt.constraints))
    kinds = list(dict.fromkeys(c.kind for c in opt.constraints))
    width = 0.8 / max(len(kinds), 1)
    for j, kind in enumerate(kinds):
        utils = []
        for lc in cases:
            group = [c for c in opt.constraints if c.load_case == lc and c.kind == kind]
            utils.append(max((_utilisation(c) for c in group), default=np.nan))
        ax2.bar(np.arange(len(cases)) + (j - (len(kinds) - 1) / 2) * width, utils, width,
                label=kind.replace("_", " "))
    ax2.axhline(1.0, color="k", lw=1, ls="--")
    ax2.set_xticks(np.arange(len(cases)), cases, rotation=45, ha="right")
    ax2.set_ylabel("utilisation (1 = limit)")
    ax2.set_title("tightest constraint per load case at the optimum")
    ax2.legend(fontsize=8)
    ax2.figure.tight_layout()
    return ax1, ax2


def _utilisation(c) -> float:
    if c.kind in ("safety_factor", "grounded_length"):
        return c.limit / c.value if c.value > 0 else np.inf
    return c.value / c.limit if c.limit > 0 else (0.0 if c.value <= 0 else np.inf)


# ---- berths: walls, piles, fenders, guides, hawsers (issue 15) ---------------------------


def _utilisation_colour(value):
    """Green to red over utilisation 0..1 (dark red beyond); grey where unknown."""
    import matplotlib.pyplot as plt
    if value is None:
        return "0.5"
    return plt.get_cmap("RdYlGn_r")(min(max(value, 0.0), 1.0))


def _hull_footprints(result: Result, ax) -> None:
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


def plot_berth(result: Result, ax=None):
    """Plan view of a berth: quay walls, piles, fenders coloured by utilisation (compression
    over rated deflection, with their reactions), pile guides and hawsers coloured by
    utilisation (tension over MBL; dashed when slack).

    Draws on ``ax`` (for instance over :func:`plot_plan`) or on new Axes; returns the Axes.
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle
    if ax is None:
        _, ax = plt.subplots()
    case = result.case
    contacts = case.contacts if case is not None else None
    points = [f["contact_point_m"][:2] for f in result.fenders]
    points += [leg.anchor[:2] for leg in result.legs] + [leg.fairlead[:2] for leg in result.legs]
    points = np.array(points) if points else np.zeros((1, 2))
    if contacts is not None:
        for wall in contacts.walls:
            n = np.array(wall.normal[:2])
            if np.linalg.norm(n) < 1e-9:
                continue          # a horizontal wall has no trace in plan
            n = n / np.linalg.norm(n)
            t = np.array([-n[1], n[0]])
            p0 = np.array(wall.point[:2])
            # Along the wall as far as the scene reaches, and a little beyond.
            along = (points - p0) @ t
            reach = 0.1 * max(np.ptp(along), 1.0)
            ends = p0 + np.outer([along.min() - reach, along.max() + reach], t)
            foot = ends.mean(axis=0)
            ax.plot(ends[:, 0], ends[:, 1], color="0.25", lw=3, solid_capstyle="butt")
            back = ends + 0.02 * np.ptp(along) * (-n)
            ax.fill(np.r_[ends[:, 0], back[::-1, 0]], np.r_[ends[:, 1], back[::-1, 1]],
                    color="0.75", zorder=0)
            ax.annotate(wall.name, foot, fontsize=7, color="0.25", xytext=(4, 4),
                        textcoords="offset points")
        for pile in contacts.piles:
            ax.add_patch(Circle(pile.position, pile.radius, color="0.3", zorder=3))
        _hull_footprints(result, ax)
    for f in result.fenders:
        colour = _utilisation_colour(f["utilisation"])
        x, y = f["contact_point_m"][:2]
        ax.plot(x, y, "s", ms=6, mfc=colour, mec="k", zorder=4)
        text = f"{f['name']}\n{f['reaction_N'] / 1e3:.0f} kN" if f["in_contact"] \
            else f"{f['name']}\nopen"
        ax.annotate(text, (x, y), fontsize=6, ha="center", va="bottom", xytext=(0, 6),
                    textcoords="offset points")
    for g in result.guides:
        pile = contacts.pile_named(g["pile"]) if contacts is not None else None
        if pile is not None:
            ax.add_patch(Circle(pile.position, pile.radius + g["clearance_m"], fill=False,
                                ec=_utilisation_colour(1.0 if g["in_contact"] else 0.0),
                                lw=1.5, zorder=4))
            ax.annotate(f"{g['name']} {g['reaction_N'] / 1e3:.0f} kN", pile.position,
                        fontsize=6, xytext=(6, -10), textcoords="offset points")
    names = {h["name"]: h for h in result.hawsers}
    for leg in result.legs:
        h = names.get(leg.name)
        if h is None:
            continue
        p = leg.profile
        ax.plot(p["x_m"], p["y_m"], color=_utilisation_colour(h["utilisation"]), lw=2,
                ls="--" if h["slack"] else "-", zorder=2)
    sm = plt.cm.ScalarMappable(cmap="RdYlGn_r", norm=plt.Normalize(0, 1))
    ax.figure.colorbar(sm, ax=ax, label="fender / hawser utilisation", shrink=0.8)
    ax.set_aspect("equal")
    return ax
