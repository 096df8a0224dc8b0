"""Design tension and utilisation of a line as DNV-OS-E301 and API RP 2SK write them.

The factors are those of ``criteria.csv`` (:mod:`.criteria`, with their source and what was
verified of them); this module only does the standards' arithmetic on a mean and a dynamic
tension, so a check with line dynamics (the mean from the static solution, the dynamic part
from :mod:`moorsolve.dynamics.line_spectral`) and one without compute the same way.

* DNV-OS-E301 (2010) Ch.2 Sec.2: ``T_d = gamma_mean T_mean + gamma_dyn T_dyn <= S_C``
  with ``S_C = 0.95 MBS``; ULS is the intact condition and ALS the damaged one (one line
  failed), with factors by consequence class. The factors are the same whether ``T_dyn``
  comes from a dynamic analysis or is zero (a mean-only check, necessary but not
  sufficient).
* API RP 2SK (3rd ed., 2005) section 7.4: ``MBL / T_max >= SF`` with ``T_max = T_mean +
  T_dyn``: the quasi-static method (``T_max`` the tension at the design offset) 2.00 intact /
  1.43 damaged, the dynamic method 1.67 / 1.25. Written here as ``T_d = SF T_max <= MBL``.

The utilisation is ``T_d / capacity``: 1 is the limit of either standard.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from ..errors import CaseError
from .criteria import Criterion, criteria_table

__all__ = ["DesignTension", "design_tension", "line_design_tensions", "METHODS",
           "STANDARDS"]

STANDARDS = ("dnv-os-e301", "api-rp-2sk")
#: API RP 2SK's two methods, as the case file spells them (criteria.csv: quasi-static).
METHODS = {"quasi_static": "quasi-static", "dynamic": "dynamic"}
CONDITIONS = ("intact", "damaged")


@dataclass(frozen=True)
class DesignTension:
    """One line end checked against one standard. Forces [N].

    ``t_max_N = t_mean_N + t_dyn_N``; ``design_N`` is the factored tension (DNV
    ``gamma_mean T_mean + gamma_dyn T_dyn``; API ``SF T_max``) and ``capacity_N`` what it
    is held against (DNV 0.95 MBS, API MBL); ``utilisation = design_N / capacity_N``.
    """

    standard: str
    condition: str
    method: str
    consequence_class: int | None
    t_mean_N: float
    t_dyn_N: float
    t_max_N: float
    design_N: float
    capacity_N: float
    utilisation: float
    criterion: Criterion

    @property
    def passed(self) -> bool:
        return self.utilisation <= 1.0

    def to_dict(self) -> dict:
        """The figures of the check table and JSON (``checks[*].lines[*]``)."""
        return {"t_mean_N": self.t_mean_N, "t_dyn_N": self.t_dyn_N, "t_max_N": self.t_max_N,
                "design_N": self.design_N, "capacity_N": self.capacity_N,
                "utilisation": self.utilisation}


def _criterion(standard: str, condition: str, method: str, consequence_class) -> Criterion:
    analysis = METHODS[method]
    for row in criteria_table():
        if row.standard != standard or row.condition != condition:
            continue
        if standard == "api-rp-2sk" and row.analysis == analysis:
            return row
        if standard == "dnv-os-e301" and row.consequence_class == consequence_class:
            return row          # DNV's factors do not depend on the method
    raise CaseError("checks", f"no {standard} factors for {condition} ({method}, "
                    f"consequence class {consequence_class}) in the criteria table")


def _force(value, field: str, *, positive: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise CaseError(field, f"{value!r} must be a force in N") from None
    if not math.isfinite(v) or v < 0 or (positive and v == 0):
        raise CaseError(field, f"{value!r} N must be finite and {'> 0' if positive else '>= 0'}")
    return v


def design_tension(*, standard: str, condition: str, t_mean: float, t_dyn: float,
                   mbl: float, consequence_class: int = 1,
                   method: str = "dynamic") -> DesignTension:
    """The design tension and utilisation of one line end.

    Parameters
    ----------
    standard : {"dnv-os-e301", "api-rp-2sk"}
    condition : {"intact", "damaged"}
        DNV: ULS and ALS.
    t_mean, t_dyn : float
        Mean and characteristic dynamic tension [N] (API quasi-static method: ``t_mean +
        t_dyn`` is the tension at the design offset).
    mbl : float
        Minimum breaking load (DNV's MBS) [N].
    consequence_class : {1, 2}
        DNV's consequence class (API has none; ignored).
    method : {"dynamic", "quasi_static"}
        API RP 2SK's method (DNV's factors are the same for both).

    Returns
    -------
    DesignTension
    """
    if standard not in STANDARDS:
        raise CaseError("checks.standard", f"{standard!r}: use one of {', '.join(STANDARDS)}")
    if condition not in CONDITIONS:
        raise CaseError("condition", f"{condition!r}: use intact or damaged")
    if method not in METHODS:
        raise CaseError("checks.method", f"{method!r}: use dynamic or quasi_static")
    if standard == "dnv-os-e301" and consequence_class not in (1, 2):
        raise CaseError("checks.consequence_class", f"{consequence_class!r}: use 1 or 2")
    t_mean = _force(t_mean, "t_mean")
    t_dyn = _force(t_dyn, "t_dyn")
    mbl = _force(mbl, "mbl", positive=True)
    row = _criterion(standard, condition, method, consequence_class)
    t_max = t_mean + t_dyn
    if standard == "dnv-os-e301":
        design = row.factor * t_mean + row.gamma_dyn * t_dyn
        cc = consequence_class
    else:
        design = row.factor * t_max
        cc = None
    capacity = row.capacity_factor * mbl
    return DesignTension(standard=standard, condition=condition, method=method,
                         consequence_class=cc, t_mean_N=t_mean, t_dyn_N=t_dyn, t_max_N=t_max,
                         design_N=design, capacity_N=capacity,
                         utilisation=design / capacity, criterion=row)


def line_design_tensions(result, dynamic_tension: Mapping, *, standard: str,
                         condition: str = "intact", consequence_class: int = 1,
                         method: str = "dynamic") -> dict:
    """The design tension of every line of a solved result, at its worse end.

    Parameters
    ----------
    result : moorsolve.Result
        The static equilibrium: its anchor and fairlead tensions are the mean tensions.
    dynamic_tension : mapping
        Line name to ``(t_dyn_anchor, t_dyn_fairlead)`` [N], the characteristic dynamic
        tension at each end (e.g. ``LineTensionStatistics.anchor.t_dyn_N``). A line not
        in it has no dynamic part (a mean-only check).
    standard, condition, consequence_class, method
        As :func:`design_tension`.

    Returns
    -------
    dict
        Line name to ``(end, DesignTension)`` with ``end`` ``"anchor"`` or
        ``"fairlead"``, the end of larger utilisation. The capacity is the line's
        ``mbl_N`` (the weakest segment's for a multi-segment line).

    Raises
    ------
    CaseError
        A line without an MBL, or a dynamic tension for a line the result does not have.
    """
    legs = {leg.name: leg for leg in result.legs}
    unknown = sorted(set(dynamic_tension) - set(legs))
    if unknown:
        raise CaseError("dynamic_tension", f"no line named {', '.join(unknown)} in the "
                        f"result (lines: {', '.join(sorted(legs))})")
    out = {}
    for name, leg in legs.items():
        if not leg.mbl_N:
            raise CaseError(f"lines.{name}", "the line type has no mbl: no design check")
        dyn_a, dyn_b = dynamic_tension.get(name, (0.0, 0.0))
        ends = [(end, design_tension(standard=standard, condition=condition, t_mean=t_mean,
                                     t_dyn=t_dyn, mbl=leg.mbl_N,
                                     consequence_class=consequence_class, method=method))
                for end, t_mean, t_dyn in (("anchor", leg.anchor_tension_N, dyn_a),
                                           ("fairlead", leg.fairlead_tension_N, dyn_b))]
        out[name] = max(ends, key=lambda e: e[1].utilisation)
    return out
