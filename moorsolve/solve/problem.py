"""Build the coupled equilibrium of a body and its legs as one CasADi problem.

Unknowns: the body's free degrees of freedom (surge = global x, sway = global y
displacement of the body origin, yaw about the vertical) and, per leg, the signed tension
variable ``u`` and the fairlead vertical tension ``V`` of :mod:`moorsolve.physics.catenary`.
Equations: each leg's two span residuals, and the force and moment balance of each free
degree of freedom. The problem is square; IPOPT solves it as a feasibility NLP.

Everything that may change between solves of one scene is a parameter (environment speeds
and headings, a load factor, the constant force, and per leg the anchor, fairlead, length,
weight, compliance and friction), so one build serves a whole sweep.
"""

from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np

from ..model import DEGREES_OF_FREEDOM, Case, Leg
from ..physics import loads as body_load_models
from ..physics.catenary import LegKind, leg_function

#: Environment parameter layout (angles in radians).
ENV_PARAMS = ("wind_speed", "wind_toward", "current_speed", "current_toward",
              "wave_hs", "wave_toward", "force_x", "force_y", "moment_z", "load_factor")
#: Per-leg parameter layout.
LEG_PARAMS = ("anchor_x", "anchor_y", "anchor_z", "fair_x", "fair_y", "fair_z",
              "length", "weight", "ea_inv", "friction")

#: Yaw is bounded to keep the solver away from the mirrored equilibrium with the lines
#: crossing under the hull (yaw near 180 deg, REFERENCE.md section 1).
YAW_LIMIT = math.pi / 2
_X_FLOOR = 1e-12


def leg_kind(case: Case, leg: Leg) -> LegKind:
    """The physics a leg needs, from what the case declares."""
    lt = leg.line_type
    w = lt.weight_in_water
    on_seabed = leg.anchor[2] <= -case.environment.depth + 1e-9
    contact = on_seabed and w > 0
    return LegKind(elastic=lt.elastic, contact=contact,
                   friction=contact and case.environment.seabed.friction > 0,
                   neutral=(w == 0))


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


