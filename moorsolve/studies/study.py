"""Design-study outputs at an equilibrium: mooring stiffness, restoring curves, natural
periods and exact parametric sensitivities.

Everything here is derived from the CasADi graph of :mod:`.problem` by automatic
differentiation and the implicit function theorem on the square residual system
``g(x, p) = 0`` of the equilibrium:

    dx/dp = -(dg/dx)^-1 dg/dp

so a derivative costs one factorisation of the Jacobian the solver already used, not a
re-solve. The finite-difference checks live in ``tests/test_study.py``.
"""

from __future__ import annotations

import dataclasses
import math
import re
import weakref
from typing import Optional, Sequence

import casadi as ca
import numpy as np

from ..model import DEGREES_OF_FREEDOM, Body, BodyLoads, Case
from ..solve.equilibrium import get_problem, solve
from ..solve.problem import ENV_PARAMS, LEG_PARAMS, parameter_vector
from ..solve.result import Result
from ..solve.stretch_params import baranov_n_column, stiffness_scale_column

#: The three horizontal-plane degrees of freedom, in the order of every matrix here.
DOFS = DEGREES_OF_FREEDOM

#: Leg outputs available to :func:`sensitivity`, in the order they are built.
LEG_OUTPUTS = ("fairlead_tension_N", "horizontal_tension_N", "fairlead_vertical_N",
               "anchor_tension_N", "anchor_horizontal_N", "anchor_vertical_N",
               "grounded_length_m")
BODY_OUTPUTS = ("x_m", "y_m", "yaw_deg")

_LEG_PARAMETERS = ("length", "ea", "weight", "anchor_x", "anchor_y", "anchor_z",
                   "fairlead_x", "fairlead_y", "fairlead_z")
_ENV_PARAMETERS = {
    "environment.wind.speed": ("wind", "wind_speed", 1.0),
    "environment.wind.toward_deg": ("wind", "wind_toward", math.pi / 180),
    "environment.current.speed": ("current", "current_speed", 1.0),
    "environment.current.toward_deg": ("current", "current_toward", math.pi / 180),
    "environment.waves.hs": ("waves", "wave_hs", 1.0),
    "environment.waves.toward_deg": ("waves", "wave_toward", math.pi / 180),
}

# Derivative functions per built problem (problems are cached by structure).
_STIFFNESS_FUNCS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()
_SENSITIVITY_FUNCS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


# ---- helpers ----------------------------------------------------------------------------


def _as_result(obj, solver: str = "ipopt") -> Result:
    if isinstance(obj, Result):
        if obj.case is None or obj.state is None:
            raise ValueError("this Result carries no case or state; solve the case with "
                             "moorsolve.solve to study it")
        return obj
    if isinstance(obj, Case):
        return solve(obj, solver=solver)
    raise TypeError(f"expected a Result or a Case, got {type(obj).__name__}")


def _position(result: Result) -> np.ndarray:
    """Body position ``[x m, y m, yaw rad]`` of a result (zeros without a body)."""
    if result.body is None:
        return np.zeros(3)
    b = result.body
    return np.array([b["x_m"], b["y_m"], math.radians(b["yaw_deg"])])


def _mooring_only(case: Case, free: tuple) -> Case:
    """``case`` with a load-free body free in ``free``: its body residual is the mooring
    force alone. A case without a body gets a virtual rigid body at the global origin
    carrying the fairleads (the legs alone)."""
    return dataclasses.replace(case, body=Body(free=free, loads=BodyLoads()))


def _params(case: Case) -> np.ndarray:
    return parameter_vector(case, 1.0)


# ---- stiffness ----------------------------------------------------------------------------


