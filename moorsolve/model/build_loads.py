"""Body load models of a case file: drag, Hu & Tang, wave drift, constant force."""

from __future__ import annotations

from collections.abc import Mapping

from ..errors import CaseError
from .fields import (MAX_AREA, MAX_FORCE, MAX_MOMENT, check_centre, check_list,
                     check_mapping, check_rows, field_path,
                     nullable_quantity, optional_quantity, quantity)
from .units import format_si, show_value
from .loads import (BodyLoads, DragLoad, DriftCoefficient, HuTangCurrent, HuTangDrift,
                    HuTangWind)


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
    m = check_mapping(m, path, section="drag_load")
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
    m = check_mapping(m, path, section="hu_tang_wind")
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
    m = check_mapping(m, path, section="hu_tang_current")
    area = quantity(m["wetted_area"], field_path(path, "wetted_area"), "area", gt=0, le=MAX_AREA)
    coefficient = optional_quantity(m, path, "coefficient", "dimensionless", 0.18, gt=0)
    return HuTangCurrent(wetted_area=area, coefficient=coefficient, centre=check_centre(m, path))


def _hu_tang_drift(m: dict, path: str) -> HuTangDrift:
    m = check_mapping(m, path, section="hu_tang_drift")
    beam = quantity(m["beam"], field_path(path, "beam"), "length", gt=0)
    length = nullable_quantity(m, path, "length", "length", gt=0)
    k = optional_quantity(m, path, "k", "dimensionless", 0.7, gt=0)
    return HuTangDrift(beam=beam, length=length, k=k, centre=check_centre(m, path))


def _drift_coefficient(m: dict, path: str) -> DriftCoefficient:
    m = check_mapping(m, path, section="drift_coefficient")
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


_FORCE_SHAPES = {3: "[Fx N, Fy N, Mz N m]", 6: "[Fx N, Fy N, Fz N, Mx N m, My N m, Mz N m]"}


def _force(raw, path: str, sizes: tuple = (3,)) -> tuple:
    """A constant load, global frame: 3 long ``[Fx, Fy, Mz]`` or (``sizes`` allowing) 6 long."""
    shape = " or ".join(_FORCE_SHAPES[n] for n in sizes)
    items = check_list(raw, path, shape)
    if len(items) not in sizes:
        raise CaseError(path, f"{show_value(raw)} has {len(items)} values; it must be {shape}")
    kinds = ("force", "force", "moment") if len(items) == 3 else ("force",) * 3 + ("moment",) * 3
    limits = {"force": MAX_FORCE, "moment": MAX_MOMENT}
    return tuple(quantity(v, field_path(path, i), k, ge=-limits[k], le=limits[k])
                 for i, (v, k) in enumerate(zip(items, kinds)))


def _loads(raw, path: str, force_sizes: tuple = (3,)) -> BodyLoads:
    m = check_mapping(raw, path, section="loads")
    force = (None if m.get("force") is None
             else _force(m["force"], field_path(path, "force"), force_sizes))
    models = {key: (None if m.get(key) is None
                    else _load_model(m[key], field_path(path, key), _LOAD_MODELS[key]))
              for key in _LOAD_MODELS}
    return BodyLoads(force=force, **models)


