"""How a loaded equilibrium is reached: the rest state every solve starts from, the
compiled kernel's strategy (with its load continuation), IPOPT's strategy (warm start,
rest state, closed-form state, load stepping, and the scene's own overdamped drift as the
last resort), and the turn check that keeps a solve on the quasi-static branch.

Each strategy returns a point (or None); :mod:`.equilibrium` certifies, examines and
reports it.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ...model import Case
from ..assembly.layout import LOAD_FACTOR_INDEX
from .newton import STATUS_TEXT
from .polish import polish_certified
from ..assembly.prepared import geometry_key
from ..stability.static import pseudo_transient
from .start import initial_point

_LOAD_STEPS = (0.25, 0.5, 0.75, 1.0)

#: The status of a solve that did not certify and whose time budget ran out on its way;
#: the rest of the status names the path that stopped (:func:`ran_out`).
BUDGET_EXHAUSTED = "budget_exhausted"


def ran_out(stats: dict, deadline, path: str) -> bool:
    """Whether the solve's time budget (``deadline``, a :func:`time.perf_counter` time) has
    passed; if so the first ``path`` it stopped is noted in ``stats`` (the status of a
    solve that then does not certify names it)."""
    if deadline is None or time.perf_counter() < deadline:
        return False
    stats.setdefault("out_of_time", path)
    return True


def budget_status(stats: dict, max_time_s: float, elapsed: float) -> str:
    """The status of an uncertified solve whose budget ran out (see :func:`ran_out`)."""
    return (f"{BUDGET_EXHAUSTED}: the time budget (solver.max_time_s = {max_time_s:g} s) "
            f"ran out in {stats['out_of_time']}; stopped after {elapsed:.3g} s "
            f"({stats['status']})")


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
    (seen at 36.5 deg yaw instead of 20.8 deg under a large couple). Solved once
    per problem and parameters and remembered: by the Newton ``kernel`` when the caller
    has one and it certifies (building an IPOPT solver costs seconds for hundreds of
    lines), else with IPOPT; the closed-form state when the scene has free bodies or points
    but no loads (its one solve is the rest solve), or when the rest state does not certify.

    With nothing free no body load moves a fairlead: the lines' state a solve certified
    (:func:`remember_lines`) is the start of the next, which it then is the answer of (or,
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
            if kernel_certified(problem, out, tol):
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


def remembered_answer(problem, case: Case, p, tol: float, start) -> tuple:
    """``(x, post)``: with nothing free and no ``start``, the lines' remembered state
    (:func:`remember_lines`) with :meth:`EquilibriumProblem.post` at it where it
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
    return (x, post) if judge_point(problem, x, post, tol)[0] else (None, None)


def remember_lines(problem, case: Case, x: np.ndarray) -> None:
    """Keep the certified state ``x`` of a scene with nothing free as the start of its
    next solve (:func:`rest_point`)."""
    problem.keep_start(_rest_key(problem, case)[1], np.array(x, dtype=float))



def newton_strategy(problem, case, kernel, p_full, tol, start, stats, deadline=None):
    """The compiled kernel from the warm start or the rest state, then from the closed-form
    state, then its load continuation (which stops at ``deadline``); ``(x or None,
    notes)``."""
    notes = []
    x0 = np.asarray(start, float) if start is not None else rest_point(problem, case, tol,
                                                                        kernel)
    out = kernel.solve(x0, p_full, tol)
    stats["iterations"] += out["iterations"]
    certified = kernel_certified(problem, out, tol)
    if not certified and start is None:
        # As in the IPOPT strategy: a slack rest state can be a poor start.
        x0 = initial_point(problem, case)
        out = kernel.solve(x0, p_full, tol)
        stats["iterations"] += out["iterations"]
        certified = kernel_certified(problem, out, tol)
    stats["status"] = STATUS_TEXT[out["status"]]
    if certified and not (start is None and turn_jump(problem, x0, out["x"])):
        return out["x"], notes
    if start is None:
        # A large turn (or no certified point) from rest: follow the load up from rest
        # with the kernel, the quasi-static branch the IPOPT strategy's load steps follow.
        x = _newton_continuation(problem, case, kernel, p_full, tol, stats, deadline)
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


