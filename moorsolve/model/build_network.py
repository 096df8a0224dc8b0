"""The network form of a case file: ``bodies``, ``points`` and ``lines`` between any two ends.

Schema (SI units; see "The scene as a network")::

    bodies:                                   optional list
      - name: str                             required, unique among bodies
        position: [x, y, z]                   body-frame origin in the scene [m]; default 0
        orientation_deg: [roll, pitch, yaw]   default 0
        free: [surge, sway, heave, roll, pitch, yaw]   any subset, [] = held; default all six
                                              with mass and hydrostatics, else surge, sway, yaw
        mass: > 0 [kg]                        needed when heave, roll or pitch is free
        centre_of_gravity: [x, y, z]          body frame [m]
        hydrostatics: {displaced_volume >= 0 [m^3], metacentre: [x, y, z],
                       waterplane_area >= 0 [m^2]}
        hull: [{shape: cylinder, radius, bottom, top, centre: [x, y]}
               | {shape: box, length, width, bottom, top, centre}]   exact buoyancy instead
        stiffness: 6x6                        extra linear springs about the rest pose [SI]
        fixed_to: water | seabed              default water: a floating body, held (and at
                                              rest) relative to the still water, rising
                                              with environment.water_level; seabed: a
                                              structure on the datum (not free in heave)
        added_mass: 6x6, inertia: [Ixx, Iyy, Izz]   for natural periods (inertia: motions too)
        hydrodynamics: {source: table | wamit, ...}  frequency-dependent (:mod:`.build_sea`)
        damping: {linear: [6], critical_fraction: {DOF: fraction}}   extra, for motions
        loads: {force: [Fx, Fy, Mz] or [Fx, Fy, Fz, Mx, My, Mz], wind, current, wave_drift}
    points:                                   optional list
      - {name, position: [x, y, z] or [x, y] (on the seabed), free: bool, mass >= 0 [kg],
         volume >= 0 [m^3]}
    lines:                                    a list; may be absent or empty where fenders
                                              or pile guides hold every free body
      - name: str
        from: END                             end A
        to: END                               end B
        segments: [...]                       as in a leg, from end A; a one-segment line of
                                              a weightless elastic type (a hawser) may give
                                              {type, pretension: N} instead of a length: the
                                              tension at the case-file pose sets the length
        anchor_type: ANCHOR                   optional, for an end A on the seabed
    walls, piles, fenders, guides:            the berth (:mod:`.build_contact`)
    END: a point name | [x, y] (on the seabed) | [x, y, z] fixed | {body: NAME, at: [x, y, z]}

Beyond the schema: names are unique; every end names a known body or point; a free point or
a free body that no line, contact (fender, pile guide) or spring holds is refused; a body free in heave,
roll or pitch needs a mass and hydrostatics; fixed ends lie on or above the seabed; an
inextensible line between fixed ends is long enough to reach.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from ..errors import CaseError
from .bodies import DOFS, FIXED_TO, HULL_SHAPES, PLANAR_DOFS, VERTICAL_DOFS, Body, \
    Hydrostatics, HullMember, Point, ShipOutline
from .build_lines import _anchor_type, _segments
from .build_loads import _loads
from .build_sea import extra_damping, hydrodynamics
from .environment import Environment
from .fields import (FAIRLEAD_Z_MAX, check_choices, MAX_AREA, MAX_DEPTH, MAX_LINE_LENGTH,
                     MIN_LINE_LENGTH,
                     check_list,
                     check_mapping, check_name, check_point, field_path, nullable_quantity,
                     optional_quantity, quantity, schema_quantity)
from .lines import End, Line
from .loads import BodyLoads
from .units import format_si, show_value

#: The schema section of each hull member shape.
_HULL_SECTIONS = {"cylinder": "hull_cylinder", "box": "hull_box"}


def rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) Ry(pitch) Rx(roll)`` [rad] as a numpy array (for checks at the case pose)."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _matrix6(raw, path: str) -> tuple:
    rows = check_list(raw, path, "a 6x6 matrix (a list of 6 rows of 6 numbers, SI)")
    if len(rows) != 6:
        raise CaseError(path, f"{len(rows)} rows; a 6x6 matrix has 6 rows of 6 numbers")
    out = []
    for i, row_raw in enumerate(rows):
        rpath = field_path(path, i)
        row = check_list(row_raw, rpath, "a row of 6 numbers")
        if len(row) != 6:
            raise CaseError(rpath, f"{show_value(row_raw)} has {len(row)} values; a row of a 6x6 "
                                   "matrix has 6")
        out.append(tuple(quantity(v, field_path(rpath, j), "dimensionless")
                         for j, v in enumerate(row)))
    return tuple(out)


def _free_dofs(raw, path: str) -> tuple:
    return check_choices(raw, path, DOFS)


def _hydrostatics(raw, path: str) -> Hydrostatics:
    m = check_mapping(raw, path, section="hydrostatics")
    volume = quantity(m["displaced_volume"], field_path(path, "displaced_volume"), "volume",
                      ge=0)
    metacentre = ((0.0, 0.0, 0.0) if "metacentre" not in m
                  else check_point(m["metacentre"], field_path(path, "metacentre"), (3,)))
    area = optional_quantity(m, path, "waterplane_area", "area", 0.0, ge=0, le=MAX_AREA)
    return Hydrostatics(displaced_volume=volume, metacentre=metacentre, waterplane_area=area)


def _hull_member(raw, path: str) -> HullMember:
    shape = raw.get("shape") if isinstance(raw, Mapping) else None
    if shape not in HULL_SHAPES:
        raise CaseError(field_path(path, "shape"), f"unknown hull shape {show_value(shape)}; "
                                                   f"allowed: {', '.join(HULL_SHAPES)}")
    size = ("radius",) if shape == "cylinder" else ("length", "width")
    m = check_mapping(raw, path, section=_HULL_SECTIONS[shape])
    bottom = quantity(m["bottom"], field_path(path, "bottom"), "length")
    top = quantity(m["top"], field_path(path, "top"), "length", gt=bottom)
    dims = {k: quantity(m[k], field_path(path, k), "length", gt=0) for k in size}
    centre = (0.0, 0.0) if "centre" not in m else check_point(m["centre"],
                                                              field_path(path, "centre"), (2,))
    return HullMember(shape=shape, bottom=bottom, top=top, centre=centre, **dims)


def _body(raw, path: str, environment: Environment) -> Body:
    m = check_mapping(raw, path, section="network_body")
    name = check_name(m["name"], field_path(path, "name"), "body name")
    position = ((0.0, 0.0, 0.0) if "position" not in m
                else check_point(m["position"], field_path(path, "position"), (3,)))
    orientation = (0.0, 0.0, 0.0)
    if "orientation_deg" in m:
        opath = field_path(path, "orientation_deg")
        items = check_list(m["orientation_deg"], opath, "[roll, pitch, yaw] [deg]")
        if len(items) != 3:
            raise CaseError(opath, f"{show_value(m['orientation_deg'])} has {len(items)} values; "
                                   "it must be [roll, pitch, yaw] [deg]")
        orientation = tuple(quantity(v, field_path(opath, i), "angle")
                            for i, v in enumerate(items))
        if abs(orientation[1]) >= 90.0:
            raise CaseError(field_path(opath, 1), f"pitch {orientation[1]:g} deg must be between "
                                                  "-90 and 90 deg (z-y-x angles)")
    mass = nullable_quantity(m, path, "mass", "mass", gt=0)
    cg = ((0.0, 0.0, 0.0) if "centre_of_gravity" not in m
          else check_point(m["centre_of_gravity"], field_path(path, "centre_of_gravity"), (3,)))
    hydro = (None if m.get("hydrostatics") is None
             else _hydrostatics(m["hydrostatics"], field_path(path, "hydrostatics")))
    hull = ()
    if m.get("hull") is not None:
        hpath = field_path(path, "hull")
        items = check_list(m["hull"], hpath, "a list of hull members {shape, ...}")
        hull = tuple(_hull_member(item, field_path(hpath, i)) for i, item in enumerate(items))
        if hydro is not None and hull:
            raise CaseError(hpath, "give either hydrostatics (the linear model) or hull (exact "
                                   "buoyancy of its members), not both")
    stiffness = (None if m.get("stiffness") is None
                 else _matrix6(m["stiffness"], field_path(path, "stiffness")))
    added = (None if m.get("added_mass") is None
             else _matrix6(m["added_mass"], field_path(path, "added_mass")))
    inertia = None
    if m.get("inertia") is not None:
        ipath = field_path(path, "inertia")
        items = check_list(m["inertia"], ipath, "[Ixx, Iyy, Izz] [kg m^2]")
        if len(items) != 3:
            raise CaseError(ipath, f"{show_value(m['inertia'])} has {len(items)} values; it must "
                                   "be [Ixx, Iyy, Izz] [kg m^2] about the centre of gravity")
        inertia = tuple(quantity(v, field_path(ipath, i), "moment_of_inertia", ge=0)
                        for i, v in enumerate(items))
    buoyant = hydro is not None or bool(hull)
    if "free" in m:
        free = _free_dofs(m["free"], field_path(path, "free"))
    else:
        free = DOFS if (mass is not None and buoyant) else PLANAR_DOFS
    for dof in free:
        if dof in VERTICAL_DOFS:
            missing = [k for k, ok in (("mass", mass is not None),
                                       ("hydrostatics (or hull)", buoyant)) if not ok]
            if missing:
                raise CaseError(field_path(path, "free"),
                                f"body {name!r} is free in {dof} but has no "
                                f"{' and no '.join(missing)}: heave, roll and pitch balance "
                                "weight against buoyancy; give them or hold that DOF")
    loads = (BodyLoads() if m.get("loads") is None
             else _loads(m["loads"], field_path(path, "loads"), (3, 6)))
    fixed_to = fixed_to_field(m, path, free)
    sea = {}
    if m.get("hydrodynamics") is not None:
        sea["hydrodynamics"] = hydrodynamics(m["hydrodynamics"], field_path(path, "hydrodynamics"),
                                             environment.water_density, environment.gravity)
        if getattr(sea["hydrodynamics"], "source", "") == "capytaine" and not hull:
            raise CaseError(field_path(path, "hull"),
                            f"body {name!r}: source capytaine meshes the body's hull members; "
                            "give hull: [{shape: cylinder | box, ...}]")
    if m.get("damping") is not None:
        sea["damping"] = extra_damping(m["damping"], field_path(path, "damping"))
    return Body(name=name, free=free, position=position, orientation_deg=orientation,
                mass=mass, centre_of_gravity=cg, hydrostatics=hydro, hull=hull,
                stiffness=stiffness, loads=loads, added_mass=added, inertia=inertia,
                fixed_to=fixed_to, **outline_fields(m, path), **sea)


def outline_fields(m: Mapping, path: str) -> dict:
    """A body's drawn-only ``outline`` and ``outline_members``, as Body keyword arguments."""
    members = ()
    if m.get("outline_members") is not None:
        mpath = field_path(path, "outline_members")
        items = check_list(m["outline_members"], mpath, "a list of members {shape, ...}")
        members = tuple(_hull_member(item, field_path(mpath, i))
                        for i, item in enumerate(items))
    return {"outline": _outline(m, path), "outline_members": members}


