"""Each line's part of a :class:`~.classes.Result`: its end forces, state, segments or nodes
and profile (drawn with the closed forms of :mod:`moorsolve.physics.catenary` in the line's
vertical plane: multi-segment lines joint by joint, lumped-node lines through their nodes),
and the notes a line earns.
"""

from __future__ import annotations

import collections
import math

import numpy as np

from ...physics.air import air_line_profile
from ...physics.catenary import LegKind, air_part
from ...physics.profile import (leg_profile, segment_profile, sloped_leg_profile,
                               surface_leg_profile, surface_segment_profile, with_air_part)
from ...physics.wall_tension import wall_tension
from ...audit import AuditFailure, air_hint
from .classes import LazyProfile, LegResult
from ..lines.stretch_params import numeric_law

_PROFILE_POINTS = 51


def line_notes(case, problem, legs) -> list:
    # A line through the seabed or out of the water, a joint held off its boundary: the
    # audit's findings (moorsolve.audit), errors of a certified point and reasons of
    # one that is not; not notes.
    notes = []
    quiet = problem.derived.get("anchored_one_segment_lines")
    if quiet is None:
        quiet = problem.derived["anchored_one_segment_lines"] = all(
            kind.single and kind.contact for kind in problem.kinds)
    if quiet:
        return notes             # nothing to say of anchored one-segment lines
    for lr, kind in zip(legs, problem.kinds):
        if kind.discrete and np.any(lr.profile["tension_N"][1:-1] < 0):
            notes.append(f"leg {lr.name}: some elements of the discretised line are in "
                         "compression (a loose line; its lumped-node shape is not unique)")
    return notes


def _ends(row: dict) -> tuple:
    """End A and B positions and the forces on them, from a report row."""
    a = (row["ax"], row["ay"], row["az"])
    b = (row["bx"], row["by"], row["bz"])
    fa = (row["FAx"], row["FAy"], row["FAz"])
    fb = (row["FBx"], row["FBy"], row["FBz"])
    return a, b, fa, fb


def _end_fields(name, a, b, fa, fb) -> dict:
    """The CONTRACT fields of a line's two ends from the forces on them."""
    return dict(
        name=name,
        fairlead_tension_N=math.hypot(*fb),
        horizontal_tension_N=float(math.hypot(fb[0], fb[1])),
        fairlead_vertical_N=float(-fb[2]),
        anchor_tension_N=math.hypot(*fa),
        anchor_horizontal_N=float(math.hypot(fa[0], fa[1])),
        anchor_vertical_N=float(fa[2]),
        # The ends are tuples of floats already (:func:`_ends` reads a row of floats).
        anchor=a, fairlead=b, fairlead_force=fb, anchor_force=fa)


def _orient(profile: dict, lower, upper, flipped: bool, length: float) -> dict:
    """A planar profile (x along the lower-to-upper direction, z up from the lower end) in
    3-D, running from end A, with ``s_m`` the unstretched arc length from end A."""
    X = math.hypot(upper[0] - lower[0], upper[1] - lower[1])
    ux, uy = ((upper[0] - lower[0]) / X, (upper[1] - lower[1]) / X) if X > 1e-12 else (1.0, 0.0)
    out = {"s_m": np.asarray(profile["s"], float),
           "x_m": lower[0] + ux * profile["x"], "y_m": lower[1] + uy * profile["x"],
           "z_m": lower[2] + profile["z"], "tension_N": profile["tension"]}
    if flipped:
        out = {k: v[::-1].copy() for k, v in out.items()}
        out["s_m"] = length - out["s_m"]
    return out


def _add_wall_tension(profile: dict, line, env) -> None:
    lt = line.line_type
    if lt.sealed and lt.diameter:
        depth_below = np.maximum(env.water_level - profile["z_m"], 0.0)
        tw = wall_tension(profile["tension_N"], depth_below, lt.diameter, env.water_density,
                          env.gravity)
        profile["wall_tension_N"] = tw
        profile["compression"] = bool(np.any(tw < 0))


