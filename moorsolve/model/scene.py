"""The scene: bodies, solver options, mooring checks and the validated Case."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Optional

from .environment import Environment
from .lines import AnchorType
from .bodies import DOFS, Body, Point
from .contact import Contacts

#: Degrees of freedom of a body, in the order of every 6-vector (see :mod:`.bodies`).
DEGREES_OF_FREEDOM = DOFS
#: Criteria tables known to ``moorsolve.checks`` (``checks.standard``).
STANDARDS = ("api-rp-2sk", "dnv-os-e301")
#: How a check takes the dynamic part of the line tension (``checks.method``) and how the
#: lines respond in a sea state (``analysis.lines``).
METHODS = ("quasi_static", "dynamic")


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
    wear : Wear or None
        Corrosion and creep over the design life, for the end-of-life check
        (:mod:`moorsolve.model.build_wear`, :mod:`moorsolve.checks.end_of_life`).
    anchors : tuple of AnchorDesign
        At most one :class:`~moorsolve.model.anchors.AnchorDesign` per anchor kind: the
        capacity each kind of anchor is checked against, and its mass for the cost.
    fatigue : FatigueSpec or None
        The fatigue check (:mod:`moorsolve.model.fatigue`), where the case asks for one.
    method : str or None
        How the dynamic part of the line tension is had in a sea state: ``quasi_static``
        (the lines re-solved with the bodies held at their design offset) or ``dynamic``
        (the lines' own dynamics driven by the bodies' motions); None follows
        ``analysis.lines``. API RP 2SK's factors depend on it (2.00 / 1.43 or 1.67 / 1.25).
    """

    standard: str = "api-rp-2sk"
    consequence_class: int = 1
    offset_limit: Optional[float] = None
    offset_limit_damaged: Optional[float] = None
    min_grounded_length: Optional[float] = None
    min_grounded_length_damaged: Optional[float] = None
    anchor: AnchorType = field(default_factory=AnchorType)
    damaged: bool = True
    wear: Optional[object] = None
    anchors: tuple = ()
    fatigue: Optional[object] = None
    method: Optional[str] = None

    def anchor_design(self, kind: str):
        """The :class:`~moorsolve.model.anchors.AnchorDesign` of anchor ``kind``, or None."""
        return next((a for a in self.anchors if a.kind == kind), None)


@dataclass(frozen=True)
class Analysis:
    """What the scene simulates beyond the statics (the case file's ``analysis``).

    Attributes
    ----------
    lines : str or None
        ``dynamic``: each line's own dynamics (lumped masses, drag linearised) driven by the
        bodies' motions in the sea state; ``quasi_static``: the lines follow the bodies
        statically. None: ``dynamic`` where the scene has a sea state and a body with
        hydrodynamics, ``quasi_static`` otherwise (:meth:`lines_in`).
    """

    lines: Optional[str] = None

    def lines_in(self, case) -> str:
        """The line model in effect for ``case``."""
        if self.lines is not None:
            return self.lines
        return "dynamic" if moves_in_sea(case) else "quasi_static"


def moves_in_sea(case) -> bool:
    """Whether ``case`` has a sea state (waves with a period) and a body with
    hydrodynamics to move in it."""
    waves = case.environment.waves
    return bool(waves is not None and waves.sea_state
                and any(getattr(b, "hydrodynamics", None) is not None for b in case.bodies))


@dataclass(frozen=True)
class Case:
    """A validated scene: environment, line types, bodies, points and lines.

    ``form`` records which case-file form it came from: ``"legs"`` (one optional body and
    anchor-to-fairlead legs; results keep ``body`` and ``legs``) or ``"network"``.
    """

    name: str
    environment: Environment
    line_types: dict
    lines: tuple
    bodies: tuple = ()
    points: tuple = ()
    solver: SolverOptions = field(default_factory=SolverOptions)
    checks: Optional[Checks] = None
    form: str = "legs"
    #: What the scene simulates beyond the statics (``analysis`` in the case file).
    analysis: Analysis = field(default_factory=Analysis)
    #: Walls, piles, fenders and pile guides (network form; :mod:`.contact`).
    contacts: Contacts = field(default_factory=Contacts)
    #: What a MoorDyn input file held that moorsolve does not use (the case file's ``moordyn``
    #: block, see ``moorsolve.model.moordyn_block``), kept for export; the solver ignores it.
    moordyn: Optional[Mapping] = field(default=None, compare=False, repr=False)
    #: The validated case-file data it was built from (for sweeps that edit it by path);
    #: None for a Case built in code.
    source: Optional[Mapping] = field(default=None, compare=False, repr=False)

    @property
    def legs(self) -> tuple:
        """The lines (the ``legs:`` form's name for them)."""
        return self.lines

    @property
    def body(self) -> Optional[Body]:
        """The one body of a ``legs:``-form case (None without a body or with several)."""
        return self.bodies[0] if len(self.bodies) == 1 else None

    def body_named(self, name: str) -> Body:
        for body in self.bodies:
            if body.name == name:
                return body
        raise KeyError(name)

    def point_named(self, name: str) -> Point:
        for point in self.points:
            if point.name == name:
                return point
        raise KeyError(name)

    @property
    def free_points(self) -> tuple:
        return tuple(p for p in self.points if p.free)
