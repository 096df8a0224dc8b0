"""Checked case-file input of the sea state and of a body's hydrodynamics and damping.

Schema (SI units)::

    environment.waves:
      hs, toward_deg | from_deg               as for the drift load models
      tp: > 0 [s]                             spectral peak period; makes the waves a sea state
      spectrum: {model: jonswap, gamma: 1..20 (default DNV-RP-C205's rule from Tp/sqrt(Hs))}
              | {model: pierson_moskowitz} | {table: [[omega rad/s, S m^2 s/rad], ...]}
      duration: > 0 [s]                       storm duration, default 3 h
    bodies[i].hydrodynamics:
      {source: table, omega: [...], added_mass: [6x6 per omega], damping: [6x6 per omega],
       excitation: [{heading_deg, re: [6 per omega], im: [6 per omega]}, ...],
       mean_drift: [{heading_deg, values: [6 per omega]}, ...]}          (optional)
      | {source: wamit, files: [NAME.1, NAME.3, NAME.8 | NAME.9 | NAME.12d], ulen: > 0 [m]}
                                              files read by load_case (moorsolve.io.wamit)
      | {source: capytaine, omega: [...], headings_deg: [...], panel_size: > 0 [m],
         cache: FOLDER}                       BEM from the body's hull members (optional extra)
    bodies[i].damping: {linear: [6 values], critical_fraction: {DOF: 0..2, ...}}
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..errors import CaseError
from .bodies import DOFS
from .fields import check_list, check_mapping, field_path, quantity
from .sea import (DEFAULT_DURATION, SPECTRUM_MODELS, CapytaineHull, DriftTable,
                  ExcitationTable, ExtraDamping, Hydrodynamics, Spectrum)
from .units import show_value

#: Largest peak enhancement factor accepted (DNV-RP-C205 gives 1 to 7 for real seas).
MAX_GAMMA = 20.0
#: Relative mismatch allowed between a tabulated spectrum's 4 sqrt(m0) and ``hs``.
TABLE_HS_TOLERANCE = 0.05
#: Frequency range a table may use [rad/s]: below it is a tide, above it a ripple.
OMEGA_RANGE = (1e-4, 100.0)


def sea_state_fields(m: dict, path: str, hs: float) -> dict:
    """``tp``, ``spectrum`` and ``duration`` of ``environment.waves`` (mapping ``m``), as
    keyword arguments of :class:`~moorsolve.model.environment.Waves`."""
    tp = None
    if m.get("tp") is not None:
        tp = quantity(m["tp"], field_path(path, "tp"), "time", gt=0, le=100.0)
    spectrum = None
    if m.get("spectrum") is not None:
        spectrum = _spectrum(m["spectrum"], field_path(path, "spectrum"), hs, tp)
    elif tp is not None:
        spectrum = Spectrum()
    duration = DEFAULT_DURATION
    if m.get("duration") is not None:
        duration = quantity(m["duration"], field_path(path, "duration"), "time", gt=0,
                            le=30 * 86400.0)
    if tp is not None and spectrum is not None and spectrum.table is None \
            and duration <= 2 * tp:
        raise CaseError(field_path(path, "duration"),
                        f"{duration:.6g} s is not a storm: it must be longer than two peak "
                        f"periods ({2 * tp:.6g} s) for most probable maxima")
    return {"tp": tp, "spectrum": spectrum, "duration": duration}


def _spectrum(raw, path: str, hs: float, tp) -> Spectrum:
    if isinstance(raw, Mapping) and "table" in raw:
        m = check_mapping(raw, path, section="spectrum_table")
        rows = _array(m["table"], field_path(path, "table"), (None, 2),
                      "a list of rows [omega rad/s, S m^2 s/rad]")
        tpath = field_path(path, "table")
        if len(rows) < 3:
            raise CaseError(tpath, f"{len(rows)} row(s); a spectrum table needs at least 3 rows "
                                   "[omega, S]")
        _increasing([r[0] for r in rows], tpath, "omega (column 0)")
        if rows[0][0] < 0 or any(r[1] < 0 for r in rows):
            raise CaseError(tpath, "omega and S must be >= 0")
        m0 = sum(0.5 * (a[1] + b[1]) * (b[0] - a[0]) for a, b in zip(rows, rows[1:]))
        hs_table = 4.0 * math.sqrt(m0)
        if abs(hs_table - hs) > TABLE_HS_TOLERANCE * max(hs, 1e-12):
            raise CaseError(tpath, f"the table's significant height 4 sqrt(m0) = "
                                   f"{hs_table:.4g} m differs from hs = {hs:.4g} m by more than "
                                   f"{TABLE_HS_TOLERANCE:.0%}; give the hs of the table")
        return Spectrum(model="table", table=tuple(tuple(r) for r in rows))
    m = check_mapping(raw, path, section="spectrum")
    model = m["model"]
    if not isinstance(model, str) or model not in SPECTRUM_MODELS:
        raise CaseError(field_path(path, "model"),
                        f"{show_value(model)} must be one of {', '.join(SPECTRUM_MODELS)} "
                        "(or give {table: [[omega, S], ...]} instead of a model)")
    if tp is None:
        raise CaseError(path.rsplit(".", 1)[0] + ".tp",
                        f"a {model} spectrum needs the peak period tp [s]")
    gamma = None
    if m.get("gamma") is not None:
        if model != "jonswap":
            raise CaseError(field_path(path, "gamma"),
                            "only a jonswap spectrum has a peak enhancement factor gamma")
        gamma = quantity(m["gamma"], field_path(path, "gamma"), "dimensionless", ge=1.0,
                         le=MAX_GAMMA)
    return Spectrum(model=model, gamma=gamma)


# ---- hydrodynamics --------------------------------------------------------------------


def _array(raw, path: str, shape: tuple, what: str):
    """A nested list of real finite numbers of ``shape`` (None: any length) as nested tuples."""
    import numpy as np

    try:
        arr = np.asarray(raw, dtype=float)
    except (TypeError, ValueError):
        raise CaseError(path, f"must be {what} (numbers only, SI)") from None
    if arr.ndim != len(shape) or any(s is not None and s != n for s, n in zip(shape, arr.shape)):
        raise CaseError(path, f"has shape {list(arr.shape)}; it must be {what}")
    if not np.all(np.isfinite(arr)):
        raise CaseError(path, "holds a value that is not finite; give real numbers")
    return arr.tolist()


def _increasing(values, path: str, what: str) -> None:
    for i in range(1, len(values)):
        if not values[i] > values[i - 1]:
            raise CaseError(path, f"{what}: {values[i]:.6g} after {values[i - 1]:.6g}; values "
                                  "must be strictly increasing")


def _heading_tables(raw, path: str, n: int, keys: tuple, make, section: str) -> tuple:
    items = check_list(raw, path, "a list of {heading_deg, ...} per heading")
    if not items:
        raise CaseError(path, "is empty; give at least one heading")
    out = []
    for i, item in enumerate(items):
        ipath = field_path(path, i)
        m = check_mapping(item, ipath, section=section)
        heading = quantity(m["heading_deg"], field_path(ipath, "heading_deg"), "angle",
                           ge=-180.0, lt=360.0)
        if out and not heading > out[-1].heading_deg:
            raise CaseError(field_path(ipath, "heading_deg"),
                            f"{heading:.6g} deg must be greater than the previous heading's "
                            f"{out[-1].heading_deg:.6g} deg (headings strictly increasing)")
        values = [tuple(map(tuple, _array(m[k], field_path(ipath, k), (n, 6),
                                          f"{n} rows (one per omega) of 6 values")))
                  for k in keys]
        out.append(make(heading, *values))
    if out[-1].heading_deg - out[0].heading_deg >= 360.0:
        raise CaseError(path, "headings span 360 deg or more; give one turn at most")
    return tuple(out)


def hydrodynamics(raw, path: str, rho: float, g: float) -> Hydrodynamics:
    """``bodies[i].hydrodynamics`` as a :class:`Hydrodynamics` (SI, body frame)."""
    if isinstance(raw, Mapping) and raw.get("source") == "wamit":
        return _wamit(raw, path, rho, g)
    if isinstance(raw, Mapping) and raw.get("source") == "capytaine":
        return _capytaine(raw, path)
    m = check_mapping(raw, path, section="hydro_table")
    if m["source"] != "table":
        raise CaseError(field_path(path, "source"),
                        f"{show_value(m['source'])} must be table, wamit or capytaine")
    return _table(m, path, "table")


def _frequencies(raw, opath: str):
    """A list of at least two increasing frequencies [rad/s] within :data:`OMEGA_RANGE`."""
    omega = _array(raw, opath, (None,), "a list of frequencies [rad/s]")
    if len(omega) < 2:
        raise CaseError(opath, f"{len(omega)} value(s); give at least 2 frequencies")
    _increasing(omega, opath, "omega")
    if omega[0] < OMEGA_RANGE[0] or omega[-1] > OMEGA_RANGE[1]:
        raise CaseError(opath, f"frequencies must lie in [{OMEGA_RANGE[0]:g}, "
                               f"{OMEGA_RANGE[1]:g}] rad/s (is a period given as omega?)")
    return omega


def _table(m: dict, path: str, source: str) -> Hydrodynamics:
    omega = _frequencies(m["omega"], field_path(path, "omega"))
    n = len(omega)
    matrices = {}
    for key in ("added_mass", "damping"):
        arr = _array(m[key], field_path(path, key), (n, 6, 6),
                     f"{n} 6x6 matrices (one per omega)")
        matrices[key] = tuple(tuple(map(tuple, a)) for a in arr)
    excitation = _heading_tables(m["excitation"], field_path(path, "excitation"), n,
                                 ("re", "im"), ExcitationTable, "excitation")
    drift = ()
    if m.get("mean_drift") is not None:
        drift = _heading_tables(m["mean_drift"], field_path(path, "mean_drift"), n,
                                ("values",), DriftTable, "mean_drift")
    return Hydrodynamics(omega=tuple(omega), added_mass=matrices["added_mass"],
                         damping=matrices["damping"], excitation=excitation,
                         mean_drift=drift, source=source)


def _wamit(raw, path: str, rho: float, g: float) -> Hydrodynamics:
    m = check_mapping(raw, path, section="hydro_wamit")
    ulen = 1.0 if m.get("ulen") is None else quantity(m["ulen"], field_path(path, "ulen"),
                                                       "length", gt=0)
    if not isinstance(m.get("values"), Mapping):
        raise CaseError(field_path(path, "files"),
                        "WAMIT files are read by moorsolve.load_case (relative to the case "
                        "file); a case given as a dict must be loaded from a file")
    from .wamit_scale import dimensional
    data = dimensional(m["values"], ulen, rho, g)
    return _table(data, field_path(path, "files"), "wamit")


def _capytaine(raw, path: str) -> CapytaineHull:
    m = check_mapping(raw, path, section="hydro_capytaine")
    omega = _frequencies(m["omega"], field_path(path, "omega"))
    hpath = field_path(path, "headings_deg")
    headings = _array(m["headings_deg"], hpath, (None,), "a list of headings [deg]")
    if not headings:
        raise CaseError(hpath, "is empty; give at least one heading")
    _increasing(headings, hpath, "headings_deg")
    if headings[0] < -180 or headings[-1] >= 360 or headings[-1] - headings[0] >= 360:
        raise CaseError(hpath, "headings must lie in [-180, 360) deg and span less than one turn")
    panel = None
    if m.get("panel_size") is not None:
        panel = quantity(m["panel_size"], field_path(path, "panel_size"), "length", gt=0)
    cache = m.get("cache")
    if cache is not None and not (isinstance(cache, str) and cache.strip()):
        raise CaseError(field_path(path, "cache"), f"{show_value(cache)} must be a folder name")
    return CapytaineHull(omega=tuple(omega), headings_deg=tuple(headings), panel_size=panel,
                         cache=cache)


def extra_damping(raw, path: str) -> ExtraDamping:
    """``bodies[i].damping``: linear values and fractions of critical, per DOF."""
    m = check_mapping(raw, path, section="damping")
    linear = (0.0,) * 6
    if m.get("linear") is not None:
        lpath = field_path(path, "linear")
        items = check_list(m["linear"], lpath, "6 values [N s/m, N m s/rad]")
        if len(items) != 6:
            raise CaseError(lpath, f"{len(items)} values; give 6 (surge ... yaw) [N s/m, "
                                   "N m s/rad]")
        linear = tuple(quantity(v, field_path(lpath, i), "dimensionless", ge=0)
                       for i, v in enumerate(items))
    fractions = [0.0] * 6
    if m.get("critical_fraction") is not None:
        cpath = field_path(path, "critical_fraction")
        c = check_mapping(m["critical_fraction"], cpath, section="critical_fraction")
        for key, value in c.items():
            fractions[DOFS.index(key)] = quantity(value, field_path(cpath, key),
                                                  "dimensionless", ge=0, le=2.0)
    return ExtraDamping(linear=linear, critical_fraction=tuple(fractions))
