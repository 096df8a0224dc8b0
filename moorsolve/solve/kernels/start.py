"""Starting points: the scene at its case-file pose with every line in a closed-form state.

A start with all lines slack gives a singular Jacobian, and the pretensioned rest state keeps
a body on the right equilibrium branch, so every line starts from
the inextensible closed-form catenary between its ends at the case pose (a multi-segment or
lumped line from the equivalent uniform line), bodies at their case pose and free points
where the case puts them. :func:`rest_point` solves the unloaded state once per layout.
"""

from __future__ import annotations

import dataclasses
import math
import numpy as np

from ...model import Case
from ...model.build_network import end_position as case_end_position
from ...physics.catenary import LegKind
from ...physics.closed_form import initial_state
from ...physics.profile import leg_profile
from ..assembly.prepared import parameter_vector
from ..lines.line_kinds import can_ground, discretised, line_kind
from ...concurrency import LockedLRU
from ..assembly.prepared import geometry_key, line_kinds_of, per_case
from ..lines.stretch_params import start_ea

#: Closed-form line states by scene (structure and parameters).
_REST_STATES = LockedLRU(256)


def end_positions(case: Case, line) -> tuple:
    """Global positions [m] of a line's ends A and B at the case-file pose."""
    bodies = {b.name: b for b in case.bodies}
    return (case_end_position(line.a, bodies), case_end_position(line.b, bodies))


def lower_upper(case: Case, line, kind=None) -> tuple:
    """The block's lower and upper end positions at the case pose, and the segments from
    the lower end."""
    kind = kind or line_kind(case, line)
    a, b = end_positions(case, line)
    if kind.flipped:
        return b, a, line.segments[::-1], tuple(reversed(line.joint_clumps))
    return a, b, line.segments, line.joint_clumps


def equivalent_line(case: Case, line, lower) -> tuple:
    """A uniform inextensible line of the same length and total weight (clumps spread):
    ``(LegKind, w)``."""
    total = sum(seg.line_type.weight_in_water * seg.length for seg in line.segments)
    total += sum(c.weight for c in line.joint_clumps if c is not None)
    w = total / line.length
    bed = case.environment.seabed_z(lower[0], lower[1])
    on_seabed = lower[2] <= bed + 1e-9 * max(case.environment.depth, 1.0)
    return LegKind(elastic=False, contact=on_seabed and w > 0, neutral=(w == 0)), w


#: Typical working strain of a hawser, for the tension scale of a scene of weightless lines.
HAWSER_STRAIN = 0.01


#: Scales by geometry (:func:`.prepared.geometry_key`), for scenes without lumped lines.
_SCALES = LockedLRU(256)


@per_case(load_independent=True)
def scales(case: Case) -> tuple:
    """Typical tension [N] and length [m] of the scene, for scaling the unknowns.

    Without a lumped line (whose flow load counts) they depend on the geometry alone, and
    are remembered by it."""
    if any(kind.discrete for kind in line_kinds_of(case)):
        return _scales(case)
    key = geometry_key(case)
    found = _SCALES.get(key)
    if found is None:
        found = _scales(case)
        _SCALES.put(key, found)
    return found


def _scales(case: Case) -> tuple:
    tensions = [sum(abs(seg.line_type.weight_in_water) * seg.length for seg in line.segments)
                + sum(abs(c.weight) for c in line.joint_clumps if c is not None)
                for line in case.lines]
    tensions += [math.hypot(max(u, 0.0), V) for u, V in rest_line_states(case)]
    tensions += [line_load(case, line)[0] * line.length for line in case.lines
                 if discretised(case, line)]
    # A free point's net weight (a clump, a buoy, a pendulum's bob) hangs on its lines.
    env = case.environment
    tensions += [abs(env.gravity * (p.mass - env.water_density * p.volume))
                 for p in case.points if p.free]
    # A weightless line (a hawser) has no weight to set a tension: one percent of its
    # axial stiffness, a typical working strain; but only where nothing in the scene weighs
    # (a 10 kg bob on a stiff weightless line would be solved against 1e7 N otherwise).
    if not any(t > 0 for t in tensions):
        tensions += [HAWSER_STRAIN * start_ea(line.line_type) for line in case.lines
                     if line.line_type.weight_in_water == 0 and line.line_type.elastic
                     and not line.multi_segment]
    if not any(t > 0 for t in tensions):
        tensions += _held_by_contacts(case)
    force = max(max(tensions, default=1.0), 1.0)
    return force, max(case.environment.depth, 1.0)