def _outline(m: Mapping, path: str):
    """A body's ``outline`` (a :class:`ShipOutline`, or None when absent or null)."""
    if m.get("outline") is None:
        return None
    opath = field_path(path, "outline")
    o = check_mapping(m["outline"], opath, section="outline")
    length = quantity(o["length"], field_path(opath, "length"), "length", gt=0,
                      le=MAX_LINE_LENGTH)
    beam = quantity(o["beam"], field_path(opath, "beam"), "length", gt=0, le=length)
    centre = ((0.0, 0.0) if "centre" not in o
              else check_point(o["centre"], field_path(opath, "centre"), (2,)))
    return ShipOutline(length=length, beam=beam,
                       draft=schema_quantity(o, opath, "outline", "draft", ge=0, le=MAX_DEPTH),
                       freeboard=schema_quantity(o, opath, "outline", "freeboard", ge=0,
                                                 le=FAIRLEAD_Z_MAX),
                       centre=centre,
                       heading_deg=schema_quantity(o, opath, "outline", "heading_deg"))


def fixed_to_field(m: Mapping, path: str, free: tuple) -> str:
    """A body's ``fixed_to`` (default ``water``): what its held pose is relative to."""
    fixed_to = m.get("fixed_to", "water")
    fpath = field_path(path, "fixed_to")
    if not isinstance(fixed_to, str) or fixed_to not in FIXED_TO:
        raise CaseError(fpath, f"{show_value(fixed_to)} is not one of {', '.join(FIXED_TO)} "
                               "(water: a floating body, held relative to the still water, "
                               "rising with the tide; seabed: a structure fixed on the datum)")
    if fixed_to == "seabed" and "heave" in free:
        raise CaseError(fpath, "a body fixed to the seabed is held in heave; free in heave it "
                               "floats (fixed_to: water) or remove heave from free")
    return fixed_to


