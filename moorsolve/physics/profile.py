"""Points and tension along a solved line, in its vertical plane: the shape of each block.

Every function here draws the state a block of :mod:`moorsolve.physics.catenary` solved, in
the same regime the block chose (the regime tests are the same inequalities), so the profile
and the reported forces come from one solution. Profiles run from the block's lower end:
``s`` unstretched arc length [m], ``x`` horizontal distance [m], ``z`` height [m] relative to
that end, ``tension`` the effective tension [N]. Arc lengths are ``n`` evenly spaced points
plus every breakpoint of the shape (touchdown, lift-off, the surface contact), so a grounded
or floating run is drawn exactly where it lies.

With ``T_v(s)`` the vertical tension, a suspended part follows
``dx/ds = (1 + T/EA) H/T`` and ``dz/ds = (1 + T/EA) T_v/T``, integrated in closed form
(Merkin 1980, sections 2.1 and 2.3). At ``H = 0`` these stay valid (a vertical
line, folded where ``T_v`` changes sign): ``z = (|T_v| - |T_v0|)/w + (T_v0 s + w s^2/2)/EA``.
Another stretch law (``law``, a :class:`~moorsolve.physics.stretch.NumericLaw`; ``ea`` is
then unused) enters through the same integrals as in the blocks: ``(H/w)[Psi(T_v) -
Psi(T_v0)]`` across and ``[E(T) - E(T_0)]/w`` up a catenary
(:mod:`moorsolve.physics.stretch`), the loaded length times the mean strain on the seabed.
"""

from __future__ import annotations

import math

import numpy as np

from .catenary import LegKind
from .segments import descent_force
from .stretch import NumericLaw

__all__ = ["leg_profile", "segment_profile", "single_leg_profile", "sloped_leg_profile",
           "surface_leg_profile", "surface_segment_profile"]


def _arc(L: float, n: int, *breaks) -> np.ndarray:
    """``n`` evenly spaced arc lengths on ``[0, L]`` and the breakpoints inside it."""
    s = _linspace(float(L), n)
    inside = [b for b in breaks if b is not None and np.isfinite(b) and 0.0 < b < L]
    if not inside:
        return s
    # np.unique's sort and mask without its overhead (profiles are drawn per line).
    a = np.concatenate([s, inside])
    a.sort()
    keep = np.empty(a.size, bool)
    keep[0] = True
    np.not_equal(a[1:], a[:-1], out=keep[1:])
    return a[keep]


_RAMPS: dict = {}


def _linspace(L: float, n: int) -> np.ndarray:
    """``np.linspace(0, L, n)``, the same numbers, for a fraction of its call overhead."""
    ramp = _RAMPS.get(n)
    if ramp is None:
        if n < 2:
            return np.linspace(0.0, L, n)
        ramp = np.arange(n, dtype=float)
        ramp.setflags(write=False)
        _RAMPS[n] = ramp       # a read-only array: threads may share it
    s = ramp * (L / (n - 1))
    s[-1] = L
    return s


class _Stretch:
    """The stretch terms of a solved line on numpy arrays: Hooke's (compliance ``1/ea``, 0
    when inextensible) in closed form, or a :class:`~moorsolve.physics.stretch.NumericLaw`'s."""

    def __init__(self, ea, law):
        self.c = 1.0 / ea if ea else 0.0
        self.law = law

    def strain(self, T):
        return float(self.law.strain(T)) if self.law is not None else self.c * T

    def across(self, H, Tv0, Tv, w):
        """Horizontal stretch [m] of a catenary between vertical tensions ``Tv0`` and ``Tv``."""
        if self.law is None:
            return H * (Tv - Tv0) / w * self.c
        return (H / w) * (self.law.horizontal(H, Tv) - self.law.horizontal(H, Tv0))

    def up(self, H, Tv0, Tv, w):
        """Vertical stretch [m] of a catenary between vertical tensions ``Tv0`` and ``Tv``."""
        if self.law is None:
            return (Tv**2 - Tv0**2) / (2 * w) * self.c
        return (self.law.energy(np.hypot(H, Tv)) - self.law.energy(np.hypot(H, Tv0))) / w

    def laid(self, s0, T_start, sg, T_end):
        """Stretch [m] from the lower end to arc length ``sg`` of line lying on the seabed:
        unloaded up to ``s0``, then the tension runs linearly from ``T_start`` to ``T_end``
        at ``sg`` (the strain's mean over a linear run is exact)."""
        loaded = np.maximum(sg - s0, 0.0)
        if self.law is None:
            return loaded * self.c * (T_start + np.maximum(T_end, 0.0)) / 2
        return loaded * self.law.mean(T_start, np.maximum(T_end, 0.0))

    def descent_force(self, H, h, w):
        """:func:`~moorsolve.physics.catenary.descent_force` on floats."""
        if self.law is None:
            return float(descent_force(H, h, w, self.c))
        delta = self.law.descent(H, w * h)
        return -math.sqrt(delta * (delta + 2 * H))


