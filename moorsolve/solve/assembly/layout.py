"""The parameter layout: where each quantity of a scene sits in the problem's parameter vector.

Everything that may change between solves of one scene structure is a parameter, so one
built problem serves a sweep, a sensitivity or an optimisation. This module is the single
place that knows the order. The vector is, in blocks:

1. ``ENV_PARAMS``: flow speeds and headings [m/s, rad], the wave height, the legacy constant
   force of the first body ``(force_x, force_y, moment_z)`` (global) and the load factor.
2. ``LINE_PARAMS`` for every line: end A's and end B's coordinates as the case gives them
   (global for a fixed end; body frame for a body end; a free point's start position), its
   total length, its first segment's weight and compliance, and the seabed friction.
3. ``SEABED_PARAMS``: depth at the origin and the seabed's gradient; on a bathymetry grid,
   then every line's own seabed plane (``line[L].seabed``, :mod:`.bathymetry`).
4. For every multi-segment line, ``SEGMENT_PARAMS`` per segment and the net clump weight of
   each joint; for every lumped-node line ``DISCRETE_PARAMS`` per segment and its clumps;
   the current profile's rows when a lumped-node line sees it.
5. ``BODY_PARAMS`` for every body, then its extra 6x6 springs (36 values, when it has them)
   and ``MEMBER_PARAMS`` per exact hull member.
6. ``POINT_PARAMS`` for every free point.
7. The berth (:mod:`moorsolve.model.contact`): every wall's point, normal, friction and
   friction slip, every pile's axis, radius, friction, friction slip and bending stiffness,
   every fender's face and reaction law (its
   stiffness, or the table's deflections then reactions), every guide's collar centre and
   clearance.
8. The stretch-law parameters of every segment whose line type has a law other than
   Hooke's (:mod:`.stretch_params`), lines and segments in case order.

:class:`ParameterLayout` names every entry (``"line[L3].length"``, ``"body[hull].pose"``) for
the studies that set or differentiate by name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...model import Case
from ..lines.bathymetry import PLANE, initial_planes
from ..lines.stretch_params import law_slot

ENV_PARAMS = ("wind_speed", "wind_toward", "current_speed", "current_toward",
              "wave_hs", "wave_toward", "force_x", "force_y", "moment_z", "load_factor",
              "water_level")
LINE_PARAMS = ("anchor_x", "anchor_y", "anchor_z", "fair_x", "fair_y", "fair_z",
               "length", "weight", "ea_inv", "friction", "weight_air")
#: The ``legs:`` form's name for :data:`LINE_PARAMS`.
LEG_PARAMS = LINE_PARAMS
SEABED_PARAMS = ("depth", "gradient_x", "gradient_y")
SEGMENT_PARAMS = ("length", "weight", "ea_inv")
DISCRETE_PARAMS = ("length", "weight", "ea_inv", "diameter", "normal", "tangential", "side")
BODY_PARAMS = ("x", "y", "z", "roll", "pitch", "yaw", "force_x", "force_y", "force_z",
               "moment_x", "moment_y", "moment_z", "mass", "cg_x", "cg_y", "cg_z",
               "volume", "metacentre_x", "metacentre_y", "metacentre_z", "waterplane_area")
MEMBER_PARAMS = ("bottom", "top", "radius", "length", "width", "centre_x", "centre_y")
POINT_PARAMS = ("x", "y", "z", "mass", "volume")


def _end_coordinates(end) -> tuple:
    return tuple(float(v) for v in end.position)


def environment_parameters(case: Case, load_factor: float = 1.0) -> np.ndarray:
    """Block 1: the environment, the legacy constant force and the load factor."""
    env = case.environment
    force = (0.0, 0.0, 0.0)
    body = case.body
    if case.form == "legs" and body is not None and body.loads.force is not None:
        force = body.loads.force
    wind, current, waves = env.wind, env.current, env.waves
    return np.array([
        wind.speed if wind else 0.0, math.radians(wind.toward_deg) if wind else 0.0,
        current.speed if current else 0.0, math.radians(current.toward_deg) if current else 0.0,
        waves.hs if waves else 0.0, math.radians(waves.toward_deg) if waves else 0.0,
        force[0], force[1], force[2], load_factor, env.water_level], dtype=float)


def line_parameters(case: Case) -> np.ndarray:
    """Block 2: ``LINE_PARAMS`` of every line."""
    mu = case.environment.seabed.friction
    rows = []
    for line in case.lines:
        lt = line.line_type
        rows.append([*_end_coordinates(line.a), *_end_coordinates(line.b), line.length,
                     lt.weight_in_water, 1.0 / lt.ea if lt.ea else 0.0, mu,
                     lt.weight_in_air if lt.weight_in_air is not None else lt.weight_in_water])
    return np.asarray(rows, dtype=float).reshape(-1)


#: The ``legs:`` form's name for :func:`line_parameters`.
leg_parameters = line_parameters


def segment_parameters(case: Case, kinds) -> np.ndarray:
    """Blocks 3 and 4: the seabed, multi-segment and lumped-node line data, the profile."""
    values = [case.environment.depth, *case.environment.seabed.gradient]
    if case.environment.seabed.bathymetry is not None:
        values += initial_planes(case, kinds).ravel().tolist()
    discrete_profile = False
    for line, kind in zip(case.lines, kinds):
        if kind.multi:
            for seg in line.segments:
                lt = seg.line_type
                values += [seg.length, lt.weight_in_water, 1.0 / lt.ea if lt.ea else 0.0]
            values += [c.weight if c is not None else 0.0 for c in line.joint_clumps]
    for line, kind in zip(case.lines, kinds):
        if kind.discrete:
            discrete_profile = True
            for seg in line.segments:
                lt = seg.line_type
                drag = lt.drag
                values += [seg.length, lt.weight_in_water, 1.0 / lt.ea if lt.ea else 0.0,
                           lt.diameter or 0.0, drag.normal if drag else 0.0,
                           drag.tangential if drag else 0.0, drag.side if drag else 0.0]
            values += [c.weight if c is not None else 0.0 for c in line.joint_clumps]
    current = case.environment.current
    if discrete_profile and current.profile:
        # (z, signed speed along the heading) rows, or (z, ux, uy) when each has a heading.
        rows = current.profile_vectors() if current.profile_headings else current.profile
        values += [v for row in rows for v in row]
    return np.asarray(values, dtype=float)


def body_parameters(case: Case) -> np.ndarray:
    """Block 5: every body's rest pose (:meth:`~moorsolve.model.Body.rest_position`), force,
    mass and hydrostatics, springs and hull members."""
    values = []
    level = case.environment.water_level
    for body in case.bodies:
        # Held, sprung and in contact relative to its rest: a floating body's rises with
        # the tide (its draft kept), a structure's stays on the datum.
        x, y, z = body.rest_position(level)
        roll, pitch, yaw = (math.radians(a) for a in body.orientation_deg)
        force = (0.0,) * 6
        if case.form == "network" and body.loads.force is not None:
            f = body.loads.force
            force = tuple(f) if len(f) == 6 else (f[0], f[1], 0.0, 0.0, 0.0, f[2])
        hydro = body.hydrostatics
        values += [x, y, z, roll, pitch, yaw, *force, body.mass or 0.0,
                   *body.centre_of_gravity,
                   hydro.displaced_volume if hydro else 0.0,
                   *(hydro.metacentre if hydro else (0.0, 0.0, 0.0)),
                   hydro.waterplane_area if hydro else 0.0]
        if body.stiffness is not None:
            values += [v for row in body.stiffness for v in row]
        for m in body.hull:
            values += [m.bottom, m.top, m.radius, m.length, m.width, *m.centre]
    return np.asarray(values, dtype=float)


def point_parameters(case: Case) -> np.ndarray:
    """Block 6: every free point's start position, mass and volume."""
    values = []
    for point in case.free_points:
        values += [*point.position, point.mass, point.volume]
    return np.asarray(values, dtype=float)


