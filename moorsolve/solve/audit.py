"""An independent audit of every result, and the warnings an engineer must see.

The certificate says the solver's residuals vanish. The audit asks a different question:
do the quantities *reported* make a physically consistent equilibrium? It reads only the
result (each line's profile, end forces, joints; the body position and loads) and the case
data (weights, lengths, stiffness, the seabed), and recomputes everything with plain numpy:
none of the solver's blocks, residuals or profile functions. A result that fails it is an
error (:class:`~moorsolve.errors.ConvergenceError` naming what failed), never a note: an
answer that is certified and wrong is the worst defect a solver can have.

Per line:

- the profile is finite and starts at the anchor and ends at the fairlead;
- it is continuous: no step between two profile points is longer than the stretched arc
  between them;
- it lies between the seabed and the surface (a point above the water only where an end
  is above it);
- its tension at the ends is the reported end tension;
- where the line leaves an end through the water, the profile's direction there is the end
  force's (to within the turning of the line over one profile step);
- a line that no current drags: the vertical forces at its ends carry the weight of the
  part the seabed or the surface does not support (found from the profile: the runs lying
  on a boundary), with every joint's clump and reaction; a frictionless line on a flat
  seabed has the same horizontal tension at both ends;
- a joint the seabed or the surface pushes is on it.

Per free body, in every free degree of freedom of six: the reported end forces at their
reported positions, the reported forces of its fenders and pile guides at their contact
points, the reported loads, the weight, the hydrostatics (recomputed here: the linear model,
and hull members by quadrature rather than the solver's closed form) and the springs balance.

Warnings (:func:`result_warnings`) are facts that do not make a result wrong but that no
engineer may miss: compression in a sealed line's wall (Sukhanov, REFERENCE.md section 2),
line floating on the surface, an end above the water (the line there is taken with its
weight in water unless the line type gives its weight in air).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ConvergenceError
from .stretch_params import numeric_law

__all__ = ["audit", "audit_findings", "result_warnings", "AuditFailure"]

#: Relative tolerance of geometric checks (of the line's length or the water depth): far
#: above the round-off of a certified solution, far below any defect worth the name.
GEOMETRY_REL = 1e-6
#: Relative tolerance of force checks, on the largest force in the line or scene.
FORCE_REL = 1e-6


class AuditFailure(ConvergenceError):
    """A certified solution whose reported quantities are not a consistent equilibrium."""


def audit(result, case) -> list[str]:
    """Check ``result`` (of ``case``) independently; raise :class:`AuditFailure` on a defect.

    Returns the names of the lines audited.
    """
    problems = audit_findings(result, case)
    if problems:
        c = result.certificate
        raise AuditFailure(
            "the solution certified but its reported quantities fail the independent audit: "
            + "; ".join(problems), residual_N=c.force_N, residual_Nm=c.moment_Nm,
            status=c.status, iterations=c.iterations, result=result)
    return [leg.name for leg in result.legs]


def audit_findings(result, case, boundaries_only: bool = False) -> list[str]:
    """What the audit finds wrong with ``result``, one sentence each (empty: nothing).

    With ``boundaries_only`` only where lines and joints sit against the seabed and the
    surface: read at the best point of a solve that did not certify (whose forces need not
    balance), it says what the model could not represent there (a joint pulled out of the
    water, a line through the seabed, loose line on a slope).
    """
    problems = []
    env = case.environment
    tol_rel = max(GEOMETRY_REL, 100.0 * result.certificate.tolerance)
    for leg_case, leg in zip(case.lines, result.legs):
        found = _audit_line(leg_case, leg, env, tol_rel, _is_lumped(case, leg_case),
                            boundaries_only)
        problems += [f"leg {leg.name}: {p}" for p in found]
    return problems + ([] if boundaries_only else _audit_body(result, case))


def _is_lumped(case, leg_case) -> bool:
    return case.environment.current is not None and any(
        seg.line_type.drag is not None for seg in leg_case.segments)


def _segment_data(leg_case):
    """Per segment: unstretched length, weight [N/m], its strain as a function of the
    tension (numpy); cumulative ends."""
    lengths = np.array([s.length for s in leg_case.segments])
    weights = np.array([s.line_type.weight_in_water for s in leg_case.segments])
    strain = [_strain_of(s.line_type) for s in leg_case.segments]
    return lengths, weights, strain, np.concatenate([[0.0], np.cumsum(lengths)])


def _strain_of(line_type):
    """The strain of a line type at tension ``T`` [N]: ``T/EA``, its stretch law's (the
    material's definition, :mod:`moorsolve.physics.stretch`), or 0 when inextensible."""
    law = numeric_law(line_type)
    if law is not None:
        return lambda T: law.strain(np.maximum(T, 0.0))
    c = 1.0 / line_type.ea if line_type.ea else 0.0
    return lambda T: c * np.asarray(T, float)


