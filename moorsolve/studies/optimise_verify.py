"""Independent checks of an optimised design: every load case re-solved from scratch, and
the constraints an infeasible study could not meet, from solves at the design IPOPT reached."""

from __future__ import annotations

import math

from ..errors import CaseError, ConvergenceError
from ..model import Case
from ..model.study import Study
from ..solve.assembly.cache import get_problem
from ..solve.equilibrium import solve
from .optimise_results import _KINDS, VERIFY_TOL, Verification
from .optimise_design import cost_value, design_case, load_case_scene


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
    for rec in records:
        if rec["kind"] == "cost":
            value = cost_value(design_case(case, study, d), study)
        elif results is None:
            continue
        else:
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
        if rec["kind"] == "cost":
            parts.append(f"{label}: {value:,.0f} against {rec['limit']:,.0f} {study.currency}")
            continue
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


