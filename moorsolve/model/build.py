"""Validate plain case data (a case-file dictionary) into a :class:`~moorsolve.model.Case`.

Validation is strict: every problem raises :class:`~moorsolve.errors.CaseError` whose
``field`` is the dotted path of the offending value (``legs[3].segments[0].length``) and
whose message names the value and what is allowed (``-5 m must be > 0``). Unknown keys are
errors; there are no aliases. Quantities may be given with units (see
:mod:`moorsolve.model.units`) and are converted to SI here, once.

A key whose absence means "none" (``ea``, ``body``, ``environment.wind``, a load model, ...)
may also be given as null with the same meaning. A key with a default value may not be null.

An outline of the schema follows (SI units, ``[...]`` lists); every key with its unit,
default and range is declared in :mod:`moorsolve.model.schema`, which the checks here read::

    name: str                                  optional, default the file stem or "case"
    environment:                               required
      depth: length > 0                        required
      water_density: > 0 [kg/m^3]              default 1025
      air_density: > 0 [kg/m^3]                default 1.225
      gravity: > 0 [m/s^2]                     default 9.80665
      seabed: {friction: >= 0,                 default 0
               gradient: [dz/dx, dz/dy],       default flat; seabed z = -depth + gx x + gy y
               bathymetry: file or {x, y, depth}  a grid instead of the gradient
               tolerance: > 0 m}               default 0.1 m; with a bathymetry grid
      directions: mathematical | nautical      default mathematical (ccw from +x); nautical:
      north_deg: [deg]                         clockwise from north, north at north_deg
                                               (ccw from +x, default 90); see directions.py
      wind: {speed: >= 0 [m/s], toward_deg     optional; toward_deg or from_deg (one);
             | from_deg}                       current likewise, plus an optional
                                               profile: [[z <= 0, speed], ...] z ascending
                                               (speed signed along toward_deg), or
                                               [[z, speed >= 0, toward_deg], ...]
      waves: {hs: >= 0 [m], toward_deg | from_deg,   optional; tp, spectrum, duration
              tp, spectrum, duration}          make it a sea state (:mod:`.build_sea`)
      water_level: [m]                         still water above the datum (tide); default 0
    line_types:                                required, at least one
      NAME: {weight_in_water [N/m or mass/m], ea > 0 [N], mbl > 0 [N], diameter > 0 [m],
             weight_in_air >= weight_in_water [N/m or mass/m] (for a line end above
             the water; a catalogue line has it from its mass),
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
      fixed_to: water | seabed                 default water: it floats, its fairleads rise
                                               with water_level; seabed: on the datum
      loads: {force: [Fx, Fy, Mz], wind: {model: drag | hu_tang, ...},
              current: {model: drag | hu_tang, ...},
              wave_drift: {model: hu_tang | coefficient, ...}}
    bodies, points, lines, walls, piles, fenders, guides:
                                               the network form instead of body + legs
                                               (:mod:`.build_network`, :mod:`.build_contact`)
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
             min_grounded_length_damaged [m], anchor: ANCHOR, damaged: bool,
             design_life, corrosion, creep (moorsolve.model.build_wear),
             anchors: {drag | suction | pile | deadweight: DESIGN}
                                               (DESIGN: moorsolve.model.build_anchors),
             fatigue: {...} (moorsolve.model.build_fatigue),
             method: quasi_static | dynamic}   optional
    analysis: {lines: dynamic | quasi_static}  optional; line dynamics in a sea state
    moordyn: {...}                             optional; MoorDyn columns moorsolve does not use,
                                               kept for export (moorsolve.model.moordyn_block);
                                               the solver ignores it
    ANCHOR: {type: drag} | {type: deadweight, allowed_uplift [N]}
            | {type: pile, allowed_uplift_angle_deg} | {type: suction}
"""

from __future__ import annotations

import json
import math
import numbers
from collections.abc import Mapping