def _point(raw, path: str, environment: Environment) -> Point:
    m = check_mapping(raw, path, section="point")
    name = check_name(m["name"], field_path(path, "name"), "point name")
    ppath = field_path(path, "position")
    position = _fixed_position(m["position"], ppath, environment)
    free = m.get("free", False)
    if not isinstance(free, bool):
        raise CaseError(field_path(path, "free"), f"{show_value(free)} is not true or false")
    mass = optional_quantity(m, path, "mass", "mass", 0.0, ge=0)
    volume = optional_quantity(m, path, "volume", "volume", 0.0, ge=0)
    if not free:
        for key in ("mass", "volume"):
            if key in m:
                raise CaseError(field_path(path, key), f"a fixed point's {key} has no effect; "
                                                       "give it only with free: true")
    return Point(name=name, position=position, free=free, mass=mass, volume=volume)


def _fixed_position(raw, path: str, environment: Environment) -> tuple:
    """``[x, y]`` on the seabed or ``[x, y, z]`` on or above it (clamped onto it by ulps)."""
    xyz = check_point(raw, path, (2, 3))
    bed = environment.seabed_z(xyz[0], xyz[1])
    if len(xyz) == 2:
        if bed >= 0:
            raise CaseError(path, f"the seabed is at z = {format_si(bed, 'length')} here, not "
                                  "under water; give [x, y, z]")
        return xyz + (bed,)
    tol = 1e-9 * max(environment.depth, 1.0)
    if xyz[2] < bed - tol:
        raise CaseError(field_path(path, 2), f"z = {format_si(xyz[2], 'length')} is below the "
                                             f"seabed (z = {format_si(bed, 'length')} here); it "
                                             "must be on or above the seabed")
    if xyz[2] > FAIRLEAD_Z_MAX:
        raise CaseError(field_path(path, 2), f"z = {format_si(xyz[2], 'length')} must be <= "
                                             f"{format_si(FAIRLEAD_Z_MAX, 'length')}")
    return xyz[:2] + (max(xyz[2], bed),)


