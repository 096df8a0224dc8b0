"""The audit's per-line checks in closed form, for one-segment catenaries on a flat seabed.

The profile audit (:mod:`.audit_lines`) samples every line's drawn profile. For the common
line (one segment, Hooke or inextensible, sinking, on a flat seabed or clear of it, in the
water) the same questions have closed answers, asked here of the reported end positions
and end forces alone, all lines at once:

- the end forces lie in the line's vertical plane and pull the ends towards each other;
- the fairlead's vertical force carries the weight of the hanging length (the whole line,
  or all but its grounded length, whose anchor end then takes no vertical force);
- the horizontal tension is the same at both ends, less the seabed friction on the
  grounded length at the anchor;
- integrating the elastic catenary from the lower end's reported force over the line's
  unstretched length reaches the other end's reported position (Irvine's closed forms,
  written out here independently of the solver's blocks);
- a grounded line's lower end is on the seabed, and no point of a hanging line is below it
  (the lowest point of a sinking catenary is its lower end or its vertex).

The tolerances are the profile audit's: lengths to ``tol_rel`` of the line's stretched
length (or the depth), forces to ``FORCE_REL + tol_rel`` of its largest tension. Lines of
any other kind, or a nearly vertical line (whose closed forms lose their digits), are left
to the profile audit: :func:`covers` says which scenes this module audits alone.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .audit_lines import FORCE_REL
from .concurrency import LockedLRU
from .problem import LINE_COLUMNS
from .stretch_params import numeric_law

__all__ = ["covers", "closed_form_findings", "table_ends"]

_COL = {name: k for k, name in enumerate(LINE_COLUMNS)}
_A = [_COL[c] for c in ("ax", "ay", "az")]
_B = [_COL[c] for c in ("bx", "by", "bz")]
_FA = [_COL[c] for c in ("FAx", "FAy", "FAz")]
_FB = [_COL[c] for c in ("FBx", "FBy", "FBz")]
_GROUNDED = _COL["grounded"]

#: Below this ratio of horizontal to vertical tension the closed forms lose digits (the
#: catenary's parameter H/w shrinks to nothing): such a line is left to the profile audit.
_STEEP = 1e-7


def _closed_kind(kind) -> bool:
    block = kind.block
    return (kind.single and not kind.lifted and not block.neutral and not block.sloped
            and not block.surface and not block.air and not block.lifted
            and block.law is None)


def covers(problem, case) -> bool:
    """Whether every line of ``case`` (built as ``problem``) is audited here: one-segment
    sinking Hooke or inextensible lines in the water, on a flat seabed without a grid."""
    key = "closed_form_audit"
    hit = problem.derived.get(key)
    if hit is None:
        hit = problem.derived[key] = all(_closed_kind(k) for k in problem.kinds)
    env = case.environment
    return (hit and env.seabed.bathymetry is None and not env.seabed.sloped
            and bool(case.lines) and _data(case.lines).sinking)


@dataclass(frozen=True)
class _Data:
    """What the checks read of the case's lines, as arrays, made once per lines tuple."""

    names: tuple
    L: np.ndarray        # unstretched length [m]
    w: np.ndarray        # weight in water [N/m]
    c: np.ndarray        # compliance 1/EA [1/N] (0: inextensible)
    sinking: bool        # every line weighs in water and has no stretch law


_DATA = LockedLRU(256)


def _data(lines) -> _Data:
    hit = _DATA.get(id(lines))
    if hit is not None and hit[0] is lines:
        return hit[1]
    types = [line.line_type for line in lines]
    data = _Data(
        names=tuple(line.name for line in lines),
        L=np.array([line.length for line in lines], float),
        w=np.array([lt.weight_in_water for lt in types], float),
        c=np.array([1.0 / lt.ea if lt.ea else 0.0 for lt in types], float),
        sinking=all(lt.weight_in_water > 0 and numeric_law(lt) is None for lt in types))
    _DATA.put(id(lines), (lines, data))
    return data


def table_ends(table: np.ndarray) -> tuple:
    """End A and B positions and the forces the lines exert on them, ``(n, 3)`` each, from
    the report's line table (:data:`~.problem.LINE_COLUMNS`)."""
    return table[:, _A], table[:, _B], table[:, _FA], table[:, _FB]


def _columns(problem) -> tuple:
    """Per line, the table columns of its lower end's position and force and its upper
    end's, side by side (the catenary is integrated from the lower end, as each line's
    block is written), and the seabed friction factor of its block (1 or 0)."""
    hit = problem.derived.get("closed_form_columns")
    if hit is None:
        flipped = np.array([k.flipped for k in problem.kinds], bool)[:, None]
        lower_first = np.array(_A + _B + _FA + _FB)
        upper_first = np.array(_B + _A + _FB + _FA)
        cols = np.where(flipped, upper_first, lower_first)
        rows = np.arange(len(problem.kinds))[:, None]
        friction = np.array([1.0 if k.friction else 0.0 for k in problem.kinds])
        hit = problem.derived["closed_form_columns"] = (rows, cols, friction)
    return hit


def _span(H, V0, s, w, c):
    """Horizontal and vertical reach [m] of an elastic catenary of weight ``w`` [N/m] and
    compliance ``c`` [1/N] over unstretched arc ``s`` from a point where its tension is
    ``(H, V0)`` (H > 0; Irvine 1981, eq. 2.8 with the stretch terms)."""
    a0, a1 = V0 / H, (V0 + w * s) / H
    r0, r1 = np.sqrt(1.0 + a0 * a0), np.sqrt(1.0 + a1 * a1)
    k = H / w
    x = k * (np.arcsinh(a1) - np.arcsinh(a0)) + H * c * s
    # sqrt(1 + a1^2) - sqrt(1 + a0^2) without the cancellation of a taut line's.
    z = k * ((a1 - a0) * (a1 + a0) / (r1 + r0)) + c * s * (V0 + 0.5 * w * s)
    return x, z


