"""Rigid-body kinematics: finite rotations, points on a body, generalized forces.

A body's pose is ``(x, y, z, roll, pitch, yaw)``; a point ``p`` fixed in the body frame sits
at ``r + R p`` with ``R = Rz(yaw) Ry(pitch) Rx(roll)`` (yaw applied first to the body; the
z-y-x convention of MoorPy, MoorDyn and OpenFAST). Rotations are
finite everywhere (no small-angle shortcut); small angles appear only in linearised stiffness.

Equilibrium in any subset of the six degrees of freedom is the vanishing of the generalized
forces conjugate to them (virtual work): the force components for the translations and, for
the angles, the moment about the axis each angle turns about,

    Q_yaw = M . e_z,   Q_pitch = M . Rz e_y,   Q_roll = M . Rz Ry e_x,

with ``M`` the resultant moment about the body-frame origin in global axes. With all three
angles free this is ``M = 0`` (away from pitch = +-90 deg, where the angles are singular).
Every function works on floats (numpy) and on CasADi symbols.
"""

from __future__ import annotations

import casadi as ca


def rotation_matrix(roll, pitch, yaw):
    """``R = Rz(yaw) Ry(pitch) Rx(roll)`` [rad] as a 3x3 CasADi matrix (SX, MX or DM).

    Notes
    -----
    Columns are the body axes in global coordinates.
    """
    cr, sr = ca.cos(roll), ca.sin(roll)
    cp, sp = ca.cos(pitch), ca.sin(pitch)
    cy, sy = ca.cos(yaw), ca.sin(yaw)
    return ca.vertcat(
        ca.horzcat(cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        ca.horzcat(sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        ca.horzcat(-sp, cp * sr, cp * cr))


def rotation_axes(pitch, yaw):
    """The global axes the three angles turn about: ``(Rz Ry e_x, Rz e_y, e_z)``.

    Returns a 3x3 matrix whose columns are the roll, pitch and yaw axes.
    """
    cp, sp = ca.cos(pitch), ca.sin(pitch)
    cy, sy = ca.cos(yaw), ca.sin(yaw)
    roll_axis = ca.vertcat(cy * cp, sy * cp, -sp)
    pitch_axis = ca.vertcat(-sy, cy, 0)
    yaw_axis = ca.vertcat(0, 0, 1)
    return ca.horzcat(roll_axis, pitch_axis, yaw_axis)


def cross(a, b):
    """``a x b`` of two 3-vectors (CasADi)."""
    return ca.vertcat(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                      a[0] * b[1] - a[1] * b[0])


def generalized_forces(force, moment, pitch, yaw):
    """The six generalized forces ``(Fx, Fy, Fz, Q_roll, Q_pitch, Q_yaw)`` of a resultant.

    Parameters
    ----------
    force : 3-vector
        Resultant force, global [N].
    moment : 3-vector
        Resultant moment about the body-frame origin, global axes [N m].
    pitch, yaw : float or symbol
        The body's pitch and yaw [rad].
    """
    axes = rotation_axes(pitch, yaw)
    return ca.vertcat(force, axes.T @ moment)


def wrap_degrees(angle):
    """An angle [deg] (float or numpy array) in (-180, 180]: the same orientation as
    reported, whichever turn the solver's unbounded yaw reached it on."""
    if type(angle) is float:
        # Python's float % rounds as numpy's remainder does; a Result's poses are floats.
        return -((-angle + 180.0) % 360.0 - 180.0)
    import numpy as np
    wrapped = -((-np.asarray(angle, dtype=float) + 180.0) % 360.0 - 180.0)
    return float(wrapped) if np.ndim(wrapped) == 0 else wrapped
