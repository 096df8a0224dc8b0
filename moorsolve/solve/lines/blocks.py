"""Line kinds behind one protocol: what each line needs, and its block in the problem.

Every line, whatever its kind, enters the equilibrium the same way: it has its own unknowns
(scaled by :meth:`LineKind.scales`), it adds its residuals, and it pulls on its two ends with
forces that the assembly (:mod:`.problem`) adds to the bodies and points those ends belong
to. :func:`line_block` builds that for a kind from the ends' global positions (symbols):

- ``single``: one segment, in the vertical plane through its ends: the catenary leg block of
  :mod:`moorsolve.physics.catenary` (anchored on the seabed, on a sloped seabed, suspended,
  weightless) or, for a sinking line whose lower end is above the seabed or moves (a free
  point, a body), the lifted block that can touch down between its ends;
- ``multi``: several segments with clumps and buoys at the joints, still in one vertical
  plane (every load on it is vertical), with each joint a free node of the line;
- ``discrete``: a lumped-node line in a current, which leaves its vertical plane
  (:mod:`.discrete`).

The catenary blocks solve from their lower end: the end on the seabed if one is (an anchor),
otherwise the end lower in the case. A line whose end B is that lower end is *flipped*: its
blocks run from B, and its forces are mapped back to A and B.

Multi-segment lines
-------------------
A leg of several segments (chain-polyester-chain, clump weights, buoys) stays in the
vertical plane through its ends: every load on it (weights, clumps, buoys, the seabed's
reaction) is vertical and friction acts along the line, so the horizontal tension is the same
in every segment and no force leaves the plane. The 2-D model is exact. Its unknowns are
``u`` (shared by all segments), the top end's ``V`` and per joint

- ``xi``: the joint's horizontal distance from the lower end in the line's plane [m];
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
between two points above or on the seabed. When the top end itself rests on the seabed the
top segment is solved from that end (``MultiLegKind.reversed_top``) for the same reason.
Limits: a joint rests on the seabed only with the segment below arriving along it (not
hanging down into it); seabed friction acts on the anchor segment only; a buoy's lift is
constant (fully submerged); the seabed under a multi-segment line is flat.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import casadi as ca

from ...physics.air import air_line
from ...physics.catenary import LEG_OUTPUTS, air_part, leg_function, weightless_line_function
from ...physics.segments import (descent_force, lifted_segment_function, straight_segment_function,
                                surface_leg_function, surface_segment_function)
from ...physics.sloped import sloped_leg_function
from ...physics.stretch import Law
from .line_kinds import LineKind, SegmentKind

__all__ = ["LineBlock", "closing_force", "plane_geometry", "single_block", "multi_block",
           "span_jacobian", "seabed_height"]

#: Keeps derivatives finite for a vertical line (X = 0); moves X by less than 1e-18 m.
_X_FLOOR = 1e-12
#: Below this horizontal span [fraction of the line's length] a line's horizontal pull
#: ``H e`` (``e = d/X``, ``d`` the horizontal offset of its ends) is written ``(dH/dX) d``:
#: its limit at ``X -> 0``, where ``H/X`` is ``0/0`` (see :func:`horizontal_pull`).
_NEAR_VERTICAL = 1e-6
#: [N/m] below which a segment's H/X counts as zero in the series sum (a slack segment).
_LATERAL_FLOOR = 1e-12

@dataclass
class LineBlock:
    """What a line contributes to the problem (CasADi expressions).

    ``residuals`` (scaled), ``force_a`` and ``force_b`` (3-vectors: the line's pull on its
    ends A and B, global [N]), ``closing`` (the force [N] that would close its mismatch,
    for the certificate), ``tensions`` (its end tensions [N]), ``row`` (the report row of
    :data:`REPORT_COLUMNS` quantities) and the per-segment or per-node rows.
    """

    residuals: list
    force_a: object
    force_b: object
    closing: object
    row: dict
    segment_rows: list
    node_rows: list


def closing_force(J, rX, rZ):
    """Size of the end-force change that closes a line's span mismatch ``(rX, rZ)``.

    ``J`` is the line's 2x2 derivative of the spans by ``(u, V)``; a singular ``J`` with a
    nonzero mismatch gives infinity (the line cannot be closed by a finite force).
    """
    a, b, c, d = J[0, 0], J[0, 1], J[1, 0], J[1, 1]
    det = a * d - b * c
    du = d * rX - b * rZ
    dV = -c * rX + a * rZ
    mismatch = ca.fabs(rX) + ca.fabs(rZ)
    return ca.if_else(det != 0, ca.hypot(du, dV) / ca.fabs(det),
                      ca.if_else(mismatch > 0, ca.inf, 0))


def plane_geometry(lower, upper):
    """Horizontal direction (unit, lower toward upper), span ``X`` and rise ``Z``."""
    dx, dy = upper[0] - lower[0], upper[1] - lower[1]
    X = ca.sqrt(dx**2 + dy**2 + _X_FLOOR**2)
    return dx / X, dy / X, X, upper[2] - lower[2]


def single_block(problem, i, kind: LineKind, xs, x, iu, P, seabed, lower, upper) -> LineBlock:
    """The block of a one-segment line (see the module notes)."""
    ux, uy, X, Z = plane_geometry(lower, upper)
    u, V = x[iu], x[iu + 1]
    block = kind.block
    args = dict(X=X, Z=Z, u=u, V=V, L=P["length"], w=P["weight"], ea_inv=P["ea_inv"],
                mu=P["friction"])
    law = None
    if block.law is not None:
        # The stretch law's parameters (solve/lines/stretch_params.py).
        args["law"] = ca.vertcat(*problem.line_laws[i][0])
        law = Law(block.law, problem.line_laws[i][0])
    if block.air_ends:
        return _air_line_block(problem, kind, xs, iu, P, args, law, ux, uy, upper)
    air = None
    if block.air:
        # The upper end is above the water: its part in air, in closed form, then the water
        # block up to the surface crossing (its top, at z = 0).
        air = air_part(ca.fmax(u, 0), V, upper[2], P["weight_air"],
                       P["ea_inv"] if block.elastic else 0, law=law)
        args = dict(args, X=X - air["x"], Z=-lower[2], V=air["V"],
                    L=P["length"] - air["length"])
    if kind.lifted:
        args["h"] = ca.fmax(lower[2] - seabed_height(seabed, lower[0], lower[1]), 0)
        fn = lifted_segment_function(block.elastic, False, model=block.law)
    elif block.neutral:
        law = {} if block.law is None else {"law": args["law"]}
        args = dict(X=X, Z=Z, u=u, V=V, L=P["length"], ea_inv=P["ea_inv"],
                    k=problem.contact_stiffness, eps=problem.smoothing_symbol, **law)
        fn = weightless_line_function(block.elastic, block.law)
    elif block.surface:
        # Depth below the surface of the end the block starts from.
        start_z = upper[2] if block.from_fairlead else lower[2]
        args["d"] = ca.fmax(-start_z, 0)
        fn = surface_leg_function(block.elastic, block.from_fairlead, block.law)
    elif block.sloped:
        # The seabed's rise per metre along the line, lower end toward upper end.
        args["t"] = seabed["gradient_x"] * ux + seabed["gradient_y"] * uy
        fn = sloped_leg_function(block.elastic, block.friction, block.law)
    else:
        fn = leg_function(block)
    out = fn.call(args)
    if air is not None:
        out = dict(out, VF=V, suspended_x=out["suspended_x"] + air["x"])
    scale = 1.0 / P["length"]
    residuals = [out["rX"] * scale, out["rZ"] * scale]
    if air is None:
        # The line's 2x2 block d(rX, rZ)/d(u, V), from the block's own derivative function
        # (a Jacobian taken against the whole unknown vector costs O(lines) per line).
        J = span_jacobian(fn).call(args)["J"]
    else:
        # The part in air depends on (u, V) too: the derivative through it.
        J = ca.jacobian(ca.vertcat(out["rX"], out["rZ"]),
                        ca.vertcat(xs[iu], xs[iu + 1])) / problem.force_scale
    # A block that knows H/X on its own span without 0/0 (a line hanging straight down)
    # says so; the part in air shifts the water block's span, so not there.
    lateral = out.get("lateral") if air is None else None
    offset = ca.vertcat(upper[0] - lower[0], upper[1] - lower[1])
    near = X < _NEAR_VERTICAL * P["length"]
    on_upper = ca.vertcat(-horizontal_pull(out["H"], X, offset, near, lateral), -out["VF"])
    on_lower = ca.vertcat(horizontal_pull(out["HA"], X, offset, near, lateral), out["VA"])
    row = dict(out, J=ca.reshape(J, 4, 1), X=X, Z=Z)
    force_a, force_b = (on_upper, on_lower) if kind.flipped else (on_lower, on_upper)
    return LineBlock(residuals, force_a, force_b, closing_force(J, out["rX"], out["rZ"]),
                     row, [], [])


def _air_line_block(problem, kind, xs, iu, P, args, law, ux, uy, upper) -> LineBlock:
    """A one-segment line with both ends above the water (physics/air.py)."""
    block = kind.block
    out = air_line(args["X"], args["Z"], args["u"], args["V"], upper[2], P["length"],
                   P["weight"], P["weight_air"], P["ea_inv"] if block.elastic else 0,
                   law=law)
    scale = 1.0 / P["length"]
    J = ca.jacobian(ca.vertcat(out["rX"], out["rZ"]),
                    ca.vertcat(xs[iu], xs[iu + 1])) / problem.force_scale
    on_upper = ca.vertcat(-out["H"] * ux, -out["H"] * uy, -out["VF"])
    on_lower = ca.vertcat(out["HA"] * ux, out["HA"] * uy, out["VA"])
    row = dict({k: out[k] for k in LEG_OUTPUTS}, J=ca.reshape(J, 4, 1), X=args["X"],
               Z=args["Z"])
    force_a, force_b = (on_upper, on_lower) if kind.flipped else (on_lower, on_upper)
    return LineBlock([out["rX"] * scale, out["rZ"] * scale], force_a, force_b,
                     closing_force(J, out["rX"], out["rZ"]), row, [], [])


def horizontal_pull(H, X, offset, near, lateral=None):
    """The horizontal force ``H e`` [N] of a line along its plane's direction ``e =
    offset / X`` (``offset`` the horizontal vector from its lower to its upper end [m]).

    ``H(X)`` vanishes with the span (a line hanging straight down pulls straight down), so
    ``H e = (H/X) offset`` is smooth in ``offset`` at ``X = 0`` although ``X = |offset|`` is
    not: its derivative there is ``(dH/dX) I``, the lateral stiffness of the hanging line.
    Written as ``H e`` at the floored span its derivative is ``H/X`` = 0/0 (whatever the
    solve left in ``H``). Within ``near`` (``X`` below :data:`_NEAR_VERTICAL` of the length)
    the block's own ``lateral`` (``H/X`` on its span, which it evaluates without 0/0:
    :func:`~moorsolve.physics.catenary.lateral_stiffness`) is used instead; at an
    equilibrium the two are equal. Both ends of a line hanging straight are suspended, so
    the lower end's ``H_A = H`` shares it.
    """
    if lateral is None:
        return (H / X) * offset
    return ca.if_else(near, lateral, H / X) * offset


@lru_cache(maxsize=None)
def span_jacobian(fn: ca.Function) -> ca.Function:
    """``J = d(rX, rZ)/d(u, V)`` (2x2) of a catenary block function, same inputs."""
    args = {name: ca.SX.sym(name, fn.size1_in(k), fn.size2_in(k))
            for k, name in enumerate(fn.name_in())}
    out = fn.call(args)
    J = ca.jacobian(ca.vertcat(out["rX"], out["rZ"]), ca.vertcat(args["u"], args["V"]))
    return ca.Function(fn.name() + "_span_jacobian", list(args.values()), [J],
                       list(args), ["J"])


def seabed_height(seabed, x, y):
    """Height of the seabed [m] at ``(x, y)`` from the seabed parameters (symbolic)."""
    return -seabed["depth"] + seabed["gradient_x"] * x + seabed["gradient_y"] * y


def multi_block(problem, i, kind: LineKind, xs, x, iu, values, P, seabed, lower,
                upper) -> LineBlock:
    """The block of a multi-segment line (see the module notes). ``values`` are its
    segment parameters in the line's own order (from end A)."""
    block = kind.block
    n = len(block.segments)
    nj = block.n_joints
    seg = [dict(zip(("length", "weight", "ea_inv"), values[3 * k: 3 * k + 3]))
           for k in range(n)]
    clump = list(values[3 * n: 3 * n + nj])
    laws = list(problem.line_laws[i])
    if kind.flipped:
        seg, clump, laws = seg[::-1], clump[::-1], laws[::-1]
    _, _, X, Z = plane_geometry(lower, upper)
    u, V_top = x[iu], x[iu + 1]
    xi = [x[iu + 2 + 2 * j] for j in range(nj)]
    sigma = [x[iu + 3 + 2 * j] for j in range(nj)]
    z_bed = seabed_height(seabed, lower[0], lower[1])
    Vs, N = [None] * nj + [V_top], []
    node_xi = [0] + xi + [X]
    node_z = [lower[2]]
    outs, res, mismatch = [], [], []
    for k, sk in enumerate(block.segments):
        Xk = node_xi[k + 1] - node_xi[k]
        top = k == n - 1
        # A joint's height is where its lower segment puts it: that segment's height
        # equation defines it instead of being a residual.
        Zk = upper[2] - node_z[k] if top else 0
        h = ca.fmax(node_z[k] - z_bed, 0)
        d = ca.fmax(-node_z[k], 0)          # depth below the surface
        if top and block.reversed_top:
            # Solved from the top end (on the seabed, or at the surface for a floating top
            # segment) toward the joint below.
            Zk = node_z[k] - upper[2]
            h = ca.fmax(upper[2] - z_bed, 0)
            d = ca.fmax(-upper[2], 0)
        L, w, c = seg[k]["length"], seg[k]["weight"], seg[k]["ea_inv"]
        # A stretch law other than Hooke's: its parameters (solve/lines/stretch_params.py).
        law = {} if sk.law is None else {"law": ca.vertcat(*laws[k])}
        if not top:
            bound = None if sk.law is None else Law(sk.law, laws[k])
            Vs[k], Nk = _joint_split(sk, sigma[k], u, L, w, c if sk.elastic else 0, h, d,
                                     bound)
            N.append(Nk)
        if sk.block == "leg":
            o = leg_function(sk.leg).call(dict(X=Xk, Z=Zk, u=u, V=Vs[k], L=L, w=w,
                                               ea_inv=c, mu=P["friction"], **law))
            o["descent_x"] = 0 * u
        elif sk.block == "floating":
            o = surface_segment_function(sk.elastic, True, sk.law).call(dict(
                X=Xk, Z=Zk, h=d, u=u, V=Vs[k], L=L, w=w, ea_inv=c, mu=0, **law))
        elif sk.block == "lifted":
            o = lifted_segment_function(sk.elastic, sk.friction, True, sk.law).call(dict(
                X=Xk, Z=Zk, h=h, u=u, V=Vs[k], L=L, w=w, ea_inv=c, mu=P["friction"], **law))
        else:
            o = straight_segment_function(sk.elastic, sk.law).call(dict(
                X=Xk, Z=Zk, u=u, V=Vs[k], L=L, ea_inv=c, **law))
        if top:
            res += [o["rX"] / L, o["rZ"] / L]
            e = ca.vertcat(o["rX"], o["rZ"])
            J = ca.jacobian(e, ca.vertcat(xs[iu], xs[iu + 1])) / problem.force_scale
            det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
            delta = ca.vertcat(J[1, 1] * e[0] - J[0, 1] * e[1],
                               -J[1, 0] * e[0] + J[0, 0] * e[1]) / det
            mismatch.append(ca.norm_2(delta))
        else:
            res.append(o["rX"] / L)
            node_z.append(node_z[k] + o["rZ"])
            o["rZ"] = 0 * u
            dX = ca.jacobian(o["rX"], xs[iu]) / problem.force_scale
            # An inextensible segment lying straight on the seabed has dX = 0: use the
            # scene's own stiffness scale then.
            mismatch.append(ca.fabs(o["rX"]) / ca.fmax(
                ca.fabs(dX), problem.length_scale / problem.force_scale))
        if top and block.reversed_top:
            # Back to the line's orientation: the top end's vertical tension is minus the
            # block's pull on its lower end; the joint is pulled down by the block's V.
            o = dict(o, VF=-o["VA"], VA=-o["VF"])
            Zk, h = -Zk, ca.fmax(node_z[k] - z_bed, 0)
        outs.append((o, Xk, node_z[k + 1] - node_z[k] if not top else Zk, h))
    joint_force = []
    for j in range(nj):
        # Joint j joins segment j (below) and j + 1 (above): the upper segment pulls it
        # with its signed lower-end force VA, the lower one down with its top tension.
        unbalanced = outs[j + 1][0]["VA"] - Vs[j] - clump[j] + N[j]
        res.append(unbalanced / problem.force_scale)
        mismatch.append(ca.fabs(unbalanced))
        joint_force.append(unbalanced)
    worst = mismatch[0]
    for m in mismatch[1:]:
        worst = ca.fmax(worst, m)
    top, bottom = outs[-1][0], outs[0][0]
    grounded = sum((o["grounded"] for o, _, _, _ in outs), 0 * u)
    floating = sum((o.get("floating", 0 * u) for o, _, _, _ in outs), 0 * u)
    row = dict(H=top["H"], VF=top["VF"], HA=bottom["HA"], VA=bottom["VA"],
               grounded=grounded, suspended_x=top["suspended_x"], rX=worst, rZ=0 * u,
               J=ca.DM([1.0, 0.0, 0.0, 1.0]), X=X, Z=Z, floating=floating)
    rows = []
    for k, (o, Xk, Zk, h) in enumerate(outs):
        rows.append(ca.vertcat(
            i, k, o["H"], o["VF"], o["HA"], o["VA"], o["grounded"], o["suspended_x"],
            o["descent_x"], o["rX"], o["rZ"], Xk, Zk, h, node_xi[k], node_z[k],
            joint_force[k] if k < nj else 0, N[k] if k < nj else 0, mismatch[k],
            o.get("floating", 0 * u)))
    # Hanging straight, the segments' spans add up as springs in series: H/X of the line
    # is 1 / sum(1 / (H/X_k)) when every segment's block gives its own.
    lateral = None
    if all("lateral" in o for o, _, _, _ in outs):
        lateral = 1 / sum((1 / ca.fmax(o["lateral"], _LATERAL_FLOOR) for o, _, _, _ in outs),
                          0 * u)
    offset = ca.vertcat(upper[0] - lower[0], upper[1] - lower[1])
    near = X < _NEAR_VERTICAL * sum((s["length"] for s in seg), 0 * u)
    on_upper = ca.vertcat(-horizontal_pull(top["H"], X, offset, near, lateral), -top["VF"])
    on_lower = ca.vertcat(horizontal_pull(bottom["HA"], X, offset, near, lateral),
                          bottom["VA"])
    force_a, force_b = (on_upper, on_lower) if kind.flipped else (on_lower, on_upper)
    return LineBlock(res, force_a, force_b, worst, row, rows, [])