def stiffness(result_or_case, *, solver: str = "ipopt") -> np.ndarray:
    """Mooring stiffness matrix at equilibrium, all three horizontal-plane DOFs.

    Parameters
    ----------
    result_or_case : Result or Case
        A solved equilibrium, or a case to solve first (with ``solver``).

    Returns
    -------
    numpy.ndarray, shape (3, 3)
        ``K[i, j] = -dF_i/dq_j`` with ``F = (Fx [N], Fy [N], Mz [N m])`` the force of the
        legs on the body (moment about the body origin) and ``q = (x [m], y [m], yaw
        [rad])`` the body position; rows and columns in the order surge, sway, yaw, so the
        units are N/m, N/rad (and N m/m) and N m/rad. Fixed DOFs are included: the body
        position is imposed, and each leg re-equilibrates. Body loads (wind, current,
        drift) are not part of it: it is the mooring's own stiffness. Without a body, the
        fairleads move as one rigid frame about the global origin.

    Notes
    -----
    With the leg unknowns ``l`` and their residuals ``g_l(q, l) = 0`` the legs follow the
    body by the implicit function theorem, ``dl/dq = -J_ll^-1 J_lq``, so

        K = -(F_q + F_l dl/dq) = -(F_q - F_l J_ll^-1 J_lq),

    every block from CasADi's automatic differentiation. Each leg pulls its fairlead with
    ``H(X)`` toward its anchor, a central force depending only on the horizontal span
    ``X`` (the fairlead height is fixed), so the mooring force has a potential and ``K``
    is symmetric, with or without seabed friction (the friction model gives a unique
    ``H(X)`` for each span). The load-dependent terms of a full system stiffness (wind
    moment varying with yaw) would not be symmetric; they are excluded.
    """
    result = _as_result(result_or_case, solver)
    case = result.case
    original = get_problem(case)
    full = _mooring_only(case, DOFS)
    problem = get_problem(full)
    legs_phys = (np.asarray(result.state) * original.x_scale)[original.n_q:]
    x_phys = np.concatenate([_position(result), legs_phys])
    x = x_phys / problem.x_scale
    f = _STIFFNESS_FUNCS.get(problem)
    if f is None:
        xs = ca.SX.sym("x", problem.n_x)
        ps = ca.SX.sym("p", problem.n_p)
        # The legs' rows: everything before the body's balance (issue 4 legs have more).
        g = problem.residual(xs, ps)[: problem.n_x - problem.n_q]
        force = problem.report(xs, ps)[1]
        xq, xl = xs[:3], xs[3:]
        f = ca.Function("stiffness_blocks", [xs, ps],
                        [ca.jacobian(g, xl), ca.jacobian(g, xq),
                         ca.jacobian(force, xl), ca.jacobian(force, xq)])
        _STIFFNESS_FUNCS[problem] = f
    J_ll, J_lq, F_l, F_q = (np.asarray(v) for v in f(x, _params(full)))
    dF = F_q
    if problem.n_legs:
        dF = F_q - F_l @ np.linalg.solve(J_ll, J_lq)
    return -dF / problem.x_scale[:3][None, :]


# ---- restoring curves ---------------------------------------------------------------------


def mooring_force(case: Case, position: Sequence[float], *, solver: str = "ipopt",
                  start: Optional[np.ndarray] = None) -> tuple[np.ndarray, Result]:
    """Force of the legs on the body held at ``position``, the legs re-solved.

    Parameters
    ----------
    case : Case
    position : (x [m], y [m], yaw [deg])
        Body position imposed, from its case-file position.

    Returns
    -------
    force : numpy.ndarray
        ``[Fx N, Fy N, Mz N m]``, the moment about the displaced body origin.
    result : Result
        The legs' equilibrium (body fixed, fairleads at their displaced positions).

    Notes
    -----
    The offset is imposed by moving the fairleads, ``f' = R(yaw) f + (x, y)``, and
    solving the legs with the body held (no free DOF, no body load).
    """
    x0, y0, yaw_deg = (float(v) for v in position)
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    legs = tuple(dataclasses.replace(
        leg, fairlead=(x0 + c * leg.fairlead[0] - s * leg.fairlead[1],
                       y0 + s * leg.fairlead[0] + c * leg.fairlead[1], leg.fairlead[2]))
        for leg in case.legs)
    held = dataclasses.replace(_mooring_only(case, ()), legs=legs)
    result = solve(held, solver=solver, start=start, allow_overload=True)
    force = np.zeros(3)
    for leg in result.legs:
        dx = leg.anchor[0] - leg.fairlead[0]
        dy = leg.anchor[1] - leg.fairlead[1]
        span = math.hypot(dx, dy)
        if span == 0.0:
            continue
        fx, fy = leg.horizontal_tension_N * dx / span, leg.horizontal_tension_N * dy / span
        force += (fx, fy, (leg.fairlead[0] - x0) * fy - (leg.fairlead[1] - y0) * fx)
    return force, result


