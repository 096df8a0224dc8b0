"""Newton polish: a few damped Newton steps that take a solver's point to the certificate's
digits (IPOPT stops at its own tolerance on a scaled problem; the certificate is exact)."""

from __future__ import annotations

import casadi as ca
import numpy as np

from .newton import FLAT, STEP_LIMIT

__all__ = ["polish", "polish_certified"]

#: Most Newton steps of one polish.
_POLISH_STEPS = 30


def polish(problem, x, p, lb, ub, stats, tol):
    """Newton steps on the square residual system until the point certifies at ``tol``,
    kept only while they reduce the residual (with complementarities, as the compiled
    kernel: a step along the exact direction that does not grow it where the smoothed one
    finds no descent; :mod:`.newton`)."""
    return polish_certified(problem, x, p, lb, ub, stats, tol)[0]


def polish_certified(problem, x, p, lb, ub, stats, tol) -> tuple:
    """:func:`polish`, and whether its point certifies: ``(x, certified)``, the verdict
    of :meth:`EquilibriumProblem.certify` at that very ``x`` (computed once, compiled
    where IPOPT's functions are: :meth:`.ipopt_solvers.IpoptSolvers.certify`; callers need
    not certify it again)."""
    if not np.all(np.isfinite(x)):
        return x, False
    certify = problem.ipopt_solvers.certify
    # Certified as the solver left it (the usual case): no residual to evaluate.
    if certify(x, p, tol):
        return x, True
    g = np.asarray(problem.residual(x, p)).ravel()
    norm = np.max(np.abs(g)) if g.size else 0.0
    for _ in range(_POLISH_STEPS):
        # Stop once certified (below). Not on a merely small residual: where a span
        # depends on a tension only to second order (a fairlead on the seabed: Z ~ V^2)
        # Newton halves the tension's error per step while the residual is already below
        # 1e-15.
        if norm == 0.0:
            break
        J = problem.step_jacobian(x, p, g)
        if not (np.all(np.isfinite(J)) and np.all(np.isfinite(g))):
            break           # absurd input (a 1e30 coefficient): nothing to polish
        found = _search(problem, x, p, g, norm, lb, ub, J, flat=False, tries=6)
        if found is None and problem.smoothed:
            spring = max(problem.REGULARISATION, float(np.max(np.abs(g))))
            J = np.asarray(problem.jacobian(x, p)) - np.asarray(
                ca.densify(problem.regularisation(spring)))
            found = _search(problem, x, p, g, norm, lb, ub, J, flat=True, tries=24)
        stats["iterations"] += 1
        stats["polish_steps"] = stats.get("polish_steps", 0) + 1
        if found is None:
            break
        x, g, norm = found
        if certify(x, p, tol):
            return x, True
    return x, False


def _search(problem, x, p, g, norm, lb, ub, J, *, flat: bool, tries: int):
    """Backtracking along the Newton step of ``J``: ``(x, g, |g|)`` where the residual
    fell (or, with ``flat``, did not grow), else None."""
    try:
        step = np.linalg.solve(J, g)
    except np.linalg.LinAlgError:
        try:
            step, *_ = np.linalg.lstsq(J, g, rcond=None)
        except np.linalg.LinAlgError:
            return None
    if flat:
        step = step * min(1.0, STEP_LIMIT / max(float(np.max(np.abs(step))), 1e-300))
    alpha = 1.0
    for _ in range(tries):
        x_new = np.clip(x - alpha * step, lb, ub)
        g_new = np.asarray(problem.residual(x_new, p)).ravel()
        n_new = np.max(np.abs(g_new))
        if np.isfinite(n_new) and (n_new < norm or (flat and n_new <= (1 + FLAT) * norm
                                                    and np.any(x_new != x))):
            return x_new, g_new, n_new
        alpha *= 0.5
    return None
