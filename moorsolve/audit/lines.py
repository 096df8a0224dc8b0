"""The audit's per-line checks (:mod:`moorsolve.audit`), over all lines at once.

Every line's profile is laid end to end in one set of arrays and each check is one numpy
expression over all profile points (or all steps between them), reduced per line; messages
are written only for the lines that fail. The checks and their tolerances are the audit's
(its module docstring lists them). Plain numpy on the reported profile and end forces and
on the case data: nothing of the solver's.
"""

from __future__ import annotations

import math

import numpy as np

from .line_data import line_data as _line_data
from .line_data import strain as _strain
from .line_data import weights_in_air

__all__ = ["line_findings", "is_lumped", "weights_in_air", "FORCE_REL"]

#: Relative tolerance of force checks, on the largest force in the line or scene.
FORCE_REL = 1e-6


def is_lumped(case, leg_case) -> bool:
    return case.environment.current is not None and any(
        seg.line_type.drag is not None for seg in leg_case.segments)


class _Profiles:
    """All lines' profiles end to end: points, tensions, arc lengths (NaN where a line's
    profile has none), and per line its first and last point."""

    def __init__(self, legs):
        # A lazy profile's dict at once (a Mapping's lookups cost more than the checks).
        profs = [p.as_dict() if hasattr(p, "as_dict") else p
                 for p in (leg.profile for leg in legs)]
        xs = [np.ravel(p["x_m"]) for p in profs]
        self.m = np.array([len(x) for x in xs], int)
        self.o = np.concatenate([[0], np.cumsum(self.m)[:-1]]).astype(int)
        self.last = self.o + self.m - 1
        self.x = np.concatenate(xs).astype(float, copy=False)
        self.y, self.z, self.T = (np.concatenate([np.ravel(p[k]) for p in profs]).astype(
            float, copy=False) for k in ("y_m", "z_m", "tension_N"))
        self.raw_s = [np.asarray(p["s_m"], float) if "s_m" in p else None for p in profs]
        self.has_s = np.array([s is not None and s.size == k
                               for s, k in zip(self.raw_s, self.m)], bool)
        self.s = (np.concatenate([s.ravel() for s in self.raw_s]) if self.has_s.all() else
                  np.concatenate([s.ravel() if ok else np.full(k, np.nan)
                                  for s, ok, k in zip(self.raw_s, self.has_s, self.m)]))
        self.line = np.repeat(np.arange(len(legs)), self.m)
        N = self.x.size
        # Step k joins point k to k + 1; a line's last point starts no step.
        self.nxt = np.minimum(np.arange(N) + 1, max(N - 1, 0))
        self.valid = np.ones(N, bool)
        self.valid[self.last] = False

    def slice(self, i):
        return slice(self.o[i], self.o[i] + self.m[i])


def _local_segments(data, i, at) -> np.ndarray:
    """Segment (of line ``i``) at arc lengths ``at``, as the audit has always found it."""
    return np.clip(np.searchsorted(data.ends[i], at) - 1, 0, data.nseg[i] - 1)


def _step_segments(data, P, mid_of) -> np.ndarray:
    """Flat segment of every step, from the arc length ``mid_of(s0, s1)`` of its middle:
    the line's only segment, or a search of its segment ends."""
    gseg = data.seg_off[P.line].copy()
    for i in np.flatnonzero(data.multi[:len(P.m)] & P.has_s):
        sl = P.slice(i)
        s0, s1 = P.s[sl], P.s[P.nxt[sl]]
        gseg[sl] += _local_segments(data, i, mid_of(s0, s1))
    return gseg


def _legs_arrays(legs):
    """The reported end quantities of every leg, as arrays."""
    cols = ("fairlead_tension_N", "anchor_tension_N", "horizontal_tension_N",
            "fairlead_vertical_N", "anchor_horizontal_N", "anchor_vertical_N",
            "grounded_length_m")
    v = np.array([[getattr(leg, c) for c in cols] for leg in legs], float).reshape(-1, 7)
    anchor = np.array([leg.anchor for leg in legs], float).reshape(-1, 3)
    fairlead = np.array([leg.fairlead for leg in legs], float).reshape(-1, 3)
    return v.T, anchor, fairlead