from ..errors import CaseError
from .directions import CONVENTIONS, Compass, flow_direction
from .environment import Environment, Flow, Seabed, Waves
from .scene import METHODS, STANDARDS, Analysis, Case, Checks, SolverOptions, moves_in_sea
from .shared import LEGS, shared_parts
from .build_legs import _body, _legs
from .build_lines import _anchor_type, _line_types
from .build_anchors import build_anchors
from .build_network import build_network, check_held, end_position
from .build_sea import sea_state_fields
from .build_wear import wear_fields
from .build_contact import build_contacts
from .contact import Contacts
from .fields import (GRAVITY_RANGE, MAX_DENSITY, MAX_DEPTH, MAX_GRADIENT, MAX_HS,
                     MAX_ITER_LIMIT, MAX_LINE_ELEMENTS,
                     MAX_SPEED, MIN_DEPTH, check_bounds, check_list,
                     check_mapping, check_name, check_rows, field_path,
                     nullable_quantity, quantity, schema_quantity)
from .schema import default as schema_default
from .bathymetry import bathymetry_from_mapping, check_scene as check_bathymetry
from .moordyn_block import validate_moordyn_block
from .units import format_si, recording_active, show_value

__all__ = ["build_case"]


# ---- environment ------------------------------------------------------------------------


def _angle(raw, path: str) -> float:
    return quantity(raw, path, "angle")


def _flow(raw, path: str, compass: Compass, profile: bool = False) -> Flow:
    m = check_mapping(raw, path, section="current" if profile else "wind")
    speed = quantity(m["speed"], field_path(path, "speed"), "speed", ge=0, le=MAX_SPEED)
    toward = flow_direction(m, path, compass, _angle)
    rows = None
    if m.get("profile") is not None:
        rows = _current_profile(m["profile"], field_path(path, "profile"), compass)
    return Flow(speed=speed, toward_deg=toward, profile=rows)


def _current_profile(raw, ppath: str, compass: Compass) -> tuple:
    """Rows ``[z, speed]`` (a signed speed along the current's ``toward_deg``: negative
    flows the other way) or ``[z, speed, toward_deg]`` (a speed >= 0 and its own heading),
    all of one form, z ascending from the seabed to the surface."""
    first = check_list(raw, ppath, "a list of rows [z, speed] or [z, speed, toward_deg]")
    width = 3 if first and isinstance(first[0], (list, tuple)) and len(first[0]) == 3 else 2
    shape = "[z, speed, toward_deg]" if width == 3 else "[z, speed]"
    rows = []
    for rpath, row in check_rows(raw, ppath, shape, width=width, min_rows=1,
                                 empty="a current profile (z <= 0, ascending)"):
        z = quantity(row[0], field_path(rpath, 0), "length", le=0)
        if width == 3:
            v = quantity(row[1], field_path(rpath, 1), "speed", ge=0, le=MAX_SPEED)
            # A row's heading is the direction it travels toward, in the case's convention.
            heading = compass.toward_deg(quantity(row[2], field_path(rpath, 2), "angle"),
                                         "toward_deg")
        else:
            v = quantity(row[1], field_path(rpath, 1), "speed", ge=-MAX_SPEED, le=MAX_SPEED)
        if rows and not z > rows[-1][0]:
            raise CaseError(field_path(rpath, 0), f"z = {format_si(z, 'length')} must be above "
                                                  "the previous row's (z ascending, from the "
                                                  "seabed up to the surface)")
        rows.append((z, v, heading) if width == 3 else (z, v))
    return tuple(rows)


def _waves(raw, path: str, compass: Compass) -> Waves:
    m = check_mapping(raw, path, section="waves")
    hs = quantity(m["hs"], field_path(path, "hs"), "length", ge=0, le=MAX_HS)
    toward = flow_direction(m, path, compass, _angle)
    return Waves(hs=hs, toward_deg=toward, **sea_state_fields(m, path, hs))


