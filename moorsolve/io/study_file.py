"""Read and validate a design-study file (YAML) against its case; write an optimised case.

Validation is as strict as for case files: every problem raises
:class:`~moorsolve.errors.CaseError` naming the dotted field of the study
(``variables.chain.lower``, ``load_cases[1].set.environment.wind.speed``) and what is allowed.

Schema (SI units or strings with units)::

    name: str                                   optional, default the file stem
    objective: mass | cost                      default mass
    line_types:                                 optional, per line type of the case
      NAME: {mass_per_length [kg/m],            needed for mass unless a catalogue line
             cost_per_length [per m],           for cost; default: priced from the cost
             material: chain | chain_studlink   basis (moorsolve.catalog.costs, USD) by its
               | wire | polyester | nylon | hmpe}   material (a catalogue line's by default)
    anchor_cost: >= 0                           optional, per anchor (cost objective
                                                and max_cost)
    max_cost: > 0 [currency]                    optional: the whole design's cost (lines
                                                and anchors, priced as for the cost
                                                objective) at most this; a number or
                                                "600000 USD" in the study's currency
    currency: str                               optional label, default EUR (USD, and
                                                only USD, where the basis prices a line)
    variables:                                  required, at least one
      VAR: {type: length | anchor_distance | anchor_radius,
            legs: "*" | NAME | [NAME, ...],     the legs that share the value
            lower: > 0 [m], upper: > lower [m],
            start: [m]}                         default the legs' common case value
    limits:                                     optional, for every load case
      {safety_factor: > 1, max_anchor_uplift: >= 0 [N], min_grounded_length: >= 0 [m],
       offset_limit: > 0 [m]}
    load_cases:                                 required, at least one
      - name: str
        set: {PATH: VALUE, ...}                 edits of the case (moorsolve.model.paths)
        headings: [deg, ...] | {every_deg: > 0, from_deg: 0, to_deg: < from + 360}
                                                one load case per heading: every wind,
                                                current and waves toward_deg set to it,
                                                and the constant force [Fx, Fy] turned
                                                toward it (its size and Mz kept)
        limits: {...}                           overrides of the study's limits
    solver: {tol: (0, 1), max_iter: int >= 1}   IPOPT settings of the optimisation
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from os import PathLike
from pathlib import Path


from ..catalog import costs as cost_basis
from .. import catalog as line_catalog
from ..model.study import OBJECTIVES, VARIABLE_KINDS, DesignVariable, Limits, LoadCase, Study
from ..errors import CaseError
from ..model import Case
from ..model.fields import check_list, check_mapping, check_name, field_path, quantity
from .case_file import _read_yaml
from .output_files import write_case_yaml as write_case_file
from ..model.directions import direction_edit
from ..model.edit import variant as load_case_variant
from ..model.units import format_si, show_value

__all__ = ["load_study", "load_case_variant", "write_case_file"]

_LIMIT_KEYS = ("safety_factor", "max_anchor_uplift", "min_grounded_length", "offset_limit")
_FLOWS = ("wind", "current", "waves")


def load_study(source, case: Case) -> Study:
    """Load and validate a design study of ``case``.

    Parameters
    ----------
    source : str, pathlib.Path or mapping
        A YAML study file, or a dictionary of the same shape.
    case : Case
        The base case (from :func:`moorsolve.load_case`; load cases edit its data).

    Raises
    ------
    CaseError
        Naming the study field at fault.
    """
    if isinstance(source, (str, PathLike)):
        path = Path(source)
        try:
            data = _read_yaml(path)
        except CaseError as exc:
            raise CaseError(exc.field, exc.detail.replace("case file", "study file")) from None
        default_name = path.stem or "study"
    elif isinstance(source, Mapping):
        data, default_name = source, "study"
    else:
        raise CaseError("study", f"{show_value(source)} is not a study: give a path to a "
                                 "YAML file or a dict")
    m = check_mapping(data, "", required=("variables", "load_cases"),
                 optional=("name", "objective", "line_types", "anchor_cost", "currency",
                           "max_cost", "limits", "solver"))
    name = default_name if "name" not in m else check_name(m["name"], "name", "study name")
    objective = m.get("objective", "mass")
    if not isinstance(objective, str) or objective not in OBJECTIVES:
        raise CaseError("objective", f"{show_value(objective)} is not an objective; allowed: "
                                     f"{', '.join(OBJECTIVES)}")
    mass, cost, materials = _line_types(m.get("line_types") or {}, case)
    # The cost cap prices the design as the cost objective does, whatever the objective.
    priced = objective == "cost" or m.get("max_cost") is not None
    why = "the cost objective" if objective == "cost" else "max_cost"
    from_basis = False
    used = sorted({seg.line_type.name for leg in case.legs for seg in leg.segments})
    for lt_name in used:
        lt = case.line_types[lt_name]
        if objective == "mass" and lt_name not in mass:
            if lt.catalog is None or lt.diameter is None:
                raise CaseError(f"line_types.{lt_name}.mass_per_length",
                                f"required for the mass objective: line type {lt_name!r} is "
                                "not a catalogue line, so its mass in air is unknown")
            mass[lt_name] = line_catalog.entries()[lt.catalog].mass_per_length(lt.diameter)
        if priced and lt_name not in cost:
            try:
                cost[lt_name] = cost_basis.line_price(
                    lt, materials.get(lt_name), gravity=case.environment.gravity,
                    water_density=case.environment.water_density).cost_per_length
            except (KeyError, ValueError) as exc:
                raise CaseError(f"line_types.{lt_name}.cost_per_length",
                                f"required for {why} unless the cost basis "
                                f"prices it: {str(exc).strip(chr(39))}") from None
            from_basis = True
    anchor_cost = 0.0 if m.get("anchor_cost") is None else quantity(
        m["anchor_cost"], "anchor_cost", "dimensionless", ge=0)
    currency = m.get("currency", cost_basis.CURRENCY if from_basis else "EUR")
    if not isinstance(currency, str) or not currency.strip():
        raise CaseError("currency", f"{show_value(currency)} must be a non-empty label")
    if from_basis and currency != cost_basis.CURRENCY:
        raise CaseError("currency", f"{show_value(currency)}: a line priced from the cost "
                                    f"basis is in {cost_basis.CURRENCY}; give every "
                                    "cost_per_length in your currency or use "
                                    f"{cost_basis.CURRENCY}")
    max_cost = None if m.get("max_cost") is None else _money(m["max_cost"], "max_cost",
                                                             currency)
    variables = _variables(m["variables"], "variables", case)
    limits = _limits(m.get("limits") or {}, "limits", case, Limits())
    load_cases = _load_cases(m["load_cases"], "load_cases", case, limits)
    tol, max_iter = _solver(m.get("solver") or {}, "solver")
    return Study(name=name, objective=objective, variables=variables, load_cases=load_cases,
                 mass_per_length=mass, cost_per_length=cost, anchor_cost=anchor_cost,
                 currency=currency, max_cost=max_cost, tol=tol, max_iter=max_iter)


def _money(raw, path: str, currency: str) -> float:
    """A positive amount: a number, or a string "AMOUNT CURRENCY" in the study's currency."""
    allowed = (f"give a positive amount in the study's currency: a number or "
               f"\"600000 {currency}\"")
    amount = raw
    if isinstance(raw, str):
        parts = raw.replace(",", "").replace("_", "").split()
        if len(parts) != 2:
            raise CaseError(path, f"{show_value(raw)} is not an amount; {allowed}")
        if parts[1] != currency:
            raise CaseError(path, f"{show_value(raw)} is in {parts[1]}, not the study's "
                                  f"currency {currency}; {allowed}")
        try:
            amount = float(parts[0])
        except ValueError:
            raise CaseError(path, f"{show_value(raw)} is not an amount; {allowed}") from None
    if isinstance(amount, bool) or not isinstance(amount, numbers.Real) \
            or not math.isfinite(amount) or amount <= 0:
        raise CaseError(path, f"{show_value(raw)} must be positive and finite; {allowed}")
    return float(amount)