def _audit_line(leg_case, leg, env, tol_rel, lumped, boundaries_only=False) -> list[str]:
    prof = leg.profile
    out = []
    consistency = []        # what needs a solved state: ends, continuity, forces
    pts = np.column_stack([np.asarray(prof[k], float) for k in ("x_m", "y_m", "z_m")])
    T = np.asarray(prof["tension_N"], float)
    s = np.asarray(prof["s_m"], float) if "s_m" in prof else None
    lengths, weights, strain, ends = _segment_data(leg_case)
    L = float(ends[-1])
    t_max = max(float(np.max(np.abs(T))) if T.size else 0.0, leg.fairlead_tension_N,
                leg.anchor_tension_N, float(np.sum(np.abs(weights) * lengths)), 1e-300)
    size = max(L * (1.0 + max(float(f(t_max)) for f in strain)), env.depth, 1.0)
    tol = tol_rel * size
    if not (np.all(np.isfinite(pts)) and np.all(np.isfinite(T)) and math.isfinite(t_max)
            and math.isfinite(size)):
        return ["the profile has non-finite points or tensions"]
    anchor, fairlead = np.asarray(leg.anchor, float), np.asarray(leg.fairlead, float)
    miss_a = float(np.linalg.norm(pts[0] - anchor))
    miss_f = float(np.linalg.norm(pts[-1] - fairlead))
    if miss_a > tol:
        consistency.append(f"the profile starts {miss_a:.3g} m from the anchor")
    if miss_f > tol:
        consistency.append(f"the profile ends {miss_f:.3g} m from the fairlead")
    step = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    if s is not None and s.size == len(pts):
        ds = np.diff(s)
        seg = np.clip(np.searchsorted(ends, s[:-1] + ds / 2) - 1, 0, len(strain) - 1)
        t_step = np.maximum(np.abs(T[1:]), np.abs(T[:-1]))
        eps = np.zeros_like(t_step)
        for k, f in enumerate(strain):
            eps[seg == k] = f(t_step[seg == k])
        allowed = ds * (1.0 + eps) * (1.0 + 1e-9) + tol
        k = int(np.argmax(step - allowed))
        if np.any(ds < -tol) or step[k] > allowed[k]:
            consistency.append(f"the profile is not continuous: a step of {step[k]:.4g} m "
                               f"between points {ds[k]:.4g} m apart along the line")
        if abs(s[-1] - L) > tol or abs(s[0]) > tol:
            consistency.append(f"the profile covers {s[0]:.4g} m to {s[-1]:.4g} m of a "
                               f"{L:.4g} m line")
    bed = env.seabed_z(pts[:, 0], pts[:, 1])
    below_tol = tol
    if leg.seabed_plane is not None:
        # On a grid the line lies on its own plane (solve/bathymetry.py): on the plane to
        # the audit's tolerance, and off the grid's surface by at most the seabed tolerance.
        z0, gx, gy = leg.seabed_plane
        plane = z0 + gx * pts[:, 0] + gy * pts[:, 1]
        under = float(np.max(plane - pts[:, 2]))
        if under > tol:
            out.append(f"the line passes {under:.3g} m below its seabed plane")
        below_tol = max(tol, env.seabed.tolerance)
    below = float(np.max(bed - pts[:, 2]))
    if below > below_tol:
        k = int(np.argmax(bed - pts[:, 2]))
        out.append(f"the line passes {below:.3g} m below the seabed (at "
                   f"{pts[k, 0]:.2f}, {pts[k, 1]:.2f}, {pts[k, 2]:.2f} m)"
                   + (f"; the bathymetry's tolerance is {env.seabed.tolerance:g} m"
                      if leg.seabed_plane is not None else ""))
    if leg.seabed_plane is not None:
        bed = plane         # where the model puts grounded line
    ceiling = max(0.0, anchor[2], fairlead[2])
    above = float(np.max(pts[:, 2])) - ceiling
    if above > tol:
        out.append(f"the line rises {above:.3g} m above the surface" if ceiling == 0.0 else
                   f"the line rises {above:.3g} m above its highest end, out of the water")
    f_tol = FORCE_REL * t_max + tol_rel * t_max
    # A lumped-node line's end node carries half of its element's weight and flow force, which
    # the seabed takes at an anchor lying on it: the end tension may differ by that much.
    end_tol = f_tol + (_element_load(leg_case, s, env) if lumped and s is not None else 0.0)
    if abs(T[0] - leg.anchor_tension_N) > end_tol:
        consistency.append(f"the profile's tension at the anchor, {T[0]:.6g} N, is not the "
                           f"reported anchor tension {leg.anchor_tension_N:.6g} N")
    if abs(T[-1] - leg.fairlead_tension_N) > end_tol:
        consistency.append(f"the profile's tension at the fairlead, {T[-1]:.6g} N, is not the "
                           f"reported fairlead tension {leg.fairlead_tension_N:.6g} N")
    if not lumped and env.seabed.sloped:
        out += _audit_slack_on_slope(pts, T, bed, env.seabed.friction, t_max, size)
    if not lumped and s is not None and s.size == len(pts):
        # On a boundary: a profile drawn from a solved state puts a grounded or floating run
        # exactly on it (to round-off), so the test is tight: a looser one would count the
        # first metres of a line rising tangentially off the boundary as supported.
        tight = 1e-12 * size
        on_bed = pts[:, 2] - bed <= tight
        on_top = np.abs(pts[:, 2]) <= tight       # afloat: on the surface, not above
        consistency += _audit_end_directions(leg, pts, s, ends, weights, on_bed | on_top, tol,
                                             _weights_in_air(leg_case))
        consistency += _audit_vertical_balance(leg_case, leg, env, pts, s, ends, weights,
                                               on_bed, on_top, t_max, tight)
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
    return out if boundaries_only else consistency + out


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


