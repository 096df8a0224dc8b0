"""Validate plain case data (a case-file dictionary) into a :class:`~moorsolve.model.Case`.

Validation is strict: every problem raises :class:`~moorsolve.errors.CaseError` whose
``field`` is the dotted path of the offending value (``legs[3].segments[0].length``) and
whose message names the value and what is allowed (``-5 m must be > 0``). Unknown keys are
errors; there are no aliases. Quantities may be given with units (see
:mod:`moorsolve.model.units`) and are converted to SI here, once.

A key whose absence means "none" (``ea``, ``body``, ``environment.wind``, a load model, ...)
may also be given as null with the same meaning. A key with a default value may not be null.

Schema (SI units, ``[...]`` lists)::

    name: str                                  optional, default the file stem or "case"
    environment:                               required
      depth: length > 0                        required
      water_density: > 0 [kg/m^3]              default 1025
      air_density: > 0 [kg/m^3]                default 1.225
      gravity: > 0 [m/s^2]                     default 9.80665
      seabed: {friction: >= 0,                 default 0
               gradient: [dz/dx, dz/dy]}       default flat; seabed z = -depth + gx x + gy y
      wind: {speed: >= 0 [m/s], toward_deg}    optional; current likewise, plus an optional
                                               profile: [[z <= 0, speed], ...] z ascending
      waves: {hs: >= 0 [m], toward_deg}        optional
    line_types:                                required, at least one
      NAME: {weight_in_water [N/m or mass/m], ea > 0 [N], mbl > 0 [N], diameter > 0 [m],
             sealed: bool, drag: {normal: Cn, tangential: Ct, side: Cm},
             stretch: STRETCH (instead of ea), fibre: bool, min_tension >= 0 [N],
             stiffness_bounds: {lower: BOUND, upper: BOUND}}
                                               drag needs a diameter
      NAME: {catalog: ENTRY, diameter > 0 [m], corrosion_allowance >= 0 [m],
             weight_in_water, ea, mbl (override the catalogue), sealed, drag,
             stretch, fibre, min_tension, stiffness_bounds}
    STRETCH: {model: hooke, ea} | {model: baranov, n > 0 [N^-1/2]}
             | {model: table, strain: [...], tension: [...]}   (moorsolve.model.stretch)
    BOUND: ea [N] | STRETCH | {model: dynamic, alpha, beta}
    body:                                      optional; absent = fairleads fixed in space
      free: [surge, sway, yaw]                 any subset, default all three
      loads: {force: [Fx, Fy, Mz], wind: {model: drag | hu_tang, ...},
              current: {model: drag | hu_tang, ...},
              wave_drift: {model: hu_tang | coefficient, ...}}
    legs:                                      required, non-empty
      - {name, anchor: [x, y] or [x, y, z], fairlead: [x, y, z],
         segments: [{type: NAME, length: > 0}, {clump: CLUMP}, {type: NAME, length}, ...],
         anchor_type: ANCHOR (optional)}
                                               from the anchor up; a clump item sits between
                                               two segments; CLUMP is {mass: kg >= 0,
                                               volume: m^3 >= 0} or {weight: N} (< 0: buoy)
    solver: {tol: (0, 1), max_iter: int >= 1, max_time_s: > 0,
             line_elements: int 2..400 (default 20)}
    checks: {standard: api-rp-2sk | dnv-os-e301, consequence_class: 1 | 2,
             offset_limit, offset_limit_damaged, min_grounded_length,
             min_grounded_length_damaged [m], anchor: ANCHOR, damaged: bool}   optional
    moordyn: {...}                             optional; MoorDyn columns moorsolve does not use,
                                               kept for export (moorsolve.model.moordyn_block);
                                               the solver ignores it
    ANCHOR: {type: drag} | {type: deadweight, allowed_uplift [N]}
            | {type: pile, allowed_uplift_angle_deg}
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping

from .. import catalog as line_catalog
from ..constants import SEAWATER_DENSITY
from ..errors import CaseError
from .environment import Environment, Flow, Seabed, Waves
from .lines import ANCHOR_KINDS, AnchorType, Clump, Leg, LineDrag, LineType, Segment
from .loads import (BodyLoads, DragLoad, DriftCoefficient, HuTangCurrent, HuTangDrift,
                    HuTangWind)
from .scene import DEGREES_OF_FREEDOM, STANDARDS, Body, Case, Checks, SolverOptions
from .fields import (FAIRLEAD_Z_MAX, GRAVITY_RANGE, MAX_AREA, MAX_DENSITY, MAX_DEPTH, MAX_EA,
                     MAX_FORCE, MAX_GRADIENT, MAX_HS, MAX_ITER_LIMIT, MAX_LINE_ELEMENTS,
                     MAX_LINE_LENGTH, MAX_MOMENT, MAX_SPEED, MAX_WEIGHT, MIN_DEPTH, MIN_EA,
                     MIN_LINE_LENGTH, MIN_WEIGHT, check_bounds, check_centre, check_list,
                     check_mapping, check_name, check_point, check_rows, field_path,
                     nullable_quantity, optional_quantity, quantity)
from .moordyn_block import validate_moordyn_block
from .stretch import LINE_TYPE_KEYS, line_type_fields
from .units import format_si, show_value, weight_per_length_to_si

__all__ = ["build_case"]


# ---- environment ------------------------------------------------------------------------


def _flow(raw, path: str, profile: bool = False) -> Flow:
    m = check_mapping(raw, path, required=("speed",),
                 optional=("toward_deg", "profile") if profile else ("toward_deg",))
    speed = quantity(m["speed"], field_path(path, "speed"), "speed", ge=0, le=MAX_SPEED)
    toward = optional_quantity(m, path, "toward_deg", "angle", 0.0)
    rows = None
    if m.get("profile") is not None:
        ppath = field_path(path, "profile")
        rows = []
        for rpath, row in check_rows(m["profile"], ppath, "[z, speed]", width=2, min_rows=1,
                                empty="a current profile (z <= 0, ascending)"):
            z = quantity(row[0], field_path(rpath, 0), "length", le=0)
            v = quantity(row[1], field_path(rpath, 1), "speed", ge=0)
            if rows and not z > rows[-1][0]:
                raise CaseError(field_path(rpath, 0), f"z = {format_si(z, 'length')} must be above "
                                                 "the previous row's (z ascending, from the "
                                                 "seabed up to the surface)")
            rows.append((z, v))
        rows = tuple(rows)
    return Flow(speed=speed, toward_deg=toward, profile=rows)


def _waves(raw, path: str) -> Waves:
    m = check_mapping(raw, path, required=("hs",), optional=("toward_deg",))
    hs = quantity(m["hs"], field_path(path, "hs"), "length", ge=0, le=MAX_HS)
    toward = optional_quantity(m, path, "toward_deg", "angle", 0.0)
    return Waves(hs=hs, toward_deg=toward)


def _environment(raw, path: str) -> Environment:
    m = check_mapping(raw, path, required=("depth",),
                 optional=("water_density", "air_density", "gravity", "seabed", "wind",
                           "current", "waves"))
    defaults = Environment(depth=1.0)
    dpath = field_path(path, "depth")
    depth = quantity(m["depth"], dpath, "length", gt=0, le=MAX_DEPTH)
    check_bounds(m["depth"], depth, "length", dpath, ge=MIN_DEPTH)
    water_density = optional_quantity(m, path, "water_density", "density", defaults.water_density,
                                      gt=0,
                           le=MAX_DENSITY)
    air_density = optional_quantity(m, path, "air_density", "density", defaults.air_density, gt=0,
                         le=MAX_DENSITY)
    gravity = optional_quantity(m, path, "gravity", "acceleration", defaults.gravity, gt=0,
                     le=GRAVITY_RANGE[1])
    check_bounds(m.get("gravity"), gravity, "acceleration", field_path(path, "gravity"),
                  ge=GRAVITY_RANGE[0])
    seabed = Seabed()
    if "seabed" in m:
        sub = field_path(path, "seabed")
        s = check_mapping(m["seabed"], sub, optional=("friction", "gradient"))
        gradient = (0.0, 0.0)
        if "gradient" in s:
            gpath = field_path(sub, "gradient")
            items = check_list(s["gradient"], gpath, "[dz/dx, dz/dy]")
            if len(items) != 2:
                raise CaseError(gpath, f"{show_value(s['gradient'])} has {len(items)} values; "
                                       "it must be [dz/dx, dz/dy]")
            gradient = tuple(quantity(v, field_path(gpath, i), "dimensionless", ge=-MAX_GRADIENT,
                                       le=MAX_GRADIENT) for i, v in enumerate(items))
            if math.hypot(*gradient) > MAX_GRADIENT:
                raise CaseError(gpath, f"slope {math.hypot(*gradient):.4g} must be <= "
                                       f"{MAX_GRADIENT} (45 deg)")
        seabed = Seabed(friction=optional_quantity(s, sub, "friction", "dimensionless", 0.0, ge=0),
                        gradient=gradient)
    wind = None if m.get("wind") is None else _flow(m["wind"], field_path(path, "wind"))
    current = (None if m.get("current") is None
               else _flow(m["current"], field_path(path, "current"), profile=True))
    waves = None if m.get("waves") is None else _waves(m["waves"], field_path(path, "waves"))
    return Environment(depth=depth, water_density=water_density, air_density=air_density,
                       gravity=gravity, seabed=seabed, wind=wind, current=current, waves=waves)


# ---- line types -------------------------------------------------------------------------


def _line_drag(raw, path: str) -> LineDrag:
    m = check_mapping(raw, path, required=("normal",), optional=("tangential", "side"))
    normal = quantity(m["normal"], field_path(path, "normal"), "dimensionless", ge=0, le=10)
    tangential = optional_quantity(m, path, "tangential", "dimensionless", 0.0, ge=0, le=10)
    side = optional_quantity(m, path, "side", "dimensionless", 0.0, ge=-10, le=10)
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
    m = check_mapping(raw, path, required=("weight_in_water",),
                 optional=("ea", "mbl", "diameter", "sealed", "catalog", "drag")
                 + LINE_TYPE_KEYS)
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
                    **line_type_fields(m, path, ea))


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
    m = check_mapping(raw, path, required=("catalog", "diameter"),
                 optional=("corrosion_allowance", "weight_in_water", "ea", "mbl", "sealed",
                           "drag") + LINE_TYPE_KEYS)
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
                                       catalogue=props))


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


# ---- body -------------------------------------------------------------------------------


def _table(raw, path: str) -> tuple:
    table = []
    for rpath, row in check_rows(raw, path, "[heading_deg, cx, cy, cmz]", width=4, min_rows=2,
                            empty="a coefficient table"):
        heading = quantity(row[0], field_path(rpath, 0), "angle", ge=-180.0, lt=360.0)
        coefficients = tuple(quantity(v, field_path(rpath, j), "dimensionless")
                             for j, v in enumerate(row[1:], start=1))
        if table and not heading > table[-1][0]:
            raise CaseError(field_path(rpath, 0), f"heading {heading:.6g} deg must be greater than "
                                             f"the previous row's {table[-1][0]:.6g} deg "
                                             "(headings strictly increasing)")
        table.append((heading,) + coefficients)
    span = table[-1][0] - table[0][0]
    if span >= 360.0:
        # The table is interpolated periodically, so it may cover at most one turn.
        raise CaseError(field_path(field_path(path, len(table) - 1), 0),
                        f"headings span {span:.6g} deg; a periodic table must span < 360 deg")
    return tuple(table)


def _drag(m: dict, path: str) -> DragLoad:
    m = check_mapping(m, path, required=("model", "area_x", "area_y"),
                 optional=("cx", "cy", "table", "length", "centre"))
    area_x = quantity(m["area_x"], field_path(path, "area_x"), "area", ge=0, le=MAX_AREA)
    area_y = quantity(m["area_y"], field_path(path, "area_y"), "area", ge=0, le=MAX_AREA)
    table = None if m.get("table") is None else _table(m["table"], field_path(path, "table"))
    if table is not None:
        for key in ("cx", "cy"):
            if key in m:
                raise CaseError(field_path(path, key),
                                f"{key} is not used with a table (the table's coefficients "
                                "replace it); give either cx/cy or a table")
    cx = optional_quantity(m, path, "cx", "dimensionless", 1.0, ge=0)
    cy = optional_quantity(m, path, "cy", "dimensionless", 1.0, ge=0)
    length = optional_quantity(m, path, "length", "length", 0.0, ge=0)
    if table is not None and length == 0.0 and any(row[3] != 0.0 for row in table):
        raise CaseError(field_path(path, "length"),
                        f"{format_si(length, 'length')}: a table with a non-zero cmz needs a "
                        "reference length > 0")
    return DragLoad(area_x=area_x, area_y=area_y, cx=cx, cy=cy, table=table, length=length,
                    centre=check_centre(m, path))


def _hu_tang_wind(m: dict, path: str) -> HuTangWind:
    m = check_mapping(m, path, required=("model", "superstructure_area", "hull_area"),
                 optional=("superstructure_area_lateral", "hull_area_lateral", "centre"))
    superstructure = quantity(m["superstructure_area"], field_path(path, "superstructure_area"),
                               "area", ge=0, le=MAX_AREA)
    hull = quantity(m["hull_area"], field_path(path, "hull_area"), "area", ge=0, le=MAX_AREA)
    superstructure_lat = nullable_quantity(m, path, "superstructure_area_lateral", "area", ge=0,
                                   le=MAX_AREA)
    hull_lat = nullable_quantity(m, path, "hull_area_lateral", "area", ge=0, le=MAX_AREA)
    if (superstructure_lat is None) != (hull_lat is None):
        missing = "hull_area_lateral" if hull_lat is None else "superstructure_area_lateral"
        raise CaseError(field_path(path, missing),
                        "superstructure_area_lateral and hull_area_lateral go together; give "
                        "both or neither")
    return HuTangWind(superstructure_area=superstructure, hull_area=hull,
                      superstructure_area_lateral=superstructure_lat,
                      hull_area_lateral=hull_lat, centre=check_centre(m, path))


def _hu_tang_current(m: dict, path: str) -> HuTangCurrent:
    m = check_mapping(m, path, required=("model", "wetted_area"), optional=("coefficient",
                                                                            "centre"))
    area = quantity(m["wetted_area"], field_path(path, "wetted_area"), "area", gt=0, le=MAX_AREA)
    coefficient = optional_quantity(m, path, "coefficient", "dimensionless", 0.18, gt=0)
    return HuTangCurrent(wetted_area=area, coefficient=coefficient, centre=check_centre(m, path))


def _hu_tang_drift(m: dict, path: str) -> HuTangDrift:
    m = check_mapping(m, path, required=("model", "beam"), optional=("length", "k", "centre"))
    beam = quantity(m["beam"], field_path(path, "beam"), "length", gt=0)
    length = nullable_quantity(m, path, "length", "length", gt=0)
    k = optional_quantity(m, path, "k", "dimensionless", 0.7, gt=0)
    return HuTangDrift(beam=beam, length=length, k=k, centre=check_centre(m, path))


def _drift_coefficient(m: dict, path: str) -> DriftCoefficient:
    m = check_mapping(m, path, required=("model", "length_x", "length_y"),
                 optional=("cx", "cy", "centre"))
    length_x = quantity(m["length_x"], field_path(path, "length_x"), "length", ge=0)
    length_y = quantity(m["length_y"], field_path(path, "length_y"), "length", ge=0)
    cx = optional_quantity(m, path, "cx", "dimensionless", 1.0, ge=0)
    cy = optional_quantity(m, path, "cy", "dimensionless", 1.0, ge=0)
    return DriftCoefficient(length_x=length_x, length_y=length_y, cx=cx, cy=cy,
                            centre=check_centre(m, path))


_LOAD_MODELS = {
    "wind": {"drag": _drag, "hu_tang": _hu_tang_wind},
    "current": {"drag": _drag, "hu_tang": _hu_tang_current},
    "wave_drift": {"hu_tang": _hu_tang_drift, "coefficient": _drift_coefficient},
}


def _load_model(raw, path: str, models: dict):
    """Dispatch on the required ``model`` key, then validate that model's keys."""
    allowed = ", ".join(models)
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping; give {{model: ...}} with model "
                              f"one of {allowed}")
    if "model" not in raw:
        raise CaseError(field_path(path, "model"), f"required key 'model' is missing; allowed "
                                              f"models: {allowed}")
    model = raw["model"]
    if not isinstance(model, str) or model not in models:
        raise CaseError(field_path(path, "model"),
                        f"unknown model {show_value(model)}; allowed models: "
                                              f"{allowed}")
    return models[model](raw, path)


