"""Labels that do not collide: a greedy placer for the plan's names and numbers.

Each label is asked for near a point, with a preferred direction (away from the scene's
centre). Labels are placed one after another (in the order given: the most important
first): around its point, on rings of growing radius, the first spot inside the Axes whose
box overlaps no label placed before and crosses the fewest drawn lines and markers wins;
a label moved far from its point gets a thin leader. The test is made in display
coordinates once the figure's layout is final, so the labels are placed last and keep
out of the layout (``in_layout=False``): laying the figure out again does not move what
they were placed against.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

__all__ = ["LabelRequest", "place_labels", "LABEL_GID"]

#: The ``gid`` of every placed label (tests find them by it).
LABEL_GID = "moorsolve-label"
#: Distances [points] of the rings of candidate spots, and directions tried on each.
_RINGS = (9.0, 14.0, 21.0, 30.0, 42.0, 58.0)
_DIRECTIONS = 16
#: Beyond this distance [points] a label gets a leader line to its point.
_LEADER = 20.0


@dataclass
class LabelRequest:
    """A label asked for at ``xy`` (data coordinates), preferably toward ``direction``
    (a 2-vector, any length; None: no preference)."""

    text: str
    xy: tuple
    direction: Optional[tuple] = None
    fontsize: float = 7.0
    color: str = "k"


def _obstacles(ax, renderer) -> np.ndarray:
    """Display points along every line drawn on ``ax`` (about one per 3 pixels) and its
    markers: what a label should not cover."""
    pts = []
    for line in ax.get_lines():
        if not line.get_visible():
            continue
        xy = np.asarray(line.get_xydata(), float)
        if xy.ndim != 2 or len(xy) == 0:
            continue
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if not len(xy):
            continue
        d = line.get_transform().transform(xy)
        pts.append(d)
        if len(d) > 1:
            seg = np.diff(d, axis=0)
            n = np.maximum(1, (np.hypot(seg[:, 0], seg[:, 1]) / 3.0).astype(int))
            for k in np.nonzero(n > 1)[0]:
                t = np.linspace(0.0, 1.0, n[k] + 1)[1:-1, None]
                pts.append(d[k] + t * seg[k])
    return np.vstack(pts) if pts else np.zeros((0, 2))


def _overlap(a, b) -> float:
    """Overlap area of two boxes ``(x0, y0, x1, y1)``."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return w * h if w > 0 and h > 0 else 0.0


def place_labels(ax, requests: list) -> list:
    """Place ``requests`` (:class:`LabelRequest`) on ``ax``; returns the annotations.

    Call it after everything else is drawn on the figure: the figure is laid out first
    (``draw_without_rendering``) so that the display coordinates the placer works in are
    those the figure is saved with.
    """
    if not requests:
        return []
    fig = ax.figure
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    points_px = fig.dpi / 72.0
    frame = ax.get_window_extent(renderer)
    blocked = _obstacles(ax, renderer)
    placed: list = []
    out = []
    for req in requests:
        anchor = ax.transData.transform(np.asarray(req.xy, float))
        probe = ax.text(0, 0, req.text, fontsize=req.fontsize, ha="center", va="center")
        box = probe.get_window_extent(renderer)
        probe.remove()
        w, h = box.width + 2.0, box.height + 2.0
        prefer = None
        if req.direction is not None and np.hypot(*req.direction) > 0:
            prefer = math.atan2(req.direction[1], req.direction[0])
        best, best_score = None, math.inf
        for ring in _RINGS:
            for k in range(_DIRECTIONS):
                angle = 2 * math.pi * k / _DIRECTIONS
                turn = 0.0 if prefer is None else abs(
                    (angle - prefer + math.pi) % (2 * math.pi) - math.pi)
                r = ring * points_px
                # The box's nearest edge, not its centre, at the ring's distance.
                cx = anchor[0] + math.cos(angle) * (r + w / 2 * abs(math.cos(angle)))
                cy = anchor[1] + math.sin(angle) * (r + h / 2 * abs(math.sin(angle)))
                rect = (cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2)
                if (rect[0] < frame.x0 or rect[2] > frame.x1 or rect[1] < frame.y0
                        or rect[3] > frame.y1):
                    continue
                hits = sum(_overlap(rect, other) for other in placed)
                covered = np.count_nonzero(
                    (blocked[:, 0] > rect[0]) & (blocked[:, 0] < rect[2])
                    & (blocked[:, 1] > rect[1]) & (blocked[:, 1] < rect[3])) if len(blocked) else 0
                # An overlap with a label is never worth it while a clear spot exists.
                score = 1e6 * hits + 4.0 * covered + ring / 6.0 + 2.0 * turn
                if score < best_score:
                    best, best_score = (cx, cy, rect, ring), score
            if best is not None and best_score < 1e6 and best_score - best[3] / 6.0 < 4.5:
                break          # clear of labels and of lines at this distance: near enough
        if best is None:       # nowhere inside the Axes: beside the point
            best = (anchor[0], anchor[1] + h, (anchor[0] - w / 2, anchor[1] + h / 2,
                                               anchor[0] + w / 2, anchor[1] + 1.5 * h), 0.0)
        cx, cy, rect, ring = best
        placed.append(rect)
        offset = ((cx - anchor[0]) / points_px, (cy - anchor[1]) / points_px)
        arrow = (dict(arrowstyle="-", color="0.45", lw=0.6, shrinkA=0, shrinkB=2)
                 if ring >= _LEADER else None)
        note = ax.annotate(req.text, req.xy, xytext=offset, textcoords="offset points",
                           ha="center", va="center", fontsize=req.fontsize, color=req.color,
                           arrowprops=arrow, zorder=8, gid=LABEL_GID, annotation_clip=False)
        note.set_in_layout(False)
        out.append(note)
    return out