def law_values(law) -> list:
    """A fender's reaction-law parameters: none (rigid), the stiffness, or the table's
    deflections then reactions."""
    if law.kind == "rigid":
        return []
    if law.kind == "linear":
        return [law.stiffness]
    return list(law.deflections) + list(law.reactions)


def hull_behind(fender) -> bool:
    """Whether the hull behind ``fender`` is modelled: a compliant fender whose full
    compression (its height) is known; the hull bears on the wall past it."""
    return fender.law.kind != "rigid" and fender.height is not None


def contact_parameters(case: Case) -> np.ndarray:
    """Block 7: walls, piles, fenders and guides."""
    c = case.contacts
    values = []
    for wall in c.walls:
        values += [*wall.point, *wall.normal, wall.friction, wall.friction_slip]
    for pile in c.piles:
        values += [*pile.position, pile.radius, pile.friction, pile.friction_slip,
                   pile.bending_stiffness or 0.0]
    for fender in c.fenders:
        values += [*fender.at, *law_values(fender.law)]
        if hull_behind(fender):
            values.append(fender.height)
    for guide in c.guides:
        values += [*guide.at, guide.clearance]
    return np.asarray(values, dtype=float)


#: Index of the load factor in every parameter vector.
LOAD_FACTOR_INDEX = ENV_PARAMS.index("load_factor")


