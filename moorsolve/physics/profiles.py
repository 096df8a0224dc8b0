"""Points and tension along a solved line, in its vertical plane: the profiles.

The closed forms of :mod:`moorsolve.physics.catenary` evaluated along the unstretched arc
length on floats (numpy), for the Result and the plots: a leg from its anchor
(:func:`leg_profile`), a segment of a multi-segment line from its lower end
(:func:`segment_profile`), a leg on a sloped seabed (:func:`sloped_leg_profile`). Hooke's
stretch has its own closed forms; another law (:class:`~moorsolve.physics.stretch.NumericLaw`)
enters through the same integrals as in the blocks: ``(H/w)[Psi(T_v) - Psi(T_v0)]`` and
``[E(T) - E(T_0)]/w`` along a catenary, the loaded length times the mean strain on the seabed.
"""

from __future__ import annotations

import math

import numpy as np

from .catenary import LegKind, descent_force
from .stretch import NumericLaw

__all__ = ["leg_profile", "segment_profile", "sloped_leg_profile"]


def leg_profile(kind: LegKind, *, H: float, V: float, L: float, w: float,
                ea: float | None, mu: float, X: float, Z: float = 0.0,
                n: int = 101, law: NumericLaw | None = None) -> dict:
    """Points and tension along a solved leg, in its vertical plane, from the anchor.

    Parameters
    ----------
    kind : LegKind
    H, V : float
        Horizontal and vertical tension at the fairlead [N] (the solved state).
    L, w, ea, mu : float
        Length [m], submerged weight [N/m], stiffness [N] (None: inextensible), friction.
    X, Z : float
        Horizontal and vertical span [m]: where a slack line's loose part ends, and the
        chord of a weightless line.
    n : int
        Number of points.
    law : NumericLaw, optional
        The line's stretch law when it is not Hooke's (``ea`` is then unused).

    Returns
    -------
    dict of numpy arrays
        ``s`` unstretched arc length from the anchor [m], ``x`` horizontal distance from the
        anchor [m], ``z`` height above the anchor [m], ``tension`` effective tension [N].

    Notes
    -----
    With ``T_v(s)`` the vertical tension at arc length s, the suspended part follows
    ``x = (H/w)[asinh(T_v/H) - asinh(T_v0/H)] + H s/EA`` and
    ``z = [sqrt(H^2+T_v^2) - sqrt(H^2+T_v0^2)]/w + (T_v0 s + w s^2/2)/EA``
    (Merkin 1980, seed 004, section 2.3, integrated from the lowest suspended point); with
    another stretch law the terms in ``1/EA`` become ``(H/w)[Psi(T_v) - Psi(T_v0)]`` and
    ``[E(T) - E(T_0)]/w`` (:mod:`moorsolve.physics.stretch`).
    """
    st = _ProfileStretch(ea, law)
    s = np.linspace(0.0, L, n)
    if kind.neutral:
        # Straight along the chord when taut; a loose weightless line has no definite
        # shape, so it is drawn along the chord as well.
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    if not kind.contact or VA >= 0:
        return _hanging_profile(s, H, VA, w, st)
    LB = L - V / w
    grounded = s <= LB
    Tv = np.where(grounded, 0.0, w * (s - LB))
    sg = np.minimum(s, LB)
    # Tension on the seabed: H at touchdown, decaying by friction toward the anchor.
    Tg = np.maximum(H - mu * w * (LB - sg), 0.0) if mu > 0 else np.full_like(s, H)
    if H > 0:
        # Where the seabed tension starts to rise (friction may use it up before the anchor).
        s0 = max(LB - H / (mu * w), 0.0) if mu > 0 else 0.0
        T_anchor = max(H - mu * w * LB, 0.0) if mu > 0 else H
        x_td = sg + _laid_stretch(st, s0, T_anchor, sg, Tg)
        T = np.hypot(H, Tv)
        xs = (H / w) * (np.arcsinh(Tv / H) + st.psi(H, Tv))
        zs = (T - H) / w + (st.energy(T) - st.energy(H)) / w
        x_touch = LB + _laid_stretch(st, s0, T_anchor, np.array([LB]), np.array([H]))[0]
        x = np.where(grounded, x_td, x_touch + xs)
        z = np.where(grounded, 0.0, zs)
        tension = np.where(grounded, Tg, T)
    else:
        # Slack: the hanging part is vertical under the fairlead, the rest lies loose
        # (buckled) between anchor and the fairlead's foot: shown straight along the seabed.
        x = np.where(grounded, np.minimum(sg, X), X)
        z = np.where(grounded, 0.0, (Tv + st.energy(Tv)) / w)
        tension = np.where(grounded, 0.0, Tv)
    return dict(s=s, x=x, z=z, tension=tension)


