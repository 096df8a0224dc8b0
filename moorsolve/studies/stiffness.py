"""Mooring stiffness, restoring forces and natural periods of the bodies of a scene.

The mooring stiffness of one body is ``K = -dW/dq`` over its six degrees of freedom, with
``W`` the force and moment (about the body origin, global axes) of the lines on it and ``q``
its translations and small rotations about the global axes, every line and free point
re-equilibrating (condensed out: ``K = -(W_q - W_r J_rr^-1 J_rq)``, every block by CasADi's
automatic differentiation). Other bodies are held where they are.
The coupled stiffness of all free degrees of freedom (several bodies, with hydrostatics and
the loads' own dependence on pose) is the matrix the stability check uses
(:func:`moorsolve.solve.stability.static.condensed_stiffness`).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Optional, Sequence

import numpy as np

from ..errors import MoorsolveWarning
from ..model import DOFS, Body, BodyLoads, Case, Contacts, End
from ..model.build_network import rotation
from ..solve.lines.bathymetry import result_parameters
from ..solve.assembly.cache import get_problem
from ..solve.equilibrium import solve
from ..solve.result.classes import Result
from ..solve.stability.static import condensed_stiffness
from .kinks import (contacts_at_first_contact, lines_at_slack_point, warn_one_sided,
                    with_lines)

#: Units of the rows and columns of a 6x6 stiffness (global axes).
STIFFNESS_UNITS = ("N/m", "N/m", "N/m", "N m/rad", "N m/rad", "N m/rad")
PLANAR = (0, 1, 5)


def as_result(obj, solver: str = "ipopt") -> Result:
    """A solved Result: ``obj`` itself, or ``obj`` (a Case) solved with ``solver``."""
    if isinstance(obj, Result):
        if obj.case is None or obj.state is None:
            raise ValueError("this Result carries no case or state; solve the case with "
                             "moorsolve.solve to study it")
        return obj
    if isinstance(obj, Case):
        return solve(obj, solver=solver)
    raise TypeError(f"expected a Result or a Case, got {type(obj).__name__}")


def _virtual_body_case(case: Case) -> Case:
    """A case without bodies, its lines' B ends carried by a held frame at the origin."""
    lines = tuple(dataclasses.replace(line, b=End(line.b.position, body="frame"))
                  if line.b.fixed and not line.b.on_seabed else line for line in case.lines)
    frame = Body(name="frame", free=())
    return dataclasses.replace(case, bodies=(frame,), lines=lines, form="network",
                               source=None)


def _solved_poses(result: Result) -> dict:
    """Each body's solved pose ``(x, y, z, roll, pitch, yaw)`` [m, rad]."""
    out = {}
    for b in result.bodies:
        out[b["name"]] = np.array([b["x_m"], b["y_m"], b["z_m"],
                                   math.radians(b["roll_deg"]), math.radians(b["pitch_deg"]),
                                   math.radians(b["yaw_deg"])])
    return out


def posed_case(case: Case, poses: dict, free_body: Optional[str] = None) -> Case:
    """``case`` with every body held at ``poses`` (loads, weight, hydrostatics and contacts
    removed: the lines and points alone act), and ``free_body`` (if given) free in all six degrees
    of freedom with its frame turned so that its orientation is zero (its attachment points
    expressed in global axes about its origin)."""
    bodies, turned = [], {}
    level = case.environment.water_level
    for body in case.bodies:
        pose = poses.get(body.name, np.array(list(body.rest_position(level)) + [
            math.radians(a) for a in body.orientation_deg]))
        # The poses are absolute, on the datum, whatever the tide: fixed_to "seabed".
        if body.name == free_body:
            turned[body.name] = rotation(*pose[3:])
            bodies.append(Body(name=body.name, free=DOFS, position=tuple(pose[:3]),
                               fixed_to="seabed"))
        else:
            bodies.append(Body(name=body.name, free=(), position=tuple(pose[:3]),
                               orientation_deg=tuple(math.degrees(a) for a in pose[3:]),
                               loads=BodyLoads(), fixed_to="seabed"))
    lines = []
    for line in case.lines:
        ends = {}
        for key in ("a", "b"):
            end = getattr(line, key)
            if end.body in turned:
                ends[key] = dataclasses.replace(
                    end, position=tuple(turned[end.body] @ np.asarray(end.position)))
        lines.append(dataclasses.replace(line, **ends) if ends else line)
    return dataclasses.replace(case, bodies=tuple(bodies), lines=tuple(lines),
                               form="network", source=None, contacts=Contacts())


