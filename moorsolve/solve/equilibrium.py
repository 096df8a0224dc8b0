"""Run the equilibrium solve, certify it, and turn it into a :class:`Result`.

Strategy, from REFERENCE.md section 1's measured pitfalls:

1. Start every leg from its inextensible closed-form state at the case-file position and
   solve the unloaded (pretensioned rest) state first; a start with all legs slack would
   give a singular Jacobian, and the rest state keeps the body on the right equilibrium
   branch (not yawed round with lines crossing under the hull).
2. Solve the loaded state from the rest state with IPOPT.
3. If that fails, step the load up from rest in increments, warm-starting each step.
4. Polish with a few Newton steps on the same residuals (the problem is square), then
   recompute the residuals from the solution and certify them against the tolerance.

A point that is not certified raises :class:`ConvergenceError` with the physical reason
found by :func:`_diagnose` and the best residual reached.
"""

from __future__ import annotations

import logging
import math
import time
from collections import OrderedDict

import numpy as np

from ..errors import ConvergenceError
from ..model import Case
from ..physics.catenary import initial_state, leg_profile
from ..physics.wall_tension import wall_tension
from .problem import (ENV_PARAMS, LEG_PARAMS, EquilibriumProblem, environment_parameters, leg_kind,
                      leg_parameters, structure_key)
from .newton import STATUS_TEXT
from .result import Certificate, LegResult, Result

log = logging.getLogger(__name__)

_PROBLEMS: "OrderedDict[tuple, EquilibriumProblem]" = OrderedDict()
_MAX_CACHED = 32
_LOAD_STEPS = (0.25, 0.5, 0.75, 1.0)
_POLISH_STEPS = 8
_PROFILE_POINTS = 51


def get_problem(case: Case) -> EquilibriumProblem:
    """The built problem for ``case``'s structure, built on first use and cached."""
    # The scales shape the solver's path (and, where a case has more than one
    # equilibrium, which one it finds), so they are part of the key: a case gets the same
    # problem whatever was solved before it. Rounding them to powers of two lets cases
    # that differ a little (a sweep, a damaged condition) share one build.
    force_scale, length_scale = (2.0 ** round(math.log2(v)) for v in _scales(case))
    key = (structure_key(case), force_scale, length_scale)
    problem = _PROBLEMS.get(key)
    if problem is None:
        problem = EquilibriumProblem(case, force_scale, length_scale)
        _PROBLEMS[key] = problem
        if len(_PROBLEMS) > _MAX_CACHED:
            _PROBLEMS.popitem(last=False)
    else:
        _PROBLEMS.move_to_end(key)
    return problem


def _scales(case: Case) -> tuple[float, float]:
    """Typical tension [N] and length [m] of the scene, for scaling the unknowns."""
    tensions = [abs(leg.line_type.weight_in_water) * leg.length for leg in case.legs]
    tensions += [math.hypot(max(u, 0.0), V) for u, V in _rest_leg_states(case)]
    force = max(max(tensions, default=1.0), 1.0)
    return force, max(case.environment.depth, 1.0)


def _rest_leg_states(case: Case):
    """Closed-form starting ``(u, V)`` of every leg with the body at its case position."""
    states = []
    for leg in case.legs:
        fx, fy, fz = leg.fairlead
        X = math.hypot(fx - leg.anchor[0], fy - leg.anchor[1])
        Z = fz - leg.anchor[2]
        lt = leg.line_type
        states.append(initial_state(leg_kind(case, leg), X, Z, leg.length,
                                    lt.weight_in_water, lt.ea))
    return states


