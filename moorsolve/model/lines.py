"""Line types, segments, clumps and anchors: what a mooring line is made of."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from .stretch import StiffnessBounds, StretchLaw

@dataclass(frozen=True)
class LineDrag:
    """Hydrodynamic coefficients of a line in a current.

    Per unit stretched length, with ``q = rho d / 2``, ``U_n`` and ``U_t`` the flow's
    components normal and tangential to the line and ``chi`` the angle of attack:
    normal ``q normal |U_n| U_n`` (``normal sin^2 chi`` times ``q v^2``; Merkin's fit is
    1.1), tangential ``q tangential |U_t| U_t`` (skin friction, on the diameter), and side
    ``q side |U_n| |U_t|`` normal to both line and flow (laid ropes; sign by lay).
    """

    normal: float
    tangential: float = 0.0
    side: float = 0.0


@dataclass(frozen=True)
class LineType:
    """Properties of one kind of line.

    Attributes
    ----------
    name : str
    weight_in_water : float
        Submerged weight per unit unstretched length [N/m]; negative for a buoyant line,
        zero for a neutrally buoyant one.
    ea : float or None
        Axial stiffness [N] of a Hooke line; None for an inextensible line or one with
        another stretch law.
    mbl : float or None
        Minimum breaking load [N].
    diameter : float or None
        Outer (hydrodynamic) diameter [m]; needed for wall tension and line drag.
    drag : LineDrag or None
        Drag coefficients: in a case with a current the leg is then discretised.
    sealed : bool
        True for a line whose wall keeps water out of its cross-section (cable, pipe,
        sheathed rope). Its wall tension differs from the effective tension by the
        hydrostatic pressure on the outer area; a chain is not sealed.
    catalog : str or None
        The line-catalogue entry the properties came from (``moorsolve.catalog``), if any.
    corrosion_allowance : float
        Diameter reduction [m] already applied to ``mbl`` (catalogue lines only).
    source : str or None
        Where the catalogue values come from (citation), for reports.
    stretch : StretchLaw or None
        A stretch law other than Hooke's (Baranov, a tension-strain table); None for Hooke
        (``ea``) and inextensible lines (:mod:`moorsolve.model.stretch`).
    fibre : bool
        A fibre rope (synthetic or plant fibre): the result flags it where it lies on the
        seabed, and the checks hold it to ``min_tension``.
    min_tension : float or None
        Least tension [N] the line must keep everywhere (a rope that must not go slack).
    stiffness_bounds : StiffnessBounds or None
        Lower and upper bound of its stiffness for the bound analysis
        (:func:`moorsolve.studies.bounds.stiffness_bounds`).
    """

    name: str
    weight_in_water: float
    ea: Optional[float] = None
    mbl: Optional[float] = None
    diameter: Optional[float] = None
    sealed: bool = False
    drag: Optional[LineDrag] = None
    catalog: Optional[str] = None
    corrosion_allowance: float = 0.0
    source: Optional[str] = None
    #: Weight per unit length in air [N/m], for the part of a line above the water (a
    #: fairlead in air); None when the case gives none (that part then takes the weight in
    #: water, with a warning).
    weight_in_air: Optional[float] = None
    stretch: Optional[StretchLaw] = None
    fibre: bool = False
    min_tension: Optional[float] = None
    stiffness_bounds: Optional[StiffnessBounds] = None

    @property
    def elastic(self) -> bool:
        return self.ea is not None or self.stretch is not None

    def strain_at(self, T: float) -> float:
        """The strain at tension ``T`` [N]: ``T/EA``, the stretch law's, or 0 when
        inextensible."""
        if self.stretch is not None:
            return self.stretch.strain_at(T)
        return T / self.ea if self.ea is not None else 0.0


@dataclass(frozen=True)
class Segment:
    """A length of one line type [m, unstretched].

    ``pretension`` [N]: the segment was given by the tension it carries at the case-file
    pose instead of a length (a hawser); ``length`` is then the unstretched length that
    gives it.
    """

    line_type: LineType
    length: float
    pretension: Optional[float] = None


ANCHOR_KINDS = ("drag", "deadweight", "pile", "suction")


@dataclass(frozen=True)
class AnchorType:
    """What an anchor allows, for the mooring checks.

    ``drag``: no uplift at all (the line must leave the anchor horizontally);
    ``deadweight`` (sinker block, Hu & Tang's floating dock): an upward pull up to
    ``allowed_uplift`` [N]; ``pile``: an uplift angle at the anchor up to
    ``allowed_uplift_angle_deg``; ``suction``: any uplift, the H-V capacity envelope of
    ``checks.anchors.suction`` governs.
    """

    kind: str = "drag"
    allowed_uplift: float = 0.0
    allowed_uplift_angle_deg: float = 0.0


@dataclass(frozen=True)
class Clump:
    """A point load at a joint between two segments: a clump weight or a buoy.

    Attributes
    ----------
    weight : float
        Net downward force in water [N]: ``g (mass - water_density volume)`` when given by
        mass and volume; negative for a buoy.
    mass : float or None
        Mass [kg], when the case gave one.
    volume : float or None
        Displaced volume [m^3], when the case gave one.
    """

    weight: float
    mass: Optional[float] = None
    volume: Optional[float] = None


@dataclass(frozen=True)
class End:
    """One end of a line: fixed in the scene, at a named point, or on a body.

    Attributes
    ----------
    position : tuple of 3 floats
        A fixed end: its global position [m]. A point end: the point's position in the case
        file (global). A body end: the attachment point in the body frame [m].
    point : str or None
        The point's name for a point end.
    body : str or None
        The body's name for a body end.
    on_seabed : bool
        A fixed end that rests on the seabed (an anchor): its height follows the seabed
        under it, so moving it in x or y moves it along the seabed.
    label : str or None
        The name of the fixed point it was given as, for reports.
    """

    position: tuple
    point: Optional[str] = None
    body: Optional[str] = None
    on_seabed: bool = False
    label: Optional[str] = None

    @property
    def kind(self) -> str:
        """``"fixed"``, ``"point"`` or ``"body"``."""
        if self.body is not None:
            return "body"
        return "point" if self.point is not None else "fixed"

    @property
    def fixed(self) -> bool:
        return self.body is None and self.point is None


@dataclass(frozen=True)
class Line:
    """One mooring line from end A to end B, of one or more segments.

    The ``body:`` + ``legs:`` form of a case makes every leg a line from its anchor (end A,
    fixed) to its fairlead (end B, on the body, or fixed without a body).

    Attributes
    ----------
    name : str
    a, b : End
        End A (``from``; the anchor of a leg) and end B (``to``; the fairlead).
    segments : tuple of Segment
        From end A to end B.
    anchor_type : AnchorType or None
        What the anchor at end A allows, for the mooring checks.
    clumps : tuple of (Clump or None)
        One entry per joint between consecutive segments (``len(segments) - 1``), from end
        A; None (or an empty tuple for all joints) is a bare joint.
    """

    name: str
    a: End
    b: End
    segments: tuple
    anchor_type: Optional[AnchorType] = None
    clumps: tuple = ()

    @property
    def anchor(self) -> tuple:
        """End A's position as the case gives it (global for a fixed end or a point)."""
        return self.a.position

    @property
    def fairlead(self) -> tuple:
        """End B's position as the case gives it (body frame for a body end)."""
        return self.b.position

    @property
    def joint_clumps(self) -> tuple:
        """The clump at every joint (None for a bare joint), ``len(segments) - 1`` entries."""
        n = len(self.segments) - 1
        return tuple(self.clumps) + (None,) * (n - len(self.clumps))

    @property
    def multi_segment(self) -> bool:
        return len(self.segments) > 1

    @property
    def line_type(self) -> LineType:
        return self.segments[0].line_type

    @property
    def length(self) -> float:
        return sum(s.length for s in self.segments)


#: The name the legacy ``legs:`` form gives its lines.
Leg = Line
