"""Line types, segments, clumps and anchor types of a case file (both forms)."""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..errors import CaseError
from .fields import (MAX_EA,
                     MAX_LINE_LENGTH, MAX_WEIGHT, MIN_EA,
                     MIN_LINE_LENGTH, MIN_WEIGHT, check_bounds, check_list,
                     check_mapping, field_path,
                     nullable_quantity, optional_quantity, quantity, schema_quantity)
from .units import format_si, show_value, weight_per_length_to_si
from .. import catalog as line_catalog
from ..constants import SEAWATER_DENSITY
from .environment import Environment
from .lines import ANCHOR_KINDS, AnchorType, Clump, LineDrag, LineType, Segment
from .stretch import line_type_fields


# ---- line types -------------------------------------------------------------------------


def _line_drag(raw, path: str) -> LineDrag:
    m = check_mapping(raw, path, section="line_drag")
    normal = quantity(m["normal"], field_path(path, "normal"), "dimensionless", ge=0, le=10)
    tangential = schema_quantity(m, path, "line_drag", "tangential", ge=0, le=10)
    side = schema_quantity(m, path, "line_drag", "side", ge=-10, le=10)
    return LineDrag(normal=normal, tangential=tangential, side=side)


def _line_type_drag(m: dict, path: str, diameter):
    """The optional ``drag`` of a line type; it needs the diameter."""
    drag = None if m.get("drag") is None else _line_drag(m["drag"], field_path(path, "drag"))
    if drag is not None and diameter is None:
        raise CaseError(field_path(path, "diameter"),
                        "a line type with drag needs a diameter (the flow force scales with "
                        "it); give diameter > 0 [m]")
    return drag


def _line_type(name: str, raw, path: str, gravity: float,
               water_density: float = SEAWATER_DENSITY) -> LineType:
    if isinstance(raw, Mapping) and "catalog" in raw:
        return _catalog_line_type(name, raw, path, gravity, water_density)
    m = check_mapping(raw, path, section="line_type")
    wpath = field_path(path, "weight_in_water")
    weight = weight_per_length_to_si(m["weight_in_water"], gravity, wpath)
    if abs(weight) > MAX_WEIGHT:
        raise CaseError(wpath, f"{format_si(weight, 'force_per_length')} must be between "
                               f"-{MAX_WEIGHT:g} and {MAX_WEIGHT:g} N/m (a unit mistake?)")
    if 0 < abs(weight) < MIN_WEIGHT:
        raise CaseError(wpath, f"{format_si(weight, 'force_per_length')} is too small to "
                               f"hang as a catenary; give 0 for a neutrally buoyant line or "
                               f"at least {MIN_WEIGHT:g} N/m in magnitude")
    ea = nullable_quantity(m, path, "ea", "force", gt=0, le=MAX_EA)
    if ea is not None:
        check_bounds(m["ea"], ea, "force", field_path(path, "ea"), ge=MIN_EA)
    mbl = nullable_quantity(m, path, "mbl", "force", gt=0)
    diameter = nullable_quantity(m, path, "diameter", "length", gt=0)
    sealed = _sealed(m, path, diameter)
    return LineType(name=name, weight_in_water=weight, mbl=mbl, diameter=diameter,
                    sealed=sealed, drag=_line_type_drag(m, path, diameter),
                    weight_in_air=_weight_in_air(m, path, gravity, weight),
                    **line_type_fields(m, path, ea))


def _weight_in_air(m: dict, path: str, gravity: float, in_water: float, default=None):
    """The optional ``weight_in_air`` [N/m, or a mass per length]: what the line weighs
    above the water. It is at least the weight in water (the water's buoyancy only lightens
    a line) and positive."""
    if m.get("weight_in_air") is None:
        return default
    wpath = field_path(path, "weight_in_air")
    value = weight_per_length_to_si(m["weight_in_air"], gravity, wpath)
    if not 0 < value <= MAX_WEIGHT:
        raise CaseError(wpath, f"{format_si(value, 'force_per_length')} must be > 0 and "
                               f"<= {MAX_WEIGHT:g} N/m")
    if value < in_water:
        raise CaseError(wpath, f"{format_si(value, 'force_per_length')} is less than the "
                               f"weight in water ({format_si(in_water, 'force_per_length')}); "
                               "a line weighs at least as much in air as in water")
    return value


def _sealed(m: dict, path: str, diameter) -> bool:
    sealed = False
    if "sealed" in m:
        sealed = m["sealed"]
        if not isinstance(sealed, bool):
            raise CaseError(field_path(path, "sealed"),
                            f"{show_value(sealed)} is not true or false")
    if sealed and diameter is None:
        raise CaseError(field_path(path, "diameter"),
                        "sealed line needs a diameter (its wall tension depends on the outer "
                        "area); give diameter > 0 [m]")
    return sealed