def _force(raw, path: str) -> tuple:
    items = check_list(raw, path, "[Fx N, Fy N, Mz N m]")
    if len(items) != 3:
        raise CaseError(path, f"{show_value(raw)} has {len(items)} values; it must be "
                              "[Fx N, Fy N, Mz N m]")
    kinds = ("force", "force", "moment")
    limits = {"force": MAX_FORCE, "moment": MAX_MOMENT}
    return tuple(quantity(v, field_path(path, i), k, ge=-limits[k], le=limits[k])
                 for i, (v, k) in enumerate(zip(items, kinds)))


def _loads(raw, path: str) -> BodyLoads:
    m = check_mapping(raw, path, optional=("force",) + tuple(_LOAD_MODELS))
    force = None if m.get("force") is None else _force(m["force"], field_path(path, "force"))
    models = {key: (None if m.get(key) is None
                    else _load_model(m[key], field_path(path, key), _LOAD_MODELS[key]))
              for key in _LOAD_MODELS}
    return BodyLoads(force=force, **models)


def _free(raw, path: str) -> tuple:
    items = check_list(raw, path, f"a list drawn from {', '.join(DEGREES_OF_FREEDOM)}")
    seen = set()
    for i, item in enumerate(items):
        if not isinstance(item, str) or item not in DEGREES_OF_FREEDOM:
            raise CaseError(field_path(path, i), f"unknown degree of freedom {show_value(item)}; "
                                            f"allowed: {', '.join(DEGREES_OF_FREEDOM)}")
        if item in seen:
            raise CaseError(field_path(path, i), f"{item!r} is listed twice")
        seen.add(item)
    # Canonical order, so that downstream code never depends on how the user listed them.
    return tuple(dof for dof in DEGREES_OF_FREEDOM if dof in seen)


