"""Build the coupled equilibrium of a scene (bodies, points, lines) as one CasADi problem.

Unknowns, in this order:

- the *nodes*: every free degree of freedom of every body (its pose ``x, y, z`` [m] and
  ``roll, pitch, yaw`` [rad], absolute, starting from the case-file pose) and every free
  point's ``x, y`` and a signed height ``zeta`` above the seabed: the point is at
  ``z = seabed + max(zeta, 0)`` and the seabed pushes it up with ``max(-zeta, 0)`` times the
  scene's stiffness scale (exact complementarity, the device of the lumped-node lines);
- then every line's own unknowns (:mod:`.lines.blocks`).

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

import math
import threading

import casadi as ca
import numpy as np

from ...model import DOFS, Case
from ...model.line_table import LINE_COLUMNS
from ...physics.kinematics import cross, rotation_matrix
from ..result.certify import Certification
from ...concurrency import SYMBOLIC_LOCK
from .nodes import node_balances
from ..kernels.numerics import SolverAccess
from ..lines.discrete import discrete_leg
from .effects import scene_effects
from .layout import BODY_PARAMS, ENV_PARAMS, LINE_PARAMS, SEABED_PARAMS, build_layout
from ..contact.blocks import add_contacts, contact_points, element_reactions
from ..lines.stretch_params import line_laws
from ..lines.line_kinds import LineKind, line_kinds
from ..lines.blocks import closing_force, multi_block, plane_geometry, seabed_height, single_block
from .prepared import parameter_vector

ROTATIONS = ("roll", "pitch", "yaw")
POINT_DOFS = ("x", "y", "zeta")


def _body_radius(case: Case) -> float:
    arms = [math.hypot(end.position[0], end.position[1])
            for line in case.lines for end in (line.a, line.b) if end.body is not None]
    return max([1.0] + arms)


class EquilibriumProblem(Certification, SolverAccess):
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
        #: Every contact (fenders, guide pads; :mod:`.contact.blocks`), its unknowns after the
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
        self.effects = scene_effects(self.case, self.kinds)
        self._lock = threading.RLock()
        self._ipopt_solvers = None
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
    def _build(self):
        case = self.case
        layout = self.layout
        xs = ca.SX.sym("x", self.n_x)
        x = xs * ca.DM(self.x_scale)
        p = ca.SX.sym("p", self.n_p)

        def par(name):
            return p[layout.slice(name)]

        E = {k: p[layout.index("env." + k)] for k in ENV_PARAMS}
        seabed = {k: p[layout.index("seabed." + k)] for k in SEABED_PARAMS}
        grid = case.environment.seabed.bathymetry is not None

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
            # On a grid each point rests on its own plane (solve/lines/bathymetry.py).
            bed = (dict(zip(SEABED_PARAMS, ca.vertsplit(par(f"point[{point.name}].seabed"))))
                   if grid else seabed)
            pos = ca.vertcat(px, py, seabed_height(bed, px, py) + ca.fmax(zeta, 0))
            points.append(dict(position=pos, zeta=zeta, force=ca.SX.zeros(3), bed=bed))
        for q in poses:
            rotations.append(rotation_matrix(q[3], q[4], q[5]))
        body_force = [ca.SX.zeros(3) for _ in case.bodies]
        body_moment = [ca.SX.zeros(3) for _ in case.bodies]
        body_index = {b.name: i for i, b in enumerate(case.bodies)}
        point_index = {pt.name: i for i, pt in enumerate(case.free_points)}

        def end_position(end, coords, bed=seabed):
            if end.body is not None:
                bi = body_index[end.body]
                r = ca.vertcat(*poses[bi][:3])
                return r + rotations[bi] @ coords
            if end.point is not None:
                return points[point_index[end.point]]["position"]
            if end.on_seabed and bed:
                return ca.vertcat(coords[0], coords[1],
                                  seabed_height(bed, coords[0], coords[1]))
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
            bed = seabed
            if grid:
                # The line's own plane passes through the seabed under its lower end; an
                # end resting on the seabed elsewhere keeps the grid's height (its case z).
                plane = ca.vertsplit(par(f"line[{line.name}].seabed"))
                bed = dict(zip(SEABED_PARAMS, plane))
            lower_end = line.b if kind.flipped else line.a
            pos_a = end_position(line.a, coords_a,
                                 bed if lower_end is line.a or not grid else {})
            pos_b = end_position(line.b, coords_b,
                                 bed if lower_end is line.b or not grid else {})
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
                block = single_block(self, i, kind, xs, x, iu, P, bed, lower, upper)
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

        # -- bodies and free points ---------------------------------------------------------
        nodes_out = node_balances(case, par, E, seabed, poses, rotations, body_force,
                                  body_moment, points, k_contact)
        generalized, point_forces = nodes_out["generalized"], nodes_out["point_forces"]
        wrenches, load_vectors = nodes_out["wrenches"], nodes_out["load_vectors"]
        body_scale, hull_range = nodes_out["body_scale"], nodes_out["hull_range"]
        self.load_names = nodes_out["load_names"]

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
        # Without complementarities the smoothed residual is the exact one: its Jacobian
        # is not differentiated twice (a farm's node rows take seconds to).
        self.smoothed_jacobian = ca.Function(
            "smoothed_jacobian", [xs, p, eps],
            [_blockwise_jacobian(g_step, xs, (len(line_res), len(contact_res)))
             if self.smoothed else jac])

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

    def keep_start(self, key: bytes, x: np.ndarray) -> None:
        """Remember the start ``x`` under ``key`` in :attr:`start_cache` (at most
        :data:`_STARTS_KEPT`, the oldest dropped: a sweep over geometries adds one each)."""
        with self._lock:
            if key not in self.start_cache and len(self.start_cache) >= _STARTS_KEPT:
                self.start_cache.pop(next(iter(self.start_cache)))
            self.start_cache[key] = x

    def parameters(self, case: Case, load_factor: float = 1.0) -> np.ndarray:
        """The parameter vector of ``case`` (same structure) for this problem."""
        return parameter_vector(case, load_factor, self.kinds)


#: Starting points a problem remembers (:meth:`EquilibriumProblem.keep_start`).
_STARTS_KEPT = 64


def _blockwise_jacobian(g, x, sizes):
    """``jacobian(g, x)`` taken by blocks of rows (``sizes`` of the leading blocks, then
    the rest), stacked."""
    edges = [0]
    for size in sizes:
        edges.append(edges[-1] + size)
    edges.append(g.numel())
    blocks = [ca.jacobian(g[a:b], x) for a, b in zip(edges[:-1], edges[1:]) if b > a]
    return ca.vertcat(*blocks) if blocks else ca.SX(0, x.numel())


__all__ = ["EquilibriumProblem", "LINE_COLUMNS", "LineKind",
           "plane_geometry", "closing_force", "BODY_PARAMS"]
