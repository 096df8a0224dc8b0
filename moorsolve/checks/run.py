"""Run the mooring checks: the intact condition and each damaged condition.

A damaged condition removes one line, any line of a network (a bridle leg, a shared line)
included (:func:`moorsolve.model.edit.without_line`), and solves the scene again from scratch
with :func:`moorsolve.solve`. A condition without a certified
equilibrium is a failed check that carries the solver's reason; it never raises.

Per leg and condition:

* line tension: ``factor * T <= capacity_factor * MBL`` (criteria table of the standard);
  ``T`` is the larger of the fairlead and anchor tension;
* anchor uplift: ``drag`` none, ``deadweight`` up to ``allowed_uplift`` [N], ``pile`` up to
  ``allowed_uplift_angle_deg`` at the anchor; and, where ``checks.anchors`` gives the
  anchor's design, its capacity against the load at its padeye (:mod:`.anchors`);
* grounded length at least ``min_grounded_length`` for legs that can rest on the seabed;
* fibre rope: none of it on the seabed (legs with a ``fibre`` line type), and the least
  tension along each segment of a line type with a ``min_tension`` at least that (a rope
  that must not go slack: :mod:`moorsolve.checks.fibre`);

and per condition the horizontal offset of the body origin against the offset limit. With
API RP 2SK and a sea state in which bodies move, the tension, uplift, grounded length and
offset are those at the bodies' design offset (the quasi-static method,
:mod:`.design_offset`); otherwise the mean tension's, and the report says so. At a
berth (:mod:`.berth`) a hawser's tension is checked against the working load
limit of OCIMF MEG4 instead of the standard's factor, each fender's compression against its
rated deflection and each pile guide's height against its pile's top.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

from ..errors import CaseError, ConvergenceError
from ..model import AnchorType, Case, Checks
from ..model.edit import without_line
from ..solve import Result, solve
from ..model.restraint import drifting_bodies
from .anchors import anchor_items
from .berth import (fender_criterion, guide_criterion, hawser_criterion, is_hawser)
from .criteria import Criterion, criterion, standard_rows
from .design_offset import (MEAN_ONLY, MEAN_ONLY_DNV, METHOD_DESIGN_OFFSET,
                            design_offset_solve, design_offset_tension, mean_tension,
                            sea_simulated)
from .drift import drift_findings, hold_drifting
from .fibre import LOWER_LIMIT_CHECKS, fibre_items
from .items import CheckItem

#: Anchor uplift below this fraction of the line tension (or 1 N) counts as none: the
#: solver's own residual is far smaller, a physical uplift far larger.
_UPLIFT_TOL_REL = 1e-6


@dataclass(frozen=True)
class ConditionResult:
    """One condition: intact, or one leg removed.

    Attributes
    ----------
    name : str
        ``intact`` or ``damaged: L3 removed``.
    kind : str
        ``intact`` or ``damaged``.
    removed : str or None
        The removed leg.
    solved : bool
        A certified equilibrium was found.
    reason : str
        Why not, when it was not.
    result : Result or None
        The equilibrium (for overloaded lines too: solved with ``allow_overload``).
    items : list of CheckItem
    criterion : Criterion
    drifting : tuple of dict
        Bodies nothing holds horizontally in this condition (a tanker whose one hawser
        broke): each ``body``, ``dofs``, ``group``, ``lines``, ``load_N``, ``toward_deg``
        and ``message`` (:mod:`.drift`). Such a condition fails; ``result`` is then the
        rest of the mooring solved with those bodies held.
    method : str
        ``mean`` (the factors on the mean tension) or ``design offset`` (API RP 2SK's
        quasi-static method, :mod:`.design_offset`).
    lines : tuple of dict
        Per line: ``leg``, ``end`` and the figures of
        :class:`~moorsolve.checks.design_tension.DesignTension` (``t_mean_N``, ``t_dyn_N``,
        ``t_max_N``, ``design_N``, ``capacity_N``, ``utilisation``).
    design_offset_m : dict
        Body name to its design offset [m] (``design offset`` method only).
    held : Result or None
        The lines with the bodies held at the design offset (``design offset`` method).
    """

    name: str
    kind: str
    removed: str | None
    solved: bool
    reason: str
    result: Result | None
    items: list
    criterion: Criterion
    drifting: tuple = ()
    method: str = "mean"
    lines: tuple = ()
    design_offset_m: dict = field(default_factory=dict)
    held: Result | None = None

    @property
    def passed(self) -> bool:
        return self.solved and not self.drifting and all(item.passed for item in self.items)

    def __repr__(self) -> str:
        if self.drifting:
            return (f"<ConditionResult {self.name!r}: FAIL, "
                    f"{'; '.join(d['message'] for d in self.drifting)}>")
        if not self.solved:
            return f"<ConditionResult {self.name!r}: FAIL, no equilibrium: {self.reason}>"
        worst = self.worst()
        tension = "" if worst is None else (f", worst tension {worst.leg} utilisation "
                                             f"{worst.utilisation:.2f}")
        return (f"<ConditionResult {self.name!r}: {'PASS' if self.passed else 'FAIL'}"
                f"{tension}>")

    @property
    def offset_m(self) -> float | None:
        """The body's horizontal offset [m]; with several bodies the largest one's. At the
        design offset where the quasi-static method ran."""
        if self.design_offset_m:
            return max(self.design_offset_m.values())
        if self.result is None:
            return None
        if self.result.body is not None:
            return math.hypot(self.result.body["x_m"], self.result.body["y_m"])
        return max((math.hypot(b["offset"]["x_m"], b["offset"]["y_m"])
                    for b in self.result.bodies), default=None)

    def worst(self, check: str = "tension") -> CheckItem | None:
        items = [i for i in self.items if i.check == check]
        return max(items, key=lambda i: i.utilisation, default=None)

    def to_dict(self) -> dict:
        worst = self.worst()
        return {
            "name": self.name, "kind": self.kind, "removed": self.removed,
            "solved": self.solved, "reason": self.reason, "passed": self.passed,
            "offset_m": self.offset_m,
            "body": None if self.result is None or self.result.body is None
            else dict(self.result.body),
            "max_tension_utilisation": None if worst is None else worst.utilisation,
            "criterion": self.criterion.describe(),
            "drifting": [dict(d) for d in self.drifting],
            "method": self.method,
            "design_offset_m": dict(self.design_offset_m),
            "lines": [dict(line) for line in self.lines],
            "checks": [item.to_dict() for item in self.items],
        }


@dataclass(frozen=True)
class CheckReport:
    """All conditions of one case under one standard."""

    case_name: str
    standard: str
    consequence_class: int
    checks: Checks
    conditions: list
    criteria: list = field(default_factory=list)
    time_s: float = 0.0
    #: The certified relative force residual every condition was solved to.
    tolerance: float = math.nan
    #: The case has a sea state (waves with a period).
    sea: bool = False
    #: The fatigue check (moorsolve.life.fatigue.FatigueResult) where checks.fatigue is given.
    fatigue: object = None

    def __repr__(self) -> str:
        verdict = "PASS" if self.passed else "FAIL"
        return (f"<CheckReport {self.case_name!r} {self.standard}: {verdict}, "
                f"{sum(c.passed for c in self.conditions)} of {len(self.conditions)} "
                f"conditions pass>")

    def _repr_html_(self) -> str:
        from ..report.notebook import check_html_table
        return check_html_table(self)

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.conditions) and (
            self.fatigue is None or self.fatigue.passed)

    @property
    def failures(self) -> list:
        out = [] if self.fatigue is None else [
            f"fatigue of {e.line} at its {e.end}: DFF x D = {e.utilisation:.3g} > 1 "
            f"(life {e.life_y:.4g} y)" for e in self.fatigue.ends if not e.passed]
        for c in self.conditions:
            out += [f"{c.name}: {d['message']}" for d in c.drifting]
            if not c.solved:
                out.append(f"{c.name}: no equilibrium: {c.reason}")
            out += [f"{c.name}: {i.check}{' of ' + i.leg if i.leg else ''}: "
                    f"{_show(i.value, i.unit)}, no limit to check against: {i.criterion}"
                    if not math.isfinite(i.limit) else
                    f"{c.name}: {i.check}{' of ' + i.leg if i.leg else ''}: "
                    f"{_show(i.value, i.unit)} > limit {_show(i.limit, i.unit)} ({i.criterion})"
                    if i.check not in LOWER_LIMIT_CHECKS else
                    f"{c.name}: {i.check} of {i.leg}: {_show(i.value, i.unit)} < "
                    f"{_show(i.limit, i.unit)}"
                    for i in c.items if not i.passed]
        return out

    @property
    def method(self) -> str:
        """What the line-tension check covers, in one sentence."""
        used = {c.method for c in self.conditions if c.solved}
        if used == {"design offset"}:
            return METHOD_DESIGN_OFFSET
        if "design offset" in used:
            return (METHOD_DESIGN_OFFSET + " where a body moves in the sea state ("
                    + ", ".join(c.name for c in self.conditions
                                if c.method == "design offset")
                    + "); elsewhere " + MEAN_ONLY)
        waves = self.sea
        if self.standard == "dnv-os-e301" and waves:
            return MEAN_ONLY_DNV
        return MEAN_ONLY

    @property
    def warnings(self) -> list[dict]:
        """Every solved condition's warnings (:attr:`moorsolve.Result.warnings`), each with
        its ``condition``: what no engineer may miss, pass or fail."""
        return [dict(w, condition=c.name) for c in self.conditions if c.result is not None
                for w in c.result.warnings]

    def to_dict(self) -> dict:
        return {
            "case": self.case_name, "standard": self.standard,
            "consequence_class": self.consequence_class, "passed": self.passed,
            "method": self.method,
            "time_s": self.time_s, "tolerance": self.tolerance,
            "limits": {"offset_limit_m": self.checks.offset_limit,
                       "offset_limit_damaged_m": _damaged(self.checks.offset_limit_damaged,
                                                          self.checks.offset_limit),
                       "min_grounded_length_m": self.checks.min_grounded_length,
                       "min_grounded_length_damaged_m": _damaged(
                           self.checks.min_grounded_length_damaged,
                           self.checks.min_grounded_length)},
            "criteria": [dataclasses.asdict(c) for c in self.criteria],
            "conditions": [c.to_dict() for c in self.conditions],
            "failures": self.failures,
            "warnings": self.warnings,
            **({} if self.fatigue is None else {"fatigue": self.fatigue.to_dict()}),
        }


def _show(value: float, unit: str) -> str:
    if not math.isfinite(value):
        return "n/a"
    return f"{value / 1e3:.1f} kN" if unit == "N" else f"{value:.2f} {unit}"


def _damaged(value, fallback):
    return fallback if value is None else value


def run_checks(case: Case, *, standard: str | None = None, tol: float | None = None,
               damaged: bool | None = None) -> CheckReport:
    """Check ``case`` intact and with each line removed in turn.

    Parameters
    ----------
    case : Case
    standard : str, optional
        ``api-rp-2sk`` or ``dnv-os-e301``; overrides ``case.checks.standard``.
    tol : float, optional
        Solver tolerance (see :func:`moorsolve.solve`).
    damaged : bool, optional
        Run the damaged conditions; overrides ``case.checks.damaged``.

    Returns
    -------
    CheckReport
    """
    checks = case.checks or Checks()
    if standard is not None:
        checks = dataclasses.replace(checks, standard=standard)
    run_damaged = checks.damaged if damaged is None else damaged
    t0 = time.perf_counter()
    simulate = sea_simulated(case, checks.standard)
    conditions = [_condition(case, checks, None, tol, simulate)]
    movable = any(b.free for b in case.bodies) or bool(case.free_points)
    if run_damaged and movable and len(case.legs) > 1:
        # With nothing free each line ends at fixed points: removing one leaves the others
        # unchanged, so there is no damaged condition to solve.
        for leg in case.legs:
            conditions.append(_condition(case, checks, leg.name, tol, simulate))
    intact = conditions[0].result
    fatigue = None
    if checks.fatigue is not None and intact is not None:
        from ..life.fatigue import fatigue as fatigue_of
        fatigue = fatigue_of(intact, checks.fatigue)
    return CheckReport(case_name=case.name, standard=checks.standard,
                       consequence_class=checks.consequence_class, checks=checks,
                       conditions=conditions, criteria=standard_rows(checks.standard),
                       time_s=time.perf_counter() - t0,
                       tolerance=case.solver.tol if tol is None else float(tol),
                       sea=bool(case.environment.waves is not None
                                and case.environment.waves.sea_state), fatigue=fatigue)


def _condition(case: Case, checks: Checks, removed: str | None, tol,
               simulate: bool = False) -> ConditionResult:
    kind = "intact" if removed is None else "damaged"
    name = "intact" if removed is None else f"damaged: {removed} removed"
    crit = criterion(checks.standard, kind, checks.consequence_class)
    scene = case if removed is None else without_line(case, removed)
    drifts = drifting_bodies(scene)
    if drifts:
        # What nothing holds is lost: say so, and check the rest with it held (no line
        # joins it to the rest, so holding it changes nothing there).
        scene = hold_drifting(scene, drifts)
    lost = {line for d in drifts for line in d.lines}
    try:
        result = solve(scene, tol=tol, allow_overload=True)
    except ConvergenceError as exc:
        return ConditionResult(name=name, kind=kind, removed=removed, solved=False,
                               reason=exc.reason, result=None, items=[], criterion=crit,
                               drifting=drift_findings(drifts, None))
    held = None
    if simulate:
        try:
            held = design_offset_solve(result, tol=tol)
        except (ConvergenceError, CaseError) as exc:
            if isinstance(exc, CaseError) and removed is None:
                raise       # the case's own sea state or hydrodynamics: bad input
            # A damaged scene whose motions cannot be had (no equilibrium with the mean
            # drift, a slow-drift mode the removed line held): not checked, so failed.
            why = exc.reason if isinstance(exc, ConvergenceError) else str(exc)
            return ConditionResult(name=name, kind=kind, removed=removed, solved=False,
                                   reason=f"the motions in the sea state: {why}", result=result,
                                   items=[], criterion=crit,
                                   drifting=drift_findings(drifts, result.loads),
                                   method="design offset")
    mean = result if held is None else held.mean
    at = result.legs if held is None else _by_name(held.held, scene.legs)
    items, lines = [], []
    for leg, lm, lr in zip(scene.legs, mean.legs, at):
        if leg.name in lost:
            continue        # it drifts off with its bodies: no tension to check
        if is_hawser(leg):
            items.append(_hawser(name, lr, leg))
            continue
        design = None
        if lr.mbl_N:
            end, design = (mean_tension(lr, crit) if held is None
                           else design_offset_tension(lm, lr, crit))
            lines.append({"leg": lr.name, "end": end, **design.to_dict()})
        # The item checks the same tension the line's design figures carry.
        items.append(_tension(name, lr, crit, at_offset=held is not None,
                              tension=None if design is None else design.t_max_N))
        if not leg.a.on_seabed:
            continue        # end A is not an anchor (a bridle leg, a shared line)
        anchor = leg.anchor_type or checks.anchor
        if anchor.kind != "suction":        # a suction anchor's envelope takes the uplift
            items.append(_uplift(name, lr, anchor))
        items += anchor_items(name, kind, leg, lm, lr, checks, crit)
        minimum = (checks.min_grounded_length if kind == "intact"
                   else _damaged(checks.min_grounded_length_damaged,
                                 checks.min_grounded_length))
        lt = leg.line_type
        bed = case.environment.seabed_z(leg.anchor[0], leg.anchor[1])   # sloped seabed
        on_seabed = leg.anchor[2] <= bed + 1e-9 and lt.weight_in_water > 0
        if minimum is not None and on_seabed:
            g = lr.grounded_length_m
            items.append(CheckItem(
                condition=name, leg=lr.name, check="grounded length", value=g,
                limit=minimum, unit="m",
                utilisation=(minimum / g if g > 0 else (math.inf if minimum > 0 else 0.0)),
                passed=g >= minimum, criterion=f"grounded length >= {minimum:.1f} m"))
        items += fibre_items(name, leg, lr)
    limit = (checks.offset_limit if kind == "intact"
             else _damaged(checks.offset_limit_damaged, checks.offset_limit))
    if limit is not None:
        design = {} if held is None else held.design_offset_m
        for body, entry in zip(scene.bodies, mean.bodies):
            if not body.free:
                continue        # held, or lost (held here, reported as drifting)
            off = entry["offset"]
            offset = design.get(body.name, math.hypot(off["x_m"], off["y_m"]))
            label = "offset" if len(scene.bodies) == 1 else f"offset of {body.name}"
            where = " (design offset)" if body.name in design else ""
            items.append(CheckItem(condition=name, leg=None, check=label, value=offset,
                                   limit=limit, unit="m", utilisation=offset / limit,
                                   passed=offset <= limit,
                                   criterion=f"horizontal offset{where} <= {limit:.2f} m"))
    items += [_fender(name, f) for f in result.fenders if f["rated_deflection_m"]]
    items += [_guide(name, g) for g in result.guides if g["pile_top_m"] is not None]
    return ConditionResult(name=name, kind=kind, removed=removed, solved=True, reason="",
                           result=mean, items=items, criterion=crit,
                           drifting=drift_findings(drifts, result.loads),
                           method="mean" if held is None else "design offset",
                           lines=tuple(lines),
                           design_offset_m={} if held is None else dict(held.design_offset_m),
                           held=None if held is None else held.held)


def _by_name(result: Result, legs) -> list:
    """``result``'s line results in the order of ``legs``."""
    found = {lr.name: lr for lr in result.legs}
    return [found[leg.name] for leg in legs]


def _hawser(condition: str, lr, line) -> CheckItem:
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


def _fender(condition: str, fender: dict) -> CheckItem:
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


def _guide(condition: str, guide: dict) -> CheckItem:
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


def _tension(condition: str, lr, crit: Criterion, at_offset: bool = False,
             tension: float | None = None) -> CheckItem:
    """The line's tension item: ``tension`` where the design figures give it (at the design
    offset, no less than the mean), else the larger end tension of ``lr``."""
    T = max(lr.fairlead_tension_N, lr.anchor_tension_N) if tension is None else tension
    if not lr.mbl_N:
        return CheckItem(condition=condition, leg=lr.name, check="tension", value=T,
                         limit=math.nan, unit="N", utilisation=math.inf, passed=False,
                         criterion="no MBL given for the line type: give mbl or a "
                                   "catalogue line")
    allowed = crit.capacity_factor * lr.mbl_N / crit.factor
    return CheckItem(condition=condition, leg=lr.name, check="tension", value=T,
                     limit=allowed, unit="N", utilisation=T / allowed, passed=T <= allowed,
                     criterion=crit.describe() + (" at the design offset" if at_offset else ""))


def _uplift(condition: str, lr, anchor: AnchorType) -> CheckItem:
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