class _ProfileStretch:
    """Stretch terms of a solved line on numpy arrays: Hooke's (compliance ``1/ea``, 0 when
    inextensible) or a :class:`~moorsolve.physics.stretch.NumericLaw`'s."""

    def __init__(self, ea, law):
        self.c = 1.0 / ea if ea else 0.0
        self.law = law

    def strain(self, T):
        return self.law.strain(T) if self.law is not None else self.c * np.asarray(T)

    def energy(self, T):
        return self.law.energy(T) if self.law is not None else self.c * np.square(T) / 2

    def mean(self, a, b):
        return self.law.mean(a, b) if self.law is not None else self.c * (a + b) / 2

    def psi(self, H, Tv):
        return self.law.horizontal(H, Tv) if self.law is not None else self.c * np.asarray(Tv)

    def descent_force(self, H, h, w):
        """:func:`descent_force` on floats."""
        if self.law is None:
            return float(descent_force(H, h, w, self.c))
        delta = self.law.descent(H, w * h)
        return -math.sqrt(delta * (delta + 2 * H))


def _laid_stretch(st, s0, T_start, sg, T_end):
    """Stretch from the anchor to arc length ``sg`` of line lying on the seabed: unloaded up
    to ``s0``, then the tension runs linearly from ``T_start`` to ``T_end`` at ``sg``."""
    loaded = np.maximum(sg - s0, 0.0)
    return loaded * st.mean(T_start, np.maximum(T_end, 0.0))


def segment_profile(*, H: float, V: float, L: float, w: float, ea: float | None, h: float,
                    X: float, Z: float, n: int = 51, law: NumericLaw | None = None) -> dict:
    """Points and tension along one segment from its lower end, in the leg's plane.

    Covers every regime of :func:`lifted_segment_equations` (``h`` may be 0) and of a
    suspended or weightless segment (``w <= 0``); see :func:`leg_profile` for the output.
    The vertical tension is ``T_v(s) = V_A + w s`` on a suspended segment; on a two-sided
    touchdown it runs from ``V1`` to 0 on the descent, is 0 on the seabed and rises from 0.
    ``law``: the stretch law when it is not Hooke's.
    """
    st = _ProfileStretch(ea, law)
    s = np.linspace(0.0, L, n)
    if w == 0:
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    V1 = st.descent_force(H, h, w) if w > 0 else -np.inf
    if VA >= V1:
        return _hanging_profile(s, H, VA, w, st)
    s1 = -V1 / w
    LB = L - s1 - V / w
    s2 = s1 + LB
    Tv = np.where(s < s1, V1 + w * s, np.where(s <= s2, 0.0, w * (s - s2)))
    T, T1 = np.hypot(H, Tv), math.hypot(H, V1)
    if H > 0:
        x_desc = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(V1 / H)
                            + st.psi(H, Tv) - st.psi(H, V1))
        x1 = (H / w) * (np.arcsinh(-V1 / H) + st.psi(H, -V1))
        eps_H = float(st.strain(H))
        x_ground = x1 + (s - s1) * (1 + eps_H)
        x2 = x1 + LB * (1 + eps_H)
        x_rise = x2 + (H / w) * (np.arcsinh(Tv / H) + st.psi(H, Tv))
    else:
        x_desc = np.zeros_like(s)
        x_ground = np.minimum(s - s1, X)
        x_rise = np.full_like(s, X)
    z_desc = (T - T1) / w + (st.energy(T) - st.energy(T1)) / w
    z_rise = -h + (T - H) / w + (st.energy(T) - st.energy(H)) / w
    x = np.where(s < s1, x_desc, np.where(s <= s2, x_ground, x_rise))
    z = np.where(s < s1, z_desc, np.where(s <= s2, -h, z_rise))
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


