"""Contacts in the problem: fenders on walls and piles, pile-guide pads.

Every contact is one point against one surface (:mod:`moorsolve.physics.contact` gives the
law and the geometry). A compliant fender's reaction is an explicit function of its
compression, ``lam = R(max(-g, 0))``: no unknown (its switch at ``g = 0`` is smoothed in the
step Jacobian only, which anticipates its reaction and the friction it will carry). A rigid
contact (a rigid fender, a guide's pad) needs the
complementarity: one unknown after the lines' in ``x``, its reaction ``lam`` [N], and one
residual after the lines' residuals, the Fischer-Burmeister residual [m, scaled by the
length scale] with the reaction weighed at the scene's contact stiffness. Friction, where
the surface has it, is an explicit function of the reaction and the slip since the
case-file pose. The force acts on the contact's body at the contact point, like a line's at
a fairlead (moments about the body origin).

Geometries (``ContactPoint.geometry``):

- ``plane``: a body-mounted fender's face ``r + R a`` (a point) against a wall (normal
  ``n``): ``g = n . (r + R a - p0)``;
- ``face``: a fender mounted on the structure at ``P`` (on a wall, or on a pile facing
  out along its radius through ``P``) against the body's flat side: the plane through ``P``
  normal to that axis at the case-file pose, moving with the body;
- ``panel``: a flat face on the body against a pile's round side: a body-mounted fender's
  panel (facing the pile at the case-file pose) or a guide's pad. Its gap is the distance
  from the pile's axis to the face's plane less the radius, ``g = m . (c - f) - r``, and
  the contact is where the pile faces the panel. Flat on round is stable; a point on round
  is not (it rolls off, as a ball off a dome), which is why a panel and not a point.

Behind every compliant fender whose height (its full compression) is known, the hull is a
contact of the same geometry with the gap ``g + height``: fully compressed, the fender is a
block and the wall bears on the hull through it with the stiffness
:data:`~moorsolve.constants.HULL_STIFFNESS` (1 mm per MN), written as a rigid contact's
complementarity on the opening ``g + height + lam / K``. Stiff enough that no berth sees
the difference from a rigid contact, compliant so that several bearing points of one hull
share the load determinately (four rigid contacts in a row would leave the share to the
solver).

A guide is expanded into its pads: a regular polygon of flat faces round the collar's
inside (``Guide.pads`` of them, the first facing body +x), each the pile's radius plus
the clearance from the collar's centre: the collar moves freely within the clearance and
bears on the pile with the pads that meet it, rigidly, or, where the pile gives its
bending stiffness, on a cantilever of stiffness ``3 E I / h^3`` at the collar's height.
It cannot pass through the pile however far a solver's step goes (the gaps are linear in
the collar's position).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import casadi as ca

from ...constants import HULL_STIFFNESS
from ...model import Case
from ...physics.contact import (fender_reaction, fischer_burmeister, friction_force,
                               natural_residual, plane_gap)
from ...physics.kinematics import rotation_matrix
from ..assembly.layout import hull_behind

#: Columns of ``EquilibriumProblem.contact_report``: gap and opening [m], reaction [N], the
#: friction force [N] and the tangential slip [m] (global vectors), the force on the body
#: [N] and its point of action [m] (global), the reaction's direction on the body, the
#: compression the reaction gives [m], the friction limit ``mu lam`` [N], the slip that
#: mobilises it [m] and 1 where the contact is closed (the reaction side of its
#: complementarity holds: ``lam / k > g + c(lam)``), else 0.
CONTACT_COLUMNS = ("gap", "opening", "reaction", "ftx", "fty", "ftz", "sx", "sy", "sz",
                   "Fx", "Fy", "Fz", "cx", "cy", "cz", "nx", "ny", "nz", "compression",
                   "limit", "mobilisation", "closed")

@dataclass(frozen=True)
class ContactPoint:
    """One contact of the problem (a fender, or one pad of a guide): structure only.

    Attributes
    ----------
    name : str
        The fender's name, or ``GUIDE.pad[k]``.
    element : str
        The fender's or guide's name.
    owner : str
        ``"fender"``, ``"guide"`` or ``"hull"`` (the hull behind a fender, bearing on the
        wall or pile once the fender is fully compressed; its ``element`` is the fender).
    body : str
    geometry : str
        ``"plane"``, ``"face"`` or ``"panel"`` (see the module notes).
    target : str
        The wall or pile it bears on.
    on_wall : bool
        The target is a wall (else a pile).
    law : str
        ``rigid``, ``linear`` or ``table`` (a fender), ``rigid`` or ``pile`` (a guide's pad
        on a rigid pile, or on a pile bending as a cantilever), ``hull`` (the hull behind a
        fender).
    table_rows : int
        Rows of a table law.
    friction : bool
        The target has friction.
    pad : int
        The pad's index round a guide (-1 for a fender).
    pads : int
        The guide's number of pads.
    """

    name: str
    element: str
    owner: str
    body: str
    geometry: str
    target: str
    on_wall: bool
    law: str = "rigid"
    table_rows: int = 0
    friction: bool = False
    pad: int = -1
    pads: int = 0

    @property
    def n_unknowns(self) -> int:
        """1 for a rigid contact or a fender's hull (its reaction), 0 for a compliant
        fender."""
        return 1 if self.law in ("rigid", "hull") else 0


def contact_points(case: Case) -> list:
    """The :class:`ContactPoint` of every fender and guide pad of ``case``."""
    c = case.contacts
    out = []
    for f in c.fenders:
        target = f.wall or f.pile
        surface = c.wall_named(target) if f.wall else c.pile_named(target)
        geometry = "face" if f.mounted == "structure" else (
            "plane" if f.wall else "panel")
        out.append(ContactPoint(name=f.name, element=f.name, owner="fender", body=f.body,
                                geometry=geometry, target=target, on_wall=f.wall is not None,
                                law=f.law.kind, table_rows=len(f.law.deflections),
                                friction=surface.friction > 0))
    for g in c.guides:
        pile = c.pile_named(g.pile)
        law = "rigid" if pile.bending_stiffness is None else "pile"
        for k in range(g.pads):
            out.append(ContactPoint(name=f"{g.name}.pad[{k}]", element=g.name,
                                    owner="guide", body=g.body, geometry="panel",
                                    target=g.pile, on_wall=False, law=law,
                                    friction=pile.friction > 0, pad=k, pads=g.pads))
    # The hull behind each compliant fender of known height: fully compressed, the fender
    # is a block and the hull bears on the wall (or pile) through it, rigidly.
    fenders = {p.element: p for p in out if p.owner == "fender"}
    for f in c.fenders:
        if hull_behind(f):
            out.append(dataclasses.replace(fenders[f.name], name=f"{f.name}.hull",
                                           owner="hull", law="hull", table_rows=0))
    return out


#: Shortest cantilever [m] a pile guide's pile is taken as (a collar at the seabed).
MIN_CANTILEVER = 0.1


def _unit(v):
    return v / ca.sqrt(ca.sumsqr(v))


def _law(point: ContactPoint, values) -> tuple:
    """``(deflections, reactions)`` symbols of a compliant law."""
    if point.law == "linear":
        return [1.0], [values[0]]
    n = point.table_rows
    return list(values[:n]), list(values[n:2 * n])


def contact_block(problem, point: ContactPoint, x, io, par, body):
    """The residuals, force and report row of one contact.

    ``x`` are the problem's unknowns (unscaled), ``io`` the index of the contact's unknown
    (a rigid contact's), ``par(name)`` the parameter slice by layout name, ``body`` a dict with the
    contact's body's ``r`` (origin), ``R`` (rotation) and ``r0``, ``R0`` (case-file pose).
    Returns ``(residuals, force, point_of_action, row, certificate terms)``.
    """
    eps = problem.smoothing_symbol
    k_c = problem.contact_stiffness
    r, R, r0, R0 = body["r"], body["R"], body["r0"], body["R0"]
    wall = point.on_wall
    target = f"{'wall' if wall else 'pile'}[{point.target}]"
    mu = par(f"{target}.friction")
    if point.geometry == "plane":
        # A body-mounted fender's face, a point, against a flat wall.
        at = par(f"fender[{point.element}].at")
        p = r + R @ at
        moved = p - (r0 + R0 @ at)
        normal = _unit(par(f"{target}.normal"))
        gap, contact = plane_gap(p, par(f"{target}.point"), normal)
    elif point.geometry == "face":
        # A fender fixed on the structure at P against the body's flat side: the plane
        # through P normal to the fender's axis at the case pose, moving with the body.
        P = par(f"fender[{point.element}].at")
        if wall:
            axis = _unit(par(f"{target}.normal"))
        else:
            centre = par(f"{target}.position")
            axis = _unit(ca.vertcat(P[0] - centre[0], P[1] - centre[1], 0))
        b = R0.T @ (P - r0)
        m = R @ (-(R0.T @ axis))
        hull = r + R @ b
        gap = ca.dot(m, P - hull)
        normal = -m
        contact = P - gap * m
        moved = hull - P
    else:
        # A flat face on the body (a fender's panel, a guide's pad) against a pile's round
        # side: flat on round, so the contact stays where the pile faces the panel.
        centre = par(f"{target}.position")
        radius = par(f"pile[{point.target}].radius")
        if point.owner == "guide":
            collar = par(f"guide[{point.element}].at")
            clearance = par(f"guide[{point.element}].clearance")
            angle = 2 * math.pi * point.pad / point.pads
            out = ca.vertcat(math.cos(angle), math.sin(angle), 0)
            face_b = collar + (radius + clearance) * out
            m_b = -out
        else:
            face_b = par(f"fender[{point.element}].at")
            face0 = r0 + R0 @ face_b
            m_b = R0.T @ _unit(ca.vertcat(centre[0] - face0[0], centre[1] - face0[1], 0))
        face = r + R @ face_b
        m = R @ m_b
        axis = ca.vertcat(centre[0], centre[1], face[2])
        gap = ca.dot(m, axis - face) - radius
        normal = -m
        contact = axis - radius * m
        # The body's material point at the contact at the case pose, where it sticks.
        face0 = r0 + R0 @ face_b
        m0 = R0 @ m_b
        contact0 = ca.vertcat(centre[0], centre[1], face0[2]) - radius * m0
        moved = r + R @ (R0.T @ (contact0 - r0)) - contact0
    if point.owner == "hull":
        # The hull behind the fender, its height back from the face: it meets the wall when
        # the fender is fully compressed. Same normal, same point of action.
        gap = gap + par(f"fender[{point.element}].height")
    if point.n_unknowns:
        lam = x[io]
        # A rigid contact opens by its gap; the hull behind a fender by its gap and its
        # compliance, g + lam / K (the complementarity of a stiff spring, written with the
        # reaction as the unknown as a rigid contact's is: the Newton path's form).
        opening = gap + lam / HULL_STIFFNESS if point.law == "hull" else gap
        residuals = [fischer_burmeister(lam / k_c, opening, eps) / problem.length_scale]
        compression = 0 * lam
        closed = ca.if_else(lam / k_c > opening, 1, 0)
        terms = dict(penetration=ca.fmax(-opening, 0),
                     complementarity=natural_residual(lam, opening, k_c),
                     reaction=ca.fabs(lam))
    else:
        if point.law == "pile":
            # The pile bends as a cantilever fixed at the seabed: 3 E I / h^3 at the
            # collar's height h above it.
            bed = (-par("seabed.depth") + par("seabed.gradient_x") * centre[0]
                   + par("seabed.gradient_y") * centre[1])
            h = ca.fmax(face[2] - bed, MIN_CANTILEVER)
            d, react = [1.0], [3 * par(f"pile[{point.target}].bending_stiffness") / h**3]
        else:
            d, react = _law(point, ca.vertsplit(par(f"fender[{point.element}].law")))
        lam = fender_reaction(-gap, d, react, problem.hinge_symbol)
        residuals, compression, opening = [], ca.fmax(-gap, 0), gap
        closed = ca.if_else(gap < 0, 1, 0)
        terms = dict(reaction=ca.fabs(lam))
    slip = moved - ca.dot(moved, normal) * normal
    delta = par(f"{target}.friction_slip")
    friction = (friction_force(slip, lam, mu, delta) if point.friction
                else ca.SX.zeros(3))
    force = lam * normal + friction
    row = ca.vertcat(gap, opening, lam, friction, slip, force, contact, normal, compression,
                     mu * ca.fmax(lam, 0), delta, closed)
    return residuals, force, contact, row, terms


def element_reactions(problem, rows) -> list:
    """The reaction [N] of every fender (zero when open) and the horizontal force of every
    guide (its bearing pads together), in the case's order, from the contacts' report rows
    (:data:`CONTACT_COLUMNS`)."""
    col = {name: k for k, name in enumerate(CONTACT_COLUMNS)}
    by_element: dict = {}
    for point, row in zip(problem.contacts, rows):
        by_element.setdefault((point.owner, point.element), []).append(row)
    out = []
    for fender in problem.case.contacts.fenders:
        row = by_element[("fender", fender.name)][0]
        out.append(row[col["closed"]] * row[col["reaction"]])
    for guide in problem.case.contacts.guides:
        rows_g = by_element[("guide", guide.name)]
        fx = sum(r[col["closed"]] * r[col["Fx"]] for r in rows_g)
        fy = sum(r[col["closed"]] * r[col["Fy"]] for r in rows_g)
        out.append(ca.sqrt(fx**2 + fy**2))
    return out


def add_contacts(problem, x, par, poses, rotations, body_index, apply):
    """Build every contact of ``problem``: returns ``(residuals, rows, terms)`` and applies
    each contact's force to its body through ``apply(body_index, point, force)``."""
    residuals, rows, terms = [], [], []
    for point, io in zip(problem.contacts, problem.contact_offsets):
        bi = body_index[point.body]
        q0 = ca.vertsplit(par(f"body[{point.body}].pose"))
        body = dict(r=ca.vertcat(*poses[bi][:3]), R=rotations[bi], r0=ca.vertcat(*q0[:3]),
                    R0=rotation_matrix(q0[3], q0[4], q0[5]))
        res, force, where, row, term = contact_block(problem, point, x, io, par, body)
        residuals += res
        rows.append(row)
        terms.append(term)
        apply(bi, where, force)
    return residuals, rows, terms


__all__ = ["ContactPoint", "contact_points", "contact_block", "add_contacts",
           "element_reactions", "CONTACT_COLUMNS"]
