"""Contact: one-sided supports (quay walls, piles, fenders, pile guides) and Coulomb friction.

The model
---------
A contact joins a point and a surface, one of them on a body. Its *gap* ``g`` [m] is the
signed distance of the point from the surface (positive: apart), its *reaction* ``lam`` [N]
pushes the two apart along the surface's normal, and a compliant contact (a fender) has a
*compression* ``c(lam)`` [m] under that reaction: 0 for a rigid contact, ``lam / k`` for a
linear fender, the inverse of the maker's curve for a cell or cone fender. The contact law is
the complementarity (REFERENCE.md section 7)::

    lam >= 0,    g + c(lam) >= 0,    lam (g + c(lam)) = 0

out of contact no reaction; in contact the fender is compressed by exactly ``-g`` (so
``lam = R(-g)`` with ``R`` the reaction curve); a rigid contact cannot be penetrated. A
weightless line (a hawser) obeys the same law with its tension for ``lam``, its slack
``L - D`` (unstretched length minus chord) for ``g`` and its stretch ``lam L / EA`` for ``c``:
slack lines carry nothing, taut ones stretch.

Why an unknown reaction and Fischer-Burmeister
----------------------------------------------
The leg block writes its slack complementarity with one signed unknown whose two halves are
tension and slack (``H = max(u, 0)``): every iterate is exactly complementary. That cannot
work for a support that is the only thing holding a body in some direction (a ship on slack
hawsers under an offshore wind, a pontoon centred between guide rollers): while the support
is open the body's balance depends on nothing at all, the Jacobian has a zero row and every
local method stops where it starts. Here the reaction itself is the one unknown of each
complementarity, and the law is imposed by the Fischer-Burmeister function (REFERENCE.md
section 7)::

    phi(a, b) = a + b - sqrt(a^2 + b^2),    phi = 0  <=>  a >= 0, b >= 0, a b = 0

with ``a = lam / k`` (the reaction as a length at the scene's contact stiffness ``k``) and
``b = g + c(lam)``. The body always feels its supports' reactions, so a load can draw a slack
hawser taut; ``phi^2`` is continuously differentiable, so Newton's Armijo search on the
squared residual keeps working across contact changes. At an open contact with no reaction
``d phi / d b = 0``: the solvers use the Jacobian of the *smoothed* function
``a + b - sqrt(a^2 + b^2 + 2 eps^2)`` with ``eps`` tied to the current residual (the Jacobian
smoothing method of Chen, Qi and Sun 1998), and the exact residual for every decision, so the
answer is exactly complementary (to ``1e-150``: the floor under the square root).

Coulomb friction
----------------
The tangential force ``f`` (two components in the surface) and the tangential slip ``s`` of
the contact point since the case-file pose obey stick (``s = 0``, ``|f| <= mu lam``) or slip
(``|f| = mu lam``, ``f`` against ``s``). One residual per component writes both (Alart and
Curnier 1991)::

    f - proj(f - k s)  = 0,     proj(y) = y min(1, mu lam / |y|)

(the projection onto the disc of radius ``mu lam``). The case-file pose is the reference: a
contact sticks where the case places it. Every function here works on floats and on CasADi
symbols.
"""

from __future__ import annotations

import casadi as ca

#: Floor under the square roots [m^2 or N^2]: derivatives exist at (0, 0); the answer is
#: complementary to 1e-150.
_FLOOR = 1e-300


def fischer_burmeister(a, b, smoothing=0.0):
    """The (smoothed) Fischer-Burmeister function ``a + b - sqrt(a^2 + b^2 + 2 eps^2)``.

    Parameters
    ----------
    a, b : float or casadi symbol
        The two quantities that must be non-negative and complementary, in the same unit.
    smoothing : float or casadi symbol
        ``eps`` in that unit; 0 gives the exact function.

    Notes
    -----
    Zero exactly when ``a >= 0``, ``b >= 0`` and ``a b = 0`` (``eps = 0``); with ``eps > 0``
    its zeros are ``a, b > 0`` with ``a b = eps^2`` (Fischer 1992; REFERENCE.md section 7).
    """
    return a + b - ca.sqrt(a**2 + b**2 + 2 * smoothing**2 + _FLOOR)