def _joint_split(kind: SegmentKind, sigma, u, L, w, c, h, d, law=None):
    """The top tension ``V`` of the segment below a joint and the boundary's reaction on
    the joint [N, upward], from the joint's signed unknown ``sigma``.

    A sinking segment arrives at a joint on the seabed along it (``V = 0``) and the seabed
    pushes the joint up: ``V = max(sigma, 0)``, ``N = max(-sigma, 0)``; a buoyant segment
    mirrors it at the surface (``V = min(sigma, 0)``, ``N = -max(sigma, 0)``). The split is
    offered only where the segment, hanging with ``V = 0`` from its lower end (``h`` above
    the seabed, or ``d`` below the surface), reaches the boundary at all; otherwise ``V =
    sigma`` and no reaction. Without that condition a state with the segment's vertex at the
    joint, clear of the boundary, and a reaction holding the joint there would satisfy every
    equation: a false root the solver can fall into. ``law``: the segment's
    bound stretch law when it is not Hooke's.
    """
    if kind.block == "lifted":
        V1 = descent_force(ca.fmax(u, 0), h, w, c, law)
        reaches = w * L > -V1
        return (ca.if_else(reaches, ca.fmax(sigma, 0), sigma),
                ca.if_else(reaches, ca.fmax(-sigma, 0), 0))
    if kind.block == "floating":
        V1 = descent_force(ca.fmax(u, 0), d, -w, c, law)
        reaches = -w * L > -V1
        return (ca.if_else(reaches, ca.fmin(sigma, 0), sigma),
                ca.if_else(reaches, -ca.fmax(sigma, 0), 0))
    return sigma, 0 * sigma