def _line_types(raw, case: Case):
    m = check_mapping(raw, "line_types", optional=tuple(case.line_types))
    mass, cost, materials = {}, {}, {}
    for lt_name, entry in m.items():
        path = field_path("line_types", lt_name)
        e = check_mapping(entry, path, optional=("mass_per_length", "cost_per_length",
                                                 "material"))
        if e.get("material") is not None:
            if e["material"] not in cost_basis.line_materials():
                raise CaseError(field_path(path, "material"),
                                f"{show_value(e['material'])} is not a material of the cost "
                                f"basis; allowed: {', '.join(cost_basis.line_materials())}")
            materials[lt_name] = e["material"]
        if e.get("mass_per_length") is not None:
            mass[lt_name] = quantity(e["mass_per_length"], field_path(path, "mass_per_length"),
                                      "mass_per_length", gt=0)
        if e.get("cost_per_length") is not None:
            cost[lt_name] = quantity(e["cost_per_length"], field_path(path, "cost_per_length"),
                                      "dimensionless", ge=0)
    return mass, cost, materials


def _leg_names(raw, path: str, case: Case) -> tuple:
    names = [leg.name for leg in case.legs]
    if raw == "*":
        return tuple(names)
    items = [raw] if isinstance(raw, str) else check_list(
        raw, path, '"*", a leg name or a list of leg names')
    if not items:
        raise CaseError(path, "the list is empty; give at least one leg")
    out = []
    for i, item in enumerate(items):
        if not isinstance(item, str) or item not in names:
            raise CaseError(field_path(path, i) if not isinstance(raw, str) else path,
                            f"no leg named {show_value(item)}; the legs are {names}")
        if item in out:
            raise CaseError(field_path(path, i), f"leg {item!r} is listed twice")
        out.append(item)
    return tuple(out)