def restoring_curve(case: Case, dof: str, offsets: Sequence[float], *,
                    about: Sequence[float] = (0.0, 0.0, 0.0),
                    solver: str = "ipopt") -> dict:
    """Mooring force against an imposed offset of one degree of freedom.

    Parameters
    ----------
    case : Case
    dof : {"surge", "sway", "yaw"}
    offsets : sequence of float
        Offsets [m, or deg for yaw] added to ``about``.
    about : (x [m], y [m], yaw [deg])
        Base position, e.g. an equilibrium's ``(x_m, y_m, yaw_deg)``; default the
        case-file position.

    Returns
    -------
    dict
        ``dof``, ``offset`` (array, m or deg), ``force`` (array (n, 3): ``Fx N, Fy N,
        Mz N m`` of the legs on the body; the restoring force is its negative of the
        offset's sign) and ``max_tension_N`` (the largest fairlead tension at each offset).
    """
    if dof not in DOFS:
        raise ValueError(f"dof {dof!r}: must be one of {', '.join(DOFS)}")
    k = DOFS.index(dof)
    offsets = np.asarray(offsets, dtype=float)
    force = np.zeros((offsets.size, 3))
    t_max = np.zeros(offsets.size)
    start = None
    for i, d in enumerate(offsets):
        pos = np.asarray(about, dtype=float).copy()
        pos[k] += d
        force[i], res = mooring_force(case, pos, solver=solver, start=start)
        start = res.state
        t_max[i] = max((leg.fairlead_tension_N for leg in res.legs), default=0.0)
    return {"dof": dof, "offset": offsets, "force": force, "max_tension_N": t_max}


# ---- natural periods ----------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class NaturalPeriods:
    """Undamped natural periods of the moored body in the horizontal plane.

    Attributes
    ----------
    dofs : tuple of str
        The degrees of freedom considered.
    periods_s : numpy.ndarray
        Coupled periods [s] from the generalized eigenproblem ``K v = w^2 (M + A) v``,
        longest first; ``inf`` for a mode with no restoring stiffness.
    modes : numpy.ndarray
        Mode shapes as columns (``(M + A)``-normalised), same order.
    diagonal_s : dict
        Uncoupled period per DOF, ``2 pi sqrt((M + A)_ii / K_ii)`` [s].
    """

    dofs: tuple
    periods_s: np.ndarray
    modes: np.ndarray
    diagonal_s: dict