def _newton_continuation(problem, case, kernel, p_full, tol, stats, deadline=None):
    """The load factor raised from 0 (the rest state) to 1 with the compiled kernel, each
    step warm-started from the last, so the solve follows the quasi-static branch.

    A step is accepted when it certifies and turns no body more than :data:`YAW_JUMP`
    from the step before; otherwise it is halved (down to :data:`_CONTINUATION_STEP`'s
    smallest). So a body that turns round under its load, by any angle, is followed in
    turns of at most ``YAW_JUMP`` each. Returns the point at load factor 1, or None (also
    when ``deadline`` passes).
    """
    largest, smallest = _CONTINUATION_STEP
    x = rest_point(problem, case, tol, kernel)
    p = p_full.copy()
    factor, step = 0.0, largest
    while factor < 1.0:
        if ran_out(stats, deadline, "the Newton load continuation"):
            return None
        target = min(1.0, factor + step)
        p[LOAD_FACTOR_INDEX] = target
        out = kernel.solve(x, p, tol)
        stats["iterations"] += out["iterations"]
        if kernel_certified(problem, out, tol) and not turn_jump(problem, x, out["x"]):
            x, factor = out["x"], target
            step = min(2.0 * step, largest)
        else:
            step /= 2.0
            if step < smallest:
                return None
    stats["status"] = STATUS_TEXT[out["status"]]
    return x


def ipopt_strategy(problem, case, p_full, tol, start, stats, t0):
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
        if ran_out(stats, deadline, "the IPOPT strategy (warm start, rest state, "
                                    "closed-form state, load steps)"):
            return x0, False
        # Each IPOPT run is capped at the whole budget; the deadline check above stops
        # further stages, so a solve ends within about twice the budget at worst.
        solver = problem.ipopt(ipopt_tol, opts.max_iter, opts.max_time_s)
        x = run_ipopt(problem, solver, x0, p, lb, ub, stats)
        if stats.get("status") == "Maximum_WallTime_Exceeded":
            stats.setdefault("out_of_time", "IPOPT")
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
            return _drift(problem, x_rest, p_full, lb, ub, stats, tol, x_try, deadline)
        x_step = x_try
    return x_step


def _drift(problem, x_rest, p, lb, ub, stats, tol, fallback, deadline):
    """The last resort: the scene's own overdamped motion under the full load from rest
    (pseudo-transient continuation), then Newton polish. It passes through states where a
    body has no stiffness (every line slack at rest), which Newton and IPOPT cannot start
    from. Returns ``fallback`` when it does not certify; the motion stops at ``deadline``
    (the solve's time budget, which IPOPT may already have spent), where the polish and
    the certificate judge the point it reached."""
    if not problem.n_q or ran_out(stats, deadline, "the pseudo-transient fallback (not "
                                                   "started: IPOPT had spent the budget)"):
        return fallback
    x = pseudo_transient(problem, x_rest, p, steps=2000, deadline=deadline)
    ran_out(stats, deadline, "the pseudo-transient fallback")
    if x is None:
        return fallback
    x, certified = polish_certified(problem, x, p, lb, ub, stats, tol)
    if certified:
        stats["status"] = "pseudo-transient continuation, then Newton"
        return x
    return fallback


#: A direct solve that turns a body further than this from its rest state is checked by
#: load stepping, which follows the quasi-static branch (a certified
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



def kernel_certified(problem, out: dict, tol: float) -> bool:
    """Whether the kernel's point certifies, from the exact certificate it returns."""
    return bool(np.isfinite(out["x"]).all()) and problem.judge(
        *out["certificate"].tolist(), tol=tol)[0]


def judge_point(problem, x, post, tol) -> tuple:
    """:meth:`EquilibriumProblem.certify` from the certificate in ``post``."""
    if not np.isfinite(x).all():
        return False, math.inf, math.inf, math.inf
    return problem.judge(*post["certificate"].ravel().tolist(), tol=tol)
