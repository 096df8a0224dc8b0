"""Turn a solved point into a :class:`~.classes.Result`: bodies, points, every line's end
forces, states and profile, the loads and the notes.

Every reported quantity comes from the same solution vector through the problem's report
functions; the profiles are drawn from the same tensions with the closed forms of
:mod:`moorsolve.physics.catenary` in each line's vertical plane (multi-segment lines joint by
joint, lumped-node lines through their nodes).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...model import Case
from ...physics.kinematics import wrap_degrees
from ..lines.bathymetry import plane_slices
from ..contact.results import contact_results, hawser_results
from .fibre import fibre_grounded, fibre_notes
from ..lines.line_kinds import SEGMENT_COLUMNS
from ..assembly.prepared import line_facts
from .profile_batch import ProfileBatch
from ..assembly.problem import LINE_COLUMNS
from .classes import LegList, Result
from .leg_results import discrete_result, line_notes, multi_result, single_result

_PROFILE_POINTS = 51


def build_result(problem, case: Case, x, p, cert, certified, solver="ipopt", notes=(),
                 stability=None, post=None) -> Result:
    """The :class:`Result` of the scaled point ``x`` of ``problem`` at parameters ``p``.

    ``post`` is :meth:`EquilibriumProblem.post` at ``x`` when the caller has it. The legs
    are made from its arrays when first read, and a one-segment line's profile when it is
    first read (:class:`~.classes.LegList`, :class:`~.classes.LazyProfile`): the same
    numbers, paid for only by a caller that reads them.
    """
    x = np.array(x, dtype=float)        # fresh: the Result's state, non-finite entries 0
    if not np.isfinite(x).all():
        x[~np.isfinite(x)] = 0.0
    if post is None:
        post = problem.post(x, p)
    poses, point_pos, load_vec = post["poses"], post["points"], post["loads"]
    xp = x * problem.x_scale
    tables = post["lines"], post["segments"], post["nodes"]
    grid = case.environment.seabed.bathymetry is not None
    planes = plane_slices(problem) if grid else None
    p = np.ravel(np.asarray(p, float)) if grid or problem.contacts else p

    def make_legs():
        table, seg_table, node_table = (np.atleast_2d(t) for t in tables)
        batch = ProfileBatch(_PROFILE_POINTS)
        for i, (line, kind) in enumerate(zip(case.lines, problem.kinds)):
            row = dict(zip(LINE_COLUMNS, table[i].tolist()))
            u = float(xp[problem.line_offsets[i]])
            if kind.discrete:
                nodes = np.array([r for r in node_table if int(r[0]) == i])
                lr = discrete_result(case, line, kind, row, nodes)
            elif kind.multi:
                rows = [dict(zip(SEGMENT_COLUMNS, r.tolist()))
                        for r in seg_table if int(r[0]) == i]
                lr = multi_result(case, line, kind, row, rows, u)
            else:
                # On a grid the line's own plane (solve/lines/bathymetry.py) gives its slope.
                plane = p[planes[i]][1:] if grid else None
                lr = single_result(case, line, kind, row, u, problem.contact_stiffness,
                                    cert, batch, plane)
            if fibre:
                lr = dataclasses.replace(lr, fibre_grounded_m=fibre_grounded(case, line, lr))
            yield lr

    facts = line_facts(case)
    fibre = facts.fibre
    legs = LegList(make_legs)
    poses = poses.ravel().tolist()
    bodies = []
    for bi, body in enumerate(case.bodies):
        q = poses[6 * bi: 6 * bi + 6]
        roll0, pitch0, yaw0 = body.orientation_deg
        d = [q[0] - body.position[0], q[1] - body.position[1], q[2] - body.position[2],
             q[3] - math.radians(roll0), q[4] - math.radians(pitch0),
             q[5] - math.radians(yaw0)]
        bodies.append({"name": body.name, "x_m": q[0], "y_m": q[1], "z_m": q[2],
                       "roll_deg": math.degrees(q[3]), "pitch_deg": math.degrees(q[4]),
                       "yaw_deg": wrap_degrees(math.degrees(q[5])),
                       "offset": {"x_m": d[0], "y_m": d[1], "z_m": d[2],
                                  "roll_deg": math.degrees(d[3]),
                                  "pitch_deg": math.degrees(d[4]),
                                  "yaw_deg": wrap_degrees(math.degrees(d[5]))}})
    body = None
    if case.body is not None:
        off = bodies[0]["offset"]
        body = {"x_m": off["x_m"], "y_m": off["y_m"], "yaw_deg": off["yaw_deg"]}
        if case.form == "network":
            body = dict(body, z_m=off["z_m"], roll_deg=off["roll_deg"],
                        pitch_deg=off["pitch_deg"])
    points = []
    for pi, point in enumerate(case.free_points):
        xyz = point_pos.ravel()[3 * pi: 3 * pi + 3]
        j = problem.nodes.index(("point", pi, "zeta"))
        reaction = max(-float(xp[j]), 0.0) * problem.force_scale / problem.length_scale
        points.append({"name": point.name, "x_m": float(xyz[0]), "y_m": float(xyz[1]),
                       "z_m": float(xyz[2]), "seabed_reaction_N": reaction})
    loads = {}
    lv = load_vec.ravel().tolist()
    for k, name in enumerate(problem.load_names):
        f = lv[6 * k: 6 * k + 6]
        loads[name] = [f[0], f[1], f[5]] if case.form == "legs" else f
    notes = list(notes) + line_notes(case, problem, legs)
    if fibre:
        notes += fibre_notes(case, legs)
    effects = [*problem.effects, *facts.clump_effects]
    fenders, guides = (contact_results(problem, case, x, p, np.asarray(poses))
                       if problem.contacts else ((), ()))
    notes += [f"guide {g['name']}: the collar is {g['height_m'] - g['pile_top_m']:.2f} m "
              f"above the top of pile {g['pile']} (it would come off the pile)"
              for g in guides if not g["on_pile"]]
    return Result(converged=certified, solver=solver, certificate=cert, effects=effects,
                  body=body, legs=legs, loads=loads, case_name=case.name, state=x,
                  notes=tuple(notes), case=case, bodies=tuple(bodies),
                  points=tuple(points), stability=stability, form=case.form,
                  fenders=fenders, guides=guides,
                  hawsers=hawser_results(case, legs) if facts.hawsers else ())


def hull_out_of_range(problem, x, p, post=None) -> list:
    """``"body B: hull member j ..."`` for every exact hull member whose formula does not
    hold at the scaled point ``x`` (the waterplane crosses its bottom or top face);
    ``post`` is :meth:`EquilibriumProblem.post` at ``x`` when the caller has it."""
    case = problem.case
    if not any(body.hull for body in case.bodies):
        return []
    if post is None:
        post = problem.post(x, p)
    flags = np.asarray(post["hull_in_range"], dtype=float).ravel()
    out, k = [], 0
    for body in case.bodies:
        for j, _ in enumerate(body.hull):
            if flags[k] < 0.5:
                out.append(f"body {body.name}: hull member {j} has the waterplane across its "
                           "bottom or top face at this pose, where its exact buoyancy does "
                           "not hold (extend the member or give the linear hydrostatics)")
            k += 1
    return out


__all__ = ["build_result", "hull_out_of_range"]