def line_findings(case, legs, tol_rel: float, boundaries_only: bool) -> list[str]:
    """The per-line findings of the audit for ``legs`` (of ``case``), one sentence each,
    prefixed with the leg's name, in the lines' order."""
    legs = list(legs)
    n = min(len(legs), len(case.lines))
    legs = legs[:n]
    if n == 0:
        return []
    env = case.environment
    data = _line_data(case.lines)
    P = _Profiles(legs)
    if np.any(P.m == 0):
        return [f"leg {leg.name}: the profile has no points"
                for leg, k in zip(legs, P.m) if k == 0]
    (FT, AT, H, FV, AH, AV, grounded), anchor, fairlead = _legs_arrays(legs)
    lumped = (np.zeros(n, bool) if env.current is None else
              np.array([is_lumped(case, lc) for lc in case.lines[:n]], bool))
    L = data.L[:n]
    o, last, m = P.o, P.last, P.m

    absT = np.abs(P.T)
    tmax_prof = np.maximum.reduceat(absT, o) if P.T.size else np.zeros(n)
    t_max = np.fmax(tmax_prof, np.fmax(np.fmax(FT, AT), np.fmax(data.wsum[:n], 1e-300)))
    at_tmax = _strain(data, data.segments,
                      np.concatenate([t_max, np.zeros(len(data.nseg) - n)])[data.seg_line])
    strain_max = np.maximum.reduceat(at_tmax, data.seg_off)[:n]
    size = np.maximum(np.maximum(L * (1.0 + strain_max), env.depth), 1.0)
    tol = tol_rel * size
    finite_pt = np.isfinite(P.x) & np.isfinite(P.y) & np.isfinite(P.z) & np.isfinite(P.T)
    finite = (np.logical_and.reduceat(finite_pt, o) & np.isfinite(t_max)
              & np.isfinite(size) & (m > 0))

    # Ends, continuity and coverage.
    miss_a = np.sqrt((P.x[o] - anchor[:, 0]) ** 2 + (P.y[o] - anchor[:, 1]) ** 2
                     + (P.z[o] - anchor[:, 2]) ** 2)
    miss_f = np.sqrt((P.x[last] - fairlead[:, 0]) ** 2 + (P.y[last] - fairlead[:, 1]) ** 2
                     + (P.z[last] - fairlead[:, 2]) ** 2)
    nx = P.nxt
    dx, dy, dz = P.x[nx] - P.x, P.y[nx] - P.y, P.z[nx] - P.z
    step = np.sqrt(dx * dx + dy * dy + dz * dz)
    ds = P.s[nx] - P.s
    gseg = _step_segments(data, P, lambda s0, s1: s0 + (s1 - s0) / 2)
    t_step = np.maximum(absT[nx], absT)
    allowed = ds * (1.0 + _strain(data, gseg, t_step)) * (1.0 + 1e-9) + tol[P.line]
    excess = np.where(P.valid, step - allowed, -np.inf)
    backward = P.valid & (ds < -tol[P.line])
    broken = ((np.maximum.reduceat(excess, o) > 0) | np.logical_or.reduceat(backward, o))
    uncovered = (np.abs(P.s[last] - L) > tol) | (np.abs(P.s[o]) > tol)

    # The seabed and the surface.
    grid = np.asarray(env.seabed_z(P.x, P.y), float) * np.ones_like(P.z)
    bed = grid
    below = np.maximum.reduceat(bed - P.z, o)
    below_tol, under_plane = tol, np.full(n, -np.inf)
    planes = [leg.seabed_plane for leg in legs]
    if any(p is not None for p in planes):
        # On a grid each line lies on its own plane (solve/lines/bathymetry.py): on the plane to
        # the audit's tolerance, off the grid's surface by at most the seabed tolerance;
        # grounded runs are then judged on the plane.
        has = np.array([p is not None for p in planes])
        coef = np.array([p if p is not None else (0.0, 0.0, 0.0) for p in planes], float)
        z0, gx, gy = coef[P.line, 0], coef[P.line, 1], coef[P.line, 2]
        plane = z0 + gx * P.x + gy * P.y
        under_plane = np.where(has, np.maximum.reduceat(plane - P.z, o), -np.inf)
        below_tol = np.where(has, np.maximum(tol, env.seabed.tolerance), tol)
        bed = np.where(has[P.line], plane, bed)
    ceiling = np.maximum(np.maximum(anchor[:, 2], fairlead[:, 2]), 0.0)
    above = np.maximum.reduceat(P.z, o) - ceiling

    f_tol = FORCE_REL * t_max + tol_rel * t_max
    end_tol = f_tol.copy()
    for i in np.flatnonzero(lumped):
        if P.raw_s[i] is not None:
            end_tol[i] += _element_load(case.lines[i], P.raw_s[i], env)
    bad_ta = np.abs(P.T[o] - AT) > end_tol
    bad_tf = np.abs(P.T[last] - FT) > end_tol

    on_boundary = ~lumped & P.has_s
    none = [[] for _ in range(n)]
    directions, vertical, horizontal = none, none, none
    if np.any(on_boundary):
        # On a boundary: a profile drawn from a solved state puts a grounded or floating run
        # exactly on it (to round-off), so the test is tight: a looser one would count the
        # first metres of a line rising tangentially off the boundary as supported.
        tight_pt = 1e-12 * size[P.line]
        on_bed = P.z - bed <= tight_pt
        on_top = np.abs(P.z) <= tight_pt       # afloat: on the surface, not above
        directions = _end_directions(data, P, on_bed | on_top, tol, anchor, fairlead,
                                     (FT, AT, H, FV, AH, AV), env.water_level)
        vertical, horizontal = _vertical_balance(
            data, P, env, legs, on_bed, on_top, t_max, size, gseg,
            (FT, AT, H, FV, AH, AV, grounded))
    v = dict(tol=tol, lumped=lumped, boundaries_only=boundaries_only, miss_a=miss_a,
             miss_f=miss_f, broken=broken, excess=excess, step=step, ds=ds,
             uncovered=uncovered, L=L, below=below, bed=bed, above=above, ceiling=ceiling,
             below_tol=below_tol, under_plane=under_plane, grid=grid,
             bad_ta=bad_ta, bad_tf=bad_tf, t_max=t_max, size=size, f_tol=f_tol,
             on_boundary=on_boundary, directions=directions, vertical=vertical,
             horizontal=horizontal)
    # Sentences only for the lines some check flags (or that _messages must look at).
    flagged = (~finite | (miss_a > tol) | (miss_f > tol) | (below > below_tol)
               | (under_plane > tol) | (above > tol)
               | bad_ta | bad_tf | (P.has_s & (broken | uncovered))
               | np.array([bool(leg.joints) or bool(d or vt or hz) for leg, d, vt, hz
                           in zip(legs, directions, vertical, horizontal)], bool))
    if env.seabed.sloped:
        flagged |= ~lumped
    out = []
    for i in np.flatnonzero(flagged):
        leg = legs[i]
        found = _messages(i, leg, env, P, v) if finite[i] else [
            "the profile has non-finite points or tensions"]
        out += [f"leg {leg.name}: {p}" for p in found]
    return out


