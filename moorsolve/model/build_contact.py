"""The berth sections of a network case file: ``walls``, ``piles``, ``fenders``, ``guides``.

Schema (SI units; see README "Berths: fenders, quay walls, hawsers")::

    walls:
      - name: str
        point: [x, y, z]                 any point of the wall's plane [m]
        normal: [nx, ny, nz]             out of the wall toward the water (normalised)
        friction: >= 0                   Coulomb coefficient; default 0
        friction_slip: > 0 [m]           slip that mobilises it; default 1 mm
    piles:                               dolphins and guide piles: vertical cylinders
      - {name, position: [x, y], radius > 0 [m], top: z [m] (optional), friction >= 0,
         friction_slip > 0 [m], bending_stiffness: E I > 0 [N m^2] (optional)}
    fenders:
      - name: str
        body: NAME                       the body it is mounted on, or bears on
        at: [x, y, z]                    its face: body frame (mounted: body), else scene
        wall: NAME | pile: NAME          what it bears on / is mounted on (one of them)
        mounted: body | structure        default body
        reaction: rigid | {stiffness: > 0 [N/m]}
                  | {table: [[deflection [m], reaction [N]], ...]}   strictly increasing
        rated_deflection: > 0 [m]        the maker's limit; a linear fender needs one, a
                                         table defaults to its last deflection
        height: > 0 [m]                  its full compression (a structure-mounted one's
                                         is its face's distance from the wall or pile,
                                         unless the face is given on it); more than the
                                         rated deflection. Past it the hull bears on the
                                         wall. Not given: not modelled.
    guides:
      - {name, body, at: [x, y, z] (collar centre, body frame), pile: NAME,
         clearance >= 0 [m], pads: int >= 3 (default 8)}

Beyond the schema: names are unique within each section; a wall's normal is not zero; at the
case-file pose every body-mounted fender touches what it bears on (its face no more than
:data:`TOUCH_TOLERANCE` off it, and compressed by no more than its rated deflection), and
every guide's collar is round its pile (centre within the clearance of the pile's axis).
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Mapping

import numpy as np

from ..constants import FRICTION_SLIP
from ..errors import CaseError
from .bodies import Body
from .contact import MOUNTINGS, Contacts, Fender, Guide, Pile, ReactionLaw, Wall
from .fields import (check_list, check_mapping, check_name, check_point, check_rows,
                     field_path, nullable_quantity, optional_quantity, quantity)
from .units import format_si, show_value

#: A fender touches what it bears on when its face is within this distance of it [m] at
#: the case-file pose (a millimetre: positions are given to the millimetre at best).
TOUCH_TOLERANCE = 1e-3
_MAX_PADS = 64


def _unique(items: list, path: str, what: str) -> dict:
    out = {}
    for i, item in enumerate(items):
        if item.name in out:
            raise CaseError(field_path(field_path(path, i), "name"),
                            f"duplicate {what} name {item.name!r}; {what} names must be unique")
        out[item.name] = item
    return out


def _items(m: Mapping, key: str, what: str) -> list:
    return [] if m.get(key) is None else check_list(m[key], key, f"a list of {what}")


def _wall(raw, path: str) -> Wall:
    m = check_mapping(raw, path, section="wall")
    name = check_name(m["name"], field_path(path, "name"), "wall name")
    point = check_point(m["point"], field_path(path, "point"), (3,))
    npath = field_path(path, "normal")
    items = check_list(m["normal"], npath, "[nx, ny, nz]")
    if len(items) != 3:
        raise CaseError(npath, f"{show_value(m['normal'])} has {len(items)} values; it must "
                               "be [nx, ny, nz]")
    normal = np.array([quantity(v, field_path(npath, i), "dimensionless")
                       for i, v in enumerate(items)])
    # hypot: a huge component must not overflow the length to inf (and the normal to 0).
    size = math.hypot(*normal.tolist())
    if not size > 0:
        raise CaseError(npath, f"{show_value(m['normal'])} has zero length; give the wall's "
                               "outward normal (from the wall toward the water)")
    friction, slip = _friction(m, path)
    return Wall(name=name, point=point, normal=tuple(float(v) for v in normal / size),
                friction=friction, friction_slip=slip)


def _friction(m: dict, path: str) -> tuple:
    friction = optional_quantity(m, path, "friction", "dimensionless", 0.0, ge=0, le=10)
    slip = optional_quantity(m, path, "friction_slip", "length", FRICTION_SLIP, gt=0, le=1)
    return friction, slip


def _pile(raw, path: str) -> Pile:
    m = check_mapping(raw, path, section="pile")
    name = check_name(m["name"], field_path(path, "name"), "pile name")
    position = check_point(m["position"], field_path(path, "position"), (2,))
    radius = quantity(m["radius"], field_path(path, "radius"), "length", gt=0, le=100)
    top = nullable_quantity(m, path, "top", "length")
    friction, slip = _friction(m, path)
    ei = nullable_quantity(m, path, "bending_stiffness", "bending_stiffness", gt=0)
    return Pile(name=name, position=position, radius=radius, top=top, friction=friction,
                friction_slip=slip, bending_stiffness=ei)


def _law(raw, path: str) -> ReactionLaw:
    if raw == "rigid":
        return ReactionLaw(kind="rigid")
    if not isinstance(raw, Mapping) or len(raw) != 1 or not (
            "stiffness" in raw or "table" in raw):
        raise CaseError(path, f"{show_value(raw)} is not a reaction law; give rigid, "
                              "{stiffness: N/m} or {table: [[deflection, reaction], ...]}")
    if "stiffness" in raw:
        k = quantity(raw["stiffness"], field_path(path, "stiffness"), "force_per_length",
                     gt=0)
        return ReactionLaw(kind="linear", stiffness=k)
    tpath = field_path(path, "table")
    deflections, reactions = [], []
    for rpath, row in check_rows(raw["table"], tpath, "[deflection, reaction]", width=2,
                                 min_rows=1, empty="a reaction table"):
        d = quantity(row[0], field_path(rpath, 0), "length", ge=0)
        r = quantity(row[1], field_path(rpath, 1), "force", ge=0)
        if d == 0:
            if r != 0 or deflections:
                raise CaseError(field_path(rpath, 1), "a row at zero deflection must be "
                                                      "[0, 0] and come first: the curve "
                                                      "starts at the origin")
            continue
        last_d, last_r = (deflections[-1], reactions[-1]) if deflections else (0.0, 0.0)
        if not d > last_d:
            raise CaseError(field_path(rpath, 0),
                            f"deflection {format_si(d, 'length')} must be greater than the "
                            f"previous row's ({format_si(last_d, 'length')}): deflections "
                            "ascend")
        if not r > last_r:
            raise CaseError(field_path(rpath, 1),
                            f"reaction {format_si(r, 'force')} must be greater than the "
                            f"previous row's ({format_si(last_r, 'force')}): the reaction "
                            "must increase with deflection (a buckling fender's dip is not "
                            "modelled: give its rising envelope)")
        deflections.append(d)
        reactions.append(r)
    if not deflections:
        raise CaseError(tpath, "the table has only the origin; give at least one row "
                               "[deflection > 0, reaction > 0]")
    return ReactionLaw(kind="table", deflections=tuple(deflections),
                       reactions=tuple(reactions))


def _pose(body: Body):
    from .build_network import rotation
    R = rotation(*(math.radians(a) for a in body.orientation_deg))
    return np.asarray(body.position, dtype=float), R


def _fender(raw, path: str, bodies: dict, walls: dict, piles: dict) -> Fender:
    m = check_mapping(raw, path, section="fender")
    name = check_name(m["name"], field_path(path, "name"), "fender name")
    body = _known(m["body"], field_path(path, "body"), bodies, "body")
    at = check_point(m["at"], field_path(path, "at"), (3,))
    if ("wall" in m) == ("pile" in m):
        raise CaseError(path, f"fender {name!r} must name what it bears on: give exactly one "
                              "of wall or pile")
    wall = _known(m["wall"], field_path(path, "wall"), walls, "wall") if "wall" in m else None
    pile = _known(m["pile"], field_path(path, "pile"), piles, "pile") if "pile" in m else None
    mounted = m.get("mounted", "body")
    if mounted not in MOUNTINGS:
        raise CaseError(field_path(path, "mounted"), f"{show_value(mounted)} must be one of "
                                                     f"{', '.join(MOUNTINGS)}")
    law = _law(m["reaction"], field_path(path, "reaction"))
    rated = nullable_quantity(m, path, "rated_deflection", "length", gt=0)
    if law.kind == "linear" and rated is None:
        raise CaseError(field_path(path, "rated_deflection"),
                        f"a linear fender needs its rated deflection [m] (the maker's limit, "
                        f"the check's criterion); fender {name!r} has none")
    if law.kind == "table" and rated is None:
        rated = law.deflections[-1]
    fender = Fender(name=name, body=body, at=at, law=law, wall=wall, pile=pile,
                    mounted=mounted, rated_deflection=rated)
    gap = _check_touching(fender, path, bodies[body], walls, piles)
    height = _height(m, path, fender, gap)
    return dataclasses.replace(fender, height=height)


def _height(m: Mapping, path: str, fender: Fender, gap: float):
    """A fender's full compression [m] (see :class:`Fender`): a structure-mounted one's is
    its face's distance ``gap`` from its wall or pile, a body-mounted one's is given; it
    must exceed the rated deflection."""
    hpath = field_path(path, "height")
    if fender.mounted == "structure" and gap > TOUCH_TOLERANCE:
        if "height" in m:
            raise CaseError(hpath, f"fender {fender.name!r} is mounted on the structure: its "
                                   "height is its face's distance from the wall or pile "
                                   f"({format_si(gap, 'length')}); give it through `at`")
        height = gap
    else:
        # On the body, or on the structure with its face given on the wall or pile's
        # surface (the surface drawn through the fenders' faces): given, or not known.
        height = nullable_quantity(m, path, "height", "length", gt=0)
    if fender.law.kind == "rigid":
        return None
    if height is not None and not fender.rated_deflection < height:
        raise CaseError(field_path(path, "rated_deflection"),
                        f"fender {fender.name!r}'s rated deflection "
                        f"{format_si(fender.rated_deflection, 'length')} (by default its "
                        "table's last row) must be less than its full compression, its "
                        f"height {format_si(height, 'length')}"
                        + (" (its face's distance from the wall or pile)"
                           if fender.mounted == "structure" else ""))
    return height


def _known(raw, path: str, known: dict, what: str) -> str:
    if not isinstance(raw, str) or raw not in known:
        names = ", ".join(known) or "none"
        raise CaseError(path, f"unknown {what} {show_value(raw)}; known {what}s: {names}")
    return raw


def _check_touching(fender: Fender, path: str, body: Body, walls: dict, piles: dict) -> float:
    """At the case pose a body-mounted fender touches what it bears on; a structure-mounted
    one stands on the water side of its wall, or outside its pile. Returns the face's gap
    from the wall or pile there [m]."""
    r0, R0 = _pose(body)
    at = np.asarray(fender.at, dtype=float)
    face = r0 + R0 @ at if fender.mounted == "body" else at
    if fender.wall is not None:
        wall = walls[fender.wall]
        gap = float(np.dot(wall.normal, face - np.asarray(wall.point)))
        target = f"wall {wall.name!r}"
    else:
        pile = piles[fender.pile]
        gap = math.hypot(face[0] - pile.position[0], face[1] - pile.position[1]) - pile.radius
        target = f"pile {pile.name!r}"
    apath = field_path(path, "at")
    if fender.mounted == "structure":
        if gap < -TOUCH_TOLERANCE:
            raise CaseError(apath, f"fender {fender.name!r} is mounted on {target} but its "
                                   f"face is {format_si(-gap, 'length')} inside it; give the "
                                   "face on the water side")
        return max(gap, 0.0)
    if gap > TOUCH_TOLERANCE:
        raise CaseError(apath, f"fender {fender.name!r} of body {fender.body!r} is "
                               f"{format_si(gap, 'length')} off {target} at the case-file "
                               f"pose; a fender must touch what it bears on at rest (within "
                               f"{format_si(TOUCH_TOLERANCE, 'length')}): move the body or "
                               "the fender's face")
    limit = fender.rated_deflection if fender.law.kind != "rigid" else TOUCH_TOLERANCE
    if -gap > limit:
        raise CaseError(apath, f"fender {fender.name!r} of body {fender.body!r} is "
                               f"{format_si(-gap, 'length')} inside {target} at the "
                               f"case-file pose, more than it can deflect "
                               f"({format_si(limit, 'length')}); does the wall's normal "
                               "point toward the water, where the body is?")
    return gap


def _guide(raw, path: str, bodies: dict, piles: dict) -> Guide:
    m = check_mapping(raw, path, section="guide")
    name = check_name(m["name"], field_path(path, "name"), "guide name")
    body = _known(m["body"], field_path(path, "body"), bodies, "body")
    at = check_point(m["at"], field_path(path, "at"), (3,))
    pile = _known(m["pile"], field_path(path, "pile"), piles, "pile")
    clearance = quantity(m["clearance"], field_path(path, "clearance"), "length", ge=0, le=10)
    pads = m.get("pads", 8)
    if isinstance(pads, bool) or not isinstance(pads, numbers.Integral) \
            or not 3 <= pads <= _MAX_PADS:
        raise CaseError(field_path(path, "pads"),
                        f"{show_value(pads)} must be an integer from 3 to {_MAX_PADS} "
                        "(flat pads evenly spaced round the collar)")
    r0, R0 = _pose(bodies[body])
    centre = r0 + R0 @ np.asarray(at, dtype=float)
    p = piles[pile]
    off = math.hypot(centre[0] - p.position[0], centre[1] - p.position[1])
    if off > clearance + TOUCH_TOLERANCE:
        raise CaseError(field_path(path, "at"),
                        f"guide {name!r}'s collar is {format_si(off, 'length')} from the "
                        f"axis of pile {pile!r} at the case-file pose, more than its "
                        f"clearance ({format_si(clearance, 'length')}): the pile must run "
                        "through the collar")
    return Guide(name=name, body=body, at=at, pile=pile, clearance=clearance, pads=int(pads))


def build_contacts(m: Mapping, bodies: tuple) -> Contacts:
    """The :class:`Contacts` of a network-form case mapping (see the module notes)."""
    by_name = {b.name: b for b in bodies}
    walls = _unique([_wall(raw, field_path("walls", i))
                     for i, raw in enumerate(_items(m, "walls", "walls {name, point, "
                                                              "normal}"))], "walls", "wall")
    piles = _unique([_pile(raw, field_path("piles", i))
                     for i, raw in enumerate(_items(m, "piles", "piles {name, position, "
                                                              "radius}"))], "piles", "pile")
    fenders = _unique([_fender(raw, field_path("fenders", i), by_name, walls, piles)
                       for i, raw in enumerate(_items(m, "fenders", "fenders {name, body, "
                                                                    "at, wall, reaction}"))],
                      "fenders", "fender")
    guides = _unique([_guide(raw, field_path("guides", i), by_name, piles)
                      for i, raw in enumerate(_items(m, "guides", "guides {name, body, at, "
                                                                  "pile, clearance}"))],
                     "guides", "guide")
    return Contacts(walls=tuple(walls.values()), piles=tuple(piles.values()),
                    fenders=tuple(fenders.values()), guides=tuple(guides.values()))


__all__ = ["build_contacts", "TOUCH_TOLERANCE"]
