"""Design optimisation: line lengths and anchor positions over many load cases, one NLP.

The problem
-----------
Design variables ``d`` (line lengths, anchor distances or radii, each shared by a group of
legs, continuous and bounded) enter the equilibrium of every load case ``k`` through its
parameter vector ``p_k(d)`` (:func:`moorsolve.solve.problem.parameter_vector`, with the
design's entries replaced by expressions of ``d``). Each load case keeps its own copy of the
equilibrium unknowns ``x_k``. One IPOPT problem

    minimise    f(d)                                  line mass or cost
    subject to  g_k(x_k, p_k(d)) = 0                  equilibrium of every load case
                h_j(x_k, p_k(d); b_j) <= 0            design constraints with limits b_j
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
* offset: ``(x^2 + y^2) / b^2 - 1 <= 0``.

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
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ..model.study import Limits, Study
from ..errors import CaseError, ConvergenceError
from ..model import Case
from ..solve.cache import get_problem
from ..solve.equilibrium import solve
from ..solve.layout import ENV_PARAMS, LEG_PARAMS, parameter_vector

log = logging.getLogger(__name__)

_I_ANCHOR_X = LEG_PARAMS.index("anchor_x")
_I_ANCHOR_Y = LEG_PARAMS.index("anchor_y")
_I_LENGTH = LEG_PARAMS.index("length")
_I_WEIGHT = LEG_PARAMS.index("weight")

#: A constraint is reported active when its scaled value is within this of its limit.
ACTIVE_TOL = 1e-5
#: A verified value may exceed its limit by this fraction of the limit's scale.
VERIFY_TOL = 1e-6

#: Per constraint kind: unit of value and limit, the step used to put a multiplier into
#: words, the direction that relaxes the limit (+1: raise it) and its description.
_KINDS = {
    "safety_factor": ("-", 0.1, -1, "safety factor"),
    "anchor_uplift": ("N", 10e3, +1, "anchor uplift limit"),
    "grounded_length": ("m", 1.0, -1, "minimum grounded length"),
    "offset": ("m", 1.0, +1, "offset limit"),
}


# ---- result --------------------------------------------------------------------------------


@dataclass(frozen=True)
class VariableResult:
    """One design variable at the optimum [m]."""

    name: str
    kind: str
    legs: tuple
    start: float
    optimum: float
    lower: float
    upper: float
    at_bound: str          # "", "lower" or "upper"
    saving_per_m: float    # objective saved per metre of relaxing the active bound

    @property
    def change(self) -> float:
        return self.optimum - self.start

    def to_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["legs"] = list(self.legs)
        d["change"] = self.change
        return d


@dataclass(frozen=True)
class ConstraintResult:
    """One design constraint in one load case at the optimum.

    ``value`` and ``limit`` in ``unit`` (the safety factor achieved for ``safety_factor``);
    ``margin`` is positive when satisfied; ``saving`` is the objective saved by relaxing
    the limit by ``step`` (linear estimate from the multiplier).
    """

    load_case: str
    kind: str
    leg: str | None
    value: float
    limit: float
    unit: str
    margin: float
    active: bool
    multiplier: float
    saving: float
    step: float

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class Verification:
    """The independent re-solve of one load case at the optimum design."""

    load_case: str
    certified: bool
    residual_N: float
    offset_m: float | None
    position_difference_m: float
    violations: tuple
    reason: str = ""

    def to_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["violations"] = list(self.violations)
        return d


@dataclass(frozen=True)
class Optimisation:
    """The outcome of :func:`optimise`.

    Attributes
    ----------
    objective : str
        ``mass`` or ``cost``; ``unit`` is ``kg`` or the study's currency.
    objective_start, objective_optimum : float
        Total line mass [kg] or cost at the starting and optimum designs (all legs).
    variables : list of VariableResult
    constraints : list of ConstraintResult
    verification : list of Verification
    status : str
        IPOPT's return status; ``iterations`` its iteration count.
    solve_time_s, total_time_s : float
        IPOPT's time, and everything (start solves, build, verification).
    optimised_case : Case
    optimised_data : dict
        Case-file data of the optimised design (for writing a case file).
    """

    study_name: str
    case_name: str
    objective: str
    unit: str
    objective_start: float
    objective_optimum: float
    variables: list
    constraints: list
    verification: list
    status: str
    iterations: int
    solve_time_s: float
    total_time_s: float
    optimised_case: Case = field(repr=False)
    optimised_data: dict = field(repr=False)
    notes: tuple = ()

    @property
    def verified(self) -> bool:
        """Every load case re-solved, certified and within every limit."""
        return all(v.certified and not v.violations for v in self.verification)

    @property
    def active(self) -> list:
        return [c for c in self.constraints if c.active]

    def plain_words(self) -> list:
        """The active constraints and bounds and what relaxing them is worth."""
        return _plain_words(self)

    def to_dict(self) -> dict:
        return {
            "study": self.study_name, "case": self.case_name,
            "objective": self.objective, "unit": self.unit,
            "objective_start": self.objective_start,
            "objective_optimum": self.objective_optimum,
            "saving": self.objective_start - self.objective_optimum,
            "status": self.status, "iterations": self.iterations,
            "solve_time_s": self.solve_time_s, "total_time_s": self.total_time_s,
            "verified": self.verified,
            "variables": [v.to_dict() for v in self.variables],
            "constraints": [c.to_dict() for c in self.constraints],
            "active": self.plain_words(),
            "verification": [v.to_dict() for v in self.verification],
            "notes": list(self.notes),
        }


# ---- design edits ----------------------------------------------------------------------------


def _leg_index(case: Case) -> dict:
    return {leg.name: i for i, leg in enumerate(case.legs)}


def _anchor_line(case: Case, leg, kind: str) -> tuple:
    """``(origin, unit direction)`` in the plane along which an anchor variable moves it."""
    ax, ay = leg.anchor[0], leg.anchor[1]
    ox, oy = (leg.fairlead[0], leg.fairlead[1]) if kind == "anchor_distance" else (0.0, 0.0)
    r = math.hypot(ax - ox, ay - oy)
    return (ox, oy), ((ax - ox) / r, (ay - oy) / r)


def design_edits(case: Case, study: Study, values) -> dict:
    """Case-file edits (dotted path -> value) that put design ``values`` into ``case``."""
    legs = {leg.name: leg for leg in case.legs}
    edits = {}
    for var, value in zip(study.variables, values):
        for name in var.legs:
            leg = legs[name]
            if var.kind == "length":
                edits[f"legs[{name}].segments[0].length"] = float(value)
            else:
                (ox, oy), (ux, uy) = _anchor_line(case, leg, var.kind)
                edits[f"legs[{name}].anchor"] = [ox + ux * float(value), oy + uy * float(value),
                                                 float(leg.anchor[2])]
    return edits


def design_case(case: Case, study: Study, values) -> Case:
    """``case`` with the design ``values`` (one per study variable) applied."""
    from ..io.study_file import load_case_variant
    return load_case_variant(case, design_edits(case, study, values), "design")


def load_case_scene(design: Case, study: Study, k: int) -> Case:
    """Load case ``k`` of ``study`` applied to the case ``design``."""
    from ..io.study_file import load_case_variant
    return load_case_variant(design, study.load_cases[k].edits, f"load_cases[{k}]")


def objective_value(case: Case, study: Study) -> float:
    """Total line mass [kg] or cost of ``case`` under the study's prices."""
    return _objective(case, study, {leg.name: leg.length for leg in case.legs})


