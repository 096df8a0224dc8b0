"""The balance of the nodes of a scene: bodies (weight, hydrostatics, loads, springs) and
free points (net weight, seabed reaction), on top of what lines and contacts put on them.
"""

from __future__ import annotations

import casadi as ca

from ...physics.hydrostatics import linear_buoyancy, member_buoyancy, weight
from ...physics.kinematics import generalized_forces
from . import body_loads as body_load_models
from .layout import MEMBER_PARAMS


def node_balances(case, par, E, seabed, poses, rotations, body_force, body_moment, points,
                  k_contact: float) -> dict:
    """The generalized forces of every body and the forces on every free point.

    ``body_force``/``body_moment`` hold what the lines and contacts already put on each
    body (about its origin); this adds the weight, the hydrostatics (about the water level),
    the load models and the constant force, then turns force and moment into the six
    generalized forces (:func:`~moorsolve.physics.kinematics.generalized_forces`) and adds
    the springs. Free points get their net weight and the seabed's reaction.

    Returns a dict: ``generalized`` (a 6-vector per body), ``point_forces``, ``wrenches``
    (force and moment per body), ``load_vectors`` and ``load_names`` (one per load),
    ``body_scale`` (the forces each balance carries, for the certificate's scale) and
    ``hull_range`` (per exact hull member, 1 where its formula holds).
    """
    env = case.environment
    lf = E["load_factor"]
    load_vectors, load_names = [], []
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
            load_names.append(key if len(case.bodies) == 1 else f"{body.name}.{key}")
        if body.loads.force is not None:
            if case.form == "legs" and bi == 0:
                cf = ca.vertcat(E["force_x"], E["force_y"], 0)
                cm = ca.vertcat(0, 0, E["moment_z"])
            else:
                f6 = par(name + ".force")
                cf, cm = f6[:3], f6[3:]
            F, M = F + lf * cf, M + lf * cm
            load_vectors.append(ca.vertcat(lf * cf, lf * cm))
            load_names.append("constant_force" if len(case.bodies) == 1
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
        bed = pt.get("bed", seabed)           # its own plane on a bathymetry grid
        gx, gy = bed["gradient_x"], bed["gradient_y"]
        normal = ca.vertcat(-gx, -gy, 1) / ca.sqrt(1 + gx**2 + gy**2)
        N = ca.fmax(-pt["zeta"], 0) * k_contact
        force = pt["force"] + ca.vertcat(0, 0, -net) + N * normal
        point_forces.append(force)
        body_scale.append(ca.fabs(net))

    return dict(generalized=generalized, point_forces=point_forces, wrenches=wrenches,
                load_vectors=load_vectors, load_names=load_names, body_scale=body_scale,
                hull_range=hull_range)
