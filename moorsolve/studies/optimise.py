"""Design optimisation: line lengths and anchor positions over many load cases, one NLP.

The problem
-----------
Design variables ``d`` (line lengths, anchor distances or radii, each shared by a group of
legs, continuous and bounded) enter the equilibrium of every load case ``k`` through its
parameter vector ``p_k(d)`` (:func:`moorsolve.solve.assembly.problem.parameter_vector`, with the
design's entries replaced by expressions of ``d``). Each load case keeps its own copy of the
equilibrium unknowns ``x_k``. One IPOPT problem

    minimise    f(d)                                  line mass or cost
    subject to  g_k(x_k, p_k(d)) = 0                  equilibrium of every load case
                h_j(x_k, p_k(d); b_j) <= 0            design constraints with limits b_j
                c(d) / c_max - 1 <= 0                 the cost cap (max_cost), design-wide
                d_lo <= d <= d_hi

is solved from the starting design solved at every load case by :func:`moorsolve.solve`
(its certified scaled states), so IPOPT starts on the equilibrium manifold.

Constraints, written to be smooth where they are active
-------------------------------------------------------
* safety factor ``SF``: ``T SF / MBL - 1 <= 0``, ``T = sqrt(H^2 + V^2)`` the fairlead
  tension of a sinking line (its largest), the anchor tension of a buoyant one;
* anchor uplift: ``(V - w L) - b <= 0`` for a one-segment leg whose anchor rests on a flat
  seabed. ``V - w L`` is the signed vertical force at the anchor, the same expression in
  both regimes of the leg block (negative: the line arrives along the seabed), so the
  constraint has no kink at touchdown, where a drag anchor (``b = 0``) makes it active;
* grounded length: ``b - (L - V / w) <= 0`` (``L - V/w`` is the grounded length while the
  line touches down, and negative, hence infeasible, when the anchor lifts);
* offset: ``(x^2 + y^2) / b^2 - 1 <= 0``;
* cost cap: ``c(d) / c_max - 1 <= 0``, ``c`` the design's cost priced as for the cost
  objective (lines and anchors), once for the whole design: it is the same in every load
  case. When no design meets it, the least-cost design that meets every load-case
  constraint is found (the study again with the cost objective and no cap) and reported.

Multipliers
-----------
With ``L = f/f0 + lambda^T h`` (IPOPT's ``lam_g >= 0`` for an active ``h <= 0``), the
envelope theorem gives the change of the optimal objective with a limit:
``df*/db_j = f0 lambda_j dh_j/db_j``, reported as what relaxing the limit by one step
would save (a linear estimate). An active bound of a design variable likewise saves
``|lam_x| f0 / ref`` per metre.

After the solve every load case is solved again by :func:`moorsolve.solve` at the optimum
design, independently (no warm start), and each constraint is checked on those results.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time

import casadi as ca
import numpy as np

from ..model.study import Limits, Study
from ..errors import CaseError, ConvergenceError
from ..model import Case
from ..solve.kernels.bundled_blas import limit_bundled_blas
from ..solve.assembly.cache import get_problem
from ..solve.equilibrium import solve
from ..solve.assembly.layout import ENV_PARAMS, LEG_PARAMS
from ..solve.assembly.prepared import parameter_vector
from .optimise_design import (_anchor_line, _leg_index, _objective, cost_value, design_case,
                              load_case_scene, objective_value)
from .optimise_results import (_KINDS, ACTIVE_TOL, DESIGN_WIDE, VERIFY_TOL, ConstraintResult,
                               Optimisation, VariableResult, _amount)
from .optimise_verify import _infeasible, verify_design

log = logging.getLogger(__name__)

_I_ANCHOR_X = LEG_PARAMS.index("anchor_x")
_I_ANCHOR_Y = LEG_PARAMS.index("anchor_y")
_I_LENGTH = LEG_PARAMS.index("length")
_I_WEIGHT = LEG_PARAMS.index("weight")

#: A constraint is reported active when its scaled value is within this of its limit.

def optimise(case: Case, study, *, verify: bool = True) -> Optimisation:
    """Choose the study's design variables to minimise line mass or cost over its load cases.

    Parameters
    ----------
    case : Case
        The base case (from :func:`moorsolve.load_case`).
    study : Study
        A validated :class:`~moorsolve.model.study.Study` (a study file or dict is read by
        :func:`moorsolve.io.study_file.load_study`, or given to :func:`moorsolve.optimise`).
    verify : bool
        Re-solve every load case independently at the optimum and check each constraint.

    Returns
    -------
    Optimisation

    Raises
    ------
    CaseError
        A bad study (naming its field), or a design variable on a leg the optimisation
        cannot vary in some load case (a line discretised in a current).
    TypeError
        ``study`` is not a :class:`~moorsolve.model.study.Study`.
    ConvergenceError
        A load case has no equilibrium at the starting design, or no feasible design was
        found (the reason lists the constraints not met and the residual reached).
    """
    if not isinstance(study, Study):
        raise TypeError(f"study: {type(study).__name__}, not a Study; read a study file with "
                        "moorsolve.io.study_file.load_study, or give it to moorsolve.optimise")
    t_all = time.perf_counter()
    n_d = len(study.variables)
    d0 = np.array([v.start for v in study.variables], dtype=float)
    ref = np.maximum(np.abs(d0), 1.0)
    start = design_case(case, study, d0)
    index = _leg_index(case)

    scenes, states = [], []
    for k, lc in enumerate(study.load_cases):
        scene = load_case_scene(start, study, k)
        try:
            result = solve(scene, allow_overload=True)
        except ConvergenceError as exc:
            raise ConvergenceError(
                f"load case {lc.name!r} has no equilibrium at the starting design: "
                f"{exc.reason}", residual_N=exc.residual_N, residual_Nm=exc.residual_Nm,
                status=exc.status, iterations=exc.iterations) from None
        scenes.append(scene)
        states.append(np.asarray(result.state, float))

    dz = ca.SX.sym("d", n_d)
    d = dz * ca.DM(ref)
    lengths = {leg.name: leg.length for leg in start.legs}
    for j, var in enumerate(study.variables):
        if var.kind == "length":
            for name in var.legs:
                lengths[name] = d[j]
    f_expr = _objective(start, study, lengths)
    f0 = float(objective_value(start, study))
    f_scale = abs(f0) if f0 != 0 else 1.0

    xs_all, x0_all, lbx, ubx = [dz], [d0 / ref], [np.array([v.lower for v in study.variables])
                                                  / ref], [
        np.array([v.upper for v in study.variables]) / ref]
    eqs, ineqs, records, notes = [], [], [], []
    body_syms = []
    for k, (lc, scene) in enumerate(zip(study.load_cases, scenes)):
        problem = get_problem(scene)
        _check_design_legs(problem, study, index, lc.name)
        xk = ca.SX.sym(f"x{k}", problem.n_x)
        pk = _parameters(scene, case, study, index, d)
        xs_all.append(xk)
        x0_all.append(states[k])
        lb, ub = problem.bounds()
        lbx.append(lb)
        ubx.append(ub)
        eqs.append(problem.residual(xk, pk))
        table = problem.report(xk, pk)[0]
        xp = xk * ca.DM(problem.x_scale)
        body = {dof: xp[i] for i, dof in enumerate(problem.free)}
        body_syms.append(body)
        new, skipped = _constraints(k, lc, scene, problem, table, pk, body)
        records += new
        notes += [f"load case {lc.name!r}: {text}" for text in skipped]
    if study.max_cost is not None:
        records.append(_cost_record(_objective(start, study, lengths, "cost"), study.max_cost))
    n_eq = sum(e.numel() for e in eqs)

    b = ca.SX.sym("b", len(records))
    for j, rec in enumerate(records):
        ineqs.append(rec["h"](b[j]))
    h = ca.vertcat(*ineqs) if ineqs else ca.SX(0, 1)
    z = ca.vertcat(*xs_all)
    g = ca.vertcat(*eqs, h)
    f = f_expr / f_scale
    b_val = np.array([rec["limit"] for rec in records], dtype=float)
    nlp = {"x": z, "p": b, "f": f, "g": g}
    opts = {"print_time": False, "error_on_fail": False, "show_eval_warnings": False,
            "calc_lam_p": False,
            "ipopt": {"print_level": 0, "sb": "yes", "tol": study.tol,
                      "constr_viol_tol": min(study.tol, 1e-9), "acceptable_tol": 1e-6,
                      "max_iter": study.max_iter, "mu_strategy": "adaptive"}}
    t_build = time.perf_counter()
    solver = ca.nlpsol("design", "ipopt", nlp, opts)
    limit_bundled_blas()
    lbg = np.concatenate([np.zeros(n_eq), np.full(len(records), -np.inf)])
    ubg = np.zeros(n_eq + len(records))
    z0 = np.concatenate(x0_all)
    t_solve = time.perf_counter()
    sol = solver(x0=z0, p=b_val, lbx=np.concatenate(lbx), ubx=np.concatenate(ubx),
                 lbg=lbg, ubg=ubg)
    solve_time = time.perf_counter() - t_solve
    log.debug("design NLP built in %.2f s, solved in %.2f s", t_solve - t_build, solve_time)
    stats = solver.stats()
    status = str(stats.get("return_status", "unknown"))
    iterations = int(stats.get("iter_count", 0))
    z_opt = np.asarray(sol["x"]).ravel()
    g_opt = np.asarray(sol["g"]).ravel()
    lam_g = np.asarray(sol["lam_g"]).ravel()
    lam_x = np.asarray(sol["lam_x"]).ravel()
    d_opt = np.clip(z_opt[:n_d] * ref, [v.lower for v in study.variables],
                    [v.upper for v in study.variables])
    h_opt = g_opt[n_eq:]
    eq_res = float(np.max(np.abs(g_opt[:n_eq]))) if n_eq else 0.0

    values_fn = ca.Function("values", [z, b], [ca.vertcat(*[r["value"] for r in records])
                                               if records else ca.SX(0, 1)])
    dh_db = ca.Function("dh_db", [z, b], [ca.diag(ca.jacobian(h, b)) if records
                                          else ca.SX(0, 1)])
    values = np.asarray(values_fn(z_opt, b_val)).ravel()
    slopes = np.asarray(dh_db(z_opt, b_val)).ravel()

    if status not in ("Solve_Succeeded", "Solved_To_Acceptable_Level") \
            or eq_res > 1e-6 or (h_opt.size and h_opt.max() > 1e-6):
        error = _infeasible(status, iterations, records, h_opt, eq_res, case, study, d_opt)
        raise error if study.max_cost is None else _cost_infeasible(case, study, error)

    constraints = []
    for j, rec in enumerate(records):
        unit, step, relax, _ = _KINDS[rec["kind"]]
        if rec["kind"] == "cost":
            # In the study's currency, relaxed by 1 % of the cap.
            unit, step = study.currency, 0.01 * rec["limit"]
        lam = float(max(lam_g[n_eq + j], 0.0))
        saving = -lam * slopes[j] * f_scale * relax * step
        constraints.append(ConstraintResult(
            load_case=rec["load_case"], kind=rec["kind"], leg=rec["leg"],
            value=float(rec["show"](values[j])), limit=rec["limit"], unit=unit,
            margin=float(rec["margin"](values[j])), active=bool(h_opt[j] > -ACTIVE_TOL),
            multiplier=lam, saving=float(saving), step=step))
    variables = []
    for j, var in enumerate(study.variables):
        lam = float(lam_x[j])
        at = ""
        if d_opt[j] <= var.lower + 1e-6 * ref[j]:
            at = "lower"
        elif d_opt[j] >= var.upper - 1e-6 * ref[j]:
            at = "upper"
        variables.append(VariableResult(
            name=var.name, kind=var.kind, legs=var.legs, start=float(d0[j]),
            optimum=float(d_opt[j]), lower=var.lower, upper=var.upper, at_bound=at,
            saving_per_m=float(abs(lam) * f_scale / ref[j]) if at else 0.0))

    optimised = design_case(case, study, d_opt)
    data = dict(optimised.source) if optimised.source is not None else {}
    verification = []
    if verify:
        verification = verify_design(optimised, study, records, z_opt, xs_all)
    priced = study.objective == "cost" or study.max_cost is not None
    return Optimisation(
        study_name=study.name, case_name=case.name, objective=study.objective,
        unit="kg" if study.objective == "mass" else study.currency,
        objective_start=f0, objective_optimum=float(objective_value(optimised, study)),
        variables=variables, constraints=constraints, verification=verification,
        status=status, iterations=iterations, solve_time_s=solve_time,
        total_time_s=time.perf_counter() - t_all, optimised_case=optimised,
        optimised_data=data, notes=tuple(dict.fromkeys(notes)),
        cost=float(cost_value(optimised, study)) if priced else None,
        max_cost=study.max_cost, currency=study.currency if priced else None)


def _cost_record(cost, cap: float) -> dict:
    """The design-wide cost cap as a constraint record (``cost`` an expression of ``d``)."""
    return dict(load_case=DESIGN_WIDE, k=None, kind="cost", leg=None, i=None, limit=cap,
                value=cost, h=lambda b, c=cost: c / b - 1, show=lambda v: v,
                margin=lambda v, cap=cap: cap - v)


def _cost_infeasible(case: Case, study: Study, error: ConvergenceError) -> ConvergenceError:
    """When the cost cap is what no design meets: say so, with the least cost reached."""
    free = dataclasses.replace(study, objective="cost", max_cost=None)
    try:
        least = optimise(case, free, verify=True)
    except ConvergenceError:
        return error  # the load-case constraints cannot be met even without the cap
    cap = study.max_cost
    if least.cost <= cap * (1 + VERIFY_TOL) or not least.verified:
        return error
    design = ", ".join(f"{v.name} = {v.optimum:.3f} m" for v in least.variables)
    return ConvergenceError(
        f"no feasible design: no design within the variables' bounds meets max_cost "
        f"{_amount(cap, study.currency)}; the least cost of a design that meets every "
        f"load-case constraint is {_amount(least.cost, study.currency)} (cost utilisation "
        f"{least.cost / cap:.4f}), at {design}", status=error.status,
        iterations=error.iterations, residual_N=float("nan"), residual_Nm=float("nan"))


def _check_design_legs(problem, study: Study, index: dict, lc_name: str) -> None:
    for j, var in enumerate(study.variables):
        for name in var.legs:
            kind = problem.kinds[index[name]]
            if not kind.single:
                raise CaseError(f"variables.{var.name}.legs",
                                f"leg {name!r} is modelled as a discretised line in load case "
                                f"{lc_name!r} (a current drags on it); design variables "
                                "apply to analytic one-segment legs")


def _parameters(scene: Case, base: Case, study: Study, index: dict, d):
    """The parameter vector of ``scene`` with the design's entries as expressions of ``d``."""
    p = ca.SX(ca.DM(parameter_vector(scene, 1.0)))
    n_env, n_leg = len(ENV_PARAMS), len(LEG_PARAMS)
    legs = {leg.name: leg for leg in base.legs}
    for j, var in enumerate(study.variables):
        for name in var.legs:
            at = n_env + index[name] * n_leg
            if var.kind == "length":
                p[at + _I_LENGTH] = d[j]
            else:
                (ox, oy), (ux, uy) = _anchor_line(base, legs[name], var.kind)
                p[at + _I_ANCHOR_X] = ox + ux * d[j]
                p[at + _I_ANCHOR_Y] = oy + uy * d[j]
    return p


