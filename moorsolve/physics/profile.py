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
(Merkin 1980, seed 004, sections 2.1 and 2.3). At ``H = 0`` these stay valid (a vertical
line, folded where ``T_v`` changes sign): ``z = (|T_v| - |T_v0|)/w + (T_v0 s + w s^2/2)/EA``.
"""

from __future__ import annotations

import numpy as np

from .catenary import LegKind, descent_force

__all__ = ["leg_profile", "segment_profile", "single_leg_profile", "sloped_leg_profile",
           "surface_leg_profile", "surface_segment_profile"]


def _arc(L: float, n: int, *breaks) -> np.ndarray:
    """``n`` evenly spaced arc lengths on ``[0, L]`` and the breakpoints inside it."""
    s = np.linspace(0.0, L, n)
    inside = [b for b in breaks if b is not None and np.isfinite(b) and 0.0 < b < L]
    return np.unique(np.concatenate([s, inside])) if inside else s


def leg_profile(kind: LegKind, *, H: float, V: float, L: float, w: float,
                ea: float | None, mu: float, X: float, Z: float = 0.0,
                n: int = 101) -> dict:
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

    Returns
    -------
    dict of numpy arrays
        ``s``, ``x``, ``z`` (height above the anchor), ``tension`` (module notes).
    """
    c = 1.0 / ea if ea else 0.0
    if kind.neutral:
        # Straight along the chord when taut; a loose weightless line has no definite
        # shape, so it is drawn along the chord as well.
        s = _arc(L, n)
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    if not kind.contact or VA >= 0:
        return _hanging_profile(_arc(L, n, -VA / w if w else None), H, VA, w, c)
    LB = L - V / w
    s = _arc(L, n, LB)
    grounded = s <= LB
    Tv = np.where(grounded, 0.0, w * (s - LB))
    sg = np.minimum(s, LB)
    # Tension on the seabed: H at touchdown, decaying by friction toward the anchor.
    Tg = np.maximum(H - mu * w * (LB - sg), 0.0) if mu > 0 else np.full_like(s, H)
    if H > 0:
        stretch_g = _grounded_stretch(H, w, mu, LB, sg, c)
        x_td = sg + stretch_g
        xs = (H / w) * np.arcsinh(Tv / H) + H * (s - sg) * c
        zs = (np.hypot(H, Tv) - H) / w + Tv**2 / (2 * w) * c
        x_touch = LB + _grounded_stretch(H, w, mu, LB, np.array([LB]), c)[0]
        x = np.where(grounded, x_td, x_touch + xs)
        z = np.where(grounded, 0.0, zs)
        tension = np.where(grounded, Tg, np.hypot(H, Tv))
    else:
        # Slack: the hanging part is vertical under the fairlead, the rest lies loose
        # (buckled) between anchor and the fairlead's foot: shown straight along the seabed.
        x = np.where(grounded, np.minimum(sg, X), X)
        z = np.where(grounded, 0.0, Tv / w + Tv**2 / (2 * w) * c)
        tension = np.where(grounded, 0.0, Tv)
    return dict(s=s, x=x, z=z, tension=tension)


def _grounded_stretch(H, w, mu, LB, sg, c):
    """Elastic stretch accumulated from the anchor to arc length ``sg`` on the seabed."""
    if c == 0:
        return np.zeros_like(sg)
    if mu <= 0:
        return H * sg * c
    # T(s) = max(H - mu w (LB - s), 0); integrate T/EA from 0 to sg.
    s0 = max(LB - H / (mu * w), 0.0)            # where the tension starts to rise
    a = np.clip(sg, s0, None)
    integral = np.where(sg > s0, (H - mu * w * LB) * (a - s0) + mu * w * (a**2 - s0**2) / 2, 0.0)
    return integral * c


