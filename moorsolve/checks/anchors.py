"""Anchor capacity: the load at each anchor's padeye against what the anchor holds.

Per leg anchored on the seabed whose anchor kind has a design in ``checks.anchors``
(:mod:`moorsolve.model.anchors`):

* the load at the mudline is the line's tension at its anchor end and the angle it makes
  with the seabed there (0 where the line lies on the seabed);
* with an ``embedment`` it is carried down to the padeye (:mod:`.padeye`, Neubecker &
  Randolph 1995); without one the padeye is at the mudline;
* ``drag``: the padeye tension against the ultimate holding capacity ``UHC`` (given, or the
  maker's curve ``UHC = a W^b``, :mod:`moorsolve.catalog.anchors`); the uplift rule at the
  mudline stays;
* ``pile``: the padeye's horizontal and vertical components each against their capacity;
* ``suction``: the interaction ``(H/H_max)^a + (V/V_max)^b <= 1`` with ``a = 0.5 + L/D``,
  ``b = 4.5 + L/(3D)`` (L skirt length, D diameter; Randolph & Gourvenec 2011, section 10.3,
  after Senders & Kay 2002); the utilisation is the factor that takes the design load
  radially onto the envelope, so 1 is the limit.

Factors (``anchor_criteria.csv``, with their source and what was verified of them):
API RP 2SK's factors of safety multiply the padeye load (a drag anchor's tension; a pile's or
suction anchor's horizontal and vertical components separately); DNV's design tension
``gamma_mean T_mean + gamma_dyn T_dyn`` (the line's factors) is formed at the mudline and
carried down to the padeye, and the capacity divided by the material factor ``gamma_m``.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from scipy.optimize import brentq

from ..catalog.anchors import drag_curve
from ..errors import CaseError
from .criteria import Criterion
from .items import CheckItem
from .padeye import PadeyeLoad, clay_resistance, padeye_load

__all__ = ["AnchorCriterion", "anchor_criterion", "anchor_items", "suction_exponents",
           "envelope_utilisation"]

#: Uplift below this fraction of the anchor tension (or 1 N) counts as none.
_UPLIFT_TOL_REL = 1e-6
CHECK = "anchor capacity"


@dataclass(frozen=True)
class AnchorCriterion:
    """One row of ``anchor_criteria.csv``."""

    standard: str
    anchor: str
    condition: str
    analysis: str
    consequence_class: int | None
    factor_h: float
    factor_v: float | None
    material_factor: float
    source: str
    verified: str


@lru_cache(maxsize=1)
def _table() -> tuple:
    text = resources.files(__package__).joinpath("anchor_criteria.csv").read_text("utf-8")
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    return tuple(AnchorCriterion(
        standard=r["standard"], anchor=r["anchor"], condition=r["condition"],
        analysis=r["analysis"],
        consequence_class=int(r["consequence_class"]) if r["consequence_class"] else None,
        factor_h=float(r["factor_h"]), factor_v=float(r["factor_v"]) if r["factor_v"] else None,
        material_factor=float(r["material_factor"]), source=r["source"],
        verified=r["verified"]) for r in csv.DictReader(io.StringIO(body)))


def anchor_criterion(standard: str, anchor: str, condition: str, analysis: str,
                     consequence_class: int = 1) -> AnchorCriterion | None:
    """The row for an anchor kind, or None where the table has none. A row of analysis
    ``any`` holds for every analysis (DNV's factors do not depend on the method)."""
    for row in _table():
        if (row.standard, row.anchor, row.condition) == (standard, anchor, condition) \
                and row.analysis in (analysis, "any") \
                and row.consequence_class in (None, consequence_class):
            return row
    return None


def suction_exponents(length: float, diameter: float) -> tuple:
    """``(a, b) = (0.5 + L/D, 4.5 + L/(3D))`` of the suction anchor's H-V envelope."""
    r = length / diameter
    return 0.5 + r, 4.5 + r / 3.0


def envelope_utilisation(h: float, v: float, a: float, b: float) -> float:
    """``u`` with ``(h/u)^a + (v/u)^b = 1``: the design load ``(h, v)`` (each over its
    capacity) is ``u`` times the point of the envelope ``x^a + y^b = 1`` on its ray.

    ``u <= 1`` lies inside; at the corners ``u = h`` (``v = 0``) and ``u = v`` (``h = 0``).
    """
    if h < 0 or v < 0:
        raise ValueError("envelope_utilisation: h and v must be >= 0")
    if h == 0 or v == 0:
        return max(h, v)
    lo = max(h, v)
    hi = lo * 2.0 ** (1.0 / min(a, b))       # each term <= 1/2 there
    return brentq(lambda u: (h / u) ** a + (v / u) ** b - 1.0, lo, hi, xtol=1e-15,
                  rtol=1e-14)


def _diameter(design, leg, path: str) -> float:
    emb = design.embedment
    if emb.line_diameter is not None:
        return emb.line_diameter
    lt = leg.segments[0].line_type
    if lt.catalog is None or lt.diameter is None:
        raise CaseError(path, f"leg {leg.name!r} enters the soil with line type {lt.name!r}, "
                              "not a catalogue line: give the nominal line_diameter [m]")
    return lt.diameter


def _mudline(lr) -> tuple:
    """``(T_m [N], theta_m [rad])`` at the anchor end."""
    T = lr.anchor_tension_N
    V = lr.anchor_vertical_N
    tiny = max(_UPLIFT_TOL_REL * T, 1.0)
    angle = math.atan2(V, lr.anchor_horizontal_N) if V > tiny else 0.0
    return T, min(max(angle, 0.0), math.pi / 2)


def _to_padeye(design, leg, tension: float, angle: float) -> PadeyeLoad:
    emb = design.embedment
    if emb is None:
        return PadeyeLoad(tension=tension, angle=angle)
    d = _diameter(design, leg, f"checks.anchors.{design.kind}.embedment.line_diameter")
    zq = clay_resistance(emb.padeye_depth, diameter=d, su0=emb.su0,
                         su_gradient=emb.su_gradient, bearing_factor=emb.bearing_factor,
                         bearing_width=emb.bearing_width)
    return padeye_load(tension, angle, zq, emb.friction)


def anchor_items(condition: str, condition_kind: str, leg, mean_leg, leg_result, checks,
                 crit: Criterion, tension: float | None = None) -> list:
    """The anchor capacity item of one leg (an empty list where its kind has no design).

    Parameters
    ----------
    condition, condition_kind : str
        The condition's name and ``intact`` or ``damaged``.
    leg : Line
    mean_leg, leg_result : LineResult
        The leg at the mean position and where the check is made (the same in the mean
        method; at the design offset in API's quasi-static method).
    checks : Checks
    crit : Criterion
        The line-tension criterion of the condition (its analysis, and DNV's load factors).
    tension : float, optional
        The anchor end's largest tension [N] where the lines' own dynamics give it (mean
        plus dynamic part); else the tension of ``leg_result`` at the anchor. The angle is
        ``leg_result``'s either way.
    """
    kind = (leg.anchor_type or checks.anchor).kind
    if kind == "deadweight" or not checks.anchors:
        return []
    design = checks.anchor_design(kind)
    name = leg_result.name
    if design is None:
        return [CheckItem(condition=condition, leg=name, check=CHECK, value=math.nan,
                          limit=math.nan, unit="-", utilisation=math.inf, passed=False,
                          criterion=f"no {kind} anchor design given: give "
                                    f"checks.anchors.{kind}")]
    row = anchor_criterion(crit.standard, kind, condition_kind, crit.analysis,
                           crit.consequence_class or 1)
    if row is None:
        return [CheckItem(condition=condition, leg=name, check=CHECK, value=math.nan,
                          limit=math.nan, unit="-", utilisation=math.inf, passed=False,
                          criterion=f"{crit.standard} has no {kind} anchor factors in "
                                    "moorsolve's table: check with another standard")]
    T, theta = _mudline(leg_result)
    if tension is not None:
        T = tension
    load = _to_padeye(design, leg, T, theta)
    if row.standard == "api-rp-2sk":
        design_load = load
        fh, fv = row.factor_h, row.factor_v if row.factor_v is not None else row.factor_h
        factors = f"FoS {fh:g}" + (f" H, {fv:g} V" if kind != "drag" else "")
    else:
        t_mean, _ = _mudline(mean_leg)
        t_dyn = max(T - t_mean, 0.0)
        gamma_dyn = crit.gamma_dyn or 0.0
        design_load = _to_padeye(design, leg, crit.factor * t_mean + gamma_dyn * t_dyn, theta)
        fh = fv = 1.0
        factors = (f"{crit.factor:g} T_mean + {gamma_dyn:g} T_dyn, gamma_m "
                   f"{row.material_factor:g}")
    gm = row.material_factor
    detail = {
        "kind": kind, "mudline_tension_N": T, "mudline_angle_deg": math.degrees(theta),
        "padeye_tension_N": load.tension, "padeye_angle_deg": math.degrees(load.angle),
        "padeye_horizontal_N": load.horizontal, "padeye_vertical_N": load.vertical_force,
        "reached_vertical": load.vertical,
        "padeye_depth_m": 0.0 if design.embedment is None else design.embedment.padeye_depth,
        "factors": factors, "material_factor": gm,
        "capacity_source": design.capacity_source, "criterion_source": row.source,
        "criterion_verified": row.verified}
    if kind == "drag":
        demand = fh * design_load.tension
        capacity = design.capacity / gm
        util = demand / capacity
        detail.update(design_N=demand, capacity_N=design.capacity, design_capacity_N=capacity)
        if design.soil is not None:
            # The least anchor of the same design that would hold (the maker's curve).
            curve = drag_curve(design.soil, design.design)
            detail["required_mass_kg"] = curve.mass_kg(demand * gm)
        text = f"{crit.standard} drag anchor: {factors}: T_padeye <= UHC"
        value, limit, unit = demand, capacity, "N"
    else:
        h = fh * design_load.horizontal / (design.h_max / gm)
        v = fv * design_load.vertical_force / (design.v_max / gm)
        detail.update(design_h_N=fh * design_load.horizontal,
                      design_v_N=fv * design_load.vertical_force,
                      h_max_N=design.h_max, v_max_N=design.v_max)
        if kind == "suction":
            a, b = suction_exponents(design.length, design.diameter)
            util = envelope_utilisation(h, v, a, b)
            detail.update(exponent_a=a, exponent_b=b)
            text = (f"{crit.standard} suction anchor: {factors}: (H/H_max)^{a:.2f} + "
                    f"(V/V_max)^{b:.2f} <= 1")
        else:
            util = max(h, v)
            text = f"{crit.standard} pile: {factors}: H <= H_max and V <= V_max"
        value, limit, unit = util, 1.0, "-"
    detail["utilisation"] = util
    return [CheckItem(condition=condition, leg=name, check=CHECK, value=value, limit=limit,
                      unit=unit, utilisation=util, passed=util <= 1.0, criterion=text,
                      detail=detail)]
