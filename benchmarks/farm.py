"""A wind farm for the scaling benchmarks: an ``n`` x ``n`` grid of VolturnUS-S-like semis.

Each platform is free in six degrees of freedom on the linear hydrostatic model and held
by three chain catenaries of the IEA-15 MW VolturnUS-S mooring (Allen et al. 2020,
NREL/TP-5000-76773: 200 m of water, fairleads 14 m deep at 58 m radius, anchors at
837.6 m radius, 850 m of 185 mm studless chain, 5842 N/m submerged, EA 3270 MN), turned so
that no anchor leg points at a neighbour; neighbours in a row and in a column are joined by a
shared synthetic line hanging clear of the seabed. The platform's mass, buoyancy and
metacentre are chosen to float it at its draft with the mooring's pretension (a "like"
model for timing, not the report's hydrodynamic model). Every platform carries a constant
thrust toward +x (the rated thrust's order).
"""

from __future__ import annotations

import math

SPACING = 1800.0        # m between neighbouring platforms
FAIRLEAD_RADIUS, FAIRLEAD_DEPTH, ANCHOR_RADIUS = 58.0, 14.0, 837.6
CHAIN_LENGTH = 850.0
SHARED_SLACK = 25.0     # m of shared line beyond the fairlead-to-fairlead span
THRUST = 1.5e6          # N per platform


def farm_dict(n: int, *, thrust: float = THRUST, spacing: float = SPACING) -> dict:
    """The case dict of an ``n`` x ``n`` farm (``moorsolve.load_case`` reads it)."""
    bodies, points, lines = [], [], []
    for i in range(n):
        for j in range(n):
            name = f"T{i}_{j}"
            cx, cy = i * spacing, j * spacing
            bodies.append({
                "name": name, "position": [cx, cy, 0.0],
                "free": ["surge", "sway", "heave", "roll", "pitch", "yaw"],
                "mass": 1.95e7, "centre_of_gravity": [0.0, 0.0, -2.0],
                "hydrostatics": {"displaced_volume": 20206.0, "metacentre": [0.0, 0.0, 9.0],
                                 "waterplane_area": 446.7},
                "loads": {"force": [thrust, 0.0, 0.0, 0.0, 0.0, 0.0]}})
            for k in range(3):
                # Legs at 30, 150 and 270 deg: between the shared lines' directions.
                a = math.radians(30.0 + 120.0 * k)
                c, s = math.cos(a), math.sin(a)
                anchor = f"{name}_A{k}"
                points.append({"name": anchor, "position": [cx + ANCHOR_RADIUS * c,
                                                            cy + ANCHOR_RADIUS * s]})
                lines.append({"name": f"{name}_L{k}", "from": anchor,
                              "to": {"body": name, "at": [FAIRLEAD_RADIUS * c,
                                                          FAIRLEAD_RADIUS * s,
                                                          -FAIRLEAD_DEPTH]},
                              "segments": [{"type": "chain", "length": CHAIN_LENGTH}]})
    gap = spacing - 2 * FAIRLEAD_RADIUS
    for i in range(n):
        for j in range(n):
            for di, dj, tag in ((1, 0, "E"), (0, 1, "N")):
                if i + di >= n or j + dj >= n:
                    continue
                ux, uy = di, dj
                lines.append({
                    "name": f"S{i}_{j}{tag}",
                    "from": {"body": f"T{i}_{j}", "at": [FAIRLEAD_RADIUS * ux,
                                                         FAIRLEAD_RADIUS * uy,
                                                         -FAIRLEAD_DEPTH]},
                    "to": {"body": f"T{i + di}_{j + dj}",
                           "at": [-FAIRLEAD_RADIUS * ux, -FAIRLEAD_RADIUS * uy,
                                  -FAIRLEAD_DEPTH]},
                    "segments": [{"type": "shared", "length": gap + SHARED_SLACK}]})
    return {
        "name": f"{n} x {n} farm of VolturnUS-S-like semis on shared lines",
        "environment": {"depth": 200.0, "water_density": 1025.0, "gravity": 9.80665},
        "line_types": {
            "chain": {"weight_in_water": 5842.122, "ea": 3.27e9, "mbl": 2.2e7},
            "shared": {"weight_in_water": 300.0, "ea": 4.0e8, "mbl": 1.0e7}},
        "bodies": bodies, "points": points, "lines": lines}


def farm_case(n: int, **options):
    """The loaded :class:`moorsolve.Case` of :func:`farm_dict`."""
    import moorsolve
    return moorsolve.load_case(farm_dict(n, **options))