def _body(raw, path: str) -> Body:
    m = check_mapping(raw, path, optional=("free", "loads"))
    free = DEGREES_OF_FREEDOM if "free" not in m else _free(m["free"], field_path(path, "free"))
    loads = BodyLoads() if m.get("loads") is None else _loads(m["loads"], field_path(path, "loads"))
    return Body(free=free, loads=loads)


# ---- legs -------------------------------------------------------------------------------


def _segment(raw, path: str, line_types: dict) -> Segment:
    m = check_mapping(raw, path, required=("type", "length"))
    type_name = m["type"]
    if not isinstance(type_name, str) or type_name not in line_types:
        raise CaseError(field_path(path, "type"), f"unknown line type {show_value(type_name)}; "
                                             f"known line types: {', '.join(line_types)}")
    lpath = field_path(path, "length")
    length = quantity(m["length"], lpath, "length", gt=0, le=MAX_LINE_LENGTH)
    check_bounds(m["length"], length, "length", lpath, ge=MIN_LINE_LENGTH)
    return Segment(line_type=line_types[type_name], length=length)


def _clump(raw, path: str, environment: Environment) -> Clump:
    """``{mass: kg, volume: m^3}`` (net weight in water) or ``{weight: N}`` (negative: buoy)."""
    m = check_mapping(raw, path, optional=("mass", "volume", "weight"))
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