def _weights_in_air(leg_case) -> np.ndarray:
    """Per segment, its weight [N/m] above the water: its weight in air where the case
    gives it, else its weight in water."""
    return np.array([sg.line_type.weight_in_air if sg.line_type.weight_in_air is not None
                     else sg.line_type.weight_in_water for sg in leg_case.segments])


def _audit_end_directions(leg, pts, s, ends, weights, on_boundary, tol,
                          in_air=None) -> list[str]:
    """The end forces point along the profile where the line leaves an end through water."""
    out = []
    ux, uy = _plane(leg)
    checks = [
        ("fairlead", -1, -2, np.array([-leg.horizontal_tension_N * ux,
                                       -leg.horizontal_tension_N * uy,
                                       -leg.fairlead_vertical_N]), leg.fairlead_tension_N),
        ("anchor", 0, 1, np.array([leg.anchor_horizontal_N * ux, leg.anchor_horizontal_N * uy,
                                   leg.anchor_vertical_N]), leg.anchor_tension_N),
    ]
    for name, i, j, force, T in checks:
        chord = pts[j] - pts[i]
        length = float(np.linalg.norm(chord))
        if T <= 0 or length <= tol or (on_boundary[i] and on_boundary[j]):
            continue
        if name == "anchor" and leg.anchor_vertical_N == 0.0 and on_boundary[i]:
            continue     # the reported upward pull is clipped at 0 where the line lies
        # The line pulls each end toward itself: along the chord from the end into the line.
        direction = force / max(np.linalg.norm(force), 1e-300)
        cosine = float(np.clip(direction @ chord / length, -1.0, 1.0))
        angle = math.acos(cosine)
        k = min(i, j) if i >= 0 else len(pts) - 2
        seg = min(np.searchsorted(ends, s[k] + 1e-12) - 1, len(weights) - 1)
        above = in_air is not None and (pts[i][2] + pts[j][2]) / 2 > 0
        w = abs((in_air if above else weights)[seg])
        ds = abs(s[j] - s[i])
        if T <= w * ds:
            continue     # too little tension for the step to bound the line's turning
        turning = w * ds / (T - w * ds) + 1e-6
        if angle > turning:
            out.append(f"the force at the {name} points {math.degrees(angle):.3g} deg away "
                       f"from the line's direction there (at most "
                       f"{math.degrees(turning):.2g} deg over one profile step)")
    return out


