"""Starting states of a line: closed forms of the inextensible catenary.

The solver starts every line from the state of the inextensible line between its ends
(a start with every line slack gives a singular Jacobian, and the
pretensioned rest state keeps a body on the quasi-static branch). These are floats-only
helpers, beside the equations of :mod:`moorsolve.physics.catenary` that they seed.
"""

from __future__ import annotations

import numpy as np

from .catenary import LegKind

__all__ = ["initial_state"]


def _bisect(f, lo, hi, iters=200):
    """Root of an increasing function on [lo, hi] by bisection in log space."""
    flo = f(lo)
    if flo > 0:
        return lo
    for _ in range(iters):
        mid = np.sqrt(lo * hi)
        if f(mid) > 0:
            hi = mid
        else:
            lo = mid
        if hi / lo < 1 + 1e-10:
            break
    return np.sqrt(lo * hi)


def initial_state(kind: LegKind, X: float, Z: float, L: float, w: float,
                  ea: float | None, gap: float = 0.0) -> tuple[float, float]:
    """A starting ``(u, V)`` for one leg from the inextensible closed forms.

    Slack when the line is long enough to hang straight down and reach the anchor along the
    seabed; touchdown when a grounded length remains; suspended otherwise; a straight
    stretched line when the chord exceeds the length. ``gap`` [m] is how far the block's
    lower end is from its boundary: the anchor's height above the seabed (``kind.lifted``)
    or its depth below the surface (``kind.surface`` solved from the anchor). A leg bounded
    by the surface starts from the mirrored sinking line's state.
    """
    if kind.surface:
        plain = LegKind(elastic=kind.elastic, contact=kind.from_fairlead)
        if kind.from_fairlead:
            # Mirrored: a sinking line from the fairlead on the "seabed" up to the anchor.
            u, V = initial_state(plain, X, Z, L, -w, ea)
        else:
            u, V = _lifted_start(plain, X, -Z, L, -w, ea, gap)
        return u, -V
    if kind.lifted:
        return _lifted_start(LegKind(elastic=kind.elastic, contact=False), X, Z, L, w, ea, gap)
    D = float(np.hypot(X, Z))
    if kind.neutral:
        # The tension of a straight line: stretched when the chord exceeds the length,
        # otherwise slack (zero; an inextensible line just reaching starts at D - L).
        if D >= L and ea:
            T = ea * (D / L - 1)
            return T, T * Z / max(D, 1e-12)
        return max(D - L, 0.0), 0.0
    aw = abs(w)
    if D >= L * (1 - 1e-9):
        # Taut: straight stretched line carrying half its weight at each end.
        T = (ea * (D / L - 1) if ea else 0.0) + aw * L
        return T * X / max(D, 1e-12), T * Z / max(D, 1e-12) + w * L / 2
    if kind.contact and X <= L - Z:
        return -w * (L - Z - X), w * Z
    if kind.contact and Z <= 1e-9 * L:
        # The fairlead level with or below the anchor (a sloped seabed): start nearly taut.
        return aw * L, 0.0
    if kind.contact:
        # Touchdown: find H with L_B + suspended span = X, while the suspended part fits in L.
        def span(H):
            Ls = np.sqrt(Z**2 + 2 * Z * H / w)
            return L - Ls + (H / w) * np.arcsinh(w * Ls / H) - X
        H_max = w * (L**2 - Z**2) / (2 * Z)
        if span(H_max) >= 0:
            H = _bisect(span, 1e-9 * w * L, H_max)
            return H, w * np.sqrt(Z**2 + 2 * Z * H / w)
    # Suspended: sqrt(L^2 - Z^2) = 2 (H/|w|) sinh(|w| X / (2 H)) for the chord's sag.
    target = np.sqrt(max(L**2 - Z**2, 0.0))
    if X <= 1e-9 * L:
        # Vertical: folded, the fairlead holding its side of the fold (of the two straight
        # runs, d_F - d_A = Z and d_F + d_A = L for a sinking line).
        return 0.0, w * (L + Z) / 2 if w > 0 else w * (L - Z) / 2

    def chord(H):
        return target - 2 * (H / aw) * np.sinh(min(aw * X / (2 * H), 700))
    H = _bisect(chord, 1e-12 * aw * L + 1e-12, 1e3 * aw * L + aw * X)
    V = (w / 2) * (Z / np.tanh(w * X / (2 * H)) + L)
    return H, V


def _lifted_start(plain: LegKind, X, Z, L, w, ea, h) -> tuple[float, float]:
    """Start of a sinking line whose lower end is ``h`` above its boundary (module notes)."""
    if L >= h + max(h + Z, 0.0) + X:
        # Slack: straight down to the boundary, loose along it, straight up.
        return -w * (L - h - max(h + Z, 0.0) - X), w * max(h + Z, 0.0)
    H, V = initial_state(plain, X, Z, L, w, ea)
    VA = V - w * L
    H = max(H, 0.0)
    if VA < 0 < V and (np.hypot(H, VA) - H) / w > h:
        # The free catenary would pass through the boundary: as if the line ran straight
        # down to it and touched down there.
        return initial_state(LegKind(elastic=plain.elastic, contact=True), X, Z + h, L - h,
                             w, ea)
    return H, V
