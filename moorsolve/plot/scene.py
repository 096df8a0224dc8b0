"""What a picture of an equilibrium shows, gathered from a Result (no matplotlib here).

Every view draws the same :class:`Scene`: lines as 3-D polylines read from each line's
profile, bodies with their pose at rest and at equilibrium, anchors, clumps, buoys and
free points, the body loads, and the seabed as a function of (x, y). The views never look
inside a leg's physics, so a scene of several bodies, free points and lines between any
two points draws the same way once the result lists them (``Result.bodies`` and
``Result.points``, when present, are read as the network form).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from .geometry import Berth, berth_of, body_shapes, convex_hull, rotation

#: A point counts as on the seabed within this fraction of the depth.
_ON_SEABED = 1e-6


@dataclass(frozen=True)
class LineView:
    """One line: its polyline [m] (global x, y, z) and what colours and labels it."""

    name: str
    xyz: np.ndarray
    tension_N: float                   # largest tension along it
    t_over_mbl: Optional[float]        # largest tension over MBL; None without an MBL
    slack: bool
    anchor: np.ndarray
    fairlead: np.ndarray
    touchdown: Optional[np.ndarray]
    grounded: np.ndarray               # per point: on the seabed
    #: What each end is held by: ``"anchor"`` (fixed on the seabed), ``"bollard"`` (fixed
    #: above still water: a quay's bollard), ``"fixed"`` (fixed in the water column),
    #: ``"body"``, ``"free"`` (a free point of the network); end A is the anchor end of a leg.
    a_kind: str = "anchor"
    b_kind: str = "body"


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

    ``shapes`` is the hull drawn (:func:`.geometry.body_shapes`: hull members, a length and
    beam, else the outline of the line ends). ``outline`` is the plan outline [m] at
    equilibrium of its line ends and origin (a segment or a point for a body on one line),
    ``outline_rest`` the same at rest; ``origin`` and
    ``origin_rest`` the body-frame origin, ``yaw_deg`` its heading; ``loads`` its loads
    (``name -> global force``).
    """

    name: str
    origin: np.ndarray
    origin_rest: np.ndarray
    yaw_deg: float
    outline: np.ndarray
    outline_rest: np.ndarray
    fairleads: np.ndarray
    loads: dict = field(default_factory=dict)
    shapes: list = field(default_factory=list)

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
    #: Quay walls, piles, fenders and pile guides (:class:`.geometry.Berth`).
    berth: Berth = field(default_factory=Berth)

    @property
    def colour_by(self) -> str:
        """``t_over_mbl`` when every line has an MBL, else ``tension``."""
        if self.lines and all(line.t_over_mbl is not None for line in self.lines):
            return "t_over_mbl"
        return "tension"

    def drawn_points(self) -> np.ndarray:
        """Every point drawn [m] (N x 3): lines, bodies (hulls top and bottom), points, the
        berth."""
        pts = [line.xyz for line in self.lines + self.removed] + [b.outline for b in self.bodies]
        pts += [np.array([b.origin, b.origin_rest]) for b in self.bodies]
        for b in self.bodies:
            for shape in b.shapes:
                for z in (shape.bottom, shape.top):
                    pts.append(np.column_stack([shape.ring, np.full(len(shape.ring), z)]))
        pts += [p.xyz[None, :] for p in self.points]
        pts.append(self.berth.points())
        pts = [p for p in pts if len(p)]
        return np.vstack(pts) if pts else np.zeros((1, 3))

    def extent(self, min_ratio: float = 0.4) -> np.ndarray:
        """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` of everything drawn, the narrower
        horizontal side widened about its middle to at least ``min_ratio`` of the wider
        (a scene of one line along x is not drawn as a strip)."""
        allp = self.drawn_points()
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
            if env.seabed.bathymetry is not None:     # the grid's interpolated surface
                return np.asarray(env.seabed_z(np.asarray(x, float), np.asarray(y, float)))
            return -env.depth + gx * np.asarray(x, float) + gy * np.asarray(y, float)
        sloped = env.seabed.sloped
        compass = env.compass
        north = compass.north_deg if compass.nautical else None
    else:
        def seabed_z(x, y):
            return np.full(np.broadcast(np.asarray(x), np.asarray(y)).shape, -depth)
        sloped, north = False, None
    topology = _topology(case, result.legs)
    lines = [_line(leg, seabed_z, depth, *topology.get(leg.name, ("anchor", "body")))
             for leg in result.legs]
    lines = [_fixed_kinds(line, seabed_z, depth) for line in lines]
    points = [p for leg in result.legs for p in _joints(leg)]
    points += [PointView(name=p["name"], xyz=np.array([p["x_m"], p["y_m"], p["z_m"]]),
                         kind="free") for p in (getattr(result, "points", None) or [])]
    bodies = _bodies(result, lines)
    fixed = np.array([line.fairlead for line in lines if line.b_kind in _FIXED])
    names = {leg.name for leg in result.legs}
    removed = [_line(leg, seabed_z, depth) for leg in
               (removed_from.legs if removed_from is not None else ()) if leg.name not in names]
    return Scene(title=result.case_name or "equilibrium", lines=lines, bodies=bodies,
                 points=points, loads={k: tuple(v) for k, v in result.loads.items()},
                 depth=depth, seabed_z=seabed_z, sloped=sloped, north_deg=north,
                 fixed_ends=fixed.reshape(-1, 3), removed=removed,
                 berth=_berth(result, lines, bodies))


