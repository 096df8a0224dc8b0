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

import dataclasses
import logging
import math
import time
from collections import OrderedDict

import numpy as np

from ..errors import ConvergenceError
from ..model import Case
from ..physics.catenary import (LegKind, initial_state, leg_profile, segment_profile,
                                sloped_leg_profile)
from ..physics.wall_tension import wall_tension
from .newton import STATUS_TEXT
from .problem import (ENV_PARAMS, LEG_PARAMS, SEGMENT_COLUMNS, DiscreteLegKind,
                      EquilibriumProblem, MultiLegKind, _can_ground, discretised, leg_kind,
                      leg_parameters, parameter_vector, segment_parameters, structure_key)
from .result import Certificate, LegResult, Result
from .fibre import fibre_grounded, fibre_notes
from .stretch_params import numeric_law, start_ea

log = logging.getLogger(__name__)

_PROBLEMS: "OrderedDict[tuple, EquilibriumProblem]" = OrderedDict()
_MAX_CACHED = 32
_LOAD_STEPS = (0.25, 0.5, 0.75, 1.0)
_POLISH_STEPS = 30
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
    tensions = [sum(abs(seg.line_type.weight_in_water) * seg.length for seg in leg.segments)
                + sum(abs(c.weight) for c in leg.joint_clumps if c is not None)
                for leg in case.legs]
    tensions += [math.hypot(max(u, 0.0), V) for u, V in _rest_leg_states(case)]
    tensions += [_line_load(case, leg)[0] * leg.length for leg in case.legs
                 if discretised(case, leg)]
    force = max(max(tensions, default=1.0), 1.0)
    return force, max(case.environment.depth, 1.0)


_REST_STATES: "OrderedDict[bytes, list]" = OrderedDict()


def _rest_leg_states(case: Case):
    """Closed-form starting ``(u, V)`` of every leg with the body at its case position.

    Remembered by everything they depend on (the legs' kinds, geometry and line data):
    the bisections cost milliseconds, far more than a compiled Newton solve.
    """
    key = repr(structure_key(case)).encode() + leg_parameters(case).tobytes() \
        + segment_parameters(case).tobytes()
    states = _REST_STATES.get(key)
    if states is None:
        states = _REST_STATES[key] = _compute_rest_leg_states(case)
        if len(_REST_STATES) > 256:
            _REST_STATES.popitem(last=False)
    return list(states)


def _compute_rest_leg_states(case: Case):
    states = []
    for leg in case.legs:
        fx, fy, fz = leg.fairlead
        X = math.hypot(fx - leg.anchor[0], fy - leg.anchor[1])
        Z = fz - leg.anchor[2]
        if leg.multi_segment or discretised(case, leg):
            kind, w = _equivalent_line(case, leg)
            states.append(initial_state(kind, X, Z, leg.length, w, None))
            continue
        lt = leg.line_type
        states.append(initial_state(leg_kind(case, leg), X, Z, leg.length,
                                    lt.weight_in_water, start_ea(lt)))
    return states


def _equivalent_line(case: Case, leg) -> tuple:
    """A uniform inextensible line of the same length and total weight (clumps spread)."""
    total = sum(seg.line_type.weight_in_water * seg.length for seg in leg.segments)
    total += sum(c.weight for c in leg.joint_clumps if c is not None)
    w = total / leg.length
    bed = case.environment.seabed_z(leg.anchor[0], leg.anchor[1])
    on_seabed = leg.anchor[2] <= bed + 1e-9 * max(case.environment.depth, 1.0)
    return LegKind(elastic=False, contact=on_seabed and w > 0, neutral=(w == 0)), w


