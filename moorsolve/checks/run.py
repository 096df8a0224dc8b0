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

and per condition the horizontal offset of the body origin against the offset limit. In a
sea state in which bodies move, the uplift, grounded length and offset are those at the
bodies' design offset (:mod:`.design_offset`), and the tension's dynamic part comes from
the lines re-solved there (``checks.method: quasi_static``) or from the lines' own dynamics
(``dynamic``, :mod:`.dynamic`; each damaged condition's motions and line dynamics
re-computed with the line removed); without, the mean tension's, and the report says so. At a
berth (:mod:`.berth`) a hawser's tension is checked against the working load
limit of OCIMF MEG4 instead of the standard's factor, each fender's compression against its
rated deflection and each pile guide's height against its pile's top.
"""

from __future__ import annotations

import dataclasses
import math
import time

from ..errors import CaseError, ConvergenceError
from ..model import Case, Checks
from ..model.edit import without_line
from ..model.restraint import drifting_bodies
from ..solve import Result, solve
from .anchors import anchor_items
from .berth import is_hawser
from .criteria import criterion, standard_rows
from .design_offset import design_offset_solve, mean_tension, sea_method
from .drift import drift_findings, hold_drifting
from .dynamic import anchor_t_max, dynamic_tension, quasi_static_tension
from .fibre import fibre_items
from .items import (CheckItem, fender_item, guide_item, hawser_item, tension_item,
                    uplift_item)
from .outcome import CheckReport, ConditionResult, damaged_value

__all__ = ["run_checks", "CheckReport", "ConditionResult"]


def run_checks(case: Case, *, standard: str | None = None, tol: float | None = None,
               damaged: bool | None = None, method: str | None = None) -> CheckReport:
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
    method : {"quasi_static", "dynamic"}, optional
        How the dynamic part of the line tension is had in a sea state; overrides
        ``case.checks.method``.

    Returns
    -------
    CheckReport

    Raises
    ------
    CaseError
        Bad input of the intact scene (a dynamic method without a sea state, a line the
        line dynamics cannot model, a body floating free without hydrodynamics).
    """
    from ..model.build import check_analysis

    checks = case.checks or Checks()
    if standard is not None:
        checks = dataclasses.replace(checks, standard=standard)
    if method is not None:
        checks = dataclasses.replace(checks, method=method)
    check_analysis(dataclasses.replace(case, checks=checks))
    run_damaged = checks.damaged if damaged is None else damaged
    t0 = time.perf_counter()
    sea = sea_method(case, checks)
    conditions = [_condition(case, checks, None, tol, sea)]
    movable = any(b.free for b in case.bodies) or bool(case.free_points)
    if run_damaged and movable and len(case.legs) > 1:
        # With nothing free each line ends at fixed points: removing one leaves the others
        # unchanged, so there is no damaged condition to solve.
        for leg in case.legs:
            conditions.append(_condition(case, checks, leg.name, tol, sea))
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


def _failed(name, kind, removed, crit, drifts, result, why, method) -> ConditionResult:
    return ConditionResult(name=name, kind=kind, removed=removed, solved=False,
                           reason=f"the motions in the sea state: {why}", result=result,
                           items=[], criterion=crit,
                           drifting=drift_findings(drifts, result.loads), method=method)