def _weightless_slack(line, row, u, stiffness) -> bool:
    """Whether a weightless line is slack: its opening (stretched length minus chord)
    exceeds its tension as a length at the contact stiffness (the side of its
    complementarity that holds, :mod:`moorsolve.physics.contact`)."""
    lt = line.line_type
    law = numeric_law(lt)
    if law is not None:
        stretched = line.length * (1 + float(law.strain(max(u, 0.0))))
    else:
        stretched = line.length * (1 + u / lt.ea) if lt.ea else line.length
    return stretched - math.hypot(row["X"], row["Z"]) > u / stiffness


def single_result(case, line, kind, row, u, stiffness, cert, batch=None,
                   plane=None) -> LegResult:
    env = case.environment
    lt = line.line_type
    if kind.neutral and _weightless_slack(line, row, u, stiffness):
        # Slack: it carries nothing (the solution's tension is below 1e-15 N).
        row = dict(row, **{k: 0.0 for k in ("H", "VF", "HA", "VA", "FAx", "FAy", "FAz",
                                            "FBx", "FBy", "FBz", "fx", "fy")})
        u = -1.0
    a, b, fa, fb = _ends(row)
    lower, upper = (b, a) if kind.flipped else (a, b)
    H, VF, HA, VA = row["H"], row["VF"], row["HA"], row["VA"]
    grounded, susp_x, X, Z = row["grounded"], row["suspended_x"], row["X"], row["Z"]
    ux, uy = ((upper[0] - lower[0]) / X, (upper[1] - lower[1]) / X) if X > 1e-9 else (1.0, 0.0)
    mu = env.seabed.friction if kind.friction else 0.0
    gx, gy = env.seabed.gradient if plane is None else plane
    slope = gx * ux + gy * uy if kind.sloped else 0.0
    floating = row["floating"]

    def draw() -> dict:
        length, Vw, Xw, Zw = line.length, VF, X, Z
        law = numeric_law(lt)
        if kind.block.air_ends:
            prof = air_line_profile(H=H, V=VF, z_top=upper[2], L=line.length,
                                    w=lt.weight_in_water, w_air=lt.weight_in_air, ea=lt.ea,
                                    n=_PROFILE_POINTS, law=law)
            prof["z"] = prof["z"] - lower[2]          # _orient takes heights above end A
            profile = _orient(prof, lower, upper, kind.flipped, line.length)
            _add_wall_tension(profile, line, env)
            return profile
        if kind.block.air:
            # The water part up to the surface crossing; the part in air is added below.
            part = {k: float(v) for k, v in air_part(
                H, VF, upper[2], lt.weight_in_air, 1.0 / lt.ea if lt.ea else 0.0,
                law=law.bound if law is not None else None).items()}
            length, Vw, Xw, Zw = (line.length - part["length"], part["V"], X - part["x"],
                                  -lower[2])
        if kind.lifted:
            h = max(lower[2] - env.seabed_z(lower[0], lower[1]), 0.0)
            prof = segment_profile(H=H, V=Vw, L=length, w=lt.weight_in_water, ea=lt.ea, h=h,
                                   X=Xw, Z=Zw, n=_PROFILE_POINTS, law=law)
        elif kind.surface:
            start_z = upper[2] if kind.block.from_fairlead else lower[2]
            prof = surface_leg_profile(from_fairlead=kind.block.from_fairlead, H=H, VF=Vw,
                                       VA=VA, L=length, w=lt.weight_in_water, ea=lt.ea,
                                       d=max(-start_z, 0.0), X=Xw, Z=Zw, n=_PROFILE_POINTS,
                                       law=law)
        elif kind.sloped:
            prof = sloped_leg_profile(H=H, V=Vw, L=length, w=lt.weight_in_water, ea=lt.ea,
                                      mu=mu, t=slope, X=Xw, Z=Zw, n=_PROFILE_POINTS, law=law)
        else:
            prof = leg_profile(kind.block, H=H, V=Vw, L=length, w=lt.weight_in_water,
                               ea=lt.ea, mu=mu, X=Xw, Z=Zw, n=_PROFILE_POINTS, law=law)
        if kind.block.air:
            prof = with_air_part(prof, H=H, V=VF, z_top=upper[2], w_air=lt.weight_in_air,
                                 ea=lt.ea, L=line.length, law=law)
        profile = _orient(prof, lower, upper, kind.flipped, line.length)
        _add_wall_tension(profile, line, env)
        return profile

    # Drawn when first read (a floating line's touch-up point reads it now); a Hooke line
    # on a flat seabed or clear of it with the result's others like it, at once.
    block = kind.block
    if (batch is not None and not (block.neutral or block.air or kind.lifted or kind.surface
                                   or kind.sloped) and numeric_law(lt) is None):
        drawing = batch.add(
            dict(H=H, V=VF, L=line.length, w=lt.weight_in_water, ea=lt.ea, mu=mu,
                 contact=block.contact, lower=lower, upper=upper, flipped=kind.flipped,
                 length=line.length),
            draw, lambda prof: _add_wall_tension(prof, line, env))
    else:
        drawing = draw
    profile = LazyProfile(_ends_checked(drawing, line, case, a, b, fa, fb, cert))
    fields = _end_fields(line.name, a, b, fa, fb)
    fields.update(floating_length_m=floating,
                  touchup_from_anchor_m=_first_at_surface(profile, a) if floating > 0 else 0.0)
    anchored = kind.block.contact
    td = max(X - susp_x, 0.0) if (anchored and grounded > 0) else 0.0
    lower_pull = fb if kind.flipped else fa
    # A weightless line (a hawser) has no anchor to lift.
    uplift = lower_pull[2] > 0 and not (kind.contact and grounded > 0) and not kind.neutral
    if kind.sloped:
        # On a slope the anchor is pulled along it: the upward part is reported (0 when
        # it pulls down-slope), the tension is the whole pull.
        fields["anchor_vertical_N"] = max(fields["anchor_vertical_N"], 0.0)
    return LegResult(
        grounded_length_m=grounded, touchdown_from_anchor_m=td,
        # Slack: no horizontal tension and line loose on the seabed (or, for a weightless
        # line, longer than its chord); a vertical taut leg is not slack.
        uplift=bool(uplift), slack=bool(u < 0.0 or (H == 0.0 and grounded > 0.0)),
        uplift_angle_deg=math.degrees(math.atan2(VA, HA)) if uplift else 0.0,
        fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
        touchdown_point=((lower[0] + ux * td, lower[1] + uy * td, lower[2] + slope * td)
                         if (anchored and grounded > 0) else None),
        mbl_N=lt.mbl, profile=profile, **fields)