def leg_profile(kind: LegKind, *, H: float, V: float, L: float, w: float,
                ea: float | None, mu: float, X: float, Z: float = 0.0,
                n: int = 101, law: NumericLaw | None = None) -> dict:
    """Points and tension along a solved one-segment leg whose anchor is on a flat seabed
    (or, without ``kind.contact``, whose line touches nothing), from the anchor.

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
        Number of evenly spaced points (the touchdown is added).
    law : NumericLaw, optional
        The line's stretch law when it is not Hooke's (module notes).

    Returns
    -------
    dict of numpy arrays
        ``s``, ``x``, ``z`` (height above the anchor), ``tension`` (module notes).
    """
    st = _Stretch(ea, law)
    if kind.neutral:
        # Straight along the chord when taut; a loose weightless line has no definite
        # shape, so it is drawn along the chord as well.
        s = _arc(L, n)
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    if not kind.contact or VA >= 0:
        return _hanging_profile(_arc(L, n, -VA / w if w else None), H, VA, w, st)
    LB = L - V / w
    s = _arc(L, n, LB)
    grounded = s <= LB
    Tv = np.where(grounded, 0.0, w * (s - LB))
    sg = np.minimum(s, LB)
    # Tension on the seabed: H at touchdown, decaying by friction toward the anchor.
    Tg = np.maximum(H - mu * w * (LB - sg), 0.0) if mu > 0 else np.full_like(s, H)
    if H > 0:
        # Where the seabed tension starts to rise (friction may use it up before the anchor).
        s0 = max(LB - H / (mu * w), 0.0) if mu > 0 else 0.0
        T_anchor = max(H - mu * w * LB, 0.0) if mu > 0 else H
        x_td = sg + st.laid(s0, T_anchor, sg, Tg)
        xs = (H / w) * np.arcsinh(Tv / H) + st.across(H, 0.0, Tv, w)
        zs = (np.hypot(H, Tv) - H) / w + st.up(H, 0.0, Tv, w)
        x_touch = LB + st.laid(s0, T_anchor, LB, H)
        x = np.where(grounded, x_td, x_touch + xs)
        z = np.where(grounded, 0.0, zs)
        tension = np.where(grounded, Tg, np.hypot(H, Tv))
    else:
        # Slack: the hanging part is vertical under the fairlead, the rest lies loose
        # (buckled) between anchor and the fairlead's foot: shown straight along the seabed.
        x = np.where(grounded, np.minimum(sg, X), X)
        z = np.where(grounded, 0.0, Tv / w + st.up(0.0, 0.0, Tv, w))
        tension = np.where(grounded, 0.0, Tv)
    return dict(s=s, x=x, z=z, tension=tension)


def segment_profile(*, H: float, V: float, L: float, w: float, ea: float | None, h: float,
                    X: float, Z: float, n: int = 51, law: NumericLaw | None = None) -> dict:
    """Points and tension along one sinking segment from its lower end, ``h`` above a flat
    seabed, in every regime of :func:`~moorsolve.physics.catenary.lifted_segment_equations`
    (``h`` may be 0), and of a buoyant (drawn as one catenary) or weightless segment.

    ``V`` is the vertical tension at the upper end. The vertical tension is
    ``T_v(s) = V_A + w s`` on a suspended segment; on a two-sided touchdown it runs from
    ``V1`` to 0 on the descent, is 0 on the seabed and rises from 0 to ``V``. ``law``: the
    stretch law when it is not Hooke's.
    """
    st = _Stretch(ea, law)
    if w == 0:
        s = _arc(L, n)
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    V1 = st.descent_force(H, h, w) if w > 0 else -np.inf
    # The block's regime test: suspended when the line leaves its lower end less steeply
    # than one touching the seabed at its vertex, or has no vertex inside (V < 0).
    if VA >= V1 or V < 0:
        return _hanging_profile(_arc(L, n, -VA / w), H, VA, w, st)
    s1 = -V1 / w
    LB = L - s1 - V / w
    s2 = s1 + LB
    s = _arc(L, n, s1, s2)
    Tv = np.where(s < s1, V1 + w * s, np.where(s <= s2, 0.0, w * (s - s2)))
    if H > 0:
        x_desc = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(V1 / H)) + st.across(H, V1, Tv, w)
        x1 = (H / w) * np.arcsinh(-V1 / H) + st.across(H, V1, 0.0, w)
        eps_H = st.strain(H)
        x_ground = x1 + (s - s1) * (1 + eps_H)
        x2 = x1 + LB * (1 + eps_H)
        x_rise = x2 + (H / w) * np.arcsinh(Tv / H) + st.across(H, 0.0, Tv, w)
    else:
        # Slack: straight down, loose along the seabed (drawn straight, piled at the
        # upper end's foot), straight up.
        x_desc = np.zeros_like(s)
        x_ground = np.minimum(s - s1, X)
        x_rise = np.full_like(s, X)
    z_desc = (np.hypot(H, Tv) - np.hypot(H, V1)) / w + st.up(H, V1, Tv, w)
    z_rise = -h + (np.hypot(H, Tv) - H) / w + st.up(H, 0.0, Tv, w)
    x = np.where(s < s1, x_desc, np.where(s <= s2, x_ground, x_rise))
    z = np.where(s < s1, z_desc, np.where(s <= s2, -h, z_rise))
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