def _objective(case: Case, study: Study, lengths: dict):
    total = 0
    for leg in case.legs:
        if leg.multi_segment:
            parts = [(seg.line_type.name, seg.length) for seg in leg.segments]
        else:
            parts = [(leg.line_type.name, lengths[leg.name])]
        for lt_name, length in parts:
            if study.objective == "mass":
                total = total + length * study.mass_per_length[lt_name]
            else:
                total = total + length * study.cost_per_length[lt_name]
    if study.objective == "cost":
        total = total + study.anchor_cost * len(case.legs)
    return total


# ---- the optimisation ------------------------------------------------------------------------


def optimise(case: Case, study, *, verify: bool = True) -> Optimisation:
    """Choose the study's design variables to minimise line mass or cost over its load cases.

    Parameters
    ----------
    case : Case
        The base case (from :func:`moorsolve.load_case`).
    study : Study, str, pathlib.Path or mapping
        A validated :class:`~moorsolve.model.study.Study` or a study file / dict
        (:func:`moorsolve.io.study_file.load_study`).
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
    ConvergenceError
        A load case has no equilibrium at the starting design, or no feasible design was
        found (the reason lists the constraints not met and the residual reached).
    """
    from ..io.study_file import load_study
    if not isinstance(study, Study):
        study = load_study(study, case)
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
        raise _infeasible(status, iterations, records, h_opt, eq_res, case, study, d_opt)

    constraints = []
    for j, rec in enumerate(records):
        unit, step, relax, _ = _KINDS[rec["kind"]]
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
    return Optimisation(
        study_name=study.name, case_name=case.name, objective=study.objective,
        unit="kg" if study.objective == "mass" else study.currency,
        objective_start=f0, objective_optimum=float(objective_value(optimised, study)),
        variables=variables, constraints=constraints, verification=verification,
        status=status, iterations=iterations, solve_time_s=solve_time,
        total_time_s=time.perf_counter() - t_all, optimised_case=optimised,
        optimised_data=data, notes=tuple(dict.fromkeys(notes)))


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