def _segments(raw, path: str, environment: Environment, line_types: dict):
    """Segments from anchor to fairlead, with optional ``{clump: ...}`` items between them."""
    items = check_list(raw, path, "a list of {type, length} segments from the anchor, with "
                                 "optional {clump: {...}} items between them")
    if not items:
        raise CaseError(path, "no segments; a leg needs one segment {type, length}")
    segments, clumps = [], []
    for j, item in enumerate(items):
        ipath = field_path(path, j)
        if isinstance(item, Mapping) and "clump" in item:
            check_mapping(item, ipath, required=("clump",))
            if not segments or len(clumps) != len(segments) - 1:
                raise CaseError(ipath, "a clump must sit between two segments (after a "
                                       "segment, not first and not after another clump)")
            clumps.append(_clump(item["clump"], field_path(ipath, "clump"), environment))
            continue
        if segments and len(clumps) < len(segments):
            clumps.append(None)
        segments.append(_segment(item, ipath, line_types))
    if len(clumps) == len(segments):
        raise CaseError(field_path(path, len(items) - 1),
                        "a clump must sit between two segments; this one ends the leg")
    return tuple(segments), tuple(clumps)


def _leg(raw, path: str, environment: Environment, line_types: dict) -> Leg:
    m = check_mapping(raw, path, required=("name", "anchor", "fairlead", "segments"),
                 optional=("anchor_type",))
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
                               "this fairlead, not under water; reduce environment.seabed."
                               "gradient or move the leg")
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
                               "this anchor, not under water; reduce environment.seabed."
                               "gradient or move the anchor")
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
        if anchor[2] > fz:
            raise CaseError(field_path(apath, 2), f"anchor z = {format_si(az, 'length')} is above "
                                             f"the fairlead (z = {format_si(fz, 'length')}); the "
                                             "anchor must not be higher than its fairlead")

    spath = field_path(path, "segments")
    segments, clumps = _segments(m["segments"], spath, environment, line_types)
    if sloped and len(segments) > 1:
        raise CaseError(spath, f"{len(segments)} segments on a sloped seabed: multi-segment legs "
                               "need a flat seabed (environment.seabed.gradient [0, 0]); a "
                               "sloped seabed takes one-segment legs")
    if not any(seg.line_type.elastic for seg in segments):
        # Body at zero offset: the body-frame fairlead is its global position.
        distance = math.dist(anchor, fairlead)
        length = sum(seg.length for seg in segments)
        if distance > length:
            raise CaseError(spath, f"the line ({format_si(length, 'length')}) cannot "
                                   f"reach from anchor to fairlead (distance "
                                   f"{format_si(distance, 'length')}); an inextensible line "
                                   "must be at least that long")
    return Leg(name=name, anchor=anchor, fairlead=fairlead, segments=segments,
               clumps=clumps if any(c is not None for c in clumps) else (),
               anchor_type=anchor_type)