def natural_residual(reaction, opening, stiffness):
    """How far a contact is from complementarity, as a force [N].

    The reaction acting across an open gap (``min(lam, k b)`` when both are positive) plus
    any pulling reaction (``max(-lam, 0)``); zero exactly when the law holds. ``opening`` is
    ``b = g + c(lam)`` [m] and ``stiffness`` the contact stiffness scale ``k`` [N/m].
    """
    return (ca.fmin(ca.fmax(reaction, 0), stiffness * ca.fmax(opening, 0))
            + ca.fmax(-reaction, 0))


def table_slopes(deflections, reactions):
    """Slopes [N/m] of a piecewise-linear reaction curve through ``(0, 0)`` and the rows.

    ``deflections`` and ``reactions`` exclude the origin; the last slope continues beyond
    the last row.
    """
    slopes, d0, r0 = [], 0.0, 0.0
    for d, r in zip(deflections, reactions):
        slopes.append((r - r0) / (d - d0))
        d0, r0 = d, r
    return slopes


def fender_reaction(compression, deflections, reactions):
    """Reaction [N] of a fender compressed by ``compression`` [m] (0 when not compressed).

    Parameters
    ----------
    compression : float or casadi symbol
        [m]
    deflections, reactions : sequences of float or symbols
        The maker's curve [m, N], rows after the origin, deflection ascending and reaction
        strictly increasing; one row is a linear fender of stiffness ``R/d``.

    Notes
    -----
    Linear interpolation through ``(0, 0)`` and the rows, the last slope continued:
    ``R = sum_i (k_i - k_{i-1}) max(delta - d_{i-1}, 0)`` with ``k_i`` the slope of
    segment ``i`` (``k_{-1} = 0``, ``d_{-1} = 0``). Cell and cone fender makers publish such
    curves (PIANC 2002 fender guidelines; the curve is the constitutive law, REFERENCE.md
    section 7).
    """
    slopes = table_slopes(deflections, reactions)
    starts = [0.0] + list(deflections[:-1])
    out, previous = 0, 0
    for k, d in zip(slopes, starts):
        out = out + (k - previous) * ca.fmax(compression - d, 0)
        previous = k
    return out


def fender_compression(reaction, deflections, reactions):
    """Compression [m] of a fender under ``reaction`` [N]: the inverse of
    :func:`fender_reaction` (negative reactions map linearly, with the first slope).

    Notes
    -----
    The inverse of a strictly increasing piecewise-linear curve is piecewise linear through
    the swapped rows: ``c = lam / k_0 + sum_{i>0} (1/k_i - 1/k_{i-1}) max(lam - R_{i-1}, 0)``.
    """
    slopes = table_slopes(deflections, reactions)
    out = reaction / slopes[0]
    for i in range(1, len(slopes)):
        out = out + (1 / slopes[i] - 1 / slopes[i - 1]) * ca.fmax(reaction - reactions[i - 1],
                                                                  0)
    return out


def fender_energy(compression, deflections, reactions):
    """Energy [J] a fender has absorbed at ``compression`` [m]: the area under its curve.

    Notes
    -----
    ``E = sum_i (k_i - k_{i-1}) max(delta - d_{i-1}, 0)^2 / 2``, exact for the piecewise-linear
    curve of :func:`fender_reaction` (the trapezoid rule on the maker's rows).
    """
    slopes = table_slopes(deflections, reactions)
    starts = [0.0] + list(deflections[:-1])
    out, previous = 0, 0
    for k, d in zip(slopes, starts):
        out = out + (k - previous) * ca.fmax(compression - d, 0) ** 2 / 2
        previous = k
    return out


