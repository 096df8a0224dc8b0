"""A leg as a lumped-node line, for lines that feel the current.

When a case has a current and a leg's line type gives drag data, the flow pushes the line
itself sideways and the leg leaves its vertical plane; no closed form covers that. The leg
is then cut into ``N`` straight elements (``solver.line_elements``, default 20, shared among
its segments in proportion to their lengths; a joint between segments is always a node).

Unknowns, in the same NLP as the body and the analytic legs: the tension ``T_e`` of each
element and, for each inner node, its horizontal position ``(x, y)`` and a signed height
``zeta`` above the seabed plane. Equations:

- each element's length: ``|r_e - r_{e-1}| = L_e (1 + T_e / EA)`` (Hooke; inextensible
  without an EA; ``L_e (1 + eps(T_e))`` with another stretch law,
  :mod:`moorsolve.physics.stretch`), so tension and stretch are exact at every element;
- each inner node's force balance (3-D): the two element tensions along their chords, half
  of each adjacent element's submerged weight ``w L_e`` (on the unstretched length) and flow
  force (:func:`moorsolve.physics.drag.line_drag` on the stretched chord, at the current
  speed of the chord's mid-height), a clump's weight at a joint, and the seabed's reaction.

Seabed contact is exact complementarity through the signed unknown, as for the joints of the
analytic multi-segment legs: the node's height above the seabed is ``max(zeta, 0)`` and the
seabed pushes it along the plane's normal with ``max(-zeta, 0) force_scale / length_scale``
[N]. The free surface bounds the node from above by the same unknown: its height above the
seabed is capped at the local water depth ``D`` (``clip(zeta, 0, D)``) and the surface holds a
node that would rise above it down with ``max(zeta - D, 0) force_scale / length_scale`` [N]
(a buoyant line floats). A node on the seabed is frictionless
(seabed friction acts only on analytic legs); on a sloped seabed a grounded node can slide
down the plane. The fairlead node carries half of the top element's weight and flow force
onto the body, the anchor node half of the first one's.

The discretisation is the midpoint rule for the distributed load: without current it tends
to the elastic catenary with the element count; the tests report the observed order. The
flow force is multiplied by the load factor, so load stepping ramps it with the body loads.
"""

from __future__ import annotations

import casadi as ca

from ...physics.drag import current_velocity, line_drag
from ...physics.stretch import Law
from ..assembly.layout import DISCRETE_PARAMS
from .blocks import LineBlock

#: Columns of ``EquilibriumProblem.node_report``: per node of a discretised leg (anchor
#: first), its position [m], the line tension there [N] (the end resultant at the anchor and
#: fairlead, the mean of the two elements elsewhere), the seabed's reaction [N], and whether
#: it rests on the seabed.
NODE_COLUMNS = ("leg", "node", "x", "y", "z", "tension", "reaction", "grounded",
                "surface_reaction", "floating")

_FLOOR = 1e-12


def _node_share(loads, j):
    """Half of the loads of the elements on either side of node ``j`` (0..N)."""
    share = 0
    if j > 0:
        share = share + loads[j - 1] / 2
    if j < len(loads):
        share = share + loads[j] / 2
    return share