def _legs(raw, path: str, environment: Environment, line_types: dict) -> tuple:
    items = check_list(raw, path, "a list of legs {name, anchor, fairlead, segments}")
    if not items:
        raise CaseError(path, "no legs; at least one leg is required")
    legs = []
    first_index = {}
    for i, item in enumerate(items):
        leg = _leg(item, field_path(path, i), environment, line_types)
        if leg.name in first_index:
            raise CaseError(field_path(field_path(path, i), "name"),
                            f"duplicate leg name {leg.name!r} (already used by "
                            f"legs[{first_index[leg.name]}]); leg names must be unique")
        first_index[leg.name] = i
        legs.append(leg)
    return tuple(legs)


# ---- mooring checks ---------------------------------------------------------------------

_ANCHOR_KEYS = {"drag": (), "deadweight": ("allowed_uplift",),
                "pile": ("allowed_uplift_angle_deg",)}


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
    keys = _ANCHOR_KEYS[kind]
    m = check_mapping(raw, path, required=("type",) + keys)
    if kind == "deadweight":
        uplift = quantity(m["allowed_uplift"], field_path(path, "allowed_uplift"), "force", ge=0)
        return AnchorType(kind=kind, allowed_uplift=uplift)
    if kind == "pile":
        angle = quantity(m["allowed_uplift_angle_deg"], field_path(path,
                                                                   "allowed_uplift_angle_deg"),
                          "angle", ge=0, lt=90)
        return AnchorType(kind=kind, allowed_uplift_angle_deg=angle)
    return AnchorType(kind=kind)


