"""One check of a mooring: a value against its limit (the row every check module makes), and
the items of a line, an anchor, a hawser, a fender and a pile guide."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from ..model import AnchorType
from .berth import fender_criterion, guide_criterion, hawser_criterion

#: Anchor uplift below this fraction of the line tension (or 1 N) counts as none: the
#: solver's own residual is far smaller, a physical uplift far larger.
_UPLIFT_TOL_REL = 1e-6

__all__ = ["CheckItem"]


@dataclass(frozen=True)
class CheckItem:
    """One check: a value against its limit.

    ``utilisation`` is demand over capacity (``<= 1`` passes; ``inf`` when the capacity is
    zero or missing). ``detail`` holds what a check has beyond the one value (an
    anchor's load at the padeye, its capacity and factors).
    """

    condition: str
    leg: str | None
    check: str
    value: float
    limit: float
    unit: str
    utilisation: float
    passed: bool
    criterion: str
    detail: dict = field(default_factory=dict, compare=False)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def hawser_item(condition: str, lr, line) -> CheckItem:
    """A ship's mooring line against MEG4's working load limit (:mod:`.berth`)."""
    T = max(lr.fairlead_tension_N, lr.anchor_tension_N)
    row = hawser_criterion(line.line_type)
    text = f"OCIMF MEG4 WLL: T <= {row.limit:.0%} MBL ({row.material.replace('_', ' ')})"
    if not lr.mbl_N:
        return CheckItem(condition=condition, leg=lr.name, check="hawser tension", value=T,
                         limit=math.nan, unit="N", utilisation=math.inf, passed=False,
                         criterion="no MBL given for the hawser's line type: give mbl")
    limit = row.limit * lr.mbl_N
    return CheckItem(condition=condition, leg=lr.name, check="hawser tension", value=T,
                     limit=limit, unit="N", utilisation=T / limit, passed=T <= limit,
                     criterion=text)


def fender_item(condition: str, fender: dict) -> CheckItem:
    """A fender's compression against its rated deflection."""
    row = fender_criterion()
    limit = row.limit * fender["rated_deflection_m"]
    value = fender["compression_m"]
    criterion = "compression <= rated deflection (PIANC fender guidelines)"
    if fender.get("hull_bears"):
        criterion += (f"; fully compressed, the hull bears on {fender['bears_on']} behind it "
                      f"with {fender['hull_reaction_N'] / 1e3:.1f} kN")
    return CheckItem(condition=condition, leg=fender["name"], check="fender compression",
                     value=value, limit=limit, unit="m", utilisation=value / limit,
                     passed=value <= limit, criterion=criterion)


def guide_item(condition: str, guide: dict) -> CheckItem:
    """A pile guide's collar must stay on its pile."""
    row = guide_criterion()
    limit = row.limit * guide["pile_top_m"]
    value = guide["height_m"]
    # Utilisation: the collar's height over the pile's length above the seabed.
    bed = guide["seabed_z_m"]
    return CheckItem(condition=condition, leg=guide["name"], check="guide on pile",
                     value=value, limit=limit, unit="m",
                     utilisation=(value - bed) / (limit - bed) if limit > bed else math.inf,
                     passed=value <= limit,
                     criterion=f"collar height <= pile {guide['pile']}'s top")


def tension_item(condition: str, lr, crit, design=None, where: str = "") -> CheckItem:
    """The line's tension item.

    With ``design`` (a :class:`~.design_tension.DesignTension`) the item checks the figure
    the line's design tensions carry: ``value`` is ``T_max`` and ``limit`` the ``T_max``
    that would give a utilisation of 1 at the same split into mean and dynamic parts, so
    ``utilisation`` is exactly ``design_N / capacity_N`` (API: ``MBL / SF``; DNV with a
    dynamic part: ``T_max capacity / design``). Without, the larger end tension of ``lr``
    against ``capacity_factor MBL / factor``. ``where`` is added to the criterion (``at
    the design offset``).
    """
    T = max(lr.fairlead_tension_N, lr.anchor_tension_N) if design is None else design.t_max_N
    if not lr.mbl_N:
        return CheckItem(condition=condition, leg=lr.name, check="tension", value=T,
                         limit=math.nan, unit="N", utilisation=math.inf, passed=False,
                         criterion="no MBL given for the line type: give mbl or a "
                                   "catalogue line")
    text = crit.describe(dynamic=design is not None and design.t_dyn_N > 0
                         and crit.gamma_dyn is not None)
    text += f" {where}" if where else ""
    if design is None:
        allowed = crit.capacity_factor * lr.mbl_N / crit.factor
        return CheckItem(condition=condition, leg=lr.name, check="tension", value=T,
                         limit=allowed, unit="N", utilisation=T / allowed,
                         passed=T <= allowed, criterion=text)
    util = design.utilisation
    allowed = T / util if util > 0 else math.inf
    return CheckItem(condition=condition, leg=lr.name, check="tension", value=T,
                     limit=allowed, unit="N", utilisation=util, passed=util <= 1.0,
                     criterion=text)


def uplift_item(condition: str, lr, anchor: AnchorType) -> CheckItem:
    VA = lr.anchor_vertical_N
    tiny = max(_UPLIFT_TOL_REL * lr.anchor_tension_N, 1.0)
    if anchor.kind == "pile":
        angle = lr.uplift_angle_deg if VA > tiny else 0.0
        limit = anchor.allowed_uplift_angle_deg
        util = angle / limit if limit > 0 else (0.0 if angle == 0 else math.inf)
        return CheckItem(condition=condition, leg=lr.name, check="anchor uplift angle",
                         value=angle, limit=limit, unit="deg", utilisation=util,
                         passed=angle <= limit,
                         criterion=f"pile: uplift angle <= {limit:.1f} deg")
    limit = anchor.allowed_uplift if anchor.kind == "deadweight" else 0.0
    value = VA if VA > tiny else 0.0
    util = value / limit if limit > 0 else (0.0 if value == 0 else math.inf)
    text = ("drag anchor: no uplift" if anchor.kind == "drag"
            else f"deadweight anchor: uplift <= {limit / 1e3:.1f} kN")
    return CheckItem(condition=condition, leg=lr.name, check="anchor uplift", value=value,
                     limit=limit, unit="N", utilisation=util, passed=value <= limit,
                     criterion=text)
