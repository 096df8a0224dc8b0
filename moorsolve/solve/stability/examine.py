"""The stability step of a solve: examine the certified point and, where it is unstable (or
where no point certified on the branch followed from rest under crossed loads), look for a
stable equilibrium: the stable heading of weathervaning bodies (:mod:`.weathervane`), else
the stable point reached from the unstable one (:func:`.static.find_stable`).
"""

from __future__ import annotations

import math

from ..kernels.polish import polish
from ..kernels.strategies import ran_out, rest_point
from .static import assess, find_stable
from .weathervane import WALKED, stable_heading, yaw_unknowns


def examine(attempt, problem, case, p, tol: float, deadline: float, walk: bool = True) -> None:
    """Set ``attempt.assessment`` (a :class:`~moorsolve.solve.result.Stability`), replacing
    an unstable point by a stable one where one is found, with a note saying so. ``walk``
    lets a point that did not certify be replaced by the stable heading of the bodies free
    in yaw (crossed wind and current can fold the branch the load stepping follows while
    the body has a stable heading elsewhere). ``deadline`` is the solve's time budget
    [s, ``time.perf_counter``]."""
    if not attempt.certified and walk:
        turned = heading_walk(problem, case, p, tol, attempt.stats, deadline)
        ran_out(attempt.stats, deadline, "the search for a stable heading")
        if turned is not None:
            attempt.x, attempt.assessment, note = turned
            attempt.notes.append("no equilibrium on the branch followed from rest; " + note)
            attempt.judge(problem, p, tol)
    if attempt.certified and attempt.assessment is None:
        x_found = attempt.x
        x, attempt.assessment, extra = stable_point(problem, case, x_found, p, tol,
                                                    attempt.stats, attempt.post, deadline)
        attempt.notes += extra
        if not attempt.assessment.stable and ran_out(attempt.stats, deadline,
                                                     "the search for a stable equilibrium"):
            attempt.notes.append(f"the time budget (solver.max_time_s = "
                                 f"{case.solver.max_time_s:g} s) ran out in the search for "
                                 "a stable equilibrium")
        if x is not x_found:
            attempt.x = x
            attempt.judge(problem, p, tol)


def stable_point(problem, case, x, p, tol, stats, post=None, deadline=None):
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
    turned = heading_walk(problem, case, p, tol, stats, deadline)
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


def heading_walk(problem, case, p, tol, stats, deadline=None):
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


__all__ = ["examine", "stable_point", "heading_walk"]
