"""Contact: one-sided supports (quay walls, piles, fenders, pile guides) and Coulomb friction.

The model
---------
A contact joins a point and a surface, one of them on a body. Its *gap* ``g`` [m] is the
signed distance of the point from the surface (positive: apart), and its *reaction* ``lam``
[N] pushes the two apart along the surface's normal.

A compliant contact (a fender) reacts to its compression by its maker's curve: the curve is
the constitutive law, so ``lam = R(max(-g, 0))`` is an explicit
function of the geometry (:func:`fender_reaction`, linear between the maker's rows), zero
out of contact. A rigid contact (a rigid fender, a rubbing strip, a pile guide's pad on a
rigid pile) needs the complementarity::

    lam >= 0,    g >= 0,    lam g = 0

and so does a weightless line (a hawser), with its tension for ``lam`` and its slack, the
stretched length less the chord, ``L (1 + lam / EA) - D``, for ``g``: slack lines carry
nothing, taut ones stretch.

Why the reaction is the unknown, with Fischer-Burmeister
--------------------------------------------------------
The leg block writes its slack complementarity with one signed unknown whose two halves are
tension and slack (``H = max(u, 0)``): every iterate is exactly complementary. That cannot
work for a support that is the only thing holding a body in some direction (a ship on slack
hawsers under an offshore wind): while the support is open the body's balance depends on
none of the unknowns, the Jacobian has a zero row and every local method stops where it
starts. Here the reaction itself is the one unknown of each complementarity, and the law is
imposed by the Fischer-Burmeister function::

    phi(a, b) = a + b - sqrt(a^2 + b^2),    phi = 0  <=>  a >= 0, b >= 0, a b = 0

with ``a = lam / k`` (the reaction as a length at the scene's contact stiffness ``k``, the
force scale over the length scale, the same weighing as the rest of the scaled residual)
and ``b`` the gap. The body always feels its supports' reactions, so a load can draw a
slack hawser taut; ``phi^2`` is continuously differentiable, so Newton's Armijo search on
the squared residual keeps working across contact changes. At an open contact with no
reaction ``d phi / d b = 0``: the solvers use the Jacobian of the *smoothed* function
``a + b - sqrt(a^2 + b^2 + 2 eps^2)`` with ``eps`` tied to the current residual (the Jacobian
smoothing method of Chen, Qi and Sun 1998), and the exact residual for every decision, so the
answer is exactly complementary (to ``1e-150``: the floor under the square root).

Coulomb friction
----------------
The tangential force on a contact is Coulomb's, mobilised over a small slip ``delta``::

    f = -mu lam s / max(|s|, delta)

with ``s`` the tangential displacement of the contact point since the case-file pose (the
reference: a contact sticks where the case places it). Below ``delta`` the contact sticks
elastically (``|f| < mu lam``, the body held within ``delta`` of where it was placed); beyond
it the contact slips with ``|f| = mu lam`` against the slip. Rigid stick (``delta = 0``) is
not used because it leaves the friction statically indeterminate as soon as two contacts of
one rigid body stick (a body on two fenders pushed along the quay: only the sum of their
friction forces is fixed by equilibrium); the elastic stick shares it in proportion to the
reactions (the stick stiffness ``mu lam / delta`` grows with the reaction) and makes the
answer unique, path-independent and explicit (no unknowns). ``delta`` defaults to a
millimetre (:data:`FRICTION_SLIP`), far below the accuracy a berth's geometry is known to.
Every function here works on floats and on CasADi symbols.
"""

from __future__ import annotations

import casadi as ca

from ..constants import FRICTION_SLIP

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
    its zeros are ``a, b > 0`` with ``a b = eps^2`` (Fischer 1992).
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


def fender_reaction(compression, deflections, reactions, smoothing=0.0):
    """Reaction [N] of a fender compressed by ``compression`` [m] (0 when not compressed).

    Parameters
    ----------
    compression : float or casadi symbol
        [m]
    deflections, reactions : sequences of float or symbols
        The maker's curve [m, N], rows after the origin, deflection ascending and reaction
        strictly increasing; one row is a linear fender of stiffness ``R/d``.
    smoothing : float or symbol
        ``eps`` [m] smoothing the contact switch at zero compression (for the solvers'
        Jacobian, :func:`smooth_max`); 0 is exact.

    Notes
    -----
    Linear interpolation through ``(0, 0)`` and the rows, the last slope continued:
    ``R = sum_i (k_i - k_{i-1}) max(delta - d_{i-1}, 0)`` with ``k_i`` the slope of
    segment ``i`` (``k_{-1} = 0``, ``d_{-1} = 0``). Cell and cone fender makers publish such
    curves (PIANC 2002 fender guidelines; the curve is the constitutive law
    section 7).
    """
    slopes = table_slopes(deflections, reactions)
    out = slopes[0] * smooth_max(compression, 0, smoothing)
    for i in range(1, len(slopes)):
        out = out + (slopes[i] - slopes[i - 1]) * ca.fmax(compression - deflections[i - 1], 0)
    return out


def smooth_max(a, b, smoothing=0.0):
    """``max(a, b)``; with ``eps > 0`` the smooth ``(a + b + sqrt((a - b)^2 + 4 eps^2)) / 2``
    (for the solvers' Jacobian smoothing)."""
    if isinstance(smoothing, (int, float)) and smoothing == 0:
        return ca.fmax(a, b)
    return (a + b + ca.sqrt((a - b) ** 2 + 4 * smoothing**2 + _FLOOR)) / 2


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


def friction_force(slip, reaction, coefficient, mobilisation=None):
    """Coulomb friction with an elastic stick, on floats or symbols [N].

    Parameters
    ----------
    slip : 3-vector
        Tangential displacement of the contact point since the case-file pose [m].
    reaction : float or symbol
        The contact's reaction [N] (friction needs a positive one).
    coefficient : float or symbol
        Coulomb coefficient ``mu``.
    mobilisation : float or symbol, optional
        The slip ``delta`` [m] over which friction is mobilised (default
        :data:`FRICTION_SLIP`).

    Returns
    -------
    3-vector
        ``-mu max(lam, 0) s / max(|s|, delta)``: against the slip, at most ``mu lam``.

    Notes
    -----
    Coulomb's law (``|F_t| <= mu lam``, sliding opposite to the
    slip) with the stick regularised as in the module notes.
    """
    delta = FRICTION_SLIP if mobilisation is None else mobilisation
    size = ca.sqrt(slip[0]**2 + slip[1]**2 + slip[2]**2 + _FLOOR)
    return -coefficient * ca.fmax(reaction, 0) * slip / ca.fmax(size, delta)


def plane_gap(point, plane_point, normal):
    """A point against a plane: ``(gap, contact point)``.

    ``gap = n . (p - p0)`` [m] (``n`` the plane's unit normal toward the side the point
    belongs on); the contact point is the point's foot on the plane, where a compressed
    fender's face sits.
    """
    gap = ca.dot(normal, point - plane_point)
    return gap, point - gap * normal


__all__ = ["fischer_burmeister", "natural_residual", "table_slopes", "fender_reaction",
           "fender_energy", "smooth_max", "friction_force", "plane_gap", "FRICTION_SLIP"]
