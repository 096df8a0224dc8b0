"""The audit's balance of every free body and free point (:mod:`moorsolve.audit`).

Per body, in every free degree of freedom: the force and the moment about the body's origin
(global axes) of every line end on the body (the reported end forces at the reported end
positions), every reported fender and pile-guide force at its contact point, every reported
load, the weight at the centre of gravity, the hydrostatics recomputed here (the linear
model; hull members by Gauss quadrature over their cross-section, not by the solver's
closed form) and the extra springs; the moments are taken about the axes the body's angles
turn about. Per free point: all three components, with its weight in water and the seabed's
reported reaction.

The line ends come as two ``(2 n, 3)`` arrays, positions and the forces the lines exert
on them, with end A of line ``i`` in row ``2 i`` and end B in row ``2 i + 1`` (read from
the legs or straight from the report's line table).
"""

from __future__ import annotations

import math

import numpy as np

from ..constants import HULL_STIFFNESS
from ..model.build_network import rotation
from ..concurrency import LockedLRU
from .lines import FORCE_REL

__all__ = ["body_findings", "one_body_inputs", "symbolic_balance"]

_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def body_findings(result, case, positions, forces, t_lines: float) -> list[str]:
    """One sentence per free degree of freedom of a body, and per free point, that the
    reported forces leave unbalanced (empty: all balance). ``t_lines`` [N]: the largest
    line tension, the scale of the force tolerance."""
    out = []
    env = case.environment
    t_max = max([t_lines] + [c["reaction_N"] for c in result.fenders + result.guides])
    rows = _end_rows(case.lines)
    certified_tol = max(10.0 * result.certificate.tolerance, FORCE_REL)
    for bi, body in enumerate(case.bodies):
        if not body.free or bi >= len(result.bodies):
            continue
        pose = result.bodies[bi]
        q = [pose["x_m"], pose["y_m"], pose["z_m"],
             *(math.radians(pose[k]) for k in ("roll_deg", "pitch_deg", "yaw_deg"))]
        origin, R = np.array(q[:3]), rotation(*q[3:])
        on_body = rows.get(("body", body.name))
        at = positions[on_body] if on_body is not None else np.zeros((0, 3))
        pulls = forces[on_body] if on_body is not None else np.zeros((0, 3))
        # Fenders' and pile guides' pads (reaction and friction) at their contact points.
        contacts = [c for c in result.fenders if c["body"] == body.name]
        # A fully compressed fender's hull, bearing on the wall at the fender's point.
        contacts += [dict(contact_point_m=c["contact_point_m"], force_N=c["hull_force_N"])
                     for c in contacts if c.get("hull_bears")]
        contacts += [pad for g in result.guides if g["body"] == body.name for pad in g["pads"]]
        if contacts:
            at = np.vstack([at, [c["contact_point_m"] for c in contacts]])
            pulls = np.vstack([pulls, [c["force_N"] for c in contacts]])
        force, moment = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        scale, radius = t_max, 1.0
        if len(pulls):
            arm = at - origin
            m = (arm.T @ pulls).tolist()     # m[j][k] = sum_i arm_ij pull_ik
            force = pulls.sum(axis=0).tolist()
            moment = [m[1][2] - m[2][1], m[2][0] - m[0][2], m[0][1] - m[1][0]]
            radius = max(radius, math.sqrt(max(x * x + y * y for x, y, _ in arm.tolist())))
        loads, largest = body_loads(result, case, body.name)
        force = [a + b for a, b in zip(force, loads[:3])]
        moment = [a + b for a, b in zip(moment, loads[3:])]
        scale = max(scale, largest)
        # Hydrostatics act about the still-water level (above the datum by a tide).
        afloat = (q[0], q[1], q[2] - env.water_level)
        for f, m in _hydrostatic_wrenches(body, afloat, R, env):
            force = [a + b for a, b in zip(force, f)]
            moment = [a + b for a, b in zip(moment, m)]
            scale = max(scale, math.hypot(f[0], f[1], f[2]))
        generalized = [*force, *_about_angle_axes(R, q[5], moment)]
        if body.stiffness is not None:
            # Springs act about the rest pose (a floating body's risen with the tide).
            q0 = np.array(list(body.rest_position(env.water_level))
                          + [math.radians(a) for a in body.orientation_deg])
            generalized = np.array(generalized) - np.asarray(body.stiffness, float) @ (
                np.array(q) - q0)
        tol = certified_tol * scale
        for dof in body.free:
            k = _DOFS.index(dof)
            # Written so that a NaN (a pose or force not a number) is unbalanced.
            if not abs(generalized[k]) <= tol * (1.0 if k < 3 else max(radius, 1.0) * 10.0):
                out.append(f"body {body.name} is not in balance in {dof}: "
                           f"{generalized[k]:.4g} {'N' if k < 3 else 'N m'} unbalanced by "
                           "the reported line forces, loads, weight and hydrostatics")
    tol = certified_tol * t_max
    for point, reported in zip(case.free_points, result.points):
        total = np.array([0.0, 0.0, -env.gravity * (point.mass
                                                    - env.water_density * point.volume)])
        on_point = rows.get(("point", point.name))
        if on_point is not None:
            total += forces[on_point].sum(axis=0)
        # The seabed's slope where the point rests (a bathymetry grid's, or the plane's).
        gx, gy = env.seabed.slope_at(reported["x_m"], reported["y_m"])
        normal = np.array([-gx, -gy, 1.0]) / math.sqrt(1 + gx * gx + gy * gy)
        total += reported.get("seabed_reaction_N", 0.0) * normal
        if not np.linalg.norm(total) <= tol:
            out.append(f"point {point.name} is not in balance: {np.linalg.norm(total):.4g} N "
                       "unbalanced by the reported line forces, its weight and the seabed")
    return out


