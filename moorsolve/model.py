"""The validated description of a mooring scene.

Frozen dataclasses, SI units throughout, degrees only in names ending ``_deg``. A
:class:`Case` is what every other part of moorsolve consumes; ``moorsolve.io`` builds one
from a case file and checks it. Nothing here imports CasADi.

Coordinates: x, y horizontal, z up, z = 0 at the still-water level, seabed at z = -depth
(or a plane through that point at the origin, :class:`Seabed`). ``toward_deg`` is the
direction a wind, current or wave train travels toward, counter-clockwise from +x.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Optional

from .constants import AIR_DENSITY, SEAWATER_DENSITY, STANDARD_GRAVITY

DEGREES_OF_FREEDOM = ("surge", "sway", "yaw")


@dataclass(frozen=True)
class LineDrag:
    """Hydrodynamic coefficients of a line in a current (REFERENCE.md section 5).

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
        Axial stiffness [N]; None for an inextensible line.
    mbl : float or None
        Minimum breaking load [N].
    diameter : float or None
        Outer (hydrodynamic) diameter [m]; needed for wall tension and line drag.
    drag : LineDrag or None
        Drag coefficients: in a case with a current the leg is then discretised.
    sealed : bool
        True for a line whose wall keeps water out of its cross-section (cable, pipe,
        sheathed rope). Its wall tension differs from the effective tension by the
        hydrostatic pressure on the outer area (REFERENCE.md section 2); a chain is not sealed.
    catalog : str or None
        The line-catalogue entry the properties came from (``moorsolve.catalog``), if any.
    corrosion_allowance : float
        Diameter reduction [m] already applied to ``mbl`` (catalogue lines only).
    source : str or None
        Where the catalogue values come from (citation), for reports.
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

    @property
    def elastic(self) -> bool:
        return self.ea is not None


@dataclass(frozen=True)
class Segment:
    """A length of one line type [m, unstretched]."""

    line_type: LineType
    length: float


ANCHOR_KINDS = ("drag", "deadweight", "pile")