def closed_form_findings(problem, case, table, tol_rel: float):
    """``(findings, t_max)``: the per-line findings (one sentence each, prefixed with the
    leg's name) and the largest end tension [N]; findings None where a line is too steep
    for the closed forms (the profile audit must answer)."""
    env = case.environment
    data = _data(case.lines)
    L, w, c = data.L, data.w, data.c
    rows, cols, friction = _columns(problem)
    ends = table[rows, cols]
    lo, up, f_lo, f_up = ends[:, 0:3], ends[:, 3:6], ends[:, 6:9], ends[:, 9:12]
    grounded = table[:, _GROUNDED]
    dx, dy = up[:, 0] - lo[:, 0], up[:, 1] - lo[:, 1]
    X = np.sqrt(dx * dx + dy * dy)
    Z = up[:, 2] - lo[:, 2]
    # (Array methods: numpy's function forms cost more than these checks compute.)
    if not ((X > 0).all() and np.isfinite(table).all()):
        return None, 0.0
    ux, uy = dx / X, dy / X
    H_lo = f_lo[:, 0] * ux + f_lo[:, 1] * uy           # pulls the lower end along +u
    H_up = -(f_up[:, 0] * ux + f_up[:, 1] * uy)        # pulls the upper end along -u
    side = np.maximum(np.abs(f_lo[:, 0] * uy - f_lo[:, 1] * ux),
                      np.abs(f_up[:, 0] * uy - f_up[:, 1] * ux))
    V_lo, V_up = f_lo[:, 2], -f_up[:, 2]
    t_ends = np.maximum(np.sqrt(H_lo * H_lo + V_lo * V_lo), np.sqrt(H_up * H_up + V_up * V_up))
    t_max = np.maximum(t_ends, w * L)
    if not (np.abs(H_up) > _STEEP * t_max).all():
        return None, 0.0
    tol = tol_rel * np.maximum(np.maximum(L * (1.0 + c * t_max), env.depth), 1.0)
    f_tol = (FORCE_REL + tol_rel) * t_max
    on_bed = grounded > 0
    mu = env.seabed.friction * friction
    Lg = np.where(on_bed, grounded, 0.0)
    hanging = L - Lg
    # Friction on the grounded length takes up to mu w Lg of the horizontal tension.
    H_anchor = np.maximum(H_up - mu * w * Lg, 0.0)
    V_start = np.where(on_bed, 0.0, V_lo)
    x_h, z_h = _span(H_up, V_start, hanging, w, c)
    # The grounded run: straight, stretched by its tension (which friction may end).
    grip = mu * w
    run = np.where(grip > 0, np.minimum(Lg, H_up / np.where(grip > 0, grip, 1.0)), Lg)
    x_g = Lg + c * (H_up * run - 0.5 * mu * w * run * run)
    bed = -env.depth                                   # a flat seabed (covers() says so)
    # Lowest point: the lower end, or the vertex of a line leaving it downwards.
    lowest = lo[:, 2]
    if (V_start < 0).any():
        s_v = np.minimum(np.maximum(-V_start / w, 0.0), hanging)
        lowest = lowest + np.minimum(_span(H_up, V_start, s_v, w, c)[1], 0.0)
    below = bed - np.minimum(lowest, up[:, 2])
    unbalanced = V_up - V_start - w * hanging
    miss = np.sqrt((x_h + x_g - X) ** 2 + (z_h - Z) ** 2)
    flags = (
        (side > f_tol, lambda i: f"the end forces leave the line's vertical plane by "
                                 f"{side[i]:.4g} N"),
        ((H_lo < -f_tol) | (H_up < -f_tol),
         lambda i: f"an end force pushes the end away from the line (horizontal tensions "
                   f"{H_lo[i]:.6g} N and {H_up[i]:.6g} N)"),
        (np.abs(unbalanced) > f_tol,
         lambda i: f"the end forces do not carry the line's weight: {unbalanced[i]:.4g} N "
                   f"of vertical force unbalanced (the line hangs {w[i] * hanging[i]:.6g} "
                   "N)"),
        (on_bed & (np.abs(V_lo) > f_tol),
         lambda i: f"a grounded line pulls its lower end with {V_lo[i]:.4g} N vertically"),
        (np.abs(H_lo - H_anchor) > f_tol,
         lambda i: f"the horizontal tension changes along the line by more than the "
                   f"seabed friction holds ({H_up[i]:.6g} N at the upper end, "
                   f"{H_lo[i]:.6g} N at the lower, {H_anchor[i]:.6g} N expected)"),
        ((grounded < -tol) | (grounded > L + tol),
         lambda i: f"the grounded length {grounded[i]:.6g} m is outside the line's "
                   f"{L[i]:.6g} m"),
        (miss > tol,
         lambda i: f"the catenary from the lower end's force reaches "
                   f"({x_h[i] + x_g[i]:.6g}, {z_h[i]:.6g}) m along and up, not the other "
                   f"end at ({X[i]:.6g}, {Z[i]:.6g}) m"),
        (on_bed & (np.abs(lo[:, 2] - bed) > tol),
         lambda i: f"the line is grounded but its lower end is {lo[i, 2] - bed:.3g} m off "
                   "the seabed"),
        (below > tol, lambda i: f"the line passes {below[i]:.3g} m below the seabed"),
    )
    bad = flags[0][0]
    for flag, _ in flags[1:]:
        bad = bad | flag
    out = []
    for i in bad.nonzero()[0] if bad.any() else ():
        out += [f"leg {data.names[i]}: {say(i)}" for flag, say in flags if flag[i]]
    return out, float(t_ends.max())
