"""Checks of fibre ropes: kept off the seabed and never slacker than their minimum tension.

Offshore practice keeps fibre mooring ropes (polyester, nylon, HMPE) off the seabed, where
soil gets into the rope and abrades its yarns, and above a least tension, where a rope
loses its construction or HMPE creeps and polyester suffers axial compression fatigue
(API RP 2SM; DNV-OS-E301 Ch.2 Sec.4). A line type says so with ``fibre: true`` (the
catalogue's fibre ropes and Baranov ropes are fibre by default) and ``min_tension``.

Per leg:

* ``fibre on seabed``: the unstretched length of fibre rope resting on the seabed
  (``LegResult.fibre_grounded_m``) must be zero;
* ``minimum tension``: the least effective tension along each segment of a line type with
  a ``min_tension`` must be at least that. Along a catenary the tension is least at the
  vertex (``H``) when the vertical tension changes sign inside the segment, and at an end
  otherwise; on the seabed it falls toward the anchor.
"""

from __future__ import annotations

import math

from .items import CheckItem

__all__ = ["fibre_items", "segment_min_tension", "LOWER_LIMIT_CHECKS"]

#: Checks whose value must be at least the limit (the others: at most).
LOWER_LIMIT_CHECKS = ("grounded length", "minimum tension")

#: Fibre rope on the seabed shorter than this [m] is taken as none (round-off).
_TOUCH = 1e-6


def segment_min_tension(leg, lr) -> list:
    """``[(line_type, least tension [N])]`` per segment of ``leg`` from its result."""
    if lr.segments and "elements" in lr.segments[0]:
        # A lumped-node line: the least node tension within each segment.
        tensions = list(lr.profile["tension_N"])
        out, node = [], 0
        for seg, s in zip(leg.segments, lr.segments):
            n = s["elements"]
            out.append((seg.line_type, min(tensions[node: node + n + 1])))
            node += n
        return out
    if lr.segments:
        # Segments from the block's lower end: their line type by name.
        types = {seg.line_type.name: seg.line_type for seg in leg.segments}
        out = []
        for s in lr.segments:
            least = min(s["top_tension_N"], s["bottom_tension_N"])
            vertex_inside = (s["top_vertical_N"] * s["bottom_vertical_N"] < 0
                             or s["grounded_length_m"] > 0)
            if vertex_inside:
                least = min(least, s["horizontal_tension_N"])
            out.append((types[s["type"]], least))
        return out
    least = min(lr.fairlead_tension_N, lr.anchor_tension_N)
    if lr.grounded_length_m > 0 or lr.slack:
        least = min(least, lr.horizontal_tension_N)
    elif lr.fairlead_vertical_N > 0 > lr.anchor_vertical_N:
        least = min(least, lr.horizontal_tension_N)
    if "tension_N" in lr.profile and len(lr.profile["tension_N"]) and not leg.multi_segment:
        least = min(least, float(min(lr.profile["tension_N"])))
    return [(leg.line_type, least)]


def fibre_items(condition: str, leg, lr) -> list:
    """The fibre-rope check items of one leg in one condition (none for a chain leg)."""
    items = []
    if lr.fibre_grounded_m is not None:
        g = lr.fibre_grounded_m
        ok = g <= _TOUCH
        items.append(CheckItem(condition=condition, leg=lr.name, check="fibre on seabed",
                               value=g, limit=0.0, unit="m",
                               utilisation=0.0 if ok else math.inf, passed=ok,
                               criterion="no fibre rope on the seabed"))
    worst = {}
    for lt, least in segment_min_tension(leg, lr):
        if lt.min_tension is not None and (lt.name not in worst or least < worst[lt.name][1]):
            worst[lt.name] = (lt, least)
    for name, (lt, least) in worst.items():
        need = lt.min_tension
        items.append(CheckItem(
            condition=condition, leg=lr.name, check="minimum tension", value=least,
            limit=need, unit="N",
            utilisation=(need / least if least > 0 else (math.inf if need > 0 else 0.0)),
            passed=least >= need,
            criterion=f"{name}: tension >= {need / 1e3:.1f} kN everywhere"))
    return items
