"""Read and validate a case file (YAML) or case dictionary into a :class:`~moorsolve.model.Case`.

Validation is strict: every problem raises :class:`~moorsolve.errors.CaseError` whose
``field`` is the dotted path of the offending value (``legs[3].segments[0].length``) and
whose message names the value and what is allowed (``-5 m must be > 0``). Unknown keys are
errors; there are no aliases. Quantities may be given with units (see
:mod:`moorsolve.io.units`) and are converted to SI here, once.

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
             sealed: bool, drag: {normal: Cn, tangential: Ct, side: Cm}}
                                               drag needs a diameter
      NAME: {catalog: ENTRY, diameter > 0 [m], corrosion_allowance >= 0 [m],
             weight_in_water, ea, mbl (override the catalogue), sealed, drag}
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
                                               kept for export (moorsolve.io.moordyn_block);
                                               the solver ignores it
    ANCHOR: {type: drag} | {type: deadweight, allowed_uplift [N]}
            | {type: pile, allowed_uplift_angle_deg}
"""

from __future__ import annotations

import copy
import dataclasses
import math
import numbers
import re
from collections.abc import Mapping
from os import PathLike
from pathlib import Path

import yaml

from .. import catalog as line_catalog
from ..constants import SEAWATER_DENSITY
from ..errors import CaseError
from ..checks.criteria import STANDARDS
from ..model import (
    ANCHOR_KINDS,
    DEGREES_OF_FREEDOM,
    AnchorType,
    Body,
    BodyLoads,
    Clump,
    Case,
    Checks,
    DragLoad,
    DriftCoefficient,
    Environment,
    Flow,
    HuTangCurrent,
    HuTangDrift,
    HuTangWind,
    Leg,
    LineDrag,
    LineType,
    Seabed,
    Segment,
    SolverOptions,
    Waves,
)
from .moordyn_block import validate_moordyn_block
from .units import describe, format_si, show_value, to_si, weight_per_length_to_si

__all__ = ["load_case", "FAIRLEAD_Z_MAX"]

#: Highest fairlead allowed [m above still water]; catches a unit slip (mm for m) early.
FAIRLEAD_Z_MAX = 1000.0
#: Steepest seabed accepted (rise per metre): 45 deg. A chain does not rest on a steeper one.
MAX_GRADIENT = 1.0
#: The deepest ocean is under 11 km; a larger depth is a unit mistake.
MAX_DEPTH = 12_000.0
#: Longer than any mooring line ever laid: a unit mistake.
MAX_LINE_LENGTH = 100_000.0

#: Plausibility limits: values outside them are unit slips or nonsense, and would only
#: reach the solver as overflow or underflow (issue 7's fuzzing found NaN solves).
MIN_DEPTH = 0.01                 # [m]
MIN_LINE_LENGTH = 1e-3           # [m]; shorter than a millimetre is a unit mistake
MAX_WEIGHT = 1e6                 # [N/m] (100 t/m; the heaviest chain is about 0.3 t/m)
MIN_WEIGHT = 1e-6                # [N/m]; a lighter line is neutral: give 0
MIN_EA, MAX_EA = 1.0, 1e15       # [N]
MAX_FORCE = 1e12                 # [N] (a hundred million tonnes-force)
MAX_MOMENT = 1e15                # [N m]
MAX_SPEED = 200.0                # [m/s] for wind and current
MAX_HS = 100.0                   # [m]
MAX_AREA = 1e8                   # [m^2]
GRAVITY_RANGE = (0.1, 100.0)     # [m/s^2]
MAX_DENSITY = 1e5                # [kg/m^3]

#: Most elements of a discretised leg: beyond it the build time, not the accuracy, grows.
MAX_LINE_ELEMENTS = 400

#: Largest ``solver.max_iter``: IPOPT takes it as a C int.
MAX_ITER_LIMIT = 2**31 - 1

_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


# ---- small helpers ----------------------------------------------------------------------


def _join(path: str, key) -> str:
    """Extend a dotted path by a mapping key (str) or a list index (int)."""
    if isinstance(key, int):
        return f"{path}[{key}]"
    if isinstance(key, str) and _IDENTIFIER.match(key):
        return f"{path}.{key}" if path else key
    return f"{path}[{show_value(key)}]"


def _mapping(raw, path: str, required=(), optional=()) -> dict:
    """Check that ``raw`` is a mapping with string keys, all known and the required present."""
    allowed = tuple(required) + tuple(optional)
    where = path or "the case"
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping; {where} takes the keys "
                              f"{', '.join(allowed)}")
    for key in raw:
        if not isinstance(key, str):
            raise CaseError(path, f"key {show_value(key)} is not a string; allowed keys: "
                                  f"{', '.join(allowed)}")
        if key not in allowed:
            raise CaseError(_join(path, key), f"unknown key {key!r} in {where}; allowed keys: "
                                              f"{', '.join(allowed)}")
    for key in required:
        if key not in raw:
            raise CaseError(_join(path, key), f"required key {key!r} is missing from {where}")
    return dict(raw)


