"""The corrosion zone of each part of a line, from its solved shape.

Along each line's unstretched arc length from end A:

* ``bottom``: lying on the seabed (both ends of a profile interval on it);
* ``splash``: at or above ``splash_depth`` below the still water (tide included), the part
  intermittently wetted by tide and waves (DNV-OS-C101's splash zone, whose extent the
  waves, the tide and the unit's motion set, so the case gives it); a part above the
  water counts here too (the atmospheric zone corrodes no faster);
* ``catenary``: the rest, hanging in the water.

The crossing of the splash depth is interpolated linearly between profile points; the
touchdown is a profile point itself, so the bottom zone's ends are exact.
"""

from __future__ import annotations

import numpy as np

from ..model.build_wear import ZONES

__all__ = ["line_zones", "segment_runs"]

#: A profile point within this height [m] of the seabed lies on it (the solver's profile
#: puts grounded points on the seabed to round-off).
_ON_SEABED_M = 1e-4


def line_zones(line, line_result, environment, splash_depth: float | None) -> list:
    """Zone runs ``[(zone, s_start, s_end), ...]`` along ``line`` [m of unstretched arc
    length from end A], consecutive runs of one zone merged; without ``splash_depth``
    there is no splash zone."""
    p = line_result.profile
    s = np.asarray(p["s_m"], float)
    z = np.asarray(p["z_m"], float)
    bed = np.asarray(environment.seabed_z(np.asarray(p["x_m"], float),
                                          np.asarray(p["y_m"], float)), float)
    on = z <= bed + _ON_SEABED_M
    top = None if splash_depth is None else environment.water_level - splash_depth
    pieces = []
    for i in range(len(s) - 1):
        s0, s1, z0, z1 = float(s[i]), float(s[i + 1]), float(z[i]), float(z[i + 1])
        if s1 <= s0:
            continue
        if on[i] and on[i + 1]:
            pieces.append(("bottom", s0, s1))
        elif top is None or (z0 < top and z1 < top):
            pieces.append(("catenary", s0, s1))
        elif z0 >= top and z1 >= top:
            pieces.append(("splash", s0, s1))
        else:
            cut = s0 + (top - z0) / (z1 - z0) * (s1 - s0)
            first, second = ("catenary", "splash") if z0 < top else ("splash", "catenary")
            pieces += [(first, s0, cut), (second, cut, s1)]
    runs = []
    for zone, a, b in pieces:
        if runs and runs[-1][0] == zone:
            runs[-1] = (zone, runs[-1][1], b)
        else:
            runs.append((zone, a, b))
    # The profile spans the line: make the ends exact (round-off in the summed arcs).
    if runs:
        runs[0] = (runs[0][0], 0.0, runs[0][2])
        runs[-1] = (runs[-1][0], runs[-1][1], float(line.length))
    return runs


def segment_runs(line, runs: list) -> list:
    """Per segment of ``line``, its zone runs ``[(zone, length), ...]`` from end A [m]."""
    out, start = [], 0.0
    for seg in line.segments:
        end = start + seg.length
        mine = []
        for zone, a, b in runs:
            lo, hi = max(a, start), min(b, end)
            if hi - lo > 1e-9 * max(1.0, seg.length):
                mine.append((zone, hi - lo))
        total = sum(length for _, length in mine)
        if mine and total != seg.length:        # round-off: the runs add up to the segment
            zone, length = mine[-1]
            mine[-1] = (zone, length + seg.length - total)
        out.append(mine or [("catenary", seg.length)])
        start = end
    return out


def zone_lengths(runs: list) -> dict:
    """Total length [m] per zone of a segment's ``runs``."""
    totals = dict.fromkeys(ZONES, 0.0)
    for zone, length in runs:
        totals[zone] += length
    return totals
