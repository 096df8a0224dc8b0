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
from .audit_closed_form import closed_form_findings, covers, table_ends
from .audit_lines import FORCE_REL, is_lumped, line_findings
from .concurrency import LockedLRU

__all__ = ["audit", "audit_findings", "result_warnings", "AuditFailure"]

#: Relative tolerance of geometric checks (of the line's length or the water depth): far
#: above the round-off of a certified solution, far below any defect worth the name.
GEOMETRY_REL = 1e-6


class AuditFailure(ConvergenceError):
    """A certified solution whose reported quantities are not a consistent equilibrium."""


def audit(result, case, problem=None, post=None, full: bool = False) -> list[str]:
    """Check ``result`` (of ``case``) independently; raise :class:`AuditFailure` on a defect.

    Given the ``problem`` and its report arrays ``post`` at the result, a scene of
    one-segment lines on a flat seabed is audited in closed form from the reported end
    positions and forces (:mod:`.audit_closed_form`), without drawing a profile; ``full``
    also runs the profile audit. Returns the names of the lines audited.
    """
    problems = (None if problem is None or post is None
                else closed_form_audit(result, case, problem, post))
    if problems is None or full:
        problems = (problems or []) + audit_findings(result, case)
    if problems:
        c = result.certificate
        raise AuditFailure(
            "the solution certified but its reported quantities fail the independent audit: "
            + "; ".join(problems), residual_N=c.force_N, residual_Nm=c.moment_Nm,
            status=c.status, iterations=c.iterations, result=result)
    return [line.name for line in case.lines]


def audit_findings(result, case, boundaries_only: bool = False) -> list[str]:
    """What the audit finds wrong with ``result``, one sentence each (empty: nothing).

    With ``boundaries_only`` only where lines and joints sit against the seabed and the
    surface: read at the best point of a solve that did not certify (whose forces need not
    balance), it says what the model could not represent there (a joint pulled out of the
    water, a line through the seabed, loose line on a slope).
    """
    tol_rel = max(GEOMETRY_REL, 100.0 * result.certificate.tolerance)
    problems = line_findings(case, result.legs, tol_rel, boundaries_only)
    if boundaries_only:
        return problems
    legs = result.legs
    ends = tuple(np.array([getattr(leg, k) if getattr(leg, k) is not None else (0.0,) * 3
                           for leg in legs], float).reshape(-1, 3)
                 for k in ("anchor", "fairlead", "anchor_force", "fairlead_force"))
    t_lines = max([1.0] + [max(leg.fairlead_tension_N, leg.anchor_tension_N)
                           for leg in legs])
    return problems + _audit_body(result, case, ends, t_lines)


def closed_form_audit(result, case, problem, post) -> list[str] | None:
    """The audit's findings from the report arrays, or None where the closed forms do not
    cover the scene (:func:`.audit_closed_form.covers`)."""
    if not covers(problem, case):
        return None
    table = np.atleast_2d(np.asarray(post["lines"], float))
    tol_rel = max(GEOMETRY_REL, 100.0 * result.certificate.tolerance)
    problems, t_lines = closed_form_findings(problem, case, table, tol_rel)
    if problems is None:
        return None
    return problems + _audit_body(result, case, table_ends(table), max(t_lines, 1.0))


def _audit_body(result, case, ends, t_lines: float) -> list[str]:
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
    t_max = max([t_lines] + [c["reaction_N"] for c in result.fenders + result.guides])
    a, b, fa, fb = ends
    by_body = _ends_by_body(case, ends)
    for bi, body in enumerate(case.bodies):
        if not body.free or bi >= len(result.bodies):
            continue
        pose = result.bodies[bi]
        q = np.array([pose["x_m"], pose["y_m"], pose["z_m"]] + [
            math.radians(pose[k]) for k in ("roll_deg", "pitch_deg", "yaw_deg")])
        origin, R = q[:3], _rotation(*q[3:])
        # The line ends on the body, then fenders' and pile guides' pads (reaction and
        # friction) at their contact points: all at once.
        positions, forces = by_body.get(body.name, (np.zeros((0, 3)), np.zeros((0, 3))))
        contacts = [c for c in result.fenders if c["body"] == body.name]
        contacts += [pad for g in result.guides if g["body"] == body.name for pad in g["pads"]]
        if contacts:
            positions = np.vstack([positions, [c["contact_point_m"] for c in contacts]])
            forces = np.vstack([forces, [c["force_N"] for c in contacts]])
        force, moment = np.zeros(3), np.zeros(3)
        scale = t_max
        radius = 1.0
        if len(forces):
            f = forces
            arm = positions - origin
            force += f.sum(axis=0)
            moment += _moment_sum(arm, f)
            radius = max(radius, float(np.hypot(arm[:, 0], arm[:, 1]).max()))
        for name, load in result.loads.items():
            if len(case.bodies) > 1 and not name.startswith(body.name + "."):
                continue
            f = np.asarray(load, float)
            if f.size == 3:                       # the legs form: [Fx, Fy, Mz]
                f = np.array([f[0], f[1], 0.0, 0.0, 0.0, f[2]])
            force += f[:3]
            moment += f[3:]
            scale = max(scale, math.hypot(f[0], f[1], f[2]))
        # Hydrostatics act about the still-water level (above the datum by a tide).
        afloat = origin - np.array([0.0, 0.0, env.water_level])
        for f, m in _hydrostatic_wrenches(body, afloat, R, env):
            force += f
            moment += m
            scale = max(scale, float(np.linalg.norm(f)))
        generalized = np.concatenate([force, _angle_axes(R, q[5]).T @ moment])
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
        for i, line in enumerate(case.lines):
            for end, force in ((line.a, fa), (line.b, fb)):
                if end.point == point.name:
                    total += force[i]
        gx, gy = env.seabed.gradient
        normal = np.array([-gx, -gy, 1.0]) / math.sqrt(1 + gx * gx + gy * gy)
        total += reported.get("seabed_reaction_N", 0.0) * normal
        if np.linalg.norm(total) > tol:
            out.append(f"point {point.name} is not in balance: {np.linalg.norm(total):.4g} N "
                       "unbalanced by the reported line forces, its weight and the seabed")
    return out


