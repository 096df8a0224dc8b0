"""Checked case-file input of ``checks.fatigue``.

Schema (SI units unless a unit string is given)::

    checks.fatigue:
      design_life: > 0 [s]            e.g. "20 y" (y, yr, year)
      sea_states: {table: [[hs m, tp s, toward_deg, probability], ...]}
      spectrum: {model: jonswap, gamma: ...} | {model: pierson_moskowitz}   (jonswap)
      curve: {catalog: NAME} | {m: > 0, a_d: > 0, basis: stress_chain | stress_wire |
             mbl_ratio}        (default {catalog: dnv_studless})
      curves: {LINE_TYPE: curve, ...}   per line type, overriding curve
      design_fatigue_factor: >= 1     (5)
      method: narrow_band | dirlik    (narrow_band)
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..catalog.fatigue import BASES, Curve, catalog
from ..errors import CaseError
from .build_sea import _spectrum
from .build_wear import SECONDS_PER_YEAR, design_life_years
from .fatigue import DEFAULT_DFF, FATIGUE_METHODS, FatigueSpec
from .fields import check_mapping, check_rows, field_path, quantity
from .sea import Spectrum
from .units import show_value

__all__ = ["fatigue_spec"]

#: The scatter diagram's probabilities must sum to 1 within this.
PROBABILITY_TOLERANCE = 1e-3


def fatigue_spec(raw, path: str, line_types, *, checks_life=None,
                 checks_life_path: str = "checks.design_life") -> FatigueSpec:
    """``checks.fatigue`` as a :class:`FatigueSpec`; ``line_types`` the case's names.

    The design life is the fatigue block's own ``design_life`` or, without one, the
    ``checks.design_life`` the wear check reads (``checks_life``); both given, they must agree.
    """
    m = check_mapping(raw, path, section="fatigue")
    life = None if checks_life is None else design_life_years(checks_life, checks_life_path)
    if m.get("design_life") is not None:
        own = design_life_years(m["design_life"], field_path(path, "design_life"))
        if life is not None and abs(own - life) > 1e-9 * life:
            raise CaseError(field_path(path, "design_life"),
                            f"{own:g} years differs from {checks_life_path} ({life:g} years); "
                            "give the design life once")
        life = own
    if life is None:
        raise CaseError(field_path(path, "design_life"),
                        "fatigue accumulates over the design life; give design_life "
                        "(e.g. '20 y') here or in checks")
    life *= SECONDS_PER_YEAR
    states = _sea_states(m["sea_states"], field_path(path, "sea_states"))
    spectrum = Spectrum()
    if m.get("spectrum") is not None:
        spath = field_path(path, "spectrum")
        if isinstance(m["spectrum"], Mapping) and "table" in m["spectrum"]:
            raise CaseError(spath, "a scatter diagram's sea states take a parametric "
                                   "spectrum: {model: jonswap | pierson_moskowitz}")
        tps = [s[1] for s in states]
        spectrum = _spectrum(m["spectrum"], spath, states[0][0], min(tps))
        if spectrum.model == "jonswap" and spectrum.gamma is None:
            spectrum = Spectrum()
    curve = (catalog()["dnv_studless"] if m.get("curve") is None
             else _curve(m["curve"], field_path(path, "curve")))
    curves = ()
    if m.get("curves") is not None:
        cpath = field_path(path, "curves")
        given = m["curves"]
        if not isinstance(given, Mapping):
            raise CaseError(cpath, f"{show_value(given)} is not a mapping of line type names "
                                   "to curves")
        for name in given:
            if name not in line_types:
                raise CaseError(field_path(cpath, name),
                                f"unknown line type {show_value(name)}; known line types: "
                                f"{', '.join(line_types)}")
        curves = tuple((name, _curve(v, field_path(cpath, name))) for name, v in given.items())
    dff = DEFAULT_DFF
    if m.get("design_fatigue_factor") is not None:
        dff = quantity(m["design_fatigue_factor"], field_path(path, "design_fatigue_factor"),
                       "dimensionless", ge=1.0)
    method = m.get("method", "narrow_band")
    if method not in FATIGUE_METHODS:
        raise CaseError(field_path(path, "method"), f"{show_value(method)} must be one of "
                                                    f"{', '.join(FATIGUE_METHODS)}")
    return FatigueSpec(design_life=life, sea_states=states, spectrum=spectrum, curve=curve,
                       curves=curves, design_fatigue_factor=dff, method=method)


def _sea_states(raw, path: str) -> tuple:
    m = check_mapping(raw, path, section="fatigue_sea_states")
    tpath = field_path(path, "table")
    rows = check_rows(m["table"], tpath, "[hs m, tp s, toward_deg, probability]", width=4,
                      min_rows=1, empty="a scatter diagram")
    out = []
    for where, row in rows:
        hs = quantity(row[0], where + "[0] (hs)", "length", gt=0)
        tp = quantity(row[1], where + "[1] (tp)", "time", gt=0, le=100.0)
        toward = quantity(row[2], where + "[2] (toward_deg)", "angle")
        p = quantity(row[3], where + "[3] (probability)", "dimensionless", ge=0, le=1)
        out.append((hs, tp, toward, p))
    total = math.fsum(r[3] for r in out)
    if abs(total - 1.0) > PROBABILITY_TOLERANCE:
        raise CaseError(tpath, f"the probabilities sum to {total:.6g}; a scatter diagram's "
                               "must sum to 1 (add the missing sea states, calm ones with "
                               "hs > 0 too, or normalise)")
    return tuple(out)


def _curve(raw, path: str) -> Curve:
    if isinstance(raw, Mapping) and "catalog" in raw:
        m = check_mapping(raw, path, section="fatigue_curve_catalog")
        name = m["catalog"]
        known = catalog()
        if not isinstance(name, str) or name not in known:
            raise CaseError(field_path(path, "catalog"),
                            f"{show_value(name)} is not a fatigue curve of the catalogue; "
                            f"allowed: {', '.join(known)}")
        return known[name]
    m = check_mapping(raw, path, section="fatigue_curve")
    slope = quantity(m["m"], field_path(path, "m"), "dimensionless", gt=0, le=20)
    a_d = quantity(m["a_d"], field_path(path, "a_d"), "dimensionless", gt=0)
    basis = m.get("basis", "stress_chain")
    if basis not in BASES:
        raise CaseError(field_path(path, "basis"), f"{show_value(basis)} must be one of "
                                                   f"{', '.join(BASES)}")
    return Curve(m=slope, a_d=a_d, basis=basis)
