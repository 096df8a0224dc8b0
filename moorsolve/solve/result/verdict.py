"""The verdict of a solve on its point: the certificate a Result carries, the refusals
(:class:`~moorsolve.errors.ConvergenceError`: not certified, outside the models' range,
overloaded) and the modelling warnings.

A point that is not certified is refused with the physical reason found by
:func:`.diagnosis.diagnose` and the best residual reached.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ...audit import result_warnings
from ...errors import ConvergenceError
from ..assembly.prepared import line_facts
from ..assembly.problem import LINE_COLUMNS
from ..kernels.strategies import budget_status
from .classes import Certificate
from .diagnosis import (SUCCESS_STATUSES, diagnose, over_mbl, over_rated, pulled_straight,
                        unbalanced_force)
from .outcome import hull_out_of_range


def out_of_range(problem, case, attempt, p) -> list:
    """What puts a certified point outside the models' range (a hull moved out of its
    hydrostatics, an inextensible line pulled straight), as sentences; ``[]`` for a point
    that did not certify (it is refused for that)."""
    if not attempt.certified:
        return []
    return (hull_out_of_range(problem, attempt.x, p, attempt.post)
            + pulled_straight(problem, case, attempt.post))


def certificate(problem, attempt, p, tol: float, t0: float, max_time_s: float) -> Certificate:
    """The certificate of ``attempt``'s point, its solver status explained where it is not
    a success but the point certifies, or the path where the time budget ``max_time_s`` [s]
    ran out where it did not; ``t0`` is the solve's start [s, ``time.perf_counter``]."""
    elapsed = time.perf_counter() - t0
    stats = attempt.stats
    stats["status"] = explain_status(stats["status"], attempt.certified,
                                     stats.get("polish_steps", 0))
    if not attempt.certified and "out_of_time" in stats:
        stats["status"] = budget_status(stats, max_time_s, elapsed)
    return Certificate(force_N=attempt.force_N, moment_Nm=attempt.moment_Nm,
                       relative=attempt.relative, tolerance=tol, status=stats["status"],
                       iterations=stats["iterations"], solve_time_s=elapsed,
                       **problem.contact_certificate(attempt.x, p))


def explain_status(status: str, certified: bool, polish_steps: int) -> str:
    """The solver status a result reports: the solver's own, explained when it is not a
    success but the point certifies (a certified point is an equilibrium whatever the
    solver's stopping reason: the certificate is recomputed from it)."""
    if not certified or status in SUCCESS_STATUSES:
        return status
    how = (f"after {polish_steps} Newton polish step{'s' if polish_steps != 1 else ''}"
           if polish_steps else "as the solver left it")
    return f"{status}; the point reached is certified {how}"


def refuse(problem, case, result, attempt, p, outside: list, allow_overload: bool) -> None:
    """Raise :class:`ConvergenceError` (carrying ``result``) for a point that did not
    certify (with the reason found), one outside the models' range (``outside``), or one
    at which a line passes its breaking load or a fender its rated deflection (unless
    ``allow_overload``); return for a sound point."""
    force_N, moment_Nm = attempt.force_N, attempt.moment_Nm
    status, iterations = attempt.stats["status"], attempt.stats["iterations"]
    if not attempt.certified:
        if not math.isfinite(force_N):
            # A line whose span cannot be closed by a finite force (an inextensible line
            # pulled straight): report the largest unbalanced force on the bodies instead.
            force_N = unbalanced_force(problem, result.state, p)
        reason = diagnose(problem, case, result)
        if "out_of_time" in attempt.stats:
            reason = (f"{status}; give it longer with solver.max_time_s (where it "
                      f"stopped: {reason})")
        raise ConvergenceError(reason, residual_N=force_N,
                               residual_Nm=moment_Nm, status=status,
                               iterations=iterations, result=result)
    if outside:
        raise ConvergenceError("; ".join(outside), residual_N=force_N,
                               residual_Nm=moment_Nm, status=status,
                               iterations=iterations, result=result)
    broken = over_mbl(result, problem, attempt.post) + over_rated(result)
    if broken and not allow_overload:
        raise ConvergenceError(
            "overload: " + "; ".join(broken) + " (the mooring cannot hold this; to accept "
            "the equilibrium anyway pass allow_overload=True, or --allow-overload)",
            residual_N=force_N, residual_Nm=moment_Nm, status=status,
            iterations=iterations, result=result)


def with_warnings(result, case, problem, post):
    """``result`` with its modelling warnings (:func:`~moorsolve.audit.result_warnings`)."""
    if not _may_warn(problem, case, post):
        return result
    return dataclasses.replace(result, warnings=tuple(result_warnings(result, case)))


# An index array (a list would be converted at every call).
_WARN_COLUMNS = np.array([LINE_COLUMNS.index(c) for c in ("floating", "az", "bz")])


def _may_warn(problem, case, post) -> bool:
    """Whether :func:`~moorsolve.audit.result_warnings` can find anything: False, from the
    arrays alone, for one-segment lines of unsealed types that neither float nor have an
    end above the water (so their legs and profiles need not be made to find nothing)."""
    if not problem.all_single or line_facts(case).sealed:
        return True
    table = post["lines"]
    return bool(np.take(table, _WARN_COLUMNS, axis=table.ndim - 1).max(initial=0.0) > 0)


__all__ = ["out_of_range", "certificate", "explain_status", "refuse", "with_warnings"]