def segment_profile(*, H: float, V: float, L: float, w: float, ea: float | None, h: float,
                    X: float, Z: float, n: int = 51) -> dict:
    """Points and tension along one sinking segment from its lower end, ``h`` above a flat
    seabed, in every regime of :func:`~moorsolve.physics.catenary.lifted_segment_equations`
    (``h`` may be 0), and of a buoyant (drawn as one catenary) or weightless segment.

    ``V`` is the vertical tension at the upper end. The vertical tension is
    ``T_v(s) = V_A + w s`` on a suspended segment; on a two-sided touchdown it runs from
    ``V1`` to 0 on the descent, is 0 on the seabed and rises from 0 to ``V``.
    """
    c = 1.0 / ea if ea else 0.0
    if w == 0:
        s = _arc(L, n)
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    V1 = float(descent_force(H, h, w, c)) if w > 0 else -np.inf
    # The block's regime test: suspended when the line leaves its lower end less steeply
    # than one touching the seabed at its vertex, or has no vertex inside (V < 0).
    if VA >= V1 or V < 0:
        return _hanging_profile(_arc(L, n, -VA / w), H, VA, w, c)
    s1 = -V1 / w
    LB = L - s1 - V / w
    s2 = s1 + LB
    s = _arc(L, n, s1, s2)
    Tv = np.where(s < s1, V1 + w * s, np.where(s <= s2, 0.0, w * (s - s2)))
    if H > 0:
        x_desc = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(V1 / H)) + H * s * c
        x1 = (H / w) * np.arcsinh(-V1 / H) + H * s1 * c
        x_ground = x1 + (s - s1) * (1 + H * c)
        x2 = x1 + LB * (1 + H * c)
        x_rise = x2 + (H / w) * np.arcsinh(Tv / H) + H * (s - s2) * c
    else:
        # Slack: straight down, loose along the seabed (drawn straight, piled at the
        # upper end's foot), straight up.
        x_desc = np.zeros_like(s)
        x_ground = np.minimum(s - s1, X)
        x_rise = np.full_like(s, X)
    z_desc = (np.hypot(H, Tv) - np.hypot(H, V1)) / w + (V1 * s + w * s**2 / 2) * c
    z_rise = -h + (np.hypot(H, Tv) - H) / w + Tv**2 / (2 * w) * c
    x = np.where(s < s1, x_desc, np.where(s <= s2, x_ground, x_rise))
    z = np.where(s < s1, z_desc, np.where(s <= s2, -h, z_rise))
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


def surface_segment_profile(*, H: float, V: float, L: float, w: float, ea: float | None,
                            d: float, X: float, Z: float, n: int = 51) -> dict:
    """Points and tension along a buoyant segment from its lower end, ``d`` below the
    surface: :func:`segment_profile` of the mirrored line, mirrored back (the profile of
    :func:`~moorsolve.physics.catenary.surface_segment_equations`)."""
    m = segment_profile(H=H, V=-V, L=L, w=-w, ea=ea, h=d, X=X, Z=-Z, n=n)
    return dict(s=m["s"], x=m["x"], z=-m["z"], tension=m["tension"])


def surface_leg_profile(*, from_fairlead: bool, H: float, VF: float, VA: float, L: float,
                        w: float, ea: float | None, d: float, X: float, Z: float,
                        n: int = 51) -> dict:
    """The profile of a buoyant leg bounded by the surface, from the anchor.

    ``VF`` and ``VA`` are the leg's end forces (upward force of the fairlead on the line;
    upward pull of the line on the anchor), ``d`` the depth of the end the block started
    from (:func:`~moorsolve.physics.catenary.surface_leg_equations`).
    """
    if not from_fairlead:
        return surface_segment_profile(H=H, V=VF, L=L, w=w, ea=ea, d=d, X=X, Z=Z, n=n)
    # Drawn from the fairlead (the block's lower end), then turned round. The block's top
    # tension is the anchor's force on the line, -VA.
    back = surface_segment_profile(H=H, V=-VA, L=L, w=w, ea=ea, d=d, X=X, Z=-Z, n=n)
    return dict(s=(L - back["s"])[::-1], x=(X - back["x"])[::-1], z=(Z + back["z"])[::-1],
                tension=back["tension"][::-1])


def sloped_leg_profile(*, H: float, V: float, L: float, w: float, ea: float | None,
                       mu: float, t: float, X: float, Z: float, n: int = 101) -> dict:
    """Points and tension along a solved leg on a sloped seabed (see :func:`leg_profile`)."""
    c = 1.0 / ea if ea else 0.0
    sec = np.sqrt(1 + t * t)
    cos_t, sin_t = 1 / sec, t / sec
    VA = V - w * L
    if VA >= H * t:
        return _hanging_profile(_arc(L, n, -VA / w), H, VA, w, c)
    LB = L - (V - H * t) / w
    s = _arc(L, n, LB)
    k = w * (sin_t + mu * cos_t)
    TA_raw = H * sec - k * LB
    sg = np.minimum(s, LB)
    Tg = np.maximum(TA_raw + k * sg, 0.0)
    if c:
        # Cumulative stretch along the slope, by the trapezoid rule on a fine grid.
        fine = np.linspace(0.0, LB, 2001)
        Tf = np.maximum(TA_raw + k * fine, 0.0)
        cum = np.concatenate([[0.0], np.cumsum((Tf[1:] + Tf[:-1]) / 2 * np.diff(fine))]) * c
        stretch = np.interp(sg, fine, cum)
        stretch_td = cum[-1]
    else:
        stretch = np.zeros_like(s)
        stretch_td = 0.0
    if H > 0:
        Tv = H * t + w * (s - LB)
        xs = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(t)) + H * (s - LB) * c
        zs = (np.hypot(H, Tv) - H * sec) / w + (Tv**2 - (H * t) ** 2) / (2 * w) * c
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
        z = np.where(ground, along * sin_t, X * t + hang + w * hang**2 / 2 * c)
        tension = np.where(ground, Tg, w * hang)
    return dict(s=s, x=x, z=z, tension=tension)