@dataclass(frozen=True)
class AnchorType:
    """What an anchor allows, for the mooring checks.

    ``drag``: no uplift at all (the line must leave the anchor horizontally);
    ``deadweight`` (sinker block, Hu & Tang's floating dock): an upward pull up to
    ``allowed_uplift`` [N]; ``pile``: an uplift angle at the anchor up to
    ``allowed_uplift_angle_deg``.
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
class Leg:
    """One mooring leg from its anchor (end A) to its fairlead (end F).

    Attributes
    ----------
    name : str
    anchor : tuple of 3 floats
        Global position [m]. An anchor on the seabed has z = -depth; one above it (a pile
        head, a mid-water point) gives its own z and is modelled without seabed contact.
    fairlead : tuple of 3 floats
        Position [m] in the body frame, or global when the case has no body.
    segments : tuple of Segment
        From anchor to fairlead.
    clumps : tuple of (Clump or None)
        One entry per joint between consecutive segments (``len(segments) - 1``), from the
        anchor up; None (or an empty tuple for all joints) is a bare joint.
    """

    name: str
    anchor: tuple
    fairlead: tuple
    segments: tuple
    anchor_type: Optional[AnchorType] = None
    clumps: tuple = ()

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


@dataclass(frozen=True)
class Flow:
    """A wind or current: speed [m/s] toward ``toward_deg``.

    A current may carry a ``profile`` of ``(z, speed)`` rows (z ascending, m and m/s) that
    the lines see, interpolated linearly and held constant beyond its ends; ``speed`` is
    then what the body's load models see. Without a profile the lines see ``speed`` at
    every depth.
    """

    speed: float
    toward_deg: float = 0.0
    profile: Optional[tuple] = None


@dataclass(frozen=True)
class Waves:
    """An irregular sea: significant height ``hs`` [m] travelling toward ``toward_deg``."""

    hs: float
    toward_deg: float = 0.0


@dataclass(frozen=True)
class Seabed:
    """Seabed contact.

    ``friction`` is the Coulomb coefficient for line on seabed (0 = none). ``gradient`` is
    ``(dz/dx, dz/dy)`` of a plane seabed: its height is ``-depth + gx x + gy y``, so
    ``depth`` is the water depth at the origin; ``(0, 0)`` is flat.
    """

    friction: float = 0.0
    gradient: tuple = (0.0, 0.0)

    @property
    def sloped(self) -> bool:
        return any(g != 0.0 for g in self.gradient)


@dataclass(frozen=True)
class Environment:
    depth: float
    water_density: float = SEAWATER_DENSITY
    air_density: float = AIR_DENSITY
    gravity: float = STANDARD_GRAVITY
    seabed: Seabed = field(default_factory=Seabed)
    wind: Optional[Flow] = None
    current: Optional[Flow] = None
    waves: Optional[Waves] = None

    def seabed_z(self, x: float, y: float) -> float:
        """Height of the seabed [m] at ``(x, y)`` (``-depth`` on a flat seabed)."""
        gx, gy = self.seabed.gradient
        return -self.depth + gx * x + gy * y


# ---- body load models ---------------------------------------------------------------
# Each model acts at ``centre`` (body frame [x, y], m), which sets its yaw moment. The
# flow heading relative to the body, theta = toward_deg - yaw, is taken in the body frame.


@dataclass(frozen=True)
class DragLoad:
    """General quadratic drag ``0.5 rho C A V^2`` for wind or current.

    Without a ``table`` the coefficients are constant and each body axis sees the flow
    component along it: ``Fx = 0.5 rho cx area_x V^2 cos(theta)|cos(theta)|`` and
    ``Fy = 0.5 rho cy area_y V^2 sin(theta)|sin(theta)|`` (body axes).
    With a ``table`` of rows ``(heading_deg, cx, cy, cmz)`` (relative heading, interpolated
    linearly and periodically) the coefficients carry their own sign:
    ``Fx = q cx(theta) area_x``, ``Fy = q cy(theta) area_y``,
    ``Mz = q cmz(theta) area_y length`` with ``q = 0.5 rho V^2``.

    Attributes
    ----------
    area_x, area_y : float
        Projected areas [m^2] facing a flow along body x and along body y.
    cx, cy : float
        Drag coefficients [-] (used without a table).
    table : tuple of (heading_deg, cx, cy, cmz) or None
    length : float
        Reference length [m] for the table's yaw-moment coefficient.
    centre : tuple of 2 floats
        Centre of pressure [m], body frame.
    """

    area_x: float
    area_y: float
    cx: float = 1.0
    cy: float = 1.0
    table: Optional[tuple] = None
    length: float = 0.0
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class HuTangWind:
    """Hu & Tang (2004) wind resistance ``R1 = 0.006 rho_a V^2 (F' + 0.31 F)`` [kN].

    ``superstructure_area`` (F') and ``hull_area`` (F, hull above water) are projected on the
    midship section, i.e. they face a flow along body x. Given alone, the force acts along
    the wind with that magnitude whatever the heading (the paper's use). With the lateral
    areas too, body x sees ``R1(frontal) cos|cos|`` and body y ``R1(lateral) sin|sin|``.
    """

    superstructure_area: float
    hull_area: float
    superstructure_area_lateral: Optional[float] = None
    hull_area_lateral: Optional[float] = None
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class HuTangCurrent:
    """Hu & Tang (2004) current resistance ``R2 = 0.01 f Omega v^1.83`` [kN], along the flow.

    ``wetted_area`` is Omega [m^2], ``coefficient`` is f (0.18 in the paper).
    """

    wetted_area: float
    coefficient: float = 0.18
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class HuTangDrift:
    """Hu & Tang (2004) wave drift ``R3 = 0.75 k rho g B (Hs/4)^2 cos(alpha) 1e-2`` [kN].

    ``beam`` B [m] gives the drift along body x (``cos alpha`` with alpha the wave heading
    relative to the bow); an optional ``length`` gives the beam-sea drift along body y the same
    way with ``sin alpha``. ``k`` is the paper's coefficient (0.7).
    """

    beam: float
    length: Optional[float] = None
    k: float = 0.7
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class DriftCoefficient:
    """Mean wave drift in a general coefficient form.

    ``Fx = rho g cx length_x (Hs/4)^2 cos(theta)`` and ``Fy = rho g cy length_y (Hs/4)^2
    sin(theta)``: drift scales with the wave height squared (Hs/4 is the standard deviation
    of the surface elevation; Hu & Tang write their formula with it) and with the waterline
    breadth facing the waves.
    """

    length_x: float
    length_y: float
    cx: float = 1.0
    cy: float = 1.0
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class BodyLoads:
    """The load models a body declares; each one present is simulated.

    ``force`` is a constant [Fx N, Fy N, Mz N m] in the global frame.
    """

    force: Optional[tuple] = None
    wind: Optional[object] = None        # DragLoad | HuTangWind
    current: Optional[object] = None     # DragLoad | HuTangCurrent
    wave_drift: Optional[object] = None  # HuTangDrift | DriftCoefficient


@dataclass(frozen=True)
class Body:
    """A rigid floating body moving in the horizontal plane.

    ``free`` lists the solved degrees of freedom among surge, sway and yaw; the others are
    held at their case-file value (zero offset).
    """

    free: tuple = DEGREES_OF_FREEDOM
    loads: BodyLoads = field(default_factory=BodyLoads)


@dataclass(frozen=True)
class SolverOptions:
    """Solver settings a case may carry; the CLI's ``--tol`` overrides ``tol``.

    ``tol`` is the certified force residual relative to the largest line tension.
    ``line_elements`` is the number of elements of a discretised leg (one in a current with
    drag data).
    """

    tol: float = 1e-9
    max_iter: int = 200
    max_time_s: float = 5.0
    line_elements: int = 20


@dataclass(frozen=True)
class Checks:
    """Acceptance limits for ``moorsolve check`` (the factors come from the standard's table).

    Attributes
    ----------
    standard : str
        Criteria table: ``api-rp-2sk`` or ``dnv-os-e301``.
    consequence_class : int
        DNV-OS-E301 consequence class (1 or 2); unused by API RP 2SK.
    offset_limit, offset_limit_damaged : float or None
        Largest horizontal offset of the body origin [m], intact and with one leg broken
        (the damaged limit defaults to the intact one).
    min_grounded_length, min_grounded_length_damaged : float or None
        Least unstretched length [m] that must stay on the seabed in every leg whose anchor
        is on the seabed (Hu & Tang keep 45 m); the damaged value defaults to the intact one.
    anchor : AnchorType
        Default anchor type for legs that do not give their own.
    damaged : bool
        Also run the damaged conditions (each leg removed in turn).
    """

    standard: str = "api-rp-2sk"
    consequence_class: int = 1
    offset_limit: Optional[float] = None
    offset_limit_damaged: Optional[float] = None
    min_grounded_length: Optional[float] = None
    min_grounded_length_damaged: Optional[float] = None
    anchor: AnchorType = field(default_factory=AnchorType)
    damaged: bool = True


@dataclass(frozen=True)
class Case:
    name: str
    environment: Environment
    line_types: dict
    legs: tuple
    body: Optional[Body] = None
    solver: SolverOptions = field(default_factory=SolverOptions)
    checks: Optional[Checks] = None
    #: What a MoorDyn input file held that moorsolve does not use (the case file's ``moordyn``
    #: block, see ``moorsolve.io.moordyn_block``), kept for export; the solver ignores it.
    moordyn: Optional[Mapping] = field(default=None, compare=False, repr=False)
    #: The validated case-file data it was built from (for sweeps that edit it by path);
    #: None for a Case built in code.
    source: Optional[Mapping] = field(default=None, compare=False, repr=False)