#: A line's name and end positions, as :func:`~.audit.air_hint` reads a leg result.
_Ends = collections.namedtuple("_Ends", "name anchor fairlead")


def _ends_checked(draw, line, case, a, b, fa, fb, cert):
    """``draw`` made to check what it drew: the profile runs from end A to end B with their
    reported tensions, or :class:`~moorsolve.audit.AuditFailure` says it does not (where
    the audit ran in closed form, :mod:`moorsolve.audit.closed_form`, this is the only look
    at a profile)."""
    def checked() -> dict:
        prof = draw()
        ta, tb = math.hypot(*fa), math.hypot(*fb)
        lt = line.line_type
        f_tol = 2e-6 * max(ta, tb, abs(lt.weight_in_water) * line.length, 1.0)
        stretch = max(ta, tb) / lt.ea if lt.ea else 0.0
        tol = 1e-6 * max(line.length * (1.0 + stretch), case.environment.depth, 1.0)
        x, y, z, t = (np.asarray(prof[k], float) for k in ("x_m", "y_m", "z_m", "tension_N"))
        misses = [("starts", math.dist((x[0], y[0], z[0]), a), "from end A"),
                  ("ends", math.dist((x[-1], y[-1], z[-1]), b), "from end B")]
        found = [f"the profile {what} {d:.3g} m {where}" for what, d, where in misses
                 if not d <= tol]
        found += [f"the profile's tension at end {end}, {got:.6g} N, is not the reported "
                  f"{want:.6g} N" for end, got, want in (("A", t[0], ta), ("B", t[-1], tb))
                  if not abs(got - want) <= f_tol]
        if found:
            raise AuditFailure(
                f"the solution certified but leg {line.name}'s profile drawn from it fails "
                "the independent audit: " + "; ".join(found)
                + air_hint(case, [_Ends(line.name, a, b)]), residual_N=cert.force_N,
                residual_Nm=cert.moment_Nm, status=cert.status, iterations=cert.iterations,
                certified=True)
        return prof
    return checked