def _on_seabed(xyz: tuple, environment: Environment) -> bool:
    return xyz[2] <= environment.seabed_z(xyz[0], xyz[1]) + 1e-9 * max(environment.depth, 1.0)


def _end(raw, path: str, environment: Environment, bodies: dict, points: dict) -> End:
    if isinstance(raw, str):
        if raw not in points:
            known = ", ".join(points) or "none"
            raise CaseError(path, f"unknown point {raw!r}; known points: {known}")
        point = points[raw]
        if point.free:
            return End(point.position, point=raw)
        return End(point.position, label=raw,
                   on_seabed=_on_seabed(point.position, environment))
    if isinstance(raw, Mapping):
        m = check_mapping(raw, path, section="body_end")
        name = m["body"]
        if not isinstance(name, str) or name not in bodies:
            known = ", ".join(bodies) or "none"
            raise CaseError(field_path(path, "body"), f"unknown body {show_value(name)}; known "
                                                      f"bodies: {known}")
        at = check_point(m["at"], field_path(path, "at"), (3,))
        body = bodies[name]
        R = rotation(*(math.radians(a) for a in body.orientation_deg))
        xyz = np.asarray(body.position) + R @ np.asarray(at)
        bed = environment.seabed_z(xyz[0], xyz[1])
        if xyz[2] < bed - 1e-9 * max(environment.depth, 1.0):
            raise CaseError(field_path(path, "at"), f"this point of body {name!r} is at z = "
                                                    f"{format_si(float(xyz[2]), 'length')}, below "
                                                    f"the seabed ({format_si(bed, 'length')})")
        return End(at, body=name)
    if isinstance(raw, (list, tuple)):
        xyz = _fixed_position(raw, path, environment)
        return End(xyz, on_seabed=_on_seabed(xyz, environment))
    raise CaseError(path, f"{show_value(raw)} is not a line end; give a point name, [x, y] on "
                          "the seabed, [x, y, z], or {body: NAME, at: [x, y, z]}")