@dataclass(frozen=True)
class ParameterLayout:
    """Names of the entries of a problem's parameter vector, each with its slice.

    ``names`` maps ``"env.wind_speed"``, ``"line[L3].anchor_x"``, ``"seabed.depth"``,
    ``"line[L3].segment[1].length"``, ``"line[L3].clump[0]"``, ``"body[hull].pose"`` (6),
    ``"body[hull].force"`` (6), ``"body[hull].mass"``, ``"body[hull].stiffness"`` (36),
    ``"point[B1].mass"``, ``"wall[quay].normal"`` (3), ``"fender[F1].law"`` ... to ``slice``
    objects into ``p``.
    """

    names: dict
    size: int

    def slice(self, name: str) -> slice:
        try:
            return self.names[name]
        except KeyError:
            raise KeyError(f"no parameter {name!r} in this problem") from None

    def load_mask(self) -> np.ndarray:
        """True for every entry that only scales with the load factor (flow speeds and
        headings, wave height, constant forces): the rest state does not depend on them.
        Not the water level (a tide), which moves the rest state itself."""
        mask = np.zeros(self.size, dtype=bool)
        for name, s in self.names.items():
            if name.startswith("env.") and name not in ("env.load_factor",
                                                        "env.water_level") or \
                    name.startswith("body[") and name.endswith("].force"):
                mask[s] = True
        return mask

    def index(self, name: str) -> int:
        s = self.slice(name)
        if s.stop - s.start != 1:
            raise KeyError(f"parameter {name!r} has {s.stop - s.start} entries, not one")
        return s.start


def build_layout(case: Case, kinds) -> ParameterLayout:
    """The :class:`ParameterLayout` of ``case`` with its line ``kinds``."""
    names: dict = {}
    cursor = 0

    def add(name: str, size: int = 1):
        nonlocal cursor
        names[name] = slice(cursor, cursor + size)
        cursor += size

    for key in ENV_PARAMS:
        add(f"env.{key}")
    for line in case.lines:
        for key in LINE_PARAMS:
            add(f"line[{line.name}].{key}")
    for key in SEABED_PARAMS:
        add(f"seabed.{key}")
    if case.environment.seabed.bathymetry is not None:
        # Each line's own seabed plane (solve/lines/bathymetry.py), only on a grid.
        for line in case.lines:
            add(f"line[{line.name}].seabed", len(PLANE))
        # and each free point's (the plane touching the grid where it rests).
        for point in case.free_points:
            add(f"point[{point.name}].seabed", len(PLANE))
    for line, kind in zip(case.lines, kinds):
        if kind.multi:
            for k in range(len(line.segments)):
                for key in SEGMENT_PARAMS:
                    add(f"line[{line.name}].segment[{k}].{key}")
            for j in range(len(line.segments) - 1):
                add(f"line[{line.name}].clump[{j}]")
    has_discrete = False
    for line, kind in zip(case.lines, kinds):
        if kind.discrete:
            has_discrete = True
            for k in range(len(line.segments)):
                for key in DISCRETE_PARAMS:
                    add(f"line[{line.name}].segment[{k}].{key}")
            for j in range(len(line.segments) - 1):
                add(f"line[{line.name}].clump[{j}]")
    current = case.environment.current
    if has_discrete and current.profile:
        add("current.profile", (3 if current.profile_headings else 2) * len(current.profile))
    for body in case.bodies:
        add(f"body[{body.name}].pose", 6)
        add(f"body[{body.name}].force", 6)
        add(f"body[{body.name}].mass")
        add(f"body[{body.name}].centre_of_gravity", 3)
        add(f"body[{body.name}].displaced_volume")
        add(f"body[{body.name}].metacentre", 3)
        add(f"body[{body.name}].waterplane_area")
        if body.stiffness is not None:
            add(f"body[{body.name}].stiffness", 36)
        for j in range(len(body.hull)):
            add(f"body[{body.name}].hull[{j}]", len(MEMBER_PARAMS))
    for point in case.free_points:
        add(f"point[{point.name}].position", 3)
        add(f"point[{point.name}].mass")
        add(f"point[{point.name}].volume")
    c = case.contacts
    for wall in c.walls:
        add(f"wall[{wall.name}].point", 3)
        add(f"wall[{wall.name}].normal", 3)
        add(f"wall[{wall.name}].friction")
        add(f"wall[{wall.name}].friction_slip")
    for pile in c.piles:
        add(f"pile[{pile.name}].position", 2)
        add(f"pile[{pile.name}].radius")
        add(f"pile[{pile.name}].friction")
        add(f"pile[{pile.name}].friction_slip")
        add(f"pile[{pile.name}].bending_stiffness")
    for fender in c.fenders:
        add(f"fender[{fender.name}].at", 3)
        if fender.law.kind != "rigid":
            add(f"fender[{fender.name}].law", len(law_values(fender.law)))
        if hull_behind(fender):
            add(f"fender[{fender.name}].height")
    for guide in c.guides:
        add(f"guide[{guide.name}].at", 3)
        add(f"guide[{guide.name}].clearance")
    for line in case.lines:
        for k, seg in enumerate(line.segments):
            if seg.line_type.stretch is not None:
                add(law_slot(line, k), len(seg.line_type.stretch.parameters()))
    return ParameterLayout(names=names, size=cursor)
