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
from moorsolve.solve.bathymetry import result_parameters
from moorsolve.solve.cache import get_problem
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
    result = moorsolve.solve(held, allow_overload=True, stability=False, tol=1e-12)
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
