"""Hydrostatics of a floating body: the linear model and exact buoyancy of simple members.

Linear model (the one MoorPy and MoorDyn use): the
weight ``m g`` acts down at the centre of gravity ``R r_G``; the buoyancy ``rho g V`` acts up
at the metacentre ``R r_M``, a point fixed in the body frame; the heave restoring force is
``-rho g A_wp z`` with ``z`` the height of the body-frame origin. Its small-angle stiffness
is ``K33 = rho g A_wp`` and ``K44 = K55 = rho g V z_M - m g z_G`` (symmetric body).

Exact members: a vertical prism (circular cylinder or rectangular box) along body z whose
submerged part is integrated at the actual pose. Along the member's axis the water surface
(global z = 0) lies at body-frame height ``zeta(x, y) = -(r_z + R20 x + R21 y) / R22``, a
linear function over the member's cross-section; the submerged height above the bottom is
``h(x, y) = zeta(x, y) - bottom``. While ``0 < h < top - bottom`` over the whole section (the
waterplane cuts the side walls only), the submerged volume and its centroid are exact
integrals of that linear function over the section:

    V = A h_c,    x_B = x_c + I_xx a_x / V,    y_B = y_c + I_yy a_y / V,
    z_B = bottom + (A h_c^2 + I_xx a_x^2 + I_yy a_y^2) / (2 V)

with ``h = h_c + a_x (x - x_c) + a_y (y - y_c)``, ``A`` the section area and ``I`` its second
moments about its centre (``pi r^4 / 4``; ``L^3 W / 12`` and ``L W^3 / 12``). A member whose
section lies wholly below the surface (h >= top - bottom everywhere) displaces its whole
volume at its centre. Buoyancy ``rho g V`` acts up through the centroid (Archimedes: the
resultant of the pressure on the wetted surface). Beyond these two regimes (the surface
crosses the bottom or top face) the formulas are not exact; :func:`member_buoyancy` reports
that as ``in_range = 0`` so the solver can refuse the point.
"""

from __future__ import annotations

import math

import casadi as ca

from .kinematics import cross


def linear_buoyancy(position, R, *, displaced_volume, metacentre, waterplane_area,
                    water_density, gravity):
    """Force and moment (about the body-frame origin, global axes) of the buoyancy and the
    heave restoring force of the linear model.

    Parameters
    ----------
    position : 3-vector
        Body-frame origin [m].
    R : 3x3
        Rotation matrix of the body.
    displaced_volume : float or symbol
        [m^3].
    metacentre : 3-vector
        Body frame [m].
    waterplane_area : float or symbol
        [m^2].
    water_density, gravity : float or symbol
        [kg/m^3], [m/s^2].

    Returns
    -------
    (force, moment) : 3-vectors [N], [N m]

    Notes
    -----
    ``rho g V`` up at ``R r_M`` and ``-rho g A_wp z`` along the vertical through the origin
    (so it adds no moment), as MoorPy and MoorDyn model it.
    """
    rho_g = water_density * gravity
    buoyant = ca.vertcat(0, 0, rho_g * displaced_volume)
    spring = ca.vertcat(0, 0, -rho_g * waterplane_area * position[2])
    moment = cross(R @ ca.vertcat(*metacentre), buoyant)
    return buoyant + spring, moment


def section_properties(shape: str, radius: float = 0.0, length: float = 0.0,
                       width: float = 0.0) -> tuple:
    """Area [m^2] and second moments ``(I_xx, I_yy)`` [m^4] of a member's cross-section about
    its centre, where ``I_xx = int (x - x_c)^2 dA`` (the moment that weights a slope along x)."""
    if shape == "cylinder":
        area = math.pi * radius**2
        inertia = math.pi * radius**4 / 4
        return area, inertia, inertia
    area = length * width
    return area, length**3 * width / 12, length * width**3 / 12


def member_buoyancy(position, R, *, shape, bottom, top, centre, water_density, gravity,
                    radius=0.0, length=0.0, width=0.0):
    """Exact buoyancy of one vertical prism of the hull at the pose ``(position, R)``.

    Returns
    -------
    dict
        ``force`` and ``moment`` (about the body-frame origin, global axes) [N, N m],
        ``volume`` [m^3], ``centroid`` (body frame [m]) and ``in_range`` (1 where the formula
        is exact: the surface cuts the side walls, or the member is wholly submerged or
        wholly out of the water; 0 otherwise).

    Notes
    -----
    See the module notes. The height of the surface along the member's axis at body-frame
    ``(x, y)`` is ``-(r_z + R20 x + R21 y) / R22``; ``R22 > 0`` (less than 90 deg of tilt).
    """
    area, ixx, iyy = section_properties(shape, radius, length, width)
    xc, yc = centre
    height = top - bottom
    r20, r21, r22 = R[2, 0], R[2, 1], R[2, 2]
    h_c = -(position[2] + r20 * xc + r21 * yc) / r22 - bottom
    a_x, a_y = -r20 / r22, -r21 / r22
    # Half-width of the section along the surface's steepest slope: extreme h deviation.
    if shape == "cylinder":
        spread = radius * ca.sqrt(a_x**2 + a_y**2)
    else:
        spread = (length / 2) * ca.fabs(a_x) + (width / 2) * ca.fabs(a_y)
    h_min, h_max = h_c - spread, h_c + spread
    submerged = h_min >= height
    dry = h_max <= 0
    cut = ca.logic_and(h_min > 0, h_max < height)
    v_cut = area * h_c
    v_safe = ca.if_else(ca.fabs(v_cut) > 0, v_cut, 1)
    x_cut = xc + ixx * a_x / v_safe
    y_cut = yc + iyy * a_y / v_safe
    z_cut = bottom + (area * h_c**2 + ixx * a_x**2 + iyy * a_y**2) / (2 * v_safe)
    volume = ca.if_else(submerged, area * height, ca.if_else(dry, 0, v_cut))
    cx = ca.if_else(submerged, xc, x_cut)
    cy = ca.if_else(submerged, yc, y_cut)
    cz = ca.if_else(submerged, (bottom + top) / 2, z_cut)
    centroid = ca.vertcat(cx, cy, cz)
    force = ca.vertcat(0, 0, water_density * gravity * volume)
    moment = cross(R @ centroid, force)
    in_range = ca.if_else(ca.logic_or(ca.logic_or(submerged, dry), cut), 1, 0)
    return dict(force=force, moment=moment, volume=volume, centroid=centroid,
                in_range=in_range)


def weight(position, R, *, mass, centre_of_gravity, gravity):
    """Force and moment (about the body-frame origin) of the body's weight [N, N m]."""
    w = ca.vertcat(0, 0, -mass * gravity)
    return w, cross(R @ ca.vertcat(*centre_of_gravity), w)
