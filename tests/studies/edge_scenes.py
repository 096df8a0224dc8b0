"""Small scenes at the non-smooth points of the line model, as case dictionaries.

Each is built so that the edge is reached exactly at its equilibrium by symmetry or by
construction (no tuning against results): tendons and chains hanging straight above their
anchors, a catenary whose touchdown point is exactly at its anchor, a hawser pulled just
taut. The values are chosen, not taken from a real design.
"""

from __future__ import annotations

import math

RHO_G = 1025.0 * 9.80665


def tlp(tendon_weight: float = 3000.0, ea: float = 8.0e9, excess: float = 1.0e8,
        depth: float = 200.0, spread: float = 25.0, draft: float = 20.0,
        force=(0.0, 0.0, 0.0)) -> dict:
    """A tension-leg platform free in six degrees of freedom on four weighted tendons, each
    exactly above its anchor; ``excess`` [N] is the buoyancy above the platform's weight."""
    volume = 5.0e4
    mass = (volume * RHO_G - excess) / 9.80665
    corners = [(spread, spread), (-spread, spread), (-spread, -spread), (spread, -spread)]
    length = depth - draft - 2.0      # shorter than the span: stretched by the pretension
    return {
        "name": "TLP on four vertical tendons",
        "environment": {"depth": depth},
        "line_types": {"tendon": {"weight_in_water": tendon_weight, "ea": ea, "mbl": 1e9}},
        "bodies": [{"name": "tlp", "free": ["surge", "sway", "heave", "roll", "pitch", "yaw"],
                    "mass": mass, "centre_of_gravity": [0, 0, 5.0],
                    "inertia": [8.0e9, 8.0e9, 9.0e9], "loads": {"force": list(force)},
                    "hydrostatics": {"displaced_volume": volume, "metacentre": [0, 0, 6.0],
                                     "waterplane_area": 900.0}}],
        "lines": [{"name": f"T{k + 1}", "from": [x, y, -depth],
                   "to": {"body": "tlp", "at": [x, y, -draft]},
                   "segments": [{"type": "tendon", "length": length}]}
                  for k, (x, y) in enumerate(corners)],
    }


def vertical_chain_buoy(depth: float = 60.0, chain_weight: float = 400.0,
                        force=(0.0, 0.0, 0.0)) -> dict:
    """A buoy free in surge, sway and heave on one chain hanging straight down to its anchor
    (the chain shorter than the depth: lifted off the seabed all the way); a weightless
    chain (``chain_weight = 0``) is a taut tether."""
    return {
        "name": "buoy on one vertical chain",
        "environment": {"depth": depth},
        "line_types": {"chain": {"weight_in_water": chain_weight, "ea": 5.0e8, "mbl": 5e6}},
        "bodies": [{"name": "buoy", "free": ["surge", "sway", "heave"], "mass": 2.0e4,
                    "loads": {"force": list(force)},
                    "hydrostatics": {"displaced_volume": 60.0, "metacentre": [0, 0, 1.0],
                                     "waterplane_area": 12.0}}],
        "lines": [{"name": "chain", "from": [0.0, 0.0, -depth],
                   "to": {"body": "buoy", "at": [0.0, 0.0, -1.5]},
                   "segments": [{"type": "chain", "length": depth - 10.0}]}],
    }


def calm_and_tanker(load: float = 3.0e5, hawser_length: float = 60.0,
                    hawser_ea: float = 5.0e7) -> dict:
    """A CALM buoy on four catenary chains and a tanker on one weightless hawser to it,
    pushed away by ``load`` [N] along +x (both bodies free in the plane; the buoy in
    heave too)."""
    chains = []
    for k in range(4):
        a = math.radians(45.0 + 90.0 * k)
        chains.append({"name": f"C{k + 1}", "from": [300.0 * math.cos(a), 300.0 * math.sin(a)],
                       "to": {"body": "buoy", "at": [3.0 * math.cos(a), 3.0 * math.sin(a),
                                                     -2.0]},
                       "segments": [{"type": "chain", "length": 320.0}]})
    return {
        "name": "CALM buoy and tanker on a hawser",
        "environment": {"depth": 80.0},
        "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 6.0e8, "mbl": 8e6},
                       "hawser": {"weight_in_water": 0.0, "ea": hawser_ea, "mbl": 5e6}},
        "bodies": [{"name": "buoy", "free": ["surge", "sway", "heave"], "mass": 2.0e5,
                    "hydrostatics": {"displaced_volume": 400.0, "metacentre": [0, 0, 2.0],
                                     "waterplane_area": 100.0}},
                   {"name": "tanker", "position": [hawser_length + 130.0, 0.0, 0.0],
                    "free": ["surge", "sway", "yaw"], "loads": {"force": [load, 0, 0]}}],
        "lines": chains + [{"name": "hawser", "from": {"body": "buoy", "at": [4.0, 0, 2.0]},
                            "to": {"body": "tanker", "at": [-125.0, 0.0, 2.0]},
                            "segments": [{"type": "hawser", "length": hawser_length}]}],
    }


def touchdown_at_anchor(H: float = 2.0e5, w: float = 800.0, length: float = 300.0,
                        ea: float = 4.0e8) -> dict:
    """A held body on one chain whose touchdown point is exactly its anchor: the fairlead
    placed where the elastic catenary with horizontal tension ``H`` [N] and vertical tension
    ``w L`` at the fairlead (so zero at the anchor) puts it (Merkin's suspended spans)."""
    V = w * length
    X = (H / w) * math.asinh(V / H) + H * length / ea
    Z = (math.hypot(H, V) - H) / w + (length / ea) * (V - w * length / 2)
    depth = Z + 5.0
    return {
        "name": "catenary touching down at its anchor",
        "environment": {"depth": depth},
        "line_types": {"chain": {"weight_in_water": w, "ea": ea, "mbl": 1e7}},
        "bodies": [{"name": "hull", "free": []}],
        "lines": [{"name": "leg", "from": [-X, 0.0, -depth],
                   "to": {"body": "hull", "at": [0.0, 0.0, -5.0]},
                   "segments": [{"type": "chain", "length": length}]}],
    }