def _points_at(case: Case, result: Result) -> Case:
    """``case`` with its free points starting where ``result`` found them."""
    found = {pt["name"]: (pt["x_m"], pt["y_m"], pt["z_m"]) for pt in result.points}
    points = tuple(dataclasses.replace(pt, position=found.get(pt.name, pt.position))
                   if pt.free else pt for pt in case.points)
    return dataclasses.replace(case, points=points)


def stiffness(result_or_case, body: Optional[str] = None, *,
              solver: str = "ipopt") -> np.ndarray:
    """The mooring's linear restoring matrix of one body about its solved position.

    Parameters
    ----------
    result_or_case : Result or Case
        A solved equilibrium, or a case to solve first (with ``solver``).
    body : str, optional
        The body's name; default the only body (a case of several bodies must name one).
        The other bodies are held at their solved poses while it moves; free points and
        lines re-equilibrate (lines shared with the others are stretched against them).
        A case without bodies: the lines' fixed upper ends move as one rigid frame about
        the global origin.

    Returns
    -------
    numpy.ndarray, shape (6, 6)
        ``K[i, j] = -dW_i/dq_j``, rows and columns surge, sway, heave, roll, pitch, yaw:
        forces [N] and moments about the body origin [N m] in global axes against
        translations [m] and rotations about the global axes [rad]
        (:data:`STIFFNESS_UNITS`). A held body is taken about its given position. Only the
        lines (and the free points they meet) act: weight, hydrostatics, springs and
        environmental loads are not part of it.

    Notes
    -----
    With the line unknowns and free points ``r`` in equilibrium, ``g_r(q, r) = 0``, they
    follow the body (implicit function theorem), so ``K = -(W_q - W_r J_rr^-1 J_rq)``. A
    line pulls its ends with a force depending on their positions only, so the mooring
    force has a potential where every line end is on the body and K is symmetric; a net
    moment of the lines about the origin (a body not in balance under its lines alone)
    adds the non-symmetric geometric part. At the line model's non-smooth points K is the
    limit from the physical side (a line hanging straight down: its pendulum stiffness);
    where a weightless line is exactly at its slack point the two sides differ: K is then
    the taut side's, with a :class:`~moorsolve.MoorsolveWarning`
    (:func:`moorsolve.one_sided_stiffness` gives both).
    """
    result = as_result(result_or_case, solver)
    at_point = lines_at_slack_point(result)
    if at_point:
        # Neither side's derivative is that of the scene as solved: give the taut side's
        # and say so (moorsolve.one_sided_stiffness gives both).
        warn_one_sided(at_point)
        return held_stiffness(with_lines(result.case, at_point, taut=True), result, body)
    return held_stiffness(result.case, result, body)


def held_stiffness(case: Case, result: Result, body: Optional[str]) -> np.ndarray:
    """:func:`stiffness` of ``case`` (``result.case`` or a variant of it with the same bodies
    and points) about the poses and free points of ``result``."""
    if not case.bodies:
        case = _virtual_body_case(case)
        poses = {"frame": np.zeros(6)}
        name = "frame"
    else:
        poses = _solved_poses(result)
        names = [b.name for b in case.bodies]
        if body is None:
            if len(names) > 1:
                raise ValueError(f"body: the case has {len(names)} bodies "
                                 f"({', '.join(names)}); name one")
            body = names[0]
        if body not in names:
            raise ValueError(f"body {body!r}: not in the case; its bodies are "
                             f"{', '.join(names)}")
        name = body
    case = _points_at(case, result) if result.points else case
    held = posed_case(case, poses)
    held_result = solve(held, allow_overload=True, stability=False)
    free = posed_case(case, poses, free_body=name)
    problem = get_problem(free)
    x = np.concatenate([np.concatenate([poses[name][:3], np.zeros(3)])
                        / problem.x_scale[:6], held_result.state])
    p = result_parameters(problem, held_result, free)
    index = [b.name for b in free.bodies].index(name)
    return _condensed_wrench_stiffness(problem, x, p, index)