def surface_segment_profile(*, H: float, V: float, L: float, w: float, ea: float | None,
                            d: float, X: float, Z: float, n: int = 51,
                            law: NumericLaw | None = None) -> dict:
    """Points and tension along a buoyant segment from its lower end, ``d`` below the
    surface: :func:`segment_profile` of the mirrored line, mirrored back (the profile of
    :func:`~moorsolve.physics.catenary.surface_segment_equations`)."""
    m = segment_profile(H=H, V=-V, L=L, w=-w, ea=ea, h=d, X=X, Z=-Z, n=n, law=law)
    return dict(s=m["s"], x=m["x"], z=-m["z"], tension=m["tension"])


def surface_leg_profile(*, from_fairlead: bool, H: float, VF: float, VA: float, L: float,
                        w: float, ea: float | None, d: float, X: float, Z: float,
                        n: int = 51, law: NumericLaw | None = None) -> dict:
    """The profile of a buoyant leg bounded by the surface, from the anchor.

    ``VF`` and ``VA`` are the leg's end forces (upward force of the fairlead on the line;
    upward pull of the line on the anchor), ``d`` the depth of the end the block started
    from (:func:`~moorsolve.physics.catenary.surface_leg_equations`).
    """
    if not from_fairlead:
        return surface_segment_profile(H=H, V=VF, L=L, w=w, ea=ea, d=d, X=X, Z=Z, n=n, law=law)
    # Drawn from the fairlead (the block's lower end), then turned round. The block's top
    # tension is the anchor's force on the line, -VA.
    back = surface_segment_profile(H=H, V=-VA, L=L, w=w, ea=ea, d=d, X=X, Z=-Z, n=n, law=law)
    return dict(s=(L - back["s"])[::-1], x=(X - back["x"])[::-1], z=(Z + back["z"])[::-1],
                tension=back["tension"][::-1])


def sloped_leg_profile(*, H: float, V: float, L: float, w: float, ea: float | None,
                       mu: float, t: float, X: float, Z: float, n: int = 101,
                       law: NumericLaw | None = None) -> dict:
    """Points and tension along a solved leg on a sloped seabed (see :func:`leg_profile`)."""
    st = _Stretch(ea, law)
    sec = np.sqrt(1 + t * t)
    cos_t, sin_t = 1 / sec, t / sec
    VA = V - w * L
    if VA >= H * t:
        return _hanging_profile(_arc(L, n, -VA / w), H, VA, w, st)
    LB = L - (V - H * t) / w
    s = _arc(L, n, LB)
    k = w * (sin_t + mu * cos_t)
    TA_raw = H * sec - k * LB
    sg = np.minimum(s, LB)
    Tg = np.maximum(TA_raw + k * sg, 0.0)
    # Stretch along the slope: unloaded up to s0 (where the tension has fallen to zero),
    # then the tension runs linearly from max(TA_raw, 0).
    s0 = min(max(-TA_raw / k, 0.0), LB) if k > 0 else 0.0
    stretch = st.laid(s0, max(TA_raw, 0.0), sg, Tg)
    stretch_td = st.laid(s0, max(TA_raw, 0.0), LB, H * sec)
    if H > 0:
        Tv = H * t + w * (s - LB)
        xs = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(t)) + st.across(H, H * t, Tv, w)
        zs = (np.hypot(H, Tv) - H * sec) / w + st.up(H, H * t, Tv, w)
        ground = s <= LB
        x = np.where(ground, (sg + stretch) * cos_t, (LB + stretch_td) * cos_t + xs)
        z = np.where(ground, (sg + stretch) * sin_t, (LB + stretch_td) * sin_t + zs)
        tension = np.where(ground, Tg, np.hypot(H, Tv))
    else:
        # Slack: loose on the slope up to below the fairlead, then hanging straight. On the
        # slope the tension is what the weight along it leaves (0 where friction holds it,
        # growing toward an anchor up a slope the line would slide down).
        foot = X / cos_t
        ground = s <= LB
        along = np.minimum(sg, foot)
        hang = np.maximum(s - LB, 0.0)
        x = np.where(ground, along * cos_t, X)
        z = np.where(ground, along * sin_t, X * t + hang + st.up(0.0, 0.0, w * hang, w))
        tension = np.where(ground, Tg, w * hang)
    return dict(s=s, x=x, z=z, tension=tension)


