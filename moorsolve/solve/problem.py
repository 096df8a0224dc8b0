"""Build the coupled equilibrium of a scene (bodies, points, lines) as one CasADi problem.

Unknowns, in this order:

- the *nodes*: every free degree of freedom of every body (its pose ``x, y, z`` [m] and
  ``roll, pitch, yaw`` [rad], absolute, starting from the case-file pose) and every free
  point's ``x, y`` and a signed height ``zeta`` above the seabed: the point is at
  ``z = seabed + max(zeta, 0)`` and the seabed pushes it up with ``max(-zeta, 0)`` times the
  scene's stiffness scale (exact complementarity, the device of the lumped-node lines);
- then every line's own unknowns (:mod:`.lines`).

Equations: every line's residuals first, then the balance of every node: for a body the
generalized forces of its free DOFs (:func:`~moorsolve.physics.kinematics.generalized_forces`:
force components and moments about the axes its angles turn about), for a point the three
force components. The problem is square; IPOPT solves it as a feasibility NLP and the
compiled Newton kernel (:mod:`.newton`) solves the same residuals.

On a body act: the lines attached to it (at ``r + R p``), its weight at the centre of
gravity, its hydrostatics (the linear model or exact hull members,
:mod:`moorsolve.physics.hydrostatics`), its extra springs, its flow load models at their
centres (:func:`.body_loads.body_loads_3d`) and its constant force. On a free point: its
lines, its net weight ``g (m - rho V)`` and the seabed. Everything that may change between
solves of one structure is a parameter (:mod:`.layout`), so one build serves a whole sweep.
"""

from __future__ import annotations

import dataclasses
import math
import threading

import casadi as ca
import numpy as np

from ..model import DOFS, Case
from ..physics.hydrostatics import linear_buoyancy, member_buoyancy, weight
from ..physics.kinematics import cross, generalized_forces, rotation_matrix
from . import body_loads as body_load_models
from .concurrency import SYMBOLIC_LOCK
from .discrete import discrete_leg
from .layout import (BODY_PARAMS, ENV_PARAMS, LINE_PARAMS, MEMBER_PARAMS, SEABED_PARAMS,
                     build_layout, parameter_vector)
from .contact import add_contacts, contact_points, element_reactions
from .stretch_params import line_laws
from .lines import (LineKind, closing_force, line_kinds, multi_block, plane_geometry,
                    seabed_height, single_block)
from .prepared import HashedKey, line_ends_of, line_kinds_of, per_case

#: Columns of the lines table of ``EquilibriumProblem.report``: the horizontal and vertical
#: tension at end B (``H``, ``VF``: the upward force B exerts on the line), the horizontal
#: pull on end A and its upward pull (``HA``, ``VA``); the grounded length and the
#: horizontal extent of the part rising to the upper end [m]; the line's mismatch as a force
#: and 0 (multi-segment and lumped lines) or its span residuals [m]; its spans ``X``, ``Z``;
#: end B's global x, y; the horizontal force on end B; the 2x2 block of a single line
#: (column-major); end A's global position and end B's z; the forces on A and B [N].
LINE_COLUMNS = ("H", "VF", "HA", "VA", "grounded", "suspended_x", "rX", "rZ", "X", "Z",
                "bx", "by", "fx", "fy", "J00", "J10", "J01", "J11",
                "ax", "ay", "az", "bz", "FAx", "FAy", "FAz", "FBx", "FBy", "FBz", "floating")
ROTATIONS = ("roll", "pitch", "yaw")
#: Outputs of :meth:`EquilibriumProblem.post_function`: the certificate, the condensed
#: stiffness and its stability test, the seven outputs of ``report``, and the segment and
#: node tables.
POST_OUTPUTS = ("certificate", "stiffness", "clearly_stable", "lines", "unbalanced",
                "loads", "poses", "points", "wrenches", "hull_in_range", "segments", "nodes")
POINT_DOFS = ("x", "y", "zeta")


def _body_radius(case: Case) -> float:
    arms = [math.hypot(end.position[0], end.position[1])
            for line in case.lines for end in (line.a, line.b) if end.body is not None]
    return max([1.0] + arms)