def body_loads(result, case, name: str) -> tuple:
    """``([Fx, Fy, Fz, Mx, My, Mz], largest)``: the sum of the reported loads on body
    ``name`` (force, and moment about its origin) and the largest force among them."""
    total, largest = [0.0] * 6, 0.0
    several = len(case.bodies) > 1
    for key, load in result.loads.items():
        if several and not key.startswith(name + "."):
            continue
        f = [float(v) for v in load]
        if len(f) == 3:                       # the legs form: [Fx, Fy, Mz]
            f = [f[0], f[1], 0.0, 0.0, 0.0, f[2]]
        total = [a + b for a, b in zip(total, f)]
        largest = max(largest, math.hypot(f[0], f[1], f[2]))
    return total, largest


#: What the compiled verdict (:mod:`.closed_form`) reads of a scene's one free body
#: per solve: its pose (m, rad), the sum of its loads (force, moment about its origin) and
#: their largest force; and per body: its weight, centre of gravity, buoyancy, metacentre,
#: waterplane stiffness, the water level, half the balance's relative tolerance, which
#: degrees of freedom are free (1 or 0), its extra stiffness (6 x 6, by rows; zero without)
#: and the pose it acts from (m, rad).
BODY_POSE = 13
BODY_DATA = 59
_STIFFNESS, _SPRING_REST = 17, 53


def one_body_inputs(problem, result, case):
    """``(name, pose, data)`` for the compiled verdict's balance of the scene's one free body
    (``pose`` a list of :data:`BODY_POSE` numbers, ``data`` an array of :data:`BODY_DATA`,
    the same array while the body's data are), or None where the scene is not that (free
    points, several free bodies, fenders, pile guides, hull members)."""
    if case.free_points or result.fenders or result.guides:
        return None
    free = [bi for bi, body in enumerate(case.bodies) if body.free]
    if len(free) != 1 or free[0] >= len(result.bodies):
        return None
    body = case.bodies[free[0]]
    if body.hull:
        return None
    pose = result.bodies[free[0]]
    loads, largest = body_loads(result, case, body.name)
    inputs = [pose["x_m"], pose["y_m"], pose["z_m"], math.radians(pose["roll_deg"]),
              math.radians(pose["pitch_deg"]), math.radians(pose["yaw_deg"]),
              *loads, largest]
    env = case.environment
    key = (body.mass, body.centre_of_gravity, body.hydrostatics, body.free, body.stiffness,
           body.position, body.fixed_to, body.orientation_deg, env.gravity, env.water_density,
           env.water_level, result.certificate.tolerance)
    hit = problem.derived.get("audit_body_data")
    if hit is None or hit[0] != key:
        g, rho, hydro = env.gravity, env.water_density, body.hydrostatics
        weight = 0.0 if body.mass is None else body.mass * g
        data = np.array([weight, *(body.centre_of_gravity if body.mass is not None
                                   else (0.0, 0.0, 0.0)),
                         0.0 if hydro is None else rho * g * hydro.displaced_volume,
                         *((0.0, 0.0, 0.0) if hydro is None else hydro.metacentre),
                         0.0 if hydro is None else rho * g * hydro.waterplane_area,
                         env.water_level,
                         0.5 * max(10.0 * result.certificate.tolerance, FORCE_REL),
                         *(1.0 if dof in body.free else 0.0 for dof in _DOFS),
                         *(np.ravel(np.asarray(body.stiffness, float))
                           if body.stiffness is not None else np.zeros(36)),
                         *body.rest_position(env.water_level),
                         *(math.radians(a) for a in body.orientation_deg)],
                        float)
        data.flags.writeable = False
        hit = problem.derived["audit_body_data"] = (key, data)
    return body.name, inputs, hit[1]