def _audit_vertical_balance(leg_case, leg, env, pts, s, ends, weights, on_bed, on_top,
                            t_max, tight) -> list[str]:
    """The end forces carry the weight the seabed and the surface do not support.

    A line leaving a boundary tangentially rises ``w s^2 / (2 T)`` in ``s``: a profile point
    within ``s = sqrt(2 T tight / w)`` of the lift-off looks supported, so each end of a
    supported run may shift the weight found by ``sqrt(2 T tight w)``.
    """
    if env.seabed.sloped and leg.grounded_length_m > 0:
        return []           # the slope's reaction has a horizontal part; not checked here
    mid = (s[1:] + s[:-1]) / 2
    seg = np.clip(np.searchsorted(ends, mid) - 1, 0, len(weights) - 1)
    w = weights[seg]
    # Above the water a line weighs its weight in air, where the case gives it.
    in_air = _weights_in_air(leg_case)[seg]
    w = np.where((pts[1:, 2] + pts[:-1, 2]) / 2 > 0, in_air, w)
    ds = np.diff(s)
    supported = (on_bed[1:] & on_bed[:-1]) | (on_top[1:] & on_top[:-1])
    hanging = float(np.sum(w * ds * ~supported))
    clumps = sum(c.weight for c in leg_case.joint_clumps if c is not None)
    reactions = sum(j.get("seabed_reaction_N", 0.0) - j.get("surface_reaction_N", 0.0)
                    for j in leg.joints)
    unbalanced = (leg.fairlead_vertical_N - _signed_anchor_pull(leg, pts) - hanging - clumps
                  + reactions)
    scale = max(t_max, float(np.sum(np.abs(weights) * np.diff(ends))), 1e-300)
    run_ends = 2 + int(np.count_nonzero(np.diff(supported.astype(int))))
    allowance = run_ends * math.sqrt(2.0 * t_max * tight * float(np.max(np.abs(weights))))
    out = []
    if abs(unbalanced) > 1e-6 * scale + allowance:
        out.append(f"the end forces do not carry the line's weight: {unbalanced:.4g} N of "
                   f"vertical force unbalanced (the line hangs {hanging:.6g} N)")
    frictionless = env.seabed.friction == 0.0 or leg.grounded_length_m == 0.0
    if frictionless and abs(leg.horizontal_tension_N - leg.anchor_horizontal_N) > 1e-6 * scale:
        out.append(f"the horizontal tension changes along a line with nothing to hold it "
                   f"({leg.horizontal_tension_N:.6g} N at the fairlead, "
                   f"{leg.anchor_horizontal_N:.6g} N at the anchor)")
    return out


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