def _catalog_line_type(name: str, raw, path: str, gravity: float,
                       water_density: float) -> LineType:
    """A line type from the catalogue: ``{catalog: studless_r3, diameter: 81 mm, ...}``.

    ``weight_in_water``, ``ea`` and ``mbl`` given beside ``catalog`` replace the catalogue
    values (e.g. a maker's certificate); ``corrosion_allowance`` reduces the diameter used
    for the catalogue MBL.
    """
    m = check_mapping(raw, path, section="catalogue_line_type")
    known = line_catalog.entries()
    entry = m["catalog"]
    if not isinstance(entry, str) or entry not in known:
        raise CaseError(field_path(path, "catalog"),
                        f"unknown catalogue entry {show_value(entry)}; "
                                                f"known entries: {', '.join(known)}")
    diameter = quantity(m["diameter"], field_path(path, "diameter"), "length", gt=0, le=1.0)
    allowance = optional_quantity(m, path, "corrosion_allowance", "length", 0.0, ge=0)
    if allowance >= diameter:
        raise CaseError(field_path(path, "corrosion_allowance"),
                        f"{format_si(allowance, 'length')} must be smaller than the diameter "
                        f"({format_si(diameter, 'length')})")
    props = line_catalog.line_properties(entry, diameter, water_density=water_density,
                                         gravity=gravity, corrosion_allowance=allowance)
    weight = props.weight_in_water
    if m.get("weight_in_water") is not None:
        weight = weight_per_length_to_si(m["weight_in_water"], gravity,
                                         field_path(path, "weight_in_water"))
    ea = nullable_quantity(m, path, "ea", "force", gt=0)
    mbl = nullable_quantity(m, path, "mbl", "force", gt=0)
    if mbl is not None and "corrosion_allowance" in m:
        raise CaseError(field_path(path, "corrosion_allowance"),
                        "applies to the catalogue MBL only; with an explicit mbl give the "
                        "corroded value directly")
    return LineType(name=name, weight_in_water=weight,
                    mbl=props.mbl if mbl is None else mbl,
                    diameter=diameter, sealed=_sealed(m, path, diameter), catalog=entry,
                    drag=_line_type_drag(m, path, diameter),
                    corrosion_allowance=allowance, source=props.source,
                    **line_type_fields(m, path, props.ea if ea is None else ea,
                                       catalogue=props),
                    # The catalogue knows the mass: the weight in air follows.
                    weight_in_air=_weight_in_air(m, path, gravity, weight,
                                                 props.mass_per_length * gravity))


def _line_types(raw, path: str, gravity: float, water_density: float = SEAWATER_DENSITY) -> dict:
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping; line_types maps each line type "
                              "name to its properties")
    if not raw:
        raise CaseError(path, "no line types; at least one is required")
    types = {}
    for name, spec in raw.items():
        if not isinstance(name, str) or not name.strip():
            raise CaseError(path, f"line type name {show_value(name)} is not a non-empty string")
        types[name] = _line_type(name, spec, field_path(path, name), gravity, water_density)
    return types


# ---- legs -------------------------------------------------------------------------------


def _segment(raw, path: str, line_types: dict, pretension: bool = False) -> Segment:
    if pretension and isinstance(raw, Mapping) and "pretension" in raw:
        return _pretensioned_segment(raw, path, line_types)
    m = check_mapping(raw, path, section="segment")
    type_name = m["type"]
    if not isinstance(type_name, str) or type_name not in line_types:
        raise CaseError(field_path(path, "type"), f"unknown line type {show_value(type_name)}; "
                                             f"known line types: {', '.join(line_types)}")
    lpath = field_path(path, "length")
    length = quantity(m["length"], lpath, "length", gt=0, le=MAX_LINE_LENGTH)
    check_bounds(m["length"], length, "length", lpath, ge=MIN_LINE_LENGTH)
    return Segment(line_type=line_types[type_name], length=length)