def _multi_leg_start(case: Case, leg, kind: MultiLegKind, u: float, V: float,
                     length_scale: float, force_scale: float) -> list:
    """Closed-form start of a multi-segment leg from its equivalent uniform line.

    The joints are put where the equivalent catenary has their arc length; the segments'
    top vertical tensions follow from the fairlead's by subtracting the weights below it
    (zero on the seabed); a joint on the seabed starts pressed onto it by its clump.
    """
    eq_kind, w_eq = _equivalent_line(case, leg)
    fx, fy, fz = leg.fairlead
    X = math.hypot(fx - leg.anchor[0], fy - leg.anchor[1])
    Z = fz - leg.anchor[2]
    if eq_kind.neutral:
        prof = dict(s=np.linspace(0, leg.length, 51), x=np.linspace(0, X, 51),
                    z=np.linspace(0, Z, 51))
    else:
        prof = leg_profile(eq_kind, H=max(u, 0.0), V=V, L=leg.length, w=w_eq, ea=None, mu=0.0,
                           X=X, Z=Z, n=201)
    z_bed = -case.environment.depth
    arc = np.cumsum([seg.length for seg in leg.segments])[:-1]
    xi = np.interp(arc, prof["s"], prof["x"])
    z = leg.anchor[2] + np.interp(arc, prof["s"], prof["z"])
    clumps = [c.weight if c is not None else 0.0 for c in leg.joint_clumps]
    grounded = z <= z_bed + 1e-6 * max(case.environment.depth, 1.0)
    Vs = [0.0] * len(leg.segments)
    Vs[-1] = V
    for k in range(len(leg.segments) - 2, -1, -1):
        above = leg.segments[k + 1]
        Vs[k] = Vs[k + 1] - above.line_type.weight_in_water * above.length - clumps[k]
    joints = []
    for j in range(kind.n_joints):
        if grounded[j] and _can_ground(kind.segments[j]):
            sigma = -(max(clumps[j], 0.0) + 1e-6 * force_scale)
        else:
            sigma = Vs[j]
        joints += [float(xi[j]), float(sigma)]
    if kind.reversed_top:
        top = leg.segments[-1]
        V = top.line_type.weight_in_water * top.length - V
    return [u, V] + joints


def _start_key(problem: EquilibriumProblem, case: Case) -> bytes:
    key = np.concatenate([leg_parameters(case), segment_parameters(case)]).tobytes()
    if any(isinstance(k, DiscreteLegKind) for k in problem.kinds):
        key += repr(case.environment.current).encode()
    return key


def rest_point(problem: EquilibriumProblem, case: Case, tol: float) -> np.ndarray:
    """The unloaded (pretensioned) equilibrium, the start of every loaded solve.

    Loading from the solved rest state keeps the solve on the quasi-static branch: a
    direct solve from the closed-form state can land on another certified equilibrium
    (seen at 36.5 deg yaw instead of 20.8 deg under a large couple, issue 7). Solved once
    with IPOPT per problem and leg parameters and remembered; the closed-form state when
    the scene has no free body or no loads, or when the rest state does not certify.
    """
    x0 = initial_point(problem, case)
    if not (problem.n_q and problem.load_names):
        return x0
    key = b"rest:" + _start_key(problem, case)
    cache = problem.start_cache
    if key not in cache:
        p_rest = parameter_vector(case, 0.0)
        lb, ub = problem.bounds()
        opts = case.solver
        solver = problem.ipopt(min(max(tol, 1e-12), 1e-4), opts.max_iter, opts.max_time_s)
        sol = solver(x0=x0, p=p_rest, lbx=lb, ubx=ub, lbg=0, ubg=0)
        x = _polish(problem, np.asarray(sol["x"]).ravel(), p_rest, lb, ub,
                    {"iterations": 0}, tol)
        cache[key] = x if problem.certify(x, p_rest, tol)[0] else x0
    return cache[key].copy()