def natural_periods(K, mass, *, added_mass=None, inertia: Optional[float] = None,
                    dofs: Sequence[str] = DOFS) -> NaturalPeriods:
    """Natural periods ``T = 2 pi sqrt((M + A) / K)`` of the moored body.

    Parameters
    ----------
    K : array (3, 3)
        Mooring stiffness from :func:`stiffness` (surge, sway, yaw).
    mass : float or array (3, 3)
        Body mass [kg], or a full rigid-body mass matrix (surge, sway, yaw).
    added_mass : float, sequence of 3 or array (3, 3), optional
        Added mass [kg, kg, kg m^2]: one value for surge and sway, three diagonal values or
        a full matrix.
    inertia : float, optional
        Yaw moment of inertia about the body origin [kg m^2]; needed for yaw with a scalar
        ``mass``.
    dofs : sequence of str
        The DOFs to consider (the others held), e.g. ``("surge", "sway")`` for a buoy.

    Notes
    -----
    Small oscillations about the equilibrium: ``(M + A) q'' + K q = 0``; the eigenvalues
    ``w^2`` of ``(K, M + A)`` give ``T = 2 pi / w``. For a diagonal system the coupled and
    uncoupled periods agree.
    """
    from scipy.linalg import eigh

    idx = [DOFS.index(d) for d in dofs]
    K = np.asarray(K, dtype=float)
    if np.ndim(mass) == 0:
        if "yaw" in dofs and inertia is None:
            raise ValueError("inertia: the yaw moment of inertia [kg m^2] is needed for yaw")
        M = np.diag([float(mass), float(mass), float(inertia or 0.0)])
    else:
        M = np.asarray(mass, dtype=float).reshape(3, 3).copy()
    if added_mass is not None:
        a = np.asarray(added_mass, dtype=float)
        if a.ndim == 0:
            a = np.diag([float(a), float(a), 0.0])
        elif a.shape == (3,):
            a = np.diag(a)
        M = M + a.reshape(3, 3)
    Ks, Ms = K[np.ix_(idx, idx)], M[np.ix_(idx, idx)]
    if np.any(np.diag(Ms) <= 0):
        raise ValueError(f"mass: the inertia of every DOF considered must be > 0, got "
                         f"{np.diag(Ms).tolist()} for {list(dofs)}")
    Ks_sym = 0.5 * (Ks + Ks.T)
    w2, modes = eigh(Ks_sym, Ms)
    with np.errstate(divide="ignore"):
        periods = np.where(w2 > 0, 2 * np.pi / np.sqrt(np.clip(w2, 1e-300, None)), np.inf)
    diag = {}
    for j, d in enumerate(dofs):
        kk = Ks[j, j]
        diag[d] = 2 * math.pi * math.sqrt(Ms[j, j] / kk) if kk > 0 else math.inf
    return NaturalPeriods(dofs=tuple(dofs), periods_s=periods, modes=modes, diagonal_s=diag)


# ---- sensitivities ------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class Sensitivity:
    """``matrix[i, j] = d outputs[i] / d parameters[j]`` at an equilibrium (SI units of the
    names: N, m, deg, N/m, m/s)."""

    outputs: tuple
    parameters: tuple
    matrix: np.ndarray

    def __getitem__(self, key) -> float:
        out, par = key
        return float(self.matrix[self.outputs.index(out), self.parameters.index(par)])

    def to_dict(self) -> dict:
        return {o: {p: float(self.matrix[i, j]) for j, p in enumerate(self.parameters)}
                for i, o in enumerate(self.outputs)}


_LEG_PATH = re.compile(r"legs\[([^\[\]]+)\]\.(\w+)$")
_TYPE_PATH = re.compile(r"line_types\[([^\[\]]+)\]\.(\w+)$")
_FORCE_PATH = re.compile(r"body\.loads\.force\[([0-2])\]$")


def _leg_index(case: Case, sel: str, name: str) -> int:
    if re.fullmatch(r"\d+", sel):
        i = int(sel)
        if i < len(case.legs):
            return i
    for i, leg in enumerate(case.legs):
        if leg.name == sel:
            return i
    raise ValueError(f"{name}: no leg {sel!r}; the legs are {[leg.name for leg in case.legs]}")


def _output_row(case: Case, name: str) -> int:
    """Row of ``name`` in the stacked outputs (body 3, then per leg ``LEG_OUTPUTS``)."""
    if name in BODY_OUTPUTS:
        if case.body is None:
            raise ValueError(f"{name}: the case has no body")
        return BODY_OUTPUTS.index(name)
    m = _LEG_PATH.match(name)
    if m and m.group(2) in LEG_OUTPUTS:
        return 3 + _leg_index(case, m.group(1), name) * len(LEG_OUTPUTS) \
            + LEG_OUTPUTS.index(m.group(2))
    raise ValueError(f"output {name!r}: must be one of {', '.join(BODY_OUTPUTS)} or "
                     f"legs[NAME].FIELD with FIELD in {', '.join(LEG_OUTPUTS)}")