def _messages(i, leg, env, P, v) -> list[str]:
    """The sentences of line ``i`` from the arrays of :func:`line_findings` (``v``)."""
    tol, lumped, boundaries_only = v["tol"][i], v["lumped"][i], v["boundaries_only"]
    consistency, out = [], []
    sl = P.slice(i)
    if v["miss_a"][i] > tol:
        consistency.append(f"the profile starts {v['miss_a'][i]:.3g} m from the anchor")
    if v["miss_f"][i] > tol:
        consistency.append(f"the profile ends {v['miss_f'][i]:.3g} m from the fairlead")
    if P.has_s[i]:
        if v["broken"][i]:
            excess = v["excess"][sl][:-1]
            k = int(np.argmax(excess))
            consistency.append(f"the profile is not continuous: a step of "
                               f"{v['step'][sl][k]:.4g} m between points "
                               f"{v['ds'][sl][k]:.4g} m apart along the line")
        if v["uncovered"][i]:
            s = P.s[sl]
            consistency.append(f"the profile covers {s[0]:.4g} m to {s[-1]:.4g} m of a "
                               f"{v['L'][i]:.4g} m line")
    if v["under_plane"][i] > tol:
        out.append(f"the line passes {v['under_plane'][i]:.3g} m below its seabed plane")
    below, on_grid = v["below"][i], leg.seabed_plane is not None
    if below > v["below_tol"][i]:
        depth = (v["grid"] - P.z)[sl]
        k = int(np.argmax(depth))
        x, y, z = P.x[sl][k], P.y[sl][k], P.z[sl][k]
        out.append(f"the line passes {below:.3g} m below the seabed (at "
                   f"{x:.2f}, {y:.2f}, {z:.2f} m)"
                   + (f"; the bathymetry's tolerance is {env.seabed.tolerance:g} m"
                      if on_grid else ""))
    above, ceiling = v["above"][i], v["ceiling"][i]
    if above > tol:
        out.append(f"the line rises {above:.3g} m above the surface" if ceiling == 0.0 else
                   f"the line rises {above:.3g} m above its highest end, out of the water")
    if v["bad_ta"][i]:
        consistency.append(f"the profile's tension at the anchor, {P.T[P.o[i]]:.6g} N, is "
                           f"not the reported anchor tension {leg.anchor_tension_N:.6g} N")
    if v["bad_tf"][i]:
        consistency.append(f"the profile's tension at the fairlead, {P.T[P.last[i]]:.6g} N, "
                           f"is not the reported fairlead tension "
                           f"{leg.fairlead_tension_N:.6g} N")
    if not lumped and env.seabed.sloped:
        pts = np.column_stack([P.x[sl], P.y[sl], P.z[sl]])
        out += _audit_slack_on_slope(pts, P.T[sl], v["bed"][sl], env.seabed.friction,
                                     v["t_max"][i], v["size"][i])
    if v["on_boundary"][i]:
        consistency += v["directions"][i]
        consistency += v["vertical"][i]
        consistency += v["horizontal"][i]
    out += _joint_findings(leg, env, v["f_tol"][i], tol)
    return out if boundaries_only else consistency + out


