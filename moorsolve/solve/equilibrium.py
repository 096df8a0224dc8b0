"""Run the equilibrium solve, certify it, check its stability, and return a :class:`Result`.

Strategy, from the pitfalls measured on hard cases:

1. Start every line from its inextensible closed-form state at the case-file pose and
   solve the unloaded (pretensioned rest) state first; a start with all lines slack would
   give a singular Jacobian, and the rest state keeps a body on the right equilibrium
   branch (not yawed round with lines crossing under the hull).
2. Solve the loaded state from the rest state with IPOPT (or the compiled Newton kernel).
3. If that fails, or turns a body far from rest, step the load up from rest in increments,
   warm-starting each step.
4. Polish with Newton steps on the same residuals (the problem is square), then recompute
   the residuals from the solution and certify them against the tolerance.
5. Examine the stability of the certified point (:mod:`.stability`); where it is unstable,
   look for a stable equilibrium and return that one, or say that only an unstable one
   was found.

A point that is not certified raises :class:`ConvergenceError` with the physical reason
found by :func:`.diagnosis.diagnose` and the best residual reached (step 4 in
:mod:`.polish`).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time

import numpy as np

from ..errors import ConvergenceError
from ..model import Case
from .bathymetry import plane_slices, point_plane_slices, solve_on_grid
from .cache import get_problem
from .diagnosis import (START_CERTIFIED, SUCCESS_STATUSES, diagnose, over_mbl, over_rated,
                        pulled_straight, unbalanced_force)
from ..audit import audit as audit_result
from ..audit import result_warnings
from .outcome import build_result, hull_out_of_range
from .polish import polish
from .prepared import line_facts
from .problem import LINE_COLUMNS
from .result import Certificate, Result
from .stability import assess, find_stable
from .start import initial_point
from .strategies import (YAW_JUMP, budget_status, ipopt_strategy, judge_point,
                         newton_strategy, ran_out, remember_lines, remembered_answer,
                         rest_point, turn_jump, turn_jumps)
from .weathervane import WALKED, stable_heading, yaw_unknowns

log = logging.getLogger(__name__)

SOLVERS = ("ipopt", "newton")

#: IPOPT's return statuses that are failures even when the point happens to certify.
_FAILED_STATUSES = ("Infeasible_Problem_Detected", "Restoration_Failed",
                    "Error_In_Step_Computation", "Invalid_Number_Detected",
                    "Not_Enough_Degrees_Of_Freedom", "Invalid_Problem_Definition",
                    "Invalid_Option", "Unrecoverable_Exception", "NonIpopt_Exception_Thrown",
                    "Insufficient_Memory", "Internal_Error")


def solve(case: Case, *, tol: float | None = None, solver: str = "ipopt",
          allow_overload: bool = False, start: np.ndarray | None = None,
          stability: bool = True, audit: bool | str = True, _planes=None) -> Result:
    """Static equilibrium of ``case``, certified.

    Parameters
    ----------
    case : Case
        From :func:`moorsolve.load_case`.
    tol : float, optional
        Largest force residual allowed, relative to the largest line tension; defaults to
        the case's ``solver.tol`` (1e-9).
    solver : {"ipopt", "newton"}
        ``"ipopt"`` (the default and the reference) or the compiled Newton fast path
        (:mod:`moorsolve.solve.newton`), which falls back to the IPOPT strategy when it
        does not certify; ``Result.solver`` tells which produced the result.
    allow_overload : bool
        Return an equilibrium in which a line exceeds its minimum breaking load, or a fender
        its rated deflection, instead of raising ConvergenceError (for damaged-condition
        checks that must report it).
    start : numpy.ndarray, optional
        A previous ``Result.state`` of the same scene structure to warm-start from.
    stability : bool
        Examine the stability of the equilibrium and, where it is unstable, look for a
        stable one (the default). ``False`` returns the first certified point without that
        examination (``Result.stability`` is then None), for sweeps that only want numbers.
    audit : bool or "full"
        Check the reported quantities independently before returning
        (:mod:`moorsolve.audit`; the default). One-segment lines on a flat seabed are
        audited in closed form from their reported end positions and forces
        (:mod:`moorsolve.audit.closed_form`); other scenes by drawing every line's
        profile, which costs a few times a compiled Newton solve. ``"full"`` runs the
        profile audit on every scene as well; ``False`` skips the audit for loops that need
        the speed (the certificate, the stability check and the warnings stay).

    Returns
    -------
    Result

    Raises
    ------
    ConvergenceError
        No certified equilibrium; carries the physical reason and the best residual.

    Notes
    -----
    Safe to call from many threads at once: the solvers of one problem are used by one
    thread at a time (:attr:`EquilibriumProblem.lock`); different problems run in parallel.
    On a bathymetry grid the solve is repeated until every line's seabed plane settles
    (:mod:`moorsolve.solve.bathymetry`); ``_planes`` is one round's planes.
    """
    if solver not in SOLVERS:
        raise ValueError(f"solver {solver!r}: must be one of {', '.join(SOLVERS)}")
    opts = case.solver
    tol = opts.tol if tol is None else tol
    problem = get_problem(case)
    if case.environment.seabed.bathymetry is not None and _planes is None:
        def once(planes, warm):
            return solve(case, tol=tol, solver=solver, allow_overload=allow_overload,
                         start=warm, stability=stability, audit=False, _planes=planes)
        result = solve_on_grid(case, problem.kinds, once, start)
        if audit:
            audit_result(result, case)
        return result
    p_full = problem.parameters(case, 1.0)
    if _planes is not None:
        for where, plane in zip(plane_slices(problem) + point_plane_slices(problem), _planes):
            p_full[where] = plane
    if start is not None and np.shape(start) != (problem.n_x,):
        start = None
    with problem.lock:
        # Building (and compiling) belongs to the problem, not to this solve's time.
        kernel = problem.newton() if solver == "newton" else None
        t0 = time.perf_counter()
        stats = dict(iterations=0, status="not run")
        notes = []
        x, post = (remembered_answer(problem, case, p_full, tol, start) if _planes is None
                   else (None, None))
        used = solver if x is not None else "ipopt"
        if x is not None:
            stats["status"] = START_CERTIFIED
        elif kernel is not None:
            x, notes = newton_strategy(problem, case, kernel, p_full, tol, start, stats,
                                       t0 + opts.max_time_s)
            used = "newton" if x is not None else "ipopt"
        if x is None:
            x = ipopt_strategy(problem, case, p_full, tol, start, stats, t0)
            if problem.smoothed and kernel is None and not problem.certify(x, p_full, tol)[0]:
                # Contacts and hawsers: where IPOPT (a smooth NLP solver) does not certify,
                # the semismooth Newton path built for them gets its turn.
                x_newton, extra = newton_strategy(problem, case, problem.newton(), p_full,
                                                   tol, start, stats, t0 + opts.max_time_s)
                if x_newton is not None:
                    x, used = x_newton, "newton"
                    notes.append("IPOPT did not certify this point; the Newton path did "
                                 "(semismooth Newton on the contacts' complementarities)")
        # One evaluation gives the certificate, the stiffness and every reported array.
        post = problem.post(_finite(x), p_full) if post is None else post
        certified, force_res, moment_res, relative = judge_point(problem, x, post, tol)
        failed_status = stats["status"] in _FAILED_STATUSES
        if certified and failed_status:
            notes.append(f"IPOPT ended with {stats['status']} but the point certifies: the "
                         "certificate, recomputed from the solution, is what is reported")
        assessment = None
        if not certified and stability and _planes is None:
            # Crossed wind and current can fold the branch the load stepping follows
            # (no equilibrium near it) while the body has a stable heading elsewhere.
            turned = _weathervane(problem, case, p_full, tol, stats,
                                  t0 + case.solver.max_time_s)
            ran_out(stats, t0 + opts.max_time_s, "the search for a stable heading")
            if turned is not None:
                x, assessment, note = turned
                notes.append("no equilibrium on the branch followed from rest; " + note)
                post = problem.post(_finite(x), p_full)
                certified, force_res, moment_res, relative = judge_point(problem, x, post, tol)
        if certified and stability and assessment is None:
            x_found = x
            x, assessment, extra = _stable_point(problem, case, x, p_full, tol, stats, post,
                                                 t0 + case.solver.max_time_s)
            notes += extra
            if not assessment.stable and ran_out(stats, t0 + opts.max_time_s,
                                                 "the search for a stable equilibrium"):
                notes.append(f"the time budget (solver.max_time_s = {opts.max_time_s:g} s) "
                             "ran out in the search for a stable equilibrium")
            if x is not x_found:
                post = problem.post(_finite(x), p_full)
                certified, force_res, moment_res, relative = judge_point(problem, x, post, tol)
        outside = (hull_out_of_range(problem, x, p_full, post)
                   + pulled_straight(problem, case, post)) if certified else []
        if certified and not outside and not problem.n_q and _planes is None:
            remember_lines(problem, case, x)
        elapsed = time.perf_counter() - t0
        stats["status"] = explain_status(stats["status"], certified,
                                         stats.get("polish_steps", 0))
        if not certified and "out_of_time" in stats:
            stats["status"] = budget_status(stats, opts.max_time_s, elapsed)
        cert = Certificate(force_N=force_res, moment_Nm=moment_res, relative=relative,
                           tolerance=tol, status=stats["status"],
                           iterations=stats["iterations"], solve_time_s=elapsed,
                           **problem.contact_certificate(x, p_full))
        result = build_result(problem, case, x, p_full, cert, certified, used, notes,
                              assessment, post)
    if not certified:
        if not math.isfinite(force_res):
            # A line whose span cannot be closed by a finite force (an inextensible line
            # pulled straight): report the largest unbalanced force on the bodies instead.
            force_res = unbalanced_force(problem, result.state, p_full)
        reason = diagnose(problem, case, result)
        if "out_of_time" in stats:
            reason = (f"{stats['status']}; give it longer with solver.max_time_s (where it "
                      f"stopped: {reason})")
        raise ConvergenceError(reason, residual_N=force_res,
                               residual_Nm=moment_res, status=stats["status"],
                               iterations=stats["iterations"], result=result)
    if outside:
        raise ConvergenceError("; ".join(outside), residual_N=force_res,
                               residual_Nm=moment_res, status=stats["status"],
                               iterations=stats["iterations"], result=result)
    broken = over_mbl(result, problem, post) + over_rated(result)
    if broken and not allow_overload:
        raise ConvergenceError(
            "overload: " + "; ".join(broken) + " (the mooring cannot hold this; to accept "
            "the equilibrium anyway pass allow_overload=True, or --allow-overload)",
            residual_N=force_res, residual_Nm=moment_res, status=stats["status"],
            iterations=stats["iterations"], result=result)
    if assessment is not None and not assessment.stable:
        log.warning("%s: only an unstable equilibrium was found (unstable in %s)",
                    case.name, ", ".join(assessment.unstable_dofs) or "a coupled mode")
    # An independent check of what is reported (raises AuditFailure), and the warnings.
    if audit:
        audit_result(result, case, problem, post, full=audit == "full")
    if not _may_warn(problem, case, post):
        return result
    return dataclasses.replace(result, warnings=tuple(result_warnings(result, case)))


# An index array (a list would be converted at every call).
_WARN_COLUMNS = np.array([LINE_COLUMNS.index(c) for c in ("floating", "az", "bz")])


def _may_warn(problem, case, post) -> bool:
    """Whether :func:`~.audit.result_warnings` can find anything: False, from the arrays
    alone, for one-segment lines of unsealed types that neither float nor have an end
    above the water (so their legs and profiles need not be made to find nothing)."""
    if not problem.all_single or line_facts(case).sealed:
        return True
    table = post["lines"]
    return bool(np.take(table, _WARN_COLUMNS, axis=table.ndim - 1).max(initial=0.0) > 0)


#: Solver statuses that are a success in their own terms (IPOPT's and the Newton kernel's).


def explain_status(status: str, certified: bool, polish_steps: int) -> str:
    """The solver status a result reports: the solver's own, explained when it is not a
    success but the point certifies (a certified point is an equilibrium whatever the
    solver's stopping reason: the certificate is recomputed from it)."""
    if not certified or status in SUCCESS_STATUSES:
        return status
    how = (f"after {polish_steps} Newton polish step{'s' if polish_steps != 1 else ''}"
           if polish_steps else "as the solver left it")
    return f"{status}; the point reached is certified {how}"


def _finite(x: np.ndarray) -> np.ndarray:
    """``x`` with any non-finite entry replaced by 0 (for reporting a failed point)."""
    return x if np.isfinite(x).all() else np.where(np.isfinite(x), x, 0.0)


def _stable_point(problem, case, x, p, tol, stats, post=None, deadline=None):
    """The stability of ``x``; where unstable, a stable equilibrium if one is found.
    ``post`` (:meth:`EquilibriumProblem.post` at ``x``) gives the condensed stiffness and
    the kernel's stability test when the caller has it.

    Returns ``(x, Stability, notes)``.
    """
    assessment = assess(problem, x, p, None if post is None else post["stiffness"],
                        post is not None and post["clearly_stable"].item() > 0.5)
    if assessment.stable:
        return x, assessment, []
    lb, ub = problem.bounds()
    turned = _weathervane(problem, case, p, tol, stats, deadline)
    if turned is not None:
        x_new, stable, note = turned
        return x_new, stable, [
            "the equilibrium first found was unstable (in "
            f"{', '.join(assessment.unstable_dofs) or 'a coupled mode'}); " + note]
    found = find_stable(problem, x, p, tol, assessment,
                        lambda z: polish(problem, z, p, lb, ub, stats, tol), deadline)
    if found is not None:
        x_new, stable = found
        return x_new, stable, [
            "the equilibrium first found was unstable (in "
            f"{', '.join(assessment.unstable_dofs) or 'a coupled mode'}); the stable one "
            "reached from it is reported"]
    return x, assessment, [
        "only an unstable equilibrium was found (unstable in "
        f"{', '.join(assessment.unstable_dofs) or 'a coupled mode'}): a small disturbance "
        "moves the body away from it"]


def _weathervane(problem, case, p, tol, stats, deadline=None):
    """The stable heading the weathervaning bodies reach from their case-file heading
    under the full load (:mod:`.weathervane`): ``(x, Stability, note)``, or None (no body
    free in yaw, or none found before ``deadline``, the solve's time budget)."""
    if not yaw_unknowns(problem):
        return None
    lb, ub = problem.bounds()
    x_rest = rest_point(problem, case, tol)
    found = stable_heading(problem, x_rest, p, tol,
                           lambda z: polish(problem, z, p, lb, ub, stats, tol), deadline)
    if found is None:
        return None
    x, stable, walked = found
    yaws = yaw_unknowns(problem)
    turns = ", ".join(
        f"{problem.case.bodies[problem.nodes[j][1]].name} turned {turn:+.1f} deg to "
        f"{math.degrees(x[j] * problem.x_scale[j]):.1f} deg" for j, turn in zip(yaws, walked))
    stats["status"] = WALKED
    return x, stable, (
        f"the stable heading reached by turning from the case heading the way the load "
        f"turns the body is reported ({turns}; other stable headings may exist: this is "
        "the one the body swings to from its case heading)")


# ---- polish and certificate -----------------------------------------------------------


__all__ = ["solve", "rest_point", "turn_jump", "turn_jumps", "polish", "get_problem",
           "initial_point",
           "SOLVERS", "YAW_JUMP"]