def _parameter_column(case: Case, problem, name: str) -> np.ndarray:
    """``dp/d(name)``: how the problem's parameter vector moves with the named input."""
    col = np.zeros(problem.n_p)
    n_env, n_leg = len(ENV_PARAMS), len(LEG_PARAMS)

    def leg_slot(i, key):
        return n_env + i * n_leg + LEG_PARAMS.index(key)

    env = case.environment
    if name in _ENV_PARAMETERS:
        model, key, factor = _ENV_PARAMETERS[name]
        if getattr(env, model) is None:
            raise ValueError(f"{name}: the case has no {model} (a scene without it builds "
                             f"no {model} model, so there is nothing to differentiate)")
        if case.body is None or not any(
                getattr(case.body.loads, m) is not None
                for m in (("wave_drift",) if model == "waves" else (model,))):
            # The environment acts only through body loads in this model.
            return col
        col[ENV_PARAMS.index(key)] = factor
        return col
    m = _FORCE_PATH.match(name)
    if m:
        if case.body is None or case.body.loads.force is None:
            raise ValueError(f"{name}: the case has no body.loads.force")
        col[ENV_PARAMS.index(("force_x", "force_y", "moment_z")[int(m.group(1))])] = 1.0
        return col
    if name == "environment.seabed.friction":
        for i, kind in enumerate(problem.kinds):
            if kind.friction:
                col[leg_slot(i, "friction")] = 1.0
        if not any(k.friction for k in problem.kinds):
            raise ValueError(f"{name}: the case has no seabed friction (0 builds none)")
        return col
    m = _TYPE_PATH.match(name)
    if m and m.group(2) in ("stiffness_scale", "n"):
        # The stretch law's parameters: every segment of the type (solve/stretch_params).
        columns = {"stiffness_scale": stiffness_scale_column, "n": baranov_n_column}
        return columns[m.group(2)](case, problem.n_p, m.group(1))
    if m:
        field = m.group(2)
        legs = [i for i, leg in enumerate(case.legs) if leg.line_type.name == m.group(1)]
        if not legs:
            raise ValueError(f"{name}: no leg uses line type {m.group(1)!r}")
        if field not in ("ea", "weight_in_water"):
            raise ValueError(f"{name}: line-type parameters are ea, weight_in_water, n "
                             "(Baranov) and stiffness_scale")
        for i in legs:
            col += _parameter_column(case, problem, f"legs[{i}]." + (
                "ea" if field == "ea" else "weight"))
        return col
    m = _LEG_PATH.match(name)
    if m and m.group(2) in _LEG_PARAMETERS:
        i = _leg_index(case, m.group(1), name)
        leg, field = case.legs[i], m.group(2)
        if field == "ea":
            if leg.line_type.ea is None:
                what = ("follows a stretch law (use line_types[NAME].stiffness_scale)"
                        if leg.line_type.stretch is not None else "is inextensible (no ea)")
                raise ValueError(f"{name}: leg {leg.name}'s line {what}")
            col[leg_slot(i, "ea_inv")] = -1.0 / leg.line_type.ea ** 2
        elif field == "anchor_z" and problem.kinds[i].contact:
            raise ValueError(f"{name}: leg {leg.name}'s anchor lies on the seabed; raising "
                             f"it changes the model (no contact), so there is no derivative")
        else:
            key = {"fairlead_x": "fair_x", "fairlead_y": "fair_y",
                   "fairlead_z": "fair_z"}.get(field, field)
            col[leg_slot(i, key)] = 1.0
        return col
    raise ValueError(
        f"parameter {name!r}: must be legs[NAME].FIELD with FIELD in "
        f"{', '.join(_LEG_PARAMETERS)}, line_types[NAME].ea, .weight_in_water, .n or "
        f".stiffness_scale, "
        f"{', '.join(_ENV_PARAMETERS)}, environment.seabed.friction or body.loads.force[0-2]")