def multi_result(case, line, kind, row, rows, u) -> LegResult:
    """A multi-segment line: CONTRACT fields, joints, segments, one profile."""
    env = case.environment
    block = kind.block
    a, b, fa, fb = _ends(row)
    lower, upper = (b, a) if kind.flipped else (a, b)
    segments_lf = line.segments[::-1] if kind.flipped else line.segments
    clumps_lf = tuple(reversed(line.joint_clumps)) if kind.flipped else line.joint_clumps
    H, VF, HA, VA, grounded = row["H"], row["VF"], row["HA"], row["VA"], row["grounded"]
    X = row["X"]
    ux, uy = ((upper[0] - lower[0]) / X, (upper[1] - lower[1]) / X) if X > 1e-12 else (1.0, 0.0)
    parts = {k: [] for k in ("s", "x", "z", "tension")}
    arc_below = 0.0
    segments, joints = [], []
    for k, (seg, sk, r) in enumerate(zip(segments_lf, block.segments, rows)):
        lt = seg.line_type
        law = numeric_law(lt)
        if sk.friction:
            prof = leg_profile(LegKind(elastic=sk.elastic, contact=True, friction=True),
                               H=r["H"], V=r["VF"], L=seg.length, w=lt.weight_in_water,
                               ea=lt.ea, mu=env.seabed.friction, X=r["X"], Z=r["Z"],
                               n=_PROFILE_POINTS, law=law)
        elif k == len(rows) - 1 and block.reversed_top:
            # Solved from the top end: draw it from there, then turn it round.
            if sk.block == "floating":
                back = surface_segment_profile(
                    H=r["H"], V=-r["VA"], L=seg.length, w=lt.weight_in_water, ea=lt.ea,
                    d=max(-upper[2], 0.0), X=r["X"], Z=-r["Z"], n=_PROFILE_POINTS, law=law)
            else:
                back = segment_profile(H=r["H"], V=-r["VA"], L=seg.length,
                                       w=lt.weight_in_water, ea=lt.ea,
                                       h=max(upper[2] - env.seabed_z(*upper[:2]), 0.0),
                                       X=r["X"], Z=-r["Z"], n=_PROFILE_POINTS, law=law)
            prof = {"s": (seg.length - back["s"])[::-1], "x": (r["X"] - back["x"])[::-1],
                    "z": (r["Z"] + back["z"])[::-1], "tension": back["tension"][::-1]}
        elif sk.block == "floating":
            prof = surface_segment_profile(H=r["H"], V=r["VF"], L=seg.length,
                                           w=lt.weight_in_water, ea=lt.ea,
                                           d=max(-r["lower_z"], 0.0), X=r["X"], Z=r["Z"],
                                           n=_PROFILE_POINTS, law=law)
        else:
            prof = segment_profile(H=r["H"], V=r["VF"], L=seg.length, w=lt.weight_in_water,
                                   ea=lt.ea, h=r["lower_h"], X=r["X"], Z=r["Z"],
                                   n=_PROFILE_POINTS, law=law)
        sl = slice(1, None) if k else slice(None)
        parts["s"].append(arc_below + prof["s"][sl])
        arc_below += seg.length
        parts["x"].append(r["lower_xi"] + prof["x"][sl])
        parts["z"].append(r["lower_z"] + prof["z"][sl])
        parts["tension"].append(prof["tension"][sl])
        segments.append({"type": lt.name, "length_m": seg.length,
                         "top_tension_N": math.hypot(r["H"], r["VF"]),
                         "bottom_tension_N": math.hypot(r["HA"], r["VA"]),
                         "horizontal_tension_N": r["H"], "top_vertical_N": r["VF"],
                         "bottom_vertical_N": r["VA"], "grounded_length_m": r["grounded"],
                         "floating_length_m": r["floating"],
                         "max_tension_N": float(np.max(prof["tension"])),
                         "t_over_mbl": (float(np.max(prof["tension"])) / lt.mbl
                                         if lt.mbl else None)})
        if k > 0:
            clump = clumps_lf[k - 1]
            joints.append({"position_m": [lower[0] + ux * r["lower_xi"],
                                          lower[1] + uy * r["lower_xi"], r["lower_z"]],
                           "height_above_seabed_m": r["lower_h"],
                           "on_seabed": bool(rows[k - 1]["joint_reaction"] > 0
                                             or r["lower_h"] <= 0),
                           "seabed_reaction_N": max(rows[k - 1]["joint_reaction"], 0.0),
                           # The surface holds a joint down (a negative reaction).
                           "on_surface": bool(rows[k - 1]["joint_reaction"] < 0
                                              or r["lower_z"] >= 0),
                           "surface_reaction_N": max(-rows[k - 1]["joint_reaction"], 0.0),
                           "clump_weight_N": clump.weight if clump is not None else 0.0})
    td = _touchdown(rows, segments_lf, block)
    prof = {"s": np.concatenate(parts["s"]), "x": np.concatenate(parts["x"]),
            "z": np.concatenate(parts["z"]) - lower[2],
            "tension": np.concatenate(parts["tension"])}
    profile = _orient(prof, lower, upper, kind.flipped, line.length)
    if kind.flipped:
        segments, joints = segments[::-1], joints[::-1]
    first = rows[0]
    uplift = VA > 0 and first["grounded"] <= 0
    mbl = min((seg.line_type.mbl for seg in line.segments if seg.line_type.mbl), default=None)
    fields = _end_fields(line.name, a, b, fa, fb)
    fields.update(floating_length_m=row["floating"],
                  touchup_from_anchor_m=(_first_at_surface(profile, a) if row["floating"] > 0
                                         else 0.0))
    if kind.lower == "anchor" and not kind.flipped:
        fields["anchor_vertical_N"] = max(fields["anchor_vertical_N"], 0.0)
        fields["anchor_tension_N"] = math.hypot(fields["anchor_horizontal_N"],
                                                fields["anchor_vertical_N"])
    return LegResult(
        grounded_length_m=grounded, touchdown_from_anchor_m=td or 0.0,
        uplift=bool(uplift), slack=bool(u < 0.0),
        uplift_angle_deg=math.degrees(math.atan2(VA, HA)) if uplift else 0.0,
        fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
        touchdown_point=((lower[0] + ux * td, lower[1] + uy * td, lower[2])
                         if td is not None else None),
        mbl_N=mbl, profile=profile, segments=tuple(segments), joints=tuple(joints),
        **fields)


