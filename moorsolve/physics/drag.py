"""Hydrodynamic force of a current on a length of line.

After Alekseev and Merkin 1980 (chapter 5): per unit length a line in a
flow of speed ``v`` feels ``lambda = C rho v^2 d / 2`` times a shape function of the angle of
attack ``chi`` between its tangent and the flow. Written with the flow's components normal
(``U_n``) and tangential (``U_t``) to the line, ``|U_n| = v sin(chi)``, ``|U_t| = v cos(chi)``:

- normal: ``(rho d / 2) C_n |U_n| U_n``; magnitude ``C_n sin^2(chi) rho v^2 d / 2``, Merkin's
  fit ``Phi_n = 1.1 sin^2 chi`` for ``C_n = 1.1``;
- tangential (skin friction): ``(rho d / 2) C_t |U_t| U_t``, referred to the diameter;
- side (laid ropes of few strands, Alekseev): ``(rho d / 2) C_m |U_n| |U_t|`` along
  ``t x U / |t x U|``, normal to both line and flow, zero along and across the flow and
  largest at 45 deg (the shape is this module's choice; Alekseev gives only the measured
  size, up to 47 % of the normal force at 50-60 deg); the sign of ``C_m`` is the lay's.

The force acts on the stretched length with the same diameter (Merkin notes Alekseev's
division of the flow force by the stretch factor as an error). All functions work on floats
and CasADi symbols.
"""

from __future__ import annotations

import casadi as ca

#: Speed [m/s] below which a component of the flow counts as zero (keeps |U| differentiable).
_V_FLOOR = 1e-9


def _norm(v):
    return ca.sqrt(ca.sumsqr(v) + _V_FLOOR**2)


def line_drag(tangent, flow, diameter, water_density, normal, tangential=0.0, side=0.0):
    """Flow force per unit stretched length on a line [N/m], as a 3-vector.

    Parameters
    ----------
    tangent : casadi 3-vector
        Unit tangent of the line.
    flow : casadi 3-vector
        Current velocity relative to the line [m/s].
    diameter : float or symbol
        Hydrodynamic diameter [m].
    water_density : float or symbol
        [kg/m^3].
    normal, tangential, side : float or symbol
        Coefficients ``C_n``, ``C_t``, ``C_m`` (see the module notes).

    Notes
    -----
    ``f = q (C_n |U_n| U_n + C_t |U_t| U_t + C_m |U_n| |U_t| e_m)`` with ``q = rho d / 2``,
    ``U_t = (U . t) t``, ``U_n = U - U_t`` and ``e_m = (t x U) / |t x U|``.
    """
    q = water_density * diameter / 2
    along = ca.dot(flow, tangent)
    u_t = along * tangent
    u_n = flow - u_t
    n_mag, t_mag = _norm(u_n), ca.fabs(along)
    force = q * (normal * n_mag * u_n + tangential * t_mag * u_t)
    if not (isinstance(side, (int, float)) and side == 0):
        cross = ca.cross(tangent, flow)
        force = force + q * side * n_mag * t_mag * cross / _norm(cross)
    return force


def current_speed(z, profile):
    """Current speed [m/s] at height ``z`` from ``profile`` rows ``(z_k, v_k)``, z ascending.

    Linear between rows, constant beyond the first and last. ``profile`` holds floats or
    symbols; ``z`` a float or a symbol.
    """
    rows = list(profile)
    speed = rows[0][1]
    for (z0, v0), (z1, v1) in zip(rows[:-1], rows[1:]):
        ramp = v0 + (v1 - v0) * (z - z0) / (z1 - z0)
        speed = ca.if_else(z >= z0, ca.if_else(z <= z1, ramp, v1), speed)
    return speed


def current_velocity(z, profile, heading, directions: bool):
    """Current velocity [m/s] at height ``z`` as a 3-vector (horizontal).

    ``profile`` rows are ``(z_k, v_k)``, a signed speed along the unit ``heading``
    (``directions`` False), or ``(z_k, ux_k, uy_k)``, velocity components in the global
    frame (``directions`` True), interpolated component by component: a current turning or
    reversing with depth. Linear between rows, constant beyond the first and last.
    """
    rows = list(profile)
    if not directions:
        return current_speed(z, rows) * heading
    ux = current_speed(z, [(r[0], r[1]) for r in rows])
    uy = current_speed(z, [(r[0], r[2]) for r in rows])
    return ca.vertcat(ux, uy, 0)