def _joint_findings(leg, env, f_tol, tol) -> list[str]:
    out = []
    for j, joint in enumerate(leg.joints):
        z = joint["position_m"][2]
        zb = env.seabed_z(joint["position_m"][0], joint["position_m"][1])
        if joint.get("seabed_reaction_N", 0.0) > f_tol and z - zb > tol:
            out.append(f"joint {j + 1} is held up by a seabed reaction of "
                       f"{joint['seabed_reaction_N']:.4g} N but is {z - zb:.3g} m above the "
                       "seabed (a segment hanging down into a joint is outside the model)")
        if joint.get("surface_reaction_N", 0.0) > f_tol and z < -tol:
            out.append(f"joint {j + 1} is held down by the surface with "
                       f"{joint['surface_reaction_N']:.4g} N but is {-z:.3g} m below it")
        if z > tol:
            clump = joint.get("clump_weight_N", 0.0)
            out.append(f"joint {j + 1} is {z:.3g} m above the still-water level" + (
                " (a buoy breaking the surface is outside the model: its lift is taken as "
                "fully submerged; use a smaller buoy or a buoyant segment)" if clump < 0 else
                " (lifted by the line above it; a joint on the surface is modelled only "
                "under a buoyant segment)"))
    return out


def _element_load(leg_case, s, env) -> float:
    """An upper bound [N] of one element's weight and flow force on a lumped-node line."""
    step = float(np.max(np.diff(s))) if s.size > 1 else 0.0
    current = env.current
    speeds = [current.speed] + [abs(row[1]) for row in (current.profile or ())] if current \
        else [0]
    v = max(abs(float(x)) for x in speeds)
    q = 0.0
    for seg in leg_case.segments:
        lt = seg.line_type
        drag = lt.drag
        flow = (0.5 * env.water_density * (lt.diameter or 0.0) * v * v
                * (drag.normal + drag.tangential + abs(drag.side)) if drag else 0.0)
        q = max(q, abs(lt.weight_in_water) + flow)
    clumps = max([abs(c.weight) for c in leg_case.joint_clumps if c is not None] + [0.0])
    return q * step + clumps


