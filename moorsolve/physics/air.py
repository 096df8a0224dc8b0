"""A one-segment line whose two ends are above the water: in air, or dipping into the water.

Above the still-water level (``z = 0``) a line weighs ``w_air`` per unstretched metre, below
it ``w`` (its weight in water). Along a catenary the vertical tension grows by the local
weight per unstretched metre and, with the stretch law's ``E(T) = int_0^T eps``, the height
by ``w dz = d[T + E(T)]`` (Merkin 1980, sections 2.1 and 2.3: the elastic
catenary in its end tensions), so the profile is piecewise catenary, continuous in force:
a new piece starts wherever the line crosses the surface. A sinking line (``w > 0``) is
convex, so the part below the water is one run in the middle of the line. Walking from the
upper end B (horizontal tension ``H``, vertical ``V``, height ``z_B > 0``) toward end A:

- the part in air from B down to the surface (:func:`~moorsolve.physics.catenary.air_part`):
  the crossing's vertical tension ``V_c`` and the length in air ``l_B``;
- **in air throughout** when the line turns up before it reaches the water (``V_c <= 0``)
  or ends first (``l_B >= L``): one catenary of weight ``w_air``;
- else a run in water of ``L - l_B``: when it is at most ``2 V_c / w`` (the length that
  brings a catenary back up to the surface, where its vertical tension is ``-V_c``) end A
  is under water; beyond it the line rises back into the air at ``-V_c`` and its last
  ``l_A = L - l_B - 2 V_c / w`` weigh ``w_air``: end A is above the water.

The three regimes meet continuously (``V_c = 0``: the vertex touches the surface; ``l_A =
0``: end A at the surface), so the residuals are continuous and Newton's method may move
end A (a free point) in and out of the water. Where the vertex grazes the surface the
length in water grows as the square root of the dip (``V_c ~ sqrt(2 H (T_c - H))``), so
the residuals' derivative is unbounded there, as the physics' is. Each piece's spans are closed forms in its
end tensions, with any stretch law (:mod:`moorsolve.physics.stretch`).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from .catenary import _H_FLOOR, _hyp, air_part

__all__ = ["air_line", "air_line_profile"]


def _piece(H, Hg, V0, V1, w, c, law):
    """Spans ``(x, z)`` [m] of a catenary piece of weight ``w`` between vertical tensions
    ``V0 < V1`` (in the direction of growing vertical tension)."""
    T0, T1 = _hyp(H, V0), _hyp(H, V1)
    x = (H / w) * (ca.asinh(V1 / Hg) - ca.asinh(V0 / Hg))
    z = (T1 - T0) / w
    if law is None:
        return x + H * (V1 - V0) / w * c, z + (V1**2 - V0**2) / (2 * w) * c
    psi1, psi0 = law.horizontal(Hg, V1, V0)
    return x + (H / w) * (psi1 - psi0), z + (law.energy(T1) - law.energy(T0)) / w


def air_line(X, Z, H, V, z_top, L, w, w_air, ea_inv, law=None):
    """Residuals and end forces of a sinking line from end A up to end B, ``z_top > 0``
    above the water (see the module notes).

    Parameters
    ----------
    X, Z : casadi expressions
        Horizontal span and rise from A to B [m].
    H, V : casadi expressions
        Horizontal and vertical tension at B [N].
    z_top : casadi expression
        Height of B above the still water [m].
    L, w, w_air, ea_inv : casadi expressions
        Unstretched length [m], weight in water and in air [N/m], compliance 1/EA [1/N]
        (ignored with a ``law``).
    law : :class:`~moorsolve.physics.stretch.Law`, optional

    Returns
    -------
    dict
        ``rX``, ``rZ`` span residuals [m]; ``H``, ``VF`` (at B), ``HA``, ``VA`` (the upward
        pull on A) [N]; ``grounded`` 0; ``suspended_x`` [m]; ``in_air`` the length above
        the water [m].
    """
    Hg = ca.fmax(H, _H_FLOOR)
    c = 0 if law is not None else ea_inv
    top = air_part(H, V, z_top, w_air, c, law=law)
    Vc, lB = top["V"], top["length"]
    # In air throughout: one catenary of the air weight.
    VA_air = V - w_air * L
    x_air, z_air = _piece(H, Hg, VA_air, V, w_air, c, law)
    # Into the water: a run of L - lB; end A under it, or back up into the air.
    Vcp = ca.fmax(Vc, 0)
    wet = L - lB
    back_up = 2 * Vcp / w
    VA_under = Vcp - w * wet
    x_w1, z_w1 = _piece(H, Hg, VA_under, Vcp, w, c, law)
    lA = wet - back_up
    VA_over = -Vcp - w_air * lA
    x_w2, _ = _piece(H, Hg, -Vcp, Vcp, w, c, law)
    x_a, z_a = _piece(H, Hg, VA_over, -Vcp, w_air, c, law)
    in_air = ca.logic_or(Vc <= 0, lB >= L)
    under = wet <= back_up
    Xm = top["x"] + ca.if_else(under, x_w1, x_w2 + x_a)
    Zm = z_top + ca.if_else(under, z_w1, z_a)     # B's height less A's
    VA = ca.if_else(in_air, VA_air, ca.if_else(under, VA_under, VA_over))
    Xm = ca.if_else(in_air, x_air, Xm)
    Zm = ca.if_else(in_air, z_air, Zm)
    length_in_air = ca.if_else(in_air, L, lB + ca.if_else(under, 0, lA))
    return dict(rX=Xm - X, rZ=Zm - Z, H=H, VF=V, HA=H, VA=VA, grounded=0 * H,
                suspended_x=Xm, in_air=length_in_air)


def air_line_profile(*, H: float, V: float, z_top: float, L: float, w: float, w_air: float,
                     ea: float | None, n: int = 61, law=None) -> dict:
    """Points and tension along a solved :func:`air_line`, from end A (``s = 0``), in the
    plane: ``x`` from A toward B, ``z`` absolute heights [m].

    Each piece is drawn by its own closed forms from its end tensions, so the profile
    meets B (``x`` = the solved span, ``z = z_top``) to round-off when the solve closed.
    """
    from .profile import _Stretch
    st = _Stretch(ea, law)
    bound = law.bound if law is not None else None
    part = {k: float(v) for k, v in air_part(H, V, z_top, w_air, st.c, law=bound).items()}
    Vc, lB = part["V"], part["length"]
    # The pieces from B toward A: (weight, vertical tension at B's side, length).
    if Vc <= 0 or lB >= L:
        pieces = [(w_air, V, L)]
    else:
        wet = L - lB
        pieces = [(w_air, V, lB)]
        if wet <= 2 * Vc / w:
            pieces.append((w, Vc, wet))
        else:
            pieces += [(w, Vc, 2 * Vc / w), (w_air, -Vc, wet - 2 * Vc / w)]
    count = max(n // len(pieces), 3)
    s, x, z, T = [0.0], [0.0], [z_top], [math.hypot(H, V)]
    for weight, Vtop, length in pieces:
        back = np.linspace(0.0, length, count)[1:]       # from this piece's B side
        Tv = Vtop - weight * back
        if H > 0:
            dx = (H / weight) * (np.arcsinh(Vtop / H) - np.arcsinh(Tv / H)) \
                + st.across(H, Tv, Vtop, weight)
        else:
            dx = np.zeros_like(Tv)
        dz = (math.hypot(H, Vtop) - np.hypot(H, Tv)) / weight + st.up(H, Tv, Vtop, weight)
        s += list(s[-1] + back)
        x += list(x[-1] - dx)
        z += list(z[-1] - dz)
        T += list(np.hypot(H, Tv))
    x = np.asarray(x)
    # From A: reverse, x measured from A.
    return dict(s=(L - np.asarray(s))[::-1], x=(x - x[-1])[::-1], z=np.asarray(z)[::-1],
                tension=np.asarray(T)[::-1])
