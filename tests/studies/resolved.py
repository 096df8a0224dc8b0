"""Central differences of re-solved equilibria: the independent reference for every
derivative the stiffness, stability, natural-period and sensitivity code reports.

Nothing here uses a Jacobian of the solver's: each column is two fresh solves of the case
with the body displaced and held (its frame turned by a small rotation about a global axis
for the rotational columns), every other body held at its solved pose and the free points
and lines re-equilibrated.
"""

from __future__ import annotations

import math

import numpy as np

import moorsolve
from moorsolve.model.build_network import rotation
from moorsolve.solve.lines.bathymetry import result_parameters
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.studies.stiffness import _points_at, _solved_poses, posed_case

#: Steps [m, rad]: small against every line's length, large against the solve tolerance.
STEPS = (1e-3, 1e-3, 1e-3, 1e-5, 1e-5, 1e-5)


def euler(R) -> np.ndarray:
    """``(roll, pitch, yaw)`` [rad] of ``R = Rz(yaw) Ry(pitch) Rx(roll)``."""
    pitch = -math.asin(max(-1.0, min(1.0, R[2, 0])))
    return np.array([math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])])


def held_wrench(case, poses: dict, name: str) -> np.ndarray:
    """The lines' force and moment on body ``name`` [N, N m] with every body held at
    ``poses`` and the lines and free points re-solved."""
    held = posed_case(case, poses)
    result = moorsolve.solve(held, allow_overload=True, stability=False, tol=1e-10)
    problem = get_problem(held)
    w = np.asarray(problem.report(result.state, result_parameters(problem, result))[5]).ravel()
    i = [b.name for b in case.bodies].index(name)
    return w[6 * i: 6 * i + 6]


def displaced(poses: dict, name: str, j: int, step: float) -> dict:
    """``poses`` with body ``name`` moved by ``step`` along DOF ``j`` (a rotation about the
    global axis for ``j >= 3``)."""
    out = {k: v.copy() for k, v in poses.items()}
    if j < 3:
        out[name][j] += step
    else:
        d = np.zeros(3)
        d[j - 3] = step
        out[name][3:] = euler(rotation(*d) @ rotation(*poses[name][3:]))
    return out


def resolved_stiffness(result, name: str, steps=STEPS) -> np.ndarray:
    """``-dW/dq`` of body ``name`` by central differences of re-solved poses."""
    case = _points_at(result.case, result) if result.points else result.case
    poses = _solved_poses(result)
    K = np.zeros((6, 6))
    for j in range(6):
        plus = held_wrench(case, displaced(poses, name, j, steps[j]), name)
        minus = held_wrench(case, displaced(poses, name, j, -steps[j]), name)
        K[:, j] = -(plus - minus) / (2 * steps[j])
    return K


def assert_matrix_close(K, ref, rtol=1e-3, label=""):
    """Each entry within ``rtol`` of the reference, relative to ``sqrt(|ref_ii ref_jj|)``
    (the dimensionless coupling scale, which makes translational and rotational entries
    commensurate); where a diagonal entry is zero, to the largest entry of the row and
    column."""
    K, ref = np.asarray(K, dtype=float), np.asarray(ref, dtype=float)
    d = np.abs(np.diag(ref))
    scale = np.sqrt(np.outer(d, d))
    spread = np.maximum.outer(np.abs(ref).max(axis=1), np.abs(ref).max(axis=0))
    scale = np.where(scale > 0, scale, spread)
    scale = np.where(scale > 0, scale, 1.0)
    err = np.abs(K - ref) / scale
    i, j = np.unravel_index(np.argmax(err), err.shape)
    assert err.max() <= rtol, (f"{label} entry ({i}, {j}): {K[i, j]:.6e} against "
                               f"{ref[i, j]:.6e} (re-solved), error {err.max():.2e} of its "
                               f"scale {scale[i, j]:.3e}")


def resolved_coupled(result, step: float = 1e-4) -> np.ndarray:
    """The total stiffness ``-dQ/dq`` [SI] of every free body DOF (the bodies' own
    coordinates, as :func:`moorsolve.coupled_stiffness` labels them) by central differences:
    each DOF moved by ``step`` [m, or rad], every other body DOF held, and the lines and
    free points re-solved (Newton on their own rows to 1e-14) before the bodies' generalized
    forces are evaluated."""
    from moorsolve.solve.stability.static import _rows, _split

    case = result.case
    problem = get_problem(case)
    p = result_parameters(problem, result)
    keep, rest = _split(problem)
    rq, rr = _rows(problem, keep), _rows(problem, rest)
    row_scale = np.array([problem.moment_scale if problem.rotational[j]
                          else problem.force_scale for j in keep])

    def forces(x):
        x = x.copy()
        for _ in range(60):
            g = np.asarray(problem.residual(x, p)).ravel()
            if rest.size == 0 or np.max(np.abs(g[rr])) < 1e-14:
                break
            J = np.asarray(problem.jacobian(x, p))
            x[rest] -= np.linalg.lstsq(J[np.ix_(rr, rest)], g[rr], rcond=None)[0]
        else:
            raise AssertionError("the lines did not re-solve")
        return row_scale * g[rq]

    K = np.zeros((keep.size, keep.size))
    for c, j in enumerate(keep):
        cols = []
        for sign in (1, -1):
            x = np.array(result.state, dtype=float)
            x[j] += sign * step / problem.x_scale[j]
            cols.append(forces(x))
        K[:, c] = -(cols[0] - cols[1]) / (2 * step)
    return K


def resolved_sensitivity(data: dict, outputs, body: str, k: int, step: float) -> np.ndarray:
    """``d outputs / d F_k`` of body ``body``'s applied force component ``k`` [per N] by
    central differences of two fresh solves of the case (dictionary ``data``)."""
    import copy

    values = []
    for sign in (1, -1):
        moved = copy.deepcopy(data)
        spec = next(b for b in moved["bodies"] if b["name"] == body)
        force = list(spec["loads"]["force"])
        force[k] += sign * step
        spec["loads"]["force"] = force
        r = moorsolve.solve(moorsolve.load_case(moved), tol=1e-12)
        values.append(np.array([_output(r, name) for name in outputs]))
    return (values[0] - values[1]) / (2 * step)


def _output(result, name: str) -> float:
    if name.startswith("bodies["):
        body, field = name[len("bodies["):].split("].")
        return next(b for b in result.bodies if b["name"] == body)[field]
    leg, field = name[len("legs["):].split("].")
    return getattr(result.leg(leg), field)


def homogenised_eigenvalues(K, dofs, arm: float) -> np.ndarray:
    """Eigenvalues [N/m] of ``K`` with rotations measured as arc length at ``arm`` [m] (the
    stability check's homogenisation), sorted by real part."""
    h = np.array([arm if d.split(".")[-1] in ("roll", "pitch", "yaw") else 1.0
                  for d in dofs])
    values = np.linalg.eigvals(np.asarray(K) / np.outer(h, h))
    return np.sort_complex(values)