def discrete_leg(problem, i, kind, x, iu, values, seabed, current, anchor, fair) -> LineBlock:
    """The block of lumped-node line ``i`` (the module notes), its nodes from end A
    (``anchor``) to end B (``fair``), both global 3-vectors [m]."""
    fs, ls = problem.force_scale, problem.length_scale
    k_N = fs / ls
    rho = problem.case.environment.water_density
    nseg = len(kind.elements)
    width = len(DISCRETE_PARAMS)
    seg = [dict(zip(DISCRETE_PARAMS, values[width * k: width * (k + 1)])) for k in range(nseg)]
    clumps = values[width * nseg: width * nseg + nseg - 1]
    n = kind.n_elements
    T = [x[iu + e] for e in range(n)]
    base = iu + n
    gx, gy = seabed["gradient_x"], seabed["gradient_y"]
    depth = seabed["depth"]
    normal = ca.vertcat(-gx, -gy, 1) / ca.sqrt(1 + gx**2 + gy**2)

    def bed(px, py):
        return -depth + gx * px + gy * py

    # Nodes 0 (end A) .. n (end B).
    nodes, zeta, water = [anchor], [], []
    for j in range(1, n):
        px, py, zj = x[base + 3 * (j - 1)], x[base + 3 * (j - 1) + 1], x[base + 3 * (j - 1) + 2]
        zeta.append(zj)
        water.append(-bed(px, py))              # water depth at the node
        nodes.append(ca.vertcat(px, py, bed(px, py) + ca.fmin(ca.fmax(zj, 0), water[-1])))
    nodes.append(fair)

    # Element properties, anchor first; joints are the nodes between segments.
    props, joint_nodes = [], {}
    count = 0
    laws = kind.laws or (None,) * nseg
    for k, m in enumerate(kind.elements):
        law = None if laws[k] is None else Law(laws[k], problem.line_laws[i][k])
        for _ in range(m):
            props.append((seg[k], seg[k]["length"] / m, kind.elastic_segments[k], law))
        count += m
        if k < nseg - 1:
            joint_nodes[count] = clumps[k]

    theta = current["toward"]
    heading = ca.vertcat(ca.cos(theta), ca.sin(theta), 0)
    res, mismatch = [], []
    tau, loads = [], []
    for e in range(n):
        sp, L_e, elastic, law = props[e]
        d = nodes[e + 1] - nodes[e]
        length = ca.sqrt(ca.sumsqr(d) + _FLOOR**2)
        t = d / length
        c = law.compliance(T[e]) if law is not None else sp["ea_inv"] if elastic else 0
        r = length - L_e * (1 + (law.strain(T[e]) if law is not None else c * T[e]))
        res.append(r / L_e)
        # The length mismatch as a force: through the axial (tangent) stiffness EA/L of an
        # elastic element; through the geometric stiffness T/L (a kink at the node) of an
        # inextensible one, and never less than the scene's scale.
        stiff = ca.fmax(ca.fabs(T[e]) / L_e, fs / ls)
        mismatch.append(ca.fabs(r) * (ca.fmax(1 / (L_e * c), stiff) if elastic else stiff))
        z_mid = (nodes[e][2] + nodes[e + 1][2]) / 2
        flow = (current_velocity(z_mid, current["profile"], heading, current["headings"])
                if current["profile"] else current["speed"] * heading)
        side = sp["side"] if kind.side else 0.0
        drag = line_drag(t, flow, sp["diameter"], rho, sp["normal"],
                         sp["tangential"], side) * length * current["factor"]
        weight = ca.vertcat(0, 0, -sp["weight"] * L_e)
        tau.append(t)
        loads.append(drag + weight)

    reactions, grounded_node, holds, floating_node = [], [], [], []
    for j in range(1, n):
        N = ca.fmax(-zeta[j - 1], 0) * k_N
        S = ca.fmax(zeta[j - 1] - water[j - 1], 0) * k_N
        reactions.append(N)
        holds.append(S)
        grounded_node.append(ca.if_else(zeta[j - 1] <= 0, 1, 0))
        floating_node.append(ca.if_else(zeta[j - 1] >= water[j - 1], 1, 0))
        force = (T[j] * tau[j] - T[j - 1] * tau[j - 1] + _node_share(loads, j) + N * normal
                 - S * ca.vertcat(0, 0, 1))
        if j in joint_nodes:
            force = force - ca.vertcat(0, 0, joint_nodes[j])
        res += [force[0] / fs, force[1] / fs, force[2] / fs]
        mismatch.append(ca.norm_2(force))

    # The line's pull on its ends (the end node takes half of its element's loads).
    on_fair = -T[-1] * tau[-1] + loads[-1] / 2
    on_anchor = T[0] * tau[0] + loads[0] / 2
    tol = 1e-9 * ca.fmax(depth, 1)
    anchor_down = ca.if_else(anchor[2] <= bed(anchor[0], anchor[1]) + tol, 1, 0)
    fair_down = ca.if_else(fair[2] <= bed(fair[0], fair[1]) + tol, 1, 0)
    flags = [anchor_down] + grounded_node + [fair_down]
    afloat = ([ca.if_else(anchor[2] >= 0, 1, 0)] + floating_node
              + [ca.if_else(fair[2] >= 0, 1, 0)])
    grounded = floating = 0
    run, touchdown = anchor_down, 0
    for e in range(n):
        L_e = props[e][1]
        both = flags[e] * flags[e + 1]
        grounded = grounded + L_e * both
        floating = floating + L_e * afloat[e] * afloat[e + 1]
        run = run * flags[e + 1]
        d = nodes[e + 1] - nodes[e]
        touchdown = touchdown + run * ca.sqrt(d[0]**2 + d[1]**2 + _FLOOR**2)
    worst = mismatch[0]
    for m in mismatch[1:]:
        worst = ca.fmax(worst, m)
    H = ca.sqrt(on_fair[0]**2 + on_fair[1]**2 + _FLOOR**2)
    X = ca.sqrt((fair[0] - anchor[0])**2 + (fair[1] - anchor[1])**2 + _FLOOR**2)
    row = dict(H=H, VF=-on_fair[2], HA=ca.sqrt(on_anchor[0]**2 + on_anchor[1]**2),
               VA=on_anchor[2], grounded=grounded, suspended_x=X - touchdown, rX=worst,
               rZ=0 * worst, J=ca.DM([1.0, 0.0, 0.0, 1.0]), X=X, Z=fair[2] - anchor[2],
               floating=floating)
    rows = []
    for j in range(n + 1):
        if j == 0:
            tension, reaction, hold = ca.norm_2(on_anchor), 0, 0
        elif j == n:
            tension, reaction, hold = ca.norm_2(on_fair), 0, 0
        else:
            tension, reaction = (T[j - 1] + T[j]) / 2, reactions[j - 1]
            hold = holds[j - 1]
        rows.append(ca.vertcat(i, j, nodes[j], tension, reaction, flags[j], hold, afloat[j]))
    return LineBlock(res, on_anchor, on_fair, worst, row, [], rows)