def _environment(raw, path: str) -> Environment:
    m = check_mapping(raw, path, section="environment")
    dpath = field_path(path, "depth")
    depth = quantity(m["depth"], dpath, "length", gt=0, le=MAX_DEPTH)
    check_bounds(m["depth"], depth, "length", dpath, ge=MIN_DEPTH)
    water_density = schema_quantity(m, path, "environment", "water_density", gt=0,
                                    le=MAX_DENSITY)
    air_density = schema_quantity(m, path, "environment", "air_density", gt=0, le=MAX_DENSITY)
    gravity = schema_quantity(m, path, "environment", "gravity", gt=0, le=GRAVITY_RANGE[1])
    check_bounds(m.get("gravity"), gravity, "acceleration", field_path(path, "gravity"),
                  ge=GRAVITY_RANGE[0])
    seabed = Seabed()
    if "seabed" in m:
        sub = field_path(path, "seabed")
        s = check_mapping(m["seabed"], sub, section="seabed")
        gradient = (0.0, 0.0)
        if "gradient" in s and "bathymetry" in s:
            raise CaseError(field_path(sub, "bathymetry"), "give either a bathymetry grid or "
                            "a plane gradient, not both (a grid can hold a plane)")
        if "tolerance" in s and "bathymetry" not in s:
            raise CaseError(field_path(sub, "tolerance"), "applies to a bathymetry grid only "
                            "(how far below the grid's surface a line may pass)")
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
        grid = None
        if "bathymetry" in s:
            bpath = field_path(sub, "bathymetry")
            raw = s["bathymetry"]
            if isinstance(raw, str):
                raise CaseError(bpath, f"file {raw!r} was not read: a bathymetry file is read "
                                       "by load_case (relative to the case file)")
            grid = bathymetry_from_mapping(raw, bpath)
        seabed = Seabed(friction=schema_quantity(s, sub, "seabed", "friction", ge=0),
                        gradient=gradient, bathymetry=grid,
                        tolerance=schema_quantity(s, sub, "seabed", "tolerance", gt=0,
                                                  le=MAX_DEPTH))
    compass = _compass(m, path)
    wind = None if m.get("wind") is None else _flow(m["wind"], field_path(path, "wind"), compass)
    current = (None if m.get("current") is None
               else _flow(m["current"], field_path(path, "current"), compass, profile=True))
    waves = (None if m.get("waves") is None
             else _waves(m["waves"], field_path(path, "waves"), compass))
    level = schema_quantity(m, path, "environment", "water_level", ge=-MAX_TIDE, le=MAX_TIDE)
    if level <= -depth:
        raise CaseError(field_path(path, "water_level"),
                        f"{format_si(level, 'length')} would leave no water over the seabed "
                        f"(depth {format_si(depth, 'length')} at the datum)")
    return Environment(depth=depth, water_density=water_density, air_density=air_density,
                       gravity=gravity, seabed=seabed, wind=wind, current=current, waves=waves,
                       compass=compass, water_level=level)


def _compass(m: dict, path: str) -> Compass:
    """``directions`` (mathematical or nautical) and ``north_deg`` (nautical only)."""
    convention = m.get("directions", schema_default("environment", "directions"))
    if not isinstance(convention, str) or convention not in CONVENTIONS:
        raise CaseError(field_path(path, "directions"),
                        f"{show_value(convention)} must be one of {', '.join(CONVENTIONS)} "
                        "(mathematical: counter-clockwise from +x; nautical: clockwise from "
                        "north)")
    if "north_deg" in m and convention != "nautical":
        raise CaseError(field_path(path, "north_deg"), "applies to compass bearings only; "
                                                       "give directions: nautical with it")
    north = schema_quantity(m, path, "environment", "north_deg")
    return Compass(convention=convention, north_deg=north)


def _checks(raw, path: str, legs: tuple, line_types: dict | None = None) -> Checks:
    m = check_mapping(raw, path, section="checks")
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
        if value is None:
            continue
        if not legs:
            raise CaseError(field_path(path, key), "the scene has no mooring legs to ground; "
                                                  "leave the limit out")
        longest = max(leg.length for leg in legs)
        if value >= longest:
            raise CaseError(field_path(path, key), f"{format_si(value, 'length')} must be shorter "
                                              f"than the longest leg "
                                              f"({format_si(longest, 'length')})")
    anchor = (defaults.anchor if m.get("anchor") is None
              else _anchor_type(m["anchor"], field_path(path, "anchor")))
    damaged = m.get("damaged", schema_default("checks", "damaged"))
    if not isinstance(damaged, bool):
        raise CaseError(field_path(path, "damaged"), f"{show_value(damaged)} is not true or false")
    anchors = (() if m.get("anchors") is None
               else build_anchors(m["anchors"], field_path(path, "anchors")))
    fatigue = None
    if m.get("fatigue") is not None:
        from .build_fatigue import fatigue_spec
        types = {seg.line_type.name for leg in legs for seg in leg.segments}
        fatigue = fatigue_spec(m["fatigue"], field_path(path, "fatigue"), sorted(types),
                               checks_life=m.get("design_life"),
                               checks_life_path=field_path(path, "design_life"))
    method = m.get("method")
    if method is not None and (not isinstance(method, str) or method not in METHODS):
        raise CaseError(field_path(path, "method"), f"{show_value(method)} must be one of "
                        f"{', '.join(METHODS)} (how the dynamic part of the line tension is "
                        "had in a sea state)")
    return Checks(anchors=anchors, standard=standard, consequence_class=int(cclass),
                  offset_limit=offset, offset_limit_damaged=offset_damaged,
                  min_grounded_length=grounded, min_grounded_length_damaged=grounded_damaged,
                  anchor=anchor, damaged=damaged,
                  wear=wear_fields(m, path, line_types or {}, legs), fatigue=fatigue,
                  method=method)