def symbolic_balance(ends, t_lines, pose, data):
    """1 where the body balances by half the margin :func:`body_findings` allows, else 0
    (a NaN fails): the same sums, written as a CasADi expression for the compiled verdict.
    ``ends``: ``(on, position, force)`` per line end (``on`` 1 where the end is on the
    body); ``t_lines`` the largest line tension; ``pose`` and ``data`` as
    :func:`one_body_inputs` gives them."""
    import casadi as ca

    x, y, z, roll, pitch, yaw = (pose[i] for i in range(6))
    weight, buoyancy, kwp, level, half_tol = data[0], data[4], data[8], data[9], data[10]
    force, moment, radius2 = [pose[6], pose[7], pose[8]], [pose[9], pose[10], pose[11]], 0.0
    for on, (px, py, pz), (fx, fy, fz) in ends:
        ax, ay, az = px - x, py - y, pz - z
        force = [a + ca.if_else(on, b, 0.0) for a, b in zip(force, (fx, fy, fz))]
        moment = [a + ca.if_else(on, b, 0.0) for a, b in
                  zip(moment, (ay * fz - az * fy, az * fx - ax * fz, ax * fy - ay * fx))]
        radius2 = ca.fmax(radius2, ca.if_else(on, ax * ax + ay * ay, 0.0))
    cr, sr, cp, sp, cy, sy = (ca.cos(roll), ca.sin(roll), ca.cos(pitch), ca.sin(pitch),
                              ca.cos(yaw), ca.sin(yaw))
    r0 = (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr)
    r1 = (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr)
    heave = -kwp * (z - level)
    force[2] = force[2] + heave
    scale = ca.fmax(ca.fmax(t_lines, pose[12]), ca.fmax(weight, ca.fabs(buoyancy)))
    scale = ca.fmax(scale, ca.fabs(heave))
    for f, at in ((-weight, (data[1], data[2], data[3])), (buoyancy, (data[5], data[6], data[7]))):
        rx = r0[0] * at[0] + r0[1] * at[1] + r0[2] * at[2]
        ry = r1[0] * at[0] + r1[1] * at[1] + r1[2] * at[2]
        force[2], moment[0], moment[1] = force[2] + f, moment[0] + ry * f, moment[1] - rx * f
    mx, my, mz = moment
    generalized = (*force, r0[0] * mx + r1[0] * my - sp * mz, -sy * mx + cy * my, mz)
    # The extra springs act on the generalized coordinates, from the case's pose.
    moved = [pose[j] - data[_SPRING_REST + j] for j in range(6)]
    generalized = [g - sum(data[_STIFFNESS + 6 * k + j] * moved[j] for j in range(6))
                   for k, g in enumerate(generalized)]
    tol = half_tol * scale
    arm = 10.0 * ca.fmax(ca.sqrt(radius2), 1.0)
    ok = 1
    for k, g in enumerate(generalized):
        ok = ca.logic_and(ok, ca.logic_or(data[11 + k] == 0,
                                          ca.fabs(g) <= (tol if k < 3 else tol * arm)))
    return ok


_END_ROWS = LockedLRU(256)


def _end_rows(lines) -> dict:
    """Per ``("body", name)`` and ``("point", name)``: the rows of the line ends on it in
    the interleaved end arrays (ends A first, then ends B), once per lines tuple."""
    hit = _END_ROWS.get(id(lines))
    if hit is not None and hit[0] is lines:
        return hit[1]
    found: dict = {}
    for side in (0, 1):
        for i, line in enumerate(lines):
            end = (line.a, line.b)[side]
            for kind, name in (("body", end.body), ("point", end.point)):
                if name is not None:
                    found.setdefault((kind, name), []).append(2 * i + side)
    found = {key: np.array(value, int) for key, value in found.items()}
    _END_ROWS.put(id(lines), (lines, found))
    return found