class EquilibriumProblem:
    """The symbolic problem of one scene structure, built once.

    Attributes
    ----------
    kinds : list of LineKind
    layout : ParameterLayout
    nodes : list of (str, int, str)
        The node unknowns: ``("body", body index, dof)`` or ``("point", free-point index,
        "x" | "y" | "zeta")``, in order.
    free : tuple of str
        The DOF name of every node unknown (``"x"``, ``"y"``, ``"zeta"`` for points).
    rotational : tuple of bool
        Whether each node unknown is an angle (its balance is a moment).
    n_q, n_x, n_p, n_legs : int
        Numbers of node unknowns, all unknowns, parameters and lines.
    line_offsets : list of int
        Index in ``x`` of each line's first unknown (also ``leg_offsets``).
    residual, jacobian, residual_jacobian, report, segment_report, node_report, certificate,
    summary : casadi.Function
        Of ``(x, p)`` with ``x`` scaled by ``x_scale``. ``report`` gives the lines table
        (:data:`LINE_COLUMNS`), the unbalanced generalized forces of every body (6 each)
        and free point (3 each), every load (force and moment, 6 each), every body's pose
        (6 each: m and rad), every free point's position, every body's resultant
        wrench (force and moment about its origin, global axes, 6 each), and per exact hull
        member 1 where its buoyancy formula is exact at the pose, else 0.
    effects : list of str
        The physical effects this problem simulates.
    """

    def __init__(self, case: Case, force_scale: float, length_scale: float):
        self.case = case
        self.kinds = line_kinds(case)
        #: Whether every line is one segment (its report is one row of the line table), and
        #: whether any is a lumped-node line (whose start depends on the flows).
        self.all_single = all(k.single for k in self.kinds)
        self.any_discrete = any(k.discrete for k in self.kinds)
        self.layout = build_layout(case, self.kinds)
        self.n_legs = len(case.lines)
        self.force_scale = force_scale
        self.length_scale = length_scale
        self.moment_scale = force_scale * max(length_scale, _body_radius(case))
        #: The stiffness [N/m] at which complementarities weigh a force against a length
        #: (hawsers, contacts; :mod:`moorsolve.physics.contact`), and the symbol of their
        #: Jacobian smoothing [m] (:meth:`step_jacobian`).
        self.contact_stiffness = force_scale / length_scale
        self.smoothing_symbol = ca.SX.sym("eps")
        #: The smoothing of compliant fenders' contact switch, in the step Jacobian only
        #: (in IPOPT's residual it would push touching fenders apart by their stiffness times
        #: the smoothing). It anticipates a closing contact's reaction, and the friction
        #: that reaction will carry.
        self.hinge_symbol = ca.SX.sym("eps_hinge")
        self.nodes, scale = [], []
        for bi, body in enumerate(case.bodies):
            for dof in DOFS:
                if dof in body.free:
                    self.nodes.append(("body", bi, dof))
                    scale.append(1.0 if dof in ROTATIONS else length_scale)
        for pi, _ in enumerate(case.free_points):
            for dof in POINT_DOFS:
                self.nodes.append(("point", pi, dof))
                scale.append(length_scale)
        self.free = tuple(dof for _, _, dof in self.nodes)
        self.rotational = tuple(dof in ROTATIONS for dof in self.free)
        self.n_q = len(scale)
        self.line_offsets = []
        for kind in self.kinds:
            self.line_offsets.append(len(scale))
            scale += kind.scales(force_scale, length_scale)
        self.leg_offsets = self.line_offsets
        #: Every contact (fenders, guide pads; :mod:`.contact`), its unknowns after the
        #: lines'.
        self.contacts = contact_points(case)
        self.contact_offsets = []
        for point in self.contacts:
            self.contact_offsets.append(len(scale))
            scale += [force_scale] * point.n_unknowns
        self.n_x = len(scale)
        self.x_scale = np.array(scale, dtype=float)
        self.n_p = self.layout.size
        #: Parameter entries that only scale with the load factor (not in the rest state).
        self.load_mask = self.layout.load_mask()
        self.effects = self._effects()
        self._lock = threading.RLock()
        self._nlp_solvers = {}
        self._newton = None
        #: Closed-form starting points by parameters (see :mod:`.start`); guarded by
        #: :attr:`lock`.
        self.start_cache: dict = {}
        self._kernel_pool = None
        self._post = None
        #: What other modules work out once from this problem (index arrays, names), by
        #: key; a value is written whole, so readers need no lock.
        self.derived: dict = {}
        with SYMBOLIC_LOCK:
            self._build()

    @property
    def lock(self) -> threading.RLock:
        """Guards this problem's caches and its CasADi solver objects."""
        return self._lock

    # -- construction ---------------------------------------------------------------
    def _effects(self) -> list:
        case = self.case
        kinds = self.kinds
        effects = []
        if any(k.elastic for k in kinds):
            effects.append("elastic")
        if not all(k.elastic for k in kinds):
            effects.append("inextensible")
        if any(seg.line_type.stretch is not None for line in case.lines
               for seg in line.segments):
            effects.append("nonlinear_stretch")
        if any(k.contact for k in kinds):
            effects.append("seabed_contact")
        if any(k.surface for k in kinds):
            effects.append("surface_contact")
        if any(k.friction for k in kinds):
            effects.append("seabed_friction")
        if any(k.sloped for k in kinds):
            effects.append("sloped_seabed")
        types = [seg.line_type for line in case.lines for seg in line.segments]
        if any(lt.weight_in_water < 0 for lt in types):
            effects.append("buoyant_line")
        if any(k.neutral for k in kinds) or any(
                s.block == "straight" for k in kinds if k.multi for s in k.block.segments):
            effects.append("neutral_line")
        if any(lt.sealed for lt in types):
            effects.append("wall_tension")
        if any(line.multi_segment for line in case.lines):
            effects.append("multi_segment")
        if any(k.discrete for k in kinds):
            effects.append("line_drag")
        if case.free_points:
            effects.append("free_points")
        if len(case.bodies) > 1:
            effects.append("several_bodies")
        if any(b.mass is not None for b in case.bodies):
            effects.append("body_weight")
        if any(b.hydrostatics is not None for b in case.bodies):
            effects.append("hydrostatics")
        if any(b.hull for b in case.bodies):
            effects.append("exact_hydrostatics")
        if any(b.stiffness is not None for b in case.bodies):
            effects.append("springs")
        names = []
        for body in case.bodies:
            for e in body_load_models.effect_names(body.loads, case.environment):
                e = "constant_force" if e == "force" else e
                if e not in names:
                    names.append(e)
        return effects + names

    def _build(self):
        case = self.case
        env = case.environment
        layout = self.layout
        xs = ca.SX.sym("x", self.n_x)
        x = xs * ca.DM(self.x_scale)
        p = ca.SX.sym("p", self.n_p)

        def par(name):
            return p[layout.slice(name)]

        E = {k: p[layout.index("env." + k)] for k in ENV_PARAMS}
        seabed = {k: p[layout.index("seabed." + k)] for k in SEABED_PARAMS}
        lf = E["load_factor"]

        # -- node positions -------------------------------------------------------------
        poses, rotations = [], []
        for bi, body in enumerate(case.bodies):
            q = list(ca.vertsplit(par(f"body[{body.name}].pose")))
            poses.append(q)
        points = []
        k_contact = self.force_scale / self.length_scale
        for j, (kind, index, dof) in enumerate(self.nodes):
            if kind == "body":
                poses[index][DOFS.index(dof)] = x[j]
        for pi, point in enumerate(case.free_points):
            j0 = self.nodes.index(("point", pi, "x"))
            px, py, zeta = x[j0], x[j0 + 1], x[j0 + 2]
            pos = ca.vertcat(px, py, seabed_height(seabed, px, py) + ca.fmax(zeta, 0))
            points.append(dict(position=pos, zeta=zeta, force=ca.SX.zeros(3)))
        for q in poses:
            rotations.append(rotation_matrix(q[3], q[4], q[5]))
        body_force = [ca.SX.zeros(3) for _ in case.bodies]
        body_moment = [ca.SX.zeros(3) for _ in case.bodies]
        body_index = {b.name: i for i, b in enumerate(case.bodies)}
        point_index = {pt.name: i for i, pt in enumerate(case.free_points)}

        def end_position(end, coords):
            if end.body is not None:
                bi = body_index[end.body]
                r = ca.vertcat(*poses[bi][:3])
                return r + rotations[bi] @ coords
            if end.point is not None:
                return points[point_index[end.point]]["position"]
            if end.on_seabed:
                return ca.vertcat(coords[0], coords[1],
                                  seabed_height(seabed, coords[0], coords[1]))
            return coords

        def apply(end, position, force):
            if end.body is not None:
                bi = body_index[end.body]
                r = ca.vertcat(*poses[bi][:3])
                body_force[bi] = body_force[bi] + force
                body_moment[bi] = body_moment[bi] + cross(position - r, force)
            elif end.point is not None:
                pt = points[point_index[end.point]]
                pt["force"] = pt["force"] + force

        # -- lines ------------------------------------------------------------------------
        seg_values = self._segment_values(p)
        # Stretch-law parameters per line and segment (None: Hooke or inextensible).
        self.line_laws = line_laws(case, layout, p)
        line_res, line_rows, seg_rows, node_rows = [], [], [], []
        closing, tensions, line_weights = [], [], []
        current = self._current(E, p)
        for i, (line, kind) in enumerate(zip(case.lines, self.kinds)):
            P = {k: par(f"line[{line.name}].{k}") for k in LINE_PARAMS}
            coords_a = ca.vertcat(P["anchor_x"], P["anchor_y"], P["anchor_z"])
            coords_b = ca.vertcat(P["fair_x"], P["fair_y"], P["fair_z"])
            pos_a = end_position(line.a, coords_a)
            pos_b = end_position(line.b, coords_b)
            lower, upper = (pos_b, pos_a) if kind.flipped else (pos_a, pos_b)
            iu = self.line_offsets[i]
            if kind.discrete:
                block = discrete_leg(self, i, kind.block, x, iu, seg_values[line.name],
                                     seabed, current, pos_a, pos_b)
                node_rows += block.node_rows
            elif kind.multi:
                block = multi_block(self, i, kind, xs, x, iu, seg_values[line.name], P,
                                    seabed, lower, upper)
                seg_rows += block.segment_rows
            else:
                block = single_block(self, i, kind, xs, x, iu, P, seabed, lower, upper)
            line_res += block.residuals
            apply(line.a, pos_a, block.force_a)
            apply(line.b, pos_b, block.force_b)
            closing.append(block.closing)
            fa, fb = block.force_a, block.force_b
            tensions.append(ca.vertcat(ca.norm_2(fb), ca.norm_2(fa)))
            # A scale for the certificate when every line is slack.
            line_weights.append(ca.fabs(P["weight"]) * P["length"])
            row = block.row
            J = row["J"] if row["J"].shape == (4, 1) else ca.reshape(row["J"], 4, 1)
            line_rows.append(ca.vertcat(
                row["H"], row["VF"], row["HA"], row["VA"], row["grounded"],
                row["suspended_x"], row["rX"], row["rZ"], row["X"], row["Z"],
                pos_b[0], pos_b[1], fb[0], fb[1], J,
                pos_a, pos_b[2], fa, fb, row.get("floating", 0 * row["H"])))

        # -- contacts ---------------------------------------------------------------------
        def apply_body(bi, where, force):
            r = ca.vertcat(*poses[bi][:3])
            body_force[bi] = body_force[bi] + force
            body_moment[bi] = body_moment[bi] + cross(where - r, force)

        contact_res, contact_rows, contact_terms = add_contacts(
            self, x, par, poses, rotations, body_index, apply_body)

        # -- body loads -------------------------------------------------------------------
        load_vectors, self.load_names = [], []
        rho, g = env.water_density, env.gravity
        body_scale = []
        generalized, wrenches, hull_range = [], [], []
        for bi, body in enumerate(case.bodies):
            q = poses[bi]
            R = rotations[bi]
            r = ca.vertcat(*q[:3])
            F, M = body_force[bi], body_moment[bi]
            name = f"body[{body.name}]"
            if body.mass is not None:
                wf, wm = weight(r, R, mass=par(name + ".mass"),
                                centre_of_gravity=ca.vertsplit(par(name + ".centre_of_gravity")),
                                gravity=g)
                F, M = F + wf, M + wm
                body_scale.append(par(name + ".mass") * g)
            # Hydrostatics act about the still-water level: the origin's height above it.
            r_water = r - ca.vertcat(0, 0, E["water_level"])
            if body.hydrostatics is not None:
                bf, bm = linear_buoyancy(
                    r_water, R, displaced_volume=par(name + ".displaced_volume"),
                    metacentre=ca.vertsplit(par(name + ".metacentre")),
                    waterplane_area=par(name + ".waterplane_area"),
                    water_density=rho, gravity=g)
                F, M = F + bf, M + bm
                body_scale.append(rho * g * par(name + ".displaced_volume"))
            for j, member in enumerate(body.hull):
                mp = dict(zip(MEMBER_PARAMS, ca.vertsplit(par(f"{name}.hull[{j}]"))))
                out = member_buoyancy(r_water, R, shape=member.shape, bottom=mp["bottom"],
                                      top=mp["top"], radius=mp["radius"],
                                      length=mp["length"], width=mp["width"],
                                      centre=(mp["centre_x"], mp["centre_y"]),
                                      water_density=rho, gravity=g)
                F, M = F + out["force"], M + out["moment"]
                body_scale.append(out["force"][2])
                hull_range.append(out["in_range"])
            loads = body_load_models.body_loads_3d(
                body.loads, env, R, q[5], E["wind_speed"], E["wind_toward"],
                E["current_speed"], E["current_toward"], E["wave_hs"], E["wave_toward"])
            for key, (lfor, lmom) in loads.items():
                F, M = F + lf * lfor, M + lf * lmom
                load_vectors.append(ca.vertcat(lf * lfor, lf * lmom))
                self.load_names.append(key if len(case.bodies) == 1 else f"{body.name}.{key}")
            if body.loads.force is not None:
                if case.form == "legs" and bi == 0:
                    cf = ca.vertcat(E["force_x"], E["force_y"], 0)
                    cm = ca.vertcat(0, 0, E["moment_z"])
                else:
                    f6 = par(name + ".force")
                    cf, cm = f6[:3], f6[3:]
                F, M = F + lf * cf, M + lf * cm
                load_vectors.append(ca.vertcat(lf * cf, lf * cm))
                self.load_names.append("constant_force" if len(case.bodies) == 1
                                       else f"{body.name}.constant_force")
            wrenches.append(ca.vertcat(F, M))
            Q = generalized_forces(F, M, q[4], q[5])
            if body.stiffness is not None:
                K = ca.reshape(par(name + ".stiffness"), 6, 6).T
                q0 = par(name + ".pose")
                Q = Q - K @ (ca.vertcat(*q) - q0)
            generalized.append(Q)

        point_forces = []
        for pi, point in enumerate(case.free_points):
            name = f"point[{point.name}]"
            net = g * (par(name + ".mass") - rho * par(name + ".volume"))
            pt = points[pi]
            gx, gy = seabed["gradient_x"], seabed["gradient_y"]
            normal = ca.vertcat(-gx, -gy, 1) / ca.sqrt(1 + gx**2 + gy**2)
            N = ca.fmax(-pt["zeta"], 0) * k_contact
            force = pt["force"] + ca.vertcat(0, 0, -net) + N * normal
            point_forces.append(force)
            body_scale.append(ca.fabs(net))

        # -- residuals ----------------------------------------------------------------------
        node_res, node_force, node_moment = [], [], []
        for kind, index, dof in self.nodes:
            if kind == "body":
                value = generalized[index][DOFS.index(dof)]
            else:
                value = point_forces[index][POINT_DOFS.index(dof)]
            if dof in ROTATIONS:
                node_res.append(value / self.moment_scale)
                node_moment.append(ca.fabs(value))
            else:
                node_res.append(value / self.force_scale)
                node_force.append(ca.fabs(value))
        g_both = ca.vertcat(*line_res, *contact_res, *node_res)
        eps, hinge = self.smoothing_symbol, self.hinge_symbol
        #: Whether the scene has one-sided elements (hawsers, contacts): then the Newton
        #: steps smooth them in the Jacobian, carry a weak spring on the node unknowns and
        #: accept steps that do not grow the residual.
        self.smoothed = bool(ca.depends_on(g_both, ca.vertcat(eps, hinge)))
        # g_smooth: the complementarities smoothed (IPOPT's residual); g_step: the compliant
        # fenders' switches too (the step Jacobian's); g_all: exact.
        g_smooth = ca.substitute(g_both, hinge, 0)
        g_step = ca.substitute(g_both, hinge, eps)
        g_all = ca.substitute(g_smooth, eps, 0)
        self.residual = ca.Function("residual", [xs, p], [g_all])
        # By row blocks: the lines' rows (each depends on its own unknowns and the nodes'),
        # the contacts' and the nodes' rows (each depends on everything). CasADi colours
        # each block with O(1) directions; the whole (dense rows and columns, an arrow)
        # would need O(lines).
        jac = _blockwise_jacobian(g_all, xs, (len(line_res), len(contact_res)))
        self.jacobian = ca.Function("jacobian", [xs, p], [jac])
        # One graph for both, so the Newton kernel evaluates the shared terms once.
        self.residual_jacobian = ca.Function("residual_jacobian", [xs, p], [g_all, jac])
        self.smoothed_jacobian = ca.Function(
            "smoothed_jacobian", [xs, p, eps],
            [_blockwise_jacobian(g_step, xs, (len(line_res), len(contact_res)))])

        def exact(expr):
            """``expr`` with the complementarities exact (no smoothing)."""
            if not self.smoothed:
                return expr
            return ca.substitute(ca.substitute(expr, hinge, 0), eps, 0)

        unbalanced = ca.vertcat(*generalized, *point_forces) if (generalized or point_forces) \
            else ca.SX(0, 1)
        pose_vec = ca.vertcat(*[ca.vertcat(*q) for q in poses]) if poses else ca.SX(0, 1)
        point_vec = ca.vertcat(*[pt["position"] for pt in points]) if points else ca.SX(0, 1)
        load_vec = ca.vertcat(*load_vectors) if load_vectors else ca.SX(0, 1)
        wrench_vec = ca.vertcat(*wrenches) if wrenches else ca.SX(0, 1)
        range_vec = ca.vertcat(*hull_range) if hull_range else ca.SX(0, 1)
        table = ca.horzcat(*line_rows).T if line_rows else ca.SX(0, len(LINE_COLUMNS))
        self.report = ca.Function(
            "report", [xs, p], [exact(v) for v in (table, unbalanced, load_vec, pose_vec,
                                                   point_vec, wrench_vec, range_vec)])
        self.segment_report = ca.Function(
            "segment_report", [xs, p], [ca.horzcat(*seg_rows).T if seg_rows else ca.DM()])
        self.node_report = ca.Function(
            "node_report", [xs, p], [ca.horzcat(*node_rows).T if node_rows else ca.DM()])
        contact_table = exact(ca.horzcat(*contact_rows).T) if contact_rows else ca.DM()
        self.contact_report = ca.Function("contact_report", [xs, p], [contact_table])

        # -- certificate ----------------------------------------------------------------------
        forces = node_force + closing
        force = ca.mmax(ca.vertcat(*forces)) if forces else ca.SX(0)
        moment = ca.mmax(ca.vertcat(*node_moment)) if node_moment else ca.SX(0)
        all_t = ca.vertcat(*tensions) if tensions else ca.SX(0)
        t_max = ca.mmax(all_t) if tensions else ca.SX(0)
        if line_weights:
            t_max = ca.fmax(t_max, 1e-3 * ca.mmax(ca.vertcat(*line_weights)))
        # The largest force in any body's balance (weight, buoyancy, applied loads) also
        # sets the scale: a floating body's residual is judged against what it carries.
        carried = [ca.fabs(v) for v in body_scale] + [ca.norm_2(v[:3]) for v in load_vectors]
        if carried:
            t_max = ca.fmax(t_max, ca.mmax(ca.vertcat(*carried)))
        penetration, complementarity = ca.SX(0), ca.SX(0)
        if contact_terms:
            t_max = ca.fmax(t_max, ca.mmax(ca.vertcat(*[t["reaction"] for t in contact_terms])))
            rigid = [t for t in contact_terms if "penetration" in t]
            if rigid:
                penetration = ca.mmax(ca.vertcat(*[t["penetration"] for t in rigid]))
                complementarity = ca.mmax(ca.vertcat(*[t["complementarity"] for t in rigid]))
        if self.smoothed:
            # Nothing loaded at all (a pontoon in calm water): judge against a millionth of
            # the force scale, not against round-off.
            t_max = ca.fmax(t_max, 1e-6 * self.force_scale)
        self.certificate = ca.Function(
            "certificate", [xs, p],
            [exact(v) for v in (force, moment, t_max, penetration, complementarity)],
            ["x", "p"], ["force", "moment", "t_max", "penetration", "complementarity"])
        T = ca.horzcat(*tensions).T if tensions else ca.SX(0, 2)
        first = self._first_body_summary(poses, p)
        reactions = element_reactions(self, contact_rows)
        reactions = exact(ca.vertcat(*reactions)) if reactions else ca.SX(0, 1)
        self.summary = ca.Function(
            "summary", [xs, p], [first, T[:, 0], T[:, 1], reactions],
            ["x", "p"], ["body", "fairlead_tension", "anchor_tension", "reactions"])
        self._xs, self._p, self._g, self._g_smooth = xs, p, g_all, g_smooth

    def _first_body_summary(self, poses, p):
        """``[x, y, yaw]`` of the first body (displacement from its case pose), then, in a
        network case, every body's absolute pose (6 each, m and rad)."""
        if not poses:
            return ca.SX.zeros(3)
        q = poses[0]
        q0 = p[self.layout.slice(f"body[{self.case.bodies[0].name}].pose")]
        first = ca.vertcat(q[0] - q0[0], q[1] - q0[1], q[5] - q0[5])
        if self.case.form != "network":
            return first
        return ca.vertcat(first, *[ca.vertcat(*pose) for pose in poses])

    def _segment_values(self, p) -> dict:
        """Each multi-segment or lumped line's segment parameters (line order)."""
        out = {}
        for line, kind in zip(self.case.lines, self.kinds):
            if kind.multi or kind.discrete:
                names = [n for n in self.layout.names
                         if n.startswith(f"line[{line.name}].segment[")
                         or n.startswith(f"line[{line.name}].clump[")]
                out[line.name] = [p[self.layout.index(n)] for n in names]
        return out

    def _current(self, E, p) -> dict:
        first = next((k.block for k in self.kinds if k.discrete), None)
        rows = first.profile_rows if first is not None else 0
        headings = first is not None and first.profile_headings
        profile = None
        if rows:
            # (z, signed speed along the heading) rows, or (z, ux, uy) with a heading each.
            width = 3 if headings else 2
            flat = ca.vertsplit(p[self.layout.slice("current.profile")])
            profile = [tuple(flat[width * r: width * (r + 1)]) for r in range(rows)]
        return dict(speed=E["current_speed"], toward=E["current_toward"], profile=profile,
                    headings=headings, factor=E["load_factor"])

    #: Jacobian smoothing relative to the residual: ``eps = SMOOTHING * L * min(1, |g|)``
    #: [m], with ``L`` the length scale and ``|g|`` the largest scaled residual.
    SMOOTHING = 0.01

    def smoothing(self, g) -> float:
        """The Jacobian smoothing ``eps`` [m] for a (scaled) residual vector ``g``."""
        size = float(np.max(np.abs(g))) if np.size(g) else 0.0
        if not np.isfinite(size):
            size = 1.0
        return self.SMOOTHING * self.length_scale * min(1.0, size)

    #: A weak spring on every node unknown in the step Jacobian (scaled units), where
    #: the scene has complementarities: a body that nothing holds in some direction at
    #: the current point (slack hawsers, open contacts, a hawser's sideways stiffness
    #: T/D at zero tension) moves with its unbalanced force instead of making the step
    #: singular; elsewhere it changes the step by parts in 1e9.
    REGULARISATION = 1e-9

    def regularisation(self, value: float | None = None) -> ca.DM:
        """The sparse matrix subtracted from the step Jacobian (``value``, default
        :data:`REGULARISATION`, on the balance row of every node unknown); empty without
        complementarities."""
        n_lines = self.n_x - self.n_q
        rows = [n_lines + j for j in range(self.n_q)] if self.smoothed else []
        sp = ca.Sparsity.triplet(self.n_x, self.n_x, rows, list(range(len(rows))))
        return ca.DM(sp, self.REGULARISATION if value is None else value)

    def step_sparsity(self) -> ca.Sparsity:
        """The sparsity of the step Jacobian (the Jacobian's and the regularisation's)."""
        sp = self.jacobian.sparsity_out(0)
        if self.smoothed:
            sp = sp + self.smoothed_jacobian.sparsity_out(0) + self.regularisation().sparsity()
        return sp

    def step_jacobian(self, x, p, g) -> np.ndarray:
        """The Jacobian a Newton step uses at ``x`` with residual ``g``: the exact one, or,
        where the scene has complementarities, that of their smoothed form with ``eps``
        tied to ``|g|`` (Jacobian smoothing; :mod:`moorsolve.physics.contact`) less the
        weak spring of :meth:`regularisation`."""
        if not self.smoothed:
            return np.asarray(self.jacobian(x, p))
        J = self.smoothed_jacobian(x, p, self.smoothing(g)) - self.regularisation()
        return np.asarray(ca.densify(J))

    # -- certificate ------------------------------------------------------------------
    def certify(self, x, p, tol: float) -> tuple:
        """``(certified, force_N, moment_Nm, relative)`` of the scaled point ``x``."""
        if not np.all(np.isfinite(x)):
            return False, math.inf, math.inf, math.inf
        return self.judge(*(float(v) for v in self.certificate(x, p)), tol=tol)

    def contact_certificate(self, x, p) -> dict:
        """``penetration_m`` and ``complementarity_N`` of the certificate at ``x`` (None
        each in a scene without contacts)."""
        if not self.contacts:
            return dict(penetration_m=None, complementarity_N=None)
        values = [float(v) for v in self.certificate(x, p)]
        return dict(penetration_m=values[3], complementarity_N=values[4])

    def judge(self, force: float, moment: float, t_max: float, penetration: float = 0.0,
              complementarity: float = 0.0, *, tol: float):
        """``(certified, force, moment, relative)`` from the certificate's numbers.

        The force (and a contact's complementarity residual, a reaction across an open gap)
        must be within ``tol`` of the largest force in the balance (the largest line
        tension or contact reaction, or a body's weight, buoyancy or applied load where
        larger), the moment within ``tol`` of that force times the scene's moment arm, and
        the largest penetration of a contact within ``tol`` of the length scale.
        """
        scale = t_max if t_max > 0 else self.force_scale
        relative = max(force, complementarity) / scale
        moment_ok = moment <= tol * scale * self.moment_scale / self.force_scale
        ok = bool(math.isfinite(relative) and math.isfinite(moment) and relative <= tol
                  and moment_ok and penetration <= tol * self.length_scale)
        return ok, force, moment, relative

    def judge_rows(self, cert: np.ndarray, tol: float) -> tuple:
        """:meth:`judge` of every row of ``cert`` (a certificate a row, as the kernel
        returns it): arrays ``(certified, force, moment, relative)``."""
        cert = np.asarray(cert, dtype=float)
        force, moment, t_max = cert[:, 0], cert[:, 1], cert[:, 2]
        zero = np.zeros(len(cert))
        penetration = cert[:, 3] if cert.shape[1] > 3 else zero
        complementarity = cert[:, 4] if cert.shape[1] > 4 else zero
        scale = np.where(t_max > 0, t_max, self.force_scale)
        with np.errstate(invalid="ignore"):
            relative = np.maximum(force, complementarity) / scale
            ok = (np.isfinite(relative) & np.isfinite(moment) & (relative <= tol)
                  & (moment <= tol * scale * self.moment_scale / self.force_scale)
                  & (penetration <= tol * self.length_scale))
        return ok, force, moment, relative

    # -- everything a Result needs, in one evaluation -------------------------------------
    def post_function(self) -> ca.Function:
        """``post(x, p)``: the certificate ``[force, moment, t_max]``, the condensed
        stiffness of the free body DOFs (:func:`.stability.stiffness_graph`) with its
        stability test (:func:`.stability.clearly_stable_graph`) and the outputs of
        :attr:`report`, :attr:`segment_report` and :attr:`node_report` (see
        :data:`POST_OUTPUTS`), all dense: what certifying, the stability check and the
        Result need from a solved point, in one call. Compiled with the Newton kernel."""
        with self._lock:
            if self._post is None:
                from .stability import clearly_stable_graph, stiffness_graph
                with SYMBOLIC_LOCK:
                    x = ca.MX.sym("x", self.n_x)
                    p = ca.MX.sym("p", self.n_p)
                    K = stiffness_graph(self, self.jacobian(x, p))
                    outs = [ca.vertcat(*self.certificate(x, p)), K,
                            clearly_stable_graph(self, K),
                            *self.report(x, p), self.segment_report(x, p),
                            self.node_report(x, p)]
                    self._post = ca.Function("moorsolve_post", [x, p],
                                             [ca.densify(o) for o in outs],
                                             ["x", "p"], list(POST_OUTPUTS))
            return self._post

    def post(self, x, p) -> dict:
        """:meth:`post_function` at the scaled point ``x``: numpy arrays by name, through
        the compiled kernel's library when it is built, else interpreted."""
        kernel = self._newton
        if kernel is not None and kernel.compiled:
            return kernel.post(x, p)
        try:
            values = self.post_function()(x, p)
        except RuntimeError:
            # A singular condensed block stops the interpreted QR solve: report the
            # stiffness as unknown (the stability check then condenses it itself).
            n_b = sum(owner == "body" for owner, _, _ in self.nodes)
            values = [ca.vertcat(*self.certificate(x, p)), np.full((n_b, n_b), np.nan), 0.0,
                      *self.report(x, p), self.segment_report(x, p), self.node_report(x, p)]
        return {name: np.asarray(v, dtype=float)
                for name, v in zip(POST_OUTPUTS, values)}

    # -- solvers --------------------------------------------------------------------
    def ipopt(self, tol: float, max_iter: int, max_time_s: float) -> ca.Function:
        """An IPOPT solver for the feasibility NLP, cached per setting.

        A CasADi solver object is not safe to run from two threads at once: callers hold
        :attr:`lock` while they run it.
        """
        key = (tol, max_iter, max_time_s)
        with self._lock:
            if key not in self._nlp_solvers:
                nlp = {"x": self._xs, "p": self._p, "f": 0, "g": self._g}
                if self.smoothed:
                    # IPOPT solves the smoothed complementarities (a smoothing parameter
                    # appended to p, nlp_parameters); the polish makes them exact. Among
                    # the equilibria it takes the one nearest its start (also appended),
                    # which keeps it from wandering through open contacts and slack
                    # hawsers, and pins a degree of freedom nothing holds.
                    start = ca.SX.sym("start", self.n_x)
                    nlp["p"] = ca.vertcat(self._p, self.smoothing_symbol, start)
                    nlp["g"] = self._g_smooth
                    nlp["f"] = self.IPOPT_PROXIMITY * ca.sumsqr(self._xs - start)
                opts = {
                    "print_time": False,
                    "error_on_fail": False,
                    # A NaN or inf met on the way (absurd input) is reported by the
                    # certificate and ConvergenceError; CasADi's per-evaluation warnings are
                    # noise.
                    "show_eval_warnings": False, "calc_lam_p": False,
                    "ipopt": {
                        "print_level": 0, "sb": "yes", "tol": tol,
                        "constr_viol_tol": tol, "max_iter": max_iter,
                        "max_wall_time": max_time_s, "nlp_scaling_method": "none",
                        "mu_strategy": "adaptive",
                    },
                }
                with SYMBOLIC_LOCK:
                    self._nlp_solvers[key] = ca.nlpsol("equilibrium", "ipopt", nlp, opts)
            return self._nlp_solvers[key]

    #: The smoothings IPOPT solves with in turn, relative to the length scale (the polish
    #: that follows makes the complementarities exact).
    IPOPT_SMOOTHING = (1e-3, 1e-5)

    #: Weight of the distance from the start in IPOPT's objective (scaled unknowns).
    IPOPT_PROXIMITY = 1e-6

    def ipopt_smoothings(self) -> tuple:
        """The smoothings [m] IPOPT solves with in turn (one run, unsmoothed-free, without
        complementarities)."""
        if not self.smoothed:
            return (None,)
        return tuple(s * self.length_scale for s in self.IPOPT_SMOOTHING)

    def nlp_parameters(self, p, start, smoothing=None) -> np.ndarray:
        """The parameters of the IPOPT problem for the problem's parameters ``p``, the
        (scaled) start ``start`` and a smoothing [m]."""
        if not self.smoothed:
            return p
        return np.concatenate([p, [smoothing], start])

    def newton(self):
        """The fast-path Newton kernel (:mod:`.newton`), built and compiled on first use."""
        with self._lock:
            if self._newton is None:
                from .newton import NewtonKernel
                with SYMBOLIC_LOCK:
                    self._newton = NewtonKernel(self)
            return self._newton

    def kernel_pool(self):
        """Clones of the Newton kernel, one per concurrently running caller (sweeps)."""
        with self._lock:
            if self._kernel_pool is None:
                from .newton import KernelPool
                self._kernel_pool = KernelPool(self.newton())
            return self._kernel_pool

    def bounds(self) -> tuple:
        lb = np.full(self.n_x, -np.inf)
        ub = np.full(self.n_x, np.inf)
        for j, (_, _, dof) in enumerate(self.nodes):
            if dof == "pitch":
                # z-y-x angles are singular at +-90 deg of pitch.
                lb[j], ub[j] = -0.49 * math.pi, 0.49 * math.pi
        # No bound on a line's u: every block continues its spans monotonically for u < 0
        # (loose line on a boundary, or, for a line with nothing to lie on, no root there),
        # so H = max(u, 0) = 0 is an interior root, not a bound IPOPT must reach (a folded
        # line hit IPOPT's iteration limit at that bound, issue 20). A hawser's u is its
        # tension and a rigid contact's unknown its reaction (Fischer-Burmeister
        # complementarities): neither pulls, and the bound keeps a Newton step from making
        # them pull where the smoothed Jacobian would.
        for i, kind in enumerate(self.kinds):
            if kind.single and kind.neutral:
                lb[self.line_offsets[i]] = 0.0
        for point, io in zip(self.contacts, self.contact_offsets):
            if point.n_unknowns:
                lb[io] = 0.0
        return lb, ub

    def parameters(self, case: Case, load_factor: float = 1.0) -> np.ndarray:
        """The parameter vector of ``case`` (same structure) for this problem."""
        return parameter_vector(case, load_factor, self.kinds)