def initial_point(problem: EquilibriumProblem, case: Case) -> np.ndarray:
    """Scaled starting vector: body at rest, legs in their closed-form states.

    Remembered per problem and leg parameters: the closed-form states cost more than a
    whole compiled Newton solve. (Multi-segment and discretised legs add their segment
    parameters, and a discretised leg the current, to the key.)
    """
    key = _start_key(problem, case)
    cache = problem.start_cache
    if key not in cache:
        x = np.zeros(problem.n_x)
        for i, (u, V) in enumerate(_rest_leg_states(case)):
            start = problem.leg_offsets[i]
            kind = problem.kinds[i]
            if isinstance(kind, MultiLegKind):
                block = _multi_leg_start(case, case.legs[i], kind, u, V, problem.length_scale,
                                         problem.force_scale)
                x[start: start + len(block)] = block
            elif isinstance(kind, DiscreteLegKind):
                block = _discrete_leg_start(case, case.legs[i], kind, u, V,
                                            problem.length_scale, problem.force_scale)
                x[start: start + len(block)] = block
            else:
                x[start] = u
                x[start + 1] = V
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
    p_full = parameter_vector(case, 1.0)
    if start is not None and np.shape(start) != (problem.n_x,):
        start = None
    # Building (and compiling) belongs to the problem, not to this solve's time.
    kernel = problem.newton() if solver == "newton" else None
    t0 = time.perf_counter()
    stats = dict(iterations=0, status="not run")
    notes = []
    x, used = None, "ipopt"
    if kernel is not None:
        x0 = np.asarray(start, float) if start is not None else rest_point(problem, case, tol)
        out = kernel.solve(x0, p_full, tol)
        stats["iterations"] += out["iterations"]
        certified = problem.certify(out["x"], p_full, tol)[0]
        if not certified and start is None:
            # As in the IPOPT strategy: a slack rest state can be a poor start.
            x0 = initial_point(problem, case)
            out = kernel.solve(x0, p_full, tol)
            stats["iterations"] += out["iterations"]
            certified = problem.certify(out["x"], p_full, tol)[0]
        stats["status"] = STATUS_TEXT[out["status"]]
        if certified and not (start is None and _yaw_jump(problem, x0, out["x"])):
            x, used = out["x"], "newton"
        elif certified:
            notes.append("the Newton fast path turned the body more than "
                         f"{math.degrees(YAW_JUMP):.0f} deg from rest; solved with IPOPT "
                         "and load stepping to stay on the quasi-static branch")
        else:
            notes.append(f"the Newton fast path did not certify ({stats['status']}); "
                         f"solved with IPOPT")
    if x is None:
        x = _ipopt_strategy(problem, case, p_full, tol, start, stats, t0)

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


def _ipopt_strategy(problem, case, p_full, tol, start, stats, t0):
    """IPOPT from the warm start, else to the load from the solved rest state, else load
    stepping from rest; the best point."""
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
    x_rest = rest_point(problem, case, tol)
    x, ok = run(x_rest, p_full)
    if ok and not _yaw_jump(problem, x_rest, x):
        return x
    x_closed = initial_point(problem, case)
    if not ok and not np.array_equal(x_closed, x_rest):
        # A rest state can be a poor start (one leg with nothing to pull against ends
        # slack at rest): try the closed-form state as well.
        x, ok = run(x_closed, p_full)
        if ok and not _yaw_jump(problem, x_closed, x):
            return x
    x_direct = x if ok else None
    # Load stepping from rest: each step starts from the last certified state.
    x_step = x_rest
    for factor in _LOAD_STEPS:
        p_step = parameter_vector(case, factor)
        x_try, ok = run(x_step, p_step)
        if not ok:
            return x_direct if x_direct is not None else x_try
        x_step = x_try
    return x_step


#: A direct solve that turns the body further than this from its rest state is checked by
#: load stepping, which follows the quasi-static branch (issue 7 found a certified
#: equilibrium at 36.5 deg where loading the body gradually ends at 20.8 deg).
YAW_JUMP = math.radians(10.0)


def _yaw_jump(problem, x_rest, x) -> bool:
    if "yaw" not in problem.free:
        return False
    i = problem.free.index("yaw")
    return abs(x[i] - x_rest[i]) * problem.x_scale[i] > YAW_JUMP


# ---- polish and certificate -----------------------------------------------------------