def initial_point(problem: EquilibriumProblem, case: Case) -> np.ndarray:
    """Scaled starting vector: body at rest, legs in their closed-form states.

    Remembered per problem and leg parameters: the closed-form states cost more than a
    whole compiled Newton solve.
    """
    key = leg_parameters(case).tobytes()
    cache = problem.start_cache
    if key not in cache:
        x = np.zeros(problem.n_x)
        for i, (u, V) in enumerate(_rest_leg_states(case)):
            x[problem.n_q + 2 * i] = u
            x[problem.n_q + 2 * i + 1] = V
        if len(cache) >= 64:
            cache.pop(next(iter(cache)))
        cache[key] = x / problem.x_scale
    return cache[key].copy()


SOLVERS = ("ipopt", "newton")


def solve(case: Case, *, tol: float | None = None, solver: str = "ipopt",
          allow_overload: bool = False, start: np.ndarray | None = None) -> Result:
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

    Returns
    -------
    Result

    Raises
    ------
    ConvergenceError
        No certified equilibrium; carries the physical reason and the best residual.
    """
    if solver not in SOLVERS:
        raise ValueError(f"solver {solver!r}: must be one of {', '.join(SOLVERS)}")
    opts = case.solver
    tol = opts.tol if tol is None else tol
    problem = get_problem(case)
    p_legs = leg_parameters(case)
    p_full = np.concatenate([environment_parameters(case, 1.0), p_legs])
    if start is not None and np.shape(start) != (problem.n_x,):
        start = None
    # Building (and compiling) belongs to the problem, not to this solve's time.
    kernel = problem.newton() if solver == "newton" else None
    t0 = time.perf_counter()
    stats = dict(iterations=0, status="not run")
    notes = []
    x, used = None, "ipopt"
    if kernel is not None:
        x0 = np.asarray(start, float) if start is not None else initial_point(problem, case)
        out = kernel.solve(x0, p_full, tol)
        stats["iterations"] += out["iterations"]
        stats["status"] = STATUS_TEXT[out["status"]]
        if problem.certify(out["x"], p_full, tol)[0]:
            x, used = out["x"], "newton"
        else:
            notes.append(f"the Newton fast path did not certify ({stats['status']}); "
                         f"solved with IPOPT")
    if x is None:
        x = _ipopt_strategy(problem, case, p_legs, p_full, tol, start, stats, t0)

    elapsed = time.perf_counter() - t0
    certified, force_res, moment_res, relative = problem.certify(x, p_full, tol)
    cert = Certificate(force_N=force_res, moment_Nm=moment_res, relative=relative,
                       tolerance=tol, status=stats["status"],
                       iterations=stats["iterations"], solve_time_s=elapsed)
    result = _build_result(problem, case, x, p_full, cert, certified, used, notes)
    if not certified:
        raise ConvergenceError(_diagnose(problem, case, result), residual_N=force_res,
                               residual_Nm=moment_res, status=stats["status"],
                               iterations=stats["iterations"], result=result)
    broken = _over_mbl(result)
    if broken and not allow_overload:
        raise ConvergenceError(
            "overload: " + "; ".join(broken) + " (the mooring cannot hold this load; "
            "pass allow_overload=True to inspect the equilibrium anyway)",
            residual_N=force_res, residual_Nm=moment_res, status=stats["status"],
            iterations=stats["iterations"], result=result)
    return result


def _ipopt_strategy(problem, case, p_legs, p_full, tol, start, stats, t0):
    """IPOPT from the warm start, else straight to the load from the closed-form state,
    else from the solved rest state, else load stepping from rest; the best point."""
    opts = case.solver
    deadline = t0 + opts.max_time_s
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
        sol = solver(x0=x0, p=p, lbx=lb, ubx=ub, lbg=0, ubg=0)
        st = solver.stats()
        stats["iterations"] += int(st.get("iter_count", 0))
        stats["status"] = st.get("return_status", "unknown")
        x = np.asarray(sol["x"]).ravel()
        x = _polish(problem, x, p, lb, ub, stats, tol)
        return x, problem.certify(x, p, tol)[0]

    if start is not None:
        x, ok = run(np.asarray(start, float), p_full)
        if ok:
            return x
    x_rest = initial_point(problem, case)
    x, ok = run(x_rest, p_full)
    if ok:
        return x
    if problem.n_q and problem.load_names:
        p_rest = np.concatenate([environment_parameters(case, 0.0), p_legs])
        x_solved, rest_ok = run(x_rest, p_rest)
        if rest_ok:
            x_rest = x_solved
            x, ok = run(x_rest, p_full)
            if ok:
                return x
    # Load stepping from rest: each step starts from the last certified state.
    x_step = x_rest
    for factor in _LOAD_STEPS:
        p_step = np.concatenate([environment_parameters(case, factor), p_legs])
        x_try, ok = run(x_step, p_step)
        if not ok:
            return x_try
        x_step = x_try
    return x_step


# ---- polish and certificate -----------------------------------------------------------


def _polish(problem, x, p, lb, ub, stats, tol):
    """Newton steps on the square residual system until the point certifies at ``tol``,
    kept only while they reduce the residual."""
    if not np.all(np.isfinite(x)):
        return x
    g = np.asarray(problem.residual(x, p)).ravel()
    norm = np.max(np.abs(g)) if g.size else 0.0
    for _ in range(_POLISH_STEPS):
        if norm < 1e-15 or problem.certify(x, p, tol)[0]:
            break
        J = np.asarray(problem.jacobian(x, p))
        try:
            step = np.linalg.solve(J, g)
        except np.linalg.LinAlgError:
            break
        improved = False
        alpha = 1.0
        for _ in range(6):
            x_new = np.clip(x - alpha * step, lb, ub)
            g_new = np.asarray(problem.residual(x_new, p)).ravel()
            n_new = np.max(np.abs(g_new))
            if np.isfinite(n_new) and n_new < norm:
                x, g, norm, improved = x_new, g_new, n_new, True
                break
            alpha *= 0.5
        stats["iterations"] += 1
        if not improved:
            break
    return x


def _over_mbl(result: Result) -> list[str]:
    out = []
    for leg in result.legs:
        u = leg.utilisation
        if u is not None and u > 1.0:
            out.append(f"leg {leg.name} would break: tension "
                       f"{max(leg.fairlead_tension_N, leg.anchor_tension_N) / 1e3:.1f} kN "
                       f"> MBL {leg.mbl_N / 1e3:.1f} kN")
    return out


def _diagnose(problem, case, result) -> str:
    """The physical reason an equilibrium was not found, at the best point reached."""
    reasons = []
    for leg, lr in zip(case.legs, result.legs):
        lt = leg.line_type
        chord = math.dist(lr.anchor, lr.fairlead)
        if lt.ea is None and chord > leg.length * (1 + 1e-9):
            reasons.append(f"leg {leg.name} cannot reach: anchor-fairlead distance "
                           f"{chord:.2f} m exceeds its inextensible length {leg.length:.2f} m")
        elif lt.ea is None and chord > leg.length * (1 - 1e-4):
            reasons.append(f"leg {leg.name} is pulled straight (chord {chord:.3f} m of "
                           f"{leg.length:.3f} m): an inextensible line would need an "
                           f"unbounded tension; give the line type an ea")
    reasons += _over_mbl(result)
    if result.body is not None and problem.load_names:
        total = np.sum([v[:2] for v in result.loads.values()], axis=0)
        if np.hypot(*total) > 0:
            heading = math.degrees(math.atan2(total[1], total[0])) % 360.0
            reasons.append(f"the legs could not balance the body load of "
                           f"{np.hypot(*total) / 1e3:.1f} kN toward {heading:.0f} deg "
                           f"(the lines may be too weak, too short or all on one side)")
    if not reasons:
        reasons.append(f"the solver stopped with status {result.certificate.status}")
    return "; ".join(reasons)


# ---- result -----------------------------------------------------------------------------


def _build_result(problem, case, x, p, cert, certified, solver="ipopt",
                  notes=()) -> Result:
    x = np.where(np.isfinite(x), x, 0.0)
    legs_out, _, load_total, load_vec = (np.asarray(v) for v in problem.report(x, p))
    xp = x * problem.x_scale
    q = dict.fromkeys(("surge", "sway", "yaw"), 0.0)
    for i, d in enumerate(problem.free):
        q[d] = float(xp[i])
    env = case.environment
    legs = []
    n_par = len(LEG_PARAMS)
    for i, (leg, kind) in enumerate(zip(case.legs, problem.kinds)):
        row = np.atleast_2d(legs_out)[i]
        H, VF, HA, VA, grounded, susp_x, _, _, X, Z, gx, gy = (float(v) for v in row[:12])
        lt = leg.line_type
        u = float(xp[problem.n_q + 2 * i])
        start_i = len(ENV_PARAMS) + i * n_par
        anchor = tuple(float(v) for v in p[start_i: start_i + 3])
        fairlead = (gx, gy, leg.fairlead[2])
        ux, uy = ((gx - anchor[0]) / X, (gy - anchor[1]) / X) if X > 1e-12 else (1.0, 0.0)
        td = max(X - susp_x, 0.0) if grounded > 0 else 0.0
        prof = leg_profile(kind, H=H, V=VF, L=leg.length, w=lt.weight_in_water, ea=lt.ea,
                           mu=env.seabed.friction if kind.friction else 0.0, X=X, Z=Z,
                           n=_PROFILE_POINTS)
        profile = {"x_m": anchor[0] + ux * prof["x"], "y_m": anchor[1] + uy * prof["x"],
                   "z_m": anchor[2] + prof["z"], "tension_N": prof["tension"]}
        if lt.sealed and lt.diameter:
            depth_below = np.maximum(-profile["z_m"], 0.0)
            tw = wall_tension(prof["tension"], depth_below, lt.diameter, env.water_density,
                              env.gravity)
            profile["wall_tension_N"] = tw
            profile["compression"] = bool(np.any(tw < 0))
        uplift = VA > 0 and not (kind.contact and grounded > 0)
        legs.append(LegResult(
            name=leg.name,
            fairlead_tension_N=math.hypot(H, VF), horizontal_tension_N=H,
            fairlead_vertical_N=VF, anchor_tension_N=math.hypot(HA, VA),
            anchor_horizontal_N=HA, anchor_vertical_N=VA,
            grounded_length_m=grounded, touchdown_from_anchor_m=td,
            # Slack: no horizontal tension and line loose on the seabed (or, for a
            # weightless line, longer than its chord); a vertical taut leg is not slack.
            uplift=bool(uplift), slack=bool(u < 0.0 or (H == 0.0 and grounded > 0.0)),
            uplift_angle_deg=math.degrees(math.atan2(VA, HA)) if uplift else 0.0,
            fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
            anchor=anchor, fairlead=fairlead,
            touchdown_point=((anchor[0] + ux * td, anchor[1] + uy * td, anchor[2])
                             if grounded > 0 else None),
            mbl_N=lt.mbl, profile=profile))
    body = None
    if case.body is not None:
        body = {"x_m": q["surge"], "y_m": q["sway"], "yaw_deg": math.degrees(q["yaw"])}
    loads = {}
    lv = np.asarray(load_vec).ravel()
    for k, name in enumerate(problem.load_names):
        loads[name] = [float(v) for v in lv[3 * k: 3 * k + 3]]
    notes = list(notes) + [f"leg {lr.name}: the line passes below the seabed (contact not modelled "
             f"for an anchor above the seabed or a buoyant line)"
             for lr, kind in zip(legs, problem.kinds)
             if not kind.contact and np.min(lr.profile["z_m"]) < -env.depth - 1e-6]
    return Result(converged=certified, solver=solver, certificate=cert,
                  effects=list(problem.effects), body=body, legs=legs, loads=loads,
                  case_name=case.name, state=x.copy(), notes=tuple(notes), case=case)