def _ends_by_body(case, ends) -> dict:
    """Per body name: the positions ``(k, 3)`` and the reported forces ``(k, 3)`` of the
    line ends on it (ends A of the lines on it, then ends B)."""
    a, b, fa, fb = ends
    out = {}
    for name, (on_a, on_b) in _ends_on_bodies(case.lines).items():
        out[name] = (np.concatenate([a[on_a], b[on_b]]), np.concatenate([fa[on_a], fb[on_b]]))
    return out


_ENDS_ON_BODIES = LockedLRU(256)


def _ends_on_bodies(lines) -> dict:
    """Per body name, the lines whose end A and whose end B are on it (index arrays), once
    per lines tuple."""
    hit = _ENDS_ON_BODIES.get(id(lines))
    if hit is not None and hit[0] is lines:
        return hit[1]
    names = {end.body for line in lines for end in (line.a, line.b) if end.body is not None}
    found = {name: (np.array([i for i, line in enumerate(lines) if line.a.body == name], int),
                    np.array([i for i, line in enumerate(lines) if line.b.body == name], int))
             for name in sorted(names)}
    _ENDS_ON_BODIES.put(id(lines), (lines, found))
    return found


def _moment_sum(arm: np.ndarray, force: np.ndarray) -> np.ndarray:
    """``sum_i arm_i x force_i`` of (n, 3) arrays (numpy's cross costs more than it
    computes)."""
    (ax, ay, az), (fx, fy, fz) = arm.T, force.T
    return np.array([ay @ fz - az @ fy, az @ fx - ax @ fz, ax @ fy - ay @ fx])


def _cross3(a, b) -> np.ndarray:
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


def _rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) Ry(pitch) Rx(roll)``, multiplied out."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _angle_axes(R: np.ndarray, yaw: float) -> np.ndarray:
    """Columns: the global axes roll, pitch and yaw turn about (z-y-x angles), for the
    body's rotation ``R`` (:func:`_rotation`): ``Rz Ry e_x`` (R's first column, as ``Rx``
    keeps ``e_x``), ``Rz e_y`` and ``e_z``."""
    return np.array([[R[0, 0], -math.sin(yaw), 0.0], [R[1, 0], math.cos(yaw), 0.0],
                     [R[2, 0], 0.0, 1.0]])


def _hydrostatic_wrenches(body, origin, R, env):
    """Weight, buoyancy and heave restoring of a body, as ``(force, moment)`` pairs."""
    g, rho = env.gravity, env.water_density
    out = []
    if body.mass is not None:
        w = np.array([0.0, 0.0, -body.mass * g])
        out.append((w, _cross3(R @ np.asarray(body.centre_of_gravity, float), w)))
    hydro = body.hydrostatics
    if hydro is not None:
        b = np.array([0.0, 0.0, rho * g * hydro.displaced_volume])
        out.append((b, _cross3(R @ np.asarray(hydro.metacentre, float), b)))
        out.append((np.array([0.0, 0.0, -rho * g * hydro.waterplane_area * origin[2]]),
                    np.zeros(3)))
    for member in body.hull:
        volume, centroid = _member_volume(member, origin, R)
        b = np.array([0.0, 0.0, rho * g * volume])
        out.append((b, _cross3(R @ centroid, b)))
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


# ---- warnings ---------------------------------------------------------------------------


def result_warnings(result, case) -> list[dict]:
    """What an engineer must not miss in ``result``: a list of ``{"code", "leg",
    "message"}`` (codes ``wall_compression``, ``floating``, ``end_in_air``; on a bathymetry
    grid :func:`.bathymetry.finish` adds ``seabed_departure``)."""
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
                       and not is_lumped(case, leg_case) else
                       "with its weight in water (give the line type a weight_in_air)"
                       if lt.weight_in_air is None else
                       "with its weight in water (a multi-segment or lumped-node line)")
                out.append(dict(code="end_in_air", leg=leg.name, message=(
                    f"leg {leg.name}: the {end} is {z:.2f} m above the water; the line above "
                    f"the surface is taken {how}")))
    return out