def _polish(problem, x, p, lb, ub, stats, tol):
    """Newton steps on the square residual system until the point certifies at ``tol``,
    kept only while they reduce the residual."""
    if not np.all(np.isfinite(x)):
        return x
    g = np.asarray(problem.residual(x, p)).ravel()
    norm = np.max(np.abs(g)) if g.size else 0.0
    for _ in range(_POLISH_STEPS):
        # Stop once certified. Not on a merely small residual: where a span depends on a
        # tension only to second order (a fairlead on the seabed: Z ~ V^2) Newton halves
        # the tension's error per step while the residual is already below 1e-15.
        if norm == 0.0 or problem.certify(x, p, tol)[0]:
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
        if not lt.elastic and chord > leg.length * (1 + 1e-9):
            reasons.append(f"leg {leg.name} cannot reach: anchor-fairlead distance "
                           f"{chord:.2f} m exceeds its inextensible length {leg.length:.2f} m")
        elif not lt.elastic and chord > leg.length * (1 - 1e-4):
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
    legs_out, _, _, load_vec = (np.asarray(v) for v in problem.report(x, p))
    xp = x * problem.x_scale
    q = dict.fromkeys(("surge", "sway", "yaw"), 0.0)
    for i, d in enumerate(problem.free):
        q[d] = float(xp[i])
    env = case.environment
    legs = []
    n_par = len(LEG_PARAMS)
    seg_table = np.atleast_2d(np.asarray(problem.segment_report(x, p)))
    node_table = np.atleast_2d(np.asarray(problem.node_report(x, p)))
    for i, (leg, kind) in enumerate(zip(case.legs, problem.kinds)):
        row = np.atleast_2d(legs_out)[i]
        if isinstance(kind, DiscreteLegKind):
            nodes = np.array([r for r in node_table if int(r[0]) == i])
            legs.append(_discrete_leg_result(case, leg, kind, row, nodes, p, i))
            continue
        if isinstance(kind, MultiLegKind):
            rows = [dict(zip(SEGMENT_COLUMNS, (float(v) for v in r)))
                    for r in seg_table if int(r[0]) == i]
            legs.append(_multi_leg_result(problem, case, leg, kind, row, rows,
                                          float(xp[problem.leg_offsets[i]]), p, i))
            continue
        H, VF, HA, VA, grounded, susp_x, _, _, X, Z, gx, gy = (float(v) for v in row[:12])
        lt = leg.line_type
        u = float(xp[problem.leg_offsets[i]])
        start_i = len(ENV_PARAMS) + i * n_par
        anchor = tuple(float(v) for v in p[start_i: start_i + 3])
        fairlead = (gx, gy, leg.fairlead[2])
        ux, uy = ((gx - anchor[0]) / X, (gy - anchor[1]) / X) if X > 1e-12 else (1.0, 0.0)
        td = max(X - susp_x, 0.0) if grounded > 0 else 0.0
        slope = 0.0
        if kind.sloped:
            slope = env.seabed.gradient[0] * ux + env.seabed.gradient[1] * uy
            prof = sloped_leg_profile(H=H, V=VF, L=leg.length, w=lt.weight_in_water, ea=lt.ea,
                                      mu=env.seabed.friction if kind.friction else 0.0,
                                      t=slope, X=X, Z=Z, n=_PROFILE_POINTS,
                                      law=numeric_law(lt))
        else:
            prof = leg_profile(kind, H=H, V=VF, L=leg.length, w=lt.weight_in_water,
                               ea=lt.ea, mu=env.seabed.friction if kind.friction else 0.0,
                               X=X, Z=Z, n=_PROFILE_POINTS, law=numeric_law(lt))
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
            # On a slope the anchor is pulled along it: the upward part is reported (0 when
            # it pulls down-slope), the tension is the whole pull.
            fairlead_vertical_N=VF, anchor_tension_N=math.hypot(HA, VA),
            anchor_horizontal_N=HA, anchor_vertical_N=max(VA, 0.0) if kind.sloped else VA,
            grounded_length_m=grounded, touchdown_from_anchor_m=td,
            # Slack: no horizontal tension and line loose on the seabed (or, for a
            # weightless line, longer than its chord); a vertical taut leg is not slack.
            uplift=bool(uplift), slack=bool(u < 0.0 or (H == 0.0 and grounded > 0.0)),
            uplift_angle_deg=math.degrees(math.atan2(VA, HA)) if uplift else 0.0,
            fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
            anchor=anchor, fairlead=fairlead,
            touchdown_point=((anchor[0] + ux * td, anchor[1] + uy * td,
                              anchor[2] + slope * td) if grounded > 0 else None),
            mbl_N=lt.mbl, profile=profile))
    table = np.atleast_2d(legs_out)
    legs = [dataclasses.replace(lr, fairlead_force=(float(table[i][12]), float(table[i][13]),
                                                    -lr.fairlead_vertical_N))
            for i, lr in enumerate(legs)]
    legs = [dataclasses.replace(lr, fibre_grounded_m=fibre_grounded(case, leg, lr))
            for leg, lr in zip(case.legs, legs)]
    body = None
    if case.body is not None:
        body = {"x_m": q["surge"], "y_m": q["sway"], "yaw_deg": math.degrees(q["yaw"])}
    loads = {}
    lv = np.asarray(load_vec).ravel()
    for k, name in enumerate(problem.load_names):
        loads[name] = [float(v) for v in lv[3 * k: 3 * k + 3]]
    notes = list(notes) + [
        f"leg {lr.name}: the line passes below the seabed (contact not modelled "
        f"for an anchor above the seabed or a buoyant line)"
        for lr, kind in zip(legs, problem.kinds)
        if not isinstance(kind, MultiLegKind) and not kind.contact
        and np.min(lr.profile["z_m"]) < -env.depth - 1e-6]
    for lr, kind in zip(legs, problem.kinds):
        if isinstance(kind, DiscreteLegKind) and np.any(lr.profile["tension_N"][1:-1] < 0):
            notes.append(f"leg {lr.name}: some elements of the discretised line are in "
                         "compression (a loose line; its lumped-node shape is not unique)")
    for lr in legs:
        for j, joint in enumerate(lr.joints):
            if joint["position_m"][2] > 0:
                notes.append(f"leg {lr.name}: joint {j + 1} is {joint['position_m'][2]:.2f} m "
                             "above the still-water level (its buoyancy is taken as fully "
                             "submerged; the buoy is too large for this leg)")
            if joint["seabed_reaction_N"] > 0 and joint["height_above_seabed_m"] > 1e-6:
                notes.append(f"leg {lr.name}: joint {j + 1} is held by a seabed reaction but "
                             f"hangs {joint['height_above_seabed_m']:.3f} m above the seabed "
                             "(a segment hanging down into a joint is outside the model)")
    notes += fibre_notes(case, legs)
    # Clump weights are parameters: what they are depends on this case, not the structure.
    effects = list(problem.effects)
    clumps = [c.weight for leg in case.legs for c in leg.joint_clumps if c is not None]
    effects += (["clump_weight"] if any(w > 0 for w in clumps) else []) + (
        ["buoy"] if any(w < 0 for w in clumps) else [])
    return Result(converged=certified, solver=solver, certificate=cert,
                  effects=effects, body=body, legs=legs, loads=loads,
                  case_name=case.name, state=x.copy(), notes=tuple(notes), case=case)