def _hanging_profile(s, H, VA, w, c) -> dict:
    """Points of a fully suspended elastic catenary from its lower end, where the vertical
    force is ``VA``; ``c`` is the compliance 1/EA. ``H = 0`` is a vertical line, which
    folds where the vertical force changes sign (the same formula: ``hypot(0, T_v)`` is
    ``|T_v|``)."""
    Tv = VA + w * s
    if H > 0:
        x = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(VA / H)) + H * s * c
    else:
        x = np.zeros_like(s)
    z = (np.hypot(H, Tv) - np.hypot(H, VA)) / w + (VA * s + w * s**2 / 2) * c
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


def single_leg_profile(kind: LegKind, *, H: float, VF: float, VA: float, L: float, w: float,
                       ea: float | None, mu: float, X: float, Z: float, anchor_z: float,
                       fairlead_z: float, depth: float, slope: float = 0.0,
                       n: int = 51) -> dict:
    """The profile of a solved one-segment leg of any :class:`LegKind`, from the anchor.

    ``H``, ``VF`` and ``VA`` are the leg's solved forces (``VA`` the signed upward pull on
    the anchor), ``anchor_z`` and ``fairlead_z`` the ends' heights [m], ``depth`` the water
    depth of a flat seabed (for an anchor above it) and ``slope`` the seabed's rise per metre
    along the leg (for a sloped seabed).
    """
    if kind.surface:
        start_z = fairlead_z if kind.from_fairlead else anchor_z
        return surface_leg_profile(from_fairlead=kind.from_fairlead, H=H, VF=VF, VA=VA, L=L,
                                   w=w, ea=ea, d=max(-start_z, 0.0), X=X, Z=Z, n=n)
    if kind.lifted:
        return segment_profile(H=H, V=VF, L=L, w=w, ea=ea, h=max(anchor_z + depth, 0.0),
                               X=X, Z=Z, n=n)
    if kind.sloped:
        return sloped_leg_profile(H=H, V=VF, L=L, w=w, ea=ea, mu=mu if kind.friction else 0.0,
                                  t=slope, X=X, Z=Z, n=n)
    return leg_profile(kind, H=H, V=VF, L=L, w=w, ea=ea, mu=mu if kind.friction else 0.0,
                       X=X, Z=Z, n=n)


def with_air_part(water: dict, *, H: float, V: float, z_top: float, w_air: float,
                  ea: float | None, L: float, n: int = 21) -> dict:
    """A profile whose upper end is ``z_top`` above the water: the water part ``water``
    (drawn up to the surface crossing, from the lower end) followed by the part in air, the
    catenary of :func:`~moorsolve.physics.catenary.air_part` under ``w_air``.

    ``V`` is the vertical tension at the upper end [N], ``L`` the line's whole unstretched
    length [m].
    """
    from .catenary import air_part
    c = 1.0 / ea if ea else 0.0
    part = {k: float(v) for k, v in air_part(H, V, z_top, w_air, c).items()}
    s_air = np.linspace(0.0, part["length"], n)
    Tv = part["V"] + w_air * s_air
    if H > 0:
        x = (H / w_air) * (np.arcsinh(Tv / H) - np.arcsinh(part["V"] / H)) + H * s_air * c
    else:
        x = np.zeros_like(s_air)
    z = (np.hypot(H, Tv) - np.hypot(H, part["V"])) / w_air + (part["V"] * s_air
                                                              + w_air * s_air**2 / 2) * c
    x0, z0 = water["x"][-1], water["z"][-1]
    return dict(s=np.concatenate([water["s"], (L - part["length"]) + s_air[1:]]),
                x=np.concatenate([water["x"], x0 + x[1:]]),
                z=np.concatenate([water["z"], z0 + z[1:]]),
                tension=np.concatenate([water["tension"], np.hypot(H, Tv)[1:]]))
