"""The profiles of a result's one-segment lines, drawn together.

Most lines of a mooring are one segment of Hooke's law lying on a flat seabed at the anchor
and rising to the fairlead. :func:`~moorsolve.physics.profile.leg_profile` draws such a line
with some thirty numpy calls on 51 points; here all such lines of one result are drawn in one
pass over a ``lines x points`` array, with the same expressions in the same order (so the same
numbers: elementwise arithmetic does not depend on the array's shape); lines hanging clear
of the seabed at the anchor likewise. A line outside those shapes, or whose touchdown falls
on a grid point, is drawn by its own function.
"""

from __future__ import annotations

import math
import threading

import numpy as np

__all__ = ["ProfileBatch"]


class ProfileBatch:
    """Lines registered by :meth:`add`, drawn together when the first of them is read."""

    def __init__(self, n: int):
        self._n = n
        self._pending: list = []
        self._lock = threading.Lock()

    def add(self, params: dict, fallback, finish):
        """Register a line; returns its draw function (for a LazyProfile).

        ``params``: ``H``, ``V``, ``L``, ``w``, ``ea``, ``mu`` of
        :func:`~moorsolve.physics.profile.leg_profile`, and ``lower``, ``upper``,
        ``flipped``, ``length`` of its orientation in 3-D, ``contact`` (the seabed
        holds it); ``fallback()`` draws it alone;
        ``finish(profile)`` completes the oriented profile (a sealed line's wall tension).
        """
        slot: dict = {}
        with self._lock:
            self._pending.append((slot, params, fallback, finish))

        def draw() -> dict:
            with self._lock:
                if self._pending:
                    pending, self._pending = self._pending, []
                    _draw_all(pending, self._n)
            return slot["profile"]

        return draw


def _group(p) -> str | None:
    """Which pass draws a line: ``"grounded"`` (lying on the seabed at the anchor),
    ``"hanging"`` (pulling its lower end up: no breakpoint inside), or None (alone)."""
    H, V, L, w = p["H"], p["V"], p["L"], p["w"]
    if not (H > 0 and w > 0 and L > 0 and math.isfinite(H) and math.isfinite(V)):
        return None
    VA = V - w * L
    if VA >= 0:
        return "hanging"
    return "grounded" if p["contact"] and 0.0 < L - V / w < L else None


def _draw_all(pending, n: int) -> None:
    groups: dict = {"grounded": [], "hanging": []}
    for item in pending:
        group = _group(item[1])
        if group is not None:
            groups[group].append(item)
    for group, rows in groups.items():
        if not rows:
            continue
        col = {k: np.array([item[1][k] for item in rows], float)[:, None]
               for k in ("H", "V", "L", "w", "mu")}
        c = np.array([1.0 / item[1]["ea"] if item[1]["ea"] else 0.0 for item in rows],
                     float)[:, None]
        if group == "grounded":
            s, ok = _arcs(col["L"], col["V"], col["w"], n)
            planar = _grounded(s, col["H"], col["V"], col["L"], col["w"], col["mu"], c)
        else:
            s, ok = _grid(col["L"], n), np.ones(len(rows), bool)
            planar = _hanging(s, col["H"], col["V"] - col["w"] * col["L"], col["w"], c)
        for r, profile in enumerate(_orient(planar, [item[1] for item in rows])):
            slot, _, _, finish = rows[r]
            if ok[r]:
                finish(profile)
                slot["profile"] = profile
    for slot, _, fallback, _ in pending:
        if "profile" not in slot:
            slot["profile"] = fallback()


def _grid(L, n):
    """Per row: ``n`` evenly spaced arc lengths on ``[0, L]``, as ``np.linspace``."""
    grid = np.arange(n, dtype=float) * (L / (n - 1))
    grid[:, -1] = L[:, 0]
    return grid


def _hanging(s, H, VA, w, c) -> dict:
    """:func:`~moorsolve.physics.profile._hanging_profile` on rows, ``H > 0`` (Hooke's
    stretch, compliance ``c``)."""
    Tv = VA + w * s
    x = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(VA / H)) + H * (Tv - VA) / w * c
    z = (np.hypot(H, Tv) - np.hypot(H, VA)) / w + (Tv ** 2 - VA ** 2) / (2 * w) * c
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


def _arcs(L, V, w, n):
    """Per row: ``n`` evenly spaced arc lengths on ``[0, L]`` and the touchdown inside,
    as :func:`~moorsolve.physics.profile._arc` makes them; whether the touchdown is off
    the grid (a row where it is not is drawn alone)."""
    grid = _grid(L, n)
    LB = L - V / w
    ok = ~np.any(grid == LB, axis=1)
    s = np.concatenate([grid, LB], axis=1)
    s.sort(axis=1)
    return s, ok


def _grounded(s, H, V, L, w, mu, c) -> dict:
    """:func:`~moorsolve.physics.profile.leg_profile` of a grounded line, ``H > 0``, on
    rows (Hooke's stretch, compliance ``c``)."""
    LB = L - V / w
    grounded = s <= LB
    Tv = np.where(grounded, 0.0, w * (s - LB))
    sg = np.minimum(s, LB)
    rough = mu > 0
    safe_mu = np.where(rough, mu, 1.0)
    Tg = np.where(rough, np.maximum(H - mu * w * (LB - sg), 0.0), H * np.ones_like(s))
    s0 = np.where(rough, np.maximum(LB - H / (safe_mu * w), 0.0), 0.0)
    T_anchor = np.where(rough, np.maximum(H - mu * w * LB, 0.0), H)
    x_td = sg + np.maximum(sg - s0, 0.0) * c * (T_anchor + np.maximum(Tg, 0.0)) / 2
    xs = (H / w) * np.arcsinh(Tv / H) + H * (Tv - 0.0) / w * c
    zs = (np.hypot(H, Tv) - H) / w + (Tv ** 2 - 0.0 ** 2) / (2 * w) * c
    x_touch = LB + np.maximum(LB - s0, 0.0) * c * (T_anchor + np.maximum(H, 0.0)) / 2
    return dict(s=s, x=np.where(grounded, x_td, x_touch + xs),
                z=np.where(grounded, 0.0, zs), tension=np.where(grounded, Tg, np.hypot(H, Tv)))


def _orient(planar: dict, params: list) -> list:
    """As :func:`~moorsolve.solve.result.outcome._orient`, on rows: each planar profile in 3-D
    from end A."""
    lower = np.array([p["lower"] for p in params], float)
    units = []
    for p in params:
        lo, up = p["lower"], p["upper"]
        X = math.hypot(up[0] - lo[0], up[1] - lo[1])
        units.append(((up[0] - lo[0]) / X, (up[1] - lo[1]) / X) if X > 1e-12 else (1.0, 0.0))
    u = np.array(units, float)
    x = planar["x"]
    cols = {"s_m": planar["s"], "x_m": lower[:, :1] + u[:, :1] * x,
            "y_m": lower[:, 1:2] + u[:, 1:2] * x, "z_m": lower[:, 2:3] + planar["z"],
            "tension_N": planar["tension"]}
    out = []
    for r, p in enumerate(params):
        if p["flipped"]:
            profile = {k: v[r, ::-1].copy() for k, v in cols.items()}
            profile["s_m"] = p["length"] - profile["s_m"]
        else:
            profile = {k: v[r] for k, v in cols.items()}
        out.append(profile)
    return out