def _held_by_contacts(case: Case) -> list:
    """Force scales [N] of a scene whose lines carry nothing to scale by (none, or slack
    weightless ones): what its fenders and pile guides hold, the bodies' weights and the
    fenders' reactions at their rated deflections."""
    out = [case.environment.gravity * body.mass for body in case.bodies
           if body.mass is not None]
    for fender in case.contacts.fenders:
        law = fender.law
        if law.kind == "linear" and fender.rated_deflection is not None:
            out.append(law.stiffness * fender.rated_deflection)
        elif law.kind == "table":
            out.append(law.reactions[-1])
    return out


def rest_line_states(case: Case) -> list:
    """Closed-form starting ``(u, V)`` of every line with the scene at its case pose.

    Remembered by everything they depend on (:func:`.prepared.geometry_key`: not the
    loads): the bisections cost milliseconds, far more than a compiled Newton solve.
    """
    key = geometry_key(case)
    states = _REST_STATES.get(key)
    if states is None:
        states = tuple(_compute_rest_states(case))
        _REST_STATES.put(key, states)
    return list(states)


def _compute_rest_states(case: Case) -> list:
    states = []
    for line in case.lines:
        kind = line_kind(case, line)
        lower, upper, _, _ = lower_upper(case, line, kind)
        X = math.hypot(upper[0] - lower[0], upper[1] - lower[1])
        Z = float(upper[2] - lower[2])
        if line.multi_segment or kind.discrete or kind.lifted:
            eq_kind, w = equivalent_line(case, line, lower)
            states.append(initial_state(eq_kind, X, Z, line.length, w, None))
            continue
        lt = line.line_type
        block = kind.block
        if block.sloped and X > 0:
            # As on a flat seabed under the upper end's height above the slope (a shear of
            # the line's plane), the touchdown's vertical force shifted by H t.
            env = case.environment
            if env.seabed.bathymetry is not None:
                # The first seabed plane's slope (solve/lines/bathymetry.py): the chord to the
                # seabed under the upper end.
                t = (env.seabed_z(upper[0], upper[1]) - env.seabed_z(lower[0], lower[1])) / X
            else:
                g = env.seabed.gradient
                t = (g[0] * (upper[0] - lower[0]) + g[1] * (upper[1] - lower[1])) / X
            u, V = initial_state(dataclasses.replace(block, sloped=False), X, Z - t * X,
                                 line.length, lt.weight_in_water, start_ea(lt))
            states.append((u, V + max(u, 0.0) * t))
            continue
        # A buoyant line solved from its lower end starts from its depth there.
        gap = -lower[2] if block.surface and not block.from_fairlead else 0.0
        states.append(initial_state(block, X, Z, line.length, lt.weight_in_water,
                                    start_ea(lt), max(gap, 0.0)))
    return states