def _end_directions(data, P, on_boundary, tol, anchor, fairlead, ends,
                    level=0.0) -> list[list[str]]:
    """The end forces point along the profile where the line leaves an end through water:
    per line, the sentences of the ends that do not (``level``: the still water's height
    above the datum [m])."""
    FT, AT, H, FV, AH, AV = ends
    n = len(P.m)
    out = [[] for _ in range(n)]
    dxy = fairlead[:, :2] - anchor[:, :2]
    X = np.hypot(dxy[:, 0], dxy[:, 1])
    far = X > 1e-12
    ux = np.where(far, dxy[:, 0] / np.where(far, X, 1.0), 1.0)
    uy = np.where(far, dxy[:, 1] / np.where(far, X, 1.0), 0.0)
    two = P.m >= 2
    if not np.any(two):
        return out
    # Both ends in one pass: rows 0..n-1 the fairleads, n..2n-1 the anchors.
    lines = np.concatenate([np.arange(n), np.arange(n)])
    two2 = np.concatenate([two, two])
    i = np.where(two2, np.concatenate([P.last, P.o]), P.o[lines])
    j = np.where(two2, np.concatenate([P.last - 1, P.o + 1]), P.o[lines])
    k = np.where(two2, np.concatenate([P.last - 1, P.o]), P.o[lines])
    force = np.column_stack([np.concatenate([-H * ux, AH * ux]),
                             np.concatenate([-H * uy, AH * uy]), np.concatenate([-FV, AV])])
    T = np.concatenate([FT, AT])
    cx, cy, cz = P.x[j] - P.x[i], P.y[j] - P.y[i], P.z[j] - P.z[i]
    length = np.sqrt(cx * cx + cy * cy + cz * cz)
    is_anchor = np.arange(2 * n) >= n
    skip = ((T <= 0) | (length <= tol[lines]) | (on_boundary[i] & on_boundary[j]) | ~two2
            | ~P.has_s[lines] | (is_anchor & (AV[lines] == 0.0) & on_boundary[i]))
    norm = np.maximum(np.sqrt(np.sum(force * force, axis=1)), 1e-300)
    dot = (force[:, 0] * cx + force[:, 1] * cy + force[:, 2] * cz) / norm
    cosine = np.minimum(np.maximum(dot / np.where(skip, 1.0, length), -1.0), 1.0)
    angle = np.arccos(cosine)
    seg = np.zeros(2 * n, int)
    for row in np.nonzero(data.multi[lines] & ~skip)[0]:
        li = lines[row]
        seg[row] = min(np.searchsorted(data.ends[li], P.s[k[row]] + 1e-12) - 1,
                       data.nseg[li] - 1)
    # A negative index is the line's last segment, as indexing a per-line array gives.
    seg = np.where(seg < 0, seg + data.nseg[lines], seg)
    gseg = data.seg_off[lines] + seg
    above = (P.z[i] + P.z[j]) / 2 > level
    w = np.abs(np.where(above, data.in_air[gseg], data.weight[gseg]))
    ds = np.abs(P.s[j] - P.s[i])
    skip |= T <= w * ds
    turning = w * ds / np.where(skip, 1.0, T - w * ds) + 1e-6
    for row in np.nonzero(~skip & (angle > turning))[0]:
        name = "anchor" if row >= n else "fairlead"
        out[lines[row]].append(f"the force at the {name} points "
                               f"{math.degrees(angle[row]):.3g} deg away from the line's "
                               f"direction there (at most {math.degrees(turning[row]):.2g} deg "
                               "over one profile step)")
    return out


