"""What each line of a case is: its kind (one segment, several, lumped nodes), which end
is lower, and the scales of its unknowns (:mod:`.blocks` builds its block in the problem;
see there for the models).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ...model import Case, Line
from ...model.build_network import end_position
from ...physics.catenary import LegKind
from ...physics.stretch import StretchModel
from .stretch_params import law_model

#: Columns of ``EquilibriumProblem.segment_report``: per segment of a multi-segment line
#: (from its lower end), its tensions [N] (top H and V, pull on its lower end HA and signed
#: VA), grounded length and horizontal extents [m], span residuals [m] and spans [m], its
#: lower node (height above the seabed, distance from the lower end, z), the unbalanced
#: vertical force and seabed reaction of the joint at its top [N] (0 for the top segment),
#: and its mismatch as a force.
SEGMENT_COLUMNS = ("leg", "segment", "H", "VF", "HA", "VA", "grounded", "suspended_x",
                   "descent_x", "rX", "rZ", "X", "Z", "lower_h", "lower_xi", "lower_z",
                   "joint_unbalanced", "joint_reaction", "mismatch_N", "floating")


@dataclass(frozen=True)
class SegmentKind:
    """Which block a segment of a multi-segment line uses.

    ``block`` is ``"lifted"`` (a sinking segment whose lower end may be above the seabed;
    ``friction`` for the anchor segment), ``"floating"`` (a buoyant segment bounded by the
    free surface, :func:`~moorsolve.physics.catenary.surface_segment_equations`),
    ``"straight"`` (weightless) or ``"leg"`` (the leg block of :func:`leg_function` with
    ``leg``). ``law``: its stretch law when it is not Hooke's.
    """

    block: str
    elastic: bool
    leg: Optional[LegKind] = None
    friction: bool = False
    law: Optional[StretchModel] = None


@dataclass(frozen=True)
class MultiLegKind:
    """The physics of a multi-segment line: one :class:`SegmentKind` per segment, from the
    lower end.

    ``reversed_top``: the top end rests on the seabed and the top segment sinks (or the top
    end is at the surface and the top segment floats), so that segment is solved from the
    top end (its block's lower end), where the line may lie flat; the unknown ``V`` is then
    its vertical tension at the joint below.
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
    def surface(self) -> bool:
        return any(s.block == "floating" for s in self.segments)

    neutral = False
    sloped = False


@dataclass(frozen=True)
class DiscreteLegKind:
    """A line discretised into lumped nodes because a current drags on it.

    ``elements`` holds the number of elements of each segment (end A first);
    ``elastic_segments`` whether each segment stretches; ``profile_rows`` the number of rows
    of the current profile (0: uniform current); ``side`` whether any segment has a
    side-force coefficient.
    """

    elements: tuple
    elastic_segments: tuple
    profile_rows: int = 0
    side: bool = False
    profile_headings: bool = False
    #: Some part of the line is buoyant: the free surface may hold nodes (the node heights
    #: are clipped to the water column in every lumped-node line).
    surface: bool = False
    #: Each segment's stretch law when it is not Hooke's (:class:`StretchModel` or None).
    laws: tuple = ()

    @property
    def elastic(self) -> bool:
        return any(self.elastic_segments)

    @property
    def n_elements(self) -> int:
        return sum(self.elements)

    contact = True
    friction = False
    neutral = False
    sloped = False


@dataclass(frozen=True)
class LineKind:
    """Everything about a line that shapes the built problem (not its values).

    Attributes
    ----------
    block : LegKind, MultiLegKind or DiscreteLegKind
        The physics of the line.
    flipped : bool
        The catenary blocks run from end B (the lower end) to end A.
    lower, upper : str
        What the block's lower and upper ends are: ``"anchor"`` (fixed on the seabed),
        ``"fixed"`` (fixed above it), ``"point"`` (a free point) or ``"body"``.
    lifted : bool
        A one-segment sinking line whose lower end is not an anchor: the lifted block, which
        may touch down between its ends.
    """

    block: object
    flipped: bool = False
    lower: str = "anchor"
    upper: str = "body"
    lifted: bool = False

    @property
    def multi(self) -> bool:
        return isinstance(self.block, MultiLegKind)

    @property
    def discrete(self) -> bool:
        return isinstance(self.block, DiscreteLegKind)

    @property
    def single(self) -> bool:
        return isinstance(self.block, LegKind)

    @property
    def elastic(self) -> bool:
        return self.block.elastic

    @property
    def contact(self) -> bool:
        return self.block.contact or self.lifted

    @property
    def friction(self) -> bool:
        return self.block.friction

    @property
    def neutral(self) -> bool:
        return self.block.neutral

    @property
    def surface(self) -> bool:
        """The free surface bounds the line (a buoyant line or segment, lumped nodes)."""
        return bool(getattr(self.block, "surface", False))

    @property
    def sloped(self) -> bool:
        return self.block.sloped

    @property
    def n_unknowns(self) -> int:
        block = self.block
        if self.multi:
            return 2 + 2 * block.n_joints
        if self.discrete:
            return block.n_elements + 3 * (block.n_elements - 1)
        return 2

    def scales(self, force_scale: float, length_scale: float) -> list:
        """Scale of each of the line's unknowns [N or m]."""
        block = self.block
        if self.multi:
            return [force_scale] * 2 + [length_scale, force_scale] * block.n_joints
        if self.discrete:
            return [force_scale] * block.n_elements + [length_scale] * (
                3 * (block.n_elements - 1))
        return [force_scale] * 2


def discretised(case: Case, line: Line) -> bool:
    """Whether a line is modelled as lumped nodes: the case has a current and one of its
    line types gives drag data."""
    return case.environment.current is not None and any(
        seg.line_type.drag is not None for seg in line.segments)


def _end_role(case: Case, end) -> str:
    if end.body is not None:
        return "body"
    if end.point is not None:
        return "point"
    return "anchor" if end.on_seabed else "fixed"


def _start_position(case: Case, end) -> tuple:
    """Global position of an end at the case-file pose."""
    if end.body is None:
        return tuple(float(v) for v in end.position)
    body = case.body_named(end.body)
    return tuple(float(v) for v in end_position(end, {body.name: body}))


def _start_height(case: Case, end) -> float:
    return _start_position(case, end)[2]


def line_kind(case: Case, line: Line) -> LineKind:
    """The physics a line needs, from what the case declares."""
    role_a, role_b = _end_role(case, line.a), _end_role(case, line.b)
    if discretised(case, line):
        n = case.solver.line_elements
        counts = tuple(max(1, round(n * seg.length / line.length)) for seg in line.segments)
        profile = case.environment.current.profile
        block = DiscreteLegKind(
            elements=counts,
            elastic_segments=tuple(seg.line_type.elastic for seg in line.segments),
            profile_rows=len(profile) if profile else 0,
            profile_headings=case.environment.current.profile_headings,
            surface=any(seg.line_type.weight_in_water < 0 for seg in line.segments)
            or any(c is not None and c.weight < 0 for c in line.joint_clumps),
            side=any(seg.line_type.drag is not None and seg.line_type.drag.side != 0
                     for seg in line.segments),
            laws=tuple(law_model(seg.line_type) for seg in line.segments))
        return LineKind(block, False, role_a, role_b)
    # The lower end: an anchor if there is one, else the end lower in the case.
    if role_a == "anchor":
        flipped = False
    elif role_b == "anchor":
        flipped = True
    else:
        flipped = _start_height(case, line.b) < _start_height(case, line.a)
    lower, upper = (role_b, role_a) if flipped else (role_a, role_b)
    segments = line.segments[::-1] if flipped else line.segments
    tx, ty, tz = _start_position(case, line.a if flipped else line.b)
    if len(segments) > 1:
        on_bed = tz <= case.environment.seabed_z(tx, ty) + 1e-9
        return LineKind(_multi_kind(case, segments, lower, on_bed, at_surface(tz)), flipped,
                        lower, upper)
    lt = line.line_type
    w = lt.weight_in_water
    contact = lower == "anchor" and w > 0
    # The free surface bounds every buoyant line; one whose upper end is at (or above) the
    # surface is solved from that end (LegKind.from_fairlead). An upper end above the water
    # with a weight in air given: the part in air is its own catenary (LegKind.air).
    air = tz > 1e-9 and w != 0 and lt.weight_in_air is not None
    # Both ends above the water (a bridle to an apex in air, a hawser): the line may hang in
    # air throughout or dip into the water between them (physics/air.py).
    lz = _start_height(case, line.b if flipped else line.a)
    if air and w > 0 and lower != "anchor" and lz > 1e-9:
        block = LegKind(elastic=lt.elastic, contact=False, air=True, air_ends=True,
                        law=law_model(lt))
        return LineKind(block, flipped, lower, upper)
    block = LegKind(elastic=lt.elastic, contact=contact,
                    friction=contact and case.environment.seabed.friction > 0,
                    neutral=(w == 0), sloped=contact and case.environment.seabed.sloped,
                    surface=w < 0, from_fairlead=w < 0 and at_surface(tz) and not air,
                    air=air, law=law_model(lt))
    return LineKind(block, flipped, lower, upper, lifted=(w > 0 and lower != "anchor"))


def at_surface(z: float) -> bool:
    """Whether a point at height ``z`` [m] is at or above the still-water level."""
    return z >= -1e-9


def _multi_kind(case: Case, segments, lower: str, top_on_seabed: bool,
                top_at_surface: bool = False) -> MultiLegKind:
    kinds = []
    for k, seg in enumerate(segments):
        lt = seg.line_type
        w = lt.weight_in_water
        law = law_model(lt)
        if w == 0:
            kinds.append(SegmentKind("straight", lt.elastic, law=law))
        elif w < 0:
            # Bounded by the free surface, which may hold the joint above it down.
            kinds.append(SegmentKind("floating", lt.elastic, law=law))
        else:
            # Friction acts on the anchor segment's grounded length only (README).
            friction = k == 0 and lower == "anchor" and case.environment.seabed.friction > 0
            kinds.append(SegmentKind("lifted", lt.elastic, friction=friction, law=law))
    return MultiLegKind(tuple(kinds), reversed_top=(
        (top_on_seabed and kinds[-1].block == "lifted")
        or (top_at_surface and kinds[-1].block == "floating")))


def line_kinds(case: Case) -> list:
    """:func:`line_kind` of every line of ``case``."""
    return [line_kind(case, line) for line in case.lines]


# ---- the symbolic block of a line -------------------------------------------------------


def can_ground(kind: SegmentKind) -> bool:
    """Whether a segment's top can arrive along the seabed (a sinking segment)."""
    return kind.block == "lifted" or (kind.leg is not None and kind.leg.contact)