#: The kinds of end fixed in the scene.
_FIXED = ("anchor", "bollard", "fixed")


def _fixed_kind(xyz, seabed_z, depth) -> str:
    """An end fixed in the scene: on the seabed an anchor, at or above still water a
    bollard (a quay's), between them a fixed point."""
    bed = float(seabed_z(np.asarray(xyz[0]), np.asarray(xyz[1])))
    if xyz[2] <= bed + 1e-3 * max(depth, 1.0):
        return "anchor"
    return "bollard" if xyz[2] >= 0.0 else "fixed"


def _fixed_kinds(line, seabed_z, depth):
    from dataclasses import replace
    a = _fixed_kind(line.xyz[0], seabed_z, depth) if line.a_kind in _FIXED else line.a_kind
    b = _fixed_kind(line.xyz[-1], seabed_z, depth) if line.b_kind in _FIXED else line.b_kind
    return replace(line, a_kind=a, b_kind=b)


def _berth(result, lines, bodies) -> Berth:
    """The berth, its walls drawn along the scene and up to the quay's bollards."""
    if getattr(result, "case", None) is None:
        return Berth()
    reach = [line.xyz[:, :2] for line in lines]
    reach += [shape.ring for b in bodies for shape in b.shapes]
    reach += [np.array([f["contact_point_m"][:2]]) for f in (result.fenders or ())]
    bollards = [line.xyz[0, 2] for line in lines if line.a_kind == "bollard"]
    bollards += [line.xyz[-1, 2] for line in lines if line.b_kind == "bollard"]
    deck = max(bollards) if bollards else 1.0
    return berth_of(result, np.vstack(reach) if reach else np.zeros((1, 2)), deck)


def _topology(case, legs) -> dict:
    """``line name -> (kind of end A, kind of end B)`` from the case (a fixed named point
    is an anchor too); without a case every line runs from an anchor to a body."""
    if case is None or not hasattr(case, "lines"):
        return {}
    free = {p.name for p in getattr(case, "points", ()) if p.free}

    def kind(end):
        if getattr(end, "body", None) is not None:
            return "body"
        return "free" if getattr(end, "point", None) in free else "anchor"
    return {line.name: (kind(line.a), kind(line.b)) for line in case.lines
            if hasattr(line, "a")}


def _deepest(result) -> float:
    return max((-float(np.min(leg.profile["z_m"])) for leg in result.legs), default=1.0)


def _line(leg, seabed_z, depth, a_kind="anchor", b_kind="body") -> LineView:
    p = leg.profile
    xyz = np.column_stack([p["x_m"], p["y_m"], p["z_m"]]).astype(float)
    tension = float(np.max(p["tension_N"])) if len(p["tension_N"]) else 0.0
    tension = max(tension, leg.fairlead_tension_N, leg.anchor_tension_N)
    grounded = xyz[:, 2] <= seabed_z(xyz[:, 0], xyz[:, 1]) + _ON_SEABED * max(depth, 1.0)
    return LineView(name=leg.name, xyz=xyz, tension_N=tension, t_over_mbl=leg.t_over_mbl,
                    slack=bool(leg.slack), anchor=np.asarray(leg.anchor, float),
                    fairlead=np.asarray(leg.fairlead, float),
                    touchdown=(None if leg.touchdown_point is None
                               else np.asarray(leg.touchdown_point, float)),
                    grounded=grounded, a_kind=a_kind, b_kind=b_kind)