def _blockwise_jacobian(g, x, sizes):
    """``jacobian(g, x)`` taken by blocks of rows (``sizes`` of the leading blocks, then
    the rest), stacked."""
    edges = [0]
    for size in sizes:
        edges.append(edges[-1] + size)
    edges.append(g.numel())
    blocks = [ca.jacobian(g[a:b], x) for a, b in zip(edges[:-1], edges[1:]) if b > a]
    return ca.vertcat(*blocks) if blocks else ca.SX(0, x.numel())


@per_case
def structure_key(case: Case) -> tuple:
    """What decides the shape of the built problem (not its parameter values); computed
    once per case object."""
    bodies = tuple(
        (b.name, tuple(b.free), b.mass is not None, b.hydrostatics is not None,
         tuple(m.shape for m in b.hull), b.stiffness is not None,
         dataclasses.replace(b.loads, force=None), b.loads.force is not None)
        for b in case.bodies)
    berth = (tuple(w.name for w in case.contacts.walls),
             tuple(p.name for p in case.contacts.piles), tuple(contact_points(case)))
    return HashedKey((
        line_kinds_of(case), line_ends_of(case), bodies,
        tuple(p.name for p in case.free_points),
        case.form, berth,
        case.environment.wind is not None, case.environment.current is not None,
        case.environment.waves is not None,
        case.environment.air_density, case.environment.water_density,
        case.environment.gravity,
    ))


__all__ = ["EquilibriumProblem", "structure_key", "LINE_COLUMNS", "LineKind",
           "plane_geometry", "closing_force", "BODY_PARAMS"]