def _sequence(raw, path: str, what: str) -> list:
    """Check that ``raw`` is a list (or tuple) and return it as a list."""
    if isinstance(raw, (list, tuple)):
        return list(raw)
    raise CaseError(path, f"{show_value(raw)} is not a list; {path or 'this'} must be {what}")


def _rows(raw, path: str, shape: str, *, width: int, min_rows: int, empty: str):
    """Check that ``raw`` is a list of at least ``min_rows`` rows of ``width`` values each
    (``shape`` names a row, e.g. ``"[z, speed]"``) and yield ``(row_path, row)``."""
    rows = _sequence(raw, path, f"a list of rows {shape}")
    if len(rows) < min_rows:
        plural = "row" if min_rows == 1 else "rows"
        raise CaseError(path, f"{len(rows)} row(s); {empty} needs at least {min_rows} "
                              f"{plural} {shape}")
    for i, row_raw in enumerate(rows):
        rpath = _join(path, i)
        row = _sequence(row_raw, rpath, f"a row {shape}")
        if len(row) != width:
            raise CaseError(rpath, f"{show_value(row_raw)} has {len(row)} values; a row is "
                                   f"{shape}")
        yield rpath, row


def _check_bounds(raw, value: float, kind: str, path: str, *, gt=None, ge=None, lt=None,
                  le=None) -> float:
    def bound(b):
        return "0" if b == 0 else format_si(b, kind)

    if gt is not None and not value > gt:
        raise CaseError(path, f"{describe(raw, value, kind)} must be > {bound(gt)}")
    if ge is not None and not value >= ge:
        raise CaseError(path, f"{describe(raw, value, kind)} must be >= {bound(ge)}")
    if lt is not None and not value < lt:
        raise CaseError(path, f"{describe(raw, value, kind)} must be < {bound(lt)}")
    if le is not None and not value <= le:
        raise CaseError(path, f"{describe(raw, value, kind)} must be <= {bound(le)}")
    return value


def _quantity(raw, path: str, kind: str, **bounds) -> float:
    """Convert a quantity to SI and check its bounds (gt, ge, lt, le, in SI)."""
    return _check_bounds(raw, to_si(raw, kind, path), kind, path, **bounds)


def _field(m: dict, path: str, key: str, kind: str, default, **bounds) -> float:
    """A quantity with a default: absent -> default, present -> converted and checked."""
    if key not in m:
        return default
    return _quantity(m[key], _join(path, key), kind, **bounds)


def _nullable(m: dict, path: str, key: str, kind: str, **bounds):
    """A quantity whose absence (or null) means None."""
    if m.get(key) is None:
        return None
    return _quantity(m[key], _join(path, key), kind, **bounds)


def _name(raw, path: str, what: str) -> str:
    if not isinstance(raw, str) or not raw.strip():
        raise CaseError(path, f"{show_value(raw)} is not a valid {what}; give a non-empty string")
    return raw


def _point(raw, path: str, sizes: tuple) -> tuple:
    """A list of lengths [m] with one of the allowed ``sizes``."""
    shape = " or ".join({2: "[x, y]", 3: "[x, y, z]"}[n] for n in sizes)
    items = _sequence(raw, path, f"a list {shape} of lengths [m]")
    if len(items) not in sizes:
        raise CaseError(path, f"{show_value(raw)} has {len(items)} values; it must be {shape}")
    return tuple(_quantity(v, _join(path, i), "length") for i, v in enumerate(items))


def _centre(m: dict, path: str) -> tuple:
    if "centre" not in m:
        return (0.0, 0.0)
    return _point(m["centre"], _join(path, "centre"), (2,))


# ---- environment ------------------------------------------------------------------------


def _flow(raw, path: str, profile: bool = False) -> Flow:
    m = _mapping(raw, path, required=("speed",),
                 optional=("toward_deg", "profile") if profile else ("toward_deg",))
    speed = _quantity(m["speed"], _join(path, "speed"), "speed", ge=0, le=MAX_SPEED)
    toward = _field(m, path, "toward_deg", "angle", 0.0)
    rows = None
    if m.get("profile") is not None:
        ppath = _join(path, "profile")
        rows = []
        for rpath, row in _rows(m["profile"], ppath, "[z, speed]", width=2, min_rows=1,
                                empty="a current profile (z <= 0, ascending)"):
            z = _quantity(row[0], _join(rpath, 0), "length", le=0)
            v = _quantity(row[1], _join(rpath, 1), "speed", ge=0)
            if rows and not z > rows[-1][0]:
                raise CaseError(_join(rpath, 0), f"z = {format_si(z, 'length')} must be above "
                                                 "the previous row's (z ascending, from the "
                                                 "seabed up to the surface)")
            rows.append((z, v))
        rows = tuple(rows)
    return Flow(speed=speed, toward_deg=toward, profile=rows)


def _waves(raw, path: str) -> Waves:
    m = _mapping(raw, path, required=("hs",), optional=("toward_deg",))
    hs = _quantity(m["hs"], _join(path, "hs"), "length", ge=0, le=MAX_HS)
    toward = _field(m, path, "toward_deg", "angle", 0.0)
    return Waves(hs=hs, toward_deg=toward)