def _signed_anchor_pull(leg, pts) -> float:
    """The line's vertical pull on its anchor, signed (upward positive).

    The result reports the upward pull, 0 for a line lying on the seabed at the anchor and
    for an anchor pulled down (on a slope the soil takes that): the downward part is then
    recovered from the reported anchor tension and the profile's direction there.
    """
    VA = leg.anchor_vertical_N
    TA, HA = leg.anchor_tension_N, leg.anchor_horizontal_N
    if VA == 0.0 and TA > HA and len(pts) > 1 and pts[1, 2] < pts[0, 2]:
        return -math.sqrt((TA - HA) * (TA + HA))
    return VA


def _plane(leg) -> tuple[float, float]:
    dx, dy = leg.fairlead[0] - leg.anchor[0], leg.fairlead[1] - leg.anchor[1]
    X = math.hypot(dx, dy)
    return (dx / X, dy / X) if X > 1e-12 else (1.0, 0.0)


def _audit_body(result, case) -> list[str]:
    """The reported line forces balance every free body and free point.

    Per body, in every free degree of freedom: the force and the moment about the body's
    origin (global axes) of every line end on the body (the reported end forces at the
    reported end positions), every reported load, the weight at the centre of gravity, the
    hydrostatics recomputed here (the linear model; hull members by Gauss quadrature over
    their cross-section, not by the solver's closed form) and the extra springs; the
    moments are taken about the axes the body's angles turn about. Per free point: all
    three components, with its weight in water and the seabed's reported reaction.
    """
    out = []
    env = case.environment
    t_max = max([1.0] + [max(leg.fairlead_tension_N, leg.anchor_tension_N)
                         for leg in result.legs]
                + [c["reaction_N"] for c in result.fenders + result.guides])
    for bi, body in enumerate(case.bodies):
        if not body.free or bi >= len(result.bodies):
            continue
        pose = result.bodies[bi]
        q = np.array([pose["x_m"], pose["y_m"], pose["z_m"]] + [
            math.radians(pose[k]) for k in ("roll_deg", "pitch_deg", "yaw_deg")])
        origin, R = q[:3], _rotation(*q[3:])
        force, moment = np.zeros(3), np.zeros(3)
        scale = t_max
        radius = 1.0
        for line, leg in zip(case.lines, result.legs):
            for end, pos, f in ((line.a, leg.anchor, _end_force(leg, "a")),
                                (line.b, leg.fairlead, _end_force(leg, "b"))):
                if end.body != body.name or f is None:
                    continue
                arm = np.asarray(pos, float) - origin
                force += f
                moment += np.cross(arm, f)
                radius = max(radius, float(np.hypot(arm[0], arm[1])))
        # Fenders and pile guides' pads (reaction and friction) at their contact points.
        contacts = [c for c in result.fenders if c["body"] == body.name]
        contacts += [pad for g in result.guides if g["body"] == body.name for pad in g["pads"]]
        for contact in contacts:
            f = np.asarray(contact["force_N"], float)
            arm = np.asarray(contact["contact_point_m"], float) - origin
            force += f
            moment += np.cross(arm, f)
            radius = max(radius, float(np.hypot(arm[0], arm[1])))
        for name, load in result.loads.items():
            if len(case.bodies) > 1 and not name.startswith(body.name + "."):
                continue
            f = np.asarray(load, float)
            if f.size == 3:                       # the legs form: [Fx, Fy, Mz]
                f = np.array([f[0], f[1], 0.0, 0.0, 0.0, f[2]])
            force += f[:3]
            moment += f[3:]
            scale = max(scale, float(np.linalg.norm(f[:3])))
        # Hydrostatics act about the still-water level (above the datum by a tide).
        afloat = origin - np.array([0.0, 0.0, env.water_level])
        for f, m in _hydrostatic_wrenches(body, afloat, R, env):
            force += f
            moment += m
            scale = max(scale, float(np.linalg.norm(f)))
        generalized = np.concatenate([force, _angle_axes(q[4], q[5]).T @ moment])
        if body.stiffness is not None:
            q0 = np.array(list(body.position) + [math.radians(a) for a in
                                                 body.orientation_deg])
            generalized -= np.asarray(body.stiffness, float) @ (q - q0)
        tol = max(10.0 * result.certificate.tolerance, FORCE_REL) * scale
        for dof in body.free:
            k = ("surge", "sway", "heave", "roll", "pitch", "yaw").index(dof)
            unit = "N" if k < 3 else "N m"
            if abs(generalized[k]) > tol * (1.0 if k < 3 else max(radius, 1.0) * 10.0):
                out.append(f"body {body.name} is not in balance in {dof}: "
                           f"{generalized[k]:.4g} {unit} unbalanced by the reported line "
                           "forces, loads, weight and hydrostatics")
    tol = max(10.0 * result.certificate.tolerance, FORCE_REL) * t_max
    for point, reported in zip(case.free_points, result.points):
        total = np.array([0.0, 0.0, -env.gravity * (point.mass
                                                    - env.water_density * point.volume)])
        for line, leg in zip(case.lines, result.legs):
            for end, which in ((line.a, "a"), (line.b, "b")):
                force = _end_force(leg, which)
                if end.point == point.name and force is not None:
                    total += force
        gx, gy = env.seabed.gradient
        normal = np.array([-gx, -gy, 1.0]) / math.sqrt(1 + gx * gx + gy * gy)
        total += reported.get("seabed_reaction_N", 0.0) * normal
        if np.linalg.norm(total) > tol:
            out.append(f"point {point.name} is not in balance: {np.linalg.norm(total):.4g} N "
                       "unbalanced by the reported line forces, its weight and the seabed")
    return out


