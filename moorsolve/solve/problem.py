"""Build the coupled equilibrium of a body and its legs as one CasADi problem.

Unknowns: the body's free degrees of freedom (surge = global x, sway = global y
displacement of the body origin, yaw about the vertical) and, per leg, the signed tension
variable ``u`` and the fairlead vertical tension ``V`` of :mod:`moorsolve.physics.catenary`.
Equations: each leg's two span residuals, and the force and moment balance of each free
degree of freedom. The problem is square; IPOPT solves it as a feasibility NLP.

Everything that may change between solves of one scene is a parameter (environment speeds
and headings, a load factor, the constant force, and per leg the anchor, fairlead, length,
weight, compliance and friction), so one build serves a whole sweep.

Multi-segment legs
------------------
A leg of several segments (chain-polyester-chain, clump weights, buoys) stays in the
vertical plane through its anchor and fairlead: every load on it (weights, clumps, buoys,
the seabed's reaction) is vertical and friction acts along the line, so the horizontal
tension is the same in every segment and no force leaves the plane. The 2-D model is exact.
Its unknowns are ``u`` (shared by all segments), the fairlead's ``V`` and per joint

- ``xi``: the joint's horizontal distance from the anchor in the leg's plane [m];
- ``sigma``: a signed force [N]. ``max(sigma, 0)`` is the vertical tension at the top of the
  segment below the joint, ``max(-sigma, 0)`` the seabed's reaction on the joint.

The joint's height is not an unknown: the segment below puts it there (its height
equation defines it). Equations: each segment's span residual ``rX``, the top segment's
``rZ``, and each joint's vertical balance ``VA_above - V_below - W_clump + N = 0``.

Contact of a joint with the seabed is therefore the complementarity ``N * V_below = 0``
written exactly with one signed unknown, the same device as the leg block's ``u`` (no
penalty stiffness, no relaxation parameter, no MPCC). It was chosen over a contact
complementarity on the joint's height because a segment lying flat up to a joint has
``Z ~ V |V| / (2 H w)``: with ``V`` and the height as separate unknowns the Jacobian is
singular exactly where a clump rests on the seabed. Here the segment below a grounded joint
has ``V = 0`` and the reaction takes over linearly. A sinking segment's lower end may be
lifted (a buoyed joint, a pile-head anchor): it then uses the two-sided touchdown block
(:func:`~moorsolve.physics.catenary.lifted_segment_equations`), which also covers the U
between two points above or on the seabed. When the fairlead itself rests on the seabed the
top segment is solved from that end (``MultiLegKind.reversed_top``) for the same reason.
Limits: a joint rests on the seabed only with the segment below arriving along it (not
hanging down into it); seabed friction acts on the anchor segment only; a buoy's lift is
constant (fully submerged). Scenes without multi-segment legs build exactly the core problem.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Optional

import casadi as ca
import numpy as np

from ..model import DEGREES_OF_FREEDOM, Case, Leg
from . import body_loads as body_load_models
from ..physics.catenary import (LegKind, leg_function, lifted_segment_function,
                                sloped_leg_function, straight_segment_function)
from ..physics.stretch import StretchModel
from .stretch_params import law_model, split_stretch_parameters, stretch_parameters

#: Environment parameter layout (angles in radians).
ENV_PARAMS = ("wind_speed", "wind_toward", "current_speed", "current_toward",
              "wave_hs", "wave_toward", "force_x", "force_y", "moment_z", "load_factor")
#: Per-leg parameter layout.
LEG_PARAMS = ("anchor_x", "anchor_y", "anchor_z", "fair_x", "fair_y", "fair_z",
              "length", "weight", "ea_inv", "friction")

#: Per-segment parameters of a multi-segment leg, and per joint the clump's net weight.
SEGMENT_PARAMS = ("length", "weight", "ea_inv")
#: Per-segment parameters of a discretised leg.
DISCRETE_PARAMS = ("length", "weight", "ea_inv", "diameter", "normal", "tangential", "side")
#: Seabed parameters, present when some leg has joints (free nodes that may rest on it).
SEABED_PARAMS = ("depth", "gradient_x", "gradient_y")

#: Columns of ``EquilibriumProblem.segment_report``: per segment of a multi-segment leg, its
#: tensions [N] (top H and V, pull on its lower end HA and signed VA), grounded length and
#: horizontal extents [m], span residuals [m] and spans [m], its lower node (height above
#: the seabed, distance from the anchor, z), the unbalanced vertical force and seabed
#: reaction of the joint at its top [N] (0 for the top segment), and its mismatch as a force.
SEGMENT_COLUMNS = ("leg", "segment", "H", "VF", "HA", "VA", "grounded", "suspended_x",
                   "descent_x", "rX", "rZ", "X", "Z", "lower_h", "lower_xi", "lower_z",
                   "joint_unbalanced", "joint_reaction", "mismatch_N")

#: Yaw is bounded to keep the solver away from the mirrored equilibrium with the lines
#: crossing under the hull (yaw near 180 deg, REFERENCE.md section 1).
YAW_LIMIT = math.pi / 2
_X_FLOOR = 1e-12


@dataclass(frozen=True)
class SegmentKind:
    """Which block a segment of a multi-segment leg uses.

    ``block`` is ``"leg"`` (the leg block of :func:`leg_function` with ``leg``: a buoyant
    segment that never touches the seabed), ``"lifted"`` (a sinking segment whose lower end
    may be above the seabed; ``friction`` for the anchor segment) or ``"straight"``
    (weightless).
    """

    block: str
    elastic: bool
    leg: Optional[LegKind] = None
    friction: bool = False
    law: Optional[StretchModel] = None


@dataclass(frozen=True)
class MultiLegKind:
    """The physics of a multi-segment leg: one :class:`SegmentKind` per segment.

    ``reversed_top``: the fairlead rests on the seabed and the top segment sinks, so that
    segment is solved from the fairlead end (its block's lower end), where the line may lie
    flat; the unknown ``V`` is then its vertical tension at the joint below.
    """

    segments: tuple
    reversed_top: bool = False

    @property
    def n_joints(self) -> int:
        return len(self.segments) - 1

    @property
    def contact(self) -> bool:
        return any(s.block == "lifted" or (s.leg is not None and s.leg.contact)
                   for s in self.segments)

    @property
    def friction(self) -> bool:
        return any(s.friction for s in self.segments)

    @property
    def elastic(self) -> bool:
        return any(s.elastic for s in self.segments)

    @property
    def neutral(self) -> bool:
        return False


def _can_ground(kind: SegmentKind) -> bool:
    """Whether a segment's top can arrive along the seabed (a sinking segment)."""
    return kind.block == "lifted" or (kind.leg is not None and kind.leg.contact)


def _on_seabed(case: Case, leg: Leg) -> bool:
    bed = case.environment.seabed_z(leg.anchor[0], leg.anchor[1])
    return leg.anchor[2] <= bed + 1e-9 * max(case.environment.depth, 1.0)


@dataclass(frozen=True)
class DiscreteLegKind:
    """A leg discretised into lumped nodes because a current drags on its line.

    ``elements`` holds the number of elements of each segment (anchor first);
    ``elastic_segments`` whether each segment stretches; ``profile_rows`` the number of rows
    of the current profile (0: uniform current); ``side`` whether any segment has a
    side-force coefficient.
    """

    elements: tuple
    elastic_segments: tuple
    profile_rows: int = 0
    side: bool = False
    laws: tuple = ()

    @property
    def elastic(self) -> bool:
        return any(self.elastic_segments)

    @property
    def n_elements(self) -> int:
        return sum(self.elements)

    @property
    def contact(self) -> bool:
        return True

    friction = False
    neutral = False
    sloped = False


def discretised(case: Case, leg: Leg) -> bool:
    """Whether a leg is modelled as a lumped-node line: the case has a current and one of
    its line types gives drag data."""
    return case.environment.current is not None and any(
        seg.line_type.drag is not None for seg in leg.segments)


def leg_kind(case: Case, leg: Leg):
    """The physics a leg needs, from what the case declares.

    A :class:`LegKind` for a one-segment leg (the core problem, unchanged), a
    :class:`MultiLegKind` for a leg of several segments, a :class:`DiscreteLegKind` for a
    leg whose line feels the current.
    """
    if discretised(case, leg):
        n = case.solver.line_elements
        counts = tuple(max(1, round(n * seg.length / leg.length)) for seg in leg.segments)
        profile = case.environment.current.profile
        return DiscreteLegKind(
            elements=counts,
            elastic_segments=tuple(seg.line_type.elastic for seg in leg.segments),
            profile_rows=len(profile) if profile else 0,
            side=any(seg.line_type.drag is not None and seg.line_type.drag.side != 0
                     for seg in leg.segments),
            laws=tuple(law_model(seg.line_type) for seg in leg.segments))
    if leg.multi_segment:
        return _multi_leg_kind(case, leg)
    lt = leg.line_type
    w = lt.weight_in_water
    contact = _on_seabed(case, leg) and w > 0
    return LegKind(elastic=lt.elastic, contact=contact,
                   friction=contact and case.environment.seabed.friction > 0,
                   neutral=(w == 0), sloped=contact and case.environment.seabed.sloped,
                   law=law_model(lt))


def _multi_leg_kind(case: Case, leg: Leg) -> MultiLegKind:
    kinds = []
    for k, seg in enumerate(leg.segments):
        lt = seg.line_type
        w = lt.weight_in_water
        law = law_model(lt)
        if w == 0:
            kinds.append(SegmentKind("straight", lt.elastic, law=law))
        elif w < 0:
            kinds.append(SegmentKind("leg", lt.elastic, LegKind(lt.elastic, contact=False,
                                                                 law=law), law=law))
        else:
            # Friction acts on the anchor segment's grounded length only (README).
            friction = k == 0 and _on_seabed(case, leg) and case.environment.seabed.friction > 0
            kinds.append(SegmentKind("lifted", lt.elastic, friction=friction, law=law))
    fairlead_on_seabed = leg.fairlead[2] <= -case.environment.depth + 1e-9
    return MultiLegKind(tuple(kinds), reversed_top=fairlead_on_seabed and kinds[-1].block
                        == "lifted")


def structure_key(case: Case) -> tuple:
    """What decides the shape of the built problem (not its parameter values)."""
    body = case.body
    return (
        tuple(leg_kind(case, leg) for leg in case.legs),
        None if body is None else tuple(body.free),
        None if body is None else dataclasses.replace(body.loads, force=None),
        None if body is None else body.loads.force is not None,
        case.environment.wind is not None, case.environment.current is not None,
        case.environment.waves is not None,
        case.environment.air_density, case.environment.water_density,
        case.environment.gravity,
    )


def environment_parameters(case: Case, load_factor: float = 1.0) -> np.ndarray:
    env = case.environment
    force = (case.body.loads.force if case.body is not None and case.body.loads.force
             is not None else (0.0, 0.0, 0.0))
    wind, current, waves = env.wind, env.current, env.waves
    return np.array([
        wind.speed if wind else 0.0, math.radians(wind.toward_deg) if wind else 0.0,
        current.speed if current else 0.0, math.radians(current.toward_deg) if current else 0.0,
        waves.hs if waves else 0.0, math.radians(waves.toward_deg) if waves else 0.0,
        force[0], force[1], force[2], load_factor], dtype=float)


def leg_parameters(case: Case) -> np.ndarray:
    mu = case.environment.seabed.friction
    rows = []
    for leg in case.legs:
        lt = leg.line_type
        rows.append([*leg.anchor, *leg.fairlead, leg.length, lt.weight_in_water,
                     1.0 / lt.ea if lt.ea else 0.0, mu])
    return np.asarray(rows, dtype=float).reshape(-1)


def segment_parameters(case: Case) -> np.ndarray:
    """Seabed and multi-segment parameters (empty for a flat scene of one-segment legs).

    The seabed (``SEABED_PARAMS``), then per multi-segment leg ``SEGMENT_PARAMS`` for each
    segment and the net clump weight [N] of each joint.
    """
    kinds = [leg_kind(case, leg) for leg in case.legs]
    multi = [leg for leg, k in zip(case.legs, kinds) if isinstance(k, MultiLegKind)]
    discrete = [leg for leg, k in zip(case.legs, kinds) if isinstance(k, DiscreteLegKind)]
    if not multi and not discrete and not case.environment.seabed.sloped:
        return np.zeros(0)
    values = [case.environment.depth, *case.environment.seabed.gradient]
    for leg in multi:
        for seg in leg.segments:
            lt = seg.line_type
            values += [seg.length, lt.weight_in_water, 1.0 / lt.ea if lt.ea else 0.0]
        values += [c.weight if c is not None else 0.0 for c in leg.joint_clumps]
    for leg in discrete:
        for seg in leg.segments:
            lt = seg.line_type
            drag = lt.drag
            values += [seg.length, lt.weight_in_water, 1.0 / lt.ea if lt.ea else 0.0,
                       lt.diameter or 0.0, drag.normal if drag else 0.0,
                       drag.tangential if drag else 0.0, drag.side if drag else 0.0]
        values += [c.weight if c is not None else 0.0 for c in leg.joint_clumps]
    if discrete and case.environment.current.profile:
        values += [v for row in case.environment.current.profile for v in row]
    return np.asarray(values, dtype=float)


def parameter_vector(case: Case, load_factor: float = 1.0) -> np.ndarray:
    """The full parameter vector ``p`` of ``case``'s problem: environment, legs, segments,
    stretch laws (:mod:`.stretch_params`)."""
    return np.concatenate([environment_parameters(case, load_factor), leg_parameters(case),
                           segment_parameters(case), stretch_parameters(case)])


class EquilibriumProblem:
    """The symbolic problem of one case structure, built once.

    Attributes
    ----------
    free : tuple of str
        Solved degrees of freedom, in ``DEGREES_OF_FREEDOM`` order.
    kinds : list of LegKind or MultiLegKind
    n_q, n_x, n_p : int
        Numbers of body unknowns, all unknowns and parameters.
    leg_offsets : list of int
        Index in ``x`` of each leg's first unknown. A one-segment leg has ``(u, V)``; a
        multi-segment leg has ``u`` and the fairlead's ``V``, then per joint its horizontal
        distance from the anchor ``xi`` [m] in the leg's plane and a signed force ``sigma``
        [N]: the top vertical tension of the segment below is ``max(sigma, 0)`` and the
        seabed's reaction on the joint ``max(-sigma, 0)`` (see the module notes).
    residual : casadi.Function
        ``(x, p) -> g`` scaled residuals (legs first, then body balance).
    report : casadi.Function
        ``(x, p) ->`` per-leg end forces, spans and Jacobian blocks, and the body's
        unbalanced load, used for the certificate and the result. For a multi-segment leg
        the row holds the top segment's tensions, the anchor segment's anchor forces, the
        total grounded length and the leg's spans; its residual columns (6, 7) hold the
        largest force mismatch [N] of its segments and joints and its Jacobian block
        (14-17) is the identity, so that ``solve(J, e)`` is that force.
    segment_report : casadi.Function
        ``(x, p) ->`` one row per segment of the multi-segment legs (``SEGMENT_COLUMNS``).
    effects : list of str
        The physical effects this problem simulates.
    """

    def __init__(self, case: Case, force_scale: float, length_scale: float):
        self.case = case
        body = case.body
        self.free = tuple(d for d in DEGREES_OF_FREEDOM if body is not None and d in body.free)
        self.kinds = [leg_kind(case, leg) for leg in case.legs]
        self.n_legs = len(case.legs)
        self.n_q = len(self.free)
        self.force_scale = force_scale
        self.length_scale = length_scale
        self.moment_scale = force_scale * max(length_scale, _body_radius(case))
        scale = [length_scale if d != "yaw" else 1.0 for d in self.free]
        self.leg_offsets = []
        for kind in self.kinds:
            self.leg_offsets.append(len(scale))
            if isinstance(kind, MultiLegKind):
                scale += [force_scale] * 2 + [length_scale, force_scale] * kind.n_joints
            elif isinstance(kind, DiscreteLegKind):
                scale += [force_scale] * kind.n_elements
                scale += [length_scale] * (3 * (kind.n_elements - 1))
            else:
                scale += [force_scale] * 2
        self.n_x = len(scale)
        self.x_scale = np.array(scale, dtype=float)
        self.effects = self._effects()
        self._build()

    # -- construction ---------------------------------------------------------------
    def _effects(self) -> list[str]:
        case = self.case
        effects = []
        if any(k.elastic for k in self.kinds):
            effects.append("elastic")
        if not all(k.elastic for k in self.kinds):
            effects.append("inextensible")
        types = [seg.line_type for leg in case.legs for seg in leg.segments]
        if any(lt.stretch is not None for lt in types):
            effects.append("nonlinear_stretch")
        if any(k.contact for k in self.kinds):
            effects.append("seabed_contact")
        if any(k.friction for k in self.kinds):
            effects.append("seabed_friction")
        if any(getattr(k, "sloped", False) for k in self.kinds):
            effects.append("sloped_seabed")
        if any(lt.weight_in_water < 0 for lt in types):
            effects.append("buoyant_line")
        if any(k.neutral for k in self.kinds) or any(
                s.block == "straight" for k in self.kinds if isinstance(k, MultiLegKind)
                for s in k.segments):
            effects.append("neutral_line")
        if any(lt.sealed for lt in types):
            effects.append("wall_tension")
        if any(leg.multi_segment for leg in case.legs):
            effects.append("multi_segment")
        if any(isinstance(k, DiscreteLegKind) for k in self.kinds):
            effects.append("line_drag")
        if case.body is not None:
            effects += [("constant_force" if e == "force" else e)
                        for e in body_load_models.effect_names(case.body.loads, case.environment)]
        return effects

    def _build(self):
        case = self.case
        xs = ca.SX.sym("x", self.n_x)
        x = xs * ca.DM(self.x_scale)
        env = ca.SX.sym("env", len(ENV_PARAMS))
        legp = ca.SX.sym("legp", len(LEG_PARAMS) * self.n_legs)
        n_seg_params = len(segment_parameters(case))
        segp = ca.SX.sym("segp", n_seg_params)
        lawp = ca.SX.sym("lawp", len(stretch_parameters(case)))
        p = ca.vertcat(env, legp, segp, lawp)
        # Stretch-law parameters per leg and segment (None: Hooke or inextensible).
        self._laws = split_stretch_parameters(case, ca.vertsplit(lawp))
        self.n_p = p.numel()
        E = dict(zip(ENV_PARAMS, ca.vertsplit(env)))
        seg_values = ca.vertsplit(segp) if n_seg_params else []
        seabed = dict(zip(SEABED_PARAMS, seg_values[:len(SEABED_PARAMS)]))
        seg_cursor = len(SEABED_PARAMS)
        n_multi = sum(3 * len(k.segments) + k.n_joints for k in self.kinds
                      if isinstance(k, MultiLegKind))
        disc_cursor = seg_cursor + n_multi
        n_disc = sum(len(DISCRETE_PARAMS) * len(k.elements) + len(k.elements) - 1
                     for k in self.kinds if isinstance(k, DiscreteLegKind))
        profile = None
        rows = next((k.profile_rows for k in self.kinds if isinstance(k, DiscreteLegKind)), 0)
        if rows:
            flat = seg_values[disc_cursor + n_disc: disc_cursor + n_disc + 2 * rows]
            profile = [(flat[2 * r], flat[2 * r + 1]) for r in range(rows)]
        current = dict(speed=E["current_speed"], toward=E["current_toward"], profile=profile,
                       factor=E["load_factor"])

        q = {d: 0 for d in DEGREES_OF_FREEDOM}
        for i, d in enumerate(self.free):
            q[d] = x[i]
        cy, sy = ca.cos(q["yaw"]), ca.sin(q["yaw"])

        fx_total, fy_total, mz_total = 0, 0, 0
        leg_res, leg_out, seg_rows, node_rows = [], [], [], []
        leg_force, tensions, line_weights = [], [], []
        for i, kind in enumerate(self.kinds):
            P = dict(zip(LEG_PARAMS, ca.vertsplit(legp[i * len(LEG_PARAMS):
                                                       (i + 1) * len(LEG_PARAMS)])))
            iu = self.leg_offsets[i]
            if case.body is not None:
                rx = cy * P["fair_x"] - sy * P["fair_y"]
                ry = sy * P["fair_x"] + cy * P["fair_y"]
                gx, gy = q["surge"] + rx, q["sway"] + ry
            else:
                rx = ry = 0
                gx, gy = P["fair_x"], P["fair_y"]
            dx, dy = gx - P["anchor_x"], gy - P["anchor_y"]
            # The tiny floor keeps derivatives finite for a vertical leg (X = 0); it moves
            # X by less than 1e-18 m at any span that matters.
            X = ca.sqrt(dx**2 + dy**2 + _X_FLOOR**2)
            Z = P["fair_z"] - P["anchor_z"]
            if isinstance(kind, MultiLegKind):
                n_par = 3 * len(kind.segments) + kind.n_joints
                values = seg_values[seg_cursor: seg_cursor + n_par]
                seg_cursor += n_par
                res, row, rows = self._multi_leg(i, kind, x, xs, iu, P, values, seabed, X, Z)
                leg_res += res
                seg_rows += rows
                H = row["H"]
            elif isinstance(kind, DiscreteLegKind):
                n_par = len(DISCRETE_PARAMS) * len(kind.elements) + len(kind.elements) - 1
                values = seg_values[disc_cursor: disc_cursor + n_par]
                disc_cursor += n_par
                res, row, rows = self._discrete_leg(i, kind, x, iu, P, values, seabed,
                                                    current, (gx, gy), X, Z)
                leg_res += res
                node_rows += rows
                H = row["H"]
            else:
                u, V = x[iu], x[iu + 1]
                args = dict(X=X, Z=Z, u=u, V=V, L=P["length"], w=P["weight"],
                            ea_inv=P["ea_inv"], mu=P["friction"])
                if kind.law is not None:
                    args["law"] = ca.vertcat(*self._laws[i][0])
                if kind.sloped:
                    # The seabed's rise per metre along the leg, anchor toward fairlead.
                    args["t"] = (seabed["gradient_x"] * dx + seabed["gradient_y"] * dy) / X
                    out = sloped_leg_function(kind.elastic, kind.friction,
                                              kind.law).call(args)
                else:
                    out = leg_function(kind).call(args)
                scale = 1.0 / P["length"]
                leg_res += [out["rX"] * scale, out["rZ"] * scale]
                J = ca.jacobian(ca.vertcat(out["rX"], out["rZ"]),
                                ca.vertcat(xs[iu], xs[iu + 1])) / self.force_scale
                row = dict(out, J=ca.reshape(J, 4, 1))
                H = out["H"]
            # The line pulls the fairlead horizontally toward the anchor with H (a
            # discretised line in a current also sideways: it gives its own force).
            fx, fy = (row["fx"], row["fy"]) if "fx" in row else (-H * dx / X, -H * dy / X)
            fx_total, fy_total = fx_total + fx, fy_total + fy
            mz_total = mz_total + rx * fy - ry * fx
            if isinstance(kind, (MultiLegKind, DiscreteLegKind)):
                # The row's residual is already the largest mismatch force of the leg.
                leg_force.append(row["rX"])
            else:
                leg_force.append(_closing_force(J, out["rX"], out["rZ"]))
            tensions.append(ca.vertcat(ca.hypot(row["H"], row["VF"]),
                                       ca.hypot(row["HA"], row["VA"])))
            # A scale for the certificate when every line is slack (the first line
            # type's weight over the whole length for a multi-segment leg).
            line_weights.append(ca.fabs(P["weight"]) * P["length"])
            leg_out.append(ca.vertcat(row["H"], row["VF"], row["HA"], row["VA"],
                                      row["grounded"], row["suspended_x"], row["rX"],
                                      row["rZ"], X, Z, gx, gy, fx, fy, row["J"]))

        loads = {}
        if case.body is not None:
            applied = dataclasses.replace(case.body.loads, force=None)
            lf = E["load_factor"]
            loads = body_load_models.body_loads(
                applied, case.environment, q["yaw"], E["wind_speed"], E["wind_toward"],
                E["current_speed"], E["current_toward"], E["wave_hs"], E["wave_toward"])
            loads = {k: tuple(lf * c for c in v) for k, v in loads.items()}
            if case.body.loads.force is not None:
                loads["constant_force"] = (lf * E["force_x"], lf * E["force_y"],
                                           lf * E["moment_z"])
        load_x = sum((v[0] for v in loads.values()), ca.SX(0))
        load_y = sum((v[1] for v in loads.values()), ca.SX(0))
        load_m = sum((v[2] for v in loads.values()), ca.SX(0))
        self.load_names = list(loads)

        unbalanced = {"surge": fx_total + load_x, "sway": fy_total + load_y,
                      "yaw": mz_total + load_m}
        body_res = [unbalanced[d] / (self.moment_scale if d == "yaw" else self.force_scale)
                    for d in self.free]
        g = ca.vertcat(*leg_res, *body_res)
        self.residual = ca.Function("residual", [xs, p], [g])
        load_vec = ca.vertcat(*[ca.vertcat(*v) for v in loads.values()]) if loads else ca.DM()
        self.report = ca.Function(
            "report", [xs, p],
            [ca.horzcat(*leg_out).T if leg_out else ca.DM(),
             ca.vertcat(unbalanced["surge"], unbalanced["sway"], unbalanced["yaw"]),
             ca.vertcat(load_x, load_y, load_m), load_vec])
        self.segment_report = ca.Function(
            "segment_report", [xs, p], [ca.horzcat(*seg_rows).T if seg_rows else ca.DM()])
        self.node_report = ca.Function(
            "node_report", [xs, p], [ca.horzcat(*node_rows).T if node_rows else ca.DM()])
        self.jacobian = ca.Function("jacobian", [xs, p], [ca.jacobian(g, xs)])
        # One graph for both, so the Newton kernel evaluates the shared terms once.
        self.residual_jacobian = ca.Function("residual_jacobian", [xs, p],
                                             [g, ca.jacobian(g, xs)])
        self._build_certificate(xs, p, unbalanced, leg_force, tensions, q, line_weights)
        self._xs, self._p, self._g = xs, p, g
        self._nlp_solvers = {}
        self._newton = None
        #: Closed-form starting points by leg parameters (see equilibrium.initial_point).
        self.start_cache: dict[bytes, np.ndarray] = {}

    def _build_certificate(self, xs, p, unbalanced, leg_force, tensions, q, line_weights=()):
        """``certificate(x, p) -> [force_N, moment_Nm, t_max_N]`` and the sweep summary.

        The force is the largest unbalanced force on a free degree of freedom or, per leg,
        the fairlead force that would close its span mismatch (one Newton step of that leg
        alone with its own 2x2 stiffness), so a mismatch anywhere shows up as force.
        ``t_max`` is the largest tension, but never less than 1e-3 of the weight of the
        heaviest line: with every line slack (tensions near zero) the residual is judged
        against the forces the scene carries, not against a vanishing tension.
        """
        forces = [ca.fabs(unbalanced[d]) for d in self.free if d != "yaw"] + leg_force
        force = ca.mmax(ca.vertcat(*forces)) if forces else ca.SX(0)
        moment = ca.fabs(unbalanced["yaw"]) if "yaw" in self.free else ca.SX(0)
        all_t = ca.vertcat(*tensions) if tensions else ca.SX(0)
        t_max = ca.mmax(all_t) if tensions else ca.SX(0)
        if line_weights:
            t_max = ca.fmax(t_max, 1e-3 * ca.mmax(ca.vertcat(*line_weights)))
        self.certificate = ca.Function("certificate", [xs, p], [force, moment, t_max],
                                       ["x", "p"], ["force", "moment", "t_max"])
        T = ca.horzcat(*tensions).T if tensions else ca.SX(0, 2)
        self.summary = ca.Function(
            "summary", [xs, p],
            [ca.vertcat(q["surge"], q["sway"], q["yaw"]), T[:, 0], T[:, 1]],
            ["x", "p"], ["body", "fairlead_tension", "anchor_tension"])

    def certify(self, x, p, tol: float) -> tuple[bool, float, float, float]:
        """``(certified, force_N, moment_Nm, relative)`` of the scaled point ``x``."""
        if not np.all(np.isfinite(x)):
            return False, math.inf, math.inf, math.inf
        force, moment, t_max = (float(v) for v in self.certificate(x, p))
        return self.judge(force, moment, t_max, tol)

    def judge(self, force: float, moment: float, t_max: float, tol: float):
        """``(certified, force, moment, relative)`` from the certificate's three numbers.

        The force must be within ``tol`` of the largest tension, and the moment within
        ``tol`` of that tension times the scene's moment arm.
        """
        scale = t_max if t_max > 0 else self.force_scale
        relative = force / scale
        moment_ok = moment <= tol * scale * self.moment_scale / self.force_scale
        ok = bool(np.isfinite(relative) and np.isfinite(moment) and relative <= tol
                  and moment_ok)
        return ok, force, moment, relative

    def _multi_leg(self, i, kind, x, xs, iu, P, values, seabed, X, Z):
        """Residuals and report rows of a multi-segment leg (see the module notes)."""
        n = len(kind.segments)
        nj = kind.n_joints
        seg = [dict(zip(SEGMENT_PARAMS, values[3 * k: 3 * k + 3])) for k in range(n)]
        clump = values[3 * n: 3 * n + nj]
        u, V_top = x[iu], x[iu + 1]
        xi = [x[iu + 2 + 2 * j] for j in range(nj)]
        sigma = [x[iu + 3 + 2 * j] for j in range(nj)]
        z_bed = -seabed["depth"]
        Vs, N = [], []
        for j in range(nj):
            if _can_ground(kind.segments[j]):
                Vs.append(ca.fmax(sigma[j], 0))
                N.append(ca.fmax(-sigma[j], 0))
            else:
                Vs.append(sigma[j])
                N.append(0 * sigma[j])
        Vs.append(V_top)
        node_xi = [0] + xi + [X]
        node_z = [P["anchor_z"]]
        outs, res, mismatch = [], [], []
        for k, sk in enumerate(kind.segments):
            Xk = node_xi[k + 1] - node_xi[k]
            top = k == n - 1
            # A joint's height is where its lower segment puts it: that segment's height
            # equation defines it instead of being a residual.
            Zk = P["fair_z"] - node_z[k] if top else 0
            h = ca.fmax(node_z[k] - z_bed, 0)
            if top and kind.reversed_top:
                # Solved from the fairlead (on the seabed) toward the joint below.
                Zk = node_z[k] - P["fair_z"]
                h = ca.fmax(P["fair_z"] - z_bed, 0)
            L, w, c = seg[k]["length"], seg[k]["weight"], seg[k]["ea_inv"]
            law = {} if sk.law is None else {"law": ca.vertcat(*self._laws[i][k])}
            if sk.block == "leg":
                o = leg_function(sk.leg).call(dict(X=Xk, Z=Zk, u=u, V=Vs[k], L=L, w=w,
                                                   ea_inv=c, mu=P["friction"], **law))
                o["descent_x"] = 0 * u
            elif sk.block == "lifted":
                o = lifted_segment_function(sk.elastic, sk.friction, sk.law).call(dict(
                    X=Xk, Z=Zk, h=h, u=u, V=Vs[k], L=L, w=w, ea_inv=c, mu=P["friction"],
                    **law))
            else:
                o = straight_segment_function(sk.elastic, sk.law).call(dict(
                    X=Xk, Z=Zk, u=u, V=Vs[k], L=L, ea_inv=c, **law))
            if top:
                res += [o["rX"] / L, o["rZ"] / L]
                e = ca.vertcat(o["rX"], o["rZ"])
                J = ca.jacobian(e, ca.vertcat(xs[iu], xs[iu + 1])) / self.force_scale
                det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
                delta = ca.vertcat(J[1, 1] * e[0] - J[0, 1] * e[1],
                                   -J[1, 0] * e[0] + J[0, 0] * e[1]) / det
                mismatch.append(ca.norm_2(delta))
            else:
                res.append(o["rX"] / L)
                node_z.append(node_z[k] + o["rZ"])
                o["rZ"] = 0 * u
                dX = ca.jacobian(o["rX"], xs[iu]) / self.force_scale
                # An inextensible segment lying straight on the seabed has dX = 0: use the
                # scene's own stiffness scale then.
                mismatch.append(ca.fabs(o["rX"]) / ca.fmax(
                    ca.fabs(dX), self.length_scale / self.force_scale))
            if top and kind.reversed_top:
                # Back to the leg's orientation: the fairlead's vertical tension is minus the
                # block's pull on its lower end; the joint is pulled down by the block's V.
                o = dict(o, VF=-o["VA"], VA=-o["VF"])
                Zk, h = -Zk, ca.fmax(node_z[k] - z_bed, 0)
            outs.append((o, Xk, node_z[k + 1] - node_z[k] if not top else Zk, h))
        joint_force = []
        for j in range(nj):
            # Joint j joins segment j (below) and j + 1 (above): the upper segment pulls it
            # with its signed lower-end force VA, the lower one down with its top tension.
            unbalanced = outs[j + 1][0]["VA"] - Vs[j] - clump[j] + N[j]
            res.append(unbalanced / self.force_scale)
            mismatch.append(ca.fabs(unbalanced))
            joint_force.append(unbalanced)
        worst = mismatch[0]
        for m in mismatch[1:]:
            worst = ca.fmax(worst, m)
        top, bottom = outs[-1][0], outs[0][0]
        grounded = sum((o["grounded"] for o, _, _, _ in outs), 0 * u)
        row = dict(H=top["H"], VF=top["VF"], HA=bottom["HA"], VA=bottom["VA"],
                   grounded=grounded, suspended_x=top["suspended_x"], rX=worst, rZ=0 * u,
                   J=ca.DM([1.0, 0.0, 0.0, 1.0]))
        rows = []
        for k, (o, Xk, Zk, h) in enumerate(outs):
            rows.append(ca.vertcat(
                i, k, o["H"], o["VF"], o["HA"], o["VA"], o["grounded"], o["suspended_x"],
                o["descent_x"], o["rX"], o["rZ"], Xk, Zk, h, node_xi[k], node_z[k],
                joint_force[k] if k < nj else 0, N[k] if k < nj else 0, mismatch[k]))
        return res, row, rows

    def _discrete_leg(self, i, kind, x, iu, P, values, seabed, current, fair_xy, X, Z):
        """Residuals and report rows of a lumped-node leg (see :mod:`.discrete` notes)."""
        from .discrete import discrete_leg
        return discrete_leg(self, i, kind, x, iu, P, values, seabed, current, fair_xy, X, Z)

    # -- solvers --------------------------------------------------------------------
    def ipopt(self, tol: float, max_iter: int, max_time_s: float) -> ca.Function:
        """An IPOPT solver for the feasibility NLP, cached per setting."""
        key = (tol, max_iter, max_time_s)
        if key not in self._nlp_solvers:
            nlp = {"x": self._xs, "p": self._p, "f": 0, "g": self._g}
            opts = {
                "print_time": False,
                "error_on_fail": False,
                # A NaN or inf met on the way (absurd input) is reported by the certificate
                # and ConvergenceError; CasADi's own per-evaluation warnings are noise.
                "show_eval_warnings": False, "calc_lam_p": False,
                "ipopt": {
                    "print_level": 0, "sb": "yes", "tol": tol,
                    "constr_viol_tol": tol, "max_iter": max_iter,
                    "max_wall_time": max_time_s, "nlp_scaling_method": "none",
                    "mu_strategy": "adaptive",
                },
            }
            self._nlp_solvers[key] = ca.nlpsol("equilibrium", "ipopt", nlp, opts)
        return self._nlp_solvers[key]

    def newton(self):
        """The fast-path Newton kernel (:mod:`.newton`), built and compiled on first use."""
        if self._newton is None:
            from .newton import NewtonKernel
            self._newton = NewtonKernel(self)
        return self._newton

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lb = np.full(self.n_x, -np.inf)
        ub = np.full(self.n_x, np.inf)
        for i, d in enumerate(self.free):
            if d == "yaw":
                lb[i], ub[i] = -YAW_LIMIT, YAW_LIMIT
        for i, kind in enumerate(self.kinds):
            if not kind.contact and not kind.neutral:
                lb[self.leg_offsets[i]] = 0.0   # a hanging catenary cannot go slack
        return lb, ub


def _closing_force(J, rX, rZ):
    """Size of the fairlead force change that closes a leg's span mismatch ``(rX, rZ)``.

    ``J`` is the leg's 2x2 derivative of the spans by ``(u, V)``; a singular ``J`` with a
    nonzero mismatch gives infinity (the leg cannot be closed by a finite force).
    """
    a, b, c, d = J[0, 0], J[0, 1], J[1, 0], J[1, 1]
    det = a * d - b * c
    du = d * rX - b * rZ
    dV = -c * rX + a * rZ
    mismatch = ca.fabs(rX) + ca.fabs(rZ)
    return ca.if_else(det != 0, ca.hypot(du, dV) / ca.fabs(det),
                      ca.if_else(mismatch > 0, ca.inf, 0))


def _body_radius(case: Case) -> float:
    if case.body is None or not case.legs:
        return 1.0
    return max(1.0, max(math.hypot(leg.fairlead[0], leg.fairlead[1]) for leg in case.legs))
