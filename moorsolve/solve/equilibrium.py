"""Run the equilibrium solve, certify it, check its stability, and return a :class:`Result`.

Strategy, from REFERENCE.md section 1's measured pitfalls:

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
from .diagnosis import (START_CERTIFIED, SUCCESS_STATUSES, diagnose, over_mbl, pulled_straight,
                        unbalanced_force)
from .audit import audit as audit_result
from .audit import result_warnings
from .newton import STATUS_TEXT
from .outcome import build_result, hull_out_of_range
from .polish import polish, polish_certified
from .prepared import geometry_key, line_facts
from .layout import LOAD_FACTOR_INDEX
from .problem import LINE_COLUMNS
from .result import Certificate, Result
from .stability import assess, find_stable, pseudo_transient
from .start import initial_point

log = logging.getLogger(__name__)

_LOAD_STEPS = (0.25, 0.5, 0.75, 1.0)
SOLVERS = ("ipopt", "newton")

#: IPOPT's return statuses that are failures even when the point happens to certify.
_FAILED_STATUSES = ("Infeasible_Problem_Detected", "Restoration_Failed",
                    "Error_In_Step_Computation", "Invalid_Number_Detected",
                    "Not_Enough_Degrees_Of_Freedom", "Invalid_Problem_Definition",
                    "Invalid_Option", "Unrecoverable_Exception", "NonIpopt_Exception_Thrown",
                    "Insufficient_Memory", "Internal_Error")


def run_ipopt(problem, solver, x0, p, lb, ub, stats) -> np.ndarray:
    """IPOPT from ``x0``; where the scene has complementarities, once per smoothing of
    :meth:`EquilibriumProblem.ipopt_smoothings`, each from the last (a continuation toward
    the exact problem, which the polish then solves)."""
    x = np.asarray(x0, dtype=float)
    for eps in problem.ipopt_smoothings():
        sol = solver(x0=x, p=problem.nlp_parameters(p, x, eps), lbx=lb, ubx=ub, lbg=0,
                     ubg=0)
        st = solver.stats()
        stats["iterations"] = stats.get("iterations", 0) + int(st.get("iter_count", 0))
        stats["status"] = st.get("return_status", "unknown")
        x_new = np.asarray(sol["x"]).ravel()
        if np.all(np.isfinite(x_new)):
            x = x_new
    return x


def _rest_key(problem, case: Case) -> tuple:
    """``(p_rest or None, key)``: the start cache's key of ``case``'s rest state. At load
    factor 0 nothing acts through the loads: one rest state per geometry (a lumped line's
    start is drawn under its current, so there all parameters count, ``p_rest`` given)."""
    p_rest = problem.parameters(case, 0.0) if problem.any_discrete else None
    return p_rest, b"rest:" + (p_rest.tobytes() if problem.any_discrete
                               else geometry_key(case)[1])


def rest_point(problem, case: Case, tol: float, kernel=None) -> np.ndarray:
    """The unloaded (pretensioned) equilibrium, the start of every loaded solve.

    Loading from the solved rest state keeps the solve on the quasi-static branch: a
    direct solve from the closed-form state can land on another certified equilibrium
    (seen at 36.5 deg yaw instead of 20.8 deg under a large couple, issue 7). Solved once
    per problem and parameters and remembered: by the Newton ``kernel`` when the caller
    has one and it certifies (building an IPOPT solver costs seconds for hundreds of
    lines), else with IPOPT; the closed-form state when the scene has free bodies or points
    but no loads (its one solve is the rest solve), or when the rest state does not certify.

    With nothing free no body load moves a fairlead: the lines' state a solve certified
    (:func:`_remember_lines`) is the start of the next, which it then is the answer of (or,
    with a current on lumped lines, next to). It is not solved here, so a first solve
    reports its own solver's work.
    """
    if problem.n_q and not problem.load_names:
        return initial_point(problem, case)
    p_rest, key = _rest_key(problem, case)
    with problem.lock:
        cached = problem.start_cache.get(key)
        if cached is not None:
            return cached.copy()
        if not problem.n_q:
            return initial_point(problem, case)
        if p_rest is None:
            p_rest = problem.parameters(case, 0.0)
        # Only a rest state not yet solved needs the closed-form start.
        x0 = initial_point(problem, case)
        if kernel is not None:
            out = kernel.solve(x0, p_rest, tol)
            if _kernel_certified(problem, out, tol):
                problem.keep_start(key, out["x"])
                return out["x"].copy()
        lb, ub = problem.bounds()
        opts = case.solver
        solver = problem.ipopt(min(max(tol, 1e-12), 1e-4), opts.max_iter, opts.max_time_s)
        x = run_ipopt(problem, solver, x0, p_rest, lb, ub, {"iterations": 0})
        x, certified = polish_certified(problem, x, p_rest, lb, ub, {"iterations": 0}, tol)
        x = x if certified else x0
        problem.keep_start(key, x)
    return x.copy()


def _remembered_answer(problem, case: Case, p, tol: float, start) -> tuple:
    """``(x, post)``: with nothing free and no ``start``, the lines' remembered state
    (:func:`_remember_lines`) with :meth:`EquilibriumProblem.post` at it where it
    certifies at ``p`` as it stands (no body load moves a held fairlead, so it does
    unless a current drags lumped lines); else ``(None, None)``. Neither solver is called
    for an answer already known: the certificate decides, as for any point."""
    if problem.n_q or start is not None:
        return None, None
    with problem.lock:
        x = problem.start_cache.get(_rest_key(problem, case)[1])
    if x is None:
        return None, None
    x = x.copy()
    post = problem.post(x, p)
    return (x, post) if _judge(problem, x, post, tol)[0] else (None, None)


def _remember_lines(problem, case: Case, x: np.ndarray) -> None:
    """Keep the certified state ``x`` of a scene with nothing free as the start of its
    next solve (:func:`rest_point`)."""
    problem.keep_start(_rest_key(problem, case)[1], np.array(x, dtype=float))


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
        Return an equilibrium in which a line exceeds its minimum breaking load instead of
        raising ConvergenceError (for damaged-condition checks that must report it).
    start : numpy.ndarray, optional
        A previous ``Result.state`` of the same scene structure to warm-start from.
    stability : bool
        Examine the stability of the equilibrium and, where it is unstable, look for a
        stable one (the default). ``False`` returns the first certified point without that
        examination (``Result.stability`` is then None), for sweeps that only want numbers.
    audit : bool or "full"
        Check the reported quantities independently before returning
        (:mod:`moorsolve.solve.audit`; the default). One-segment lines on a flat seabed are
        audited in closed form from their reported end positions and forces
        (:mod:`moorsolve.solve.audit_closed_form`); other scenes by drawing every line's
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
        x, post = (_remembered_answer(problem, case, p_full, tol, start) if _planes is None
                   else (None, None))
        used = solver if x is not None else "ipopt"
        if x is not None:
            stats["status"] = START_CERTIFIED
        elif kernel is not None:
            x, notes = _newton_strategy(problem, case, kernel, p_full, tol, start, stats)
            used = "newton" if x is not None else "ipopt"
        if x is None:
            x = _ipopt_strategy(problem, case, p_full, tol, start, stats, t0)
            if problem.smoothed and kernel is None and not problem.certify(x, p_full, tol)[0]:
                # Contacts and hawsers: where IPOPT (a smooth NLP solver) does not certify,
                # the semismooth Newton path built for them gets its turn.
                x_newton, extra = _newton_strategy(problem, case, problem.newton(), p_full,
                                                   tol, start, stats)
                if x_newton is not None:
                    x, used = x_newton, "newton"
                    notes.append("IPOPT did not certify this point; the Newton path did "
                                 "(semismooth Newton on the contacts' complementarities)")
        # One evaluation gives the certificate, the stiffness and every reported array.
        post = problem.post(_finite(x), p_full) if post is None else post
        certified, force_res, moment_res, relative = _judge(problem, x, post, tol)
        failed_status = stats["status"] in _FAILED_STATUSES
        if certified and failed_status:
            notes.append(f"IPOPT ended with {stats['status']} but the point certifies: the "
                         "certificate, recomputed from the solution, is what is reported")
        assessment = None
        if certified and stability:
            x_found = x
            x, assessment, extra = _stable_point(problem, case, x, p_full, tol, stats, post)
            notes += extra
            if x is not x_found:
                post = problem.post(_finite(x), p_full)
                certified, force_res, moment_res, relative = _judge(problem, x, post, tol)
        outside = (hull_out_of_range(problem, x, p_full, post)
                   + pulled_straight(problem, case, post)) if certified else []
        if certified and not outside and not problem.n_q and _planes is None:
            _remember_lines(problem, case, x)
        elapsed = time.perf_counter() - t0
        stats["status"] = explain_status(stats["status"], certified,
                                         stats.get("polish_steps", 0))
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
        raise ConvergenceError(diagnose(problem, case, result), residual_N=force_res,
                               residual_Nm=moment_res, status=stats["status"],
                               iterations=stats["iterations"], result=result)
    if outside:
        raise ConvergenceError("; ".join(outside), residual_N=force_res,
                               residual_Nm=moment_res, status=stats["status"],
                               iterations=stats["iterations"], result=result)
    broken = over_mbl(result, problem, post)
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


def _newton_strategy(problem, case, kernel, p_full, tol, start, stats):
    """The compiled kernel from the warm start or the rest state, then from the closed-form
    state; ``(x or None, notes)``."""
    notes = []
    x0 = np.asarray(start, float) if start is not None else rest_point(problem, case, tol,
                                                                        kernel)
    out = kernel.solve(x0, p_full, tol)
    stats["iterations"] += out["iterations"]
    certified = _kernel_certified(problem, out, tol)
    if not certified and start is None:
        # As in the IPOPT strategy: a slack rest state can be a poor start.
        x0 = initial_point(problem, case)
        out = kernel.solve(x0, p_full, tol)
        stats["iterations"] += out["iterations"]
        certified = _kernel_certified(problem, out, tol)
    stats["status"] = STATUS_TEXT[out["status"]]
    if certified and not (start is None and turn_jump(problem, x0, out["x"])):
        return out["x"], notes
    if start is None:
        # A large turn (or no certified point) from rest: follow the load up from rest
        # with the kernel, the quasi-static branch the IPOPT strategy's load steps follow.
        x = _newton_continuation(problem, case, kernel, p_full, tol, stats)
        if x is not None:
            return x, notes
    if certified:
        notes.append("the Newton fast path turned a body more than "
                     f"{math.degrees(YAW_JUMP):.0f} deg from rest and could not follow the "
                     "load up in steps; solved with IPOPT and load stepping to stay on the "
                     "quasi-static branch")
    else:
        notes.append(f"the Newton fast path did not certify ({stats['status']}); "
                     f"solved with IPOPT")
    return None, notes


#: Load-factor steps of the kernel's continuation: the first and largest step, and the
#: smallest before it gives up.
_CONTINUATION_STEP = (0.25, 1.0 / 256)


def _newton_continuation(problem, case, kernel, p_full, tol, stats):
    """The load factor raised from 0 (the rest state) to 1 with the compiled kernel, each
    step warm-started from the last, so the solve follows the quasi-static branch.

    A step is accepted when it certifies and turns no body more than :data:`YAW_JUMP`
    from the step before; otherwise it is halved (down to :data:`_CONTINUATION_STEP`'s
    smallest). So a body that turns round under its load, by any angle, is followed in
    turns of at most ``YAW_JUMP`` each. Returns the point at load factor 1, or None.
    """
    largest, smallest = _CONTINUATION_STEP
    x = rest_point(problem, case, tol, kernel)
    p = p_full.copy()
    factor, step = 0.0, largest
    while factor < 1.0:
        target = min(1.0, factor + step)
        p[LOAD_FACTOR_INDEX] = target
        out = kernel.solve(x, p, tol)
        stats["iterations"] += out["iterations"]
        if _kernel_certified(problem, out, tol) and not turn_jump(problem, x, out["x"]):
            x, factor = out["x"], target
            step = min(2.0 * step, largest)
        else:
            step /= 2.0
            if step < smallest:
                return None
    stats["status"] = STATUS_TEXT[out["status"]]
    return x


def _ipopt_strategy(problem, case, p_full, tol, start, stats, t0):
    """IPOPT from the warm start, else to the load from the solved rest state, else load
    stepping from rest; the best point."""
    opts = case.solver
    deadline = t0 + opts.max_time_s
    problem.ipopt_solvers.note_solve()
    # IPOPT's own tolerance is on the scaled residual; the polish and certificate
    # decide acceptance, so IPOPT only needs to get about as close as asked.
    ipopt_tol = min(max(tol, 1e-12), 1e-4)
    lb, ub = problem.bounds()

    def run(x0, p):
        if time.perf_counter() >= deadline:
            return x0, False
        # Each IPOPT run is capped at the whole budget; the deadline check above stops
        # further stages, so a solve ends within about twice the budget at worst.
        solver = problem.ipopt(ipopt_tol, opts.max_iter, opts.max_time_s)
        x = run_ipopt(problem, solver, x0, p, lb, ub, stats)
        stats["polish_steps"] = 0
        return polish_certified(problem, x, p, lb, ub, stats, tol)

    if start is not None:
        x, ok = run(np.asarray(start, float), p_full)
        if ok:
            return x
    x_rest = rest_point(problem, case, tol)
    x, ok = run(x_rest, p_full)
    if ok and not turn_jump(problem, x_rest, x):
        return x
    x_closed = initial_point(problem, case)
    if not ok and not np.array_equal(x_closed, x_rest):
        # A rest state can be a poor start (one line with nothing to pull against ends
        # slack at rest): try the closed-form state as well.
        x, ok = run(x_closed, p_full)
        if ok and not turn_jump(problem, x_closed, x):
            return x
    x_direct = x if ok else None
    # Load stepping from rest: each step starts from the last certified state.
    x_step = x_rest
    for factor in _LOAD_STEPS:
        p_step = problem.parameters(case, factor)
        x_try, ok = run(x_step, p_step)
        if not ok:
            if x_direct is not None:
                return x_direct
            return _drift(problem, x_rest, p_full, lb, ub, stats, tol, x_try)
        x_step = x_try
    return x_step


def _drift(problem, x_rest, p, lb, ub, stats, tol, fallback):
    """The last resort: the scene's own overdamped motion under the full load from rest
    (pseudo-transient continuation), then Newton polish. It passes through states where a
    body has no stiffness (every line slack at rest), which Newton and IPOPT cannot start
    from. Returns ``fallback`` when it does not certify."""
    if not problem.n_q:
        return fallback
    x = pseudo_transient(problem, x_rest, p, steps=2000)
    if x is None:
        return fallback
    x, certified = polish_certified(problem, x, p, lb, ub, stats, tol)
    if certified:
        stats["status"] = "pseudo-transient continuation, then Newton"
        return x
    return fallback


#: A direct solve that turns a body further than this from its rest state is checked by
#: load stepping, which follows the quasi-static branch (issue 7 found a certified
#: equilibrium at 36.5 deg where loading the body gradually ends at 20.8 deg).
YAW_JUMP = math.radians(10.0)


def turn_jump(problem, x_rest, x) -> bool:
    """Whether any free angle moved more than :data:`YAW_JUMP` from ``x_rest``."""
    for j, rotational in enumerate(problem.rotational):
        if rotational and abs(x[j] - x_rest[j]) * problem.x_scale[j] > YAW_JUMP:
            return True
    return False


def turn_jumps(problem, x_rest, X: np.ndarray) -> np.ndarray:
    """:func:`turn_jump` of every row of ``X`` (a scaled point a row), as an array."""
    jumped = np.zeros(len(X), bool)
    for j, rotational in enumerate(problem.rotational):
        if rotational:
            jumped |= np.abs(X[:, j] - x_rest[j]) * problem.x_scale[j] > YAW_JUMP
    return jumped


def _finite(x: np.ndarray) -> np.ndarray:
    """``x`` with any non-finite entry replaced by 0 (for reporting a failed point)."""
    return x if np.isfinite(x).all() else np.where(np.isfinite(x), x, 0.0)


def _kernel_certified(problem, out: dict, tol: float) -> bool:
    """Whether the kernel's point certifies, from the exact certificate it returns."""
    return bool(np.isfinite(out["x"]).all()) and problem.judge(
        *out["certificate"].tolist(), tol=tol)[0]


def _judge(problem, x, post, tol) -> tuple:
    """:meth:`EquilibriumProblem.certify` from the certificate in ``post``."""
    if not np.isfinite(x).all():
        return False, math.inf, math.inf, math.inf
    return problem.judge(*post["certificate"].ravel().tolist(), tol=tol)


def _stable_point(problem, case, x, p, tol, stats, post=None):
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
    found = find_stable(problem, x, p, tol, assessment,
                        lambda z: polish(problem, z, p, lb, ub, stats, tol))
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


# ---- polish and certificate -----------------------------------------------------------


__all__ = ["solve", "rest_point", "turn_jump", "turn_jumps", "polish", "get_problem",
           "initial_point",
           "SOLVERS", "YAW_JUMP"]
