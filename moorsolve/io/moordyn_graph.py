"""The ends of a MoorDyn file's lines as one graph: where each line end is, and what holds it.

Every line end becomes a :class:`Node`: a point of the POINTS table or an end of a rod. A
node is

- ``fixed``: held in place (a Fixed point, an end of a Fixed rod);
- ``free``: a Free point, in balance under its lines, weight and buoyancy;
- ``carrier``: on a rigid carrier that may hold it or move it: ``("vessel",)`` groups the
  Coupled (Vessel, Fairlead) points and the ends of Coupled rods, as MoorDyn v1's one
  platform does; ``("body", N)`` is BODIES entry N (its points and the ends of its rigid
  rods); ``("turbine", N)`` a FAST.Farm turbine; ``("rod", N)`` a pinned or free rod, its
  own rigid carrier.

A carrier is *held* (Coupled, Fixed and Turbine bodies, the vessel: MoorDyn drives or fixes
them, so a static solve takes them where the file puts them) or *moving* (Free and
CoupledPinned bodies, pinned and free rods). Positions are global at the file's pose.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .moordyn_scene import MDRod, MDScene
from .rotations import apply, apply_transpose, case_angles, moordyn_matrix

__all__ = ["Node", "Carrier", "Graph", "build_graph"]

_IDENTITY = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True)
class Carrier:
    """A rigid frame nodes ride on: its origin and rotation at the file's pose."""

    key: tuple
    held: bool
    origin: tuple
    matrix: tuple
    line: int | None                 # the file line defining it (None for the vessel)
    axis: str = ""                   # a rod's own frame: "z" or "x" along the rod
    turn: tuple = _IDENTITY          # file-frame coordinates to this frame's

    @property
    def name(self) -> str:
        return self.key[0] if len(self.key) == 1 else f"{self.key[0]}{self.key[1]}"

    def to_global(self, local) -> tuple:
        return tuple(o + v for o, v in zip(self.origin, apply(self.matrix, local)))

    def from_file(self, file_local) -> tuple:
        """Coordinates the file gives in the body's own frame, in this carrier's frame."""
        return tuple(0.0 if abs(c) < 1e-12 else c for c in apply(self.turn, file_local))

    def to_local(self, point) -> tuple:
        v = apply_transpose(self.matrix, tuple(p - o for p, o in zip(point, self.origin)))
        return tuple(0.0 if abs(c) < 1e-12 else c for c in v)


@dataclass(frozen=True)
class Node:
    key: tuple                        # ("point", N) or ("rod", N, "A" | "B")
    label: str                        # "point 3", "rod 2 end A"
    kind: str                         # fixed, free, carrier
    carrier: Carrier | None
    local: tuple | None               # carrier frame [m]
    position: tuple                   # global at the file's pose [m]
    line: int                         # file line that defines it

    @property
    def name(self) -> str:
        """The case's name for a node that becomes a point: point3, rod2A."""
        if self.key[0] == "point":
            return f"point{self.key[1]}"
        return f"rod{self.key[1]}" + ("" if self.key[2] == "AB" else self.key[2])


@dataclass
class Graph:
    scene: MDScene
    nodes: dict                        # key -> Node (only the ends some line uses)
    at: dict                           # key -> [line ids meeting there]
    carriers: dict                     # carrier key -> Carrier
    unused: list = field(default_factory=list)   # points no line uses

    def point_name(self, node: Node) -> str:
        """The case name of a fixed or free node (the source's name where it has one)."""
        if node.key[0] == "point" and node.key[1] in self.scene.point_names:
            return self.scene.point_names[node.key[1]]
        return node.name

    def line_name(self, line_id: int, default: str = "line") -> str:
        """The case name of a line: the source's, else ``line<N>`` (``L<N>`` for a leg)."""
        return self.scene.line_names.get(line_id, f"{default}{line_id}")

    def line_label(self, line_id: int) -> str:
        """How a message names a line: the source's name, else its number."""
        return self.scene.line_names.get(line_id, str(line_id))

    def ends(self, line_id: int) -> tuple:
        line = self.scene.lines[line_id]
        return tuple(self.nodes[_key(self.scene, e)] for e in line.ends)


def _key(scene: MDScene, end) -> tuple:
    kind, ident, rod_end = end
    if kind == "point":
        return ("point", ident)
    # Both ends of a zero-length rod (MoorDyn's point-like connector) are one node.
    return ("rod", ident, "AB" if scene.rods[ident].length == 0.0 else rod_end)


def rod_ends_global(scene: MDScene, rod: MDRod) -> tuple:
    """Global end positions of a rod at the file's pose (body rods placed by their body)."""
    if rod.kind in ("body", "body_pinned"):
        body = _body_carrier(scene, rod.body)
        return (body.to_global(body.from_file(rod.end_a)),
                body.to_global(body.from_file(rod.end_b)))
    return rod.end_a, rod.end_b


def _body_carrier(scene: MDScene, ident: int) -> Carrier:
    """A body's frame: MoorDyn's when it is only yawed (the same rotation in both
    conventions); a body with roll or pitch gets a frame parallel to the scene's axes, its
    points turned into it, so its pose needs no angle conversion and never meets the z-y-x
    angles' singular pitch."""
    body = scene.bodies[ident]
    turn = moordyn_matrix(*body.pose[3:])
    tilted = bool(body.pose[3] or body.pose[4])
    return Carrier(key=("body", ident), held=body.kind in ("fixed", "coupled", "turbine"),
                   origin=body.pose[:3], matrix=_IDENTITY if tilted else turn, line=body.line,
                   turn=turn if tilted else _IDENTITY)