def _constraints(k: int, lc, scene: Case, problem, table, p, body) -> tuple:
    """Constraint records of load case ``k`` and notes on limits that do not apply."""
    limits: Limits = lc.limits
    records, skipped = [], []
    n_env, n_leg = len(ENV_PARAMS), len(LEG_PARAMS)
    for i, (leg, kind) in enumerate(zip(scene.legs, problem.kinds)):
        row = table[i, :]
        H, VF, HA, VA = row[0], row[1], row[2], row[3]
        if limits.safety_factor is not None:
            mbl = min(seg.line_type.mbl for seg in leg.segments)
            buoyant = leg.segments[-1].line_type.weight_in_water < 0
            T = ca.sqrt(HA**2 + VA**2) if buoyant else ca.sqrt(H**2 + VF**2)
            records.append(dict(
                load_case=lc.name, k=k, kind="safety_factor", leg=leg.name, i=i,
                limit=limits.safety_factor, value=T, mbl=mbl,
                h=lambda sf, T=T, mbl=mbl: T * sf / mbl - 1,
                show=lambda t, mbl=mbl: mbl / t if t > 0 else math.inf,
                margin=lambda t, mbl=mbl, sf=limits.safety_factor:
                    (mbl / t if t > 0 else math.inf) - sf))
        simple = (kind.single and kind.block.contact and not kind.sloped
                  and leg.line_type.weight_in_water > 0)
        wanted = [key for key in ("max_anchor_uplift", "min_grounded_length")
                  if getattr(limits, key) is not None]
        if wanted and not simple:
            skipped.append(f"anchor uplift and grounded length are not constrained on leg "
                           f"{leg.name} (only one-segment legs with the anchor on a flat "
                           "seabed are)")
            continue
        at = n_env + i * n_leg
        L, w = p[at + _I_LENGTH], p[at + _I_WEIGHT]
        scale_f = problem.force_scale
        if limits.max_anchor_uplift is not None:
            up = VF - w * L
            lim = limits.max_anchor_uplift
            records.append(dict(
                load_case=lc.name, k=k, kind="anchor_uplift", leg=leg.name, i=i, limit=lim,
                value=up, h=lambda b, up=up, s=scale_f: (up - b) / s,
                show=lambda v: max(v, 0.0), margin=lambda v, lim=lim: lim - max(v, 0.0)))
        if limits.min_grounded_length is not None:
            grounded = L - VF / w
            lim = limits.min_grounded_length
            s = max(leg.length, 1.0)
            records.append(dict(
                load_case=lc.name, k=k, kind="grounded_length", leg=leg.name, i=i, limit=lim,
                value=grounded, h=lambda b, gl=grounded, s=s: (b - gl) / s,
                show=lambda v: max(v, 0.0), margin=lambda v, lim=lim: v - lim))
    if limits.offset_limit is not None:
        r2 = body.get("surge", 0) ** 2 + body.get("sway", 0) ** 2
        lim = limits.offset_limit
        if isinstance(r2, (int, float)):
            skipped.append("the offset limit does not apply: surge and sway are not free")
        else:
            records.append(dict(
                load_case=lc.name, k=k, kind="offset", leg=None, i=None, limit=lim,
                value=ca.sqrt(r2 + 1e-30), h=lambda b, r2=r2: r2 / b**2 - 1,
                show=lambda v: v, margin=lambda v, lim=lim: lim - v))
    return records, skipped


