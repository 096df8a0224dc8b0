"""The ``body:`` + ``legs:`` form of a case file: one body on anchor-to-fairlead legs."""

from __future__ import annotations

import math

from ..errors import CaseError
from .fields import (check_choices, FAIRLEAD_Z_MAX, check_list,
                     check_mapping, check_name, check_point, field_path)
from .units import format_si
from .bodies import PLANAR_DOFS, Body
from .environment import Environment
from .build_lines import _anchor_type, _segments
from .build_loads import _loads
from .build_network import fixed_to_field, outline_fields
from .lines import End, Line
from .loads import BodyLoads


def _free(raw, path: str) -> tuple:
    return check_choices(raw, path, PLANAR_DOFS)


def _body(raw, path: str) -> Body:
    m = check_mapping(raw, path, section="body")
    free = PLANAR_DOFS if "free" not in m else _free(m["free"], field_path(path, "free"))
    loads = BodyLoads() if m.get("loads") is None else _loads(m["loads"], field_path(path, "loads"))
    return Body(name="body", free=free, loads=loads, fixed_to=fixed_to_field(m, path, free),
                **outline_fields(m, path))


def _leg(raw, path: str, environment: Environment, line_types: dict, body: bool) -> Line:
    m = check_mapping(raw, path, section="leg")
    name = check_name(m["name"], field_path(path, "name"), "leg name")
    anchor_type = (None if m.get("anchor_type") is None
                   else _anchor_type(m["anchor_type"], field_path(path, "anchor_type")))
    depth = environment.depth
    seabed_tol = 1e-9 * max(depth, 1.0)  # unit conversions may leave the seabed z a few ulp off
    sloped = environment.seabed.sloped
    allowed = "must be on or above the (sloped) seabed" if sloped else "must be >= -depth"

    fpath = field_path(path, "fairlead")
    fairlead = check_point(m["fairlead"], fpath, (3,))
    fz = fairlead[2]
    bed = environment.seabed_z(fairlead[0], fairlead[1])
    if bed >= 0:
        raise CaseError(fpath, f"the sloped seabed is at z = {format_si(bed, 'length')} under "
                               "this fairlead, not under water; lower the seabed "
                               "(environment.seabed) or move the leg")
    if fz < bed - seabed_tol:
        raise CaseError(field_path(fpath, 2), f"fairlead z = {format_si(fz, 'length')} is below "
                                         f"the seabed (z = {format_si(bed, 'length')}); it "
                                         f"{allowed}")
    fz = max(fz, bed)
    fairlead = fairlead[:2] + (fz,)
    if fz > FAIRLEAD_Z_MAX:
        raise CaseError(field_path(fpath, 2), f"fairlead z = {format_si(fz, 'length')} must be <= "
                                         f"{format_si(FAIRLEAD_Z_MAX, 'length')}")

    apath = field_path(path, "anchor")
    anchor = check_point(m["anchor"], apath, (2, 3))
    bed = environment.seabed_z(anchor[0], anchor[1])
    if bed >= 0:
        raise CaseError(apath, f"the sloped seabed is at z = {format_si(bed, 'length')} at "
                               "this anchor, not under water; lower the seabed "
                               "(environment.seabed) or move the anchor")
    if len(anchor) == 2:
        anchor = anchor + (bed,)
    else:
        az = anchor[2]
        if az < bed - seabed_tol:
            raise CaseError(field_path(apath, 2),
                            f"anchor z = {format_si(az, 'length')} is below the "
                                             f"seabed (z = {format_si(bed, 'length')}); it "
                                             f"{allowed}")
        if az < bed:
            anchor = anchor[:2] + (bed,)
        # An anchor may lie higher than its fairlead (a deep spar fairlead, an anchor up a
        # slope or on a pile head): every line block takes either sign of the height.
        if az > 0:
            raise CaseError(field_path(apath, 2),
                            f"anchor z = {format_si(az, 'length')} is above the still-water "
                            "level (z = 0); an anchor must be in the water (a fixed point in "
                            "air can be the leg's fairlead, with no body)")

    spath = field_path(path, "segments")
    segments, clumps = _segments(m["segments"], spath, environment, line_types)
    if sloped and len(segments) > 1:
        raise CaseError(spath, f"{len(segments)} segments on a sloped seabed: multi-segment legs "
                               "need a flat seabed (environment.seabed.gradient [0, 0], no "
                               "bathymetry); a sloped seabed or a grid takes one-segment legs")
    if not any(seg.line_type.elastic for seg in segments):
        # Body at zero offset: the body-frame fairlead is its global position.
        distance = math.dist(anchor, fairlead)
        length = sum(seg.length for seg in segments)
        if distance > length:
            raise CaseError(spath, f"the line ({format_si(length, 'length')}) cannot "
                                   f"reach from anchor to fairlead (distance "
                                   f"{format_si(distance, 'length')}); an inextensible line "
                                   "must be at least that long")
    on_seabed = anchor[2] <= environment.seabed_z(anchor[0], anchor[1]) + seabed_tol
    return Line(name=name, a=End(anchor, on_seabed=on_seabed),
                b=End(fairlead, body="body" if body else None,
                      on_seabed=not body and fairlead[2] <= environment.seabed_z(
                          fairlead[0], fairlead[1]) + seabed_tol),
                segments=segments,
               clumps=clumps if any(c is not None for c in clumps) else (),
               anchor_type=anchor_type)


def _legs(raw, path: str, environment: Environment, line_types: dict, body: bool) -> tuple:
    items = check_list(raw, path, "a list of legs {name, anchor, fairlead, segments}")
    if not items:
        raise CaseError(path, "no legs; at least one leg is required")
    legs = []
    first_index = {}
    for i, item in enumerate(items):
        leg = _leg(item, field_path(path, i), environment, line_types, body)
        if leg.name in first_index:
            raise CaseError(field_path(field_path(path, i), "name"),
                            f"duplicate leg name {leg.name!r} (already used by "
                            f"legs[{first_index[leg.name]}]); leg names must be unique")
        first_index[leg.name] = i
        legs.append(leg)
    return tuple(legs)