def _pretensioned_segment(raw, path: str, line_types: dict) -> Segment:
    """``{type, pretension}``: a weightless elastic segment (a hawser) given by its tension
    at the case-file pose; its length is set once the line's ends are known."""
    m = check_mapping(raw, path, section="pretension_segment")
    type_name = m["type"]
    if not isinstance(type_name, str) or type_name not in line_types:
        raise CaseError(field_path(path, "type"), f"unknown line type {show_value(type_name)}; "
                                                  f"known line types: {', '.join(line_types)}")
    lt = line_types[type_name]
    if lt.weight_in_water != 0 or not lt.elastic:
        raise CaseError(field_path(path, "pretension"),
                        f"a pretension sets the length of a weightless elastic line (a "
                        f"hawser); line type {type_name!r} has weight_in_water "
                        f"{format_si(lt.weight_in_water, 'force_per_length')} and ea "
                        f"{'none' if lt.ea is None else format_si(lt.ea, 'force')}: give a "
                        "length")
    # Hooke: below EA (a strain under 1); a stretch law stretches finitely at any tension.
    limits = {"lt": lt.ea} if lt.ea is not None else {}
    tension = quantity(m["pretension"], field_path(path, "pretension"), "force", ge=0,
                       **limits)
    return Segment(line_type=lt, length=math.nan, pretension=tension)


def _clump(raw, path: str, environment: Environment) -> Clump:
    """``{mass: kg, volume: m^3}`` (net weight in water) or ``{weight: N}`` (negative: buoy)."""
    m = check_mapping(raw, path, section="clump")
    if "weight" in m:
        for key in ("mass", "volume"):
            if key in m:
                raise CaseError(field_path(path, key),
                                f"{key} is not used with weight; give either "
                                                  "weight [N] or mass [kg] and volume [m^3]")
        weight = quantity(m["weight"], field_path(path, "weight"), "force")
        return Clump(weight=weight)
    if "mass" not in m:
        raise CaseError(field_path(path, "mass"), "a clump needs mass [kg] (and optionally volume "
                                             "[m^3]) or a net weight [N]")
    mass = quantity(m["mass"], field_path(path, "mass"), "mass", ge=0)
    volume = optional_quantity(m, path, "volume", "volume", 0.0, ge=0)
    weight = environment.gravity * (mass - environment.water_density * volume)
    return Clump(weight=weight, mass=mass, volume=volume)


def _segments(raw, path: str, environment: Environment, line_types: dict,
              pretension: bool = False):
    """Segments from anchor to fairlead, with optional ``{clump: ...}`` items between them."""
    items = check_list(raw, path, "a list of {type, length} segments from the anchor, with "
                                 "optional {clump: {...}} items between them")
    if not items:
        raise CaseError(path, "no segments; a leg needs one segment {type, length}")
    segments, clumps = [], []
    for j, item in enumerate(items):
        ipath = field_path(path, j)
        if isinstance(item, Mapping) and "clump" in item:
            held = check_mapping(item, ipath, section="clump_item")
            if not segments or len(clumps) != len(segments) - 1:
                raise CaseError(ipath, "a clump must sit between two segments (after a "
                                       "segment, not first and not after another clump)")
            clumps.append(_clump(held["clump"], field_path(ipath, "clump"), environment))
            continue
        if segments and len(clumps) < len(segments):
            clumps.append(None)
        segments.append(_segment(item, ipath, line_types, pretension))
    if len(clumps) == len(segments):
        raise CaseError(field_path(path, len(items) - 1),
                        "a clump must sit between two segments; this one ends the leg")
    return tuple(segments), tuple(clumps)


# ---- mooring checks ---------------------------------------------------------------------

#: The schema section of each anchor kind.
_ANCHOR_SECTIONS = {"drag": "anchor_drag", "deadweight": "anchor_deadweight",
                    "pile": "anchor_pile", "suction": "anchor_suction"}


def _anchor_type(raw, path: str) -> AnchorType:
    """``{type: drag}``, ``{type: deadweight, allowed_uplift}`` or ``{type: pile,
    allowed_uplift_angle_deg}``."""
    allowed = ", ".join(ANCHOR_KINDS)
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping; give {{type: ...}} with type "
                              f"one of {allowed}")
    kind = raw.get("type")
    if not isinstance(kind, str) or kind not in ANCHOR_KINDS:
        raise CaseError(field_path(path, "type"),
                        f"unknown anchor type {show_value(kind)}; allowed: "
                                             f"{allowed}")
    m = check_mapping(raw, path, section=_ANCHOR_SECTIONS[kind])
    if kind == "deadweight":
        uplift = quantity(m["allowed_uplift"], field_path(path, "allowed_uplift"), "force", ge=0)
        return AnchorType(kind=kind, allowed_uplift=uplift)
    if kind == "pile":
        angle = quantity(m["allowed_uplift_angle_deg"], field_path(path,
                                                                   "allowed_uplift_angle_deg"),
                          "angle", ge=0, lt=90)
        return AnchorType(kind=kind, allowed_uplift_angle_deg=angle)
    return AnchorType(kind=kind)