def end_position(end: End, bodies: dict) -> np.ndarray:
    """Global position [m] of an end at the case-file pose."""
    if end.body is None:
        return np.asarray(end.position, dtype=float)
    body = bodies[end.body]
    R = rotation(*(math.radians(a) for a in body.orientation_deg))
    return np.asarray(body.position) + R @ np.asarray(end.position)


def _line(raw, path: str, environment: Environment, line_types: dict, bodies: dict,
          points: dict) -> Line:
    m = check_mapping(raw, path, section="line")
    name = check_name(m["name"], field_path(path, "name"), "line name")
    a = _end(m["from"], field_path(path, "from"), environment, bodies, points)
    b = _end(m["to"], field_path(path, "to"), environment, bodies, points)
    spath = field_path(path, "segments")
    segments, clumps = _segments(m["segments"], spath, environment, line_types,
                                 pretension=True)
    segments = _pretensioned_length(segments, spath, a, b, bodies)
    anchor_type = (None if m.get("anchor_type") is None
                   else _anchor_type(m["anchor_type"], field_path(path, "anchor_type")))
    if a.fixed and b.fixed and not any(seg.line_type.elastic for seg in segments):
        distance = math.dist(a.position, b.position)
        length = sum(seg.length for seg in segments)
        if distance > length:
            raise CaseError(spath, f"the line ({format_si(length, 'length')}) cannot reach "
                                   f"between its fixed ends ({format_si(distance, 'length')} "
                                   "apart); an inextensible line must be at least that long")
    if a == b and a.fixed:
        raise CaseError(field_path(path, "to"), "both ends are the same fixed point")
    return Line(name=name, a=a, b=b, segments=segments,
                clumps=clumps if any(c is not None for c in clumps) else (),
                anchor_type=anchor_type)