def _analysis(raw, path: str) -> Analysis:
    m = check_mapping(raw, path, section="analysis")
    lines = m.get("lines")
    if lines is not None and (not isinstance(lines, str) or lines not in METHODS):
        raise CaseError(field_path(path, "lines"), f"{show_value(lines)} must be one of "
                        f"{', '.join(METHODS)}")
    return Analysis(lines=lines)


def check_analysis(case: Case) -> None:
    """Refuse line dynamics, or a dynamic check, in a scene with nothing that moves in a
    sea state, naming the field."""
    sea = moves_in_sea(case)
    waves = case.environment.waves
    why = ("the scene has no sea state (environment.waves with tp)"
           if waves is None or not waves.sea_state else
           "no body has hydrodynamics (bodies[i].hydrodynamics) to move in the sea state")
    if case.analysis.lines == "dynamic" and not sea:
        raise CaseError("analysis.lines", f"dynamic: {why}; line dynamics are driven by the "
                        "bodies' motions in it (use quasi_static, or give the sea state and "
                        "the hydrodynamics)")
    method = None if case.checks is None else case.checks.method
    if method == "dynamic" and not sea:
        raise CaseError("checks.method", f"dynamic: {why}; drop the method (the check then "
                        "covers the mean tension) or give the sea state and the "
                        "hydrodynamics")
    if method == "dynamic" and case.analysis.lines == "quasi_static":
        raise CaseError("checks.method", "dynamic needs the lines' dynamics, but "
                        "analysis.lines is quasi_static: use one of them")


# ---- solver -----------------------------------------------------------------------------


def _solver(raw, path: str) -> SolverOptions:
    m = check_mapping(raw, path, section="solver")
    defaults = SolverOptions()
    tol = schema_quantity(m, path, "solver", "tol", gt=0, lt=1)
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
    max_time = schema_quantity(m, path, "solver", "max_time_s", gt=0)
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


_LEGS_FORM = ("body", "legs")
_NETWORK_FORM = ("bodies", "points", "lines")
#: Berth sections (network form only; :mod:`.build_contact`).
_BERTH = ("walls", "piles", "fenders", "guides")
#: Largest tide accepted [m]; a larger water level is a unit mistake.
MAX_TIDE = 100.0


def check_tide_on_lines(environment, lines, bodies: tuple) -> None:
    """Refuse a tide (``water_level`` other than 0) where a line meets the free surface.

    The lines' own free surface (a buoyant segment or float held up by it, the part of a
    line in air weighed by ``weight_in_air`` above an end over z = 0 in the case file) is
    modelled at the datum z = 0; floating bodies and the hydrostatics follow the tide, these
    lines would not. Refused rather than answered at the wrong surface, with the equivalent
    scene to give instead. A line whose ends are at or under z = 0 in the case file (a
    floating body's fairleads at its waterline) takes its weight in water and follows the
    tide with the body: its ``weight_in_air`` is not used.
    """
    if environment.water_level == 0.0:
        return
    by_name = {b.name: b for b in bodies}
    for line in lines:
        types = [seg.line_type for seg in line.segments]
        floats = [c for c in line.joint_clumps if c is not None and c.weight < 0]
        in_air = any(end_position(end, by_name)[2] > 1e-9 for end in (line.a, line.b))
        meets = ("a buoyant segment" if any(lt.weight_in_water < 0 for lt in types)
                 else "a float" if floats
                 else "an end in air weighed by weight_in_air"
                 if in_air and any(lt.weight_in_air is not None for lt in types)
                 else None)
        if meets:
            raise CaseError(
                "environment.water_level",
                f"{environment.water_level:g} m with line {line.name!r}, which has {meets}: "
                "a line's own free surface is modelled at the datum only; give the same "
                "scene on a datum at the still water (depth increased by the water level, "
                "fixed points and anchors lowered by it, water_level 0)")