def base_value(case: Case, leg, kind: str) -> float:
    """The case's value of a design variable of ``kind`` for ``leg`` [m]."""
    if kind == "length":
        return leg.length
    ax, ay = leg.anchor[0], leg.anchor[1]
    if kind == "anchor_distance":
        return math.hypot(ax - leg.fairlead[0], ay - leg.fairlead[1])
    return math.hypot(ax, ay)


def _variables(raw, path: str, case: Case) -> tuple:
    if not isinstance(raw, Mapping) or not raw:
        raise CaseError(path, f"{show_value(raw)} must be a mapping of variable names to "
                              "{type, legs, lower, upper}, with at least one variable")
    if case.environment.seabed.bathymetry is not None:
        # Each line's seabed plane follows its touchdown (solve/lines/bathymetry.py), which the
        # optimiser's one NLP over design and state does not iterate.
        raise CaseError(path, "design variables on a bathymetry grid are not modelled yet "
                              "(the lines' seabed planes move with the design); give the "
                              "seabed as a plane (environment.seabed.gradient) to optimise")
    legs_by_name = {leg.name: leg for leg in case.legs}
    taken: dict = {}
    out = []
    for var_name, entry in raw.items():
        vpath = field_path(path, var_name)
        if not isinstance(var_name, str) or not var_name.strip():
            raise CaseError(vpath, f"{show_value(var_name)} is not a variable name")
        e = check_mapping(entry, vpath, required=("type", "legs", "lower", "upper"),
                     optional=("start",))
        kind = e["type"]
        if not isinstance(kind, str) or kind not in VARIABLE_KINDS:
            raise CaseError(field_path(vpath, "type"),
                            f"{show_value(kind)} is not a variable type; "
                                                  f"allowed: {', '.join(VARIABLE_KINDS)}")
        legs = _leg_names(e["legs"], field_path(vpath, "legs"), case)
        for leg_name in legs:
            leg = legs_by_name[leg_name]
            group = "length" if kind == "length" else "anchor"
            if (leg_name, group) in taken:
                raise CaseError(field_path(vpath, "legs"),
                                f"leg {leg_name!r} is already moved by variable "
                                f"{taken[leg_name, group]!r}; a leg's {group} may belong to "
                                "one variable only")
            taken[leg_name, group] = var_name
            if kind == "length" and leg.multi_segment:
                raise CaseError(field_path(vpath, "legs"),
                                f"leg {leg_name!r} has {len(leg.segments)} segments; length "
                                "variables apply to one-segment legs")
            if kind != "length":
                if case.environment.seabed.sloped:
                    raise CaseError(field_path(vpath, "type"),
                                    "anchor variables need a flat seabed (on a slope the "
                                    "anchor's depth would change with its position)")
                if base_value(case, leg, kind) <= 0:
                    raise CaseError(field_path(vpath, "legs"),
                                    f"leg {leg_name!r} has its anchor under the "
                                    f"{'fairlead' if kind == 'anchor_distance' else 'origin'}"
                                    ": it has no heading to move along")
        lower = quantity(e["lower"], field_path(vpath, "lower"), "length", gt=0)
        upper = quantity(e["upper"], field_path(vpath, "upper"), "length", gt=lower)
        values = [base_value(case, legs_by_name[n], kind) for n in legs]
        if e.get("start") is not None:
            start = quantity(e["start"], field_path(vpath, "start"), "length", gt=0)
            spath = field_path(vpath, "start")
        else:
            # Case files round coordinates (the dock's anchors to 0.1 mm): values within
            # 1e-4 of each other share their mean.
            if max(values) - min(values) > 1e-4 * max(values):
                raise CaseError(field_path(vpath, "start"),
                                f"the legs {list(legs)} have different case values "
                                f"({', '.join(format_si(v, 'length') for v in values)}); "
                                "give the shared starting value")
            start = sum(values) / len(values)
            spath = field_path(vpath, "legs")
        if not lower <= start <= upper:
            raise CaseError(spath, f"the starting value {format_si(start, 'length')} is "
                                   f"outside the bounds [{format_si(lower, 'length')}, "
                                   f"{format_si(upper, 'length')}]")
        out.append(DesignVariable(name=var_name, kind=kind, legs=legs, lower=lower,
                                  upper=upper, start=start))
    return tuple(out)