def smooth_max(a, b, smoothing=0.0):
    """``max(a, b)``, smoothed by ``eps``: ``(a + b + sqrt((a - b)^2 + 4 eps^2)) / 2``."""
    return (a + b + ca.sqrt((a - b) ** 2 + 4 * smoothing**2 + _FLOOR)) / 2


def friction_residual(force, slip, limit, stiffness, smoothing=0.0):
    """Coulomb stick/slip residual (2-vector, N): ``f - proj_{|y| <= limit}(f - k s)``.

    Parameters
    ----------
    force : 2-vector
        Tangential force on the body [N], in the contact's tangent basis.
    slip : 2-vector
        Tangential displacement of the contact since the case-file pose [m].
    limit : float or symbol
        ``mu lam``: the largest friction force the reaction allows [N] (0 out of contact).
    stiffness : float
        The contact stiffness scale ``k`` [N/m] weighing slip against force.
    smoothing : float or symbol
        ``eps`` [N] for the solvers' Jacobian; 0 is exact.

    Notes
    -----
    Zero exactly in stick (``s = 0``, ``|f| <= limit``) or slip (``|f| = limit`` and ``f``
    opposite to ``s``); Alart and Curnier (1991), the augmented-Lagrangian form of Coulomb's
    law.
    """
    y0, y1 = force[0] - stiffness * slip[0], force[1] - stiffness * slip[1]
    size = ca.sqrt(y0**2 + y1**2 + _FLOOR)
    bound = ca.fmax(limit, 0)
    scale = bound / smooth_max(size, bound, smoothing)
    return ca.vertcat(force[0] - y0 * scale, force[1] - y1 * scale)


def tangent_basis(normal):
    """Two unit vectors spanning the plane normal to ``normal`` (unit 3-vector).

    ``t1`` is horizontal (``e_z x n`` normalised; ``e_x`` direction for a horizontal
    surface) and ``t2 = n x t1`` (upward on a vertical wall).
    """
    hx, hy = -normal[1], normal[0]
    size = ca.sqrt(hx**2 + hy**2)
    level = size > 1e-9
    safe = ca.if_else(level, size, 1)
    t1 = ca.vertcat(ca.if_else(level, hx / safe, 1), ca.if_else(level, hy / safe, 0), 0)
    t2 = ca.vertcat(normal[1] * t1[2] - normal[2] * t1[1],
                    normal[2] * t1[0] - normal[0] * t1[2],
                    normal[0] * t1[1] - normal[1] * t1[0])
    return t1, t2


def plane_gap(point, plane_point, normal):
    """A point against a plane: ``(gap, contact point)``.

    ``gap = n . (p - p0)`` [m] (``n`` the plane's unit normal toward the side the point
    belongs on); the contact point is the point's foot on the plane, where a compressed
    fender's face sits.
    """
    gap = ca.dot(normal, point - plane_point)
    return gap, point - gap * normal


def cylinder_gap(point, centre, radius):
    """A point against a fixed vertical cylinder (a pile): ``(gap, unit normal, contact
    point)``.

    ``gap = |p_xy - c| - r`` [m]; the normal is horizontal, from the axis toward the point;
    the contact point is on the cylinder's surface at the point's height.
    """
    dx, dy = point[0] - centre[0], point[1] - centre[1]
    rho = ca.sqrt(dx**2 + dy**2 + _FLOOR)
    nx, ny = dx / rho, dy / rho
    normal = ca.vertcat(nx, ny, 0)
    contact = ca.vertcat(centre[0] + radius * nx, centre[1] + radius * ny, point[2])
    return rho - radius, normal, contact


__all__ = ["fischer_burmeister", "natural_residual", "table_slopes", "fender_reaction",
           "fender_compression", "fender_energy", "smooth_max", "friction_residual",
           "tangent_basis", "plane_gap", "cylinder_gap"]