def _condensed_wrench_stiffness(problem, x, p, index: int) -> np.ndarray:
    """``-dW/dq`` of the wrench on body ``index`` (in the case's order) against the six
    unknowns of the one free body (the problem's first six), the rest condensed out."""
    import casadi as ca

    key = f"_wrench_jacobian_{index}"
    with problem.lock:
        f = problem.__dict__.get(key)
        if f is None:
            xs = ca.SX.sym("x", problem.n_x)
            ps = ca.SX.sym("p", problem.n_p)
            W = problem.report(xs, ps)[5][6 * index: 6 * index + 6]
            g = problem.residual(xs, ps)
            f = ca.Function("wrench_jacobian", [xs, ps], [ca.jacobian(W, xs),
                                                          ca.jacobian(g, xs)])
            problem.__dict__[key] = f
        W_x, G_x = (np.asarray(v) for v in f(x, p))
    q = np.arange(6)
    rest = np.arange(6, problem.n_x)
    n_line_rows = problem.n_x - problem.n_q
    # Rows balancing the condensed unknowns: line rows (first), then the points' rows.
    rows = np.concatenate([np.arange(n_line_rows), n_line_rows + np.arange(6, problem.n_q)])
    J_rr = G_x[np.ix_(rows, rest)]
    J_rq = G_x[np.ix_(rows, q)]
    dW = W_x[:, q] - W_x[:, rest] @ np.linalg.solve(J_rr, J_rq)
    return -dW / problem.x_scale[q][None, :]


def coupled_stiffness(result_or_case, *, solver: str = "ipopt") -> tuple:
    """``(K, dofs)``: the total tangent stiffness of every free body DOF (mooring,
    hydrostatics, springs and the loads' dependence on pose; lines and free points
    condensed out), with ``dofs`` labels ``"body.surge"`` ... [SI; rotations are the
    bodies' own angles]."""
    result = as_result(result_or_case, solver)
    at_point = lines_at_slack_point(result)
    if at_point:
        warnings.warn(
            f"line(s) {', '.join(at_point)} at their slack point (chord = unstretched "
            "length): the coupled stiffness differs on the two sides and this matrix is "
            "neither's (moorsolve.one_sided_stiffness gives each body's mooring stiffness "
            "on both sides)", MoorsolveWarning, stacklevel=2)
    touching = contacts_at_first_contact(result)
    if touching:
        warnings.warn(
            f"{', '.join(touching)} exactly at first contact (touching, no reaction): the "
            "coupled stiffness differs on the two sides (closing adds their stiffness, "
            "opening nothing) and this matrix is one side's", MoorsolveWarning, stacklevel=2)
    problem = get_problem(result.case)
    K, keep = condensed_stiffness(problem, result.state, result_parameters(problem, result))
    dofs = [f"{result.case.bodies[problem.nodes[j][1]].name}.{problem.nodes[j][2]}"
            for j in keep]
    return K, dofs


# ---- restoring curves ---------------------------------------------------------------------


def _pose6(position, body: Body, level: float = 0.0) -> np.ndarray:
    """A 3-long ``(x, y, yaw_deg)`` offset or a 6-long ``(x, y, z, roll, pitch, yaw)``
    offset [m, deg] from the body's case pose (its rest at the water ``level`` [m]), as an
    absolute pose [m, rad]."""
    pos = np.asarray(position, dtype=float)
    if pos.size == 3:
        pos = np.array([pos[0], pos[1], 0.0, 0.0, 0.0, pos[2]])
    if pos.size != 6:
        raise ValueError(f"position {position!r}: give (x, y, yaw_deg) or "
                         "(x, y, z, roll_deg, pitch_deg, yaw_deg) from the case pose")
    base = np.array(list(body.rest_position(level))
                    + [math.radians(a) for a in body.orientation_deg])
    return base + np.concatenate([pos[:3], np.radians(pos[3:])])


def mooring_force(case: Case, position: Sequence[float], *, body: Optional[str] = None,
                  solver: str = "ipopt", start: Optional[np.ndarray] = None) -> tuple:
    """Force of the lines on a body held at ``position``, the lines re-solved.

    Parameters
    ----------
    case : Case
    position : (x [m], y [m], yaw [deg]) or (x, y, z [m], roll, pitch, yaw [deg])
        Offset of the body from its case-file pose.
    body : str, optional
        Default the only body (a case without bodies: a frame at the origin carrying the
        lines' upper ends).

    Returns
    -------
    force : numpy.ndarray
        ``[Fx N, Fy N, Mz N m]`` for a 3-long position (the legacy form), else the full
        ``[Fx, Fy, Fz, Mx, My, Mz]``; moments about the displaced body origin.
    result : Result
        The lines' equilibrium with the body held.
    """
    if not case.bodies:
        case = _virtual_body_case(case)
    names = [b.name for b in case.bodies]
    name = body or names[0]
    target = case.body_named(name)
    poses = {name: _pose6(position, target, case.environment.water_level)}
    held = posed_case(case, poses)
    result = solve(held, solver=solver, start=start, allow_overload=True, stability=False)
    problem = get_problem(held)
    wrenches = np.asarray(problem.report(result.state,
                                          result_parameters(problem, result))[5]).ravel()
    w = wrenches[6 * names.index(name): 6 * names.index(name) + 6]
    force = w if np.size(position) == 6 else np.array([w[0], w[1], w[5]])
    return force, result