def _limits(raw, path: str, case: Case, defaults: Limits) -> Limits:
    m = check_mapping(raw, path, optional=_LIMIT_KEYS)
    values = {}
    bounds = {"safety_factor": ("dimensionless", dict(gt=1)),
              "max_anchor_uplift": ("force", dict(ge=0)),
              "min_grounded_length": ("length", dict(ge=0)),
              "offset_limit": ("length", dict(gt=0))}
    for key in _LIMIT_KEYS:
        if key in m:
            kind, b = bounds[key]
            values[key] = None if m[key] is None else quantity(m[key], field_path(path, key),
                                                                kind, **b)
        else:
            values[key] = getattr(defaults, key)
    if values["safety_factor"] is not None:
        missing = [leg.name for leg in case.legs
                   if any(not seg.line_type.mbl for seg in leg.segments)]
        if missing:
            raise CaseError(field_path(path, "safety_factor"),
                            f"needs a breaking load (mbl) for every line; legs {missing} "
                            "have none")
    if values["offset_limit"] is not None and case.body is None:
        raise CaseError(field_path(path, "offset_limit"), "the case has no body to offset")
    return Limits(**values)


def _headings(raw, path: str) -> list:
    if isinstance(raw, Mapping):
        m = check_mapping(raw, path, required=("every_deg",), optional=("from_deg", "to_deg"))
        step = quantity(m["every_deg"], field_path(path, "every_deg"), "angle", gt=0, le=360)
        start = quantity(m.get("from_deg", 0.0), field_path(path, "from_deg"), "angle")
        if m.get("to_deg") is None:
            # A full turn: the heading one step short of coming back to the first.
            count = int(math.ceil(360.0 / step - 1e-9))
        else:
            end = quantity(m["to_deg"], field_path(path, "to_deg"), "angle", ge=start,
                            lt=start + 360.0)
            count = int(math.floor((end - start) / step + 1e-9)) + 1
        if count > 360:
            raise CaseError(field_path(path, "every_deg"), f"{count} headings: at most 360")
        return [start + k * step for k in range(count)]
    items = check_list(raw, path, "a list of headings [deg] or {every_deg, from_deg, to_deg}")
    if not items:
        raise CaseError(path, "the list is empty; give at least one heading")
    return [quantity(v, field_path(path, i), "angle") for i, v in enumerate(items)]