def validated_legs(m, environment, body: bool) -> tuple:
    """``(line_types, legs)`` of the legs form, validated once per distinct case-file data
    of both sections (with the environment and whether a body holds the fairleads): a loop
    that loads one mooring under many loads (``load_case(d)``, ``case.with_values``)
    validates its legs once. Not while a sweep records what its values convert to."""
    def build():
        types = _line_types(m["line_types"], "line_types", environment.gravity,
                            environment.water_density)
        return types, _legs(m["legs"], "legs", environment, types, body)

    if recording_active():
        return build()
    try:
        key = (json.dumps([m["line_types"], m["legs"]], sort_keys=True), environment, body)
        hash(key)
    except (TypeError, ValueError):      # not plain data (numpy values): validate anew
        return build()
    hit = LEGS.get(key)
    if hit is None:
        hit = build()
        LEGS.put(key, hit)
    return hit


def build_case(data, default_name: str = "case") -> Case:
    """The validated :class:`Case` of plain case-file data (see the module notes).

    Two forms: ``body`` + ``legs`` (one body on anchor-to-fairlead legs) or the network form
    ``bodies``, ``points``, ``lines`` (:mod:`.build_network`); a case uses one of them.

    Raises :class:`CaseError` naming the field for any problem.
    """
    if isinstance(data, Mapping) and not any(k in data for k in _LEGS_FORM + _NETWORK_FORM):
        raise CaseError("legs", "required key 'legs' is missing from the case; a case holds "
                                "legs (with an optional body) or lines between points and "
                                "bodies (bodies, points, lines)")
    network = isinstance(data, Mapping) and any(k in data for k in _NETWORK_FORM)
    if network:
        for key in _LEGS_FORM:
            if key in data:
                raise CaseError(key, f"{key!r} belongs to the body + legs form; this case uses "
                                     "the network form (bodies, points, lines): give one form")
        m = check_mapping(data, "", section="network")
        if m.get("lines") and "line_types" not in m:
            raise CaseError("line_types", "required key 'line_types' is missing: the lines "
                                          "name their types there")
    else:
        if isinstance(data, Mapping):
            for key in _BERTH:
                if key in data:
                    raise CaseError(key, f"{key!r} belongs to the network form (bodies, "
                                         "points, lines): fenders name the body they are on")
        m = check_mapping(data, "", section="case")
    name = default_name if "name" not in m else check_name(m["name"], "name", "case name")
    # Environment first: gravity converts weights given as mass per length, and depth
    # places anchors given as [x, y].
    environment = _environment(m["environment"], "environment")
    contacts = Contacts()
    if network:
        # A network scene held by contacts alone may have no lines and no line types.
        line_types = ({} if m.get("line_types") is None and not m.get("lines")
                      else _line_types(m["line_types"], "line_types", environment.gravity,
                                       environment.water_density))
        bodies, points, lines = build_network(m, environment, line_types)
        contacts = build_contacts(m, bodies)
        check_held(bodies, lines, contacts)
    else:
        body = None if m.get("body") is None else _body(m["body"], "body")
        line_types, lines = validated_legs(m, environment, body is not None)
        bodies, points = (() if body is None else (body,)), ()
    check_bathymetry(environment, lines, points, contacts, network)
    check_tide_on_lines(environment, lines, bodies)
    solver = SolverOptions() if "solver" not in m else _solver(m["solver"], "solver")
    checks = (None if m.get("checks") is None
              else _checks(m["checks"], "checks", lines, line_types))
    moordyn = (None if m.get("moordyn") is None
               else validate_moordyn_block(m["moordyn"], "moordyn", line_types, lines))
    analysis = Analysis() if m.get("analysis") is None else _analysis(m["analysis"],
                                                                        "analysis")
    # Equal parts of earlier cases are shared, so what was derived from them is found again.
    case = shared_parts(Case(name=name, environment=environment, line_types=line_types,
                             lines=lines, bodies=bodies, points=points, solver=solver,
                             checks=checks, moordyn=moordyn,
                             form="network" if network else "legs", contacts=contacts,
                             analysis=analysis))
    check_analysis(case)
    return case