def _hanging_profile(s, H, VA, w, st) -> dict:
    """Points of a fully suspended elastic catenary from its lower end, where the vertical
    force is ``VA``; ``st`` its stretch (:class:`_Stretch`). ``H = 0`` is a vertical line, which
    folds where the vertical force changes sign (the same formula: ``hypot(0, T_v)`` is
    ``|T_v|``)."""
    Tv = VA + w * s
    if H > 0:
        x = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(VA / H)) + st.across(H, VA, Tv, w)
    else:
        x = np.zeros_like(s)
    z = (np.hypot(H, Tv) - np.hypot(H, VA)) / w + st.up(H, VA, Tv, w)
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


def single_leg_profile(kind: LegKind, *, H: float, VF: float, VA: float, L: float, w: float,
                       ea: float | None, mu: float, X: float, Z: float, anchor_z: float,
                       fairlead_z: float, depth: float, slope: float = 0.0,
                       n: int = 51, law: NumericLaw | None = None) -> dict:
    """The profile of a solved one-segment leg of any :class:`LegKind`, from the anchor.

    ``H``, ``VF`` and ``VA`` are the leg's solved forces (``VA`` the signed upward pull on
    the anchor), ``anchor_z`` and ``fairlead_z`` the ends' heights [m], ``depth`` the water
    depth of a flat seabed (for an anchor above it) and ``slope`` the seabed's rise per metre
    along the leg (for a sloped seabed), ``law`` the stretch law when it is not Hooke's.
    """
    if kind.surface:
        start_z = fairlead_z if kind.from_fairlead else anchor_z
        return surface_leg_profile(from_fairlead=kind.from_fairlead, H=H, VF=VF, VA=VA, L=L,
                                   w=w, ea=ea, d=max(-start_z, 0.0), X=X, Z=Z, n=n, law=law)
    if kind.lifted:
        return segment_profile(H=H, V=VF, L=L, w=w, ea=ea, h=max(anchor_z + depth, 0.0),
                               X=X, Z=Z, n=n, law=law)
    if kind.sloped:
        return sloped_leg_profile(H=H, V=VF, L=L, w=w, ea=ea, mu=mu if kind.friction else 0.0,
                                  t=slope, X=X, Z=Z, n=n, law=law)
    return leg_profile(kind, H=H, V=VF, L=L, w=w, ea=ea, mu=mu if kind.friction else 0.0,
                       X=X, Z=Z, n=n, law=law)


def with_air_part(water: dict, *, H: float, V: float, z_top: float, w_air: float,
                  ea: float | None, L: float, n: int = 21,
                  law: NumericLaw | None = None) -> dict:
    """A profile whose upper end is ``z_top`` above the water: the water part ``water``
    (drawn up to the surface crossing, from the lower end) followed by the part in air, the
    catenary of :func:`~moorsolve.physics.catenary.air_part` under ``w_air``.

    ``V`` is the vertical tension at the upper end [N], ``L`` the line's whole unstretched
    length [m], ``law`` its stretch law when it is not Hooke's.
    """
    from .catenary import air_part
    st = _Stretch(ea, law)
    bound = law.bound if law is not None else None
    part = {k: float(v) for k, v in air_part(H, V, z_top, w_air, st.c, law=bound).items()}
    s_air = np.linspace(0.0, part["length"], n)
    Tv = part["V"] + w_air * s_air
    if H > 0:
        x = ((H / w_air) * (np.arcsinh(Tv / H) - np.arcsinh(part["V"] / H))
             + st.across(H, part["V"], Tv, w_air))
    else:
        x = np.zeros_like(s_air)
    z = (np.hypot(H, Tv) - np.hypot(H, part["V"])) / w_air + st.up(H, part["V"], Tv, w_air)
    x0, z0 = water["x"][-1], water["z"][-1]
    return dict(s=np.concatenate([water["s"], (L - part["length"]) + s_air[1:]]),
                x=np.concatenate([water["x"], x0 + x[1:]]),
                z=np.concatenate([water["z"], z0 + z[1:]]),
                tension=np.concatenate([water["tension"], np.hypot(H, Tv)[1:]]))