def _checks(raw, path: str, legs: tuple) -> Checks:
    m = check_mapping(raw, path, optional=("standard", "consequence_class", "offset_limit",
                                      "offset_limit_damaged", "min_grounded_length",
                                      "min_grounded_length_damaged", "anchor", "damaged"))
    defaults = Checks()
    standard = m.get("standard", defaults.standard)
    if not isinstance(standard, str) or standard not in STANDARDS:
        raise CaseError(field_path(path, "standard"), f"unknown standard {show_value(standard)}; "
                                                 f"allowed: {', '.join(STANDARDS)}")
    cclass = m.get("consequence_class", defaults.consequence_class)
    if isinstance(cclass, bool) or cclass not in (1, 2):
        raise CaseError(field_path(path, "consequence_class"),
                        f"{show_value(cclass)} must be 1 or 2 (DNV-OS-E301 consequence class)")
    offset = nullable_quantity(m, path, "offset_limit", "length", gt=0)
    offset_damaged = nullable_quantity(m, path, "offset_limit_damaged", "length", gt=0)
    grounded = nullable_quantity(m, path, "min_grounded_length", "length", ge=0)
    grounded_damaged = nullable_quantity(m, path, "min_grounded_length_damaged", "length", ge=0)
    for key, value in (("min_grounded_length", grounded),
                       ("min_grounded_length_damaged", grounded_damaged)):
        longest = max(leg.length for leg in legs)
        if value is not None and value >= longest:
            raise CaseError(field_path(path, key), f"{format_si(value, 'length')} must be shorter "
                                              f"than the longest leg "
                                              f"({format_si(longest, 'length')})")
    anchor = (defaults.anchor if m.get("anchor") is None
              else _anchor_type(m["anchor"], field_path(path, "anchor")))
    damaged = m.get("damaged", True)
    if not isinstance(damaged, bool):
        raise CaseError(field_path(path, "damaged"), f"{show_value(damaged)} is not true or false")
    return Checks(standard=standard, consequence_class=int(cclass), offset_limit=offset,
                  offset_limit_damaged=offset_damaged, min_grounded_length=grounded,
                  min_grounded_length_damaged=grounded_damaged, anchor=anchor,
                  damaged=damaged)


