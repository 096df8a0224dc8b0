"""Rotation matrices of the two angle conventions the files use (pure Python, 3x3 tuples).

MoorDyn-C v2 turns a body by ``R = Rx(roll) Ry(pitch) Rz(yaw)`` (``Euler2Quat`` in
``Misc.hpp``: the quaternion product of the x, y and z angle-axis rotations). The case
file's angles are the z-y-x sequence (yaw first, then pitch, then roll, each about the
turned axes): ``R = Rz(yaw) Ry(pitch) Rx(roll)``, MoorPy's ``rotationMatrix``. The two agree
whenever at most one angle is non-zero; :func:`case_angles` converts the general case.
"""

from __future__ import annotations

import math

__all__ = ["moordyn_matrix", "moordyn_angles", "case_matrix", "case_angles", "apply",
           "apply_transpose", "yawed"]


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return ((1.0, 0.0, 0.0), (0.0, c, -s), (0.0, s, c))


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return ((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c))


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))


def _mul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3))
                 for i in range(3))


def moordyn_matrix(roll_deg: float, pitch_deg: float, yaw_deg: float) -> tuple:
    """MoorDyn-C's body rotation ``Rx Ry Rz`` of its r0, p0, y0 [deg]."""
    r, p, y = (math.radians(a) for a in (roll_deg, pitch_deg, yaw_deg))
    return _mul(_mul(_rx(r), _ry(p)), _rz(y))


def moordyn_angles(matrix) -> tuple:
    """(r0, p0, y0) [deg] of MoorDyn-C's convention for a rotation matrix."""
    pitch = math.asin(max(-1.0, min(1.0, matrix[0][2])))
    roll = math.atan2(-matrix[1][2], matrix[2][2])
    yaw = math.atan2(-matrix[0][1], matrix[0][0])
    return tuple(0.0 if abs(a) < 1e-15 else math.degrees(a) for a in (roll, pitch, yaw))


def yawed(matrix, yaw_deg: float) -> tuple:
    """``Rz(yaw) @ matrix``: a rotation turned further about the vertical."""
    return _mul(_rz(math.radians(yaw_deg)), matrix)


def case_matrix(roll_deg: float, pitch_deg: float, yaw_deg: float) -> tuple:
    """The case file's rotation ``Rz Ry Rx`` of ``orientation_deg`` [deg]."""
    r, p, y = (math.radians(a) for a in (roll_deg, pitch_deg, yaw_deg))
    return _mul(_mul(_rz(y), _ry(p)), _rx(r))


def case_angles(matrix) -> tuple:
    """(roll, pitch, yaw) [deg] of the case convention for a rotation matrix."""
    pitch = -math.asin(max(-1.0, min(1.0, matrix[2][0])))
    roll = math.atan2(matrix[2][1], matrix[2][2])
    yaw = math.atan2(matrix[1][0], matrix[0][0])
    return tuple(0.0 if abs(a) < 1e-15 else math.degrees(a) for a in (roll, pitch, yaw))


def apply(matrix, v) -> tuple:
    """``matrix @ v``."""
    return tuple(sum(matrix[i][k] * v[k] for k in range(3)) for i in range(3))


def apply_transpose(matrix, v) -> tuple:
    """``matrix.T @ v`` (the inverse rotation)."""
    return tuple(sum(matrix[k][i] * v[k] for k in range(3)) for i in range(3))