def _rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) Ry(pitch) Rx(roll)`` as the product of the three elementary rotations."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    return rz @ ry @ rx


def _angle_axes(pitch: float, yaw: float) -> np.ndarray:
    """Columns: the global axes roll, pitch and yaw turn about (z-y-x angles)."""
    rz = _rotation(0.0, 0.0, yaw)
    return np.column_stack([rz @ _rotation(0.0, pitch, 0.0) @ [1.0, 0.0, 0.0],
                            rz @ [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def _hydrostatic_wrenches(body, origin, R, env):
    """Weight, buoyancy and heave restoring of a body, as ``(force, moment)`` pairs."""
    g, rho = env.gravity, env.water_density
    out = []
    if body.mass is not None:
        w = np.array([0.0, 0.0, -body.mass * g])
        out.append((w, np.cross(R @ np.asarray(body.centre_of_gravity, float), w)))
    hydro = body.hydrostatics
    if hydro is not None:
        b = np.array([0.0, 0.0, rho * g * hydro.displaced_volume])
        out.append((b, np.cross(R @ np.asarray(hydro.metacentre, float), b)))
        out.append((np.array([0.0, 0.0, -rho * g * hydro.waterplane_area * origin[2]]),
                    np.zeros(3)))
    for member in body.hull:
        volume, centroid = _member_volume(member, origin, R)
        b = np.array([0.0, 0.0, rho * g * volume])
        out.append((b, np.cross(R @ centroid, b)))
    return out


_GAUSS = np.polynomial.legendre.leggauss(24)


def _member_volume(member, origin, R) -> tuple:
    """Submerged volume [m^3] and its centroid (body frame) of a vertical prism, by Gauss
    quadrature of the submerged column height over its cross-section."""
    nodes, weights = _GAUSS
    cx, cy = member.centre
    if member.shape == "cylinder":
        # Polar: r = a (n + 1) / 2 over [0, a], theta over [0, 2 pi]; dA = r dr dtheta.
        r = member.radius * (nodes + 1) / 2
        th = math.pi * (nodes + 1)
        rr, tt = np.meshgrid(r, th, indexing="ij")
        ww = np.outer(weights * member.radius / 2 * r, weights * math.pi)
        xs, ys = cx + rr * np.cos(tt), cy + rr * np.sin(tt)
    else:
        xs1 = cx + member.length / 2 * nodes
        ys1 = cy + member.width / 2 * nodes
        xs, ys = np.meshgrid(xs1, ys1, indexing="ij")
        ww = np.outer(weights * member.length / 2, weights * member.width / 2)
    # The water surface along the member's axis at (x, y): origin_z + (R [x, y, z])_z = 0.
    surface = -(origin[2] + R[2, 0] * xs + R[2, 1] * ys) / R[2, 2]
    h = np.clip(surface - member.bottom, 0.0, member.top - member.bottom)
    volume = float(np.sum(ww * h))
    if volume <= 0.0:
        return 0.0, np.zeros(3)
    centroid = np.array([np.sum(ww * h * xs), np.sum(ww * h * ys),
                         np.sum(ww * h * (member.bottom + h / 2))]) / volume
    return volume, centroid


def _end_force(leg, which: str):
    """The force [N] the line exerts on its end A or B, as reported (global 3-vector)."""
    force = leg.anchor_force if which == "a" else leg.fairlead_force
    return None if force is None else np.asarray(force, float)


# ---- warnings ---------------------------------------------------------------------------


def result_warnings(result, case) -> list[dict]:
    """What an engineer must not miss in ``result``: a list of ``{"code", "leg",
    "message"}`` (codes ``wall_compression``, ``floating``, ``end_in_air``)."""
    out = []
    for leg_case, leg in zip(case.lines, result.legs):
        # Only a sealed line's profile has a wall tension (and a profile costs its drawing).
        sealed = any(seg.line_type.sealed for seg in leg_case.segments)
        prof = leg.profile if sealed else {}
        wall = prof.get("wall_tension_N")
        if wall is not None and np.any(np.asarray(wall) < 0):
            k = int(np.argmin(wall))
            out.append(dict(code="wall_compression", leg=leg.name, message=(
                f"leg {leg.name}: the wall tension of the sealed line is compressive, down to "
                f"{float(wall[k]) / 1e3:.4g} kN at z = {float(prof['z_m'][k]):.1f} m (the "
                "effective tension is positive there; the wall may buckle)")))
        if leg.floating_length_m > 0:
            out.append(dict(code="floating", leg=leg.name, message=(
                f"leg {leg.name}: {leg.floating_length_m:.2f} m of line floats on the surface "
                f"(from {leg.touchup_from_anchor_m:.2f} m from the anchor)")))
        level = case.environment.water_level
        for end, z in (("fairlead", leg.fairlead[2] - level), ("anchor", leg.anchor[2] - level)):
            lt = leg_case.segments[-1 if end == "fairlead" else 0].line_type
            if lt.weight_in_water == 0 and lt.weight_in_air is None:
                continue        # a hawser: weightless by definition, in air as in water
            if z > 0:
                how = (f"with its weight in air, {lt.weight_in_air:.4g} N/m"
                       if lt.weight_in_air is not None and not leg_case.multi_segment
                       and not _is_lumped(case, leg_case) else
                       "with its weight in water (give the line type a weight_in_air)"
                       if lt.weight_in_air is None else
                       "with its weight in water (a multi-segment or lumped-node line)")
                out.append(dict(code="end_in_air", leg=leg.name, message=(
                    f"leg {leg.name}: the {end} is {z:.2f} m above the water; the line above "
                    f"the surface is taken {how}")))
    return out