def rod_carrier(scene: MDScene, rod: MDRod) -> Carrier:
    """The frame of a pinned or free rod, chosen so that its two tilts are two of the case's
    angles and its spin about itself is the third, held, away from the z-y-x angles'
    singular pitch of 90 deg: a rod steeper than 45 deg gets its z axis along the rod
    (pointing up; tilts: roll, pitch), a flatter one its x axis (from end A to end B;
    tilts: pitch, yaw). The origin is end A for a pinned rod (the pin); for a free rod it is
    where it crosses the water line (the origin of the linear hydrostatic model) if it
    does, else end A."""
    a, b = rod_ends_global(scene, rod)
    length = math.dist(a, b)
    k = tuple((q - p) / length for p, q in zip(a, b))
    if abs(k[2]) >= math.sqrt(0.5):
        axis = "z"
        u = k if k[2] > 0 else tuple(-c for c in k)
        horizontal = math.hypot(u[0], u[1])
        yaw = math.atan2(u[1], u[0]) if horizontal > 1e-12 else 0.0
        pitch = math.atan2(horizontal, u[2])
    else:
        axis = "x"
        yaw = math.atan2(k[1], k[0])
        pitch = -math.asin(max(-1.0, min(1.0, k[2])))
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    matrix = ((cy * cp, -sy, cy * sp), (sy * cp, cy, sy * sp), (-sp, 0.0, cp))
    origin = a
    if rod.kind == "free" and a[2] * b[2] < 0:
        t = a[2] / (a[2] - b[2])
        origin = tuple(p + t * (q - p) for p, q in zip(a, b))
    return Carrier(key=("rod", rod.id), held=False, origin=origin, matrix=matrix,
                   line=rod.line, axis=axis)


def carrier_angles(carrier: Carrier) -> tuple:
    """The carrier's orientation as case angles (roll, pitch, yaw) [deg]."""
    return case_angles(carrier.matrix)


def build_graph(scene: MDScene) -> Graph:
    """Nodes for every line end, with their carriers; points no line uses are listed."""
    carriers = {}
    vessel = Carrier(key=("vessel",), held=True, origin=(0.0, 0.0, 0.0), matrix=_IDENTITY,
                     line=None)

    def carrier_of(key):
        if key not in carriers:
            if key[0] == "vessel":
                carriers[key] = vessel
            elif key[0] == "turbine":
                carriers[key] = Carrier(key=key, held=True, origin=(0.0, 0.0, 0.0),
                                        matrix=_IDENTITY, line=None)
            elif key[0] == "body":
                carriers[key] = _body_carrier(scene, key[1])
            else:
                carriers[key] = rod_carrier(scene, scene.rods[key[1]])
        return carriers[key]

    nodes, at = {}, {}
    for line in scene.lines.values():
        for end in line.ends:
            key = _key(scene, end)
            at.setdefault(key, []).append(line.id)
            if key in nodes:
                continue
            if key[0] == "point":
                p = scene.points[key[1]]
                label = f"point {scene.point_names.get(p.id, p.id)}"
                if p.kind == "fixed":
                    node = Node(key, label, "fixed", None, None, p.position, p.line)
                elif p.kind == "free":
                    node = Node(key, label, "free", None, None, p.position, p.line)
                else:
                    ck = (("vessel",) if p.kind == "coupled" else ("turbine", p.body)
                          if p.kind == "turbine" else ("body", p.body))
                    c = carrier_of(ck)
                    local = c.from_file(p.position)
                    node = Node(key, label, "carrier", c, local, c.to_global(local), p.line)
            else:
                rod = scene.rods[key[1]]
                point_like = key[2] == "AB"
                label = (f"rod {rod.id} (zero length)" if point_like
                         else f"rod {rod.id} end {key[2]}")
                a, b = rod_ends_global(scene, rod)
                where = b if key[2] == "B" else a
                # A zero-length rod is a point: pinned ones are held where they are.
                kind = rod.kind
                if point_like:
                    kind = {"pinned": "fixed", "coupled_pinned": "coupled",
                            "body_pinned": "body"}.get(kind, kind)
                if kind == "fixed":
                    node = Node(key, label, "fixed", None, None, where, rod.line)
                elif kind == "free" and point_like:
                    node = Node(key, label, "free", None, None, where, rod.line)
                elif kind in ("coupled", "body"):
                    c = carrier_of(("vessel",) if kind == "coupled" else ("body", rod.body))
                    local = c.from_file(rod.end_b if key[2] == "B" else rod.end_a)
                    node = Node(key, label, "carrier", c, local, where, rod.line)
                else:
                    c = carrier_of(("rod", rod.id))
                    node = Node(key, label, "carrier", c, c.to_local(where), where, rod.line)
            nodes[key] = node
    unused = [p for p in scene.points.values() if ("point", p.id) not in at]
    return Graph(scene=scene, nodes=nodes, at=at, carriers=carriers, unused=unused)
