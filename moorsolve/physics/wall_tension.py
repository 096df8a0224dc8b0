"""True (wall) tension of a sealed line from its effective tension.

The catenary shape and the end reactions follow the *effective* tension, computed with the
submerged weight. In a sealed line (cable, pipe, sheathed rope) the wall also carries the
hydrostatic pressure acting on the cross-section, so the tension in the wall is lower by
``rho g A_o d`` at depth d and can turn compressive deep down while the effective tension is
positive (Sukhanov). A chain, wetted all round, has no
such difference.
"""

from __future__ import annotations

import math

import numpy

__all__ = ["outer_area", "wall_tension", "sukhanov_wall_tension"]


def outer_area(outer_diameter):
    """Outer cross-sectional area ``A_o = pi d^2 / 4`` [m^2] of a line of diameter d [m]."""
    return 0.25 * math.pi * outer_diameter * outer_diameter


def wall_tension(effective_tension, depth_below_surface, outer_diameter, water_density,
                 gravity):
    """Wall tension of a sealed line, ``T_wall = T_eff - rho g (pi d^2 / 4) depth``.

    Parameters
    ----------
    effective_tension : float, numpy.ndarray, casadi.SX or casadi.MX
        T_eff, tension from the submerged-weight catenary [N].
    depth_below_surface : float, numpy.ndarray, casadi.SX or casadi.MX
        Depth of the point below the still-water level [m], positive downward. A point
        above the water (negative depth) feels no hydrostatic pressure: the depth is
        clipped at 0 (computed as ``(depth + |depth|) / 2``, exact for depth >= 0).
    outer_diameter : float
        Outer diameter of the line [m].
    water_density : float
        [kg/m^3].
    gravity : float
        [m/s^2].

    Returns
    -------
    float, numpy.ndarray, casadi.SX or casadi.MX
        T_wall [N]; negative means the wall is in compression.

    Notes
    -----
    A. A. Sukhanov, "Catenary in water", eq. (25):
    ``T = q_c a ch(x/a) - q_h (h + a)`` with ``q_h = rho g A_o`` is this relation written for
    a catenary whose vertex is at depth h (see :func:`sukhanov_wall_tension`). The wall
    is taken to be at zero gauge pressure inside (a sealed, dry line).
    """
    depth_in_water = 0.5 * (depth_below_surface + abs(depth_below_surface))
    return (effective_tension
            - water_density * gravity * outer_area(outer_diameter) * depth_in_water)


def sukhanov_wall_tension(q_air, q_displaced, a, vertex_depth, x):
    """Sukhanov's closed-form wall tension along a submerged catenary.

    ``T = q_c a ch(x/a) - q_h (h + a)``.

    Parameters
    ----------
    q_air : float
        q_c, weight of the line in air per unit length [force/length].
    q_displaced : float
        q_h = rho g A_o, weight of the displaced water per unit length [force/length].
    a : float
        Catenary parameter ``H / (q_c - q_h)`` [length].
    vertex_depth : float
        h, depth of the catenary's lowest point below the surface [length].
    x : float or numpy.ndarray
        Horizontal distance from the vertex [length].

    Returns
    -------
    float or numpy.ndarray
        Wall tension [force], in the units of ``q_air * a``.

    Notes
    -----
    A. A. Sukhanov, "Catenary in water", eq. (25). It equals
    ``T_eff - q_h d`` with ``T_eff = (q_c - q_h) a ch(x/a)`` (eqs. (14), (24)) and the depth
    ``d = h - a (ch(x/a) - 1)`` of the point (eq. (20)).
    """
    return q_air * a * numpy.cosh(numpy.asarray(x) / a) - q_displaced * (vertex_depth + a)