def _environment(raw, path: str) -> Environment:
    m = _mapping(raw, path, required=("depth",),
                 optional=("water_density", "air_density", "gravity", "seabed", "wind",
                           "current", "waves"))
    defaults = Environment(depth=1.0)
    dpath = _join(path, "depth")
    depth = _quantity(m["depth"], dpath, "length", gt=0, le=MAX_DEPTH)
    _check_bounds(m["depth"], depth, "length", dpath, ge=MIN_DEPTH)
    water_density = _field(m, path, "water_density", "density", defaults.water_density, gt=0,
                           le=MAX_DENSITY)
    air_density = _field(m, path, "air_density", "density", defaults.air_density, gt=0,
                         le=MAX_DENSITY)
    gravity = _field(m, path, "gravity", "acceleration", defaults.gravity, gt=0,
                     le=GRAVITY_RANGE[1])
    _check_bounds(m.get("gravity"), gravity, "acceleration", _join(path, "gravity"),
                  ge=GRAVITY_RANGE[0])
    seabed = Seabed()
    if "seabed" in m:
        sub = _join(path, "seabed")
        s = _mapping(m["seabed"], sub, optional=("friction", "gradient"))
        gradient = (0.0, 0.0)
        if "gradient" in s:
            gpath = _join(sub, "gradient")
            items = _sequence(s["gradient"], gpath, "[dz/dx, dz/dy]")
            if len(items) != 2:
                raise CaseError(gpath, f"{show_value(s['gradient'])} has {len(items)} values; "
                                       "it must be [dz/dx, dz/dy]")
            gradient = tuple(_quantity(v, _join(gpath, i), "dimensionless", ge=-MAX_GRADIENT,
                                       le=MAX_GRADIENT) for i, v in enumerate(items))
            if math.hypot(*gradient) > MAX_GRADIENT:
                raise CaseError(gpath, f"slope {math.hypot(*gradient):.4g} must be <= "
                                       f"{MAX_GRADIENT} (45 deg)")
        seabed = Seabed(friction=_field(s, sub, "friction", "dimensionless", 0.0, ge=0),
                        gradient=gradient)
    wind = None if m.get("wind") is None else _flow(m["wind"], _join(path, "wind"))
    current = (None if m.get("current") is None
               else _flow(m["current"], _join(path, "current"), profile=True))
    waves = None if m.get("waves") is None else _waves(m["waves"], _join(path, "waves"))
    return Environment(depth=depth, water_density=water_density, air_density=air_density,
                       gravity=gravity, seabed=seabed, wind=wind, current=current, waves=waves)


# ---- line types -------------------------------------------------------------------------


def _line_drag(raw, path: str) -> LineDrag:
    m = _mapping(raw, path, required=("normal",), optional=("tangential", "side"))
    normal = _quantity(m["normal"], _join(path, "normal"), "dimensionless", ge=0, le=10)
    tangential = _field(m, path, "tangential", "dimensionless", 0.0, ge=0, le=10)
    side = _field(m, path, "side", "dimensionless", 0.0, ge=-10, le=10)
    return LineDrag(normal=normal, tangential=tangential, side=side)


def _line_type_drag(m: dict, path: str, diameter):
    """The optional ``drag`` of a line type; it needs the diameter."""
    drag = None if m.get("drag") is None else _line_drag(m["drag"], _join(path, "drag"))
    if drag is not None and diameter is None:
        raise CaseError(_join(path, "diameter"),
                        "a line type with drag needs a diameter (the flow force scales with "
                        "it); give diameter > 0 [m]")
    return drag


def _line_type(name: str, raw, path: str, gravity: float,
               water_density: float = SEAWATER_DENSITY) -> LineType:
    if isinstance(raw, Mapping) and "catalog" in raw:
        return _catalog_line_type(name, raw, path, gravity, water_density)
    m = _mapping(raw, path, required=("weight_in_water",),
                 optional=("ea", "mbl", "diameter", "sealed", "catalog", "drag"))
    wpath = _join(path, "weight_in_water")
    weight = weight_per_length_to_si(m["weight_in_water"], gravity, wpath)
    if abs(weight) > MAX_WEIGHT:
        raise CaseError(wpath, f"{format_si(weight, 'force_per_length')} must be between "
                               f"-{MAX_WEIGHT:g} and {MAX_WEIGHT:g} N/m (a unit mistake?)")
    if 0 < abs(weight) < MIN_WEIGHT:
        raise CaseError(wpath, f"{format_si(weight, 'force_per_length')} is too small to "
                               f"hang as a catenary; give 0 for a neutrally buoyant line or "
                               f"at least {MIN_WEIGHT:g} N/m in magnitude")
    ea = _nullable(m, path, "ea", "force", gt=0, le=MAX_EA)
    if ea is not None:
        _check_bounds(m["ea"], ea, "force", _join(path, "ea"), ge=MIN_EA)
    mbl = _nullable(m, path, "mbl", "force", gt=0)
    diameter = _nullable(m, path, "diameter", "length", gt=0)
    sealed = _sealed(m, path, diameter)
    return LineType(name=name, weight_in_water=weight, ea=ea, mbl=mbl, diameter=diameter,
                    sealed=sealed, drag=_line_type_drag(m, path, diameter))


