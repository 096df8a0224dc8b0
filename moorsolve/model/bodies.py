"""Rigid bodies and connection points of a scene.

A body's pose is ``(x, y, z, roll, pitch, yaw)``: the position of its body-frame origin in the
scene and its orientation, with ``R = Rz(yaw) Ry(pitch) Rx(roll)`` (the z-y-x convention of MoorPy, MoorDyn and OpenFAST). ``free`` names the degrees of freedom
the solver finds; the others are held at the case-file pose.

Hydrostatics: the linear model MoorPy and MoorDyn use (:class:`Hydrostatics`), or the exact
buoyancy of simple hull members (:class:`HullMember`) integrated at the actual pose.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from .loads import BodyLoads

#: All six degrees of freedom of a rigid body, in the order of every 6-vector and 6x6 matrix.
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: The planar degrees of freedom: what the ``body:`` + ``legs:`` form may free.
PLANAR_DOFS = ("surge", "sway", "yaw")
#: Degrees of freedom whose balance needs mass and hydrostatics (weight against buoyancy).
VERTICAL_DOFS = ("heave", "roll", "pitch")
#: What a body's held pose is relative to: the still water (``water``: a floating body, the
#: default, rises and falls with the tide) or the datum (``seabed``: a jetty, a structure on
#: piles).
FIXED_TO = ("water", "seabed")


@dataclass(frozen=True)
class Hydrostatics:
    """The linear hydrostatic model of a floating body.

    Buoyancy ``rho g V`` acts upward at the ``metacentre`` (body frame, rotates with the
    body); the heave restoring force is ``-rho g A_wp z`` with z the height of the body-frame
    origin. Small-angle stiffness ``K33 = rho g A_wp`` and ``K44 = K55 = rho g V z_M - m g z_G``.
    """

    displaced_volume: float
    metacentre: tuple = (0.0, 0.0, 0.0)
    waterplane_area: float = 0.0


HULL_SHAPES = ("cylinder", "box")


@dataclass(frozen=True)
class HullMember:
    """A vertical prism of the hull whose buoyancy is integrated exactly at the actual pose.

    A ``cylinder`` of ``radius`` or a ``box`` of ``length`` (along body x) by ``width``
    (body y), with its axis along body z through ``centre`` (body frame x, y), from
    ``bottom`` to ``top`` (body-frame z). Its submerged volume and centre of buoyancy are
    exact while the waterplane cuts its side walls or the member is fully submerged
    (:mod:`moorsolve.physics.hydrostatics`).
    """

    shape: str
    bottom: float
    top: float
    radius: float = 0.0
    length: float = 0.0
    width: float = 0.0
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class ShipOutline:
    """The hull of a ship as the pictures draw it: length overall and beam in plan (a
    parallel middle body, a rounded bow, a transom stern), its sides from ``draft`` below
    the waterline to ``freeboard`` above it [m]. ``centre`` is midship on the waterline
    (body frame x, y [m]); the bow points along body x turned by ``heading_deg``.

    It draws the ship and nothing else: buoyancy is ``hydrostatics`` or ``hull``, loads
    are the load models.
    """

    length: float
    beam: float
    draft: float = 0.0
    freeboard: float = 0.0
    centre: tuple = (0.0, 0.0)
    heading_deg: float = 0.0


@dataclass(frozen=True)
class Body:
    """A rigid body: its pose in the case, which degrees of freedom are solved, and its
    mass, hydrostatics, extra springs and load models.

    Attributes
    ----------
    name : str
    free : tuple of str
        Solved degrees of freedom, a subset of :data:`DOFS` in that order.
    position : tuple of 3 floats
        Body-frame origin in the scene [m] (the case-file pose).
    orientation_deg : tuple of 3 floats
        Roll, pitch, yaw [deg].
    mass : float or None
        [kg]; its weight acts at ``centre_of_gravity``.
    centre_of_gravity : tuple of 3 floats
        Body frame [m].
    hydrostatics : Hydrostatics or None
        The linear model.
    hull : tuple of HullMember
        Members whose buoyancy is integrated exactly (instead of ``hydrostatics``).
    stiffness : tuple of 6 tuples of 6 floats, or None
        Extra linear springs about the rest pose (:meth:`rest_position`), ``F = -K (q - q0)`` (SI, rotations in
        rad).
    loads : BodyLoads
    added_mass : tuple of 6 tuples or None
        Added mass [kg, kg m, kg m^2] for natural periods.
    inertia : tuple of 3 floats or None
        Moments of inertia about the centre of gravity [kg m^2] (roll, pitch, yaw axes).
    fixed_to : str
        ``"water"`` (floats: its case-file height is above the still water, which is
        ``water_level`` above the datum) or ``"seabed"`` (its case-file height is on the
        datum, whatever the tide); :data:`FIXED_TO`.
    hydrodynamics : Hydrodynamics or None
        Frequency-dependent added mass, damping, excitation and mean drift
        (:class:`~moorsolve.model.sea.Hydrodynamics`): the body moves in a sea state.
    damping : ExtraDamping or None
        Damping added to the radiation damping for motions
        (:class:`~moorsolve.model.sea.ExtraDamping`).
    outline : ShipOutline or None
        The ship hull the pictures draw (no effect on the solve).
    outline_members : tuple of HullMember
        Members the pictures draw (a platform's columns where its buoyancy is the linear
        ``hydrostatics``); no effect on the solve.
    """

    name: str = "body"
    free: tuple = PLANAR_DOFS
    position: tuple = (0.0, 0.0, 0.0)
    orientation_deg: tuple = (0.0, 0.0, 0.0)
    mass: Optional[float] = None
    centre_of_gravity: tuple = (0.0, 0.0, 0.0)
    hydrostatics: Optional[Hydrostatics] = None
    hull: tuple = ()
    stiffness: Optional[tuple] = None
    loads: BodyLoads = field(default_factory=BodyLoads)
    added_mass: Optional[tuple] = None
    inertia: Optional[tuple] = None
    fixed_to: str = "water"
    hydrodynamics: Optional[object] = None
    damping: Optional[object] = None
    outline: Optional[ShipOutline] = None
    outline_members: tuple = ()

    @property
    def pose(self) -> tuple:
        """The case-file pose ``(x, y, z, roll, pitch, yaw)`` [m, deg]."""
        return tuple(self.position) + tuple(self.orientation_deg)

    def rest_position(self, water_level: float) -> tuple:
        """The body-frame origin [m] at rest with the still water ``water_level`` [m] above
        the datum: where its held degrees of freedom are held, its springs and contacts are
        referred to and a solve starts. A floating body rises with the water (same draft);
        one fixed to the seabed does not."""
        x, y, z = self.position
        return (x, y, z + water_level) if self.fixed_to == "water" else (x, y, z)

    @property
    def buoyant(self) -> bool:
        """Whether the body has a hydrostatic model (linear or exact)."""
        return self.hydrostatics is not None or bool(self.hull)


@dataclass(frozen=True)
class Point:
    """A connection point: fixed in the scene, or free (a bridle apex, a buoy, a clump).

    ``mass`` [kg] and ``volume`` [m^3] give its net weight in water
    ``g (mass - rho volume)`` (negative: it floats up); a free point is held only by its
    lines and, when it sinks onto it, by the seabed.
    """

    name: str
    position: tuple
    free: bool = False
    mass: float = 0.0
    volume: float = 0.0
