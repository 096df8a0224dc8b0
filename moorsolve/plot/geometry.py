"""What a picture draws besides the lines: each body's hull and the berth's structures (no
matplotlib here).

A body is drawn from the most exact geometry the case gives:

1. its hull members (``hull:``: boxes and vertical cylinders of the exact hydrostatics, and
   ``outline_members:``, drawn only), each drawn as the prism it is, and its ship outline (``outline:``, length, beam, draft and
   freeboard: a parallel middle body, a rounded bow and a transom stern);
2. else a length and beam the case gives for its loads (the wave drift model's ``beam`` and
   ``length``), drawn as a rectangle about the body origin; a beam without a length is
   completed by twice the farthest line end from the origin along the body's x (the bow
   fairlead of a ship on one chain);
3. else, where nothing is known of the hull, the convex outline of the line ends, fender
   points and origin it carries (the legend says so).

The berth is read from the case and the Result: quay walls (planes), piles, fenders (at
their solved contact points, with compression over rated deflection) and pile guides.
Everything is in global coordinates [m]; plan rings are counter-clockwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

__all__ = ["Shape", "WallView", "PileView", "FenderView", "GuideView", "Berth", "body_shapes",
           "berth_of", "convex_hull", "rotation"]

#: Points on the plan ring of a cylinder.
_CYLINDER_POINTS = 36

#: What each kind of shape is called in a legend.
SHAPE_SOURCES = {
    "box": "hull members from the case",
    "cylinder": "hull members from the case",
    "ship": "ship outline from the case",
    "dimensions": "length x beam from the case",
    "fairleads": "outline of fairleads (no hull given)",
}


@dataclass(frozen=True)
class Shape:
    """One vertical prism of a body: its plan ring at equilibrium and at rest [m], and the
    heights [m] of its bottom and top at equilibrium."""

    kind: str
    ring: np.ndarray
    ring_rest: np.ndarray
    bottom: float
    top: float

    @property
    def source(self) -> str:
        return SHAPE_SOURCES[self.kind]


@dataclass(frozen=True)
class WallView:
    """A quay wall: the plane through ``point`` with outward ``normal`` (unit, horizontal
    part), drawn between ``ends`` (plan [m]) from the seabed up to ``top`` [m]."""

    name: str
    point: np.ndarray
    normal: np.ndarray
    ends: np.ndarray
    top: float


@dataclass(frozen=True)
class PileView:
    name: str
    xy: np.ndarray
    radius: float
    top: float


@dataclass(frozen=True)
class FenderView:
    """A fender at its solved contact point; ``utilisation`` is compression over the rated
    deflection (None when unknown)."""

    name: str
    xyz: np.ndarray
    utilisation: Optional[float]
    reaction_N: float
    in_contact: bool


@dataclass(frozen=True)
class GuideView:
    """A pile guide: the collar (pile radius plus clearance) around its pile, at ``z``."""

    name: str
    xy: np.ndarray
    radius: float
    z: float
    reaction_N: float
    in_contact: bool


@dataclass(frozen=True)
class Berth:
    walls: list = field(default_factory=list)
    piles: list = field(default_factory=list)
    fenders: list = field(default_factory=list)
    guides: list = field(default_factory=list)

    def __bool__(self) -> bool:
        return bool(self.walls or self.piles or self.fenders or self.guides)

    def points(self) -> np.ndarray:
        """Every point of the berth [m] (N x 3) an Axes must hold."""
        pts = [np.zeros((0, 3))]
        for w in self.walls:
            pts.append(np.column_stack([w.ends, np.full(2, w.top)]))
        for p in self.piles:
            pts.append(np.array([[p.xy[0] - p.radius, p.xy[1] - p.radius, p.top],
                                 [p.xy[0] + p.radius, p.xy[1] + p.radius, p.top]]))
        pts += [f.xyz[None, :] for f in self.fenders]
        for g in self.guides:
            pts.append(np.array([[g.xy[0] - g.radius, g.xy[1] - g.radius, g.z],
                                 [g.xy[0] + g.radius, g.xy[1] + g.radius, g.z]]))
        return np.vstack(pts)


def rotation(yaw_deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    return np.array([[c, -s], [s, c]])


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Convex hull of 2-D points (scipy's Qhull), counter-clockwise; fewer than three
    distinct or collinear points come back as they are (unique)."""
    from scipy.spatial import ConvexHull, QhullError
    pts = np.unique(np.round(np.asarray(points, float).reshape(-1, 2), 9), axis=0)
    try:
        hull = ConvexHull(pts)
    except (QhullError, ValueError):
        return pts
    return pts[hull.vertices]