def _joints(leg) -> list:
    out = []
    for j, joint in enumerate(leg.joints):
        w = float(joint.get("clump_weight_N", 0.0))
        kind = "clump" if w > 0 else ("buoy" if w < 0 else "joint")
        out.append(PointView(name=f"{leg.name}.{j + 1}",
                             xyz=np.asarray(joint["position_m"], float), kind=kind,
                             weight_N=w))
    return out


def _bodies(result, lines) -> list:
    """Every body of a result with its pose at rest and at equilibrium, its outline through
    the ends of the lines it holds (read from the case) and its loads."""
    poses = list(getattr(result, "bodies", None) or ())
    if not poses and result.body is not None:
        poses = [dict(result.body, name="body")]
    case = result.case
    ends_of = _body_ends(case, lines) if case is not None else {}
    models = {b.name: b for b in getattr(case, "bodies", ())} if case is not None else {}
    fender_of = _fender_points(result, case)
    several = len(poses) > 1
    out = []
    for pose in poses:
        name = pose["name"]
        origin = np.array([pose.get("x_m", 0.0), pose.get("y_m", 0.0), pose.get("z_m", 0.0)])
        offset = pose.get("offset", pose)
        origin_rest = origin - np.array([offset.get("x_m", 0.0), offset.get("y_m", 0.0),
                                         offset.get("z_m", 0.0)])
        yaw = float(pose.get("yaw_deg", 0.0))
        yaw_rest = yaw - float(offset.get("yaw_deg", 0.0))
        ends = ends_of.get(name)
        if ends is None:          # no case: every line ends on the one body
            fair = np.array([line.fairlead for line in lines], float).reshape(-1, 3)
            local = (fair[:, :2] - origin[:2]) @ rotation(yaw)
        else:
            fair = np.array([g for g, _ in ends], float).reshape(-1, 3)
            local = np.array([at[:2] for _, at in ends], float).reshape(-1, 2)
        rest = origin_rest[:2] + local @ rotation(yaw_rest).T
        # The outline runs through the line ends and the body origin.
        outline = convex_hull(np.vstack([fair[:, :2], origin[:2]]))
        outline_rest = convex_hull(np.vstack([rest, origin_rest[:2]]))
        model = models.get(name) or (models.get("body") if len(models) == 1 else None)
        fend_g, fend_l = fender_of.get(name, (np.zeros((0, 3)), np.zeros((0, 2))))
        shapes = body_shapes(model, origin, origin_rest, yaw, yaw_rest,
                             np.vstack([local, fend_l]), np.concatenate([fair[:, 2],
                                                                         fend_g[:, 2]]))
        loads = {k.split(".", 1)[1] if several else k: tuple(v)
                 for k, v in result.loads.items()
                 if not several or k.startswith(name + ".")}
        out.append(BodyView(name=name, origin=origin, origin_rest=origin_rest, yaw_deg=yaw,
                            outline=_at(outline, origin[2]),
                            outline_rest=_at(outline_rest, origin_rest[2]),
                            fairleads=fair, loads=loads, shapes=shapes))
    return out


def _fender_points(result, case) -> dict:
    """``body name -> (global contact points at equilibrium, body-frame plan points)`` of
    the fenders on each body: where the hull's side is."""
    out: dict = {}
    poses = {p["name"]: p for p in (getattr(result, "bodies", None) or ())}
    for f in (getattr(result, "fenders", None) or ()):
        pose = poses.get(f["body"]) or (result.body if result.body is not None else None)
        if pose is None:
            continue
        g = np.asarray(f["contact_point_m"], float)
        local = (g[:2] - np.array([pose["x_m"], pose["y_m"]])) @ rotation(pose["yaw_deg"])
        glob, loc = out.get(f["body"], (np.zeros((0, 3)), np.zeros((0, 2))))
        out[f["body"]] = (np.vstack([glob, g]), np.vstack([loc, local]))
    return out


def _body_ends(case, lines) -> dict:
    """``body name -> [(global position at equilibrium, position in the body frame)]``
    of every line end on that body."""
    by_name = {line.name: line for line in lines}
    out: dict = {}
    for line in getattr(case, "lines", ()):
        view = by_name.get(line.name)
        if view is None or not hasattr(line, "a"):
            continue
        for end, where in ((line.a, view.xyz[0]), (line.b, view.xyz[-1])):
            if end.body is not None:
                out.setdefault(end.body, []).append((where, np.asarray(end.position, float)))
    return out


def _at(points2d: np.ndarray, z: float) -> np.ndarray:
    return np.column_stack([points2d, np.full(len(points2d), z)]) if len(points2d) \
        else np.zeros((0, 3))
