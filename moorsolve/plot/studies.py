"""Pictures of studies: check utilisation, accuracy ladder, offset envelope, polar fields,
design optimisation and restoring curves."""

from __future__ import annotations

import numpy as np

#: The checks drawn as columns of the utilisation grid.
_TENSION_CHECKS = ("tension", "hawser tension")


def _tension_legs(report) -> list:
    legs = []
    for c in report.conditions:
        for item in c.items:
            if item.check in _TENSION_CHECKS and item.leg not in legs:
                legs.append(item.leg)
    return legs


def plot_utilisation(report, ax=None):
    """Tension utilisation per leg (columns) and condition (rows) of a check report.

    ``report`` is a :class:`moorsolve.checks.CheckReport`. Each cell is the line's tension
    over its allowed tension under the standard's factor (1 = at the limit); cells of the
    removed leg are blank, a condition without equilibrium is hatched. Hawsers (their
    working load limit) are columns as mooring lines are. Returns the Axes.
    """
    import matplotlib.pyplot as plt
    legs = _tension_legs(report)
    rows = [c.name for c in report.conditions]
    grid = np.full((len(rows), len(legs)), np.nan)
    for i, c in enumerate(report.conditions):
        for item in c.items:
            if item.check in _TENSION_CHECKS:
                grid[i, legs.index(item.leg)] = item.utilisation
    if ax is None:
        _, ax = plt.subplots(figsize=(1.0 + 0.6 * max(len(legs), 4), 1.0 + 0.35 * len(rows)))
    if not legs:          # nothing under tension is checked: say so, draw no empty grid
        ax.text(0.5, 0.5, "no line or hawser tension checked", ha="center", va="center",
                transform=ax.transAxes, fontsize=8)
        ax.set_axis_off()
        return ax
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
                r, g, b, _ = image.cmap(image.norm(grid[i, j]))
                dark = 0.299 * r + 0.587 * g + 0.114 * b < 0.5
                ax.text(j, i, f"{grid[i, j]:.2f}", ha="center", va="center", fontsize=7,
                        color="white" if dark else "k")
    ax.set_xticks(range(len(legs)), legs, fontsize=7)
    ax.set_yticks(range(len(rows)), rows, fontsize=7)
    ax.set_title(f"tension utilisation ({report.standard}; 1.0 = limit)", fontsize=9)
    bar = ax.figure.colorbar(image, ax=ax, label="utilisation", shrink=0.8)
    bar.ax.axhline(1.0, color="k", lw=1.5)
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
    import matplotlib.pyplot as plt
    legs = _tension_legs(report)
    fig = plt.figure(figsize=(1.6 + 0.6 * max(len(legs), 4), 1.4 + 0.35 * len(report.conditions)),
                     layout="constrained")
    return plot_utilisation(report, fig.add_subplot()).figure


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
    (east up the page's right). Each plot rings the heading that governs what it shows:
    the largest offset on the left, the worst tension on the right.

    Parameters
    ----------
    envelope : moorsolve.studies.envelope.Envelope
    axes : pair of polar matplotlib Axes, optional
    marks : dict of str to float, optional
        Named headings [deg] drawn as rays (e.g. ``{"bora": 225}``).

    Returns
    -------
    pair of matplotlib Axes
    """
    import matplotlib.pyplot as plt

    e = envelope
    if axes is None:
        fig = plt.figure(figsize=(10, 5.6), layout="constrained")
        axes = (fig.add_subplot(1, 2, 1, projection="polar"),
                fig.add_subplot(1, 2, 2, projection="polar"))
    ax_off, ax_t = axes
    for ax, values, label, unit, scale in (
            (ax_off, e.offset_m, "offset", "m", 1.0),
            (ax_t, e.worst_tension_N, "worst tension", "kN", 1e-3)):
        values = np.asarray(values, float) * scale
        ok = np.isfinite(values)
        theta, r = _closed(e.heading_deg, values)
        ax.plot(theta, r, "o-", markersize=3)
        r_max = np.nanmax(values) * 1.05 if ok.any() else 1.0
        if ok.any():
            k = int(np.nanargmax(values))
            h = float(e.heading_deg[k])
            ax.plot(np.radians(h), values[k], "o", markersize=12, markerfacecolor="none",
                    markeredgecolor="C3", markeredgewidth=1.8)
            what = (f"largest offset {values[k]:.3f} m" if unit == "m"
                    else f"worst tension {values[k]:,.0f} kN ({e.worst_leg[k]})")
            ax.set_xlabel(f"ringed: {what},\n{_heading_words(e, k)}", fontsize=9)
        _mark_headings(ax, marks, r_max)
        ax.set_ylim(0, r_max * 1.02)
        if e.compass.nautical:
            _bearing_ticks(ax, e.compass.north_deg)
            ax.set_title(f"{label} [{unit}] against the bearing the load goes toward",
                         fontsize=10)
        else:
            ax.set_title(f"{label} [{unit}] against heading (toward)", fontsize=10)
    return axes


def _heading_words(e, k: int) -> str:
    """Heading ``k`` as the case file writes it, short: ``wind from 045 deg``."""
    word = "from" if e.heading_key == "from_deg" else "toward"
    if e.compass.nautical:
        return f"{e.flows[0]} {word} {e.file_heading(k):03.0f} deg (compass)"
    return f"{e.flows[0]} {word} {e.file_heading(k):g} deg"


def _bearing_ticks(ax, north_deg):
    """Compass bearings (clockwise from north) on a polar axis drawn in the model's frame, so
    that the picture stays the plan view and only its labels change."""
    bearings = np.arange(0.0, 360.0, 45.0)
    ax.set_xticks(np.radians((north_deg - bearings) % 360.0))
    ax.set_xticklabels([("N " if b == 0 else "") + f"{b:03.0f}" for b in bearings])


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
    lo, hi = 0.97 * min(before + after), max(before + after)
    # Headroom above the bars for the legend (the axis starts near the shortest length:
    # the change is small against the lengths).
    ax1.set_ylim(lo, hi + 0.35 * (hi - lo))
    ax1.set_ylabel("unstretched length [m]")
    ax1.set_title(f"{opt.objective}: {opt.objective_start:,.0f} -> "
                  f"{opt.objective_optimum:,.0f} {opt.unit}")
    ax1.legend(loc="upper center", ncol=2)

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
    top = max([1.0] + [p.get_height() for p in ax2.patches if np.isfinite(p.get_height())])
    ax2.set_ylim(0.0, 1.3 * top)
    ax2.legend(fontsize=8, loc="upper center", ncol=len(kinds))
    ax2.figure.tight_layout()
    return ax1, ax2


def _utilisation(c) -> float:
    if c.kind in ("safety_factor", "grounded_length"):
        return c.limit / c.value if c.value > 0 else np.inf
    return c.value / c.limit if c.limit > 0 else (0.0 if c.value <= 0 else np.inf)


def plot_restoring(curve, ax=None, *, operating: float = 0.0, stiffness=None):
    """A restoring curve: the mooring force on the body against an imposed offset, with
    the operating point and, given the stiffness, its tangent there.

    Parameters
    ----------
    curve : dict
        From :func:`moorsolve.restoring_curve` (``dof``, ``offset``, ``force``,
        ``max_tension_N``).
    ax : matplotlib Axes, optional
    operating : float
        Offset of the operating point [m, or deg for yaw] on the curve's axis: 0 when the
        curve was taken ``about`` the equilibrium.
    stiffness : float or array (3, 3) or (6, 6), optional
        The diagonal stiffness of this DOF (or the whole matrix from
        :func:`moorsolve.stiffness`): drawn as the tangent at the operating point.

    Returns
    -------
    matplotlib Axes
        The force axis; the largest line tension is on a twin axis.
    """
    import matplotlib.pyplot as plt

    six = ("surge", "sway", "heave", "roll", "pitch", "yaw")
    planar = ("surge", "sway", "yaw")
    dof = curve["dof"]
    forces = np.asarray(curve["force"], float)
    k = (six if forces.shape[1] == 6 else planar).index(dof)
    offset = np.asarray(curve["offset"], float)
    rotational = dof in ("roll", "pitch", "yaw")
    scale, unit = (1e-6, "MN m") if rotational else (1e-3, "kN")
    force = forces[:, k] * scale
    name = {"surge": "force Fx", "sway": "force Fy", "heave": "force Fz", "roll": "moment Mx",
            "pitch": "moment My", "yaw": "moment Mz"}[dof]
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
    ax.plot(offset, force, "o-", color="C0", ms=3, label=f"mooring {name} on the body")
    f0 = float(np.interp(operating, offset, force))
    ax.plot(operating, f0, "o", ms=10, mfc="none", mec="C3", mew=2,
            label=f"operating point: {operating:g} {'deg' if rotational else 'm'}, "
                  f"{f0:,.1f} {unit}")
    if stiffness is not None:
        K = np.asarray(stiffness, float)
        if K.ndim == 2:
            j = (six if K.shape == (6, 6) else planar).index(dof)
            kk = float(K[j, j])
        else:
            kk = float(K)
        per = kk * (np.pi / 180 if rotational else 1.0) * scale
        span = np.array([offset.min(), offset.max()])
        ax.plot(span, f0 - per * (span - operating), "--", color="C3", lw=1,
                label=f"tangent: stiffness {kk:.4g} "
                      f"{'N m/rad' if rotational else 'N/m'}")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel(f"{curve['dof']} offset [{'deg' if rotational else 'm'}]")
    ax.set_ylabel(f"{'moment' if rotational else 'force'} [{unit}]")
    twin = ax.twinx()
    twin.plot(offset, np.asarray(curve["max_tension_N"]) / 1e3, color="0.5", lw=1, ls=":")
    twin.set_ylabel("largest fairlead tension [kN] (dotted)", color="0.4")
    ax.legend(fontsize=8, loc="best")
    ax.set_title(f"restoring curve, {curve['dof']}", fontsize=10)
    return ax
