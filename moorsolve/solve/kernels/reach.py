"""How a solve reaches its first point, and the :class:`Attempt` its steps pass on.

The first point is, in this order: the lines' remembered answer (a scene with nothing free
whose lines' state certifies as it stands: no solver called), the compiled Newton kernel's
strategy (when asked for), IPOPT's strategy, and where a scene with contacts or hawsers did
not certify under IPOPT (a smooth NLP solver), the semismooth Newton path built for their
complementarities (:func:`newton_fallback`). The point is then judged against the
certificate (:meth:`Attempt.judge`); the stability step
(:mod:`moorsolve.solve.stability.examine`) may replace it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..result.diagnosis import START_CERTIFIED
from .strategies import ipopt_strategy, judge_point, newton_strategy, remembered_answer

#: IPOPT's return statuses that are failures even when the point happens to certify.
FAILED_STATUSES = ("Infeasible_Problem_Detected", "Restoration_Failed",
                   "Error_In_Step_Computation", "Invalid_Number_Detected",
                   "Not_Enough_Degrees_Of_Freedom", "Invalid_Problem_Definition",
                   "Invalid_Option", "Unrecoverable_Exception", "NonIpopt_Exception_Thrown",
                   "Insufficient_Memory", "Internal_Error")


@dataclass
class Attempt:
    """A solve's current point and what is known of it, passed from step to step.

    Attributes
    ----------
    x : numpy.ndarray
        The scaled unknowns.
    used : str
        The solver that produced ``x`` (``"ipopt"`` or ``"newton"``).
    stats : dict
        The solver status (``"status"``), the iterations and the polish steps so far.
    notes : list of str
        What the Result will say of how ``x`` was reached.
    post : dict
        :meth:`EquilibriumProblem.post` at ``x`` (certificate, stiffness, report arrays).
    certified : bool
        Whether ``x`` passes the certificate.
    force_N, moment_Nm, relative : float
        The certificate's residuals [N], [N m] and the force residual relative to the
        largest line tension [-].
    assessment : Stability or None
        The stability of ``x``, once examined.
    """

    x: np.ndarray
    used: str
    stats: dict
    notes: list = field(default_factory=list)
    post: dict | None = None
    certified: bool = False
    force_N: float = math.inf
    moment_Nm: float = math.inf
    relative: float = math.inf
    assessment: object = None

    def judge(self, problem, p, tol: float, post: dict | None = None) -> None:
        """Evaluate ``post`` at ``x`` (unless given) and the certificate from it."""
        self.post = problem.post(finite(self.x), p) if post is None else post
        self.certified, self.force_N, self.moment_Nm, self.relative = judge_point(
            problem, self.x, self.post, tol)


def reach(problem, case, kernel, p, tol: float, start, t0: float,
          remembered: bool = True) -> Attempt:
    """The first point of a solve, judged: the remembered answer (where ``remembered``),
    else the Newton kernel's strategy (where ``kernel`` is given), else IPOPT's, with the
    Newton fallback for contacts; ``t0`` is the solve's start: IPOPT's time budget, and the
    Newton paths stop at ``t0 + case.solver.max_time_s``."""
    stats = dict(iterations=0, status="not run")
    notes = []
    x, post = (remembered_answer(problem, case, p, tol, start) if remembered
               else (None, None))
    used = "ipopt"
    if x is not None:
        stats["status"] = START_CERTIFIED
        used = "ipopt" if kernel is None else "newton"    # the solver asked for; none ran
    elif kernel is not None:
        x, notes = newton_strategy(problem, case, kernel, p, tol, start, stats,
                                   t0 + case.solver.max_time_s)
        used = "newton" if x is not None else "ipopt"
    if x is None:
        x = ipopt_strategy(problem, case, p, tol, start, stats, t0)
        if problem.smoothed and kernel is None and not problem.certify(x, p, tol)[0]:
            x, used = newton_fallback(problem, case, x, p, tol, start, stats, notes,
                                      t0 + case.solver.max_time_s)
    attempt = Attempt(x=x, used=used, stats=stats, notes=notes)
    attempt.judge(problem, p, tol, post)
    if attempt.certified and stats["status"] in FAILED_STATUSES:
        notes.append(f"IPOPT ended with {stats['status']} but the point certifies: the "
                     "certificate, recomputed from the solution, is what is reported")
    return attempt


def newton_fallback(problem, case, x, p, tol: float, start, stats: dict,
                    notes: list, deadline: float | None = None) -> tuple:
    """Contacts and hawsers: where IPOPT (a smooth NLP solver) does not certify, the
    semismooth Newton path built for them gets its turn. ``(x, solver used)``: the Newton
    path's point where it certifies (with a note), else IPOPT's ``x``; it stops at
    ``deadline`` [s, ``time.perf_counter``]."""
    x_newton, _ = newton_strategy(problem, case, problem.newton(), p, tol, start, stats,
                                  deadline)
    if x_newton is None:
        return x, "ipopt"
    notes.append("IPOPT did not certify this point; the Newton path did "
                 "(semismooth Newton on the contacts' complementarities)")
    return x_newton, "newton"


def finite(x: np.ndarray) -> np.ndarray:
    """``x`` with any non-finite entry replaced by 0 (for reporting a failed point)."""
    return x if np.isfinite(x).all() else np.where(np.isfinite(x), x, 0.0)


__all__ = ["Attempt", "reach", "newton_fallback", "finite", "FAILED_STATUSES"]