def _sensitivity_function(problem) -> ca.Function:
    f = _SENSITIVITY_FUNCS.get(problem)
    if f is None:
        xs = ca.SX.sym("x", problem.n_x)
        ps = ca.SX.sym("p", problem.n_p)
        g = problem.residual(xs, ps)
        legs_out = problem.report(xs, ps)[0]
        body, t_fair, t_anchor = problem.summary(xs, ps)
        rows = [body[0], body[1], body[2] * (180.0 / math.pi)]
        for i in range(problem.n_legs):
            H, VF, HA, VA, grounded = (legs_out[i, k] for k in range(5))
            rows += [t_fair[i], H, VF, t_anchor[i], HA, VA, grounded]
        y = ca.vertcat(*rows)
        f = ca.Function("sensitivity_blocks", [xs, ps],
                        [ca.jacobian(g, xs), ca.jacobian(g, ps),
                         ca.jacobian(y, xs), ca.jacobian(y, ps)])
        _SENSITIVITY_FUNCS[problem] = f
    return f


def sensitivity(result: Result, outputs, parameters) -> Sensitivity:
    """Exact derivatives of equilibrium outputs by case parameters.

    Parameters
    ----------
    result : Result
        A certified equilibrium from :func:`moorsolve.solve`.
    outputs : str or sequence of str
        ``x_m``, ``y_m``, ``yaw_deg`` and ``legs[NAME].FIELD`` with FIELD one of
        ``LEG_OUTPUTS`` (``fairlead_tension_N``, ``anchor_vertical_N`` ...).
    parameters : str or sequence of str
        ``legs[NAME].length | ea | weight | anchor_x | anchor_y | anchor_z | fairlead_x |
        fairlead_y | fairlead_z`` (that leg's line only), ``line_types[NAME].ea`` and
        ``.weight_in_water`` (every leg of the type), ``line_types[NAME].n`` (Baranov's
        coefficient) and ``.stiffness_scale`` (per unit factor on the tension at every
        strain: a stiffer rope; any stretch law, every segment of the type),
        ``environment.wind.speed``,
        ``environment.current.speed``, ``environment.waves.hs`` and their
        ``toward_deg``, ``environment.seabed.friction``, ``body.loads.force[0|1|2]``.

    Returns
    -------
    Sensitivity
        ``sens[output, parameter]`` in the units of the names (e.g. N per m of length,
        m per (m/s) of current, deg per deg).

    Notes
    -----
    Implicit function theorem on the square residual system ``g(x, p) = 0``:
    ``dx/dp = -(dg/dx)^-1 dg/dp``, then ``dy/dp = y_x dx/dp + y_p`` for each output
    ``y(x, p)``; every block by CasADi automatic differentiation. A named parameter maps
    onto the parameter vector by the chain rule (``ea`` enters as ``1/ea``: ``-1/ea^2``;
    headings in radians: ``pi/180``). At a regime boundary (touchdown exactly at the
    anchor, a leg going slack) the derivative is the one of the regime the solution is in.
    """
    result = _as_result(result)
    case = result.case
    outputs = (outputs,) if isinstance(outputs, str) else tuple(outputs)
    parameters = (parameters,) if isinstance(parameters, str) else tuple(parameters)
    problem = get_problem(case)
    rows = [_output_row(case, o) for o in outputs]
    C = np.column_stack([_parameter_column(case, problem, q) for q in parameters]) \
        if parameters else np.zeros((problem.n_p, 0))
    G_x, G_p, Y_x, Y_p = (np.asarray(v) for v in
                          _sensitivity_function(problem)(result.state, _params(case)))
    dx = -np.linalg.solve(G_x, G_p @ C)
    dy = Y_x[rows] @ dx + Y_p[rows] @ C
    return Sensitivity(outputs=outputs, parameters=parameters, matrix=dy)