def _condition(case: Case, checks: Checks, removed: str | None, tol,
               sea: str | None = None) -> ConditionResult:
    kind = "intact" if removed is None else "damaged"
    name = "intact" if removed is None else f"damaged: {removed} removed"
    cclass = checks.consequence_class
    crit = criterion(checks.standard, kind, cclass)
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
    held, tensions = None, None
    method = "mean" if sea is None else ("dynamic" if sea == "dynamic" else "design offset")
    if sea is not None:
        try:
            held = design_offset_solve(result, tol=tol)
            if held is not None and sea == "dynamic":
                from ..dynamics.line_sea import line_tensions
                tensions = line_tensions(held.motions,
                                         lines=[ln.name for ln in scene.lines
                                                if ln.name not in lost])
        except (ConvergenceError, CaseError) as exc:
            if isinstance(exc, CaseError) and removed is None:
                raise       # the case's own sea state, hydrodynamics or lines: bad input
            # A damaged scene whose motions cannot be had (no equilibrium with the mean
            # drift, a slow-drift mode the removed line held): not checked, so failed.
            why = exc.reason if isinstance(exc, ConvergenceError) else str(exc)
            return _failed(name, kind, removed, crit, drifts, result, why, method)
    if held is None:
        method = "mean"
    elif sea == "dynamic" and checks.standard == "api-rp-2sk":
        crit = criterion(checks.standard, kind, cclass, analysis="dynamic")
    mean = result if held is None else held.mean
    at = result.legs if held is None else _by_name(held.held, scene.legs)
    items, lines = [], []
    where = {"mean": "", "design offset": "at the design offset",
             "dynamic": "with line dynamics"}[method]
    for leg, lm, lr in zip(scene.legs, mean.legs, at):
        if leg.name in lost:
            continue        # it drifts off with its bodies: no tension to check
        if is_hawser(leg):
            items.append(hawser_item(name, lr, leg))
            continue
        design = None
        if lr.mbl_N:
            figures = {}
            if held is None:
                end, design = mean_tension(lr, crit)
            elif tensions is not None and leg.name in tensions:
                end, design, stats = dynamic_tension(
                    lm, tensions[leg.name], standard=checks.standard, condition=kind,
                    consequence_class=cclass)
                figures = {"dynamic": stats.to_dict()}
            else:
                end, design = quasi_static_tension(
                    lm, lr, standard=checks.standard, condition=kind,
                    consequence_class=cclass)
            lines.append({"leg": lr.name, "end": end, **design.to_dict(), **figures})
        # The item checks the same tension the line's design figures carry.
        items.append(tension_item(name, lr, crit, design, where))
        if leg.a.on_seabed:     # else end A is not an anchor (a bridle leg, a shared line)
            t_anchor = (anchor_t_max(lm, tensions[leg.name], checks.standard)
                        if tensions is not None and leg.name in tensions else None)
            items += _seabed_items(case, checks, kind, name, leg, lm, lr, crit, t_anchor)
            items += fibre_items(name, leg, lr)
    limit = (checks.offset_limit if kind == "intact"
             else damaged_value(checks.offset_limit_damaged, checks.offset_limit))
    if limit is not None:
        design = {} if held is None else held.design_offset_m
        for body, entry in zip(scene.bodies, mean.bodies):
            if not body.free:
                continue        # held, or lost (held here, reported as drifting)
            off = entry["offset"]
            offset = design.get(body.name, math.hypot(off["x_m"], off["y_m"]))
            label = "offset" if len(scene.bodies) == 1 else f"offset of {body.name}"
            shown = " (design offset)" if body.name in design else ""
            items.append(CheckItem(condition=name, leg=None, check=label, value=offset,
                                   limit=limit, unit="m", utilisation=offset / limit,
                                   passed=offset <= limit,
                                   criterion=f"horizontal offset{shown} <= {limit:.2f} m"))
    items += [fender_item(name, f) for f in result.fenders if f["rated_deflection_m"]]
    items += [guide_item(name, g) for g in result.guides if g["pile_top_m"] is not None]
    return ConditionResult(name=name, kind=kind, removed=removed, solved=True, reason="",
                           result=mean, items=items, criterion=crit,
                           drifting=drift_findings(drifts, result.loads), method=method,
                           lines=tuple(lines),
                           design_offset_m={} if held is None else dict(held.design_offset_m),
                           held=None if held is None else held.held,
                           sea=None if held is None else held, tensions=tensions)


def _seabed_items(case, checks, kind, name, leg, lm, lr, crit, t_anchor=None) -> list:
    """The anchor's uplift and capacity (where its design is given) and the grounded length
    of a line anchored on the seabed; ``lm`` the line at the mean position, ``lr`` where it
    is checked, ``t_anchor`` the anchor end's largest tension from the lines' dynamics
    (None: ``lr``'s)."""
    anchor = leg.anchor_type or checks.anchor
    # A suction anchor's H-V envelope takes the uplift.
    items = [] if anchor.kind == "suction" else [uplift_item(name, lr, anchor)]
    items += anchor_items(name, kind, leg, lm, lr, checks, crit, tension=t_anchor)
    minimum = (checks.min_grounded_length if kind == "intact"
               else damaged_value(checks.min_grounded_length_damaged,
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
    return items


def _by_name(result: Result, legs) -> list:
    """``result``'s line results in the order of ``legs``."""
    found = {lr.name: lr for lr in result.legs}
    return [found[leg.name] for leg in legs]