_DOF_INDEX = {d: i for i, d in enumerate(DOFS)}


def restoring_curve(case: Case, dof: str, offsets: Sequence[float], *,
                    about: Sequence[float] = (0.0, 0.0, 0.0), body: Optional[str] = None,
                    solver: str = "ipopt") -> dict:
    """Mooring force against an imposed offset of one degree of freedom.

    Parameters
    ----------
    case : Case
    dof : one of surge, sway, heave, roll, pitch, yaw
    offsets : sequence of float
        Offsets [m, or deg for rotations] added to ``about``.
    about : (x, y, yaw_deg) or (x, y, z, roll_deg, pitch_deg, yaw_deg)
        Base offset from the case pose, e.g. an equilibrium's; default the case pose.

    Returns
    -------
    dict
        ``dof``, ``offset`` (array), ``force`` (array (n, 3) ``Fx, Fy, Mz`` for a planar
        ``about`` and dof, else (n, 6)) and ``max_tension_N`` (the largest line tension at
        each offset).
    """
    if dof not in DOFS:
        raise ValueError(f"dof {dof!r}: must be one of {', '.join(DOFS)}")
    planar = len(about) == 3 and dof in ("surge", "sway", "yaw")
    base = np.asarray(about, dtype=float)
    if len(base) == 3 and not planar:
        base = np.array([base[0], base[1], 0.0, 0.0, 0.0, base[2]])
    k = (0, 1, None, None, None, 2)[_DOF_INDEX[dof]] if planar else _DOF_INDEX[dof]
    offsets = np.asarray(offsets, dtype=float)
    force = np.zeros((offsets.size, 3 if planar else 6))
    t_max = np.zeros(offsets.size)
    start = None
    for i, d in enumerate(offsets):
        pos = base.copy()
        pos[k] += d
        force[i], res = mooring_force(case, pos, body=body, solver=solver, start=start)
        start = res.state
        t_max[i] = max((leg.fairlead_tension_N for leg in res.legs), default=0.0)
    return {"dof": dof, "offset": offsets, "force": force, "max_tension_N": t_max}


