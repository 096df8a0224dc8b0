"""The berth's part of a Result: every fender, every pile guide and every hawser.

A contact is reported closed or open by the side of its complementarity that holds at the
solution (``EquilibriumProblem.contact_report``'s ``closed`` column), so "in contact" is
decided exactly; an open contact's reaction, friction and force are then exactly zero (the
solution's are below 1e-15 N).
"""

from __future__ import annotations

import math

import numpy as np

from ...model import Case
from ...model.build_network import rotation
from ...physics.contact import fender_energy
from .blocks import CONTACT_COLUMNS


def _rows(problem, x, p) -> list:
    if not problem.contacts:
        return []
    table = np.atleast_2d(np.asarray(problem.contact_report(x, p), dtype=float))
    return [dict(zip(CONTACT_COLUMNS, (float(v) for v in r))) for r in table]


def _vector(row: dict, keys: str, closed: bool) -> list:
    return [row[k] if closed else 0.0 for k in keys]


#: Relative margin past the rated deflection before a fender counts as overloaded (a fender
#: placed at exactly its rated deflection is not, whatever the round-off).
OVER_RATED = 1e-9


def over_rated(compression: float, rated) -> bool:
    """Whether a compression [m] is past the rated deflection [m] (None: no rating)."""
    return rated is not None and compression > rated * (1.0 + OVER_RATED)


def _fender(fender, row: dict, friction: bool, hull=None) -> dict:
    closed = row["closed"] > 0.5
    law = fender.law
    compression = max(-row["gap"], 0.0) if (closed and law.kind != "rigid") else 0.0
    # Fully compressed, the fender is a block: the hull behind it bears on the wall.
    bears = hull is not None and hull["closed"] > 0.5
    tangential = _vector(row, ("ftx", "fty", "ftz"), closed)
    slip = math.sqrt(row["sx"] ** 2 + row["sy"] ** 2 + row["sz"] ** 2)
    energy = 0.0
    if law.kind != "rigid":
        energy = float(fender_energy(compression, *law.curve))
    rated = fender.rated_deflection if law.kind != "rigid" else None
    return {
        "name": fender.name, "body": fender.body, "bears_on": fender.wall or fender.pile,
        "mounted": fender.mounted, "in_contact": closed,
        "compression_m": compression, "gap_m": max(row["gap"], 0.0),
        "reaction_N": row["reaction"] if closed else 0.0,
        "friction_N": float(np.linalg.norm(tangential)),
        "stick": (slip < row["mobilisation"]) if (closed and friction) else None,
        "slip_m": slip if (closed and friction) else 0.0,
        "energy_J": energy, "rated_deflection_m": rated,
        "utilisation": None if rated is None else compression / rated,
        "overloaded": over_rated(compression, rated),
        "height_m": fender.height if law.kind != "rigid" else None,
        "hull_bears": bears,
        "hull_gap_m": None if hull is None else hull["gap"],
        "hull_reaction_N": hull["reaction"] if bears else 0.0,
        "hull_force_N": _vector(hull, ("Fx", "Fy", "Fz"), True) if bears else [0.0] * 3,
        "force_N": _vector(row, ("Fx", "Fy", "Fz"), closed),
        "contact_point_m": [row["cx"], row["cy"], row["cz"]],
        "normal": [row["nx"], row["ny"], row["nz"]],
    }


def _guide(case: Case, guide, rows: list, pose: np.ndarray) -> dict:
    pile = case.contacts.pile_named(guide.pile)
    R = rotation(*pose[3:])
    centre = pose[:3] + R @ np.asarray(guide.at, dtype=float)
    force = np.zeros(3)
    pads = []
    for k, row in enumerate(rows):
        closed = row["closed"] > 0.5
        f = np.array(_vector(row, ("Fx", "Fy", "Fz"), closed))
        force += f
        pads.append({"pad": k, "in_contact": closed,
                     "reaction_N": row["reaction"] if closed else 0.0, "force_N": f.tolist(),
                     "contact_point_m": [row["cx"], row["cy"], row["cz"]]})
    horizontal = math.hypot(force[0], force[1])
    bed = case.environment.seabed_z(*pile.position)
    offset = math.hypot(centre[0] - pile.position[0], centre[1] - pile.position[1])
    return {
        "name": guide.name, "body": guide.body, "pile": guide.pile,
        "in_contact": any(r["in_contact"] for r in pads),
        "reaction_N": horizontal, "force_N": force.tolist(),
        "offset_m": offset, "clearance_m": guide.clearance,
        "height_m": float(centre[2]),
        "on_pile": pile.top is None or float(centre[2]) <= pile.top,
        "pile_top_m": pile.top, "seabed_z_m": bed,
        # The pile as a cantilever from the seabed: the guide's horizontal force at the
        # collar's height.
        "pile_moment_Nm": horizontal * max(float(centre[2]) - bed, 0.0),
        "pads": pads,
    }


def contact_results(problem, case: Case, x, p, poses: np.ndarray) -> tuple:
    """``(fenders, guides)``: one dict per fender and per guide of ``case`` at the scaled
    point ``x``; ``poses`` holds every body's pose (6 per body: m and rad)."""
    rows = _rows(problem, x, p)
    by_element: dict = {}
    friction: dict = {}
    for point, row in zip(problem.contacts, rows):
        by_element.setdefault((point.owner, point.element), []).append(row)
        friction[point.element] = point.friction
    fenders = tuple(_fender(f, by_element[("fender", f.name)][0], friction[f.name],
                            by_element.get(("hull", f.name), [None])[0])
                    for f in case.contacts.fenders)
    index = {b.name: i for i, b in enumerate(case.bodies)}
    guides = tuple(_guide(case, g, by_element[("guide", g.name)],
                          poses[6 * index[g.body]: 6 * index[g.body] + 6])
                   for g in case.contacts.guides)
    return fenders, guides


def hawser_results(case: Case, legs) -> tuple:
    """One dict per weightless one-segment line (a hawser): tension, slack, T/MBL."""
    out = []
    for line, leg in zip(case.lines, legs):
        lt = line.line_type
        if lt.weight_in_water != 0 or line.multi_segment:
            continue
        tension = max(leg.fairlead_tension_N, leg.anchor_tension_N)
        chord = math.dist(leg.anchor, leg.fairlead)
        out.append({
            "name": line.name, "tension_N": tension, "slack": leg.slack,
            "length_m": line.length, "chord_m": chord,
            "pretension_N": line.segments[0].pretension,
            "mbl_N": lt.mbl, "t_over_mbl": None if not lt.mbl else tension / lt.mbl,
        })
    return tuple(out)


__all__ = ["contact_results", "hawser_results"]