def _pretensioned_length(segments: tuple, path: str, a: End, b: End, bodies: dict) -> tuple:
    """Segments with the length a pretension gives at the case-file pose:
    ``L = D / (1 + T0 / EA)``, ``D`` the distance between the line's ends there."""
    if not any(seg.pretension is not None for seg in segments):
        return segments
    if len(segments) != 1:
        raise CaseError(field_path(path, 0), "a pretension gives the length of a one-segment "
                                             "line; give the segments of this line lengths")
    seg = segments[0]
    distance = math.dist(end_position(a, bodies), end_position(b, bodies))
    if not distance > 0:
        raise CaseError(field_path(field_path(path, 0), "pretension"),
                        "the line's ends coincide at the case-file pose; a pretension cannot "
                        "give its length")
    length = distance / (1 + seg.line_type.strain_at(seg.pretension))
    if not MIN_LINE_LENGTH <= length <= MAX_LINE_LENGTH:
        raise CaseError(field_path(field_path(path, 0), "pretension"),
                        f"the line's ends are {format_si(distance, 'length')} apart at the "
                        f"case-file pose: its length would be {format_si(length, 'length')}, "
                        f"outside {format_si(MIN_LINE_LENGTH, 'length')} to "
                        f"{format_si(MAX_LINE_LENGTH, 'length')}")
    return (dataclasses.replace(seg, length=length),)


def _unique(items, path: str, what: str) -> dict:
    out, first = {}, {}
    for i, item in enumerate(items):
        if item.name in out:
            raise CaseError(field_path(field_path(path, i), "name"),
                            f"duplicate {what} name {item.name!r} (already used by "
                            f"{path}[{first[item.name]}]); {what} names must be unique")
        out[item.name] = item
        first[item.name] = i
    return out


def build_network(m: Mapping, environment: Environment, line_types: dict) -> tuple:
    """``(bodies, points, lines)`` of a network-form case mapping (see the module notes)."""
    body_items = [] if m.get("bodies") is None else check_list(
        m["bodies"], "bodies", "a list of bodies {name, ...}")
    bodies = _unique([_body(raw, field_path("bodies", i), environment)
                      for i, raw in enumerate(body_items)],
                     "bodies", "body")
    point_items = [] if m.get("points") is None else check_list(
        m["points"], "points", "a list of points {name, position, ...}")
    points = _unique([_point(raw, field_path("points", i), environment)
                      for i, raw in enumerate(point_items)], "points", "point")
    line_items = [] if m.get("lines") is None else check_list(
        m["lines"], "lines", "a list of lines {name, from, to, segments}")
    lines = _unique([_line(raw, field_path("lines", i), environment, line_types, bodies, points)
                     for i, raw in enumerate(line_items)], "lines", "line")
    attached = {}
    for line in lines.values():
        for end in (line.a, line.b):
            key = end.point or end.body
            if key is not None:
                attached[key] = attached.get(key, 0) + 1
    for i, point in enumerate(points.values()):
        if point.free and point.name not in attached:
            raise CaseError(field_path(field_path("points", i), "free"),
                            f"free point {point.name!r} is not attached to any line: nothing "
                            "holds it; attach a line or make it fixed")
    return tuple(bodies.values()), tuple(points.values()), tuple(lines.values())


def check_held(bodies: tuple, lines: tuple, contacts) -> None:
    """Every body free in a horizontal degree of freedom is held by something that can
    hold it: a line, a spring, or a contact (a fender or a pile guide); a scene has at
    least one line or contact. Raises :class:`CaseError` naming the field."""
    if not lines and not contacts:
        raise CaseError("lines", "no lines; a scene needs at least one line, or fenders or "
                                 "pile guides that hold its bodies")
    attached = {end.body for line in lines for end in (line.a, line.b)}
    attached |= {c.body for c in contacts.fenders + contacts.guides}
    for i, body in enumerate(bodies):
        held_by_springs = body.stiffness is not None
        horizontal = [d for d in body.free if d not in VERTICAL_DOFS]
        if horizontal and body.name not in attached and not held_by_springs:
            raise CaseError(field_path(field_path("bodies", i), "free"),
                            f"body {body.name!r} is free in {', '.join(horizontal)} but no line, "
                            "fender, pile guide or spring holds it; attach a line, give a "
                            "stiffness, or hold those degrees of freedom")