def _infeasible(status, iterations, records, h, eq_res, case, study, d) -> ConvergenceError:
    """The constraints not met at the design IPOPT ended at, from independent solves there
    (IPOPT's restoration phase may end off the equilibrium, where its own values mean
    nothing physical)."""
    unmet, worst = [], 0.0
    try:
        designed = design_case(case, study, d)
        results = [solve(load_case_scene(designed, study, k), allow_overload=True)
                   for k in range(len(study.load_cases))]
    except (ConvergenceError, CaseError):
        results = None
    if results is not None:
        for rec in records:
            value = _result_value(rec, results[rec["k"]])
            unit, _, relax, label = _KINDS[rec["kind"]]
            excess = relax * (value - rec["limit"])
            if excess > VERIFY_TOL * max(abs(rec["limit"]), 1.0):
                unmet.append((excess / max(abs(rec["limit"]), 1.0), rec, value))
    unmet.sort(key=lambda item: -item[0])
    parts = []
    for _, rec, value in unmet[:8]:
        unit, _, _, label = _KINDS[rec["kind"]]
        where = f" of leg {rec['leg']}" if rec["leg"] else ""
        parts.append(f"{label}{where} in load case {rec['load_case']!r}: "
                     f"{_fmt(value, unit)} against {_fmt(rec['limit'], unit)}")
    worst = float(h.max()) if len(h) else 0.0
    design = ", ".join(f"{v.name} = {x:.3f} m" for v, x in zip(study.variables, d))
    text = f"no feasible design within the variables' bounds (IPOPT: {status})"
    if parts:
        text += f"; at the design reached ({design}) these constraints are not met: " + \
            "; ".join(parts)
        if len(unmet) > len(parts):
            text += f" (and {len(unmet) - len(parts)} more)"
    text += (f"; residual reached: equilibrium {eq_res:.3g}, constraints {max(worst, 0):.3g} "
             "(scaled)")
    return ConvergenceError(text, status=status, iterations=iterations,
                            residual_N=float("nan"), residual_Nm=float("nan"))


def _result_value(rec, result) -> float:
    """A constraint's value (as reported) from an ordinary solve's Result."""
    if rec["kind"] == "offset":
        return math.hypot(result.body["x_m"], result.body["y_m"])
    lr = result.legs[rec["i"]]
    if rec["kind"] == "safety_factor":
        T = max(lr.fairlead_tension_N, lr.anchor_tension_N)
        return rec["mbl"] / T if T > 0 else math.inf
    if rec["kind"] == "anchor_uplift":
        return lr.anchor_vertical_N
    return lr.grounded_length_m


def _fmt(value: float, unit: str) -> str:
    if unit == "N":
        return f"{value / 1e3:.1f} kN"
    if unit == "-":
        return f"{value:.3f}"
    return f"{value:.3f} {unit}"


# ---- verification -------------------------------------------------------------------------