def _vertical_balance(data, P, env, legs, on_bed, on_top, t_max, size, gseg_cont, ends):
    """The end forces carry the weight the seabed and the surface do not support; a
    frictionless line keeps its horizontal tension. Per line, the sentences of each.

    A line leaving a boundary tangentially rises ``w s^2 / (2 T)`` in ``s``: a profile point
    within ``s = sqrt(2 T tight / w)`` of the lift-off looks supported, so each end of a
    supported run may shift the weight found by ``sqrt(2 T tight w)``.
    """
    FT, AT, H, FV, AH, AV, grounded = ends
    n = len(P.m)
    nx, valid = P.nxt, P.valid
    # The segment of each step from its middle, found as this check always has.
    gseg = (gseg_cont if not np.any(data.multi[:n])
            else _step_segments(data, P, lambda s0, s1: (s1 + s0) / 2))
    # Above the still water (water_level above the datum) a line weighs its weight in
    # air, where the case gives it.
    w = np.where((P.z[nx] + P.z) / 2 > env.water_level, data.in_air[gseg], data.weight[gseg])
    ds = P.s[nx] - P.s
    supported = (on_bed[nx] & on_bed) | (on_top[nx] & on_top)
    hanging = np.add.reduceat(np.where(valid & ~supported, w * ds, 0.0), P.o)
    # Runs of support: a change between two steps of the same line.
    pair = valid & valid[nx]
    changes = np.add.reduceat((pair & (supported != supported[nx])).astype(int), P.o)
    reactions = np.array([sum(j.get("seabed_reaction_N", 0.0) - j.get("surface_reaction_N", 0.0)
                              for j in leg.joints) for leg in legs], float)
    # The upward pull on the anchor, signed: the result reports 0 for a line lying there
    # and for an anchor pulled down; the downward part comes from the anchor tension and the
    # profile's direction there.
    two = P.m > 1
    falls = two & (P.z[np.where(two, P.o + 1, P.o)] < P.z[P.o])
    pulled_down = (AV == 0.0) & (AT > AH) & falls
    pull = np.where(pulled_down, -np.sqrt(np.maximum((AT - AH) * (AT + AH), 0.0)), AV)
    unbalanced = FV - pull - hanging - data.clumps[:n] + reactions
    scale = np.maximum(np.maximum(t_max, data.wsum_ends[:n]), 1e-300)
    tight = 1e-12 * size
    allowance = (2 + changes) * np.sqrt(2.0 * t_max * tight * data.wmax[:n])
    sloped_grounded = env.seabed.sloped & (grounded > 0)
    frictionless = (env.seabed.friction == 0.0) | (grounded == 0.0)
    vertical, horizontal = [[] for _ in range(n)], [[] for _ in range(n)]
    # On a slope the reaction has a horizontal part: a grounded line is not checked here.
    for i in np.flatnonzero(~sloped_grounded & (np.abs(unbalanced) > 1e-6 * scale + allowance)):
        vertical[i].append(f"the end forces do not carry the line's weight: "
                           f"{unbalanced[i]:.4g} N of vertical force unbalanced (the line "
                           f"hangs {hanging[i]:.6g} N)")
    for i in np.flatnonzero(~sloped_grounded & frictionless
                            & (np.abs(H - AH) > 1e-6 * scale)):
        horizontal[i].append(f"the horizontal tension changes along a line with nothing to "
                             f"hold it ({H[i]:.6g} N at the fairlead, {AH[i]:.6g} N at the "
                             "anchor)")
    return vertical, horizontal


def _audit_slack_on_slope(pts, T, bed, mu, t_max, size) -> list[str]:
    """Line lying on a slope without tension stays only where friction holds it.

    A grounded run whose tension is zero (a loose, slack line; or the far end of a run whose
    tension friction and the slope used up) is held by static friction alone: it slides
    unless the slope along it is at most the friction coefficient. The model keeps loose
    line where it lies, so a run steeper than that is not an equilibrium.
    """
    on = pts[:, 2] - bed <= 1e-9 * size
    loose = on & (np.abs(T) <= 1e-9 * t_max)
    both = loose[1:] & loose[:-1]
    run = np.linalg.norm(np.diff(pts[:, :2], axis=0), axis=1)
    rise = np.abs(np.diff(pts[:, 2]))
    steep = both & (run > 1e-12 * size) & (rise > (mu + 1e-9) * run)
    if not np.any(steep):
        return []
    k = int(np.argmax(steep))
    return [f"{float(np.sum(np.hypot(run, rise)[steep])):.3g} m of line lies without tension "
            f"on a seabed sloping {rise[k] / run[k]:.3g} along it, steeper than the friction "
            f"coefficient {mu:g} holds: it would slide (loose line on a slope is outside the "
            "model; give the seabed friction, or a shorter or a lumped-node line)"]
