"""Fibre rope on the seabed: how much of a leg's fibre rope lies on it, and the notes.

Offshore practice keeps fibre ropes (polyester, nylon, HMPE, plant fibre) off the seabed:
soil gets into the rope and abrades its yarns (API RP 2SM; DNV-OS-E301 Ch.2 Sec.4). A leg
whose line type is a fibre rope (``LineType.fibre``) reports the unstretched length of
fibre rope resting on the seabed in ``LegResult.fibre_grounded_m`` (None for a leg without
fibre rope), and the Result carries a note for each leg where it is not zero.
"""

from __future__ import annotations

import numpy as np

__all__ = ["fibre_grounded", "fibre_notes"]

#: Height above the seabed [m] under which a lumped node counts as resting on it.
_ON_SEABED = 1e-6


def fibre_grounded(case, leg, result) -> float | None:
    """Unstretched length [m] of ``leg``'s fibre rope on the seabed in its ``result``."""
    types = {seg.line_type.name: seg.line_type for seg in leg.segments}
    if not any(lt.fibre for lt in types.values()):
        return None
    if not leg.multi_segment and not result.segments:
        return float(result.grounded_length_m)
    if result.segments and "elements" not in result.segments[0]:
        # Segments from the block's lower end: picked by their type's name.
        return float(sum(s["grounded_length_m"] for s in result.segments
                         if types[s["type"]].fibre))
    # A lumped-node line: an element rests on the seabed when both its nodes do.
    p = result.profile
    env = case.environment
    on = np.asarray(p["z_m"]) <= np.array([env.seabed_z(x, y) for x, y in
                                           zip(p["x_m"], p["y_m"])]) + _ON_SEABED
    total, node = 0.0, 0
    counts = ([s["elements"] for s in result.segments] if result.segments
              else [len(on) - 1])
    for seg, n in zip(leg.segments, counts):
        if seg.line_type.fibre:
            both = on[node: node + n] & on[node + 1: node + n + 1]
            total += float(np.sum(both)) * seg.length / n
        node += n
    return total


def fibre_notes(case, results) -> list[str]:
    """A note per leg whose fibre rope touches the seabed."""
    notes = []
    for leg, lr in zip(case.lines, results):
        g = lr.fibre_grounded_m
        if g:
            names = sorted({seg.line_type.name for seg in leg.segments if seg.line_type.fibre})
            notes.append(f"leg {lr.name}: {g:.1f} m of fibre rope ({', '.join(names)}) lies "
                         "on the seabed (soil ingress and abrasion; offshore practice keeps "
                         "fibre rope off the seabed)")
    return notes
