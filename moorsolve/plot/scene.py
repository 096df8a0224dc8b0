"""What a picture of an equilibrium shows, gathered from a Result (no matplotlib here).

Every view draws the same :class:`Scene`: lines as 3-D polylines read from each line's
profile, bodies with their pose at rest and at equilibrium, anchors, clumps, buoys and
free points, the body loads, and the seabed as a function of (x, y). The views never look
inside a leg's physics, so a scene of several bodies, free points and lines between any
two points draws the same way once the result lists them (``Result.bodies`` and
``Result.points``, when present, are read as the network form of CONTRACT.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

#: A point counts as on the seabed within this fraction of the depth.
_ON_SEABED = 1e-6


@dataclass(frozen=True)
class LineView:
    """One line: its polyline [m] (global x, y, z) and what colours and labels it."""

    name: str
    xyz: np.ndarray
    tension_N: float                   # largest tension along it
    utilisation: Optional[float]       # largest tension over MBL; None without an MBL
    slack: bool
    anchor: np.ndarray
    fairlead: np.ndarray
    touchdown: Optional[np.ndarray]
    grounded: np.ndarray               # per point: on the seabed


@dataclass(frozen=True)
class PointView:
    """A point that is not a line end at a body: ``kind`` is ``clump``, ``buoy``,
    ``joint`` (a bare connection) or ``free`` (a free point of the network)."""

    name: str
    xyz: np.ndarray
    kind: str
    weight_N: float = 0.0


@dataclass(frozen=True)
class BodyView:
    """A body at rest (case-file pose) and at equilibrium.

    ``outline`` is the plan outline [m] at equilibrium (the convex hull of its line ends
    and its origin: the case gives no hull geometry; a segment or a point for a body on
    one line), ``outline_rest`` the same at rest; ``origin`` and
    ``origin_rest`` the body-frame origin, ``yaw_deg`` its heading.
    """

    name: str
    origin: np.ndarray
    origin_rest: np.ndarray
    yaw_deg: float
    outline: np.ndarray
    outline_rest: np.ndarray
    fairleads: np.ndarray

    @property
    def offset(self) -> np.ndarray:
        return self.origin - self.origin_rest


@dataclass(frozen=True)
class Scene:
    """Everything the views draw, in global coordinates [m]."""

    title: str
    lines: list
    bodies: list
    points: list
    loads: dict                          # name -> (Fx N, Fy N, Mz N m), global
    depth: float
    seabed_z: Callable[[np.ndarray, np.ndarray], np.ndarray]
    sloped: bool
    north_deg: Optional[float] = None    # set when the case speaks in compass bearings
    fixed_ends: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    #: Lines of another result missing from this one (a damaged condition's broken line),
    #: drawn as ghosts where they were.
    removed: list = field(default_factory=list)

    @property
    def colour_by(self) -> str:
        """``utilisation`` when every line has an MBL, else ``tension``."""
        if self.lines and all(line.utilisation is not None for line in self.lines):
            return "utilisation"
        return "tension"

    def extent(self, min_ratio: float = 0.4) -> np.ndarray:
        """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` of everything drawn, the narrower
        horizontal side widened about its middle to at least ``min_ratio`` of the wider
        (a scene of one line along x is not drawn as a strip)."""
        pts = [line.xyz for line in self.lines + self.removed] + [b.outline for b in self.bodies]
        pts += [np.array([b.origin, b.origin_rest]) for b in self.bodies]
        pts += [p.xyz[None, :] for p in self.points]
        allp = np.vstack([p for p in pts if len(p)]) if pts else np.zeros((1, 3))
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        wide = max(hi[0] - lo[0], hi[1] - lo[1], 1.0)
        for k in (0, 1):
            grow = max(0.0, min_ratio * wide - (hi[k] - lo[k])) / 2
            lo[k], hi[k] = lo[k] - grow, hi[k] + grow
        return np.array([lo, hi])


def scene_of(result, removed_from=None) -> Scene:
    """The :class:`Scene` of a :class:`~moorsolve.Result`.

    ``removed_from``: another Result (e.g. the intact condition) whose lines missing here
    are kept as :attr:`Scene.removed`, to be drawn as ghosts.
    """
    case = result.case
    env = case.environment if case is not None else None
    depth = env.depth if env is not None else _deepest(result)
    if env is not None:
        gx, gy = env.seabed.gradient

        def seabed_z(x, y):
            return -env.depth + gx * np.asarray(x, float) + gy * np.asarray(y, float)
        sloped = env.seabed.sloped
        compass = env.compass
        north = compass.north_deg if compass.nautical else None
    else:
        def seabed_z(x, y):
            return np.full(np.broadcast(np.asarray(x), np.asarray(y)).shape, -depth)
        sloped, north = False, None
    lines = [_line(leg, seabed_z, depth) for leg in result.legs]
    points = [p for leg in result.legs for p in _joints(leg)]
    points += [PointView(name=p["name"], xyz=np.array([p["x_m"], p["y_m"], p["z_m"]]),
                         kind="free") for p in (getattr(result, "points", None) or [])]
    bodies = _bodies(result)
    fixed = np.zeros((0, 3))
    if not bodies:
        fixed = np.array([line.fairlead for line in lines]).reshape(-1, 3)
    names = {leg.name for leg in result.legs}
    removed = [_line(leg, seabed_z, depth) for leg in
               (removed_from.legs if removed_from is not None else ()) if leg.name not in names]
    return Scene(title=result.case_name or "equilibrium", lines=lines, bodies=bodies,
                 points=points, loads={k: tuple(v) for k, v in result.loads.items()},
                 depth=depth, seabed_z=seabed_z, sloped=sloped, north_deg=north,
                 fixed_ends=fixed, removed=removed)


def _deepest(result) -> float:
    return max((-float(np.min(leg.profile["z_m"])) for leg in result.legs), default=1.0)


def _line(leg, seabed_z, depth) -> LineView:
    p = leg.profile
    xyz = np.column_stack([p["x_m"], p["y_m"], p["z_m"]]).astype(float)
    tension = float(np.max(p["tension_N"])) if len(p["tension_N"]) else 0.0
    tension = max(tension, leg.fairlead_tension_N, leg.anchor_tension_N)
    grounded = xyz[:, 2] <= seabed_z(xyz[:, 0], xyz[:, 1]) + _ON_SEABED * max(depth, 1.0)
    return LineView(name=leg.name, xyz=xyz, tension_N=tension, utilisation=leg.utilisation,
                    slack=bool(leg.slack), anchor=np.asarray(leg.anchor, float),
                    fairlead=np.asarray(leg.fairlead, float),
                    touchdown=(None if leg.touchdown_point is None
                               else np.asarray(leg.touchdown_point, float)),
                    grounded=grounded)


def _joints(leg) -> list:
    out = []
    for j, joint in enumerate(leg.joints):
        w = float(joint.get("clump_weight_N", 0.0))
        kind = "clump" if w > 0 else ("buoy" if w < 0 else "joint")
        out.append(PointView(name=f"{leg.name}.{j + 1}",
                             xyz=np.asarray(joint["position_m"], float), kind=kind,
                             weight_N=w))
    return out


def _rotation(yaw_deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    return np.array([[c, -s], [s, c]])


def _bodies(result) -> list:
    """The bodies of a result: ``Result.bodies`` (network form) or the one ``body``."""
    poses = getattr(result, "bodies", None)
    if not poses:
        if result.body is None:
            return []
        poses = [dict(result.body, name="body", z_m=0.0)]
    out = []
    for pose in poses:
        # The lines ending on this body; the one-body form: all of them.
        ends = [leg for leg in result.legs
                if getattr(leg, "body", pose["name"]) in (pose["name"], None)]
        fair = np.array([leg.fairlead for leg in ends], float).reshape(-1, 3)
        origin = np.array([pose.get("x_m", 0.0), pose.get("y_m", 0.0), pose.get("z_m", 0.0)])
        yaw = float(pose.get("yaw_deg", 0.0))
        # Back to the case-file pose: undo the yaw about the origin, then the offset.
        local = (fair[:, :2] - origin[:2]) @ _rotation(yaw)
        rest = np.column_stack([local, fair[:, 2]])
        # The outline runs through the line ends and the body origin.
        outline = _hull(np.vstack([fair[:, :2], origin[:2]]))
        outline_rest = _hull(np.vstack([rest[:, :2], np.zeros(2)]))
        out.append(BodyView(name=pose["name"], origin=origin, origin_rest=np.zeros(3),
                            yaw_deg=yaw, outline=_at(outline, 0.0),
                            outline_rest=_at(outline_rest, 0.0), fairleads=fair))
    return out


def _at(points2d: np.ndarray, z: float) -> np.ndarray:
    return np.column_stack([points2d, np.full(len(points2d), z)]) if len(points2d) \
        else np.zeros((0, 3))


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull of 2-D points (scipy's Qhull), counter-clockwise."""
    from scipy.spatial import ConvexHull, QhullError
    pts = np.unique(np.round(points, 9), axis=0)
    try:
        hull = ConvexHull(pts)
    except (QhullError, ValueError):          # fewer than 3 distinct or collinear points
        return pts
    return pts[hull.vertices]