# ---- natural periods ----------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class NaturalPeriods:
    """Undamped natural periods of a moored body.

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


def rigid_body_mass(mass: float, centre_of_gravity=(0.0, 0.0, 0.0),
                    inertia=(0.0, 0.0, 0.0)) -> np.ndarray:
    """The 6x6 mass matrix about the body origin of a body of ``mass`` [kg] with its centre
    of gravity at ``centre_of_gravity`` [m] and principal moments ``inertia`` about it
    [kg m^2] (along the body axes)."""
    m = float(mass)
    c = np.asarray(centre_of_gravity, dtype=float)
    skew = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    M = np.zeros((6, 6))
    M[:3, :3] = m * np.eye(3)
    M[:3, 3:] = -m * skew
    M[3:, :3] = m * skew
    M[3:, 3:] = np.diag(np.asarray(inertia, dtype=float)) - m * skew @ skew
    return M


def natural_periods(K, mass, *, added_mass=None, inertia=None,
                    dofs: Optional[Sequence[str]] = None) -> NaturalPeriods:
    """Natural periods ``T = 2 pi sqrt((M + A) / K)`` of a moored body.

    Parameters
    ----------
    K : array (6, 6) or (3, 3)
        Stiffness: from :func:`stiffness` (six DOFs) or a planar (surge, sway, yaw) matrix;
        add the hydrostatic stiffness for heave, roll and pitch.
    mass : float or array like K
        Body mass [kg], or a full rigid-body mass matrix (:func:`rigid_body_mass`).
    added_mass : float, sequence or array like K, optional
        Added mass: one value for surge and sway, the diagonal, or a full matrix.
    inertia : float or sequence of 3, optional
        Moments of inertia about the origin [kg m^2]: the yaw one (planar K) or roll, pitch
        and yaw; needed for the rotations with a scalar ``mass``.
    dofs : sequence of str, optional
        The DOFs to consider (the others held), e.g. ``("surge", "sway")`` for a buoy;
        default all of K's.

    Notes
    -----
    Small oscillations about the equilibrium: ``(M + A) q'' + K q = 0``; the eigenvalues
    ``w^2`` of ``(K, M + A)`` give ``T = 2 pi / w`` (Merkin 1980 has
    hanging-chain values for the line's own modes). For a diagonal system the coupled and
    uncoupled periods agree.
    """
    from scipy.linalg import eigh

    K = np.asarray(K, dtype=float)
    n = K.shape[0]
    names = DOFS if n == 6 else ("surge", "sway", "yaw")
    dofs = tuple(names) if dofs is None else tuple(dofs)
    for d in dofs:
        if d not in names:
            raise ValueError(f"dofs: {d!r} is not one of {', '.join(names)}")
    idx = [names.index(d) for d in dofs]
    rotations = [i for i, d in enumerate(names) if d in ("roll", "pitch", "yaw")]
    if np.ndim(mass) == 0:
        need = [names[i] for i in rotations if names[i] in dofs]
        if need and inertia is None:
            raise ValueError(f"inertia: the moment of inertia [kg m^2] is needed for "
                             f"{', '.join(need)}")
        inert = np.atleast_1d(np.asarray(0.0 if inertia is None else inertia, dtype=float))
        if inert.size == 1:
            inert = np.repeat(inert, len(rotations))
        diag = [float(mass)] * (n - len(rotations)) + list(inert)
        M = np.diag(diag)
    else:
        M = np.asarray(mass, dtype=float).reshape(n, n).copy()
    if added_mass is not None:
        a = np.asarray(added_mass, dtype=float)
        if a.ndim == 0:
            a = np.diag([float(a), float(a)] + [0.0] * (n - 2))
        elif a.shape == (n,):
            a = np.diag(a)
        M = M + a.reshape(n, n)
    Ks, Ms = K[np.ix_(idx, idx)], M[np.ix_(idx, idx)]
    if np.any(np.diag(Ms) <= 0):
        raise ValueError(f"mass: the inertia of every DOF considered must be > 0, got "
                         f"{np.diag(Ms).tolist()} for {list(dofs)}")
    Ks_sym = 0.5 * (Ks + Ks.T)
    w2, modes = eigh(Ks_sym, Ms)
    with np.errstate(divide="ignore"):
        periods = np.where(w2 > 0, 2 * np.pi / np.sqrt(np.clip(w2, 1e-300, None)), np.inf)
    diagonal = {}
    for j, d in enumerate(dofs):
        kk = Ks[j, j]
        diagonal[d] = 2 * math.pi * math.sqrt(Ms[j, j] / kk) if kk > 0 else math.inf
    return NaturalPeriods(dofs=dofs, periods_s=periods, modes=modes, diagonal_s=diagonal)


def body_natural_periods(result_or_case, body: Optional[str] = None, *,
                         added_mass=None, solver: str = "ipopt") -> NaturalPeriods:
    """Natural periods of one body from its total stiffness (mooring, hydrostatics,
    springs) and its 6x6 mass matrix (``mass``, ``centre_of_gravity``, ``inertia`` of the
    case; ``added_mass`` from the case unless given), over its free DOFs."""
    result = as_result(result_or_case, solver)
    case = result.case
    names = [b.name for b in case.bodies]
    body = body or (names[0] if len(names) == 1 else None)
    if body not in names:
        raise ValueError(f"body: name one of {', '.join(names)}")
    b = case.body_named(body)
    if b.mass is None:
        raise ValueError(f"body {body!r} has no mass; natural periods need one")
    K, labels = coupled_stiffness(result)
    own = [i for i, lab in enumerate(labels) if lab.startswith(body + ".")]
    dofs = tuple(labels[i].split(".", 1)[1] for i in own)
    K6 = np.zeros((6, 6))
    for a, i in enumerate(own):
        for c, j in enumerate(own):
            K6[DOFS.index(dofs[a]), DOFS.index(dofs[c])] = K[i, j]
    M = rigid_body_mass(b.mass, b.centre_of_gravity, b.inertia or (0.0, 0.0, 0.0))
    added = added_mass if added_mass is not None else b.added_mass
    return natural_periods(K6, M, added_mass=added, dofs=dofs)