def verify_design(optimised: Case, study: Study, records, z_opt=None, xs_all=None) -> list:
    """Solve every load case of ``study`` at the ``optimised`` case independently and
    check each constraint record on the results."""
    out = []
    offsets_nlp = {}
    if z_opt is not None and xs_all is not None:
        cursor = xs_all[0].numel()
        for k, xk in enumerate(xs_all[1:]):
            n = xk.numel()
            offsets_nlp[k] = z_opt[cursor: cursor + n]
            cursor += n
    for k, lc in enumerate(study.load_cases):
        scene = load_case_scene(optimised, study, k)
        try:
            result = solve(scene, allow_overload=True)
        except ConvergenceError as exc:
            out.append(Verification(load_case=lc.name, certified=False,
                                    residual_N=exc.residual_N, offset_m=None,
                                    position_difference_m=math.nan, violations=(),
                                    reason=exc.reason))
            continue
        violations = []
        for rec in records:
            if rec["k"] != k:
                continue
            violations += _check(rec, result)
        offset = None if result.body is None else math.hypot(result.body["x_m"],
                                                             result.body["y_m"])
        diff = 0.0
        if k in offsets_nlp and result.body is not None:
            problem = get_problem(scene)
            xp = offsets_nlp[k] * problem.x_scale
            q = dict(zip(problem.free, xp))
            diff = math.hypot(q.get("surge", 0.0) - result.body["x_m"],
                              q.get("sway", 0.0) - result.body["y_m"])
        out.append(Verification(load_case=lc.name, certified=result.converged,
                                residual_N=result.certificate.force_N, offset_m=offset,
                                position_difference_m=diff, violations=tuple(violations)))
    return out


def _check(rec, result) -> list:
    kind, lim = rec["kind"], rec["limit"]
    value = _result_value(rec, result)
    unit, _, relax, label = _KINDS[kind]
    scale = max(abs(lim), 1.0) if kind != "anchor_uplift" else max(
        result.legs[rec["i"]].anchor_tension_N, 1.0)
    if relax * (value - lim) > VERIFY_TOL * scale:
        where = f"leg {rec['leg']}: " if rec["leg"] else ""
        return [f"{where}{label} {_fmt(value, unit)} against {_fmt(lim, unit)}"]
    return []


# ---- plain words ----------------------------------------------------------------------------


def _plain_words(opt: Optimisation) -> list:
    what = "of line" if opt.objective == "mass" else ""
    lines = []
    for c in opt.active:
        unit, step, relax, label = _KINDS[c.kind]
        where = f" on leg {c.leg}" if c.leg else ""
        verb = "relaxing it" if relax > 0 else "lowering it"
        if c.kind == "safety_factor":
            limit = f"{label} of {c.limit:g}"
            by = f"{step:g}"
        elif c.kind == "anchor_uplift":
            limit = f"{label} of {c.limit / 1e3:g} kN"
            by = f"{step / 1e3:g} kN"
        else:
            limit = f"{label} of {c.limit:g} m"
            by = f"{step:g} m"
        lines.append(f"the {limit}{where} in load case {c.load_case!r} is active; {verb} by "
                     f"{by} would save {_amount(c.saving, opt.unit)} {what}".rstrip())
    by_kind: dict = {}
    for c in opt.active:
        by_kind.setdefault(c.kind, []).append(c)
    for kind, group in by_kind.items():
        if len(group) > 1:
            unit, step, relax, label = _KINDS[kind]
            by = f"{step / 1e3:g} kN" if unit == "N" else f"{step:g}" + (" m" if unit == "m"
                                                                          else "")
            cases = len({c.load_case for c in group})
            lines.append(f"together: {'relaxing' if relax > 0 else 'lowering'} the {label} "
                         f"by {by} wherever it is active ({len(group)} constraints in {cases} "
                         f"load case{'s' if cases > 1 else ''}) would save "
                         f"{_amount(sum(c.saving for c in group), opt.unit)} {what}".rstrip())
    for v in opt.variables:
        if v.at_bound:
            bound = v.lower if v.at_bound == "lower" else v.upper
            move = "lowering" if v.at_bound == "lower" else "raising"
            lines.append(f"the {v.at_bound} bound {bound:g} m of variable {v.name!r} "
                         f"({v.kind}) is active; {move} it by 1 m would save "
                         f"{_amount(v.saving_per_m, opt.unit)} {what}".rstrip())
    return lines


def _amount(value: float, unit: str) -> str:
    if unit == "kg":
        return f"{value:,.0f} kg" if abs(value) >= 10 else f"{value:.3g} kg"
    return f"{value:,.0f} {unit}" if abs(value) >= 10 else f"{value:.3g} {unit}"