class EquilibriumProblem:
    """The symbolic problem of one case structure, built once.

    Attributes
    ----------
    free : tuple of str
        Solved degrees of freedom, in ``DEGREES_OF_FREEDOM`` order.
    kinds : list of LegKind
    n_q, n_x, n_p : int
        Numbers of body unknowns, all unknowns and parameters.
    residual : casadi.Function
        ``(x, p) -> g`` scaled residuals (legs first, then body balance).
    report : casadi.Function
        ``(x, p) ->`` per-leg end forces, spans and Jacobian blocks, and the body's
        unbalanced load, used for the certificate and the result.
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
        self.n_x = self.n_q + 2 * self.n_legs
        self.force_scale = force_scale
        self.length_scale = length_scale
        self.moment_scale = force_scale * max(length_scale, _body_radius(case))
        self.x_scale = np.array(
            [length_scale if d != "yaw" else 1.0 for d in self.free]
            + [force_scale] * (2 * self.n_legs))
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
        if any(k.contact for k in self.kinds):
            effects.append("seabed_contact")
        if any(k.friction for k in self.kinds):
            effects.append("seabed_friction")
        if any(leg.line_type.weight_in_water < 0 for leg in case.legs):
            effects.append("buoyant_line")
        if any(k.neutral for k in self.kinds):
            effects.append("neutral_line")
        if any(leg.line_type.sealed for leg in case.legs):
            effects.append("wall_tension")
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
        p = ca.vertcat(env, legp)
        self.n_p = p.numel()
        E = dict(zip(ENV_PARAMS, ca.vertsplit(env)))

        q = {d: 0 for d in DEGREES_OF_FREEDOM}
        for i, d in enumerate(self.free):
            q[d] = x[i]
        cy, sy = ca.cos(q["yaw"]), ca.sin(q["yaw"])

        fx_total, fy_total, mz_total = 0, 0, 0
        leg_res, leg_out = [], []
        leg_force, tensions = [], []
        for i, kind in enumerate(self.kinds):
            P = dict(zip(LEG_PARAMS, ca.vertsplit(legp[i * len(LEG_PARAMS):
                                                       (i + 1) * len(LEG_PARAMS)])))
            u, V = x[self.n_q + 2 * i], x[self.n_q + 2 * i + 1]
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
            out = leg_function(kind).call(dict(X=X, Z=Z, u=u, V=V, L=P["length"],
                                               w=P["weight"], ea_inv=P["ea_inv"],
                                               mu=P["friction"]))
            scale = 1.0 / P["length"]
            leg_res += [out["rX"] * scale, out["rZ"] * scale]
            # The line pulls the fairlead horizontally toward the anchor with H.
            fx, fy = -out["H"] * dx / X, -out["H"] * dy / X
            fx_total, fy_total = fx_total + fx, fy_total + fy
            mz_total = mz_total + rx * fy - ry * fx
            iu = self.n_q + 2 * i
            J = ca.jacobian(ca.vertcat(out["rX"], out["rZ"]),
                            ca.vertcat(xs[iu], xs[iu + 1])) / self.force_scale
            leg_force.append(_closing_force(J, out["rX"], out["rZ"]))
            tensions.append(ca.vertcat(ca.hypot(out["H"], out["VF"]),
                                       ca.hypot(out["HA"], out["VA"])))
            leg_out.append(ca.vertcat(out["H"], out["VF"], out["HA"], out["VA"],
                                      out["grounded"], out["suspended_x"], out["rX"],
                                      out["rZ"], X, Z, gx, gy, fx, fy,
                                      ca.reshape(J, 4, 1)))

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
        self.jacobian = ca.Function("jacobian", [xs, p], [ca.jacobian(g, xs)])
        # One graph for both, so the Newton kernel evaluates the shared terms once.
        self.residual_jacobian = ca.Function("residual_jacobian", [xs, p],
                                             [g, ca.jacobian(g, xs)])
        self._build_certificate(xs, p, unbalanced, leg_force, tensions, q)
        self._xs, self._p, self._g = xs, p, g
        self._nlp_solvers = {}
        self._newton = None
        #: Closed-form starting points by leg parameters (see equilibrium.initial_point).
        self.start_cache: dict[bytes, np.ndarray] = {}

    def _build_certificate(self, xs, p, unbalanced, leg_force, tensions, q):
        """``certificate(x, p) -> [force_N, moment_Nm, t_max_N]`` and the sweep summary.

        The force is the largest unbalanced force on a free degree of freedom or, per leg,
        the fairlead force that would close its span mismatch (one Newton step of that leg
        alone with its own 2x2 stiffness), so a mismatch anywhere shows up as force.
        """
        forces = [ca.fabs(unbalanced[d]) for d in self.free if d != "yaw"] + leg_force
        force = ca.mmax(ca.vertcat(*forces)) if forces else ca.SX(0)
        moment = ca.fabs(unbalanced["yaw"]) if "yaw" in self.free else ca.SX(0)
        all_t = ca.vertcat(*tensions) if tensions else ca.SX(0)
        t_max = ca.mmax(all_t) if tensions else ca.SX(0)
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

    # -- solvers --------------------------------------------------------------------
    def ipopt(self, tol: float, max_iter: int, max_time_s: float) -> ca.Function:
        """An IPOPT solver for the feasibility NLP, cached per setting."""
        key = (tol, max_iter, max_time_s)
        if key not in self._nlp_solvers:
            nlp = {"x": self._xs, "p": self._p, "f": 0, "g": self._g}
            opts = {
                "print_time": False,
                "error_on_fail": False,
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
                lb[self.n_q + 2 * i] = 0.0      # a hanging catenary cannot go slack
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