def _multi_leg_result(problem, case, leg, kind, row, rows, u, p, i) -> LegResult:
    """The result of a multi-segment leg: CONTRACT fields, joints, segments, one profile."""
    env = case.environment
    H, VF, HA, VA, grounded, _, _, _, X, Z, gx, gy = (float(v) for v in row[:12])
    start_i = len(ENV_PARAMS) + i * len(LEG_PARAMS)
    anchor = tuple(float(v) for v in p[start_i: start_i + 3])
    fairlead = (gx, gy, leg.fairlead[2])
    ux, uy = ((gx - anchor[0]) / X, (gy - anchor[1]) / X) if X > 1e-12 else (1.0, 0.0)
    parts = {k: [] for k in ("x", "z", "tension")}
    segments, joints = [], []
    td = None
    for k, (seg, sk, r) in enumerate(zip(leg.segments, kind.segments, rows)):
        lt = seg.line_type
        law = numeric_law(lt)
        if sk.friction:
            prof = leg_profile(LegKind(elastic=sk.elastic, contact=True, friction=True),
                               H=r["H"], V=r["VF"], L=seg.length, w=lt.weight_in_water,
                               ea=lt.ea, mu=env.seabed.friction, X=r["X"], Z=r["Z"],
                               n=_PROFILE_POINTS, law=law)
        elif k == len(rows) - 1 and kind.reversed_top:
            # Solved from the fairlead end: draw it from there, then turn it round.
            back = segment_profile(H=r["H"], V=-r["VA"], L=seg.length, w=lt.weight_in_water,
                                   ea=lt.ea, h=max(leg.fairlead[2] + env.depth, 0.0),
                                   X=r["X"], Z=-r["Z"], n=_PROFILE_POINTS, law=law)
            prof = {"x": (r["X"] - back["x"])[::-1], "z": (r["Z"] + back["z"])[::-1],
                    "tension": back["tension"][::-1]}
        else:
            prof = segment_profile(H=r["H"], V=r["VF"], L=seg.length, w=lt.weight_in_water,
                                   ea=lt.ea, h=r["lower_h"], X=r["X"], Z=r["Z"],
                                   n=_PROFILE_POINTS, law=law)
        sl = slice(1, None) if k else slice(None)
        parts["x"].append(r["lower_xi"] + prof["x"][sl])
        parts["z"].append(r["lower_z"] + prof["z"][sl])
        parts["tension"].append(prof["tension"][sl])
        top = math.hypot(r["H"], r["VF"])
        bottom = math.hypot(r["HA"], r["VA"])
        segments.append({"type": lt.name, "length_m": seg.length,
                         "top_tension_N": top, "bottom_tension_N": bottom,
                         "horizontal_tension_N": r["H"], "top_vertical_N": r["VF"],
                         "bottom_vertical_N": r["VA"], "grounded_length_m": r["grounded"],
                         "max_tension_N": float(np.max(prof["tension"])),
                         "utilisation": (float(np.max(prof["tension"])) / lt.mbl
                                         if lt.mbl else None)})
        if k > 0:
            clump = leg.joint_clumps[k - 1]
            joints.append({"position_m": [anchor[0] + ux * r["lower_xi"],
                                          anchor[1] + uy * r["lower_xi"], r["lower_z"]],
                           "height_above_seabed_m": r["lower_h"],
                           "on_seabed": bool(rows[k - 1]["joint_reaction"] > 0
                                             or r["lower_h"] <= 0),
                           "seabed_reaction_N": max(rows[k - 1]["joint_reaction"], 0.0),
                           "clump_weight_N": clump.weight if clump is not None else 0.0})
    td = _anchor_touchdown(rows, leg, kind)
    xs = np.concatenate(parts["x"])
    profile = {"x_m": anchor[0] + ux * xs, "y_m": anchor[1] + uy * xs,
               "z_m": np.concatenate(parts["z"]), "tension_N": np.concatenate(parts["tension"])}
    first = rows[0]
    uplift = VA > 0 and first["grounded"] <= 0
    mbl = min((seg.line_type.mbl for seg in leg.segments if seg.line_type.mbl), default=None)
    return LegResult(
        name=leg.name,
        fairlead_tension_N=math.hypot(H, VF), horizontal_tension_N=H,
        fairlead_vertical_N=VF, anchor_tension_N=math.hypot(HA, max(VA, 0.0)),
        anchor_horizontal_N=HA, anchor_vertical_N=max(VA, 0.0),
        grounded_length_m=grounded, touchdown_from_anchor_m=td or 0.0,
        uplift=bool(uplift), slack=bool(u < 0.0),
        uplift_angle_deg=math.degrees(math.atan2(VA, HA)) if uplift else 0.0,
        fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
        anchor=anchor, fairlead=fairlead,
        touchdown_point=((anchor[0] + ux * td, anchor[1] + uy * td, anchor[2] + 0.0)
                         if td is not None else None),
        mbl_N=mbl, profile=profile, segments=tuple(segments), joints=tuple(joints))