def sloped_leg_profile(*, H: float, V: float, L: float, w: float, ea: float | None,
                       mu: float, t: float, X: float, Z: float, n: int = 101,
                       law: NumericLaw | None = None) -> dict:
    """Points and tension along a solved leg on a sloped seabed (see :func:`leg_profile`)."""
    st = _ProfileStretch(ea, law)
    s = np.linspace(0.0, L, n)
    sec = np.sqrt(1 + t * t)
    cos_t, sin_t = 1 / sec, t / sec
    VA = V - w * L
    if VA >= H * t:
        return _hanging_profile(s, H, VA, w, st)
    LB = L - (V - H * t) / w
    k = w * (sin_t + mu * cos_t)
    TA_raw = H * sec - k * LB
    sg = np.minimum(s, LB)
    Tg = np.maximum(TA_raw + k * sg, 0.0)
    # Stretch along the slope: unloaded up to s0 (where the tension has fallen to zero),
    # then the tension runs linearly from max(TA_raw, 0).
    s0 = min(max(-TA_raw / k, 0.0), LB) if k > 0 else 0.0
    stretch = _laid_stretch(st, s0, max(TA_raw, 0.0), sg, Tg)
    stretch_td = float(_laid_stretch(st, s0, max(TA_raw, 0.0), np.array([LB]),
                                       np.array([H * sec]))[0])
    if H > 0:
        Tv = H * t + w * (s - LB)
        T = np.hypot(H, Tv)
        xs = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(t) + st.psi(H, Tv) - st.psi(H, H * t))
        zs = (T - H * sec) / w + (st.energy(T) - st.energy(H * sec)) / w
        ground = s <= LB
        x = np.where(ground, (sg + stretch) * cos_t, (LB + stretch_td) * cos_t + xs)
        z = np.where(ground, (sg + stretch) * sin_t, (LB + stretch_td) * sin_t + zs)
        tension = np.where(ground, Tg, np.hypot(H, Tv))
    else:
        # Slack: loose on the slope up to below the fairlead, then hanging straight.
        foot = X / cos_t
        ground = s <= LB
        along = np.minimum(sg, foot)
        hang = np.maximum(s - LB, 0.0)
        x = np.where(ground, along * cos_t, X)
        z = np.where(ground, along * sin_t, X * t + hang + st.energy(w * hang) / w)
        tension = np.where(ground, 0.0, w * hang)
    return dict(s=s, x=x, z=z, tension=tension)


def _hanging_profile(s, H, VA, w, st) -> dict:
    """Points of a fully suspended elastic catenary from its lower end, where the vertical
    force is ``VA``; ``st`` its stretch (:class:`_ProfileStretch`). ``H = 0`` is a vertical
    line, which folds where the vertical force changes sign (the integral of its sign)."""
    Tv = VA + w * s
    T, T0 = np.hypot(H, Tv), math.hypot(H, VA)
    stretch_z = (st.energy(T) - st.energy(T0)) / w
    if H > 0:
        x = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(VA / H) + st.psi(H, Tv) - st.psi(H, VA))
        z = (T - T0) / w + stretch_z
    else:
        x = np.zeros_like(s)
        z = (np.abs(Tv) - abs(VA)) / w * np.sign(Tv) + stretch_z
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))