def _first_at_surface(profile: dict, a) -> float:
    """Horizontal distance [m] from end A of the first profile point at the surface."""
    at = np.flatnonzero(np.asarray(profile["z_m"]) >= -1e-9)
    if not at.size:
        return 0.0
    k = int(at[0])
    return float(math.hypot(profile["x_m"][k] - a[0], profile["y_m"][k] - a[1]))


def _touchdown(rows, segments, block):
    """Distance from the lower end [m] where the line first leaves the seabed (None:
    uplift). The grounded run starts at the lower end and continues through segments lying
    wholly on the seabed; it ends in the first segment that lifts off."""
    for k, r in enumerate(rows):
        reversed_top = k == len(rows) - 1 and block.reversed_top
        if r["grounded"] <= 0 or reversed_top or r["lower_h"] > 0:
            return r["lower_xi"] if k else None
        if r["grounded"] < segments[k].length * (1 - 1e-12):
            return r["lower_xi"] + r["X"] - r["suspended_x"]
    return rows[-1]["lower_xi"] + rows[-1]["X"]


def discrete_result(case, line, kind, row, nodes) -> LegResult:
    """A lumped-node line: CONTRACT fields, a 3-D profile through its nodes."""
    env = case.environment
    block = kind.block
    a, b, fa, fb = _ends(row)
    H, VF, HA, VA_raw = row["H"], row["VF"], row["HA"], row["VA"]
    grounded, susp_x, X = row["grounded"], row["suspended_x"], row["X"]
    on_bed = a[2] <= env.seabed_z(a[0], a[1]) + 1e-9 * max(env.depth, 1.0)
    flags = nodes[:, 7] > 0.5
    td = X - susp_x if (on_bed and flags[1]) else None
    arc = np.concatenate([[0.0], np.cumsum(np.repeat(
        [seg.length / m for seg, m in zip(line.segments, block.elements)], block.elements))])
    profile = {"s_m": arc,
               "x_m": nodes[:, 2].copy(), "y_m": nodes[:, 3].copy(), "z_m": nodes[:, 4].copy(),
               "tension_N": nodes[:, 5].copy(), "seabed_reaction_N": nodes[:, 6].copy(),
               "surface_reaction_N": nodes[:, 8].copy()}
    _add_wall_tension(profile, line, env)
    segments, joints = [], []
    start = 0
    for k, (seg, m) in enumerate(zip(line.segments, block.elements)):
        part = nodes[start: start + m + 1]
        lt = seg.line_type
        segments.append({"type": lt.name, "length_m": seg.length, "elements": m,
                         "top_tension_N": float(part[-1, 5]),
                         "bottom_tension_N": float(part[0, 5]),
                         "max_tension_N": float(np.max(part[:, 5])),
                         "t_over_mbl": float(np.max(part[:, 5])) / lt.mbl if lt.mbl else None})
        start += m
        if k < len(line.segments) - 1:
            clump = line.joint_clumps[k]
            node = nodes[start]
            joints.append({"position_m": [float(v) for v in node[2:5]],
                           "height_above_seabed_m": float(node[4] - env.seabed_z(node[2],
                                                                                 node[3])),
                           "on_seabed": bool(node[7] > 0.5),
                           "seabed_reaction_N": float(node[6]),
                           "clump_weight_N": clump.weight if clump is not None else 0.0})
    uplift = VA_raw > 0 and not (on_bed and flags[1])
    mbl = min((seg.line_type.mbl for seg in line.segments if seg.line_type.mbl), default=None)
    u_dir = ((b[0] - a[0]) / X, (b[1] - a[1]) / X) if X > 1e-12 else (1.0, 0.0)
    fields = _end_fields(line.name, a, b, fa, fb)
    fields.update(floating_length_m=row["floating"],
                  touchup_from_anchor_m=(_first_at_surface(profile, a) if row["floating"] > 0
                                         else 0.0))
    if on_bed:
        # The anchor's vertical pull: the seabed takes a downward one.
        fields["anchor_vertical_N"] = max(VA_raw, 0.0)
        fields["anchor_tension_N"] = math.hypot(HA, fields["anchor_vertical_N"])
    return LegResult(
        grounded_length_m=grounded, touchdown_from_anchor_m=td or 0.0,
        uplift=bool(uplift), slack=bool(H <= 1e-9 * max(abs(VF), 1.0)),
        uplift_angle_deg=math.degrees(math.atan2(VA_raw, HA)) if uplift else 0.0,
        fairlead_angle_deg=math.degrees(math.atan2(VF, H)) if (H or VF) else 90.0,
        touchdown_point=((a[0] + u_dir[0] * td, a[1] + u_dir[1] * td,
                          env.seabed_z(a[0] + u_dir[0] * td, a[1] + u_dir[1] * td))
                         if td is not None else None),
        mbl_N=mbl, profile=profile,
        segments=tuple(segments) if line.multi_segment else (),
        joints=tuple(joints), **fields)


__all__ = ["single_result", "multi_result", "discrete_result", "line_notes"]