def _line_load(case: Case, leg) -> tuple:
    """Typical load per length on a discretised leg [N/m]: its size and unit direction.

    The mean submerged weight (clumps spread) and the normal flow force of the current at
    mid-depth on a line across it.
    """
    _, w = _equivalent_line(case, leg)
    env = case.environment
    cur = env.current
    speed = cur.speed
    if cur.profile:
        zs, vs = zip(*cur.profile)
        speed = float(np.interp(-env.depth / 2, zs, vs))
    drag = sum(0.5 * env.water_density * (seg.line_type.diameter or 0.0)
               * (seg.line_type.drag.normal if seg.line_type.drag else 0.0) * speed**2
               * seg.length for seg in leg.segments) / leg.length
    th = math.radians(cur.toward_deg)
    q = np.array([drag * math.cos(th), drag * math.sin(th), -w])
    size = float(np.linalg.norm(q))
    return size, (q / size if size > 0 else np.array([0.0, 0.0, -1.0]))


def _discrete_leg_start(case: Case, leg, kind, u: float, V: float, length_scale: float,
                        force_scale: float) -> list:
    """Start of a lumped-node leg from a closed-form catenary under its typical load.

    Without a significant flow force the nodes sit on the equivalent line's catenary with its
    seabed contact. When the flow force is a tenth of the weight or more, the line is drawn
    as the catenary of the combined load (weight plus flow force at mid-depth) in the plane
    of the chord and that load, which keeps a weightless tether in a current from starting
    straight and tensionless. Element tensions are the catenary's at the element midpoints;
    a node on or below the seabed starts pressed onto it by its share of the weight.
    """
    eq_kind, w_eq = _equivalent_line(case, leg)
    env = case.environment
    A = np.array(leg.anchor, dtype=float)
    F = np.array(leg.fairlead, dtype=float)
    size, down = _line_load(case, leg)
    drag_led = size > 0 and abs(size * down[2] + w_eq) >= 0.1 * max(abs(w_eq), 1e-300) \
        and abs(down[2]) < 0.995
    if drag_led:
        chord = F - A
        along = float(chord @ down)
        perp = chord - along * down
        Xp = float(np.linalg.norm(perp))
        e_perp = perp / Xp if Xp > 1e-12 else np.cross(down, [0.0, 0.0, 1.0])
        kind_q = LegKind(elastic=False, contact=False)
        Hq, Vq = initial_state(kind_q, Xp, -along, leg.length, size, None)
        prof = leg_profile(kind_q, H=max(Hq, 0.0), V=Vq, L=leg.length, w=size, ea=None,
                           mu=0.0, X=Xp, Z=-along, n=401)
        points = (A[None, :] + prof["x"][:, None] * e_perp[None, :]
                  - prof["z"][:, None] * down[None, :])
    else:
        X = math.hypot(*(F - A)[:2])
        ux, uy = ((F[0] - A[0]) / X, (F[1] - A[1]) / X) if X > 1e-12 else (1.0, 0.0)
        prof = leg_profile(eq_kind, H=max(u, 0.0), V=V, L=leg.length, w=w_eq, ea=None,
                           mu=0.0, X=X, Z=F[2] - A[2], n=401)
        points = np.stack([A[0] + ux * prof["x"], A[1] + uy * prof["x"], A[2] + prof["z"]],
                          axis=1)
    lengths, weights = [], []
    for seg, m in zip(leg.segments, kind.elements):
        lengths += [seg.length / m] * m
        weights += [seg.line_type.weight_in_water * seg.length / m] * m
    arc = np.concatenate([[0.0], np.cumsum(lengths)])
    mid = (arc[1:] + arc[:-1]) / 2
    floor = max(1e-6 * force_scale, 0.05 * size * leg.length)
    tensions = np.maximum(np.interp(mid, prof["s"], prof["tension"]), floor)
    k_N = force_scale / length_scale
    block = list(tensions)
    for j in range(1, kind.n_elements):
        px, py, z = (float(np.interp(arc[j], prof["s"], points[:, c])) for c in range(3))
        above = z - env.seabed_z(px, py)
        if above <= 1e-6 * max(env.depth, 1.0):
            zeta = -max((weights[j - 1] + weights[j]) / 2, 1e-6 * force_scale) / k_N
        else:
            zeta = above
        block += [px, py, zeta]
    return block