def _load_cases(raw, path: str, case: Case, limits: Limits) -> tuple:
    items = check_list(raw, path, "a list of load cases")
    if not items:
        raise CaseError(path, "the list is empty; give at least one load case")
    out, names = [], set()
    for i, entry in enumerate(items):
        lpath = field_path(path, i)
        e = check_mapping(entry, lpath, required=("name",), optional=("set", "headings", "limits"))
        name = check_name(e["name"], field_path(lpath, "name"), "load case name")
        edits = e.get("set") or {}
        spath = field_path(lpath, "set")
        if not isinstance(edits, Mapping):
            raise CaseError(spath, f"{show_value(edits)} must be a mapping of case paths to "
                                   "values")
        for key in edits:
            if not isinstance(key, str):
                raise CaseError(spath, f"key {show_value(key)} is not a case path")
        variant = load_case_variant(case, dict(edits), spath)
        lc_limits = _limits(e.get("limits") or {}, field_path(lpath, "limits"), variant, limits)
        if e.get("headings") is None:
            expanded = [(name, dict(edits))]
        else:
            hpath = field_path(lpath, "headings")
            flows = [f for f in _FLOWS if getattr(variant.environment, f) is not None]
            force = (variant.body.loads.force if variant.body is not None else None)
            if not flows and force is None:
                raise CaseError(hpath, "the load case has no wind, current, waves or constant "
                                       "force to turn")
            expanded = []
            for h in _headings(e["headings"], hpath):
                turned = dict(edits)
                # In the case file's own terms (from_deg, a compass bearing) if it uses them.
                turned.update(direction_edit(variant, f, h) for f in flows)
                if force is not None:
                    # The constant force keeps its size and turns toward the heading.
                    size = math.hypot(force[0], force[1])
                    a = math.radians(h)
                    turned["body.loads.force"] = [size * math.cos(a), size * math.sin(a),
                                                  force[2]]
                expanded.append((f"{name} {h:g} deg", turned))
        for lc_name, lc_edits in expanded:
            if lc_name in names:
                raise CaseError(field_path(lpath, "name"), f"load case {lc_name!r} appears twice")
            names.add(lc_name)
            out.append(LoadCase(name=lc_name, edits=lc_edits, limits=lc_limits))
    return tuple(out)


def _solver(raw, path: str):
    m = check_mapping(raw, path, optional=("tol", "max_iter"))
    tol = 1e-8 if m.get("tol") is None else quantity(m["tol"], field_path(path, "tol"),
                                                      "dimensionless", gt=0, lt=1)
    max_iter = m.get("max_iter", 500)
    if isinstance(max_iter, bool) or not isinstance(max_iter, numbers.Integral) \
            or not 1 <= max_iter <= 100_000:
        raise CaseError(field_path(path, "max_iter"), f"{show_value(max_iter)} must be an integer "
                                                 "from 1 to 100000")
    return tol, int(max_iter)