def _sealed(m: dict, path: str, diameter) -> bool:
    sealed = False
    if "sealed" in m:
        sealed = m["sealed"]
        if not isinstance(sealed, bool):
            raise CaseError(_join(path, "sealed"), f"{show_value(sealed)} is not true or false")
    if sealed and diameter is None:
        raise CaseError(_join(path, "diameter"),
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
    m = _mapping(raw, path, required=("catalog", "diameter"),
                 optional=("corrosion_allowance", "weight_in_water", "ea", "mbl", "sealed",
                           "drag"))
    known = line_catalog.entries()
    entry = m["catalog"]
    if not isinstance(entry, str) or entry not in known:
        raise CaseError(_join(path, "catalog"), f"unknown catalogue entry {show_value(entry)}; "
                                                f"known entries: {', '.join(known)}")
    diameter = _quantity(m["diameter"], _join(path, "diameter"), "length", gt=0, le=1.0)
    allowance = _field(m, path, "corrosion_allowance", "length", 0.0, ge=0)
    if allowance >= diameter:
        raise CaseError(_join(path, "corrosion_allowance"),
                        f"{format_si(allowance, 'length')} must be smaller than the diameter "
                        f"({format_si(diameter, 'length')})")
    props = line_catalog.line_properties(entry, diameter, water_density=water_density,
                                         gravity=gravity, corrosion_allowance=allowance)
    weight = props.weight_in_water
    if m.get("weight_in_water") is not None:
        weight = weight_per_length_to_si(m["weight_in_water"], gravity,
                                         _join(path, "weight_in_water"))
    ea = _nullable(m, path, "ea", "force", gt=0)
    mbl = _nullable(m, path, "mbl", "force", gt=0)
    if mbl is not None and "corrosion_allowance" in m:
        raise CaseError(_join(path, "corrosion_allowance"),
                        "applies to the catalogue MBL only; with an explicit mbl give the "
                        "corroded value directly")
    return LineType(name=name, weight_in_water=weight,
                    ea=props.ea if ea is None else ea,
                    mbl=props.mbl if mbl is None else mbl,
                    diameter=diameter, sealed=_sealed(m, path, diameter), catalog=entry,
                    drag=_line_type_drag(m, path, diameter),
                    corrosion_allowance=allowance, source=props.source)


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
        types[name] = _line_type(name, spec, _join(path, name), gravity, water_density)
    return types


# ---- body -------------------------------------------------------------------------------


def _table(raw, path: str) -> tuple:
    table = []
    for rpath, row in _rows(raw, path, "[heading_deg, cx, cy, cmz]", width=4, min_rows=2,
                            empty="a coefficient table"):
        heading = _quantity(row[0], _join(rpath, 0), "angle", ge=-180.0, lt=360.0)
        coefficients = tuple(_quantity(v, _join(rpath, j), "dimensionless")
                             for j, v in enumerate(row[1:], start=1))
        if table and not heading > table[-1][0]:
            raise CaseError(_join(rpath, 0), f"heading {heading:.6g} deg must be greater than "
                                             f"the previous row's {table[-1][0]:.6g} deg "
                                             "(headings strictly increasing)")
        table.append((heading,) + coefficients)
    span = table[-1][0] - table[0][0]
    if span >= 360.0:
        # The table is interpolated periodically, so it may cover at most one turn.
        raise CaseError(_join(_join(path, len(table) - 1), 0),
                        f"headings span {span:.6g} deg; a periodic table must span < 360 deg")
    return tuple(table)


def _drag(m: dict, path: str) -> DragLoad:
    m = _mapping(m, path, required=("model", "area_x", "area_y"),
                 optional=("cx", "cy", "table", "length", "centre"))
    area_x = _quantity(m["area_x"], _join(path, "area_x"), "area", ge=0, le=MAX_AREA)
    area_y = _quantity(m["area_y"], _join(path, "area_y"), "area", ge=0, le=MAX_AREA)
    table = None if m.get("table") is None else _table(m["table"], _join(path, "table"))
    if table is not None:
        for key in ("cx", "cy"):
            if key in m:
                raise CaseError(_join(path, key),
                                f"{key} is not used with a table (the table's coefficients "
                                "replace it); give either cx/cy or a table")
    cx = _field(m, path, "cx", "dimensionless", 1.0, ge=0)
    cy = _field(m, path, "cy", "dimensionless", 1.0, ge=0)
    length = _field(m, path, "length", "length", 0.0, ge=0)
    if table is not None and length == 0.0 and any(row[3] != 0.0 for row in table):
        raise CaseError(_join(path, "length"),
                        f"{format_si(length, 'length')}: a table with a non-zero cmz needs a "
                        "reference length > 0")
    return DragLoad(area_x=area_x, area_y=area_y, cx=cx, cy=cy, table=table, length=length,
                    centre=_centre(m, path))


def _hu_tang_wind(m: dict, path: str) -> HuTangWind:
    m = _mapping(m, path, required=("model", "superstructure_area", "hull_area"),
                 optional=("superstructure_area_lateral", "hull_area_lateral", "centre"))
    superstructure = _quantity(m["superstructure_area"], _join(path, "superstructure_area"),
                               "area", ge=0, le=MAX_AREA)
    hull = _quantity(m["hull_area"], _join(path, "hull_area"), "area", ge=0, le=MAX_AREA)
    superstructure_lat = _nullable(m, path, "superstructure_area_lateral", "area", ge=0,
                                   le=MAX_AREA)
    hull_lat = _nullable(m, path, "hull_area_lateral", "area", ge=0, le=MAX_AREA)
    if (superstructure_lat is None) != (hull_lat is None):
        missing = "hull_area_lateral" if hull_lat is None else "superstructure_area_lateral"
        raise CaseError(_join(path, missing),
                        "superstructure_area_lateral and hull_area_lateral go together; give "
                        "both or neither")
    return HuTangWind(superstructure_area=superstructure, hull_area=hull,
                      superstructure_area_lateral=superstructure_lat,
                      hull_area_lateral=hull_lat, centre=_centre(m, path))


def _hu_tang_current(m: dict, path: str) -> HuTangCurrent:
    m = _mapping(m, path, required=("model", "wetted_area"), optional=("coefficient", "centre"))
    area = _quantity(m["wetted_area"], _join(path, "wetted_area"), "area", gt=0, le=MAX_AREA)
    coefficient = _field(m, path, "coefficient", "dimensionless", 0.18, gt=0)
    return HuTangCurrent(wetted_area=area, coefficient=coefficient, centre=_centre(m, path))


def _hu_tang_drift(m: dict, path: str) -> HuTangDrift:
    m = _mapping(m, path, required=("model", "beam"), optional=("length", "k", "centre"))
    beam = _quantity(m["beam"], _join(path, "beam"), "length", gt=0)
    length = _nullable(m, path, "length", "length", gt=0)
    k = _field(m, path, "k", "dimensionless", 0.7, gt=0)
    return HuTangDrift(beam=beam, length=length, k=k, centre=_centre(m, path))


def _drift_coefficient(m: dict, path: str) -> DriftCoefficient:
    m = _mapping(m, path, required=("model", "length_x", "length_y"),
                 optional=("cx", "cy", "centre"))
    length_x = _quantity(m["length_x"], _join(path, "length_x"), "length", ge=0)
    length_y = _quantity(m["length_y"], _join(path, "length_y"), "length", ge=0)
    cx = _field(m, path, "cx", "dimensionless", 1.0, ge=0)
    cy = _field(m, path, "cy", "dimensionless", 1.0, ge=0)
    return DriftCoefficient(length_x=length_x, length_y=length_y, cx=cx, cy=cy,
                            centre=_centre(m, path))


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
        raise CaseError(_join(path, "model"), f"required key 'model' is missing; allowed "
                                              f"models: {allowed}")
    model = raw["model"]
    if not isinstance(model, str) or model not in models:
        raise CaseError(_join(path, "model"), f"unknown model {show_value(model)}; allowed models: "
                                              f"{allowed}")
    return models[model](raw, path)


def _force(raw, path: str) -> tuple:
    items = _sequence(raw, path, "[Fx N, Fy N, Mz N m]")
    if len(items) != 3:
        raise CaseError(path, f"{show_value(raw)} has {len(items)} values; it must be "
                              "[Fx N, Fy N, Mz N m]")
    kinds = ("force", "force", "moment")
    limits = {"force": MAX_FORCE, "moment": MAX_MOMENT}
    return tuple(_quantity(v, _join(path, i), k, ge=-limits[k], le=limits[k])
                 for i, (v, k) in enumerate(zip(items, kinds)))


def _loads(raw, path: str) -> BodyLoads:
    m = _mapping(raw, path, optional=("force",) + tuple(_LOAD_MODELS))
    force = None if m.get("force") is None else _force(m["force"], _join(path, "force"))
    models = {key: (None if m.get(key) is None
                    else _load_model(m[key], _join(path, key), _LOAD_MODELS[key]))
              for key in _LOAD_MODELS}
    return BodyLoads(force=force, **models)


def _free(raw, path: str) -> tuple:
    items = _sequence(raw, path, f"a list drawn from {', '.join(DEGREES_OF_FREEDOM)}")
    seen = set()
    for i, item in enumerate(items):
        if not isinstance(item, str) or item not in DEGREES_OF_FREEDOM:
            raise CaseError(_join(path, i), f"unknown degree of freedom {show_value(item)}; "
                                            f"allowed: {', '.join(DEGREES_OF_FREEDOM)}")
        if item in seen:
            raise CaseError(_join(path, i), f"{item!r} is listed twice")
        seen.add(item)
    # Canonical order, so that downstream code never depends on how the user listed them.
    return tuple(dof for dof in DEGREES_OF_FREEDOM if dof in seen)


def _body(raw, path: str) -> Body:
    m = _mapping(raw, path, optional=("free", "loads"))
    free = DEGREES_OF_FREEDOM if "free" not in m else _free(m["free"], _join(path, "free"))
    loads = BodyLoads() if m.get("loads") is None else _loads(m["loads"], _join(path, "loads"))
    return Body(free=free, loads=loads)


# ---- legs -------------------------------------------------------------------------------


def _segment(raw, path: str, line_types: dict) -> Segment:
    m = _mapping(raw, path, required=("type", "length"))
    type_name = m["type"]
    if not isinstance(type_name, str) or type_name not in line_types:
        raise CaseError(_join(path, "type"), f"unknown line type {show_value(type_name)}; "
                                             f"known line types: {', '.join(line_types)}")
    lpath = _join(path, "length")
    length = _quantity(m["length"], lpath, "length", gt=0, le=MAX_LINE_LENGTH)
    _check_bounds(m["length"], length, "length", lpath, ge=MIN_LINE_LENGTH)
    return Segment(line_type=line_types[type_name], length=length)


def _clump(raw, path: str, environment: Environment) -> Clump:
    """``{mass: kg, volume: m^3}`` (net weight in water) or ``{weight: N}`` (negative: buoy)."""
    m = _mapping(raw, path, optional=("mass", "volume", "weight"))
    if "weight" in m:
        for key in ("mass", "volume"):
            if key in m:
                raise CaseError(_join(path, key), f"{key} is not used with weight; give either "
                                                  "weight [N] or mass [kg] and volume [m^3]")
        weight = _quantity(m["weight"], _join(path, "weight"), "force")
        return Clump(weight=weight)
    if "mass" not in m:
        raise CaseError(_join(path, "mass"), "a clump needs mass [kg] (and optionally volume "
                                             "[m^3]) or a net weight [N]")
    mass = _quantity(m["mass"], _join(path, "mass"), "mass", ge=0)
    volume = _field(m, path, "volume", "volume", 0.0, ge=0)
    weight = environment.gravity * (mass - environment.water_density * volume)
    return Clump(weight=weight, mass=mass, volume=volume)


def _segments(raw, path: str, environment: Environment, line_types: dict):
    """Segments from anchor to fairlead, with optional ``{clump: ...}`` items between them."""
    items = _sequence(raw, path, "a list of {type, length} segments from the anchor, with "
                                 "optional {clump: {...}} items between them")
    if not items:
        raise CaseError(path, "no segments; a leg needs one segment {type, length}")
    segments, clumps = [], []
    for j, item in enumerate(items):
        ipath = _join(path, j)
        if isinstance(item, Mapping) and "clump" in item:
            _mapping(item, ipath, required=("clump",))
            if not segments or len(clumps) != len(segments) - 1:
                raise CaseError(ipath, "a clump must sit between two segments (after a "
                                       "segment, not first and not after another clump)")
            clumps.append(_clump(item["clump"], _join(ipath, "clump"), environment))
            continue
        if segments and len(clumps) < len(segments):
            clumps.append(None)
        segments.append(_segment(item, ipath, line_types))
    if len(clumps) == len(segments):
        raise CaseError(_join(path, len(items) - 1),
                        "a clump must sit between two segments; this one ends the leg")
    return tuple(segments), tuple(clumps)


def _leg(raw, path: str, environment: Environment, line_types: dict) -> Leg:
    m = _mapping(raw, path, required=("name", "anchor", "fairlead", "segments"),
                 optional=("anchor_type",))
    name = _name(m["name"], _join(path, "name"), "leg name")
    anchor_type = (None if m.get("anchor_type") is None
                   else _anchor_type(m["anchor_type"], _join(path, "anchor_type")))
    depth = environment.depth
    seabed_tol = 1e-9 * max(depth, 1.0)  # unit conversions may leave the seabed z a few ulp off
    sloped = environment.seabed.sloped
    allowed = "must be on or above the (sloped) seabed" if sloped else "must be >= -depth"

    fpath = _join(path, "fairlead")
    fairlead = _point(m["fairlead"], fpath, (3,))
    fz = fairlead[2]
    bed = environment.seabed_z(fairlead[0], fairlead[1])
    if bed >= 0:
        raise CaseError(fpath, f"the sloped seabed is at z = {format_si(bed, 'length')} under "
                               "this fairlead, not under water; reduce environment.seabed."
                               "gradient or move the leg")
    if fz < bed - seabed_tol:
        raise CaseError(_join(fpath, 2), f"fairlead z = {format_si(fz, 'length')} is below "
                                         f"the seabed (z = {format_si(bed, 'length')}); it "
                                         f"{allowed}")
    fz = max(fz, bed)
    fairlead = fairlead[:2] + (fz,)
    if fz > FAIRLEAD_Z_MAX:
        raise CaseError(_join(fpath, 2), f"fairlead z = {format_si(fz, 'length')} must be <= "
                                         f"{format_si(FAIRLEAD_Z_MAX, 'length')}")

    apath = _join(path, "anchor")
    anchor = _point(m["anchor"], apath, (2, 3))
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
            raise CaseError(_join(apath, 2), f"anchor z = {format_si(az, 'length')} is below the "
                                             f"seabed (z = {format_si(bed, 'length')}); it "
                                             f"{allowed}")
        if az < bed:
            anchor = anchor[:2] + (bed,)
        if anchor[2] > fz:
            raise CaseError(_join(apath, 2), f"anchor z = {format_si(az, 'length')} is above "
                                             f"the fairlead (z = {format_si(fz, 'length')}); the "
                                             "anchor must not be higher than its fairlead")

    spath = _join(path, "segments")
    segments, clumps = _segments(m["segments"], spath, environment, line_types)
    if sloped and len(segments) > 1:
        raise CaseError(spath, f"{len(segments)} segments on a sloped seabed: multi-segment legs "
                               "need a flat seabed (environment.seabed.gradient [0, 0]); a "
                               "sloped seabed takes one-segment legs")
    if all(seg.line_type.ea is None for seg in segments):
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
    items = _sequence(raw, path, "a list of legs {name, anchor, fairlead, segments}")
    if not items:
        raise CaseError(path, "no legs; at least one leg is required")
    legs = []
    first_index = {}
    for i, item in enumerate(items):
        leg = _leg(item, _join(path, i), environment, line_types)
        if leg.name in first_index:
            raise CaseError(_join(_join(path, i), "name"),
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
        raise CaseError(_join(path, "type"), f"unknown anchor type {show_value(kind)}; allowed: "
                                             f"{allowed}")
    keys = _ANCHOR_KEYS[kind]
    m = _mapping(raw, path, required=("type",) + keys)
    if kind == "deadweight":
        uplift = _quantity(m["allowed_uplift"], _join(path, "allowed_uplift"), "force", ge=0)
        return AnchorType(kind=kind, allowed_uplift=uplift)
    if kind == "pile":
        angle = _quantity(m["allowed_uplift_angle_deg"], _join(path, "allowed_uplift_angle_deg"),
                          "angle", ge=0, lt=90)
        return AnchorType(kind=kind, allowed_uplift_angle_deg=angle)
    return AnchorType(kind=kind)


def _checks(raw, path: str, legs: tuple) -> Checks:
    m = _mapping(raw, path, optional=("standard", "consequence_class", "offset_limit",
                                      "offset_limit_damaged", "min_grounded_length",
                                      "min_grounded_length_damaged", "anchor", "damaged"))
    defaults = Checks()
    standard = m.get("standard", defaults.standard)
    if not isinstance(standard, str) or standard not in STANDARDS:
        raise CaseError(_join(path, "standard"), f"unknown standard {show_value(standard)}; "
                                                 f"allowed: {', '.join(STANDARDS)}")
    cclass = m.get("consequence_class", defaults.consequence_class)
    if isinstance(cclass, bool) or cclass not in (1, 2):
        raise CaseError(_join(path, "consequence_class"),
                        f"{show_value(cclass)} must be 1 or 2 (DNV-OS-E301 consequence class)")
    offset = _nullable(m, path, "offset_limit", "length", gt=0)
    offset_damaged = _nullable(m, path, "offset_limit_damaged", "length", gt=0)
    grounded = _nullable(m, path, "min_grounded_length", "length", ge=0)
    grounded_damaged = _nullable(m, path, "min_grounded_length_damaged", "length", ge=0)
    for key, value in (("min_grounded_length", grounded),
                       ("min_grounded_length_damaged", grounded_damaged)):
        longest = max(leg.length for leg in legs)
        if value is not None and value >= longest:
            raise CaseError(_join(path, key), f"{format_si(value, 'length')} must be shorter "
                                              f"than the longest leg "
                                              f"({format_si(longest, 'length')})")
    anchor = (defaults.anchor if m.get("anchor") is None
              else _anchor_type(m["anchor"], _join(path, "anchor")))
    damaged = m.get("damaged", True)
    if not isinstance(damaged, bool):
        raise CaseError(_join(path, "damaged"), f"{show_value(damaged)} is not true or false")
    return Checks(standard=standard, consequence_class=int(cclass), offset_limit=offset,
                  offset_limit_damaged=offset_damaged, min_grounded_length=grounded,
                  min_grounded_length_damaged=grounded_damaged, anchor=anchor,
                  damaged=damaged)


# ---- solver -----------------------------------------------------------------------------


def _solver(raw, path: str) -> SolverOptions:
    m = _mapping(raw, path, optional=("tol", "max_iter", "max_time_s", "line_elements"))
    defaults = SolverOptions()
    tol = _field(m, path, "tol", "dimensionless", defaults.tol, gt=0, lt=1)
    max_iter = defaults.max_iter
    if "max_iter" in m:
        raw_iter = m["max_iter"]
        ipath = _join(path, "max_iter")
        if isinstance(raw_iter, bool) or not isinstance(raw_iter, numbers.Integral):
            raise CaseError(ipath, f"{show_value(raw_iter)} is not an integer; max_iter must be an "
                                   f"integer from 1 to {MAX_ITER_LIMIT}")
        max_iter = int(raw_iter)
        if not 1 <= max_iter <= MAX_ITER_LIMIT:
            raise CaseError(ipath, f"{max_iter} must be an integer from 1 to {MAX_ITER_LIMIT}")
    max_time = _field(m, path, "max_time_s", "time", defaults.max_time_s, gt=0)
    elements = defaults.line_elements
    if "line_elements" in m:
        raw_n = m["line_elements"]
        epath = _join(path, "line_elements")
        if isinstance(raw_n, bool) or not isinstance(raw_n, numbers.Integral) \
                or not 2 <= raw_n <= MAX_LINE_ELEMENTS:
            raise CaseError(epath, f"{show_value(raw_n)} must be an integer from 2 to "
                                   f"{MAX_LINE_ELEMENTS}")
        elements = int(raw_n)
    return SolverOptions(tol=tol, max_iter=max_iter, max_time_s=max_time,
                         line_elements=elements)


# ---- the case ---------------------------------------------------------------------------


def _build_case(data, default_name: str) -> Case:
    m = _mapping(data, "", required=("environment", "line_types", "legs"),
                 optional=("name", "body", "solver", "checks", "moordyn"))
    name = default_name if "name" not in m else _name(m["name"], "name", "case name")
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


class _StrictLoader(yaml.SafeLoader):
    """A safe YAML loader that rejects duplicate mapping keys instead of keeping the last."""


def _construct_strict_mapping(loader, node):
    seen = set()
    for key_node, _ in node.value:
        if key_node.tag == "tag:yaml.org,2002:merge":
            continue
        key = loader.construct_object(key_node, deep=True)
        try:
            duplicate = key in seen
        except TypeError:
            raise yaml.constructor.ConstructorError(
                "while constructing a mapping", node.start_mark, "found an unhashable key",
                key_node.start_mark) from None
        if duplicate:
            raise yaml.constructor.ConstructorError(
                "while constructing a mapping", node.start_mark,
                f"found duplicate key {key!r}", key_node.start_mark)
        seen.add(key)
    return loader.construct_mapping(node, deep=True)


_StrictLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG,
                              _construct_strict_mapping)


def _yaml_message(exc: Exception) -> str:
    mark = getattr(exc, "problem_mark", None)
    problem = getattr(exc, "problem", None)
    if mark is not None and problem:
        return f"invalid YAML at line {mark.line + 1}, column {mark.column + 1}: {problem}"
    return "invalid YAML: " + " ".join(str(exc).split())


def _read_yaml(path: Path):
    label = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise CaseError(label, "case file not found") from None
    except IsADirectoryError:
        raise CaseError(label, "is a directory, not a case file") from None
    except UnicodeDecodeError as exc:
        raise CaseError(label, f"is not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    except (OSError, ValueError) as exc:
        raise CaseError(label, f"cannot read the case file: {exc}") from None
    try:
        data = yaml.load(text, Loader=_StrictLoader)
    except RecursionError:
        raise CaseError(label, "invalid YAML: nested too deeply") from None
    except Exception as exc:  # YAMLError, and ValueError from e.g. a date like 2020-13-45
        raise CaseError(label, _yaml_message(exc)) from None
    if not isinstance(data, Mapping):
        raise CaseError(label, f"the file holds {type(data).__name__}, not a mapping; a case "
                               "file has the keys environment, line_types, legs (and optionally "
                               "name, body, solver)")
    return data


def load_case(source, *, keep_source: bool = True) -> Case:
    """Load and validate a mooring case.

    Parameters
    ----------
    source : str, pathlib.Path or mapping
        Path to a YAML case file, or a dictionary of the same shape.
    keep_source : bool
        Keep a copy of the case-file data as ``Case.source`` (what sweeps edit); a
        caller that validates many throw-away variants may skip the copy.

    Returns
    -------
    moorsolve.model.Case
        The validated case, in SI units. Its name defaults to the file stem (or ``"case"``
        for a dictionary).

    Raises
    ------
    CaseError
        For any problem with the input; ``field`` is the dotted path of the offending value
        (``legs[3].segments[0].length``), or the file name for a file that cannot be read or
        parsed. No other exception escapes.

    Notes
    -----
    Checks beyond the schema: anchors lie on or above the seabed and below their fairlead;
    fairleads lie above the seabed and at most :data:`FAIRLEAD_Z_MAX` above still water; an
    inextensible line is at least as long as the straight distance from its anchor to its
    fairlead at the case-file position (body at zero offset); leg names are unique; clump
    items sit between two segments.

    Examples
    --------
    >>> case = load_case("cases/floating_dock.yaml")  # doctest: +SKIP
    >>> case.legs[0].anchor  # doctest: +SKIP
    (-240.0, -120.0, -20.85)
    """
    if isinstance(source, (str, PathLike)):
        try:
            path = Path(source)
        except TypeError:
            raise CaseError("", f"{show_value(source)} is not a usable path") from None
        data = _read_yaml(path)
        default_name = path.stem or "case"
    elif isinstance(source, Mapping):
        data, default_name = source, "case"
    else:
        raise CaseError("", f"{show_value(source)} is not a case: give a path to a YAML file or a "
                            "dict")
    try:
        case = _build_case(data, default_name)
    except RecursionError:
        # A self-referencing or absurdly nested dict; report it as bad input.
        raise CaseError("", "the case is nested too deeply") from None
    if not keep_source:
        return case
    source = copy.deepcopy(dict(data))
    source["name"] = case.name
    return dataclasses.replace(case, source=source)