def _discrete_leg_result(case, leg, kind, row, nodes, p, i) -> LegResult:
    """The result of a lumped-node leg: CONTRACT fields, a 3-D profile through its nodes."""
    env = case.environment
    H, VF, HA, VA_raw, grounded, susp_x, _, _, X, Z, gx, gy = (float(v) for v in row[:12])
    start_i = len(ENV_PARAMS) + i * len(LEG_PARAMS)
    anchor = tuple(float(v) for v in p[start_i: start_i + 3])
    fairlead = (gx, gy, leg.fairlead[2])
    on_bed = anchor[2] <= env.seabed_z(anchor[0], anchor[1]) + 1e-9 * max(env.depth, 1.0)
    flags = nodes[:, 7] > 0.5
    # The anchor's vertical pull: the seabed takes a downward one when the anchor lies on it.
    VA = max(VA_raw, 0.0) if on_bed else VA_raw
    td = X - susp_x if (on_bed and flags[1]) else None
    profile = {"x_m": nodes[:, 2].copy(), "y_m": nodes[:, 3].copy(), "z_m": nodes[:, 4].copy(),
               "tension_N": nodes[:, 5].copy(), "seabed_reaction_N": nodes[:, 6].copy()}
    segments, joints = [], []
    start = 0
    for k, (seg, m) in enumerate(zip(leg.segments, kind.elements)):
        part = nodes[start: start + m + 1]
        lt = seg.line_type
        segments.append({"type": lt.name, "length_m": seg.length, "elements": m,
                         "top_tension_N": float(part[-1, 5]),
                         "bottom_tension_N": float(part[0, 5]),
                         "max_tension_N": float(np.max(part[:, 5])),
                         "utilisation": float(np.max(part[:, 5])) / lt.mbl if lt.mbl else None})
        start += m
        if k < len(leg.segments) - 1:
            clump = leg.joint_clumps[k]
            node = nodes[start]
            joints.append({"position_m": [float(v) for v in node[2:5]],
                           "height_above_seabed_m": float(node[4] - env.seabed_z(node[2],
                                                                                 node[3])),
                           "on_seabed": bool(node[7] > 0.5),
                           "seabed_reaction_N": float(node[6]),
                           "clump_weight_N": clump.weight if clump is not None else 0.0})
    uplift = VA_raw > 0 and not (on_bed and flags[1])
    mbl = min((seg.line_type.mbl for seg in leg.segments if seg.line_type.mbl), default=None)
    u_dir = ((gx - anchor[0]) / X, (gy - anchor[1]) / X) if X > 1e-12 else (1.0, 0.0)
    return LegResult(
        name=leg.name,
        fairlead_tension_N=math.hypot(H, VF), horizontal_tension_N=H,
        fairlead_vertical_N=VF, anchor_tension_N=math.hypot(HA, VA),
        anchor_horizontal_N=HA, anchor_vertical_N=VA,
        grounded_length_m=grounded, touchdown_from_anchor_m=td or 0.0,
        uplift=bool(uplift), slack=bool(H <= 1e-9 * max(abs(VF), 1.0)),
        uplift_angle_deg=math.degrees(math.atan2(VA, HA)) if uplift else 0.0,
        fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
        anchor=anchor, fairlead=fairlead,
        touchdown_point=((anchor[0] + u_dir[0] * td, anchor[1] + u_dir[1] * td,
                          env.seabed_z(anchor[0] + u_dir[0] * td, anchor[1] + u_dir[1] * td))
                         if td is not None else None),
        mbl_N=mbl, profile=profile,
        segments=tuple(segments) if leg.multi_segment else (),
        joints=tuple(joints))


def _anchor_touchdown(rows, leg, kind):
    """Distance from the anchor [m] where the line first leaves the seabed (None: uplift).

    The grounded run starts at the anchor and continues through segments lying wholly on
    the seabed; it ends in the first segment that lifts off.
    """
    for k, r in enumerate(rows):
        reversed_top = k == len(rows) - 1 and kind.reversed_top
        if r["grounded"] <= 0 or reversed_top or r["lower_h"] > 0:
            return r["lower_xi"] if k else None
        if r["grounded"] < leg.segments[k].length * (1 - 1e-12):
            return r["lower_xi"] + r["X"] - r["suspended_x"]
    return rows[-1]["lower_xi"] + rows[-1]["X"]