def _multi_start(case, line, kind, lower, upper, segments, clumps, u, V, force_scale) -> list:
    """Closed-form start of a multi-segment line from its equivalent uniform line.

    The joints are put where the equivalent catenary has their arc length; the segments'
    top vertical tensions follow from the top end's by subtracting the weights below it
    (zero on the seabed); a joint on the seabed starts pressed onto it by its clump.
    """
    eq_kind, w_eq = equivalent_line(case, line, lower)
    X = math.hypot(upper[0] - lower[0], upper[1] - lower[1])
    Z = float(upper[2] - lower[2])
    if eq_kind.neutral:
        prof = dict(s=np.linspace(0, line.length, 51), x=np.linspace(0, X, 51),
                    z=np.linspace(0, Z, 51))
    else:
        prof = leg_profile(eq_kind, H=max(u, 0.0), V=V, L=line.length, w=w_eq, ea=None,
                           mu=0.0, X=X, Z=Z, n=201)
    z_bed = case.environment.seabed_z(lower[0], lower[1])
    arc = np.cumsum([seg.length for seg in segments])[:-1]
    xi = np.interp(arc, prof["s"], prof["x"])
    z = lower[2] + np.interp(arc, prof["s"], prof["z"])
    weights = [c.weight if c is not None else 0.0 for c in clumps]
    grounded = z <= z_bed + 1e-6 * max(case.environment.depth, 1.0)
    Vs = [0.0] * len(segments)
    Vs[-1] = V
    for k in range(len(segments) - 2, -1, -1):
        above = segments[k + 1]
        Vs[k] = Vs[k + 1] - above.line_type.weight_in_water * above.length - weights[k]
    joints = []
    block = kind.block
    for j in range(block.n_joints):
        if grounded[j] and can_ground(block.segments[j]):
            sigma = -(max(weights[j], 0.0) + 1e-6 * force_scale)
        elif z[j] >= 0 and block.segments[j].block == "floating":
            # A joint afloat starts held down by the surface (the mirror image).
            sigma = max(-weights[j], 0.0) + 1e-6 * force_scale
        else:
            sigma = Vs[j]
        joints += [float(xi[j]), float(sigma)]
    if block.reversed_top:
        top = segments[-1]
        V = top.line_type.weight_in_water * top.length - V
    return [u, V] + joints


def line_load(case: Case, line) -> tuple:
    """Typical load per length on a lumped-node line [N/m]: its size and unit direction.

    The mean submerged weight (clumps spread) and the normal flow force of the current at
    mid-depth on a line across it.
    """
    a, _ = end_positions(case, line)
    _, w = equivalent_line(case, line, a)
    env = case.environment
    cur = env.current
    ux, uy = cur.velocity(-env.depth / 2)
    speed = math.hypot(ux, uy)
    drag = sum(0.5 * env.water_density * (seg.line_type.diameter or 0.0)
               * (seg.line_type.drag.normal if seg.line_type.drag else 0.0) * speed**2
               * seg.length for seg in line.segments) / line.length
    th = math.atan2(uy, ux)
    q = np.array([drag * math.cos(th), drag * math.sin(th), -w])
    size = float(np.linalg.norm(q))
    return size, (q / size if size > 0 else np.array([0.0, 0.0, -1.0]))