def _place(local: np.ndarray, origin, yaw_deg: float) -> np.ndarray:
    return np.asarray(origin, float)[:2] + np.asarray(local, float) @ rotation(yaw_deg).T


def _member_ring(member) -> np.ndarray:
    """The plan ring of a hull member in the body frame [m]."""
    cx, cy = member.centre
    if member.shape == "cylinder":
        t = np.linspace(0.0, 2 * math.pi, _CYLINDER_POINTS, endpoint=False)
        return np.column_stack([cx + member.radius * np.cos(t), cy + member.radius * np.sin(t)])
    hx, hy = member.length / 2, member.width / 2
    return np.array([[cx - hx, cy - hy], [cx + hx, cy - hy], [cx + hx, cy + hy],
                     [cx - hx, cy + hy]])


#: Share of a ship's length in its bow and stern (the rest is the parallel middle body), and
#: the transom's half-width over the half-beam: a typical merchant hull's waterline.
_BOW, _STERN, _TRANSOM = 0.22, 0.15, 0.7


def ship_ring(outline, points: int = 24) -> np.ndarray:
    """The waterline of a :class:`~moorsolve.model.bodies.ShipOutline` in the body frame
    [m], counter-clockwise: a transom stern, a parallel middle body and a pointed bow
    (half-breadth falling as a parabola to the stem)."""
    half_l, half_b = outline.length / 2, outline.beam / 2
    bow_start = half_l - _BOW * outline.length
    stern_end = -half_l + _STERN * outline.length
    u = np.linspace(0.0, 1.0, points)
    bow_x = bow_start + (half_l - bow_start) * u
    bow_y = half_b * (1.0 - u ** 2)
    s = np.linspace(0.0, 1.0, points // 2)
    stern_x = stern_end - (stern_end + half_l) * s
    stern_y = half_b * (1.0 - (1.0 - _TRANSOM) * s ** 2)
    side_x = np.concatenate([stern_x[::-1], bow_x])
    side_y = np.concatenate([stern_y[::-1], bow_y])
    # Starboard (y < 0) from stern to bow, then port back from bow to stern.
    ring = np.vstack([np.column_stack([side_x, -side_y]),
                      np.column_stack([side_x[::-1], side_y[::-1]])[1:]])
    turned = ring @ rotation(outline.heading_deg).T
    return turned + np.asarray(outline.centre, float)


def _dimensions(model, local_ends: np.ndarray) -> Optional[tuple]:
    """``(length, beam)`` [m] the case gives for the body's loads, or None."""
    drift = getattr(getattr(model, "loads", None), "wave_drift", None)
    beam = getattr(drift, "beam", None)
    if not beam:
        return None
    length = getattr(drift, "length", None)
    if not length:
        reach = 2.0 * float(np.max(np.abs(local_ends[:, 0]))) if len(local_ends) else 0.0
        if reach <= beam:
            return None
        length = reach
    return float(length), float(beam)


def body_shapes(model, origin, origin_rest, yaw_deg: float, yaw_rest_deg: float,
                local_ends: np.ndarray, ends_z: np.ndarray) -> list:
    """The :class:`Shape` list of one body.

    Parameters
    ----------
    model : moorsolve.model.Body or None
        The case's body (None: only its line ends are known).
    origin, origin_rest : array of 3 floats
        Body-frame origin at equilibrium and at rest [m].
    yaw_deg, yaw_rest_deg : float
        Heading at equilibrium and at rest [deg].
    local_ends : (n, 2) array
        The line ends and fender points on the body, body frame [m].
    ends_z : (n,) array
        Their heights at equilibrium [m].
    """
    z0 = float(origin[2])
    members = tuple(getattr(model, "hull", ()) or ()) + \
        tuple(getattr(model, "outline_members", ()) or ())
    outline = getattr(model, "outline", None)
    shapes = [Shape(kind=m.shape, ring=_place(_member_ring(m), origin, yaw_deg),
                    ring_rest=_place(_member_ring(m), origin_rest, yaw_rest_deg),
                    bottom=z0 + m.bottom, top=z0 + m.top) for m in members]
    if outline is not None:
        ring = ship_ring(outline)
        shapes.append(Shape(kind="ship", ring=_place(ring, origin, yaw_deg),
                            ring_rest=_place(ring, origin_rest, yaw_rest_deg),
                            bottom=z0 - outline.draft, top=z0 + outline.freeboard))
    if shapes:
        return shapes
    zs = np.concatenate([[z0], np.asarray(ends_z, float)])
    size = _dimensions(model, local_ends)
    if size is not None:
        length, beam = size
        ring = np.array([[-length / 2, -beam / 2], [length / 2, -beam / 2],
                         [length / 2, beam / 2], [-length / 2, beam / 2]])
        return [Shape(kind="dimensions", ring=_place(ring, origin, yaw_deg),
                      ring_rest=_place(ring, origin_rest, yaw_rest_deg),
                      bottom=float(zs.min()), top=float(zs.max()))]
    local = np.vstack([np.zeros((1, 2)), np.asarray(local_ends, float).reshape(-1, 2)])
    ring = convex_hull(local)
    return [Shape(kind="fairleads", ring=_place(ring, origin, yaw_deg),
                  ring_rest=_place(ring, origin_rest, yaw_rest_deg),
                  bottom=float(zs.min()), top=float(zs.max()))]


def berth_of(result, reach_xy: np.ndarray, deck_z: float) -> Berth:
    """The berth of a Result: walls drawn along the part of the scene ``reach_xy`` (N x 2
    plan points [m]) spans, up to ``deck_z`` [m] (the quay's bollards, else 1 m above still
    water); piles to their tops; fenders and guides as solved."""
    case = result.case
    contacts = getattr(case, "contacts", None)
    if contacts is None:
        return Berth()
    walls = []
    for wall in contacts.walls:
        n = np.asarray(wall.normal[:2], float)
        if np.linalg.norm(n) < 1e-9:
            continue          # a horizontal wall has no trace in plan
        n = n / np.linalg.norm(n)
        t = np.array([-n[1], n[0]])
        p0 = np.asarray(wall.point[:2], float)
        along = (reach_xy - p0) @ t
        margin = 0.05 * max(float(np.ptp(along)), 1.0)
        ends = p0 + np.outer([along.min() - margin, along.max() + margin], t)
        walls.append(WallView(name=wall.name, point=np.asarray(wall.point, float), normal=n,
                              ends=ends, top=deck_z))
    depth = case.environment.depth
    piles = [PileView(name=p.name, xy=np.asarray(p.position, float), radius=float(p.radius),
                      top=float(p.top) if p.top is not None else max(deck_z, 0.1 * depth))
             for p in contacts.piles]
    fenders = [FenderView(name=f["name"], xyz=np.asarray(f["contact_point_m"], float),
                          utilisation=f.get("utilisation"), reaction_N=float(f["reaction_N"]),
                          in_contact=bool(f["in_contact"]))
               for f in (result.fenders or ())]
    guides = []
    for g in (result.guides or ()):
        pile = contacts.pile_named(g["pile"])
        guides.append(GuideView(name=g["name"], xy=np.asarray(pile.position, float),
                                radius=float(pile.radius + g["clearance_m"]),
                                z=float(g.get("height_m", 0.0)),
                                reaction_N=float(g["reaction_N"]),
                                in_contact=bool(g["in_contact"])))
    return Berth(walls=walls, piles=piles, fenders=fenders, guides=guides)
