"""The plan view of an equilibrium: lines, anchors, bodies at rest and at equilibrium, the
offset, the loads in an inset force diagram, seabed contours, a legend, a scale and north."""

from __future__ import annotations

import math

import numpy as np

from .scene import Scene
from .style import (LOAD_COLOURS, POINT_STYLE, SEABED, as_scene, colour_bar, kn, line_colours,
                    line_label, new_axes, nice, si_force)

__all__ = ["plot_plan"]


# ---- plan -------------------------------------------------------------------------------


#: Markers of the ends fixed in the scene.
FIXED_STYLE = {"anchor": dict(marker="v", color="k", ms=6, label="anchor"),
               "bollard": dict(marker="o", mfc="0.25", mec="w", color="0.25", ms=7,
                               label="bollard (fixed above water)"),
               "fixed": dict(marker="D", color="0.25", ms=5, label="fixed point")}
BODY_FILL = "0.8"


def draw_bodies(ax, scene: Scene) -> list:
    """Each body's hull (:attr:`.scene.BodyView.shapes`) at rest (dashed) and at
    equilibrium (filled), its origin and fairleads; returns the legend handles."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    sources = []
    for body in scene.bodies:
        for shape in body.shapes:
            ring, rest = shape.ring, shape.ring_rest
            if len(ring) > 2:
                ax.fill(*rest.T, fill=False, ls="--", ec="0.5", lw=1, zorder=1)
                ax.fill(*ring.T, color=BODY_FILL, alpha=0.9, ec="0.3", lw=1, zorder=1,
                        hatch="..." if shape.kind == "fairleads" else None)
            elif len(ring) == 2:        # a body on one line end: origin to fairlead
                ax.plot(*rest.T, color="0.5", ls="--", lw=1, zorder=1)
                ax.plot(*ring.T, color="0.6", lw=7, alpha=0.8, solid_capstyle="round",
                        zorder=1)
            else:                       # lines meeting at the origin: a point
                ax.plot(*body.origin_rest[:2], "o", mfc="none", mec="0.5", ms=12, ls="",
                        zorder=1)
                ax.plot(*body.origin[:2], "o", color="0.7", mec="0.3", ms=12, zorder=1)
            if shape.source not in sources:
                sources.append(shape.source)
        ax.plot(*body.origin[:2], "+", color="k", ms=9, zorder=5)
        ax.plot(body.fairleads[:, 0], body.fairleads[:, 1], "s", color="k", ms=3, zorder=4)
    points = all(len(shape.ring) <= 1 for b in scene.bodies for shape in b.shapes)
    if points:              # lines meeting at each body's origin: drawn as a disc
        handles = [Line2D([], [], marker="o", color="0.7", mec="0.3", ms=9, ls="",
                          label="body at equilibrium (its lines meet at its origin)")]
    else:
        handles = [Patch(fc=BODY_FILL, ec="0.3", hatch="..." if "fairleads" in src else None,
                         label=f"body, {src}") for src in sources]
    if scene.bodies:
        rest = (Line2D([], [], marker="o", mfc="none", mec="0.5", ms=9, ls="",
                       label="body at rest") if points
                else Patch(fill=False, ec="0.5", ls="--", label="body at rest"))
        handles += [rest,
                    Line2D([], [], marker="+", color="k", ls="", ms=8,
                           label="body origin; fairleads")]
    return handles


def plot_plan(result, ax=None, *, colour_bar_: bool = True, legend=True):
    """Plan view: lines, anchors and bollards, touchdowns, clumps and buoys, bodies (their
    hulls) at rest and at equilibrium, the berth (quay walls, piles, fenders, guides), the
    offset and the body loads, the seabed depth (contours on a sloped seabed), a legend, a
    scale bar and, for compass cases, north. Labels are placed so that none overlaps
    another (:mod:`.labels`): draw anything else on the figure first.

    Parameters
    ----------
    result : Result or Scene
    ax : matplotlib Axes, optional
    colour_bar_ : bool
        Draw the colour bar beside the Axes.
    legend : bool, "figure" or "narrow"
        Draw the legend below the Axes in three columns (``"figure"``: four, for the wide
        plan of the equilibrium figure; ``"narrow"``: two, for a plan beside other views).

    Returns
    -------
    matplotlib Axes
    """
    from matplotlib.lines import Line2D

    from .berth import draw_berth_plan
    from .labels import LabelRequest, place_labels
    scene = as_scene(result)
    ax = new_axes(ax, figsize=(9, 8))
    colour, _, _ = line_colours(scene)
    lo, hi = scene.extent(min_ratio=0.2)
    span = float(max(hi[0] - lo[0], hi[1] - lo[1], 1.0))
    xlim = (lo[0] - 0.06 * span, hi[0] + 0.06 * span)
    ylim = (lo[1] - 0.10 * span, hi[1] + 0.06 * span)      # room for the scale bar
    handles, labels = [], []
    if scene.sloped:
        gx = np.linspace(*xlim, 60)
        gy = np.linspace(ylim[0], ylim[1] + 0.6 * span, 60)    # the inset may raise the top
        X, Y = np.meshgrid(gx, gy)
        depth = -scene.seabed_z(X, Y)
        filled = ax.contourf(X, Y, depth, levels=10, cmap="Blues", alpha=0.35, zorder=0)
        lines = ax.contour(X, Y, depth, levels=filled.levels, colors="0.45",
                           linewidths=0.5, zorder=0)
        ax.clabel(lines, fmt="%.1f m", fontsize=6)
        handles.append(Line2D([], [], color="0.45", lw=0.5, label="seabed depth contours"))
    handles += draw_bodies(ax, scene)
    handles += draw_berth_plan(ax, scene.berth, labels)
    centre = (np.mean([line.fairlead[:2] for line in scene.lines], axis=0) if scene.lines
              else np.zeros(2))
    if len(scene.bodies) == 1:
        centre = scene.bodies[0].origin[:2]
    for line in scene.removed:
        ax.plot(*line.xyz[:, :2].T, color="0.55", lw=1.2, ls=(0, (4, 3)), zorder=2)
        labels.insert(0, LabelRequest(f"{line.name} removed", tuple(line.anchor[:2]),
                                      tuple(line.anchor[:2] - centre), color="0.4"))
    if scene.removed:
        handles.append(Line2D([], [], color="0.55", lw=1.2, ls=(0, (4, 3)),
                              label="removed line (where it was)"))
    fixed_kinds = []
    line_labels = []
    for line in scene.lines:
        c = colour(line)
        xy = line.xyz[:, :2]
        if line.grounded.any():
            ground = np.where(line.grounded[:, None], xy, np.nan)
            ax.plot(*ground.T, color=SEABED, lw=5, alpha=0.55, solid_capstyle="round",
                    zorder=2)
        ax.plot(*xy.T, color=c, lw=1.8, ls=":" if line.slack else "-", zorder=3)
        for kind, end in ((line.a_kind, line.xyz[0]), (line.b_kind, line.xyz[-1])):
            if kind in FIXED_STYLE:
                style = {k: v for k, v in FIXED_STYLE[kind].items() if k != "label"}
                ax.plot(*end[:2], ls="", zorder=4, **style)
                if kind not in fixed_kinds:
                    fixed_kinds.append(kind)
        if line.touchdown is not None:
            ax.plot(*line.touchdown[:2], "o", mfc="white", mec=c, ms=5, zorder=4)
        text = line_label(line, scene).replace("\n", " ")
        if line.a_kind in FIXED_STYLE:      # labelled beyond its fixed end
            line_labels.append(LabelRequest(text, tuple(line.anchor[:2]),
                                            tuple(line.anchor[:2] - centre)))
        elif np.ptp(xy[:, 0]) + np.ptp(xy[:, 1]) > 0.08 * span:   # a shared line: middle
            line_labels.append(LabelRequest(text, tuple(xy[len(xy) // 2]), None, fontsize=6,
                                            color="0.25"))
    labels[:0] = line_labels
    for kind in fixed_kinds:
        style = dict(FIXED_STYLE[kind])
        handles.append(Line2D([], [], ls="", **style))
    if any(line.touchdown is not None for line in scene.lines):
        handles.append(Line2D([], [], marker="o", mfc="white", mec="k", ls="",
                              label="touchdown"))
    if any(line.grounded.any() for line in scene.lines):
        handles.append(Line2D([], [], color=SEABED, lw=5, alpha=0.55,
                              label="line on the seabed"))
    if any(line.slack for line in scene.lines):
        handles.append(Line2D([], [], color="k", ls=":", label="slack line"))
    for kind in ("clump", "buoy", "joint", "free"):
        pts = [p for p in scene.points if p.kind == kind]
        if pts:
            style = dict(POINT_STYLE[kind])
            label = style.pop("label")
            xy = np.array([p.xyz[:2] for p in pts])
            ax.plot(xy[:, 0], xy[:, 1], ls="", zorder=5, **style)
            handles.append(Line2D([], [], ls="", label=label, **style))
    ax.set_aspect("equal")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    handles += _arrows(ax, scene, span)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    _scale_bar(ax, span)
    if scene.north_deg is not None:
        _north(ax, scene.north_deg)
    title = "plan"
    if len(scene.bodies) == 1:
        b = scene.bodies[0]
        title += (f": offset {np.hypot(*b.offset[:2]):.3f} m "
                  f"(x {b.offset[0]:+.3f}, y {b.offset[1]:+.3f}), yaw {b.yaw_deg:+.3f} deg")
    elif scene.bodies:
        far = max(scene.bodies, key=lambda b: np.hypot(*b.offset[:2]))
        title += (f": {len(scene.bodies)} bodies; largest offset "
                  f"{np.hypot(*far.offset[:2]):.3f} m ({far.name})")
    if not scene.sloped:
        handles.append(Line2D([], [], color=SEABED, lw=2,
                              label=f"flat seabed, depth {scene.depth:.2f} m"))
    ax.set_title(title, fontsize=9)
    if colour_bar_:
        bar = colour_bar(ax, scene, shrink=0.7, aspect=30, pad=0.01)
        if scene.berth.fenders and scene.colour_by == "utilisation":
            bar.set_label("utilisation: line tension / MBL;\nfender compression / rated "
                          "deflection")
        elif scene.berth.fenders:      # lines by tension: the fenders need their own scale
            import matplotlib as mpl
            ax.figure.colorbar(mpl.cm.ScalarMappable(cmap="RdYlGn_r",
                                                     norm=mpl.colors.Normalize(0, 1)),
                               ax=ax, label="fender compression / rated deflection",
                               shrink=0.8, aspect=30, pad=0.01)
    if legend:
        from matplotlib.transforms import ScaledTranslation
        below = ScaledTranslation(0.0, -34 / 72, ax.figure.dpi_scale_trans)  # under x label
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                  bbox_transform=ax.transAxes + below,
                  ncol={"figure": 4, "narrow": 2}.get(legend, 3),
                  fontsize=7, frameon=False, handlelength=2.2, columnspacing=1.2)
    place_labels(ax, labels)
    return ax


def _arrows(ax, scene: Scene, span: float) -> list:
    """The offset of every body as an arrow from its rest origin, and the loads of the body
    that carries the most in an inset force diagram (head to tail, the total closing it)
    in the emptiest corner."""
    from matplotlib.lines import Line2D
    if not scene.bodies:
        return []
    handles = []
    sizes = [float(np.hypot(*b.offset[:2])) for b in scene.bodies]
    largest = max(sizes)
    # Below what the legend's three decimals show, an offset is the solver's rounding:
    # magnified to a visible arrow it would draw noise as a displacement.
    if largest < 5e-4:
        handles.append(Line2D([], [], color="none", label="offset < 0.5 mm (not drawn)"))
    else:
        gain = nice(0.12 * span / largest) if largest < 0.12 * span else 1.0
        for body in scene.bodies:
            ax.annotate("", xy=body.origin_rest[:2] + gain * body.offset[:2],
                        xytext=body.origin_rest[:2], zorder=7,
                        arrowprops=dict(arrowstyle="-|>", color="tab:red", lw=1.8, ls="--",
                                        shrinkA=0, shrinkB=0))
        which = "" if len(scene.bodies) == 1 else \
            f" (largest: {scene.bodies[int(np.argmax(sizes))].name})"
        handles.append(Line2D([], [], color="tab:red", ls="--", lw=1.8,
                              label=f"offset {largest:.3f} m{which}" + (
                                  f" (drawn x{gain:g})" if gain != 1 else "")))
    carried = [(sum(np.hypot(*v[:2]) for v in b.loads.values()), k)
               for k, b in enumerate(scene.bodies)]
    body = scene.bodies[max(carried)[1]]
    loads = {k: np.array(v[:2]) for k, v in body.loads.items() if np.hypot(*v[:2]) > 0}
    if loads:
        title = "body loads" if len(scene.bodies) == 1 else f"loads on {body.name}"
        _load_inset(ax, scene, loads, title)
        total = np.sum(list(loads.values()), axis=0)
        for name, f in list(loads.items()) + ([("total", total)] if len(loads) > 1 else []):
            wide = name == "total"
            handles.append(Line2D([], [], color=LOAD_COLOURS.get(name, "tab:red"),
                                  lw=4 if wide else 2, alpha=0.45 if wide else 1.0,
                                  label=f"{name.replace('_', ' ')} load {kn(np.hypot(*f))} "
                                        f"toward {_direction(f, scene.north_deg)} (inset)"))
    return handles


def _direction(f, north_deg) -> str:
    """The direction of a horizontal force in the case's words: degrees counter-clockwise
    from +x, or a compass bearing when the case gives bearings."""
    angle = math.degrees(math.atan2(f[1], f[0]))
    if north_deg is None:
        return f"{round(angle) % 360:.0f} deg"
    return f"{round(north_deg - angle) % 360:03.0f} (compass)"


def _emptiest_corner(ax, scene: Scene) -> tuple:
    """Inset bounds (axes fraction) in the corner with the fewest drawn points."""
    pts = np.vstack([line.xyz[:, :2] for line in scene.lines + scene.removed]
                    + [b.outline[:, :2] for b in scene.bodies])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    u, v = (pts[:, 0] - x0) / (x1 - x0), (pts[:, 1] - y0) / (y1 - y0)
    w, h = 0.26, 0.26
    corners = [(0.01, 1 - h - 0.01), (1 - w - 0.01, 1 - h - 0.01), (0.01, 0.08),
               (1 - w - 0.01, 0.08)]
    counts = [np.count_nonzero((u > cx - 0.03) & (u < cx + w + 0.03) & (v > cy - 0.03)
                               & (v < cy + h + 0.03)) for cx, cy in corners]
    if min(counts) > 0:
        # Every corner is taken: raise the top of the plan to free a band for the inset.
        top = y0 + (pts[:, 1].max() - y0) / (1 - h - 0.06)
        ax.set_ylim(y0, max(y1, top))
        return corners[0][0], corners[0][1], w, h
    cx, cy = corners[int(np.argmin(counts))]
    return cx, cy, w, h


def _load_inset(ax, scene: Scene, loads: dict, title: str) -> None:
    """The body loads (global frame) as a force polygon in an inset, with a force scale."""
    bounds = _emptiest_corner(ax, scene)
    inset = ax.inset_axes(bounds)
    inset.set_facecolor((1, 1, 1, 0.85))
    total = np.sum(list(loads.values()), axis=0)
    items = list(loads.items()) + ([("total", total)] if len(loads) > 1 else [])
    tips = [np.zeros(2)]
    for _, f in loads.items():
        tips.append(tips[-1] + f / 1e3)
    tips = np.array(tips)
    reach = max(float(np.ptp(tips[:, 0])), float(np.ptp(tips[:, 1])), 1e-9)
    for name, f in items:
        start = np.zeros(2) if name == "total" else tips[list(loads).index(name)]
        end = start + f / 1e3
        wide = name == "total"
        inset.annotate("", xy=end, xytext=start,
                       arrowprops=dict(arrowstyle="-|>", color=LOAD_COLOURS.get(name, "tab:red"),
                                       lw=3.5 if wide else 1.6, alpha=0.45 if wide else 1.0,
                                       shrinkA=0, shrinkB=0))
    # Square limits about the polygon, so the inset keeps its square box.
    centre = (tips.min(axis=0) + tips.max(axis=0)) / 2
    half = 0.62 * reach
    inset.set_xlim(centre[0] - half, centre[0] + half)
    inset.set_ylim(centre[1] - half, centre[1] + half)
    inset.set_aspect("equal", adjustable="box")
    inset.set_xticks([])
    inset.set_yticks([])
    key = nice(0.4 * reach)
    inset.set_title(title, fontsize=7, pad=2)
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar
    inset.add_artist(AnchoredSizeBar(inset.transData, key, si_force(key * 1e3),
                                     "lower right", pad=0.2, sep=2, frameon=False,
                                     fontproperties={"size": 6}))


def _scale_bar(ax, span: float) -> None:
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar
    length = nice(0.2 * span)
    ax.add_artist(AnchoredSizeBar(ax.transData, length, f"{length:g} m", "lower right",
                                  pad=0.4, sep=3, frameon=False, size_vertical=0,
                                  fontproperties={"size": 7}))


def _north(ax, north_deg: float) -> None:
    t = math.radians(north_deg)
    ax.annotate("N", xy=(0.93 + 0.05 * math.cos(t), 0.9 + 0.05 * math.sin(t)),
                xytext=(0.93, 0.9), xycoords="axes fraction", textcoords="axes fraction",
                ha="center", va="center", fontsize=8, fontweight="bold",
                arrowprops=dict(arrowstyle="-|>", color="k"))