# ---- solver -----------------------------------------------------------------------------


def _solver(raw, path: str) -> SolverOptions:
    m = check_mapping(raw, path, optional=("tol", "max_iter", "max_time_s", "line_elements"))
    defaults = SolverOptions()
    tol = optional_quantity(m, path, "tol", "dimensionless", defaults.tol, gt=0, lt=1)
    max_iter = defaults.max_iter
    if "max_iter" in m:
        raw_iter = m["max_iter"]
        ipath = field_path(path, "max_iter")
        if isinstance(raw_iter, bool) or not isinstance(raw_iter, numbers.Integral):
            raise CaseError(ipath, f"{show_value(raw_iter)} is not an integer; max_iter must be an "
                                   f"integer from 1 to {MAX_ITER_LIMIT}")
        max_iter = int(raw_iter)
        if not 1 <= max_iter <= MAX_ITER_LIMIT:
            raise CaseError(ipath, f"{max_iter} must be an integer from 1 to {MAX_ITER_LIMIT}")
    max_time = optional_quantity(m, path, "max_time_s", "time", defaults.max_time_s, gt=0)
    elements = defaults.line_elements
    if "line_elements" in m:
        raw_n = m["line_elements"]
        epath = field_path(path, "line_elements")
        if isinstance(raw_n, bool) or not isinstance(raw_n, numbers.Integral) \
                or not 2 <= raw_n <= MAX_LINE_ELEMENTS:
            raise CaseError(epath, f"{show_value(raw_n)} must be an integer from 2 to "
                                   f"{MAX_LINE_ELEMENTS}")
        elements = int(raw_n)
    return SolverOptions(tol=tol, max_iter=max_iter, max_time_s=max_time,
                         line_elements=elements)


# ---- the case ---------------------------------------------------------------------------


def build_case(data, default_name: str = "case") -> Case:
    """The validated :class:`Case` of plain case-file data (see the module notes).

    Raises :class:`CaseError` naming the field for any problem.
    """
    m = check_mapping(data, "", required=("environment", "line_types", "legs"),
                 optional=("name", "body", "solver", "checks", "moordyn"))
    name = default_name if "name" not in m else check_name(m["name"], "name", "case name")
    # Environment first: gravity converts weights given as mass per length, and depth
    # places anchors given as [x, y].
    environment = _environment(m["environment"], "environment")
    line_types = _line_types(m["line_types"], "line_types", environment.gravity,
                             environment.water_density)
    body = None if m.get("body") is None else _body(m["body"], "body")
    legs = _legs(m["legs"], "legs", environment, line_types)
    solver = SolverOptions() if "solver" not in m else _solver(m["solver"], "solver")
    checks = None if m.get("checks") is None else _checks(m["checks"], "checks", legs)
    moordyn = (None if m.get("moordyn") is None
               else validate_moordyn_block(m["moordyn"], "moordyn", line_types, legs))
    if body is not None and "yaw" in body.free and all(
            leg.fairlead[0] == 0.0 and leg.fairlead[1] == 0.0 for leg in legs):
        # Every line acts through the body origin: no leg can resist a yaw moment, so the
        # yaw of the body is undetermined (and any applied moment unbalanced).
        raise CaseError("body.free", "yaw is free but every fairlead is at the body origin "
                                     "(x = y = 0), so nothing restrains yaw; remove yaw from "
                                     "body.free")
    return Case(name=name, environment=environment, line_types=line_types, legs=legs,
                body=body, solver=solver, checks=checks, moordyn=moordyn)