def _discrete_start(case: Case, line, kind, u: float, V: float, force_scale: float) -> list:
    """Start of a lumped-node line from a closed-form catenary under its typical load.

    Without a significant flow force the nodes sit on the equivalent line's catenary with its
    seabed contact. When the flow force is a tenth of the weight or more, the line is drawn
    as the catenary of the combined load (weight plus flow force at mid-depth) in the plane
    of the chord and that load, which keeps a weightless tether in a current from starting
    straight and tensionless. Element tensions are the catenary's at the element midpoints;
    a node on or below the seabed starts pressed onto it by its share of the weight.
    """
    A, F = (np.asarray(v, dtype=float) for v in end_positions(case, line))
    eq_kind, w_eq = equivalent_line(case, line, A)
    env = case.environment
    size, down = line_load(case, line)
    drag_led = size > 0 and abs(size * down[2] + w_eq) >= 0.1 * max(abs(w_eq), 1e-300) \
        and abs(down[2]) < 0.995
    if drag_led:
        chord = F - A
        along = float(chord @ down)
        perp = chord - along * down
        Xp = float(np.linalg.norm(perp))
        e_perp = perp / Xp if Xp > 1e-12 else np.cross(down, [0.0, 0.0, 1.0])
        kind_q = LegKind(elastic=False, contact=False)
        Hq, Vq = initial_state(kind_q, Xp, -along, line.length, size, None)
        prof = leg_profile(kind_q, H=max(Hq, 0.0), V=Vq, L=line.length, w=size, ea=None,
                           mu=0.0, X=Xp, Z=-along, n=401)
        points = (A[None, :] + prof["x"][:, None] * e_perp[None, :]
                  - prof["z"][:, None] * down[None, :])
    else:
        X = math.hypot(*(F - A)[:2])
        ux, uy = ((F[0] - A[0]) / X, (F[1] - A[1]) / X) if X > 1e-12 else (1.0, 0.0)
        if A[2] > F[2] or not eq_kind.contact:
            # A line hanging from both ends: the equivalent catenary from end A.
            eq_kind = LegKind(elastic=False, contact=False, neutral=eq_kind.neutral)
            u, V = initial_state(eq_kind, X, F[2] - A[2], line.length, w_eq, None)
        prof = leg_profile(eq_kind, H=max(u, 0.0), V=V, L=line.length, w=w_eq, ea=None,
                           mu=0.0, X=X, Z=F[2] - A[2], n=401)
        points = np.stack([A[0] + ux * prof["x"], A[1] + uy * prof["x"], A[2] + prof["z"]],
                          axis=1)
    lengths, weights = [], []
    for seg, m in zip(line.segments, kind.block.elements):
        lengths += [seg.length / m] * m
        weights += [seg.line_type.weight_in_water * seg.length / m] * m
    arc = np.concatenate([[0.0], np.cumsum(lengths)])
    mid = (arc[1:] + arc[:-1]) / 2
    floor = max(1e-6 * force_scale, 0.05 * size * line.length)
    tensions = np.maximum(np.interp(mid, prof["s"], prof["tension"]), floor)
    length_scale = max(env.depth, 1.0)
    k_N = force_scale / length_scale
    block = list(tensions)
    for j in range(1, kind.block.n_elements):
        px, py, z = (float(np.interp(arc[j], prof["s"], points[:, c])) for c in range(3))
        above = z - env.seabed_z(px, py)
        if above <= 1e-6 * max(env.depth, 1.0):
            zeta = -max((weights[j - 1] + weights[j]) / 2, 1e-6 * force_scale) / k_N
        else:
            zeta = above
        block += [px, py, zeta]
    return block


def initial_point(problem, case: Case) -> np.ndarray:
    """Scaled starting vector: bodies at their case pose, points where the case puts them,
    lines in their closed-form states.

    Remembered per problem and load-free parameters (in the problem's own cache, under its
    lock).
    """
    # A lumped line starts from a shape drawn under the current: its start depends on
    # the flow too. Every other start depends on the geometry alone.
    key = b"start:" + (parameter_vector(case).tobytes() if problem.any_discrete
                       else geometry_key(case)[1])
    with problem.lock:
        cached = problem.start_cache.get(key)
    if cached is not None:
        return cached.copy()
    x = np.zeros(problem.n_x)
    for j, (owner, index, dof) in enumerate(problem.nodes):
        if owner == "body":
            body = case.bodies[index]
            # A floating body starts at its rest: risen with the tide, where it floats as
            # placed.
            value = dict(zip(("surge", "sway", "heave"),
                             body.rest_position(case.environment.water_level)))
            value.update(zip(("roll", "pitch", "yaw"),
                             (math.radians(a) for a in body.orientation_deg)))
            x[j] = value[dof]
        else:
            point = case.free_points[index]
            px, py, pz = point.position
            if dof == "x":
                x[j] = px
            elif dof == "y":
                x[j] = py
            else:
                above = pz - case.environment.seabed_z(px, py)
                net = case.environment.gravity * (
                    point.mass - case.environment.water_density * point.volume)
                k_N = problem.force_scale / problem.length_scale
                x[j] = above if above > 1e-6 * problem.length_scale else \
                    -max(net, 1e-6 * problem.force_scale) / k_N
    for i, (u, V) in enumerate(rest_line_states(case)):
        start = problem.line_offsets[i]
        kind = problem.kinds[i]
        line = case.lines[i]
        if kind.multi:
            lower, upper, segments, clumps = lower_upper(case, line, kind)
            block = _multi_start(case, line, kind, lower, upper, segments, clumps, u, V,
                                 problem.force_scale)
        elif kind.discrete:
            block = _discrete_start(case, line, kind, u, V, problem.force_scale)
        else:
            block = [u, V]
        x[start: start + len(block)] = block
    x = x / problem.x_scale
    problem.keep_start(key, x)
    return x.copy()