def _about_angle_axes(R: np.ndarray, yaw: float, moment) -> tuple:
    """A moment's components about the global axes roll, pitch and yaw turn about (z-y-x
    angles), for the body's rotation ``R = Rz Ry Rx``: ``Rz Ry e_x`` (R's first column, as
    ``Rx`` keeps ``e_x``), ``Rz e_y`` and ``e_z``."""
    mx, my, mz = moment
    return (R[0, 0] * mx + R[1, 0] * my + R[2, 0] * mz,
            -math.sin(yaw) * mx + math.cos(yaw) * my, mz)


def _hydrostatic_wrenches(body, origin, R, env):
    """Weight, buoyancy and heave restoring of a body, as ``(force, moment)`` pairs of
    3-sequences; ``origin`` above the still-water level."""
    g, rho = env.gravity, env.water_density
    out = []

    def vertical(fz, at_body):       # a vertical force at a body-frame point
        rx, ry, _ = _turn(R, at_body)
        return (0.0, 0.0, fz), (ry * fz, -rx * fz, 0.0)

    if body.mass is not None:
        out.append(vertical(-body.mass * g, body.centre_of_gravity))
    hydro = body.hydrostatics
    if hydro is not None:
        out.append(vertical(rho * g * hydro.displaced_volume, hydro.metacentre))
        out.append(((0.0, 0.0, -rho * g * hydro.waterplane_area * origin[2]),
                    (0.0, 0.0, 0.0)))
    for member in body.hull:
        volume, centroid = _member_volume(member, origin, R)
        out.append(vertical(rho * g * volume, centroid))
    return out


def _turn(R, v) -> tuple:
    """``R @ v`` of a 3-vector, as floats."""
    x, y, z = (float(c) for c in v)
    return tuple(R[i, 0] * x + R[i, 1] * y + R[i, 2] * z for i in range(3))


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


def wall_findings(result, case) -> list[str]:
    """No body is inside a quay wall or a pile: per fender, the hull behind it (its height
    back from the face, in the body) is not inside what the fender bears on by more than
    the compliance the hull bears with (:data:`~moorsolve.constants.HULL_STIFFNESS`); a
    rigid fender's face not at all. Recomputed from the reported pose and the case's
    geometry. One sentence per defect (empty: none)."""
    out = []
    c = case.contacts
    poses = {b["name"]: b for b in result.bodies}
    reported = {f["name"]: f for f in result.fenders}
    length = max(case.environment.depth, 1.0)
    tol = max(1e-6, 100.0 * result.certificate.tolerance) * length
    for fender in c.fenders:
        rigid = fender.law.kind == "rigid"
        if not rigid and fender.height is None:
            continue
        body = case.body_named(fender.body)
        pose = poses.get(body.name)
        if pose is None:
            continue
        r = np.array([pose["x_m"], pose["y_m"], pose["z_m"]])
        R = rotation(*(math.radians(pose[k]) for k in ("roll_deg", "pitch_deg", "yaw_deg")))
        r0 = np.array(body.rest_position(case.environment.water_level))
        R0 = rotation(*(math.radians(a) for a in body.orientation_deg))
        at = np.asarray(fender.at, float)
        wall = c.wall_named(fender.wall) if fender.wall else None
        pile = c.pile_named(fender.pile) if fender.pile else None
        if fender.mounted == "structure":
            # The hull's side where it meets the fender's face at rest.
            hull_b = R0.T @ (at - r0)
        else:
            face0 = r0 + R0 @ at
            if wall is not None:
                away = np.asarray(wall.normal, float)
            else:
                d = face0[:2] - np.asarray(pile.position, float)
                away = np.array([d[0], d[1], 0.0]) / max(np.hypot(d[0], d[1]), 1e-300)
            hull_b = at + (0.0 if rigid else fender.height) * (R0.T @ away)
        point = r + R @ hull_b
        if wall is not None:
            gap = float(np.dot(wall.normal, point - np.asarray(wall.point, float)))
        else:
            gap = float(np.hypot(*(point[:2] - np.asarray(pile.position, float)))
                        - pile.radius)
        f = reported.get(fender.name, {})
        give = 0.0 if rigid else f.get("hull_reaction_N", 0.0) / HULL_STIFFNESS
        if -gap > give + tol:
            what = "its face" if rigid else "the hull behind it"
            out.append(f"fender {fender.name}: {what} is {-gap:.4g} m inside "
                       f"{fender.wall or fender.pile} (at most {give + tol:.2g} m allowed): "
                       f"body {body.name} is inside the structure it bears on")
    return out
