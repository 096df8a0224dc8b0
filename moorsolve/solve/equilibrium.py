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
5. Examine the stability of the certified point (:mod:`.stability.static`); where it is
   unstable, look for a stable equilibrium and return that one, or say that only an
   unstable one was found.

A point that is not certified raises :class:`ConvergenceError` with the physical reason
found by :func:`.result.diagnosis.diagnose` and the best residual reached (step 4 in
:mod:`.kernels.polish`).

:func:`solve` is these steps in order, each a named function in its room: the first point
(:func:`.kernels.reach.reach`: the remembered answer, the chosen solver's strategy, the
Newton fallback for contacts), the stability step (:func:`.stability.examine.examine`),
the verdict (:mod:`.result.verdict`: the certificate, the refusals), the Result
(:func:`.result.outcome.build_result`), the independent audit (:func:`moorsolve.audit.audit`)
and the warnings (:func:`.result.verdict.with_warnings`).
"""

from __future__ import annotations

import logging
import time

import numpy as np

from ..audit import audit as audit_result
from ..model import Case
from .assembly.cache import get_problem
from .kernels.polish import polish
from .kernels.reach import reach
from .kernels.start import initial_point
from .kernels.strategies import YAW_JUMP, remember_lines, rest_point, turn_jump, turn_jumps
from .lines.bathymetry import plane_slices, point_plane_slices, solve_on_grid
from .result.classes import Result
from .result.outcome import build_result
from .result.verdict import certificate, out_of_range, refuse, with_warnings
from .stability.examine import examine

log = logging.getLogger(__name__)

SOLVERS = ("ipopt", "newton")


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
        (:mod:`moorsolve.solve.kernels.newton`), which falls back to the IPOPT strategy
        when it does not certify; ``Result.solver`` tells which produced the result.
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
    (:mod:`moorsolve.solve.lines.bathymetry`); ``_planes`` is one round's planes.
    """
    if solver not in SOLVERS:
        raise ValueError(f"solver {solver!r}: must be one of {', '.join(SOLVERS)}")
    tol = case.solver.tol if tol is None else tol
    problem = get_problem(case)
    if case.environment.seabed.bathymetry is not None and _planes is None:
        return _on_grid(case, problem, tol=tol, solver=solver, allow_overload=allow_overload,
                        start=start, stability=stability, audit=audit)
    p = _parameters(problem, case, _planes)
    if start is not None and np.shape(start) != (problem.n_x,):
        start = None
    with problem.lock:
        # Building (and compiling) belongs to the problem, not to this solve's time.
        kernel = problem.newton() if solver == "newton" else None
        t0 = time.perf_counter()
        attempt = reach(problem, case, kernel, p, tol, start, t0, remembered=_planes is None)
        if stability:
            examine(attempt, problem, case, p, tol, t0 + case.solver.max_time_s,
                    walk=_planes is None)
        outside = out_of_range(problem, case, attempt, p)
        if attempt.certified and not outside and not problem.n_q and _planes is None:
            remember_lines(problem, case, attempt.x)
        result = build_result(problem, case, attempt.x, p,
                              certificate(problem, attempt, p, tol, t0,
                                          case.solver.max_time_s), attempt.certified,
                              attempt.used, attempt.notes, attempt.assessment, attempt.post)
    refuse(problem, case, result, attempt, p, outside, allow_overload)
    if attempt.assessment is not None and not attempt.assessment.stable:
        log.warning("%s: only an unstable equilibrium was found (unstable in %s)",
                    case.name, ", ".join(attempt.assessment.unstable_dofs) or "a coupled mode")
    # An independent check of what is reported (raises AuditFailure), and the warnings.
    if audit:
        audit_result(result, case, problem, attempt.post, full=audit == "full")
    return with_warnings(result, case, problem, attempt.post)


def _on_grid(case: Case, problem, *, tol, solver, allow_overload, start, stability,
             audit) -> Result:
    """On a bathymetry grid: solve until every line's seabed plane settles
    (:func:`.lines.bathymetry.solve_on_grid`, each round a :func:`solve` on that round's
    planes), then audit the last round's result."""
    def once(planes, warm):
        return solve(case, tol=tol, solver=solver, allow_overload=allow_overload,
                     start=warm, stability=stability, audit=False, _planes=planes)
    result = solve_on_grid(case, problem.kinds, once, start)
    if audit:
        audit_result(result, case)
    return result


def _parameters(problem, case: Case, planes) -> np.ndarray:
    """The problem's parameter vector of ``case`` under its full load, with one round's
    seabed ``planes`` of a bathymetry grid written in where given."""
    p = problem.parameters(case, 1.0)
    if planes is not None:
        for where, plane in zip(plane_slices(problem) + point_plane_slices(problem), planes):
            p[where] = plane
    return p


__all__ = ["solve", "rest_point", "turn_jump", "turn_jumps", "polish", "get_problem",
           "initial_point",
           "SOLVERS", "YAW_JUMP"]
